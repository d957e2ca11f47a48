#!/usr/bin/python3
"""Every row of a claims table (paper_claims.json) can fail: its criterion is an
interval with a finite end, its verdict is the interval's verdict on its
measured value, and the value pushed past an end (claims_check.outside) is
judged "no". Also the reference checks. And each row says how large its runs
were against the seed's (claims_size.py), and its timings are medians of at
least 3 steps. Exit 0 when all hold, 1 otherwise with
each offending row named.

Usage: check_claims_can_fail.py PAPER_CLAIMS_JSON [--min-rows N]"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from claims_check import judge, outside  # noqa: E402


def problems(table):
    out = []
    for r in table["rows"] + table.get("reference_checks", []):
        c = r.get("check")
        if not c or (c["low"] is None and c["high"] is None):
            out.append(f"{r['id']}: no finite bound, the row cannot fail")
            continue
        measured = r["measured"] if r["measured"] is not None else float("nan")
        if isinstance(r["measured"], (bool, str)):
            out.append(f"{r['id']}: measured {r['measured']!r} is a flag or a label, not a value")
        if judge(measured, c) != r["agrees"]:
            out.append(f"{r['id']}: agrees = {r['agrees']} but the interval says {judge(measured, c)}")
        if judge(outside(c), c):
            out.append(f"{r['id']}: a value past the interval's end ({outside(c)}) is still judged 'yes'")
        size = r.get("size")
        if not size or "fraction" not in size or "run" not in size:
            out.append(f"{r['id']}: no size (its fraction of the seed's unknowns and the job that ran it)")
        elif size["fraction"] is not None and size["at_seed_size"] != (size["fraction"] >= 0.5):
            out.append(f"{r['id']}: at_seed_size = {size['at_seed_size']} but the fraction is {size['fraction']}")
        few = [t["run"] for t in r.get("timings", []) if t["steps"] < 3]
        if few:
            out.append(f"{r['id']}: timed by a median of fewer than 3 steps in {', '.join(few)}")
    return out


def main(argv):
    with open(argv[1]) as f:
        table = json.load(f)
    min_rows = int(argv[argv.index("--min-rows") + 1]) if "--min-rows" in argv else 1
    found = problems(table)
    if len(table["rows"]) < min_rows:
        found.append(f"{len(table['rows'])} rows, fewer than {min_rows}")
    for p in found:
        print(f"check_claims_can_fail: {p}")
    if found:
        print(f"check_claims_can_fail: FAILED ({len(found)} problems)")
        return 1
    print(f"check_claims_can_fail: {len(table['rows'])} rows and {len(table.get('reference_checks', []))} reference "
          "checks, each with a finite bound, each judged 'no' past it")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
