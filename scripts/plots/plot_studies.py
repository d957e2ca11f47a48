#!/usr/bin/python3
"""Work-precision plots of the studies (reports/studies/NAME/study.json, written
by `hofem study`): the study's metric (max over its frames) against the median
time per step, one marker per family, a family's resolutions joined coarse to
fine; the thresholds as dashed lines, the reference's own error (Richardson) as a
shaded band, each run's faceting floor (t = 0) as a small open marker below it.
Where runs solve iteratively, a second panel sets the same error against the
linear iterations per step (the thesis' Figs. 13-14: error against iterations
and against time). Writes reports/studies/NAME/work_precision.png. Run with Debian's interpreter
(python3-matplotlib)."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_style  # noqa: E402  (sets the Agg back end before pyplot)
import matplotlib.pyplot as plt  # noqa: E402

MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">"]
# One colour per family, fixed by the family's order of appearance (colour-blind safe, Okabe-Ito).
COLOURS = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"]
# Scenes are in SI units (m, kg, s): the metrics' units (norms over the body's volume).
METRIC_UNITS = {"surface_rms": "m", "surface_max": "m", "displacement_rms": "m", "relative_l2": "-",
                "relative_h1": "-", "l2": "m^(5/2)", "h1": "m^(3/2)"}


def plot(study, path):
    metric = study["metric"]
    runs = [r for r in study["runs"] if r["ok"]]
    families = []
    for r in runs:
        if r["family"] not in families:
            families.append(r["family"])
    # Floors at round-off (a box's flat faces are exact at t = 0) are not drawn.
    # (1e-10 of the largest error: a box's floor is ~1e-17 m, where a run converged to round-off also sits).
    smallest, largest = min(r["metric"] for r in runs), max(r["metric"] for r in runs)
    visible = lambda r: metric.startswith("surface") and r["floor"]["surface_rms"] > max(1e-3 * smallest, 1e-10 * largest)
    iterative = [r for r in runs if r["linear_iterations"] > 0]
    fig, axes = plt.subplots(1, 2 if iterative else 1, figsize=(13.0 if iterative else 7.0, 5.0), squeeze=False)
    ax = axes[0][0]
    per_step = lambda r: r["linear_iterations"] / max(r["steps"], 1)
    for i, family in enumerate(families):
        rows = sorted((r for r in runs if r["family"] == family), key=lambda r: (r["unknowns"], r["linear_iterations"]))
        colour, marker = COLOURS[i % len(COLOURS)], MARKERS[i % len(MARKERS)]
        if iterative:
            its = [r for r in rows if r["linear_iterations"] > 0]
            if its:
                axes[0][1].plot([per_step(r) for r in its], [r["metric"] for r in its], marker=marker, color=colour,
                                label=family, markersize=7)
        x = [r["time_per_step_median"] for r in rows]
        y = [r["metric"] for r in rows]
        ax.plot(x, y, marker=marker, color=colour, label=family, markersize=7)
        floors = [(r["time_per_step_median"], r["floor"]["surface_rms"]) for r in rows if visible(r)]
        if floors:
            ax.plot(*zip(*floors), linestyle="none", marker=marker, color=colour, markerfacecolor="none", markersize=5,
                    alpha=0.7)
        for r in rows:
            ax.annotate(f'{r["unknowns"]}', (r["time_per_step_median"], r["metric"]), textcoords="offset points",
                        xytext=(4, 4), fontsize=7, color=colour)
    for t in study["thresholds"]:
        ax.axhline(t, color="0.4", linestyle="--", linewidth=0.8)
        ax.annotate(f"threshold {t:g}", (0.01, t), xycoords=("axes fraction", "data"), xytext=(0, 2),
                    textcoords="offset points", fontsize=8, color="0.3")
    richardson = study["reference"].get("richardson")
    if richardson:
        ax.axhspan(1e-300, richardson["estimate"][metric], color="0.85", zorder=0,
                   label="reference's own error (Richardson)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per step, median [s]")
    ax.set_ylabel(f"{metric.replace('_', ' ')}, max over frames [{METRIC_UNITS.get(metric, 'm')}]")
    ax.set_title(f'{study["name"]}: error against time per step\n(open markers: faceting floor at t = 0; labels: unknowns)',
                 fontsize=10)
    ys = [r["metric"] for r in runs] + list(study["thresholds"])
    ys += [r["floor"]["surface_rms"] for r in runs if visible(r)]
    if richardson:
        ys.append(richardson["estimate"][metric])
    ax.set_ylim(min(ys) / 3, max(ys) * 2)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE, loc="lower left")
    plot_style.log_ticks(ax)
    if iterative:
        it = axes[0][1]
        for t in study["thresholds"]:
            it.axhline(t, color="0.4", linestyle="--", linewidth=0.8)
        it.set_xscale("log")
        it.set_yscale("log")
        it.set_ylim(*ax.get_ylim())
        it.set_xlabel("linear (Krylov) iterations per step [-]")
        it.set_ylabel(ax.get_ylabel())
        it.set_title(f'{study["name"]}: error against iterations per step\n(runs that solve iteratively)', fontsize=10)
        it.grid(True, which="both", alpha=0.3)
        it.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE, loc="lower left")
        plot_style.log_ticks(it)
    plot_style.save(fig, path, dpi=110)


def main(reports):
    root = os.path.join(reports, "studies")
    if not os.path.isdir(root):
        return 0
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name, "study.json")
        if os.path.isfile(path):
            with open(path) as f:
                plot(json.load(f), os.path.join(root, name, "work_precision.png"))
            print(f"plot_studies: {os.path.join(root, name, 'work_precision.png')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "reports"))
