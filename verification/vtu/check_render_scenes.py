"""hofem run --no-frames --final-frame, then scripts/render_scenes.py on its output.

Usage: check_render_scenes.py HOFEM SOURCE_DIR WORKDIR

Runs the linear cantilever for 0.4 s (20 implicit steps; it sags under gravity,
from 0 at the clamped end to ~cm at the tip) into WORKDIR/reports/scenes/cantilever/
and checks that only final.vtu and stats.json were written (no frame_*.vtu, no
.pvd); renders it and checks that reports/scenes/cantilever.png exists, is a small
~100 dpi figure and is not blank: the axes part (left of the colorbar) must hold
coloured faces - pixels whose channels differ (greys, text and white do not) -
in several colours (the |displacement| gradient along the beam).
"""
import subprocess
import sys
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np


def fail(msg):
    print(f"check_render_scenes: FAIL: {msg}")
    sys.exit(1)


def main():
    hofem, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    out = work / "reports" / "scenes" / "cantilever"
    subprocess.run([hofem, "run", str(source / "scripts/scenes/cantilever-linear.json"), "--out", str(out),
                    "--no-frames", "--final-frame", "--set", "duration=0.4"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    written = sorted(p.name for p in out.iterdir())
    if written != ["final.vtu", "stats.json"]:
        fail(f"{out} holds {written}, expected final.vtu and stats.json only")
    subprocess.run([sys.executable, str(source / "scripts/render_scenes.py"), str(work / "reports")], check=True)
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
