#!/usr/bin/python3
"""Turns reports/verification.json, reports/convergence.json (the manufactured-solution
study's table, through scripts/plots/plot_convergence.py) and reports/benchmarks.json into PNG
plots (their look shared through scripts/plots/plot_style.py) and prints a short summary table; with reports/solver_benchmarks.json (the solver
sweep) also its plots, tables and target verdicts (scripts/plots/plot_solver_sweep.py). Run with Debian's interpreter (python3-numpy,
python3-matplotlib): /usr/bin/python3 scripts/plots/plot_reports.py reports
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
import plot_convergence  # noqa: E402  (mms_convergence.png, mms_h1.png from convergence.json)
import plot_style  # noqa: E402
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
        ax.set_xlabel("degree of exactness p [-]")
        ax.set_ylabel("quadrature points [-]")
        plot_style.log_ticks(ax)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    plot_style.save(fig, out, dpi=120)


def plot_exactness(report, out):
    rows = [r for r in report["rows"] if r["group"] == "quadrature.exactness"]
    fig, ax = plt.subplots(figsize=(12, 5))
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
    ax.set_xlabel("degree of exactness [-]")
    ax.set_ylabel("max relative monomial error [-]")
    ax.set_title("Quadrature exactness: every rule, every monomial up to its degree")
    ax.grid(True, which="both", alpha=0.3)
    # Many rule families: the legend goes beside the axes, in a readable size.
    ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE, ncol=2, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    plot_style.save(fig, out, dpi=120)


def plot_conditioning(report, out):
    ortho = {r["name"]: r["measured"] for r in report["rows"] if r["group"] == "basis.vandermonde_condition"}
    mono = {m["name"]: m["value"] for m in measurements(report, "basis.vandermonde_condition_monomial")}
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for cell, marker in (("triangle", "o"), ("tet", "s")):
        names = sorted((n for n in ortho if n.startswith(cell + " ")), key=lambda n: int(n.split()[-1]))
        p = [int(n.split()[-1]) for n in names]
        ax.semilogy(p, [ortho[n] for n in names], marker + "-", label=f"{cell}: orthonormal (Dubiner)")
        ax.semilogy(p, [mono.get(n, float("nan")) for n in names], marker + "--", label=f"{cell}: monomial (thesis 4.28)")
    ax.set_xlabel("Lagrange order p [-]")
    ax.set_ylabel("cond_2 of the Vandermonde matrix [-]")
    ax.set_title("Why the basis is built over orthonormal polynomials")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    plot_style.save(fig, out, dpi=120)


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
        ax.set_xlabel("Lagrange order p [-]")
        ax.set_ylabel("median time [us]")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=plot_style.LEGEND_FONTSIZE)
        plot_style.log_ticks(ax)
    plot_style.save(fig, out, dpi=120)


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
    # The materials the benchmark ran (its names BM_AssembleHessian/tet10/<material>
    # follow the material registry), in the order of their first appearance.
    materials = list(dict.fromkeys(k.split("/")[2] for k in med if k.startswith("BM_AssembleHessian/")))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for ax, what in zip(axes, ("Energy", "Gradient", "Hessian")):
        width = 0.15
        for mi, mat in enumerate(materials):
            rates = []
            for kind in kinds:  # names BM_AssembleHessian/tet10/neohookean
                b = med.get(f"BM_Assemble{what}/{kind.lower()}/{mat}")
                rates.append(b[2].get("qpoints_per_s", float("nan")) if b else float("nan"))
            ax.bar(np.arange(len(kinds)) + (mi - (len(materials) - 1) / 2) * width, rates, width, label=mat)
        ax.set_xticks(np.arange(len(kinds)))
        ax.set_xticklabels(kinds)
        ax.set_yscale("log")
        ax.set_xlabel("element")
        ax.set_ylabel("throughput [quadrature points / s]")
        ax.set_title(f"{what} assembly throughput")
        ax.grid(True, axis="y", which="both", alpha=0.3)
        plot_style.log_ticks(ax, "y")
    axes[0].legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
    plot_style.save(fig, out, dpi=110)


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
    for (problem, order, solver, label), pts in sorted(series.items()):
        ax = axes[0 if problem == "linear" else 1]
        pts.sort(key=lambda p: p[2])
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-" if solver == "auto" else "s--",
                  color=plot_style.order_colour(order), label=label, alpha=1.0 if solver == "auto" else 0.6)
        for t, e, n, b in pts:  # n, and for auto the solver it chose
            used = b["label"].split("|")[1]
            ax.annotate(f"n={n}" + (f" {used}" if solver == "auto" else ""), (t, e), textcoords="offset points",
                        xytext=(4, 3), fontsize=7)
    for ax, title in zip(axes, ("linear elasticity (one solve)", "Neo-Hookean (Newton)")):
        ax.set_xlabel("time to solution [s], median of 3\n(DOF map, pattern, load, assembly, solver set-up, solve)")
        ax.set_ylabel("L2 error against u* [-]")
        ax.set_title(f"work-precision, manufactured cube: {title}", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
        plot_style.log_ticks(ax)
    plot_style.save(fig, reports / "time_to_error.png", dpi=110)
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
        colour = plot_style.order_colour(order)
        ax[0].semilogx(u, [b["us_per_unknown"] for _, b in pts], "o-", color=colour, label=f"linear P{order}")
        ax[1].semilogx(u, [b["peak_bytes_per_unknown"] / 1e3 for _, b in pts], "o-", color=colour,
                       label=f"linear P{order}")
    ax[0].set_xlabel("free unknowns [-]")
    ax[0].set_ylabel("time to solution per unknown [us]")
    ax[1].set_xlabel("free unknowns [-]")
    ax[1].set_ylabel("peak memory per unknown [kB]")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=plot_style.LEGEND_FONTSIZE)
        plot_style.log_ticks(a)
    fig.suptitle("Linear cube, CG + p-multigrid, 2 threads: cost per unknown with size")
    plot_style.save(fig, path.with_suffix(".png"), dpi=120)
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
    plot_assembly(bench, reports / "benchmark_assembly.png")
    summary(report, bench)
    if (reports / "convergence.json").exists():  # the study's tidy table (hofem verify)
        plot_convergence.main(reports / "convergence.json", reports)
    else:
        print("\nplot_reports: no convergence.json (hofem verify --convergence none?): no mms plots")
    print_kernel_floors(bench)
    plot_time_to_error(reports)  # BM_TimeToError
    plot_sweep(reports)  # solver_benchmarks.json and solver_histories.json, if the sweep ran
    print(f"\nplots: {', '.join(sorted(p.name for p in reports.glob('*.png')))}")


if __name__ == "__main__":
    main()
