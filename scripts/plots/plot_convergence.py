#!/usr/bin/python3
"""Convergence plots of the manufactured-solution study from its tidy table
(convergence.json, written by `hofem verify` beside verification.json; the
columns are described in the file itself):

- mms_convergence.png: per problem (rows), the L2 error against h, against the
  unknowns and against the wall time of the run;
- mms_h1.png: per problem, the H1-seminorm error against h.

One colour per element order in every panel (plot_style.py), marker per cell,
line style per mesh kind; the observed rate of each series' finest pair (the
table's rate_l2 / rate_h1 of its last row) is written at its last segment.

    /usr/bin/python3 scripts/plots/plot_convergence.py reports/convergence.json [OUT_DIR]

Prints the table (errors and rates per series) and writes the PNGs into OUT_DIR
(default: the table's directory).
"""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import plot_style  # noqa: E402  (sets the Agg back end before pyplot)
import matplotlib.pyplot as plt  # noqa: E402

REQUIRED = ("problem", "cell", "order", "mesh", "n", "h", "unknowns", "l2_error", "h1_error", "rate_l2", "rate_h1",
            "total_seconds")


def load_table(path):
    """The table's rows grouped by series: {(problem, cell, order, mesh): [row, ...]} in the table's order."""
    try:
        with open(path) as f:
            table = json.load(f)
    except FileNotFoundError:
        sys.exit(f"plot_convergence: {path} not found (written by `hofem verify --convergence ci|full`)")
    except json.JSONDecodeError as e:
        sys.exit(f"plot_convergence: {path}: invalid JSON at line {e.lineno}: {e.msg}")
    names = {c["name"] for c in table.get("columns", [])}
    missing = [c for c in REQUIRED if c not in names]
    if missing:
        sys.exit(f"plot_convergence: {path}: columns missing: {', '.join(missing)}")
    series = {}
    for row in table["rows"]:
        series.setdefault((row["problem"], row["cell"], row["order"], row["mesh"]), []).append(row)
    return series


def draw_series(ax, rows, x_of, y_key, rate_key=None):
    """One series on log-log axes in its order's colour and its cell / mesh style;
    with rate_key, the last row's rate at the last segment."""
    cell, order, mesh = rows[0]["cell"], rows[0]["order"], rows[0]["mesh"]
    x = [x_of(r) for r in rows]
    y = [r[y_key] for r in rows]
    colour = plot_style.order_colour(order)
    ax.loglog(x, y, color=colour, marker=plot_style.CELL_MARKERS.get(cell, "^"),
              linestyle=plot_style.MESH_LINESTYLES.get(mesh, "-."), markersize=5,
              alpha=0.75 if mesh == "perturbed" else 1.0)
    if rate_key:
        # Perturbed series sit on their uniform twins: their rates go below the line.
        plot_style.annotate_rate(ax, x, y, rows[-1][rate_key], colour, below=mesh == "perturbed" or cell == "hex")


def reference_slopes(ax, series, problem, y_key, power):
    """A dotted h^(p + power) line per order, through the finest point of the
    order's first series (tet, uniform where present)."""
    for order in sorted({k[2] for k in series if k[0] == problem}):
        keys = sorted((k for k in series if k[0] == problem and k[2] == order),
                      key=lambda k: (k[1] != "tet", k[3] != "uniform"))
        rows = series[keys[0]]
        h = [r["h"] for r in rows]
        ax.loglog(h, [rows[-1][y_key] * (v / h[-1]) ** (order + power) for v in h], ":",
                  color=plot_style.order_colour(order), linewidth=1.0, alpha=0.7)


def add_legends(fig, series):
    orders = {k[2] for k in series}
    styles = {(k[1], k[3]) for k in series}
    handles = plot_style.order_legend_handles(orders) + plot_style.style_legend_handles(styles)
    handles.append(plt.Line2D([], [], color="0.35", linestyle=":", label="reference slope"))
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=plot_style.LEGEND_FONTSIZE,
               frameon=False, bbox_to_anchor=(0.5, 0.0))


H_LABEL = "h = 1/n [cube side]"


def plot_l2(series, out):
    problems = sorted({k[0] for k in series})
    fig, axes = plt.subplots(len(problems), 3, figsize=(15, 4.3 * len(problems) + 0.5), squeeze=False)
    for row, problem in enumerate(problems):
        ax_h, ax_dof, ax_time = axes[row]
        for key, rows in sorted(series.items()):
            if key[0] != problem:
                continue
            draw_series(ax_h, rows, lambda r: r["h"], "l2_error", "rate_l2")
            draw_series(ax_dof, rows, lambda r: r["unknowns"], "l2_error")
            draw_series(ax_time, rows, lambda r: r["total_seconds"], "l2_error")
        reference_slopes(ax_h, series, problem, "l2_error", 1)
        plot_style.h_ticks(ax_h, {r["n"] for k, rows in series.items() if k[0] == problem for r in rows})
        ax_h.set_title(f"{problem}: L2 error vs h (numbers: rate of the finest pair;\ndotted: h^(p+1))", fontsize=10)
        ax_h.set_xlabel(H_LABEL)
        ax_dof.set_title(f"{problem}: L2 error vs unknowns", fontsize=10)
        ax_dof.set_xlabel("free unknowns (DOFs) [-]")
        ax_time.set_title(f"{problem}: L2 error vs run time (solver 'auto')", fontsize=10)
        ax_time.set_xlabel("wall time of the run: mesh, set-up, solve, error [s]")
        for ax in (ax_h, ax_dof, ax_time):
            ax.set_ylabel("L2 error ||u_h - u*|| [-]")
            ax.grid(True, which="both", alpha=0.3)
            plot_style.log_ticks(ax)
    add_legends(fig, series)
    return plot_style.save(fig, out, dpi=110, rect=(0, 0.05, 1, 1))


def plot_h1(series, out):
    problems = sorted({k[0] for k in series})
    fig, axes = plt.subplots(1, len(problems), figsize=(6.5 * len(problems), 5.2), squeeze=False)
    for ax, problem in zip(axes[0], problems):
        for key, rows in sorted(series.items()):
            if key[0] == problem:
                draw_series(ax, rows, lambda r: r["h"], "h1_error", "rate_h1")
        reference_slopes(ax, series, problem, "h1_error", 0)
        plot_style.h_ticks(ax, {r["n"] for k, rows in series.items() if k[0] == problem for r in rows})
        ax.set_xlabel(H_LABEL)
        ax.set_ylabel("H1-seminorm error |u_h - u*|_H1 [-]")
        ax.set_title(f"{problem}: H1 error vs h (numbers: rate of the finest pair;\ndotted: h^p)", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        plot_style.log_ticks(ax)
    add_legends(fig, series)
    return plot_style.save(fig, out, dpi=110, rect=(0, 0.07, 1, 1))


def print_table(series):
    print("\nmanufactured solutions (L2 / H1 errors, observed rates against the previous n):")
    for (problem, cell, order, mesh), rows in sorted(series.items()):
        print(f"  {problem} {cell} p={order} {mesh}")
        for r in rows:
            rates = "" if r["rate_l2"] is None else f"  rates L2 {r['rate_l2']:5.2f}  H1 {r['rate_h1']:5.2f}"
            print(f"    n={r['n']:3d} dofs={r['unknowns']:8d}  L2 {r['l2_error']:.3e}  H1 {r['h1_error']:.3e}  "
                  f"{r['total_seconds']:7.2f} s{rates}")


def main(table_path, out_dir):
    series = load_table(table_path)
    if not series:
        print(f"plot_convergence: {table_path} has no rows; no plots")
        return []
    print_table(series)
    return [plot_l2(series, out_dir / "mms_convergence.png"), plot_h1(series, out_dir / "mms_h1.png")]


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: plot_convergence.py convergence.json [OUT_DIR]")
    table = Path(sys.argv[1])
    written = main(table, Path(sys.argv[2]) if len(sys.argv) > 2 else table.parent)
    print(f"plot_convergence: wrote {', '.join(str(p) for p in written) or 'nothing'}")
