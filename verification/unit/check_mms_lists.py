#!/usr/bin/python3
"""Checks `hofem mms` with comma lists of orders and sizes.

    check_mms_lists.py HOFEM json    --order 1,2 --n 2,4 --json: four JSON lines,
                                     orders outer, sizes inner, each with the
                                     single run's fields plus rate_l2 / rate_h1:
                                     none for an order's first n, else the rate
                                     recomputed here from the lines' own errors and h
    check_mms_lists.py HOFEM table   the same runs as a readable table: a header,
                                     four rows, "-" for the first rate of an order
    check_mms_lists.py HOFEM single  --order 1 --n 2 --json: one line, the fields of
                                     a single run as before lists existed (no rates)
"""
import json
import math
import subprocess
import sys

ARGS = ["mms", "--problem", "linear", "--order", "1,2", "--n", "2,4"]
# The keys of a single run's JSON object (cli/commands.cpp mms_json); a list run
# adds exactly rate_l2 and rate_h1.
SINGLE_KEYS = {"problem", "cell", "order", "n", "perturbed", "h", "cells", "nodes", "dofs", "l2_error", "h1_error",
               "newton_iterations", "converged", "linear_solver", "linear_solver_reason", "linear_iterations",
               "newton_rtol", "newton_residuals", "quadrature_degree", "error_quadrature_degree", "setup_seconds",
               "assembly_seconds", "solve_seconds", "total_seconds", "message", "distributed", "ranks",
               "distributed_solver", "per_rank"}
# The rates are printed from the same doubles the lines hold (shortest
# round-trip decimals); recomputing them differs by libm's rounding of two
# logarithms only (~1e-15 relative). 1e-12 allows that and nothing else.
RATE_TOLERANCE = 1e-12


def fail(message):
    # "FAIL:" against the successes' "OK:", so that no pattern for one matches the
    # other; exit status 1 is the verdict either way (ctest cli.mms_lists_*).
    print(f"check_mms_lists: FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def run(hofem, args):
    done = subprocess.run([hofem] + args, capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        fail(f"{' '.join(args)}: exit status {done.returncode}: {done.stderr.strip()}")
    return done.stdout.splitlines()


def check_json(hofem):
    lines = run(hofem, ARGS + ["--json"])
    if len(lines) != 4:
        fail(f"{len(lines)} lines, expected 4 (orders 1,2 x n 2,4)")
    runs = [json.loads(line) for line in lines]
    if [(r["order"], r["n"]) for r in runs] != [(1, 2), (1, 4), (2, 2), (2, 4)]:
        fail(f"runs in the order {[(r['order'], r['n']) for r in runs]}")
    for r in runs:
        if set(r) != SINGLE_KEYS | {"rate_l2", "rate_h1"}:
            fail(f"keys {sorted(set(r) ^ (SINGLE_KEYS | {'rate_l2', 'rate_h1'}))} differ from a single run's + rates")
        if not r["converged"]:
            fail(f"order {r['order']} n {r['n']} did not converge")
    for coarse, fine in ((runs[0], runs[1]), (runs[2], runs[3])):
        if coarse["rate_l2"] is not None or coarse["rate_h1"] is not None:
            fail(f"order {coarse['order']} n {coarse['n']}: the first n of an order has a rate")
        for rate, error in (("rate_l2", "l2_error"), ("rate_h1", "h1_error")):
            expected = math.log(coarse[error] / fine[error]) / math.log(coarse["h"] / fine["h"])
            if fine[rate] is None or abs(fine[rate] - expected) > RATE_TOLERANCE * max(1.0, abs(expected)):
                fail(f"order {fine['order']} n {fine['n']}: {rate} {fine[rate]}, recomputed {expected!r}")
    print("check_mms_lists: OK: 4 JSON lines, rates = log(e_prev / e) / log(h_prev / h), none for each order's first n")


def check_table(hofem):
    lines = run(hofem, ARGS)
    rows = [line.split() for line in lines if line.strip() and line.split()[0].isdigit()]
    if not lines[0].startswith("linear tet, solver auto") or len(rows) != 4:
        fail("expected a title line and 4 rows:\n" + "\n".join(lines))
    # columns: order n h DOFs L2 rate H1 rate ...
    if [(int(r[0]), int(r[1])) for r in rows] != [(1, 2), (1, 4), (2, 2), (2, 4)]:
        fail("rows out of order:\n" + "\n".join(lines))
    if rows[0][5] != "-" or rows[2][5] != "-" or rows[1][5] == "-" or rows[3][5] == "-":
        fail("the first n of each order has no rate, the second one:\n" + "\n".join(lines))
    print("check_mms_lists: OK: table with 4 rows, '-' for the first rate of each order")


def check_single(hofem):
    lines = run(hofem, ["mms", "--problem", "linear", "--order", "1", "--n", "2", "--json"])
    if len(lines) != 1 or set(json.loads(lines[0])) != SINGLE_KEYS:
        fail("a single run prints one JSON object with the fields it always had:\n" + "\n".join(lines))
    print("check_mms_lists: OK: a single run prints the object it always did")


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[2] not in ("json", "table", "single"):
        sys.exit("usage: check_mms_lists.py HOFEM json|table|single")
    {"json": check_json, "table": check_table, "single": check_single}[sys.argv[2]](sys.argv[1])
