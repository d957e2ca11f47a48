"""The benchmark headline figures of reports/index.html (scripts/report/report_index.py):
the dozen numbers a reader of the main job's run looks for first, taken from the
files the run wrote, each with the file it came from.

- time to solution of the manufactured cube at the finest size of each problem
  and order (`time_to_error.json`, the `auto` solver), beside CHOLMOD at the
  largest size both ran (the comparison DEVELOPERS.md's time-to-error table makes);
- the fastest solver configuration per element and order at the largest size
  of the solver sweep (`solver_benchmarks.json`; solver_sweep_tables.py prints
  the fastest at every size);
- the machine floors measured in the same run and the kernels against them
  (`benchmarks.json`: FMA peak, element Hessians; `solver_benchmarks.json`:
  triad; the pmg-CG iteration over its bytes at the triad), the figures
  plot_reports.py prints and DEVELOPERS.md quotes;
- how many built-in scenes completed (`scenes/*/stats.json`).
Each function returns rows (figure, value, context, source) or [] when its
file is absent; a field that is missing raises KeyError, which the caller
reports with the file's name."""
import glob
import os
import statistics
import sys

# bench_json (reading Google Benchmark JSON) is shared with the plots; it is in scripts/plots/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "plots"))
from bench_json import base_name, representatives  # noqa: E402
from report_html import load_json  # noqa: E402

UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def seconds(entry):
    return entry["real_time"] * UNIT_SECONDS[entry.get("time_unit", "ns")]


def time_to_error_rows(reports):
    bench = load_json(reports, "time_to_error.json")
    if bench is None:
        return []
    runs = {}  # (problem, order, solver) -> {n: entry}
    for b in representatives(bench):
        parts = base_name(b.get("run_name", b["name"])).split("/")
        if parts[0] != "BM_TimeToError" or b.get("error_occurred") or len(parts) < 5:
            continue
        _, problem, order, n, solver = parts[:5]
        runs.setdefault((problem, order, solver), {})[int(n.lstrip("n"))] = b
    rows = []
    for (problem, order, solver), by_n in sorted(runs.items()):
        if solver != "auto":
            continue
        n = max(by_n)
        b = by_n[n]
        used = b.get("label", "").split("|")[-1] or "auto"
        context = ""
        direct = runs.get((problem, order, "cholmod"), {})
        common = [k for k in direct if k in by_n]
        if common:
            m = max(common)
            t_direct, t_auto = direct[m]["total_s"], by_n[m]["total_s"]
            context = (f"at n = {m}: CHOLMOD {t_direct:.3g} s, auto {t_auto:.3g} s "
                       f"({t_direct / t_auto:.1f}x faster)")
        rows.append((f"time to solution, {problem} {order.upper()} n = {n} ({b['unknowns']:.0f} unknowns)",
                     f"{b['total_s']:.3g} s to L2 error {b['l2_error']:.3g} ({used})", context, "time_to_error.json"))
    return rows


def fastest_solver_rows(reports):
    """For the manufactured problems (linear solve, Neo-Hookean Newton solve),
    per element and order at the largest size the sweep reached, the fastest
    configuration and the runner-up (medians over successful repetitions)."""
    bench = load_json(reports, "solver_benchmarks.json")
    if bench is None:
        return []
    times = {}  # (kind, problem, element, order, n) -> {configuration: ([seconds], entry)}
    for b in bench.get("benchmarks", []):
        parts = base_name(b.get("run_name", b["name"])).split("/")
        if b.get("run_type") == "aggregate" or b.get("error_occurred") or len(parts) < 6:
            continue
        if (parts[0], parts[1]) in (("BM_LinearSolve", "mms-linear"), ("BM_NewtonSolve", "mms-neohookean")):
            size = tuple(parts[:4]) + (int(parts[4].lstrip("n")),)
            times.setdefault(size, {}).setdefault("/".join(parts[5:]), ([], b))[0].append(seconds(b))
    largest = {}
    for size in times:
        if size[:4] not in largest or size[4] > largest[size[:4]]:
            largest[size[:4]] = size[4]
    rows = []
    for key, n in sorted(largest.items()):
        ranked = sorted((statistics.median(ts), config, b) for config, (ts, b) in times[key + (n,)].items())
        t, config, b = ranked[0]
        context = f"next {ranked[1][1]} {ranked[1][0]:.3g} s ({ranked[1][0] / t:.2f}x)" if len(ranked) > 1 else ""
        what = "Newton solve" if key[0] == "BM_NewtonSolve" else "linear solve"
        rows.append((f"fastest {what}, {key[1]} {key[2]} {key[3].upper()} n = {n} ({b['unknowns']:.0f} unknowns)",
                     f"{t:.3g} s: {config}", f"{context}; {len(ranked)} configurations ran".lstrip("; "),
                     "solver_benchmarks.json"))
    return rows


def floor_rows(reports):
    rows = []
    bench = load_json(reports, "benchmarks.json")
    entries = representatives(bench) if bench else []
    fma = [b for b in entries if b["name"].startswith("BM_FmaPeak/")]
    if fma:
        b = max(fma, key=lambda e: e["threads"])
        rows.append((f"FMA peak, {b['threads']:.0f} threads", f"{b['GFLOPs']:.1f} GF/s", b.get("label", ""),
                     "benchmarks.json"))
    kernels = [b for b in entries if b["name"].startswith("BM_ElementKernel/") and "fma_peak_GFLOPs" in b]
    if kernels:
        b = max(kernels, key=lambda e: e["GFLOPs"] / e["fma_peak_GFLOPs"])
        rows.append((f"best element Hessian kernel ({b.get('label', b['name'])})",
                     f"{b['GFLOPs']:.1f} GF/s = {b['GFLOPs'] / b['fma_peak_GFLOPs']:.1%} of the FMA peak",
                     "FLOPs executed (element_hessian_flops), dP/dF not counted", "benchmarks.json"))
    for b in (e for e in entries if e["name"].startswith("BM_PmgIteration/")):
        rows.append((f"one pmg-CG iteration ({b.get('label', b['name'])})",
                     f"{b['floor_ratio']:.2f}x its time at the triad",
                     f"{b['bytes'] / 1e6:.0f} MB at {b['triad_all_threads_GBps']:.1f} GB/s", "benchmarks.json"))
    sweep = load_json(reports, "solver_benchmarks.json")
    triads = [b for b in representatives(sweep) if b["name"].startswith("BM_Triad/")] if sweep else []
    if triads:
        b = max(triads, key=lambda e: e["threads"])
        rows.append((f"triad bandwidth, {b['threads']:.0f} threads", f"{b['achieved_GBps']:.1f} GB/s",
                     b.get("label", ""), "solver_benchmarks.json"))
    return rows


def scene_rows(reports):
    paths = sorted(glob.glob(os.path.join(reports, "scenes", "*", "stats.json")))
    if not paths:
        return []
    stats = {os.path.basename(os.path.dirname(p)): load_json(reports, os.path.relpath(p, reports)) for p in paths}
    done = [n for n, s in stats.items() if s["ok"]]
    slowest = max(stats, key=lambda n: stats[n]["wall_seconds"])
    failed = sorted(set(stats) - set(done))
    return [("built-in scenes completed", f"{len(done)} of {len(stats)}",
             (f"failed: {', '.join(failed)}; " if failed else "")
             + f"slowest {slowest} {stats[slowest]['wall_seconds']:.3g} s", "scenes/*/stats.json")]


def headline_rows(reports):
    return time_to_error_rows(reports) + fastest_solver_rows(reports) + floor_rows(reports) + scene_rows(reports)
