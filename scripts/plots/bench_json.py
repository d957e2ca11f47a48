#!/usr/bin/python3
"""Reading the Google Benchmark JSON of build/bin/hofem_bench: one entry per
benchmark (its median when it was repeated), names without the suffixes Google
Benchmark appends, and the configurations skipped on purpose, which are not in
the results but in the file HOFEM_BENCH_SKIPS_OUT named (benchmarks/bench_skip_reporter.hpp)."""
import json
import re
from pathlib import Path

# What Google Benchmark appends to a name for settings made in code
# (Iterations(), Repetitions(), MinTime(), MeasureProcessCPUTime(), UseRealTime(),
# UseManualTime(), Threads()).
SUFFIX = re.compile(r"/(iterations|repeats|min_time|min_warmup_time|threads):[^/]+|/process_time|/manual_time|/real_time")


def base_name(name):
    """BM_LinearSolve/mms-linear/tet/p2/n8/cg+pmg/iterations:1/repeats:5/process_time -> BM_LinearSolve/mms-linear/tet/p2/n8/cg+pmg"""
    return SUFFIX.sub("", name)


def representatives(bench):
    """One entry per benchmark, in file order: its median aggregate when Google
    Benchmark computed aggregates (two or more repetitions that did not fail),
    else its first repetition (a single run, or a failure: every repetition of a
    failure carries the same message)."""
    entries = bench.get("benchmarks", [])
    aggregated = {b.get("run_name") for b in entries if b.get("run_type") == "aggregate"}
    out, seen = [], set()
    for b in entries:
        run = b.get("run_name", b["name"])
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                out.append(b)
        elif run not in aggregated and run not in seen:
            seen.add(run)
            out.append(b)
    return out


def load_skips(path):
    """[{"name", "reason"}] of a skips file; [] when there is none (files written
    before skips had their own file kept them among the results)."""
    path = Path(path)
    if not path.exists():
        return []
    with open(path) as f:
        return json.load(f)["skipped"]
