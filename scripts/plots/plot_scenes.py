#!/usr/bin/python3
"""Plots of the built-in scene runs (reports/scenes/*/stats.json, written by
`hofem run`): the drop test's displacement curve per integrator (thesis Fig.
10-11), energies over time per scene, and CG iterations per step of the
slingshot. Run with Debian's interpreter (python3-numpy, python3-matplotlib)."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_style  # noqa: E402  (sets the Agg back end before pyplot)
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, out, name, dpi):
    """Lays out, writes and closes the figure (plot_style.save); returns its path."""
    return plot_style.save(fig, os.path.join(out, name), dpi=dpi)


def load(directory):
    runs = {}
    root = os.path.join(directory, "scenes")
    if not os.path.isdir(root):
        return runs
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name, "stats.json")
        if os.path.isfile(path):
            with open(path) as f:
                runs[name] = json.load(f)
    return runs


def series(run, key):
    steps = [s for s in run.get("steps", []) if s.get("ok")]
    t = [s["t"] for s in steps]
    return t, [key(s) for s in steps]


def plot_drop(runs, out):
    drops = {k: v for k, v in runs.items() if k.startswith("drop-")}
    if not drops:
        return None
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for name, run in drops.items():
        t, z = series(run, lambda s: s["mean_displacement"][2])
        ax[0].plot(t, z, label=f"{run['integrator']} (dt = {run['dt']:.2g})")
        t, low = series(run, lambda s: s["lowest_z"])
        ax[1].plot(t, low, label=run["integrator"])
    ax[0].set(xlabel="t [s]", ylabel="mean vertical displacement [m]", title="Body dropped on the floor")
    ax[1].set(xlabel="t [s]", ylabel="lowest point z [m] (floor at 0)", title="Contact (penalty floor)")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
    return save(fig, out, "scene_drop.png", 120)


# One colour per kind of energy in every panel (a scene without gravity would
# otherwise shift the colour cycle and paint "total" in gravity's green).
ENERGY_COLOURS = {"kinetic": "#0072B2", "elastic": "#D55E00", "gravity": "#009E73", "total": "black"}


def plot_energies(runs, out):
    if not runs:
        return None
    names = list(runs)
    cols = 3
    rows = (len(names) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.0 * rows), squeeze=False)
    for ax, name in zip(axes.flat, names):
        run = runs[name]
        for key, colour in ENERGY_COLOURS.items():
            t, e = series(run, lambda s, k=key: s["energy"][k] if "energy" in s else float("nan"))
            if any(abs(v) > 0 for v in e):
                ax.plot(t, e, color=colour, label=key)
        ax.set_title(f"{name} ({run['integrator']})", fontsize=9)
        ax.set_xlabel("t [s]", fontsize=8)
        ax.set_ylabel("energy [J]", fontsize=8)  # scenes are in SI units (m, kg, s, Pa)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    return save(fig, out, "scene_energies.png", 110)


def plot_iterations(runs, out):
    picked = {k: v for k, v in runs.items() if k == "slingshot" or k.startswith("twisting")}
    if not picked:
        return None
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, run in picked.items():
        t, lin = series(run, lambda s: s["linear_iterations"])
        t2, newton = series(run, lambda s: s["newton_iterations"])
        if any(lin):
            ax.plot(t, lin, label=f"{name}: CG iterations per step")
        ax.plot(t2, newton, ls="--", label=f"{name}: Newton iterations per step")
    ax.set(xlabel="t [s]", ylabel="iterations per time step [-]", title="Solver work per step")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
    return save(fig, out, "scene_iterations.png", 120)


def summary(runs):
    print("| scene | integrator | unknown nodes | steps | ok | Newton its | linear its | Hessians | mass | wall s |")
    print("|---|---|---:|---:|---|---:|---:|---:|---|---:|")
    for name, run in runs.items():
        b = run.get("built", {})
        print(f"| {name} | {run['integrator']} | {run['mesh']['nodes']} | {run.get('steps_done', '-')} | {run['ok']} | "
              f"{b.get('newton_iterations', '-')} | {b.get('linear_iterations', '-')} | "
              f"{b.get('hessian_assemblies', '-')} | {b.get('mass', '-')} | {run['wall_seconds']:.1f} |")


def main(directory):
    runs = load(directory)
    if not runs:
        print("plot_scenes: no reports/scenes/*/stats.json")
        return
    made = [p for p in (plot_drop(runs, directory), plot_energies(runs, directory), plot_iterations(runs, directory)) if p]
    summary(runs)
    print("plots:", ", ".join(os.path.basename(p) for p in made))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "reports")
