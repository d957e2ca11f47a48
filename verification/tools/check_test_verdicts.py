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
import sys

import ctest_list

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
    ctest_list.add_arguments(ap)
    a = ap.parse_args(argv)
    tests, error = ctest_list.load_tests(ap, a, "check_test_verdicts")
    if error:
        print(error)
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
