#!/usr/bin/python3
"""Plots and tables of the solver sweep from solver_benchmarks.json,
solver_skips.json (the configurations skipped on purpose, with the reason) and
solver_histories.json (written by build/bin/hofem_bench, see reports/README.md).
Used by plot_reports.py; on its own, for the full preset's directory:

    /usr/bin/python3 scripts/plots/plot_solver_sweep.py reports/full
"""
import json
import math
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_json import load_skips  # noqa: E402
from solver_sweep_tables import best_per_size, parse, print_tables, series_key, series_label, sweep_runs  # noqa: E402

METHOD_STYLE = {"cg": "-", "cr": "--", "minres": "-.", "gmres": ":"}


def plot_histories(hist, out):
    runs = hist.get("runs", [])
    # Fig. 13 of the thesis: residual vs iteration, one panel per Krylov method,
    # one line per preconditioner; a row per problem: the order-2 tetrahedral
    # system of each problem with the most recorded runs (the size where every
    # combination ran), the larger if tied.
    count = {}
    for r in runs:
        count.setdefault(r["problem"], [0, r["unknowns"]])[0] += 1
    rows = []
    for problem in ("mms-linear", "hessian-nh", "hessian-nh-psd"):
        cands = [(c, u, p) for p, (c, u) in count.items() if p.startswith(problem + "/tet/p2/")]
        if cands:
            rows.append(max(cands)[2])
    if not rows:
        return False
    methods = ["cg", "cr", "minres", "gmres"]
    fig, axes = plt.subplots(len(rows), 4, figsize=(17, 3.8 * len(rows)), squeeze=False, sharey=True)
    colours = plt.get_cmap("tab10").colors
    pcs = sorted({r["solver"].split("+", 1)[1] for r in runs if "+" in r["solver"]})
    for i, problem in enumerate(rows):
        for j, method in enumerate(methods):
            ax = axes[i][j]
            for r in runs:
                if r["problem"] != problem or not r["solver"].startswith(method + "+"):
                    continue
                pc = r["solver"].split("+", 1)[1]
                ax.semilogy(r["iteration"], np.maximum(r["relative_residual"], 1e-16), lw=1.2,
                            color=colours[pcs.index(pc) % len(colours)], label=pc)
            unknowns = next((r["unknowns"] for r in runs if r["problem"] == problem), 0)
            ax.set_title(f"{method}: {problem} ({int(unknowns)} unknowns)", fontsize=9)
            ax.set_xlabel("iteration")
            ax.grid(True, which="both", alpha=0.3)
            if j == 0:
                ax.set_ylabel("||r|| / ||b||")
            if ax.lines:
                ax.legend(fontsize=7)
    fig.suptitle("Residual history per solver / preconditioner (cf. thesis Fig. 13)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return True


def split_combo(combo):
    """(method, component): ("cg", "amg") for "cg+amg", (None, "cholmod") for direct solvers and hypre."""
    solver = combo.split("/")[0]
    if "+" in solver and not solver.startswith("hypre"):
        method, pc = solver.split("+", 1)
        return method, pc
    return None, solver


def plot_time_vs_unknowns(runs, out):
    lin = [r for r in sweep_runs(runs, "BM_LinearSolve") if r["status"] == "ok"]
    if not lin:
        return False
    order = {"mms-linear": 0, "hessian-nh": 1, "hessian-nh-psd": 2}
    panels = sorted({(r["problem"], r["cell"], r["order"]) for r in lin},
                    key=lambda k: (order.get(k[0], 9), k[1] != "tet", k[1], k[2]))
    components = sorted({split_combo(r["combo"])[1] for r in lin})
    colours = {c: plt.get_cmap("tab20").colors[i % 20] for i, c in enumerate(components)}
    cols = 3
    rows = math.ceil(len(panels) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(17, 4.3 * rows), squeeze=False)
    for ax, (problem, cell, order_) in zip(axes.flat, panels):
        combos = {}
        for r in lin:
            if (r["problem"], r["cell"], r["order"]) == (problem, cell, order_):
                combos.setdefault(r["combo"], []).append((r["unknowns"], r["seconds"]))
        for combo, pts in sorted(combos.items()):
            pts.sort()
            method, comp = split_combo(combo)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], METHOD_STYLE.get(method, "-"),
                      marker="o" if method else "s", ms=3, color=colours[comp], lw=1.1)
        ax.set_title(f"{problem} {series_label(cell, order_)}", fontsize=9)
        ax.set_xlabel("unknowns")
        ax.set_ylabel("set-up + solve [s]")
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    handles = [plt.Line2D([], [], color=colours[c], marker="s" if c in ("cholmod", "umfpack", "eigen-ldlt") or
                          c.startswith("hypre") else "o", lw=2, label=c) for c in components]
    handles += [plt.Line2D([], [], color="k", ls=st, label=m) for m, st in METHOD_STYLE.items()]
    fig.legend(handles=handles, loc="upper center", ncol=min(len(handles), 9), fontsize=8, bbox_to_anchor=(0.5, 0.995))
    fig.suptitle("Time to solution vs unknowns (colour: preconditioner or direct solver; line style: Krylov method)",
                 y=1.02)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.savefig(out, dpi=100, bbox_inches="tight")
    plt.close(fig)
    return True


def plot_work_precision(runs, out):
    panels = [("BM_LinearSolve", "mms-linear", "linear elasticity: one linear solve"),
              ("BM_NewtonSolve", "mms-neohookean", "Neo-Hookean: whole Newton solve")]
    fig, axes = plt.subplots(1, 2, figsize=(14, 5))
    any_data = False
    for ax, (kind, problem, title) in zip(axes, panels):
        sel = [r for r in sweep_runs(runs, kind, problem) if r["status"] == "ok" and r.get("l2_error")]
        colours = {}
        for r in sel:  # every solved run, faint
            c = colours.setdefault(series_key(r), plt.get_cmap("tab10").colors[len(colours) % 10])
            ax.loglog(r["seconds"], r["l2_error"], ".", color=c, alpha=0.25, ms=4)
        for sk, pts in sorted(best_per_size(sel).items()):  # the fastest per size, joined
            c = colours[sk]
            ax.loglog([p[1]["seconds"] for p in pts], [p[1]["l2_error"] for p in pts], "o-", color=c,
                      label=f"{series_label(*sk)} (fastest per size)")
            for _, r in pts:
                ax.annotate(r["combo"], (r["seconds"], r["l2_error"]), fontsize=5, alpha=0.8)
            any_data = True
        ax.axhline(1e-4, color="k", ls=":", lw=0.8)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("L2 error against u*")
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    fig.suptitle("Work-precision per element order (dots: every solved run)")
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return any_data


def plot_bandwidth(runs, out):
    sel = [r for r in runs if r["kind"] in ("BM_SpMV", "BM_CgIteration")]
    if not sel:
        return False
    fig, ax = plt.subplots(figsize=(8, 4.2))
    labels = sorted({(r["order"], r["n"]) for r in sel})
    x = np.arange(len(labels))
    for k, (kind, name) in enumerate((("BM_SpMV", "SpMV"), ("BM_CgIteration", "Jacobi-CG iteration"))):
        vals, now = [], []
        for order, n in labels:
            m = [r for r in sel if r["kind"] == kind and r["order"] == order and r["n"] == n]
            vals.append(m[0].get("floor_ratio", float("nan")) if m else float("nan"))
            now.append(m[0].get("floor_ratio_now", float("nan")) if m else float("nan"))
        ax.bar(x + (k - 0.5) * 0.38, vals, 0.38, label=f"{name} (floor: start-up triad)")
        ax.plot(x + (k - 0.5) * 0.38, now, "kv", ms=6, label="against a triad right after the kernel" if k else None)
    ax.axhline(1.5, color="r", ls="--", lw=1, label="target 1.5x (CG, order 2)")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(x)
    ax.set_xticklabels([f"P{o}, n={n}" for o, n in labels])
    ax.set_ylabel("time / (bytes / triad bandwidth)")
    ax.set_title("Sparse kernels against the triad bandwidth floor (same run)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return True


def plot_newton_share(runs, out):
    best = best_per_size(sweep_runs(runs, "BM_NewtonSolve", "mms-neohookean"))
    if not best:
        return False
    fig, ax = plt.subplots(figsize=(8, 4.2))
    labels, asm, sol = [], [], []
    for sk, pts in sorted(best.items()):
        for unknowns, r in pts:
            labels.append(f"{series_label(*sk)}\n{int(unknowns)}\n{r['combo']}")
            asm.append(r.get("assembly_s", 0.0))
            sol.append(r.get("solve_s", 0.0))
    x = np.arange(len(labels))
    total = np.array(asm) + np.array(sol)
    share = np.array(asm) / np.where(total > 0, total, 1.0)
    ax.bar(x, share, label="assembly (energy, gradient, Hessian)")
    ax.bar(x, 1.0 - share, bottom=share, label="linear solves (set-up + solve)")
    for xi, t in zip(x, total):
        ax.annotate(f"{t:.3g} s", (xi, 1.01), ha="center", fontsize=7)
    ax.set_ylim(0, 1.1)
    ax.set_xticks(x)
    ax.set_xticklabels(labels, fontsize=6)
    ax.set_ylabel("share of the Newton solve's time")
    ax.set_title("Assembly vs linear solves in Newton (fastest combination per order and size; total on top)",
                 fontsize=9)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return True


def plot_sweep(directory):
    """Makes the sweep's plots in `directory` if its JSON is there; returns the PNG names."""
    directory = Path(directory)
    path = directory / "solver_benchmarks.json"
    if not path.exists():
        return []
    with open(path) as f:
        runs = parse(json.load(f), load_skips(directory / "solver_skips.json"))
    made = []
    hist_path = directory / "solver_histories.json"
    if hist_path.exists():
        with open(hist_path) as f:
            if plot_histories(json.load(f), directory / "solver_residual_history.png"):
                made.append("solver_residual_history.png")
    for fn, name in ((plot_time_vs_unknowns, "solver_time_vs_unknowns.png"),
                     (plot_work_precision, "solver_work_precision.png"),
                     (plot_bandwidth, "solver_bandwidth.png"),
                     (plot_newton_share, "solver_newton_share.png")):
        if fn(runs, directory / name):
            made.append(name)
    print_tables(runs)
    return made


if __name__ == "__main__":
    print("plots:", ", ".join(plot_sweep(sys.argv[1] if len(sys.argv) > 1 else "reports")))
