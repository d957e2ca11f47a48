"""hofem run --no-frames --final-frame, then scripts/plots/render_scenes.py on its output.

Usage: check_render_scenes.py HOFEM SOURCE_DIR WORKDIR

Runs the linear cantilever for 0.4 s (20 implicit steps; it sags under gravity,
from 0 at the clamped end to ~cm at the tip) into WORKDIR/reports/scenes/cantilever/
and checks that only final.vtu and stats.json were written (no frame_*.vtu, no
.pvd); renders it and checks that reports/scenes/cantilever.png exists, is a small
~100 dpi figure and is not blank: the axes part (left of the colorbar) must hold
coloured faces - pixels whose channels differ (greys, text and white do not) -
in several colours (the |displacement| gradient along the beam).

First, on a unit cube of one Hex8 (hand-made faces, so the expected answers are
known without the code under test): its six boundary faces are consistently
oriented, the three facing the default eye (elev 30, azim -60: the faces x = 1,
y = 0, z = 1) are kept and the three facing away dropped; one face flipped makes
the surface inconsistent, and then nothing is dropped.
"""
import subprocess
import sys
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np


def fail(msg):
    print(f"check_render_scenes: FAIL: {msg}")
    sys.exit(1)


def check_culling(source):
    sys.path.insert(0, str(source / "scripts" / "plots"))
    import render_scenes as rs  # noqa: E402 (scripts/plots/ is not a package)

    # VTK's Hex8 vertex order on the unit cube.
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
    faces = rs.boundary_faces(rs.cell_faces("hexahedron", np.arange(8)[None, :]), False)
    if len(faces) != 6 or not rs.consistently_oriented(faces):
        fail(f"a cube's {len(faces)} boundary faces are not found consistently oriented")
    e, a = np.radians(rs.ELEV), np.radians(rs.AZIM)
    eye = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])  # (0.43, -0.75, 0.5)
    kept, shade = rs.visible(x, faces, eye)
    # The faces towards that eye are x = 1, y = 0 and z = 1: their outward normals
    # (+x, -y, +z) have eye components 0.43, 0.75, 0.5 > 0; the other three < 0.
    centres = sorted(tuple(np.round(x[f].mean(axis=0), 6)) for f in kept)
    if centres != sorted([(1.0, 0.5, 0.5), (0.5, 0.0, 0.5), (0.5, 0.5, 1.0)]):
        fail(f"a cube seen from {eye.round(2)} keeps the faces centred at {centres}")
    if not np.allclose(sorted(shade), sorted(np.abs(eye))):  # cos to the eye = the eye's components
        fail(f"shades {shade} are not the eye's components {eye}")
    flipped = faces.copy()
    flipped[0] = flipped[0][::-1]
    if rs.consistently_oriented(flipped) or len(rs.visible(x, flipped, eye)[0]) != 6:
        fail("one face flipped: the surface must be found inconsistent and every face kept")


def main():
    hofem, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    check_culling(source)
    out = work / "reports" / "scenes" / "cantilever"
    subprocess.run([hofem, "run", str(source / "scripts/scenes/cantilever-linear.json"), "--out", str(out),
                    "--no-frames", "--final-frame", "--set", "duration=0.4"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    written = sorted(p.name for p in out.iterdir())
    if written != ["final.vtu", "stats.json"]:
        fail(f"{out} holds {written}, expected final.vtu and stats.json only")
    subprocess.run([sys.executable, str(source / "scripts/plots/render_scenes.py"), str(work / "reports")], check=True)
    png = work / "reports" / "scenes" / "cantilever.png"
    if not png.exists():
        fail(f"{png} was not written")
    img = mpimg.imread(png)[..., :3]
    h, w = img.shape[:2]
    if not (200 <= w <= 800 and 200 <= h <= 800):
        fail(f"{png} is {w}x{h} pixels, expected a small ~100 dpi figure")
    axes = img[:, : int(0.7 * w)]  # the colorbar sits in the right ~30%
    coloured = axes[axes.max(axis=2) - axes.min(axis=2) > 0.15]  # viridis is never grey
    shades = len(np.unique((coloured * 255).astype(np.uint8), axis=0))
    # At least 1% of the axes area in colour and 10 shades: a drawn beam covers
    # far more; an empty axes box has no coloured pixel at all.
    if coloured.shape[0] < 0.01 * axes.shape[0] * axes.shape[1] or shades < 10:
        fail(f"{png}: {coloured.shape[0]} coloured pixels in {shades} shades in the axes: blank?")
    print(f"check_render_scenes: OK, {png.name} {w}x{h}, {coloured.shape[0]} coloured pixels, {shades} shades")


if __name__ == "__main__":
    main()
