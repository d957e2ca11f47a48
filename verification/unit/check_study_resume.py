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
  3. the same study with another Young's modulus: no record is reused;
  4. a study killed (SIGKILL) while its last run goes on leaves study.json and
     summary.md with the runs done, "complete": false and the last run
     "pending"; resumed, it completes with the earlier runs stored.
Exit status 0 when all hold, 1 otherwise (with the reason).
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time


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
# 4. Killed part-way: a quick run, then a slow one (P2 on 4^3 cells for 1 s of
# the scene: ~10^2 times the quick run), killed once the quick run's rows are written.
killed_dir = os.path.join(out, "killed")
changed["runs"] = [changed["runs"][0], {"name": "slow", "family": "Tet10",
                                        "overrides": ["mesh.order=2", "mesh.box.cells=[4,4,4]", "duration=1.0"]}]
changed["frames"] = [changed["frames"][0]]
with open(changed_path, "w") as f:
    json.dump(changed, f)
proc = subprocess.Popen([hofem, "study", changed_path, "--out", killed_dir, "--resume"],
                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
partial = None
deadline = time.monotonic() + 300
while time.monotonic() < deadline and proc.poll() is None:
    # study.json is written before summary.md: wait for both (each atomically).
    try:
        with open(os.path.join(killed_dir, "study.json")) as f:
            partial = json.load(f)
        if os.path.exists(os.path.join(killed_dir, "summary.md")):
            break
    except (OSError, ValueError):
        pass
    time.sleep(0.01)
if proc.poll() is not None:
    fail("the study ended before it could be killed part-way (the slow run is not slow enough)")
proc.send_signal(signal.SIGKILL)
proc.wait()
if partial is None or partial.get("complete") is not False or partial.get("pending") != ["slow"]:
    fail(f"a study killed part-way left no partial study.json with the slow run pending: {partial and partial.get('pending')}")
with open(os.path.join(killed_dir, "summary.md")) as f:
    if "Incomplete" not in f.read():
        fail("the partial summary.md does not say it is incomplete")
resumed = study(hofem, changed_path, killed_dir)
if resumed.get("complete") is not True or not resumed["runs"][0]["stored"] or resumed["runs"][1]["stored"]:
    fail("the resumed study did not complete with the first run stored and the slow run computed")
print(f"check_study_resume: {len(first['runs'])} runs and the reference stored, reused with equal errors, "
      f"recomputed after a change; a study killed part-way kept its rows and completed when resumed")
