#!/usr/bin/python3
"""Checks the convergence table `hofem verify` writes beside its report
(PREFIX.csv and PREFIX.json) against the report itself:

- every column the format promises is described (name, unit, description) and
  the CSV header lists the same columns in the same order;
- one row per run of the study: as many rows as expected, no (problem, cell,
  order, mesh, n) twice, and each row's L2 / H1 errors and unknowns equal to the
  report's measurements of that run (mms.l2_error, ... under the run's name);
- the rates, recomputed here from the table's own errors and h, against the
  previous row of the same series: log(e_prev / e) / log(h_prev / h); a series'
  first row has none (null in JSON, an empty CSV field);
- the CSV holds the same values as the JSON.

    check_convergence_table.py PREFIX REPORT.json EXPECTED_ROWS
"""
import csv
import json
import math
import sys

COLUMNS = ["problem", "cell", "order", "mesh", "n", "h", "unknowns", "cells", "l2_error", "h1_error", "rate_l2",
           "rate_h1", "setup_seconds", "assembly_seconds", "solve_seconds", "total_seconds", "newton_iterations",
           "linear_iterations", "linear_solver", "converged"]

# The table's numbers round-trip exactly through JSON (shortest round-trip
# decimal), so the recomputed rate differs from the written one only by libm's
# rounding of the two logarithms (<= 1 ulp each): ~1e-15 relative, over a log(2)
# denominator. 1e-12 leaves room for that and nothing else.
RATE_TOLERANCE = 1e-12


def fail(message):
    sys.exit(f"check_convergence_table: {message}")


def check_columns(table, header):
    described = [c["name"] for c in table["columns"]]
    if described != COLUMNS:
        fail(f"JSON columns {described}, expected {COLUMNS}")
    for c in table["columns"]:
        if not c.get("unit") or not c.get("description"):
            fail(f"column {c['name']} lacks a unit or description: {c}")
    if header != COLUMNS:
        fail(f"CSV header {header}, expected {COLUMNS}")


def check_rows_match_report(rows, report, expected_rows):
    if len(rows) != expected_rows:
        fail(f"{len(rows)} rows, expected {expected_rows} (one per run of the study)")
    keys = [(r["problem"], r["cell"], r["order"], r["mesh"], r["n"]) for r in rows]
    if len(set(keys)) != len(keys):
        fail("a (problem, cell, order, mesh, n) appears twice")
    measured = {(m["group"], m["name"]): m["value"] for m in report["measurements"]}
    for r in rows:
        run = f"{r['problem']}|{r['cell']}|p{r['order']}|{r['mesh']}|n{r['n']}"
        for column, group in (("l2_error", "mms.l2_error"), ("h1_error", "mms.h1_error"), ("unknowns", "mms.dofs")):
            if measured.get((group, run)) != r[column]:
                fail(f"{run}: {column} {r[column]} but the report's {group} is {measured.get((group, run))}")


def check_rates(rows):
    previous = {}
    checked = 0
    for r in rows:
        series = (r["problem"], r["cell"], r["order"], r["mesh"])
        prev = previous.get(series)
        for rate, error in (("rate_l2", "l2_error"), ("rate_h1", "h1_error")):
            if prev is None:
                if r[rate] is not None:
                    fail(f"{series} n={r['n']}: first row of its series has {rate} = {r[rate]}, expected none")
                continue
            expected = math.log(prev[error] / r[error]) / math.log(prev["h"] / r["h"])
            if r[rate] is None or abs(r[rate] - expected) > RATE_TOLERANCE * max(1.0, abs(expected)):
                fail(f"{series} n={r['n']}: {rate} = {r[rate]}, recomputed {expected!r}")
            checked += 1
        previous[series] = r
    return checked


def check_csv_matches(rows, csv_rows):
    if len(csv_rows) != len(rows):
        fail(f"CSV has {len(csv_rows)} rows, JSON {len(rows)}")
    for j, c in zip(rows, csv_rows):
        for name in COLUMNS:
            value = j[name]
            if value is None:
                same = c[name] == ""
            elif isinstance(value, bool):
                same = c[name] == ("true" if value else "false")
            elif isinstance(value, (int, float)):
                same = float(c[name]) == float(value)  # both are the same double, printed round-trip
            else:
                same = c[name] == value
            if not same:
                fail(f"CSV {name} = '{c[name]}', JSON {value!r} (row {j['problem']} {j['cell']} p{j['order']} n{j['n']})")


def main(prefix, report_path, expected_rows):
    with open(prefix + ".json") as f:
        table = json.load(f)
    with open(prefix + ".csv", newline="") as f:
        reader = csv.DictReader(f)
        csv_rows = list(reader)
        header = reader.fieldnames
    with open(report_path) as f:
        report = json.load(f)
    check_columns(table, header)
    rows = table["rows"]
    check_rows_match_report(rows, report, expected_rows)
    rates = check_rates(rows)
    check_csv_matches(rows, csv_rows)
    series = len({(r["problem"], r["cell"], r["order"], r["mesh"]) for r in rows})
    print(f"check_convergence_table: {len(rows)} rows in {series} series, {rates} rates recomputed, "
          f"CSV = JSON, errors = the report's")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: check_convergence_table.py PREFIX REPORT.json EXPECTED_ROWS")
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
