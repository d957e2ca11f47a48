#!/usr/bin/python3
"""ctest schema.cases: the table scene_cases.json through hofem's parser and scene.schema.json.

  check_cases.py HOFEM SCHEMA CASES DATA_DIR

Each case's scene is written to a file and checked with `HOFEM run FILE --check`
(exit 0: valid, 2: invalid, anything else is a failure of this test) and with the
schema (jsonschema). hofem must give the case's verdict and, for an invalid one,
name the case's key path ("message"); the schema must give the same verdict,
except for cases marked cpp_only (what a schema cannot express), where the
schema must ACCEPT - otherwise the mark would hide a schema that could say it.
Exits 1 listing every disagreement."""
import copy
import json
import os
import subprocess
import sys
import tempfile

import jsonschema


def walk(doc, path, create):
    """The container and last key of a dotted path ("boundary.0.nodes")."""
    keys = path.split(".")
    at = doc
    for k in keys[:-1]:
        if isinstance(at, list):
            at = at[int(k)]
        else:
            if k not in at and create:
                at[k] = {}
            at = at[k]
    last = keys[-1]
    return at, int(last) if isinstance(at, list) else last


def build(base, case, data_dir):
    doc = copy.deepcopy(base)
    for path in case.get("delete", []):
        at, k = walk(doc, path, False)
        del at[k]
    for path, value in case.get("set", {}).items():
        at, k = walk(doc, path, True)
        at[k] = value
    text = json.dumps(doc).replace("@DATA@", os.path.abspath(data_dir))
    return json.loads(text)


def hofem_verdict(hofem, doc, folder, index):
    path = os.path.join(folder, f"case_{index:02d}.json")
    with open(path, "w") as f:
        json.dump(doc, f)
    p = subprocess.run([hofem, "run", path, "--check"], capture_output=True, text=True, timeout=120)
    if p.returncode not in (0, 2):
        return None, f"exit status {p.returncode}: {p.stderr.strip()}"
    return p.returncode == 0, (p.stdout + p.stderr).strip()


def main(hofem, schema_path, cases_path, data_dir):
    with open(schema_path) as f:
        schema = json.load(f)
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    validator = cls(schema)
    with open(cases_path) as f:
        table = json.load(f)
    failures = []
    with tempfile.TemporaryDirectory() as folder:
        for i, case in enumerate(table["cases"]):
            doc = build(table["base"], case, data_dir)
            want = case["valid"]
            cpp, output = hofem_verdict(hofem, doc, folder, i)
            errors = list(validator.iter_errors(doc))
            schema_ok = not errors
            problems = []
            if cpp is None or cpp != want:
                problems.append(f"hofem says {'valid' if cpp else 'invalid' if cpp is False else 'neither'}: {output[:300]}")
            elif not want and case.get("message", "") not in output:
                problems.append(f"hofem's message does not contain {case['message']!r}: {output[:300]}")
            expect_schema = True if "cpp_only" in case else want
            if schema_ok != expect_schema:
                why = errors[0].message[:200] if errors else "accepted"
                problems.append(f"the schema says {'valid' if schema_ok else 'invalid'} ({why})")
            status = "ok" if not problems else "DISAGREES"
            tag = " [hofem only: " + case["cpp_only"] + "]" if "cpp_only" in case else ""
            print(f"{status}: {case['name']} ({'valid' if want else 'invalid'}){tag}")
            for p in problems:
                print("    " + p)
            if problems:
                failures.append(case["name"])
    print(f"{len(table['cases']) - len(failures)} of {len(table['cases'])} cases agree")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
