#!/usr/bin/env python3
"""ctest verify.junit: the JUnit XML `hofem verify --junit` wrote is well-formed
and says what its JSON report says.

  check_junit.py REPORT.xml REPORT.json

Checks: the XML parses; <testsuites> counts tests and failures as the JSON's
summary does; one <testsuite> per group with that group's counts; every
<testcase> has a classname (its group) and a name, and carries a <failure> with
the measured value and threshold exactly when its row failed."""
import json
import sys
import xml.etree.ElementTree as ET


def main(xml_path, json_path):
    root = ET.parse(xml_path).getroot()
    report = json.load(open(json_path))
    summary = report["summary"]
    problems = []
    if root.tag != "testsuites":
        problems.append(f"root element is <{root.tag}>, not <testsuites>")
    if int(root.get("tests", -1)) != summary["checks"] or int(root.get("failures", -1)) != summary["failed"]:
        problems.append(f"testsuites counts {root.get('tests')}/{root.get('failures')}, JSON {summary['checks']}/{summary['failed']}")
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    if set(suites) != set(summary["groups"]):
        problems.append(f"suites {sorted(suites)} != groups {sorted(summary['groups'])}")
    # Each group's rows in order: a rate's two rows share a name (Report::check_rate),
    # so the testcases are matched to the rows by position, not by name.
    rows_of = {}
    for r in report["rows"]:
        rows_of.setdefault(r["group"], []).append(r)
    cases = 0
    for name, suite in suites.items():
        group = summary["groups"].get(name, {})
        if int(suite.get("tests", -1)) != group.get("checks") or int(suite.get("failures", -1)) != group.get("failed"):
            problems.append(f"suite {name}: counts differ from the JSON")
        for k, case in enumerate(suite.findall("testcase")):
            cases += 1
            row = rows_of.get(name, [])[k] if k < len(rows_of.get(name, [])) else None
            if case.get("classname") != name or not case.get("name"):
                problems.append(f"suite {name}: testcase without its group or name")
            failure = case.find("failure")
            if row is None or row["name"] != case.get("name"):
                problems.append(f"{name} | {case.get('name')}: not the JSON's row at position {k}")
            elif (failure is not None) != (not row["pass"]):
                problems.append(f"{name} | {case.get('name')}: <failure> does not match the row's verdict")
            if failure is not None and not ("measured" in failure.get("message", "") and "threshold" in failure.get("message", "")):
                problems.append(f"{name} | {case.get('name')}: failure message lacks measured/threshold")
    if cases != summary["checks"]:
        problems.append(f"{cases} testcases, {summary['checks']} checks")
    for p in problems:
        print("check_junit:", p)
    print(f"check_junit: {cases} testcases in {len(suites)} suites, {summary['failed']} failures: "
          + ("agree with the JSON" if not problems else f"{len(problems)} problems"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
