#!/usr/bin/env python3
"""Fails when a ctest is judged by anything but its exit status.

Three test properties let a failing command pass:
  PASS_REGULAR_EXPRESSION  replaces the exit status: the expected words printed
                           by a command that then fails pass the test (use
                           hofem_output_test, cmake/HofemOutputTest.cmake);
  WILL_FAIL                inverts it: a crash passes as well as the refusal
                           meant (use hofem_output_test with EXIT n|nonzero);
  SKIP_REGULAR_EXPRESSION  turns a failure that prints the words into a skip;
                           only GoogleTest's own "[  SKIPPED ]" (set by
                           gtest_discover_tests) is allowed.

usage: check_test_verdicts.py --build DIR --ctest CTEST   (ctest --show-only=json-v1 in DIR)
       check_test_verdicts.py --json FILE                 (that output, saved or fabricated)
Prints "check_test_verdicts: N tests, 0 judged other than by exit status" and
exits 0, or "check_test_verdicts: FAIL: ..." with each test and property, exit 1.
"""
import argparse
import json
import subprocess
import sys

GTEST_SKIP = ["\\[  SKIPPED \\]"]  # gtest_discover_tests' value, as ctest's JSON lists it


def cmake_true(value):
    # ctest's JSON gives WILL_FAIL as a boolean; a hand-written file may use CMake's words.
    if isinstance(value, str):
        return value.upper() in ("1", "ON", "YES", "TRUE", "Y")
    return bool(value)


def offending(test):
    props = {p["name"]: p["value"] for p in test.get("properties", [])}
    found = []
    if "PASS_REGULAR_EXPRESSION" in props:
        found.append("PASS_REGULAR_EXPRESSION")
    if cmake_true(props.get("WILL_FAIL", False)):
        found.append("WILL_FAIL")
    if "SKIP_REGULAR_EXPRESSION" in props and props["SKIP_REGULAR_EXPRESSION"] != GTEST_SKIP:
        found.append("SKIP_REGULAR_EXPRESSION")
    return found


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", help="build directory to run ctest in")
    ap.add_argument("--ctest", default="ctest", help="the ctest executable")
    ap.add_argument("--json", help="read ctest --show-only=json-v1 output from this file instead")
    a = ap.parse_args(argv)
    if bool(a.build) == bool(a.json):
        ap.error("give either --build DIR or --json FILE")
    if a.json:
        with open(a.json) as f:
            doc = json.load(f)
    else:
        run = subprocess.run([a.ctest, "--show-only=json-v1"], cwd=a.build, capture_output=True, text=True)
        if run.returncode != 0:
            print(f"check_test_verdicts: FAIL: ctest --show-only=json-v1 in {a.build}: exit {run.returncode}: {run.stderr}")
            return 1
        doc = json.loads(run.stdout)
    tests = doc.get("tests", [])
    # An empty list would pass vacuously (a wrong directory, a broken ctest).
    if not tests:
        print("check_test_verdicts: FAIL: no tests listed")
        return 1
    bad = [(t["name"], found) for t in tests if (found := offending(t))]
    if bad:
        print(f"check_test_verdicts: FAIL: {len(bad)} of {len(tests)} tests judged other than by exit status")
        for name, found in bad:
            print(f"  {name}: {', '.join(found)}")
        return 1
    print(f"check_test_verdicts: {len(tests)} tests, 0 judged other than by exit status")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
