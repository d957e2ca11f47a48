#!/usr/bin/python3
"""Every number of two verification reports side by side: for a refactoring
that must not change results (a moved file, a renamed type), run the main job
before and after and compare the two reports/verification.json.

Rows are matched by (group, name) (a name two rows share, as a rate's two
bounds do, by its comparison too): their `measured` values, thresholds and
verdicts; measurements by (group, name): their `value`. Wall-clock figures
(group "timing", and any group or name that says "seconds") are left out unless
--timing: they change from run to run. Prints the
number of values compared, how many are bitwise equal, the largest absolute and
relative differences (with the row), rows only in one file and changed verdicts.

Usage: verification_diff.py BEFORE.json AFTER.json [--tolerance REL] [--timing]
Exits 1 if a verdict changed, a row appeared or vanished, or (with
--tolerance) a relative difference exceeds REL; 2 if a file cannot be read."""
import json
import math
import sys


def is_wall_clock(group, name):
    return group == "timing" or "seconds" in group or "seconds" in name


def row_keys(rows):
    """(group, name) per row; a name two rows share (a rate's lower and upper bound,
    Report::check_rate) is told apart by its comparison: "name (>=)", "name (<=)"."""
    seen = {}
    for r in rows:
        seen[(r["group"], r["name"])] = seen.get((r["group"], r["name"]), 0) + 1
    return [(r["group"], r["name"] if seen[(r["group"], r["name"])] == 1 else f"{r['name']} ({r.get('compare')})")
            for r in rows]


def numbers(report, timing):
    """(kind, group, name) -> value for every number of the report."""
    out, verdicts = {}, {}
    rows = report.get("rows", [])
    for r, key in zip(rows, row_keys(rows)):
        if is_wall_clock(r["group"], r["name"]) and not timing:
            continue
        out[("measured",) + key] = r.get("measured")
        out[("threshold",) + key] = r.get("threshold")
        verdicts[key] = r.get("pass")
    for m in report.get("measurements", []):
        if is_wall_clock(m["group"], m["name"]) and not timing:
            continue
        out[("value", m["group"], m["name"])] = m.get("value")
    return out, verdicts


def difference(a, b):
    """(absolute, relative) difference; equal non-finite values and equal
    non-numbers differ by 0, anything else that is not a number by inf."""
    if a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)):
        return 0.0, 0.0
    if not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in (a, b)):
        return math.inf, math.inf
    d = abs(a - b)
    scale = max(abs(a), abs(b))
    return d, (d / scale if scale > 0 else math.inf)


def compare(before, after, timing=False):
    nb, vb = numbers(before, timing)
    na, va = numbers(after, timing)
    common = sorted(set(nb) & set(na))
    result = {"compared": len(common), "bitwise_equal": 0, "max_abs": (0.0, None), "max_rel": (0.0, None),
              "only_before": sorted(set(vb) - set(va)), "only_after": sorted(set(va) - set(vb)),
              "verdicts_changed": sorted(k for k in set(vb) & set(va) if vb[k] != va[k])}
    for k in common:
        a, r = difference(nb[k], na[k])
        if a == 0.0 and json.dumps(nb[k]) == json.dumps(na[k]):
            result["bitwise_equal"] += 1
        if a > result["max_abs"][0]:
            result["max_abs"] = (a, k)
        if r > result["max_rel"][0]:
            result["max_rel"] = (r, k)
    return result


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    tolerance = None
    if "--tolerance" in argv:
        tolerance = float(argv[argv.index("--tolerance") + 1])
        args = [a for a in args if a != argv[argv.index("--tolerance") + 1]]
    if len(args) != 2:
        print(__doc__.split("\n\n")[-1], file=sys.stderr)
        return 2
    try:
        reports = []
        for path in args:
            with open(path) as f:
                reports.append(json.load(f))
    except (OSError, ValueError) as e:
        print(f"verification_diff: cannot read {path}: {e}", file=sys.stderr)
        return 2
    r = compare(*reports, timing="--timing" in argv)
    print(f"verification_diff: {r['compared']} values compared, {r['bitwise_equal']} bitwise equal"
          + (" (every one)" if r["compared"] == r["bitwise_equal"] else ""))
    print(f"  largest absolute difference {r['max_abs'][0]:.3g}" + (f" ({r['max_abs'][1]})" if r["max_abs"][1] else ""))
    print(f"  largest relative difference {r['max_rel'][0]:.3g}" + (f" ({r['max_rel'][1]})" if r["max_rel"][1] else ""))
    for label in ("only_before", "only_after", "verdicts_changed"):
        for k in r[label]:
            print(f"  {label.replace('_', ' ')}: {k}")
    failed = bool(r["only_before"] or r["only_after"] or r["verdicts_changed"])
    if tolerance is not None and r["max_rel"][0] > tolerance:
        print(f"  relative difference {r['max_rel'][0]:.3g} exceeds --tolerance {tolerance:g}")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
