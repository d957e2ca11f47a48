#!/usr/bin/python3
"""hofem study --resume keeps each finished run's record and reuses it only for
the same scene.

Usage: check_study_resume.py HOFEM STUDY OUT_DIR

  1. a first run computes every run (no row "stored");
     Each measured run keeps its errors in its record and drops its states;
     the reference keeps its states (a later run is measured against them);
  2. run again: every run and the reference come from their records ("stored"),
     with the same errors and costs bit for bit (the records hold the states as
     doubles), and in a fraction of the first run's time is not asserted (noise);
  3. the same study with another Young's modulus: no record is reused.
Exit status 0 when all hold, 1 otherwise (with the reason).
"""
import json
import os
import shutil
import subprocess
import sys


def fail(message):
    print(f"check_study_resume: FAILED: {message}")
    sys.exit(1)


def study(hofem, path, out):
    r = subprocess.run([hofem, "study", path, "--out", out, "--resume"], capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail(f"hofem study {path} exited {r.returncode}: {r.stdout}{r.stderr}")
    with open(os.path.join(out, "study.json")) as f:
        return json.load(f)


hofem, study_file, out = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(out, ignore_errors=True)
first = study(hofem, study_file, out)
if any(r["stored"] for r in first["runs"]) or first["reference"]["stored"]:
    fail("a first run reported a stored record")
runs_dir = os.path.join(out, "runs")
reference_dir = os.path.join(runs_dir, first["reference"]["name"])
for name in sorted(os.listdir(runs_dir)):
    files = os.listdir(os.path.join(runs_dir, name))
    states = [f for f in files if f.endswith(".state")]
    with open(os.path.join(runs_dir, name, "record.json")) as f:
        record = json.load(f)
    if os.path.join(runs_dir, name) == reference_dir:
        if not states:
            fail("the reference's record lost its states (later runs are measured against them)")
    elif states or "measured" not in record:
        fail(f"{name}: a measured run kept its states {states} or has no stored measurement")
second = study(hofem, study_file, out)
if not all(r["stored"] for r in second["runs"]) or not second["reference"]["stored"]:
    fail("the second run did not reuse every record: " + str([(r["name"], r["stored"]) for r in second["runs"]]))
for a, b in zip(first["runs"], second["runs"]):
    if a.get("max_over_frames") != b.get("max_over_frames"):
        fail(f"{a['name']}: errors changed when taken from the record: {a.get('max_over_frames')} vs {b.get('max_over_frames')}")
    if a.get("time_per_step_median") != b.get("time_per_step_median"):
        fail(f"{a['name']}: the stored run's cost changed")

# Another material: every scene differs, so nothing may be reused.
with open(study_file) as f:
    changed = json.load(f)
changed["scene"] = os.path.join(os.path.dirname(os.path.abspath(study_file)), changed["scene"])
changed["overrides"] = changed.get("overrides", []) + ["material.young=2e5"]
changed_path = os.path.join(out, "changed_study.json")
with open(changed_path, "w") as f:
    json.dump(changed, f)
third = study(hofem, changed_path, out)
if any(r["stored"] for r in third["runs"]) or third["reference"]["stored"]:
    fail("a record was reused for a changed scene")
print(f"check_study_resume: {len(first['runs'])} runs and the reference stored, reused with equal errors, "
      f"recomputed after a change")
