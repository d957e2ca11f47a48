#!/usr/bin/python3
"""ctest bench.compare_skips: two short runs of the same build, compared by
Google Benchmark's own tools/compare.py, give rows only for runs that were made.

    compare_check.py HOFEM_BENCH COMPARE_PY WORKDIR

Runs hofem_bench twice on a small filter: the solver sweep on the indefinite
Hessian at ~1e3 unknowns, order 1 (where the policy skips the methods that need
a positive-definite matrix, and pmg, which needs order >= 2: both skipped on purpose)
and a few foundation benchmarks, each with HOFEM_BENCH_SKIPS_OUT. Then
compare.py (--dump_to_json) on the two result files. Fails unless
  - both runs recorded configurations skipped on purpose (otherwise this test
    could not see the defect it guards against),
  - no result entry is a skip (message "skipped: ..."): skips are only in the
    skips file, and errors left in the results are failures ("failed: ..."),
  - compare.py ran and produced rows for the sweep and the foundation
    benchmarks, with its U test on at least one of them (repetitions present),
  - no row belongs to a skipped configuration, and no row pairs a zero time
    with a non-zero one (what a skip against a run used to look like: a
    spurious -100 % or +200 %).
"""
import json
import os
import re
import subprocess
import sys
from pathlib import Path

# The sweep's configurations at ~1e3 unknowns (level 0: five repetitions each)
# and tabulation, which repeats by the command line's --benchmark_repetitions.
FILTER = r"^BM_(LinearSolve/hessian-nh/tet/p1/n4/|Tabulate/tet/order:[12]$)"
AGGREGATE = re.compile(r"_(mean|median|stddev|cv)$")


def run_bench(bench, work, tag):
    out, skips = work / f"{tag}.json", work / f"skips_{tag}.json"
    env = dict(os.environ, HOFEM_BENCH_PRESET="quick", HOFEM_BENCH_SKIPS_OUT=str(skips))
    subprocess.run([bench, f"--benchmark_filter={FILTER}", "--benchmark_min_time=0.01", "--benchmark_repetitions=5",
                    f"--benchmark_out={out}", "--benchmark_out_format=json"],
                   env=env, check=True, stdout=subprocess.DEVNULL)
    results = json.loads(out.read_text())
    skipped = {s["name"] for s in json.loads(skips.read_text())["skipped"]}
    return out, results, skipped


def check_results(tag, results, skipped):
    """The results of one run: skips recorded apart, none among the entries."""
    errors = []
    if not skipped:
        errors.append(f"{tag}: no configuration was skipped on purpose; the filter must include some")
    for b in results["benchmarks"]:
        message = b.get("error_message", "")
        if b.get("error_occurred") and not message.startswith("failed: "):
            errors.append(f"{tag}: {b['name']} is an error that is not a failure: {message!r}")
        if b["name"] in skipped or b.get("run_name") in skipped:
            errors.append(f"{tag}: {b['name']} is both in the results and in the skips file")
    return errors


def check_rows(diff, skipped):
    """compare.py's rows: present for both groups, U test run, none for a skip."""
    rows = [r for r in diff if r["name"] != "OVERALL_GEOMEAN"]
    errors = []
    for family in ("BM_LinearSolve/", "BM_Tabulate/"):
        if not any(r["name"].startswith(family) for r in rows):
            errors.append(f"compare.py gave no row for {family}")
    if not any(r.get("utest") for r in rows):
        errors.append("compare.py ran its U test on no row (no repetitions in the results?)")
    for r in rows:
        if AGGREGATE.sub("", r["name"]) in skipped:
            errors.append(f"compare.py row for a skipped configuration: {r['name']}")
        if r.get("run_type") == "aggregate":
            continue  # a skip was an iteration entry; a cv or stddev may be near zero
        for m in r["measurements"]:
            for field in ("real_time", "cpu_time"):
                if (m[field] == 0) != (m[field + "_other"] == 0):
                    errors.append(f"{r['name']}: {field} {m[field]} against {m[field + '_other']}")
    return rows, errors


def main():
    bench, compare, work = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    if not Path(compare).is_file():
        sys.exit(f"compare_check: compare.py not found at '{compare}' (Debian package libbenchmark-tools)")
    work.mkdir(parents=True, exist_ok=True)
    out_a, results_a, skipped_a = run_bench(bench, work, "a")
    out_b, results_b, skipped_b = run_bench(bench, work, "b")
    errors = check_results("a", results_a, skipped_a) + check_results("b", results_b, skipped_b)
    diff_path = work / "diff.json"
    shown = subprocess.run(["/usr/bin/python3", compare, "--no-color", "--dump_to_json", str(diff_path),
                            "benchmarks", str(out_a), str(out_b)], check=True, capture_output=True, text=True)
    rows, row_errors = check_rows(json.loads(diff_path.read_text()), skipped_a | skipped_b)
    errors += row_errors
    print(f"compare_check: {len(results_a['benchmarks'])} / {len(results_b['benchmarks'])} result entries, "
          f"{len(skipped_a)} / {len(skipped_b)} skipped configurations, {len(rows)} compare.py rows, "
          f"{sum(1 for r in rows if r.get('utest'))} with a U test")
    print("\n".join(shown.stdout.splitlines()[:12]))
    if errors:
        print("\n".join(errors[:40]), file=sys.stderr)
        sys.exit(1)
    print("compare_check: no row for a skipped configuration")


if __name__ == "__main__":
    main()
