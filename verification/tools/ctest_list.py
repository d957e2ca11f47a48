"""The tests ctest lists, for the checks that read them (check_test_verdicts.py,
check_doc_test_names.py): `ctest --show-only=json-v1` run in a build directory,
or that output saved (or fabricated) in a file. One home for the options, the
run and the refusal of an empty list (a wrong directory would pass every check
vacuously)."""
import json
import subprocess


def add_arguments(ap):
    ap.add_argument("--build", help="build directory to run ctest in")
    ap.add_argument("--ctest", default="ctest", help="the ctest executable")
    ap.add_argument("--json", help="read ctest --show-only=json-v1 output from this file instead")


def load_tests(ap, a, who):
    """The test entries (ctest's JSON objects), or (None, message) when they
    cannot be had or the list is empty: returns (tests, error)."""
    if bool(a.build) == bool(a.json):
        ap.error("give either --build DIR or --json FILE")
    if a.json:
        with open(a.json) as f:
            doc = json.load(f)
    else:
        run = subprocess.run([a.ctest, "--show-only=json-v1"], cwd=a.build, capture_output=True, text=True)
        if run.returncode != 0:
            return None, f"{who}: FAIL: ctest --show-only=json-v1 in {a.build}: exit {run.returncode}: {run.stderr}"
        doc = json.loads(run.stdout)
    tests = doc.get("tests", [])
    if not tests:
        return None, f"{who}: FAIL: no tests listed"
    return tests, None
