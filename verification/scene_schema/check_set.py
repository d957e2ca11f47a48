#!/usr/bin/python3
"""ctest schema.set: `hofem run --set key.path=VALUE` overrides.

  check_set.py HOFEM SCENE      (SCENE: verification/unit/data/scene_tiny.json, a
                                 2x2x2-cell box of Tet4, dt 0.02, duration 0.1)

Expected figures are counted by hand, not taken from hofem: a box of n^3 cells
of order p has (p n + 1)^3 nodes and 6 n^3 tetrahedra.
Exits 1 listing every failed check."""
import json
import os
import subprocess
import sys
import tempfile


def run(hofem, *args):
    p = subprocess.run([hofem, "run", *args], capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout + p.stderr


def main(hofem, scene):
    failures = []

    def expect(what, status, output, want_status, *parts):
        missing = [p for p in parts if p not in output]
        ok = status == want_status and not missing
        print(f"{'ok' if ok else 'FAILED'}: {what}")
        if not ok:
            failures.append(what)
            print(f"    exit {status} (want {want_status}); missing {missing}; output: {output.strip()[:400]}")

    # Without overrides: n = 2, p = 1: 27 nodes, 48 tets.
    expect("no override", *run(hofem, scene, "--check"), 0, "27 nodes, 48 tet elements of order 1", "dt 0.02,")
    # p = 2: 5^3 = 125 nodes; dt replaced.
    expect("mesh.order=2 dt=0.005", *run(hofem, scene, "--check", "--set", "mesh.order=2", "--set", "dt=0.005"), 0,
           "125 nodes, 48 tet elements of order 2", "dt 0.005,")
    # A JSON array value: n = 3: 4^3 = 64 nodes, 6 * 27 = 162 tets.
    expect("mesh.box.cells=[3,3,3]", *run(hofem, scene, "--check", "--set", "mesh.box.cells=[3,3,3]"), 0,
           "64 nodes, 162 tet elements")
    # A bare word is a string: hex cells, n = 2, p = 1: 27 nodes, 8 hexes.
    expect("mesh.cell=hex", *run(hofem, scene, "--check", "--set", "mesh.cell=hex"), 0, "27 nodes, 8 hex elements")
    # Validated exactly like the file: the message names the key path and value.
    expect("material.poisson=0.7 refused", *run(hofem, scene, "--check", "--set", "material.poisson=0.7"), 2,
           "material.poisson = 0.7 is out of range")
    expect("mesh.order=two refused", *run(hofem, scene, "--check", "--set", "mesh.order=two"), 2,
           "mesh.order must be an integer")
    expect("an unknown key refused", *run(hofem, scene, "--check", "--set", "colour=red"), 2, "'colour' is unknown")
    expect("a path through a number refused", *run(hofem, scene, "--check", "--set", "dt.x=1"), 2,
           "dt.x is inside a value that is not an object")
    expect("not key=value refused", *run(hofem, scene, "--check", "--set", "mesh.order"), 2, "is not key.path=VALUE")
    # A real run takes the overrides too: stats.json records them (4 steps of 0.01 to 0.04).
    with tempfile.TemporaryDirectory() as out:
        status, output = run(hofem, scene, "--out", out, "--no-frames", "--set", "dt=0.01", "--set", "duration=0.04")
        stats_path = os.path.join(out, "stats.json")
        stats = json.load(open(stats_path)) if os.path.exists(stats_path) else {}
        summary = f"dt {stats.get('dt')}, duration {stats.get('duration')}, steps {len(stats.get('steps', []))}"
        expect("a run with --set", status, summary + "\n" + output, 0, "dt 0.01, duration 0.04, steps 4")
    print(f"{len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
