"""The shared look of hofem's plots (imported by plot_convergence.py, plot_reports.py,
plot_scenes.py, plot_fcm.py and plot_studies.py).

- One colour per element order, the same in every panel of every script, so
  "orange" means p = 2 wherever it appears (Okabe & Ito's colour-blind-safe
  palette, https://jfly.uni-koeln.de/color/).
- Marker per cell shape, line style per mesh kind; the colours and the styles
  get separate, short legends instead of one entry per series.
- Log axes carry at least two labelled ticks: an axis spanning less than two
  decades gets ticks at 1, 2 and 5 times the powers of ten (matplotlib's default
  labels only the decades, which left the h axes with a single "10^-1").
- save() lays out and writes a figure and lists what a reader would miss: an axis
  without a label, a log axis with fewer than two labelled ticks, a legend font
  under 8 pt. HOFEM_PLOT_STRICT=1 (the tests) turns those into errors.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

# Okabe-Ito: blue, vermillion, bluish green, reddish purple, orange, sky blue.
ORDER_COLOURS = {1: "#0072B2", 2: "#D55E00", 3: "#009E73", 4: "#CC79A7", 5: "#E69F00", 6: "#56B4E9"}
CELL_MARKERS = {"tet": "o", "hex": "s"}
MESH_LINESTYLES = {"uniform": "-", "perturbed": "--"}
LEGEND_FONTSIZE = 9
MIN_LEGEND_FONTSIZE = 8


def order_colour(order):
    """The colour of element order `order` (black past the palette)."""
    return ORDER_COLOURS.get(int(order), "black")


def order_legend_handles(orders):
    """Legend handles: one coloured line per order."""
    return [Line2D([], [], color=order_colour(p), linewidth=2.5, label=f"p = {p}") for p in sorted(orders)]


def style_legend_handles(styles):
    """Legend handles, grey: one per (cell, mesh) pair present, marker and line style as drawn."""
    return [Line2D([], [], color="0.35", marker=CELL_MARKERS.get(cell, "^"),
                   linestyle=MESH_LINESTYLES.get(mesh, "-."), label=f"{cell}, {mesh}")
            for cell, mesh in sorted(styles)]


def annotate_rate(ax, x, y, rate, colour, below=False):
    """Writes the observed rate at the middle of a series' last segment (log-log:
    the geometric mean of its end points), above the line (or below). Error
    against h rises to the right, so "above" is up and to the left of the point."""
    if rate is None or len(x) < 2 or not math.isfinite(rate):
        return
    xm, ym = math.sqrt(x[-2] * x[-1]), math.sqrt(y[-2] * y[-1])
    ax.annotate(f"{rate:.2f}", (xm, ym), textcoords="offset points", xytext=(5, -12) if below else (-5, 4),
                ha="left" if below else "right", fontsize=8, color=colour, fontweight="bold")


def h_ticks(ax, ns, axis="x"):
    """Ticks of an h = 1/n axis at the sizes run, labelled 1/n."""
    hs = sorted({1.0 / n for n in ns})
    a = ax.xaxis if axis == "x" else ax.yaxis
    a.set_major_locator(ticker.FixedLocator(hs))
    a.set_major_formatter(ticker.FixedFormatter([f"1/{round(1 / h)}" for h in hs]))
    a.set_minor_formatter(ticker.NullFormatter())


def log_ticks(ax, axis="both"):
    """After the data are drawn: log axes spanning under two decades get major
    ticks at 1, 2, 5 x 10^k, all labelled; wider ones keep the decades."""
    for name in ("x", "y") if axis == "both" else (axis,):
        a = ax.xaxis if name == "x" else ax.yaxis
        if a.get_scale() != "log" or isinstance(a.get_major_locator(), ticker.FixedLocator):
            continue  # linear, or ticks placed on purpose (h_ticks)
        lo, hi = sorted(ax.get_xlim() if name == "x" else ax.get_ylim())
        if lo <= 0 or math.log10(hi / lo) >= 2:
            continue
        a.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        # matplotlib's LogFormatter drops the 2s and 5s again over a decade or more.
        a.set_major_formatter(ticker.FuncFormatter(_power_of_ten_label))
        a.set_minor_formatter(ticker.NullFormatter())


def _power_of_ten_label(value, _position=None):
    """Plain decimals from 0.001 to 1000 ("0.02", "5", "200"), m x 10^e in mathtext
    beyond ("10^e" alone for m = 1)."""
    if value <= 0:
        return ""
    if 1e-3 <= value < 1e4:
        return f"{value:g}"
    exponent = math.floor(math.log10(value) + 1e-9)
    mantissa = round(value / 10 ** exponent, 6)
    if mantissa == 1:
        return f"$10^{{{exponent}}}$"
    return f"${mantissa:g}\\times10^{{{exponent}}}$"


def _labelled_ticks(ax, name):
    a = ax.xaxis if name == "x" else ax.yaxis
    lo, hi = sorted(ax.get_xlim() if name == "x" else ax.get_ylim())
    count = 0
    for which in ("major", "minor"):
        locs = a.get_majorticklocs() if which == "major" else a.get_minorticklocs()
        labels = a.get_majorticklabels() if which == "major" else a.get_minorticklabels()
        for loc, text in zip(locs, labels):
            if text.get_text().strip() and text.get_visible() and lo * (1 - 1e-9) <= loc <= hi * (1 + 1e-9):
                count += 1
    return count


def readability_problems(fig):
    """What a reader would miss in the figure, one line per finding."""
    fig.canvas.draw()
    problems = []
    for i, ax in enumerate(fig.axes):
        if not ax.axison:
            continue
        where = f"axes {i} ('{ax.get_title()[:40]}')"
        for name in ("x", "y"):
            a = ax.xaxis if name == "x" else ax.yaxis
            if not a.get_visible():
                continue
            if not a.get_label_text().strip() and not _shares_label(ax, name):
                problems.append(f"{where}: no {name} label")
            if a.get_scale() == "log" and max(_labelled_ticks(o, name) for o in _sharing(ax, name)) < 2:
                problems.append(f"{where}: {name} axis (log) has fewer than 2 labelled ticks")
        legend = ax.get_legend()
        if legend and any(t.get_fontsize() < MIN_LEGEND_FONTSIZE for t in legend.get_texts()):
            problems.append(f"{where}: legend font under {MIN_LEGEND_FONTSIZE} pt")
    for legend in fig.legends:
        if any(t.get_fontsize() < MIN_LEGEND_FONTSIZE for t in legend.get_texts()):
            problems.append(f"figure legend font under {MIN_LEGEND_FONTSIZE} pt")
    return problems


def _sharing(ax, name):
    """The axes sharing ax's x or y axis, ax included (panels of a row with
    sharey=True hide their tick labels but the first's)."""
    group = ax.get_shared_y_axes() if name == "y" else ax.get_shared_x_axes()
    return group.get_siblings(ax)


def _shares_label(ax, name):
    """A panel sharing its y (x) axis may leave the label to its neighbour."""
    return any((o.yaxis if name == "y" else o.xaxis).get_label_text().strip() for o in _sharing(ax, name))


def save(fig, path, dpi=110, **layout):
    """Lays out and writes the figure, closes it, reports readability problems
    (errors under HOFEM_PLOT_STRICT=1); returns the path."""
    fig.tight_layout(**layout)
    problems = readability_problems(fig)
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    for p in problems:
        print(f"plot_style: {os.path.basename(str(path))}: {p}", file=sys.stderr)
    if problems and os.environ.get("HOFEM_PLOT_STRICT") == "1":
        sys.exit(f"plot_style: {path}: {len(problems)} readability problem(s) (HOFEM_PLOT_STRICT=1)")
    return path
