#!/usr/bin/python3
"""A run killed with SIGKILL at random instants and resumed each time from its
checkpoint ends bitwise identical to an uninterrupted run.

Usage: check_resume_after_kills.py HOFEM SCENE OUT_DIR

The scene runs with a deterministic solver (CHOLMOD; scene/run_checkpoint.hpp says
why Krylov set-up reuse is not bitwise). Checked, each a failure with a reason:
  - at least 5 kills landed while the run was stepping, and the last run continued
    from the last checkpoint (stats.json's resumed_from_step) (the kill times are drawn
    from a seeded generator; the run is long enough that most land);
  - the final state file (positions, velocities, time, step) is byte for byte the
    uninterrupted run's;
  - stats.json lists every step once, in order, with the uninterrupted run's times
    and Newton iterations, and the .pvd lists the uninterrupted run's frames;
  - a checkpoint of another scene (another Young's modulus) is refused, naming the
    checkpoint file, with exit status 2, and the earlier run's stats.json is kept.
Exit status 0 when all hold, 1 otherwise.
"""
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time


def fail(message):
    print(f"check_resume_after_kills: FAILED: {message}")
    sys.exit(1)


def run(hofem, scene, out, extra, timeout=120):
    return subprocess.run([hofem, "run", scene, "--out", out] + COMMON + extra,
                          capture_output=True, text=True, timeout=timeout)


def frames_of(out):
    pvd = [f for f in os.listdir(out) if f.endswith(".pvd")]
    if len(pvd) != 1:
        fail(f"{out}: expected one .pvd, found {pvd}")
    with open(os.path.join(out, pvd[0])) as f:
        return re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', f.read())


def steps_of(out):
    with open(os.path.join(out, "stats.json")) as f:
        stats = json.load(f)
    return [(s["step"], s["t"], s["newton_iterations"]) for s in stats["steps"]]


hofem, scene, base = sys.argv[1], sys.argv[2], sys.argv[3]
COMMON = ["--set", "duration=6", "--set", "solver.linear=cholmod", "--vtu-format", "binary"]
shutil.rmtree(base, ignore_errors=True)
os.makedirs(base)
whole, killed = os.path.join(base, "whole"), os.path.join(base, "killed")

t0 = time.time()
r = run(hofem, scene, whole, ["--save-state", os.path.join(whole, "final.state")])
if r.returncode != 0:
    fail(f"the uninterrupted run failed ({r.returncode}): {r.stdout}{r.stderr}")
seconds = time.time() - t0

rng = random.Random(20261206)
kills, attempts = 0, 0
resume = ["--resume", "--checkpoint-every", "1", "--save-state", os.path.join(killed, "final.state")]
while kills < 5:
    attempts += 1
    if attempts > 40:
        fail(f"only {kills} of 40 attempts were killed while stepping (the run takes {seconds:.2f} s)")
    p = subprocess.Popen([hofem, "run", scene, "--out", killed] + COMMON + resume,
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(rng.uniform(0.15, max(0.3, 0.5 * seconds)))
    if p.poll() is None:
        os.kill(p.pid, signal.SIGKILL)
        p.wait()
        kills += 1
        checkpoint = os.path.join(killed, "checkpoint", "checkpoint.json")
        step = json.load(open(checkpoint))["step"] if os.path.exists(checkpoint) else 0
        print(f"kill {kills}: SIGKILL after the checkpoint of step {step}")
    else:
        # Finished before the kill: start over, so that every kill lands mid-run.
        if p.returncode != 0:
            fail(f"a resumed run failed with status {p.returncode}")
        shutil.rmtree(killed)
last = json.load(open(os.path.join(killed, "checkpoint", "checkpoint.json")))["step"]
r = run(hofem, scene, killed, resume)
if r.returncode != 0:
    fail(f"the last resumed run failed ({r.returncode}): {r.stdout}{r.stderr}")
# It must have continued from the checkpoint, not started again from rest.
with open(os.path.join(killed, "stats.json")) as f:
    resumed_from = json.load(f).get("resumed_from_step")
if last == 0 or resumed_from != last:
    fail(f"the last run resumed from step {resumed_from}, the checkpoint was of step {last}")

with open(os.path.join(whole, "final.state"), "rb") as a, open(os.path.join(killed, "final.state"), "rb") as b:
    if a.read() != b.read():
        fail("the final states differ")
if steps_of(whole) != steps_of(killed):
    fail(f"stats.json steps differ: {len(steps_of(whole))} uninterrupted, {len(steps_of(killed))} resumed")
if frames_of(whole) != frames_of(killed):
    fail("the .pvd frames differ")
for t, name in frames_of(killed):
    if not os.path.exists(os.path.join(killed, name)):
        fail(f"frame {name} (t = {t}) is listed but missing")

# Another scene's checkpoint is refused by name, before anything is written.
counts = (len(steps_of(killed)), len(frames_of(killed)))
r = subprocess.run([hofem, "run", scene, "--out", killed, "--resume", "--set", "material.young=2e5"] + COMMON,
                   capture_output=True, text=True, timeout=120)
if r.returncode != 2 or "checkpoint.json" not in r.stderr + r.stdout or "another scene" not in r.stderr + r.stdout:
    fail(f"a checkpoint of another scene was not refused with status 2 naming it: {r.returncode} {r.stderr}")

if steps_of(whole) != steps_of(killed):
    fail("the refused resume changed the earlier run's stats.json")
print(f"check_resume_after_kills: {kills} kills, final state bitwise equal, {counts[0]} steps and "
      f"{counts[1]} frames as uninterrupted")
