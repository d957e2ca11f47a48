#!/usr/bin/python3
"""The solver sweep's data (parsed from Google Benchmark JSON), its tables and the
verdicts on the sweep's targets, printed as Markdown. Used by plot_solver_sweep.py."""
import math
import re

from bench_json import base_name, representatives

SWEEP_KINDS = ("BM_LinearSolve", "BM_NewtonSolve")
TIME_UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


# Preconditioner names of files written before the context key
# "preconditioner_names" (version 2): their "ic0" was Eigen's incomplete
# Cholesky (Lin-More, memory-limited), which is "eigen-ict" since "ic0" became
# the zero-fill IC(0) of the thesis' Algorithm 2.
OLD_PRECONDITIONER_NAMES = {"ic0": "eigen-ict"}


def current_name(run_name, names_version):
    """The benchmark name under today's preconditioner names."""
    if names_version >= 2:
        return run_name
    parts = run_name.split("/")
    for i, p in enumerate(parts):
        if "+" in p:
            method, pc = p.split("+", 1)
            parts[i] = method + "+" + OLD_PRECONDITIONER_NAMES.get(pc, pc)
    return "/".join(parts)


def skipped_entries(skips):
    """The skips file's configurations (bench_json.load_skips) as entries of the
    form older files kept them in among the results."""
    return [{"name": s["name"], "run_name": s["name"], "error_occurred": True, "error_message": "skipped: " + s["reason"],
             "real_time": 0.0, "time_unit": "ms"} for s in skips]


def parse(bench, skips=()):
    """Runs of the sweep and the bandwidth kernels: the benchmark's JSON entry plus
    kind, problem, cell, order, n, combo, seconds, status ('ok' / 'skipped' /
    'failed'). Of repeated benchmarks only the median aggregate is kept
    (bench_json.representatives); `skips` (bench_json.load_skips) adds the
    configurations skipped on purpose, which today's files keep apart. Names are
    today's (OLD_PRECONDITIONER_NAMES maps an older file's)."""
    version = int(bench.get("context", {}).get("preconditioner_names", "1"))
    if any("eigen-ict" in b["name"] for b in bench.get("benchmarks", [])):
        version = 2  # written between the rename and the context key: already today's names
    entries = [dict(b, name=current_name(b["name"], version),
                    run_name=current_name(b.get("run_name", b["name"]), version))
               for b in representatives(bench) + skipped_entries(skips)]
    runs = []
    for b in entries:
        parts = base_name(b.get("run_name", b["name"])).split("/")
        r = dict(b)
        r["kind"] = parts[0]
        if parts[0] in SWEEP_KINDS + ("BM_SpMV", "BM_CgIteration") and len(parts) >= 5:
            r.update(problem=parts[1], cell=parts[2], order=int(parts[3][1:]), n=int(parts[4][1:]),
                     combo="/".join(parts[5:]))
        msg = b.get("error_message", "")
        r["status"] = "ok" if not b.get("error_occurred") else ("skipped" if msg.startswith("skipped") else "failed")
        # One CG iteration is a difference of two timed runs (BM_CgIteration): a
        # counter; the entry's own time is the longer run's.
        r["seconds"] = b.get("seconds_per_iteration", b["real_time"] * TIME_UNITS[b.get("time_unit", "ns")])
        runs.append(r)
    return runs


def sweep_runs(runs, kind, problem=None):
    return [r for r in runs if r["kind"] == kind and (problem is None or r.get("problem") == problem)]


def series_key(r):
    return (r["cell"], r["order"])


def series_label(cell, order):
    return f"{cell} p={order}" if cell == "tet" else cell


def best_per_size(runs):
    """(cell, order) -> [(unknowns, run)]: the fastest solved run per size."""
    best = {}
    for r in runs:
        if r["status"] != "ok":
            continue
        k = (series_key(r), r["n"])
        if k not in best or r["seconds"] < best[k]["seconds"]:
            best[k] = r
    out = {}
    for (sk, _), r in best.items():
        out.setdefault(sk, []).append((r.get("unknowns", 0), r))
    for v in out.values():
        v.sort(key=lambda t: t[0])
    return out


def fmt(x, spec=".3g"):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def print_best_table(runs, kind, problem):
    best = best_per_size(sweep_runs(runs, kind, problem))
    if not best:
        return
    print(f"\n### {problem}: fastest solved combination per (element, size)\n")
    print("| element | unknowns | combination | time s | set-up s | solve s | iterations | L2 error | rel. residual "
          "| run's MB / process peak MB |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for sk, pts in sorted(best.items()):
        for unknowns, r in pts:
            its = r.get("iterations", r.get("linear_iterations"))
            if kind == "BM_NewtonSolve":
                its = f"{int(r.get('newton_iterations', 0))} N / {int(r.get('linear_iterations', 0))} lin"
            print(f"| {series_label(*sk)} | {int(unknowns)} | {r['combo']} | {fmt(r['seconds'])} | "
                  f"{fmt(r.get('setup_s'))} | {fmt(r.get('solve_s'))} | {its if isinstance(its, str) else fmt(its, '.0f')} | "
                  f"{fmt(r.get('l2_error'))} | {fmt(r.get('rel_residual'))} | {fmt(r.get('extra_MB'), '.0f')} / "
                  f"{fmt(r.get('peak_MB'), '.0f')} |")


def print_status(runs):
    print("\n### Runs made, skipped (with the reason in the skips file) and failed\n")
    print("| benchmark | problem | ok | skipped | failed |")
    print("|---|---|---:|---:|---:|")
    counts = {}
    for r in runs:
        if r["kind"] in SWEEP_KINDS:
            c = counts.setdefault((r["kind"], r["problem"]), {"ok": 0, "skipped": 0, "failed": 0})
            c[r["status"]] += 1
    for (kind, problem), c in sorted(counts.items()):
        print(f"| {kind} | {problem} | {c['ok']} | {c['skipped']} | {c['failed']} |")
    reasons = {}
    for r in runs:
        if r["kind"] in SWEEP_KINDS and r["status"] != "ok":
            key = re.sub(r"[-+]?\d[\d.e+-]*", "#", r.get("error_message", ""))[:110]
            reasons[key] = reasons.get(key, 0) + 1
    print("\nmost frequent reasons (numbers replaced by #):")
    for why, n in sorted(reasons.items(), key=lambda t: -t[1])[:12]:
        print(f"  {n:4d}  {why}")


def print_bandwidth(runs):
    sel = [r for r in runs if r["kind"] in ("BM_SpMV", "BM_CgIteration", "BM_Triad")]
    if not sel:
        return
    print("\n### Bandwidth: kernels against the triad floor of the same run\n")
    print("| kernel | matrix | unknowns | nonzeros | MB moved | time ms | floor ms | time / floor | achieved GB/s | floor GB/s "
          "| triad right after GB/s | time / that floor |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in sel:
        matrix = f"tet P{r['order']} n={r['n']}" if "order" in r else r.get("label", "")
        print(f"| {r['kind'][3:]} | {matrix} | {fmt(r.get('unknowns'), '.0f')} | {fmt(r.get('nonzeros'), '.0f')} | "
              f"{fmt(r.get('bytes', 0) / 1e6, '.1f')} | {fmt(r['seconds'] * 1e3)} | {fmt(r.get('floor_seconds', 0) * 1e3)} | "
              f"{fmt(r.get('floor_ratio'))} | {fmt(r.get('achieved_GBps'))} | {fmt(r.get('floor_GBps'))} | "
              f"{fmt(r.get('triad_now_GBps'))} | {fmt(r.get('floor_ratio_now'))} |")


def print_newton(runs):
    sel = sweep_runs(runs, "BM_NewtonSolve", "mms-neohookean")
    pairs = {}
    for r in sel:
        if r["status"] == "ok" and "/" in r["combo"]:
            solver, variant = r["combo"].rsplit("/", 1)
            pairs.setdefault((r["order"], r["n"], r.get("unknowns", 0), solver), {})[variant] = r
    rows = [(k, v) for k, v in pairs.items() if "ew" in v and "fixed" in v]
    if rows:
        print("\n### Inexact Newton: Eisenstat-Walker (ew) vs fixed linear tolerance 1e-8 (fixed)\n")
        print("| order | unknowns | solver | time fixed s | time ew s | ew / fixed | Newton its fixed / ew | linear its fixed / ew |")
        print("|---:|---:|---|---:|---:|---:|---|---|")
        rows.sort(key=lambda kv: (kv[0][0], kv[0][2], kv[1]["fixed"]["seconds"]))
        for (order, _, unknowns, solver), v in rows:
            f, e = v["fixed"], v["ew"]
            print(f"| {order} | {int(unknowns)} | {solver} | {fmt(f['seconds'])} | {fmt(e['seconds'])} | "
                  f"{fmt(e['seconds'] / f['seconds'], '.2f')} | {int(f['newton_iterations'])} / {int(e['newton_iterations'])} | "
                  f"{int(f['linear_iterations'])} / {int(e['linear_iterations'])} |")
    best = best_per_size(sel)
    if best:
        print("\n### Newton step: assembly vs linear solve (fastest combination per order and size)\n")
        print("| order | unknowns | combination | Newton its | assembly s | solve s | assembly share |")
        print("|---:|---:|---|---:|---:|---:|---:|")
        for sk, pts in sorted(best.items()):
            for unknowns, r in pts:
                print(f"| {sk[1]} | {int(unknowns)} | {r['combo']} | {int(r['newton_iterations'])} | "
                      f"{fmt(r.get('assembly_s'))} | {fmt(r.get('solve_s'))} | {fmt(r.get('assembly_share'), '.2f')} |")


def time_at_error(pts, error):
    """Log-log interpolation of time vs error along a work-precision curve
    [(seconds, error)], extrapolated from the end segment; (time, extrapolated)."""
    pts = sorted(pts, key=lambda p: -p[1])  # decreasing error
    if len(pts) < 2:
        return None, True
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= error <= e0 and e0 > e1:
            s = math.log(error / e0) / math.log(e1 / e0)
            return math.exp(math.log(t0) + s * math.log(t1 / t0)), False
    (t0, e0), (t1, e1) = (pts[-2], pts[-1]) if error < pts[-1][1] else (pts[0], pts[1])
    if e0 <= e1 or t0 <= 0 or t1 <= 0:
        return None, True
    s = math.log(error / e0) / math.log(e1 / e0)
    return math.exp(math.log(t0) + s * math.log(t1 / t0)), True


def print_targets(runs):
    print("\n### The sweep's targets (measured, this run)\n")
    cg = [r for r in runs if r["kind"] == "BM_CgIteration" and r.get("order") == 2]
    for r in cg:
        ratio = r.get("floor_ratio", float("nan"))
        print(f"- one Jacobi-CG iteration, P2, {int(r.get('unknowns', 0))} unknowns: {fmt(ratio)} x the bandwidth floor "
              f"({fmt(r.get('floor_ratio_now'))} x a triad measured right after it; target <= 1.5): "
              f"{'MET' if ratio <= 1.5 else 'NOT MET'}")
    lin = sweep_runs(runs, "BM_LinearSolve", "mms-linear")
    p2 = [r for r in lin if r["status"] == "ok" and r["cell"] == "tet" and r["order"] == 2
          and 5e4 <= r.get("unknowns", 0) <= 2e5]
    if p2:
        b = min(p2, key=lambda r: r["seconds"])
        print(f"- fastest ~1e5-unknown P2 linear solve: {b['combo']}, {int(b['unknowns'])} unknowns, {fmt(b['seconds'])} s "
              f"(set-up {fmt(b.get('setup_s'))} + solve {fmt(b.get('solve_s'))}; target < 1 s): "
              f"{'MET' if b['seconds'] < 1.0 else 'NOT MET'}")
    else:
        print("- ~1e5-unknown P2 linear solve: no solved run in this sweep")
    best = best_per_size([r for r in lin if r["cell"] == "tet"])
    for what, extra in (("linear solve", lambda r: 0.0), ("assembly + linear solve", lambda r: r.get("assembly_s", 0.0))):
        curves = {sk[1]: [(r["seconds"] + extra(r), r["l2_error"]) for _, r in pts if r.get("l2_error")]
                  for sk, pts in best.items()}
        for p in (1, 2):
            if p not in curves or p + 1 not in curves:
                continue
            verdicts = []
            for e in (1e-4, 1e-5, 1e-6):
                lo = min(min(x[1] for x in curves[p]), min(x[1] for x in curves[p + 1]))
                if e < lo / 10:
                    continue
                ta, xa = time_at_error(curves[p], e)
                tb, xb = time_at_error(curves[p + 1], e)
                if ta is None or tb is None:
                    continue
                tag = " (extrapolated)" if xa or xb else ""
                verdicts.append((tb < ta, f"L2 {e:.0e}: P{p} {fmt(ta)} s, P{p + 1} {fmt(tb)} s, ratio {fmt(ta / tb, '.2f')}{tag}"))
            if verdicts:
                met = all(v for v, _ in verdicts)
                print(f"- {what}: P{p + 1} faster than P{p} at equal error <= 1e-4: {'MET' if met else 'NOT MET'} — "
                      + "; ".join(t for _, t in verdicts))


def print_tables(runs):
    for kind, problem in (("BM_LinearSolve", "mms-linear"), ("BM_LinearSolve", "hessian-nh"),
                          ("BM_LinearSolve", "hessian-nh-psd"), ("BM_NewtonSolve", "mms-neohookean")):
        print_best_table(runs, kind, problem)
    print_bandwidth(runs)
    print_newton(runs)
    print_status(runs)
    print_targets(runs)
