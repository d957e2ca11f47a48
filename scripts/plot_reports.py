#!/usr/bin/python3
"""Turns reports/verification.json and reports/benchmarks.json into PNG plots and
prints a short summary table; with reports/solver_benchmarks.json (the solver
sweep) also its plots, tables and target verdicts (scripts/plot_solver_sweep.py). Run with Debian's interpreter (python3-numpy,
python3-matplotlib): /usr/bin/python3 scripts/plot_reports.py reports
"""
import json
import math
import re
import sys
from pathlib import Path

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as e:  # pragma: no cover - environment problem, say what is missing
    sys.exit(f"plot_reports: {e}; install the Debian packages python3-numpy python3-matplotlib "
             f"and run with /usr/bin/python3")

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_json import base_name, representatives  # noqa: E402
from plot_solver_sweep import plot_sweep  # noqa: E402  (the solver sweep)

RULE_NAME = re.compile(r"^(\w+) (\S+) \(n=(\d+), degree (\d+)\)$")


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        sys.exit(f"plot_reports: {path} not found (run scripts/run first)")
    except json.JSONDecodeError as e:
        sys.exit(f"plot_reports: {path}: invalid JSON at line {e.lineno}: {e.msg}")


def measurements(report, group):
    return [m for m in report.get("measurements", []) if m["group"] == group]


def family(rule_id):
    for prefix, fam in (("gauss-legendre", "Gauss-Legendre"), ("gauss-tensor", "tensor Gauss"),
                        ("collapsed", "collapsed Gauss"), ("hammer", "Hammer (thesis)")):
        if rule_id.startswith(prefix):
            return fam
    return rule_id.split("-")[0]  # published source: WV15, CCGV22, Pap16, ...


def plot_points(report, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, cell, dim in zip(axes, ("triangle", "tet"), (2, 3)):
        q = sorted((int(m["name"].split()[1]), m["value"]) for m in measurements(report, "quadrature.points_query")
                   if m["name"].startswith(cell + " "))
        c = sorted((int(m["name"].split()[1]), m["value"]) for m in measurements(report, "quadrature.points_collapsed")
                   if m["name"].startswith(cell + " "))
        deg = np.array([d for d, _ in q])
        ax.semilogy(deg, [v for _, v in c], "s--", color="0.5", label="collapsed Gauss (Stroud)")
        ax.semilogy(deg, [v for _, v in q], "o-", label="hofem query (fewest positive-interior)")
        # Lower bound N >= dim P_floor(p/2) (Cools 1997).
        k = deg // 2
        bound = [math.comb(int(kk) + dim, dim) for kk in k]
        ax.semilogy(deg, bound, ":", color="k", label="lower bound dim P_{p/2}")
        ax.set_title(f"{cell}: quadrature points vs degree")
        ax.set_xlabel("degree of exactness p")
        ax.set_ylabel("points")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def plot_exactness(report, out):
    rows = [r for r in report["rows"] if r["group"] == "quadrature.exactness"]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    by_family = {}
    threshold = None
    for r in rows:
        m = RULE_NAME.match(r["name"])
        if not m:
            continue
        cell, rid, _, deg = m.groups()
        key = f"{cell}: {family(rid)}"
        by_family.setdefault(key, ([], []))
        by_family[key][0].append(int(deg))
        by_family[key][1].append(max(float(r["measured"]), 1e-18))
        threshold = r["threshold"]
    colours = plt.get_cmap("tab20").colors
    markers = "os^Dv<>p*hX"
    for i, (key, (d, e)) in enumerate(sorted(by_family.items())):
        ax.semilogy(d, e, markers[i % len(markers)], ms=4, color=colours[i % len(colours)], label=key)
    if threshold:
        ax.axhline(threshold, color="r", ls="--", label=f"threshold {threshold:g}")
    ax.set_xlabel("degree of exactness")
    ax.set_ylabel("max relative monomial error")
    ax.set_title("Quadrature exactness: every rule, every monomial up to its degree")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def plot_conditioning(report, out):
    ortho = {r["name"]: r["measured"] for r in report["rows"] if r["group"] == "basis.vandermonde_condition"}
    mono = {m["name"]: m["value"] for m in measurements(report, "basis.vandermonde_condition_monomial")}
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for cell, marker in (("triangle", "o"), ("tet", "s")):
        names = sorted((n for n in ortho if n.startswith(cell + " ")), key=lambda n: int(n.split()[-1]))
        p = [int(n.split()[-1]) for n in names]
        ax.semilogy(p, [ortho[n] for n in names], marker + "-", label=f"{cell}: orthonormal (Dubiner)")
        ax.semilogy(p, [mono.get(n, float("nan")) for n in names], marker + "--", label=f"{cell}: monomial (thesis 4.28)")
    ax.set_xlabel("Lagrange order p")
    ax.set_ylabel("cond_2 of the Vandermonde matrix")
    ax.set_title("Why the basis is built over orthonormal polynomials")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def mms_series(report):
    """{(problem, cell, order, mesh): [(n, h, dofs, l2, h1, seconds)]} from the measurements."""
    values = {}
    for m in report.get("measurements", []):
        if m["group"] in ("mms.l2_error", "mms.h1_error", "mms.dofs", "mms.seconds"):
            values.setdefault(m["name"], {})[m["group"]] = m["value"]
    series = {}
    for name, v in values.items():
        problem, cell, order, mesh, n = name.split("|")
        n = int(n[1:])
        series.setdefault((problem, cell, int(order[1:]), mesh), []).append(
            (n, 1.0 / n, v.get("mms.dofs"), v.get("mms.l2_error"), v.get("mms.h1_error"), v.get("mms.seconds")))
    for k in series:
        series[k].sort()
    return series


def plot_convergence(report, out):
    series = mms_series(report)
    if not series:
        return False
    problems = sorted({k[0] for k in series})
    fig, axes = plt.subplots(len(problems), 3, figsize=(15, 4.2 * len(problems)), squeeze=False)
    for row, problem in enumerate(problems):
        ax_h, ax_dof, ax_time = axes[row]
        for (prob, cell, order, mesh), pts in sorted(series.items()):
            if prob != problem:
                continue
            label = f"{cell} p={order}{' perturbed' if mesh == 'perturbed' else ''}"
            style = "--" if mesh == "perturbed" else "-"
            h = np.array([p[1] for p in pts])
            dofs = np.array([p[2] for p in pts], dtype=float)
            l2 = np.array([p[3] for p in pts])
            secs = np.array([p[5] for p in pts])
            line, = ax_h.loglog(h, l2, "o" + style, label=label)
            # Reference slope h^(p+1) through the finest point.
            ax_h.loglog(h, l2[-1] * (h / h[-1]) ** (order + 1), ":", color=line.get_color(), alpha=0.6)
            ax_dof.loglog(dofs, l2, "o" + style, color=line.get_color(), label=label)
            ax_time.loglog(secs, l2, "o" + style, color=line.get_color(), label=label)
        ax_h.set_title(f"{problem}: L2 error vs h (dotted: h^(p+1))")
        ax_h.set_xlabel("h")
        ax_dof.set_title(f"{problem}: L2 error vs DOFs")
        ax_dof.set_xlabel("free DOFs")
        ax_time.set_title(f"{problem}: work-precision (direct solver)")
        ax_time.set_xlabel("wall time per solve [s]")
        for ax in (ax_h, ax_dof, ax_time):
            ax.set_ylabel("L2 error")
            ax.grid(True, which="both", alpha=0.3)
        ax_h.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return True


def plot_h1(report, out):
    series = mms_series(report)
    if not series:
        return False
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (prob, cell, order, mesh), pts in sorted(series.items()):
        h = np.array([p[1] for p in pts])
        h1 = np.array([p[4] for p in pts])
        line, = ax.loglog(h, h1, "o-" if mesh == "uniform" else "s--", ms=4,
                          label=f"{prob} {cell} p={order} {mesh}")
        ax.loglog(h, h1[-1] * (h / h[-1]) ** order, ":", color=line.get_color(), alpha=0.5)
    ax.set_xlabel("h")
    ax.set_ylabel("H1-seminorm error")
    ax.set_title("H1 error vs h (dotted: h^p)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return True


def bench_medians(bench):
    """name without Google Benchmark's suffixes -> (median real time, unit, entry):
    each benchmark's median aggregate, or its single run (bench_json.representatives)."""
    return {base_name(b.get("run_name", b["name"])): (b["real_time"], b["time_unit"], b) for b in representatives(bench)}


def plot_bench(bench, out):
    med = bench_medians(bench)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, prefix, title in ((axes[0], "BM_Tabulate", "tabulation over the degree-2p rule"),
                              (axes[1], "BM_BuildLagrangeBasis", "building the Lagrange basis")):
        for cell in ("triangle", "tet"):  # names BM_Tabulate/tet/order:3
            pts = sorted((int(n.split("/")[2].split(":")[1]), v[0]) for n, v in med.items()
                         if n.startswith(prefix + "/" + cell + "/order:"))
            if pts:
                ax.semilogy([p for p, _ in pts], [t for _, t in pts], "o-", label=cell)
        ax.set_xlabel("order p")
        ax.set_ylabel("median time [us]")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def summary(report, bench):
    s = report["summary"]
    print(f"\nverification: {s['checks']} checks, {s['passed']} passed, {s['failed']} failed")
    print(f"{'group':34} {'checks':>7} {'failed':>7}")
    for g, c in sorted(s["groups"].items()):
        print(f"{g:34} {c['checks']:>7} {c['failed']:>7}")
    worst = {}
    for r in report["rows"]:
        if r["compare"] == "<=" and isinstance(r["measured"], (int, float)) and r["threshold"] > 0:
            ratio = r["measured"] / r["threshold"]
            if ratio > worst.get(r["group"], (0, ""))[0]:
                worst[r["group"]] = (ratio, r["name"], r["measured"])
    print("\nclosest to failing (measured / threshold):")
    for g, (ratio, name, meas) in sorted(worst.items()):
        print(f"  {g:32} {ratio:9.3g}  {name}: {meas:.3g}")
    med = bench_medians(bench)
    print("\nbenchmarks (median of 3 repetitions):")
    for key in ("BM_GaussLegendre/points:64", "BM_CollapsedRule/tet/degree:30", "BM_BuildLagrangeBasis/tet/order:3",
                "BM_BuildLagrangeBasis/tet/order:6", "BM_Tabulate/tet/order:2", "BM_Tabulate/tet/order:3",
                "BM_Tabulate/tet/order:6", "BM_CachedTabulation/tet/order:3", "BM_EvaluateAtPoint/tet/order:3"):
        if key in med:
            t, unit, _ = med[key]
            print(f"  {key:32} {t:12.4g} {unit}")
    ctx = bench.get("context", {})
    print(f"  machine: {ctx.get('num_cpus', '?')} cpus @ {ctx.get('mhz_per_cpu', '?')} MHz, build: {ctx.get('hofem_build_type', '?')} {ctx.get('hofem_compiler', '')} commit {ctx.get('hofem_commit', '?')[:10]}")


def plot_assembly(bench, out):
    med = bench_medians(bench)
    kinds = ["Tet4", "Tet10", "Tet20", "Hex8", "Hex20"]
    materials = ["linear", "stvk", "corotated", "neohookean", "stable-neohookean"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for ax, what in zip(axes, ("Energy", "Gradient", "Hessian")):
        width = 0.15
        for mi, mat in enumerate(materials):
            rates = []
            for kind in kinds:  # names BM_AssembleHessian/tet10/neohookean
                b = med.get(f"BM_Assemble{what}/{kind.lower()}/{mat}")
                rates.append(b[2].get("qpoints_per_s", float("nan")) if b else float("nan"))
            ax.bar(np.arange(len(kinds)) + (mi - 2) * width, rates, width, label=mat)
        ax.set_xticks(np.arange(len(kinds)))
        ax.set_xticklabels(kinds)
        ax.set_yscale("log")
        ax.set_ylabel("quadrature points / s")
        ax.set_title(f"{what} assembly throughput")
        ax.grid(True, axis="y", which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def print_mms_table(report):
    series = mms_series(report)
    if not series:
        return
    print("\nmanufactured solutions (L2 / H1 errors, observed rates on consecutive pairs):")
    for (prob, cell, order, mesh), pts in sorted(series.items()):
        print(f"  {prob} {cell} p={order} {mesh}")
        prev = None
        for n, h, dofs, l2, h1, secs in pts:
            rates = ""
            if prev:
                rl2 = math.log(prev[3] / l2) / math.log(prev[1] / h)
                rh1 = math.log(prev[4] / h1) / math.log(prev[1] / h)
                rates = f"  rates L2 {rl2:5.2f}  H1 {rh1:5.2f}"
            print(f"    n={n:3d} dofs={int(dofs):8d}  L2 {l2:.3e}  H1 {h1:.3e}  {secs:7.2f} s{rates}")
            prev = (n, h, dofs, l2, h1)


def plot_time_to_error(reports):
    """reports/time_to_error.json (BM_TimeToError): work-precision plot, total
    time to solution vs L2 error per problem and order, one line per solver,
    and the table of the targets (medians of this run)."""
    path = reports / "time_to_error.json"
    if not path.exists():
        return
    med = bench_medians(load(path))
    series = {}
    for name, (t, unit, b) in med.items():
        if not name.startswith("BM_TimeToError/") or b.get("error_occurred"):
            continue
        _, problem, order, n, solver = name.split("/")[:5]
        label = f"{problem} P{order[1:]} {solver}"
        series.setdefault((problem, int(order[1:]), solver, label), []).append(
            (b["total_s"], b["l2_error"], int(n[1:]), b))
    if not series:
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    colours = {1: "tab:green", 2: "tab:blue", 3: "tab:red"}
    for (problem, order, solver, label), pts in sorted(series.items()):
        ax = axes[0 if problem == "linear" else 1]
        pts.sort(key=lambda p: p[2])
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-" if solver == "auto" else "s--",
                  color=colours.get(order, "black"), label=label, alpha=1.0 if solver == "auto" else 0.6)
        for t, e, n, b in pts:  # n, and for auto the solver it chose
            used = b["label"].split("|")[1]
            ax.annotate(f"n={n}" + (f" {used}" if solver == "auto" else ""), (t, e), textcoords="offset points",
                        xytext=(4, 3), fontsize=6)
    for ax, title in zip(axes, ("linear elasticity (one solve)", "Neo-Hookean (Newton)")):
        ax.set_xlabel("time to solution [s], median of 3\n(DOF map, pattern, load, assembly, solver set-up, solve)")
        ax.set_ylabel("L2 error against u*")
        ax.set_title(f"work-precision, manufactured cube: {title}", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(reports / "time_to_error.png", dpi=110)
    plt.close(fig)
    print("\n## Time to error (BM_TimeToError medians, 2 cores)\n")
    print("| case | solver used | unknowns | total s | setup / assembly / solve s | solver set-up s (us/unknown) "
          "| iterations (linear / Newton) | L2 error | reference L2 | diff | peak MB |")
    print("|---|---|---:|---:|---|---|---|---:|---:|---:|---:|")
    for (problem, order, solver, label), pts in sorted(series.items()):
        for t, e, n, b in sorted(pts, key=lambda p: p[2]):
            print(f"| {problem} P{order} n={n} {solver} | {b['label'].split('|')[1]} | {b['unknowns']:.0f} | {t:.3f} "
                  f"| {b['setup_s']:.3f} / {b['assembly_s']:.3f} / {b['solve_s']:.3f} "
                  + (f"| {b['solver_setup_s']:.3f} ({b['solver_setup_us_per_unknown']:.2f}) " if "solver_setup_s" in b
                     else "| (direct: its solve) ")
                  + f"| {b['linear_iterations']:.0f} / {b['newton_iterations']:.0f} | {e:.4e} "
                  f"| {b['reference_l2_error']:.4e} | {b['l2_vs_reference']:.1e} | {b['peak_mb']:.0f} |")
    targets = (("linear", 3, 12, 1.8), ("linear", 2, 16, 0.9), ("neohookean", 3, 8, 1.3), ("linear", 3, 16, 4.5))
    print("\n| target | total s (auto) | limit s | verdict |\n|---|---:|---:|---|")
    for problem, order, n, limit in targets:
        hit = [p for (pr, o, sv, _), pts in series.items() if pr == problem and o == order and sv == "auto"
               for p in pts if p[2] == n]
        if hit:
            t = hit[0][0]
            print(f"| {problem} P{order} n={n} | {t:.3f} | {limit} | {'met' if t <= limit else 'NOT met'} |")


def print_kernel_floors(bench):
    """The machine floors of this run beside the kernels measured against them:
    BM_ElementKernel (executed GFLOP/s over the FMA peak on as many threads) and
    BM_PmgIteration (time over bytes at the all-thread triad; target <= 1.5)."""
    med = bench_medians(bench)
    rows = [(n, b) for n, (t, u, b) in med.items() if n.startswith(("BM_ElementKernel/", "BM_PmgIteration/", "BM_FmaPeak/"))]
    if not rows:
        return
    print("\n| kernel | measured | floor | ratio |\n|---|---:|---:|---:|")
    for name, b in sorted(rows):
        if name.startswith("BM_FmaPeak/"):
            print(f"| FMA peak, {int(b['threads'])} thread(s) | {b['GFLOPs']:.1f} GF/s | | |")
        elif name.startswith("BM_ElementKernel/"):
            # GFLOPs is a rate counter: (FLOPs / 1e9) per second of the benchmark's time
            print(f"| element Hessian {b.get('label', name)} | {b['GFLOPs']:.1f} GF/s "
                  f"| {b['fma_peak_GFLOPs']:.0f} GF/s | {b['GFLOPs'] / b['fma_peak_GFLOPs']:.1%} |")
        else:
            # one iteration: the counter (a difference of two timed CG runs, bench_bandwidth.cpp)
            print(f"| {b.get('label', name)} | {b['seconds_per_iteration'] * 1e3:.1f} ms, {b['bytes'] / 1e6:.0f} MB "
                  f"| {b['floor_seconds'] * 1e3:.1f} ms at {b['triad_all_threads_GBps']:.1f} GB/s | {b['floor_ratio']:.2f} |")


def plot_scaling(path):
    """reports/scaling.json (BM_Scaling, scripts/scaling): time, iterations and
    peak memory per unknown against unknowns, the table, and the ratio of P3
    n = 24's time per unknown to n = 12's (target <= 1.3)."""
    med = bench_medians(load(path))
    series = {}
    for name, (t, unit, b) in med.items():
        if not name.startswith("BM_Scaling/") or b.get("error_occurred"):
            continue
        _, problem, order, n, solver = name.split("/")[:5]
        series.setdefault(int(order[1:]), []).append((int(n[1:]), b))
    print("\n| order | n | unknowns | total s | us/unknown | CG its | peak MB | peak bytes/unknown |\n"
          "|---|---:|---:|---:|---:|---:|---:|---:|")
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for order, pts in sorted(series.items()):
        pts.sort()
        for n, b in pts:
            print(f"| P{order} | {n} | {b['unknowns']:.0f} | {b['total_s']:.2f} | {b['us_per_unknown']:.2f} "
                  f"| {b['linear_iterations']:.0f} | {b['peak_mb']:.0f} | {b['peak_bytes_per_unknown']:.0f} |")
        u = [b["unknowns"] for _, b in pts]
        ax[0].semilogx(u, [b["us_per_unknown"] for _, b in pts], "o-", label=f"linear P{order}")
        ax[1].semilogx(u, [b["peak_bytes_per_unknown"] / 1e3 for _, b in pts], "o-", label=f"linear P{order}")
    ax[0].set_xlabel("free unknowns")
    ax[0].set_ylabel("time to solution per unknown (us)")
    ax[1].set_xlabel("free unknowns")
    ax[1].set_ylabel("peak memory per unknown (kB)")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend()
    fig.suptitle("Linear cube, CG + p-multigrid, 2 threads: cost per unknown with size")
    fig.tight_layout()
    fig.savefig(path.with_suffix(".png"), dpi=120)
    p3 = {n: b for n, b in series.get(3, [])}
    if 12 in p3 and 24 in p3:
        ratio = p3[24]["us_per_unknown"] / p3[12]["us_per_unknown"]
        print(f"\nP3 n=24 / n=12 time per unknown: {ratio:.2f} (target <= 1.3: {'met' if ratio <= 1.3 else 'NOT met'})")


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--scaling":
        plot_scaling(Path(sys.argv[2]))
        return
    reports = Path(sys.argv[1] if len(sys.argv) > 1 else "reports")
    report = load(reports / "verification.json")
    bench = load(reports / "benchmarks.json")
    plot_points(report, reports / "quadrature_points.png")
    plot_exactness(report, reports / "quadrature_exactness.png")
    plot_conditioning(report, reports / "basis_conditioning.png")
    plot_bench(bench, reports / "benchmark_foundation.png")
    plot_convergence(report, reports / "mms_convergence.png")
    plot_h1(report, reports / "mms_h1.png")
    plot_assembly(bench, reports / "benchmark_assembly.png")
    summary(report, bench)
    print_mms_table(report)
    print_kernel_floors(bench)
    plot_time_to_error(reports)  # BM_TimeToError
    plot_sweep(reports)  # solver_benchmarks.json and solver_histories.json, if the sweep ran
    print(f"\nplots: {', '.join(sorted(p.name for p in reports.glob('*.png')))}")


if __name__ == "__main__":
    main()
