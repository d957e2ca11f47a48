#!/usr/bin/python3
"""ctest bench.implicit_step: BM_ImplicitStep (bench_implicit_step.cpp) runs from
its stored states and measures what it claims to.

    implicit_step_check.py HOFEM_BENCH WORKDIR

Runs the Hex20 FCM case (auto and CHOLMOD, one repetition each) and fails
(exit 1, with the reason) unless each row
  - has no error (a state that cannot be read or a run that failed is an error),
  - took one implicit step with Newton iterations >= 1 and a positive time,
  - reports the unknowns of the case (> 0) and a peak RSS per unknown > 0,
  - auto ran an iterative solver (Krylov iterations > 0) and CHOLMOD none:
    otherwise the two rows would not compare what the table says.
"""
import json
import subprocess
import sys
from pathlib import Path


def main() -> int:
    bench, workdir = sys.argv[1], Path(sys.argv[2])
    workdir.mkdir(parents=True, exist_ok=True)
    out = workdir / "implicit_step.json"
    run = subprocess.run([bench, "--benchmark_filter=^BM_ImplicitStep/hex20-fcm/", "--benchmark_repetitions=1",
                          f"--benchmark_out={out}", "--benchmark_out_format=json"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        print(f"implicit_step_check: hofem_bench exited {run.returncode}: {run.stderr[-2000:]}")
        return 1
    rows = {b["name"].split("/")[2]: b for b in json.loads(out.read_text())["benchmarks"]
            if b.get("run_type") == "iteration"}
    problems = []
    if set(rows) != {"auto", "cholmod"}:
        problems.append(f"rows {sorted(rows)}, expected auto and cholmod")
    for name, b in rows.items():
        if b.get("error_occurred"):
            problems.append(f"{name}: {b.get('error_message')}")
            continue
        for key, ok in (("newton_iterations", b.get("newton_iterations", 0) >= 1), ("real_time", b.get("real_time", 0) > 0),
                        ("unknowns", b.get("unknowns", 0) > 0),
                        ("peak_rss_bytes_per_unknown", b.get("peak_rss_bytes_per_unknown", 0) > 0)):
            if not ok:
                problems.append(f"{name}: {key} = {b.get(key)}")
        krylov = b.get("krylov_iterations", -1)
        if (name == "auto") != (krylov > 0):
            problems.append(f"{name}: {krylov} Krylov iterations")
    for p in problems:
        print(f"implicit_step_check: {p}")
    if problems:
        return 1
    print(f"implicit_step_check: {len(rows)} rows, auto {rows['auto']['real_time']:.0f} ms "
          f"({rows['auto']['krylov_iterations']:.0f} Krylov iterations), cholmod {rows['cholmod']['real_time']:.0f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
