#!/usr/bin/python3
"""The plotting scripts run on small generated inputs and write their PNGs:

- scripts/plots/plot_convergence.py on a convergence table of two problems, three
  orders, tet and hex, uniform and perturbed meshes (errors C h^(p+1) and
  C h^p, slightly off the asymptote so the rates are not round numbers);
- scripts/plots/plot_scenes.py on two scenes' stats.json (one without gravity).

Both run with HOFEM_PLOT_STRICT=1, so an axis without a label, a log axis with
fewer than two labelled ticks or a legend under 8 pt fails the run
(scripts/plots/plot_style.py). The PNGs must exist and be PNG images, and the printed
convergence table must show the rates of the generated table.

    check_plots.py PLOTS_DIR OUT_DIR   (PLOTS_DIR: scripts/plots)
"""
import json
import math
import os
import subprocess
import sys
from pathlib import Path

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def fail(message):
    sys.exit(f"check_plots: {message}")


def convergence_table():
    """A table in the format `hofem verify` writes (core/study/convergence_table.cpp)."""
    names = ["problem", "cell", "order", "mesh", "n", "h", "unknowns", "cells", "l2_error", "h1_error", "rate_l2",
             "rate_h1", "setup_seconds", "assembly_seconds", "solve_seconds", "total_seconds", "newton_iterations",
             "linear_iterations", "linear_solver", "converged"]
    rows = []
    series = [("linear", "tet", p, "uniform") for p in (1, 2, 3)] + [("linear", "tet", 2, "perturbed"),
                                                                    ("linear", "hex", 1, "uniform"),
                                                                    ("neohookean", "tet", 1, "uniform"),
                                                                    ("neohookean", "tet", 2, "uniform")]
    for problem, cell, p, mesh in series:
        prev = None
        for n in (2, 4, 8):
            h = 1.0 / n
            row = {"problem": problem, "cell": cell, "order": p, "mesh": mesh, "n": n, "h": h,
                   "unknowns": 3 * (p * n - 1) ** 3, "cells": n ** 3 * (6 if cell == "tet" else 1),
                   "l2_error": 0.3 * h ** (p + 1) * (1 + 0.2 * h), "h1_error": 0.8 * h ** p * (1 + 0.3 * h),
                   "rate_l2": None, "rate_h1": None, "setup_seconds": 1e-3 * n ** 3, "assembly_seconds": 2e-3 * n ** 3,
                   "solve_seconds": 3e-3 * n ** 3, "total_seconds": 7e-3 * n ** 3, "newton_iterations": 1,
                   "linear_iterations": 10 * n, "linear_solver": "cg+pmg", "converged": True}
            if prev:
                for rate, error in (("rate_l2", "l2_error"), ("rate_h1", "h1_error")):
                    row[rate] = math.log(prev[error] / row[error]) / math.log(prev["h"] / h)
            rows.append(row)
            prev = row
    return {"columns": [{"name": n, "unit": "-", "description": n} for n in names], "rows": rows}


def scene(name, integrator, gravity):
    steps = []
    for k in range(1, 21):
        t = 0.05 * k
        energy = {"kinetic": t, "elastic": 0.5 * t * t, "gravity": -t if gravity else 0.0, "total": 0.5 * t * t}
        steps.append({"t": t, "ok": True, "energy": energy, "mean_displacement": [0, 0, -0.1 * t * t],
                      "lowest_z": 0.5 - 0.1 * t * t, "linear_iterations": 10 + k, "newton_iterations": 2})
    return {"integrator": integrator, "dt": 0.05, "ok": True, "steps": steps, "steps_done": 20,
            "mesh": {"nodes": 125}, "built": {}, "wall_seconds": 0.1}


def run(args, out):
    env = dict(os.environ, HOFEM_PLOT_STRICT="1")
    done = subprocess.run(["/usr/bin/python3"] + args, capture_output=True, text=True, env=env, timeout=300)
    if done.returncode != 0:
        fail(f"{' '.join(args)}: exit status {done.returncode}\n{done.stdout}\n{done.stderr}")
    return done.stdout


def check_png(path):
    if not path.is_file():
        fail(f"{path} not written")
    with open(path, "rb") as f:
        if f.read(8) != PNG_MAGIC:
            fail(f"{path} is not a PNG")


def main(scripts, out):
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.png"):
        old.unlink()  # a PNG left by an earlier run must not pass for this one's
    table = convergence_table()
    (out / "convergence.json").write_text(json.dumps(table))
    printed = run([str(scripts / "plot_convergence.py"), str(out / "convergence.json"), str(out)], out)
    for name in ("mms_convergence.png", "mms_h1.png"):
        check_png(out / name)
    last = [r for r in table["rows"] if r["problem"] == "linear" and r["order"] == 3][-1]
    expected = f"rates L2 {last['rate_l2']:5.2f}  H1 {last['rate_h1']:5.2f}"
    if expected not in printed:
        fail(f"plot_convergence's table lacks '{expected}':\n{printed}")

    for name, integrator, gravity in (("drop-implicit-euler", "implicit-euler", True),
                                      ("slingshot", "implicit-euler", False)):
        (out / "scenes" / name).mkdir(parents=True, exist_ok=True)
        (out / "scenes" / name / "stats.json").write_text(json.dumps(scene(name, integrator, gravity)))
    run([str(scripts / "plot_scenes.py"), str(out)], out)
    for name in ("scene_drop.png", "scene_energies.png", "scene_iterations.png"):
        check_png(out / name)
    print(f"check_plots: plot_convergence.py and plot_scenes.py wrote 5 PNGs into {out}, every axis labelled")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: check_plots.py PLOTS_DIR OUT_DIR")
    main(Path(sys.argv[1]), Path(sys.argv[2]))
