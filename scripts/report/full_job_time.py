#!/usr/bin/python3
"""The full job's time (scripts/studies-full), study by study, against its budget.

Reads each full-size study file (scripts/studies/full/NAME.json: which runs are in
the "extended" tier) and its results (reports/full/studies/NAME/study.json: each
run's own wall time, `total_seconds`, plus its measurement, `measure_seconds`;
the reference and its coarser level from the study's `run_seconds`) and writes
reports/full/job_time.{md,json}: per study the seconds of the runs the job runs
by default and of the extended tier (`scripts/studies-full --extended`), runs not
measured yet, and the default job's total against the 4 h budget. Times are each
run's own, summed over the sessions that made them (a study run in parts), so
the total is what one uninterrupted job on this machine would take, not the
wall time of any one session.

Usage: full_job_time.py [ROOT]   (ROOT: the repository, default: this script's)
"""
import json
import os
import sys

BUDGET_SECONDS = 4 * 3600  # the full job's budget on this 2-core machine (the studies alone, build excluded)


def run_seconds(row):
    return row.get("total_seconds", 0.0) + row.get("measure_seconds", 0.0)


def study_time(study_file, result_file):
    spec = json.load(open(study_file))
    extended = {r["name"] for r in spec["runs"] if r.get("extended", False)}
    out = {"name": spec["name"], "runs": len(spec["runs"]), "extended_runs": sorted(extended),
           "default_seconds": None, "extended_seconds": 0.0, "not_measured": [], "not_measured_extended": []}
    if not os.path.exists(result_file):
        out["not_measured"] = [r["name"] for r in spec["runs"] if r["name"] not in extended]
        out["not_measured_extended"] = sorted(extended)
        return out
    result = json.load(open(result_file))
    measured = {r["name"]: r for r in result["runs"]}  # a failed run is a row too: it ran
    # run_seconds: reference, coarser level and runs (each run's total, a shared coarser level once);
    # studies written before it existed: the reference's and the runs' totals.
    default = result.get("run_seconds")
    if default is None:
        default = result["reference"].get("total_seconds", 0.0) + sum(
            r.get("total_seconds", 0.0) for r in result["runs"] if not r.get("same_as"))
    for r in result["runs"]:
        if r.get("same_as"):
            continue
        if r["name"] in extended:  # its stepping is in run_seconds, its measurement nowhere yet
            default -= r.get("total_seconds", 0.0)
            out["extended_seconds"] += run_seconds(r)
        else:
            default += r.get("measure_seconds", 0.0)
    out["default_seconds"] = default
    for r in spec["runs"]:
        if r["name"] not in measured:
            (out["not_measured_extended"] if r["name"] in extended else out["not_measured"]).append(r["name"])
    return out


def hours(s):
    return f"{s / 3600:.2f} h" if s is not None else "-"


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    folder = os.path.join(root, "scripts", "studies", "full")
    rows = []
    for name in sorted(f[:-5] for f in os.listdir(folder) if f.endswith(".json")):
        rows.append(study_time(os.path.join(folder, name + ".json"),
                               os.path.join(root, "reports", "full", "studies", name, "study.json")))
    total = sum(r["default_seconds"] or 0.0 for r in rows)
    extended = sum(r["extended_seconds"] for r in rows)
    missing = [f"{r['name']}/{n}" for r in rows for n in r["not_measured"]]
    summary = {"budget_seconds": BUDGET_SECONDS, "default_seconds": total, "extended_seconds": extended,
               "within_budget": total <= BUDGET_SECONDS and not missing, "not_measured": missing, "studies": rows}
    md = ["# The full job's time (scripts/studies-full)", "",
          "Written by `scripts/report/full_job_time.py`. Each run's own wall time (stepping and measurement), summed "
          "over the sessions that ran it; the reference and its coarser level are in their study's row. The default "
          "job runs every run not marked `extended` in `scripts/studies/full/*.json`; `scripts/studies-full "
          "--extended` adds the extended tier (the costliest rungs: the seed's largest Tet4 and Hex8 meshes, the "
          "variants that only explain a row).", "",
          "| study | runs | default job | extended tier | not measured yet |", "|---|---:|---:|---:|---|"]
    for r in rows:
        pending = r["not_measured"] + [n + " (extended)" for n in r["not_measured_extended"]]
        md.append(f"| {r['name']} | {r['runs']} ({len(r['extended_runs'])} extended) | {hours(r['default_seconds'])} "
                  f"| {hours(r['extended_seconds'])} | {', '.join(pending) or '-'} |")
    md += ["", f"Default job: **{hours(total)}** against the budget of {hours(BUDGET_SECONDS)}"
           + (" (within)" if summary["within_budget"] else
              " (over)" if total > BUDGET_SECONDS else f" (so far; not measured yet: {', '.join(missing)})")
           + f"; the extended tier adds {hours(extended)} (measured runs only).", ""]
    out = os.path.join(root, "reports", "full")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "job_time.json"), "w") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")
    with open(os.path.join(out, "job_time.md"), "w") as f:
        f.write("\n".join(md))
    print("\n".join(md))


if __name__ == "__main__":
    main()
