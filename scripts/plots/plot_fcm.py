#!/usr/bin/python3
"""Figures of the finite-cell experiments of Longva et al. 2020, drawn from the rows and
measurements of reports/verification.json (`hofem verify`).

    /usr/bin/python3 scripts/plots/plot_fcm.py [reports-dir | report.json]

Writes the PNGs next to the JSON. One function per figure; each returns the file
it wrote, or None after saying which rows it missed (the group did not run), so
figures of other experiments (fig4, fig6, fig10) can be added as further entries
of FIGURES.
"""
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
try:
    import plot_style  # sets the Agg back end before pyplot
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as e:  # pragma: no cover - environment problem, say what is missing
    sys.exit(f"plot_fcm: {e}; install the Debian packages python3-numpy python3-matplotlib "
             f"and run with /usr/bin/python3")

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_json import representatives  # noqa: E402


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        sys.exit(f"plot_fcm: {path} not found (run `hofem verify` first)")
    except json.JSONDecodeError as e:
        sys.exit(f"plot_fcm: {path}: invalid JSON at line {e.lineno}: {e.msg}")


def measurements(report, group):
    return [m for m in report.get("measurements", []) if m["group"] == group]


# --- Fig. 5: condition numbers vs smallest volume fraction (group embedded.fig5) ---

FIG5_KAPPA = re.compile(r"^(tet\d+) (none|jacobi|schwarz) (stabilised|unstabilised) eps=(\S+) fraction=(\S+)$")
FIG5_FRACTION = re.compile(r"^(tet\d+) smallest volume fraction eps=(\S+)$")
FIG5_LABELS = {"none": "none (A)", "jacobi": "Jacobi", "schwarz": "Additive Schwarz"}
FIG5_COLOURS = {"none": "tab:grey", "jacobi": "tab:blue", "schwarz": "tab:red"}
FIG5_STYLES = {"tet4": ("o", "--"), "tet10": ("s", "-")}


def fig5_curves(report):
    """({(stabilisation, cell, preconditioner): sorted [(eps, fraction, kappa)]}, breakdowns).

    kappa is None where the report has no finite value: "breakdown" rows (the
    Schwarz preconditioner not numerically SPD, kappa +inf, written as null)."""
    rows = measurements(report, "embedded.fig5")
    fraction = {}  # (cell, eps string) -> computed smallest volume fraction
    for m in rows:
        f = FIG5_FRACTION.match(m["name"])
        if f and m["value"] is not None:
            fraction[f.groups()] = m["value"]
    curves = {}
    for m in rows:
        k = FIG5_KAPPA.match(m["name"])
        if not k:
            continue
        cell, preconditioner, stabilisation, eps, named_fraction = k.groups()
        kappa = m["value"]
        if kappa is None or not np.isfinite(kappa):
            kappa = None
            print(f"plot_fcm: fig5: no finite kappa for '{m['name']}': {m.get('what', '')}")
        x = fraction.get((cell, eps), float(named_fraction))
        curves.setdefault((stabilisation, cell, preconditioner), []).append((float(eps), x, kappa))
    return {key: sorted(points, reverse=True) for key, points in curves.items()}


def plot_fig5(report, out_dir):
    curves = fig5_curves(report)
    if not curves:
        print("plot_fcm: fig5 skipped: no 'embedded.fig5' condition-number measurements "
              "(run `hofem verify --convergence ci` or `full`)")
        return None
    finite = [k for points in curves.values() for _, _, k in points if k is not None]
    top = 10 ** np.ceil(np.log10(max(finite)) + 0.5)  # breakdowns are drawn on this line
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, stabilisation, title in zip(axes, ("stabilised", "unstabilised"),
                                        ("with stabilisation (1e-6)", "without stabilisation")):
        broken = False
        for cell in ("tet4", "tet10"):
            marker, line = FIG5_STYLES[cell]
            for preconditioner in ("none", "jacobi", "schwarz"):
                points = curves.get((stabilisation, cell, preconditioner))
                if not points:
                    continue
                colour = FIG5_COLOURS[preconditioner]
                ok = [(x, k) for _, x, k in points if k is not None]
                if ok:
                    ax.loglog(*zip(*ok), marker=marker, linestyle=line, color=colour,
                              label=f"{cell.capitalize()}, {FIG5_LABELS[preconditioner]}")
                bad = [x for _, x, k in points if k is None]
                if bad:
                    broken = True
                    ax.loglog(bad, [top] * len(bad), marker="x", linestyle="none", color=colour, markersize=9)
        if broken:
            ax.axhline(top, color="k", linewidth=0.5, linestyle=":")
            ax.text(0.02, 0.97, "x: preconditioner breakdown (S not numerically SPD)", transform=ax.transAxes,
                    fontsize=8, va="top")
        ax.invert_xaxis()  # eps -> 0 to the right, as the sweep runs
        ax.set_title(f"$\\kappa(SA)$, $A = M + \\Delta t^2 K(u)$, {title}", fontsize=10)
        ax.set_xlabel("smallest volume fraction $\\epsilon^3$ [-]")
        ax.grid(True, which="both", alpha=0.3)
        plot_style.log_ticks(ax)
    axes[0].set_ylabel("$\\kappa = \\max|\\lambda| / \\min|\\lambda|$ [-]")
    axes[0].legend(fontsize=8, loc="center left")
    fig.suptitle("Seed Fig. 5: 4x4x4 tet grid on $[0, 4/3]^3$, embedded box $[0, 1+\\epsilon/3]^3$, "
                 "Stable Neo-Hookean (A indefinite)", fontsize=10)
    out = plot_style.save(fig, out_dir / "fcm_fig5_conditioning.png", dpi=120)
    print_fig5_table(curves)
    return out


def print_fig5_table(curves):
    cells = sorted({c for _, c, _ in curves}, key=lambda c: int(c[3:]))
    columns = [(c, p) for c in cells for p in ("none", "jacobi", "schwarz")]
    for stabilisation in ("stabilised", "unstabilised"):
        table = {}  # eps -> {(cell, preconditioner): kappa}
        for (s, c, p), points in curves.items():
            if s == stabilisation:
                for eps, _, k in points:
                    table.setdefault(eps, {})[(c, p)] = k
        print(f"\nFig. 5 kappa, {stabilisation} (eps^3 = smallest volume fraction; '-' not computed, "
              f"'breakdown' no spectrum)")
        print(f"{'eps':<8}" + "".join(f"{c + ' ' + p:>15}" for c, p in columns))
        for eps in sorted(table, reverse=True):
            row = table[eps]
            cols = [f"{'-':>15}" if (c, p) not in row else f"{'breakdown':>15}" if row[(c, p)] is None
                    else f"{row[(c, p)]:15.3e}" for c, p in columns]
            print(f"{eps:<8g}" + "".join(cols))


def rows(report, group):
    return [r for r in report.get("rows", []) if r["group"] == group]


# --- Fig. 4: simplified vs initial rules (group embedded.fig4) ---

FIG4_ROW = re.compile(r"^(.+) m=(\d+): (initial|simplified) max rel\. error$")
FIG4_POINTS = re.compile(r"^(.+) m=(\d+): points (before|after)$")


def plot_fig4(report, out_dir):
    errors, points = {}, {}
    for r in rows(report, "embedded.fig4"):
        if (m := FIG4_ROW.match(r["name"])):
            errors.setdefault((m[1], m[3]), []).append((int(m[2]), r["measured"]))
    for m_ in measurements(report, "embedded.fig4"):
        if (m := FIG4_POINTS.match(m_["name"])):
            points.setdefault((m[1], m[3]), []).append((int(m[2]), m_["value"]))
    if not errors:
        print("plot_fcm: fig4 skipped: no 'embedded.fig4' rows")
        return None
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (geometry, kind), values in sorted(errors.items()):
        values.sort()
        a.semilogy(*zip(*values), marker="o" if kind == "initial" else "s",
                   linestyle="--" if kind == "initial" else "-", label=f"{geometry}, {kind}")
    a.axhline(1e-12, color="k", linewidth=0.6, linestyle=":", label="threshold 1e-12")
    a.set_xlabel("strength m [-]")
    a.set_ylabel("max relative error, monomials of degree <= m [-]")
    a.legend(fontsize=8)
    a.grid(True, which="both", alpha=0.3)
    for (geometry, kind), values in sorted(points.items()):
        values.sort()
        b.semilogy(*zip(*values), marker="o", linestyle="--" if kind == "before" else "-",
                   label=f"{geometry}, {kind}")
    ms = np.arange(1, 11)
    b.semilogy(ms, [(m + 1) * (m + 2) * (m + 3) / 6 for m in ms], "k:", label="M = C(m+3, 3) per cell")
    b.set_xlabel("strength m [-]")
    b.set_ylabel("quadrature points, summed over cells [-]")
    b.legend(fontsize=8)
    b.grid(True, which="both", alpha=0.3)
    fig.suptitle("Seed Fig. 4: monomials over a rotated cuboid in the reference hex, clipped vs LP-simplified rules",
                 fontsize=10)
    out = plot_style.save(fig, out_dir / "fcm_fig4_simplification.png", dpi=120)
    return out


# --- Fig. 6: centre of mass of a spinning body (group embedded.fig6) ---

def plot_fig6(report, out_dir):
    drift = [(r["name"].split(":")[0] if ":" in r["name"] else r["name"].replace(" centre-of-mass drift / size", ""),
              r["measured"], r["threshold"]) for r in rows(report, "embedded.fig6")
             if r["name"].endswith("centre-of-mass drift / size")]
    if not drift:
        print("plot_fcm: fig6 skipped: no 'embedded.fig6' rows")
        return None
    fig, ax = plt.subplots(figsize=(8, 3.8))
    names = [d[0] for d in drift]
    values = [max(d[1], 1e-17) for d in drift]
    ax.barh(names, values, color=["tab:red" if "coarse" in n else "tab:blue" for n in names])
    ax.set_xscale("log")
    ax.set_xlabel("centre-of-mass drift after half a turn / body size [-]")
    ax.set_ylabel("discretisation")
    ax.set_title("Seed Fig. 6: a half tube spinning about its centre of mass (implicit Euler, 50 steps)", fontsize=10)
    ax.grid(True, which="both", axis="x", alpha=0.3)
    out = plot_style.save(fig, out_dir / "fcm_fig6_centre_of_mass.png", dpi=120)
    return out


# --- Fig. 10: static L2 convergence (group embedded.fig10) ---

FIG10 = re.compile(r"^(.+) h=1/(\d+) l2$")


def plot_fig10(report, out_dir):
    series = {}
    for m_ in measurements(report, "embedded.fig10"):
        if (m := FIG10.match(m_["name"])):
            series.setdefault(m[1], []).append((1.0 / int(m[2]), m_["value"]))
    if not series:
        print("plot_fcm: fig10 skipped: no 'embedded.fig10' measurements")
        return None
    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    for name, values in sorted(series.items()):
        values.sort(reverse=True)  # coarse to fine: the last segment is the finest pair
        order = 2 if "Hex20" in name else 1  # Hex8: order 1, Hex20: order 2 (plot_style's order colours)
        hs, errors = zip(*values)
        colour = plot_style.order_colour(order)
        ax.loglog(hs, errors, marker="s" if order == 2 else "o", color=colour,
                  linestyle="-" if name.startswith("FCM") else "--", label=name)
        if len(values) > 1:
            rate = np.log(errors[-2] / errors[-1]) / np.log(hs[-2] / hs[-1])
            # The two staircase lines run close together: Hex8's rate goes below its line.
            plot_style.annotate_rate(ax, hs, errors, rate, colour, below=order == 1 and not name.startswith("FCM"))
    h = np.array(sorted({v[0] for values in series.values() for v in values}))
    for rate, anchor in ((1, 0.3), (2, 0.08), (3, 0.004)):
        ax.loglog(h, anchor * (h / h[-1]) ** rate, "k:", linewidth=0.7)
        ax.text(h[-1], anchor * 1.1, f"O(h^{rate})", fontsize=8)
    ax.set_xlabel("h = 1/n, hex grid spacing [model length; ball radius 1/2]")
    plot_style.h_ticks(ax, [round(1 / v) for v in h])
    ax.set_ylabel("relative L2 error (manufactured solution) [-]")
    ax.set_title("Seed Fig. 10: half ball in hex grids, FCM vs staircase FEM\n(numbers: rate of the finest pair)",
                 fontsize=10)
    ax.legend(fontsize=plot_style.MIN_LEGEND_FONTSIZE)
    ax.grid(True, which="both", alpha=0.3)
    out = plot_style.save(fig, out_dir / "fcm_fig10_convergence.png", dpi=120)
    return out


# --- Benchmarks: quadrature point reduction and FEM vs FCM per step (BM_Fcm*, BM_ElasticStep) ---

def benchmark_runs(directory):
    """Finite-cell benchmark entries (medians) of the main job's benchmarks.json."""
    path = directory / "benchmarks.json"
    if not path.exists():
        return []
    return [b for b in representatives(load(path))
            if b["name"].startswith(("BM_FcmQuadrature", "BM_ElasticStep")) and "error_occurred" not in b]


def plot_benchmarks(report, out_dir):
    runs = benchmark_runs(out_dir)
    quad = [b for b in runs if b["name"].startswith("BM_FcmQuadrature")]
    step = [b for b in runs if b["name"].startswith("BM_ElasticStep")]
    if not quad and not step:
        print("plot_fcm: benchmarks skipped: no BM_FcmQuadrature / BM_ElasticStep runs in benchmarks.json")
        return None
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    labels = [q["name"].split("/")[0].replace("BM_FcmQuadrature_", "") for q in quad]
    x = np.arange(len(quad))
    a.bar(x - 0.2, [q["points_before"] for q in quad], 0.4, label="clipped (§4.5)")
    a.bar(x + 0.2, [q["points_after"] for q in quad], 0.4, label="LP-simplified (§4.4)")
    for i, q in enumerate(quad):
        a.text(i, q["points_before"], f"{q['reduction']:.0f}x\n{q['generation_cpu_s']:.2f} s + "
               f"{q['simplification_cpu_s']:.1f} s CPU", ha="center", va="bottom", fontsize=8)
    a.set_xticks(x, labels)
    a.set_yscale("log")
    a.set_ylim(top=max([q["points_before"] for q in quad] + [1]) * 8)  # room for the labels above the bars
    a.set_xlabel("embedded geometry")
    a.set_ylabel("stiffness quadrature points [-]")
    a.set_title("quadrature generation + simplification", fontsize=10)
    a.legend(fontsize=8)
    names = [s.get("label", s["name"]) for s in step]
    ms = [s["real_time"] for s in step]
    bars = b.barh(names, ms, color=["tab:blue", "tab:orange"][: len(step)])
    for bar, s in zip(bars, step):
        b.text(bar.get_width(), bar.get_y() + bar.get_height() / 2,
               f" {s['cg_iterations_per_step']:.0f} CG its", va="center", fontsize=8)
    b.set_xlabel("time per implicit Euler step, median [ms]")
    b.set_ylabel("discretisation")
    b.set_title("FEM vs FCM per step (seed §6.5)", fontsize=10)
    out = plot_style.save(fig, out_dir / "fcm_benchmarks.png", dpi=120)
    return out


FIGURES = [("fig4", plot_fig4), ("fig5", plot_fig5), ("fig6", plot_fig6), ("fig10", plot_fig10),
           ("benchmarks", plot_benchmarks)]


def main():
    target = Path(sys.argv[1] if len(sys.argv) > 1 else "reports")
    path = target if target.suffix == ".json" else target / "verification.json"
    report = load(path)
    written = [out for _, plot in FIGURES if (out := plot(report, path.parent)) is not None]
    print(f"\nplot_fcm: wrote {', '.join(str(p) for p in written) if written else 'nothing'}")


if __name__ == "__main__":
    main()
