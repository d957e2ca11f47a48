#!/usr/bin/python3
"""The seeds' reported numbers beside hofem's: reads the main job's reports
(studies, verification.json) and writes reports/paper_claims.json and
reports/paper_claims.md. Each row: id, source (document, section, table or
figure), quantity, paper_value, measured, unit, criterion (written here, before
any measurement it judges), agrees, size (main-job or full), note.

Sources: Longva et al. 2020, "Higher-order finite elements for embedded
simulation" (Table 1, §6.2-6.5, Fig. 10), and the thesis on a high-order FEM
simulator (§5.2 Fig. 9: the cantilever's inversion; §5.3.1 Figs. 10-11: the
drop's integrators; §5.3.2 Figs. 12-13: fixed Krylov budgets and
preconditioners; §5.4 Fig. 14: P1 against P2). Each row's function says how
its experiment is scaled to this machine. The twisting cylinder is scaled: the
seed's is 16 m long with E = 5e6, nu = 0.48 and a 0.015 m RMS threshold; ours
(scripts/studies/twisting-cylinder.json) is 3 m long (radii 0.5 / 1 m), the
same material, 1 s of a 2 s quarter turn at dt = 0.1, and the threshold scaled
with the length, 0.015 x 3 / 16 = 0.0028, rounded to 0.003.

Usage: paper_claims.py [REPORTS] [--out DIR] [--full] (default REPORTS and DIR:
reports). Exits 1 if a source file is missing (the row would be silent garbage).
--full builds the rows of the full-size studies instead (REPORTS/full/studies,
written by scripts/studies-full; default DIR: REPORTS/full), size "full"; a
study that was not run at full size leaves its rows out and is listed as
skipped (exit 1 only if none was run)."""
import json
import math
import os
import re
import sys

THRESHOLD = 0.003  # the twisting cylinder's scaled threshold (above)


def load(reports, studies_dir="studies"):
    with open(os.path.join(reports, "verification.json")) as f:
        verification = json.load(f)
    rows = {(r["group"], r["name"]): r["measured"] for r in verification["rows"]}
    rows.update({(m["group"], m["name"]): m["value"] for m in verification.get("measurements", [])})
    studies = {}
    root = os.path.join(reports, studies_dir)
    for name in sorted(os.listdir(root)):
        if studies_dir != "studies" and not os.path.exists(os.path.join(root, name, "study.json")):
            continue  # a full-size study that did not finish: its rows are listed as skipped
        with open(os.path.join(root, name, "study.json")) as f:
            studies[name] = json.load(f)

    def run_stats(study, run):
        with open(os.path.join(root, study, "runs", run, "stats.json")) as f:
            return json.load(f)

    def scene_stats(scene):
        with open(os.path.join(reports, "scenes", scene, "stats.json")) as f:
            return json.load(f)

    return {"verification": rows, "studies": studies, "run_stats": run_stats, "scene_stats": scene_stats}


def time_at(study, family, threshold):
    """Median time per step at which the family's curve crosses the threshold
    (log-log interpolation between the two runs that bracket it). Returns
    (seconds, kind): kind "interpolated", "at most" (every run is under the
    threshold: the coarsest's time bounds it) or "more than" (none is: the
    finest's time is a lower bound)."""
    runs = sorted((r for r in study["runs"] if r["ok"] and r["family"] == family), key=lambda r: r["unknowns"])
    if not runs:
        raise KeyError(f"no run of family {family!r}")
    if runs[0]["metric"] <= threshold:
        return runs[0]["time_per_step_median"], "at most"
    for coarse, fine in zip(runs, runs[1:]):
        if fine["metric"] <= threshold < coarse["metric"]:
            a = math.log(threshold / coarse["metric"]) / math.log(fine["metric"] / coarse["metric"])
            t = math.exp(math.log(coarse["time_per_step_median"]) +
                         a * (math.log(fine["time_per_step_median"]) - math.log(coarse["time_per_step_median"])))
            return t, "interpolated"
    return runs[-1]["time_per_step_median"], "more than"


def ratio_row(R, cid, family, paper_ms, note):
    tc = R["studies"]["twisting-cylinder"]
    t, kind = time_at(tc, family, THRESHOLD)
    h, hkind = time_at(tc, "Hex20 FCM", THRESHOLD)
    paper = paper_ms / 359.0
    measured = t / h
    # The ratio is exact when both crossings are interpolated, a lower bound
    # when the family only bounds its time from below ("more than") or Hex20
    # FCM from above ("at most"), an upper bound the other way round.
    lower = kind == "more than" or hkind == "at most"
    upper = kind == "at most" or hkind == "more than"
    if lower and upper:
        raise KeyError(f"{family} / Hex20 FCM: the bounds point both ways; add runs around the threshold")
    low, high = paper / 3, paper * 3
    # A bound agrees when the values it allows meet the seed's interval on the seed's side of 1.
    if lower:
        agrees = measured <= high and (paper > 1 or max(measured, low) < 1)
    elif upper:
        agrees = measured >= low and (paper < 1 or min(measured, high) > 1)
    else:
        agrees = (measured > 1) == (paper > 1) and low <= measured <= high
    return {"id": cid, "source": "Longva et al. 2020, Table 1 (§6.2)",
            "quantity": f"time per step of {family} / Hex20 FCM at surface RMS = {THRESHOLD} (max over frames)",
            "paper_value": round(paper, 3), "measured": measured,
            "unit": "ratio (a lower bound)" if lower else "ratio (an upper bound)" if upper else "ratio",
            "criterion": "same side of 1 as the seed and within a factor 3 of its ratio; where hofem's ratio is only "
                         "a bound (a family not reaching the threshold), the bound must leave room for such a value",
            "agrees": bool(agrees), "size": "main-job",
            "note": f"{family}: {kind} {t:.4g} s per step; Hex20 FCM: {hkind} {h:.4g} s. {note}"}


def twisting_cylinder_rows(R):
    tc = R["studies"]["twisting-cylinder"]
    rows = [
        ratio_row(R, "table1.tet10_over_hex20", "Tet10 FEM", 560.0,
                  "The seed: 'FCM roughly 1.6 times faster than the Tet10 FEM'."),
        ratio_row(R, "table1.hex8_over_hex20", "Hex8 FCM", 2907.0, "The seed: 2,907 ms against 359 ms."),
        ratio_row(R, "table1.tet4_over_hex20", "Tet4 FEM", 56321.0, "The seed: 56,321 ms against 359 ms."),
    ]
    first = [r for r in tc["runs"] if r["ok"] and r["family"] in ("Tet4 FEM", "Hex8 FCM") and r["metric"] <= THRESHOLD]
    higher = [r for r in tc["runs"] if r["ok"] and r["family"] in ("Tet10 FEM", "Hex20 FCM") and r["metric"] <= THRESHOLD]
    best_first = min((r["time_per_step_median"] for r in first), default=math.inf)
    best_higher = min((r["time_per_step_median"] for r in higher), default=math.inf)
    rows.append({
        "id": "table1.higher_order_essential", "source": "Longva et al. 2020, §6.2, Table 1",
        "quantity": f"cheapest first-order run under surface RMS {THRESHOLD} / cheapest higher-order run",
        "paper_value": round(2907.0 / 359.0, 3), "measured": best_first / best_higher, "unit": "ratio",
        "criterion": ">= 2, or no first-order run under the threshold ('higher-order elements are essential')",
        "agrees": bool(best_first / best_higher >= 2), "size": "main-job",
        "note": f"first order: {best_first:.4g} s per step (inf: none under the threshold); higher order: "
                f"{best_higher:.4g} s. The seed's value is its best first-order (Hex8 FCM) over Hex20 FCM."})
    richardson = tc["reference"]["richardson"]["estimate"]["surface_rms"]
    rows.append({
        "id": "table1.reference_error", "source": "Longva et al. 2020, §6.2 (reference: 86k Tet10)",
        "quantity": "the reference's own surface RMS error (Richardson) / the threshold",
        "paper_value": None, "measured": richardson / THRESHOLD, "unit": "ratio",
        "criterion": "<= 0.1: the reference resolves the threshold (the seed reports no estimate)",
        "agrees": bool(richardson / THRESHOLD <= 0.1), "size": "main-job",
        "note": f"Tet20 reference, Richardson estimate {richardson:.3g} from its coarser level."})
    return rows


def simplification_rows(R):
    """§6.3: Hex20 FCM (4 x 4 x 6 cells) with and without quadrature simplification."""
    tc = R["studies"]["twisting-cylinder"]
    s = R["run_stats"]("twisting-cylinder", "hex20-4")
    u = R["run_stats"]("twisting-cylinder", "hex20-4-unsimplified")
    q = s["embedded"]["quadrature"]
    cut = s["embedded"]["cells"]["cut"]
    by_name = {r["name"]: r for r in tc["runs"]}
    fast, slow = by_name["hex20-4"], by_name["hex20-4-unsimplified"]
    m = q["stiffness_degree"]
    bound = math.comb(m + 3, 3)
    src = "Longva et al. 2020, §6.3"
    saved = slow["time_per_step_median"] - fast["time_per_step_median"]
    return [
        {"id": "s6.3.points_reduction", "source": src, "quantity": "cut cells' stiffness points before / after simplification",
         "paper_value": round(5857880 / 70560, 2), "measured": q["points_before"] / q["points_after"], "unit": "ratio",
         "criterion": ">= 20 (an order of magnitude; the factor grows with the embedded mesh's tets per cell)",
         "agrees": q["points_before"] / q["points_after"] >= 20, "size": "main-job",
         "note": f"{q['points_before']} -> {q['points_after']} points over {cut} cut cells (seed: 5,857,880 -> 70,560 "
                 f"over 2,016 cells)."},
        {"id": "s6.3.points_per_cut_cell", "source": src, "quantity": "stiffness points per cut cell after simplification",
         "paper_value": round(70560 / 2016, 2), "measured": q["points_after"] / cut, "unit": "points",
         "criterion": f"= C(m + 3, 3) for the stiffness degree m of each code (the LP's basic solution): the seed's m = 4 "
                      f"gives 35, hofem's m = {m} gives {bound}",
         "agrees": abs(q["points_after"] / cut - bound) < 1e-9, "size": "main-job",
         "note": "hofem integrates the cut Hex20 stiffness exactly (degree 6) where the seed uses degree 4 "
                 "(core/embedded/finite_cell_quadrature.hpp explains why): 84 points instead of 35."},
        {"id": "s6.3.step_speedup", "source": src, "quantity": "time per step without / with simplification",
         "paper_value": round(5691 / 359, 2), "measured": slow["time_per_step_median"] / fast["time_per_step_median"],
         "unit": "ratio", "criterion": ">= 5 (the seed: 15.8)",
         "agrees": slow["time_per_step_median"] / fast["time_per_step_median"] >= 5, "size": "main-job",
         "note": f"{slow['time_per_step_median']:.4g} s against {fast['time_per_step_median']:.4g} s per step, CHOLMOD both."},
        {"id": "s6.3.simplification_over_generation", "source": src,
         "quantity": "simplification seconds / quadrature generation seconds",
         "paper_value": round(5.23 / 0.255, 2), "measured": q["simplification_seconds"] / q["generation_seconds"],
         "unit": "ratio", "criterion": ">= 5 (the LPs dominate the set-up; the seed: 255 ms and 5.23 s)",
         "agrees": q["simplification_seconds"] / q["generation_seconds"] >= 5, "size": "main-job",
         "note": f"generation {q['generation_seconds']:.3g} s, simplification {q['simplification_seconds']:.3g} s."},
        {"id": "s6.3.pays_off", "source": src, "quantity": "steps after which the simplification has paid for itself",
         "paper_value": round(5.23 / ((5691 - 359) / 1000.0), 2), "measured": q["simplification_seconds"] / saved,
         "unit": "steps", "criterion": "<= 10 (within one of our runs; the seed: after the first step)",
         "agrees": q["simplification_seconds"] / saved <= 10, "size": "main-job",
         "note": f"{q['simplification_seconds']:.3g} s of LPs against {saved:.3g} s saved per step."},
        {"id": "s6.3.rms_unchanged", "source": src, "quantity": "|surface RMS with / without simplification - 1|",
         "paper_value": round(abs(0.0149 / 0.0153 - 1), 4), "measured": abs(fast["metric"] / slow["metric"] - 1),
         "unit": "relative", "criterion": "<= 0.05 (the seed: 0.0149 against 0.0153 m)",
         "agrees": abs(fast["metric"] / slow["metric"] - 1) <= 0.05, "size": "main-job",
         "note": f"{fast['metric']:.5g} against {slow['metric']:.5g} (max over frames)."},
    ]


def fig10_rows(R):
    v = R["verification"]
    g = "embedded.fig10"
    src = "Longva et al. 2020, §6.6, Fig. 10"
    out = []
    for cid, name, paper, criterion, ok in [
        ("fig10.fcm_hex8_rate", "FCM Hex8 L2 rate h=1/16 -> 1/32", 2, ">= 1.8 (optimal O(h^2))", lambda x: x >= 1.8),
        ("fig10.fcm_hex20_rate", "FCM Hex20 L2 rate h=1/16 -> 1/32", 3, ">= 2.7 (optimal O(h^3))", lambda x: x >= 2.7),
        ("fig10.staircase_hex8_rate", "staircase FEM Hex8 L2 rate h=1/16 -> 1/32", 1,
         "<= 1.5 ('dramatically reduced' by the voxel geometry)", lambda x: x <= 1.5),
        ("fig10.staircase_hex20_rate", "staircase FEM Hex20 L2 rate h=1/16 -> 1/32", 1,
         "<= 1.5 ('dramatically reduced' by the voxel geometry)", lambda x: x <= 1.5),
    ]:
        x = v[(g, name)]
        out.append({"id": cid, "source": src, "quantity": f"L2 convergence rate, {name.split(' L2')[0]}, h = 1/16 -> 1/32",
                    "paper_value": paper, "measured": x, "unit": "rate", "criterion": criterion, "agrees": bool(ok(x)),
                    "size": "main-job",
                    "note": "Verification rows of embedded.fig10 (a clamped half ball under load, linear elasticity; "
                            "the seed's slopes read from its figure)."})
    return out


def drop_integrator_rows(R):
    """Thesis §5.3.1, Figs. 10-11: the drop at one dt = 1e-3 for explicit,
    semi-implicit and implicit Euler (27 vertices, 48 tets here; the thesis: 20
    and 24), each against an RK4 run at dt = 1e-4; contact at t = sqrt(2 x 0.5 /
    9.81) = 0.32 s."""
    st = R["studies"]["drop-integrators"]
    runs = {r["name"]: r for r in st["runs"]}
    src = "thesis §5.3.1, Figs. 10-11"
    contact = math.sqrt(2 * 0.5 / 9.81)
    ex, semi, imp = runs["explicit-euler"], runs["semi-implicit"], runs["implicit-euler"]
    if ex["ok"]:
        dev = [f["surface_rms"] for f in ex["frames"] if f["t"] > contact]
        fails_at, grows = math.inf, all(b > a for a, b in zip(dev, dev[1:]))
    else:
        match = re.search(r"t = ([0-9.eE+-]+)", ex["message"])
        fails_at, grows = (float(match.group(1)) if match else math.nan), True
    ratio = semi["metric"] / imp["metric"]
    return [
        {"id": "thesis.drop.explicit_unstable_after_contact", "source": src,
         "quantity": "explicit Euler at dt = 1e-3: the time it fails by energy growth (inf: it does not)",
         "paper_value": "deviates after contact, ever more (instability)", "measured": fails_at, "unit": "s",
         "criterion": f"fails after the contact (t > {contact:.2f} s) or its deviation from the reference grows from "
                      "frame to frame after it; the implicit runs complete",
         "agrees": bool(fails_at > contact and grows and semi["ok"] and imp["ok"]), "size": "main-job",
         "note": ex["message"] if not ex["ok"] else "completed"},
        {"id": "thesis.drop.semi_implicit_follows_implicit", "source": src,
         "quantity": "semi-implicit's deviation from the reference / implicit Euler's (surface RMS, max over frames)",
         "paper_value": "consistent trend, acceptable error", "measured": ratio, "unit": "ratio",
         "criterion": "within [0.5, 2]", "agrees": bool(0.5 <= ratio <= 2), "size": "main-job",
         "note": f"semi-implicit {semi['metric']:.3g}, implicit {imp['metric']:.3g} m: both first order, both damp "
                 "the bounce at this dt."},
        {"id": "thesis.drop.explicit_faster_than_semi_implicit", "source": src,
         "quantity": "time per step, semi-implicit / explicit Euler", "paper_value": round(120 / 45, 3),
         "measured": semi["time_per_step_median"] / ex["time_per_step_median"], "unit": "ratio",
         "criterion": "> 1 (the thesis: 120 against 45 frames per second)",
         "agrees": bool(semi["time_per_step_median"] > ex["time_per_step_median"]), "size": "main-job",
         "note": f"{ex['time_per_step_median'] * 1e3:.3g} ms against {semi['time_per_step_median'] * 1e3:.3g} ms."},
        {"id": "thesis.drop.semi_implicit_faster_than_implicit", "source": src,
         "quantity": "time per step, implicit / semi-implicit Euler", "paper_value": round(45 / 5, 3),
         "measured": imp["time_per_step_median"] / semi["time_per_step_median"], "unit": "ratio",
         "criterion": "> 1 (the thesis: 45 against 5 frames per second)",
         "agrees": bool(imp["time_per_step_median"] > semi["time_per_step_median"]), "size": "main-job",
         "note": f"{semi['time_per_step_median'] * 1e3:.3g} ms against {imp['time_per_step_median'] * 1e3:.3g} ms. "
                 "hofem's semi-implicit step projects every quadrature point's stress derivative to positive "
                 "semi-definite (a 9 x 9 eigendecomposition, ~25 % of its profile) where implicit Euler's Newton "
                 "(1.7 iterations per step here) does not, and on 48 tets OpenMP's barriers dominate both."},
    ]


def within(measured, low, high, factor):
    """The seed's interval [low, high] widened by `factor` both ways."""
    return low / factor <= measured <= high * factor


def hollow_ball_rows(R):
    """Longva et al. 2020 §6.4, Fig. 8: the hollow ball compressed and twisted
    (scripts/studies/hollow-ball.json: radius 1 m, 1 s of the built-in scene's
    3 s, a Tet10 reference at mesh size 0.12)."""
    st = R["studies"]["hollow-ball"]
    runs = {r["name"]: r for r in st["runs"]}
    fcm, fem, t4lo, t4hi = runs["tet10-fcm-6"], runs["tet10-fem-h030"], runs["tet4-h020"], runs["tet4-h010"]
    src = "Longva et al. 2020, §6.4, Fig. 8"
    why = ("The seed's FCM background is a coarse conforming mesh of a cage around the ball (its Tet10 FEM ran on that "
           "cage, a coarser geometry); ours is a 6 x 6 x 6 box grid (cells 0.425 m across a 0.3 m shell), so the "
           "'FEM on the same background' is a conforming Tet10 mesh of the true ball at mesh size 0.3 with about twice "
           "the FCM's unknowns. The FCM's geometry is the reference mesh's straight-sided tets (its measurement floor, "
           f"{fcm['floor']['surface_rms']:.3g} m, is {fcm['floor']['surface_rms'] / fcm['metric']:.0%} of its error); "
           "a finer 8^3 box grid moves the clamped planes off z = -0.85 and 0.85 and solves another problem.")
    return [
        {"id": "ball.fem_over_fcm_error", "source": src,
         "quantity": "max surface RMS over frames, Tet10 FEM (coarse) / Tet10 FCM", "paper_value": round(0.047 / 0.018, 3),
         "measured": fem["metric"] / fcm["metric"], "unit": "ratio",
         "criterion": "> 1: the FCM is the more accurate of the two (the seed: 0.047 against 0.018 m)",
         "agrees": fem["metric"] > fcm["metric"], "size": "main-job",
         "note": f"FEM {fem['metric']:.3g} m ({fem['unknowns']} unknowns), FCM {fcm['metric']:.3g} m "
                 f"({fcm['unknowns']} unknowns). " + why},
        {"id": "ball.tet4_fine_over_fcm_error", "source": src,
         "quantity": "max surface RMS over frames, fine Tet4 FEM / Tet10 FCM",
         "paper_value": "> 1 ('Tet4 is not able to capture the complex deformation')",
         "measured": t4hi["metric"] / fcm["metric"], "unit": "ratio",
         "criterion": "> 1: the FCM beats the fine Tet4 mesh",
         "agrees": t4hi["metric"] > fcm["metric"], "size": "main-job",
         "note": f"Tet4 at mesh size 0.2 {t4lo['metric']:.3g} m, at 0.1 {t4hi['metric']:.3g} m ({t4hi['unknowns']} "
                 f"unknowns); FCM {fcm['metric']:.3g} m. " + why},
        {"id": "ball.fcm_over_fem_time", "source": src,
         "quantity": "time per step, Tet10 FCM / Tet10 FEM (coarse)", "paper_value": round(739 / 607, 3),
         "measured": fcm["time_per_step_median"] / fem["time_per_step_median"], "unit": "ratio",
         "criterion": "within a factor 2 of the seed's ratio (739 against 607 ms: 'a modest overhead')",
         "agrees": within(fcm["time_per_step_median"] / fem["time_per_step_median"], 739 / 607, 739 / 607, 2),
         "size": "main-job",
         "note": f"{fcm['time_per_step_median'] * 1e3:.3g} ms against {fem['time_per_step_median'] * 1e3:.3g} ms; "
                 f"fine Tet4 {t4hi['time_per_step_median'] * 1e3:.3g} ms (the seed: 519 ms). Our coarse FEM has about "
                 "twice the FCM's unknowns, the seed's the same mesh."},
    ]


def slingshot_rows(R):
    """Longva et al. 2020 §6.5: Tet10 FEM (CG + Jacobi) against Tet10 FCM (CG +
    Additive Schwarz on cut cells under volume fraction 0.5, Jacobi elsewhere)
    at equal background resolution (scripts/studies/slingshot.json: a 3 x 0.3 x
    0.3 m bar, E = 1e5, nu = 0.4, pulled sideways at its middle for 1 s and
    released; the seed: an armadillo, E = 5e5, nu = 0.4)."""
    st = R["studies"]["slingshot"]
    runs = {r["name"]: r for r in st["runs"]}
    src = "Longva et al. 2020, §6.5"
    # FEM and FCM runs in pairs at equal resolution (fem-N, fcm-N): the coarser
    # pair set beside the seed's 5k-element meshes, the finer beside its 35k.
    sizes = sorted((n[4:] for n in runs if n.startswith("fem-") and "fcm-" + n[4:] in runs), key=int)
    if len(sizes) < 2:
        raise KeyError(f"slingshot: needs FEM and FCM runs at two resolutions, has {sizes}")
    seed = {sizes[0]: (230 / 184, 147 / 102), sizes[-1]: (1683 / 1465, 293 / 231)}
    rows = []
    for n, label in ((sizes[0], "coarse (5k elements in the seed)"), (sizes[-1], "fine (35k in the seed)")):
        fem, fcm = runs[f"fem-{n}"], runs[f"fcm-{n}"]
        stats = {k: R["run_stats"]("slingshot", k) for k in (f"fem-{n}", f"fcm-{n}")}
        cg = [stats[k]["built"]["linear_iterations"] / max(stats[k]["steps_done"], 1) for k in (f"fem-{n}", f"fcm-{n}")]
        t = fcm["time_per_step_median"] / fem["time_per_step_median"]
        pts = fcm["quadrature_points"] / fem["quadrature_points"]
        rows.append({
            "id": f"slingshot.time_fcm_over_fem.{'coarse' if n == sizes[0] else 'fine'}", "source": src,
            "quantity": f"time per step, Tet10 FCM / Tet10 FEM, {label}", "paper_value": [1.15, 1.25],
            "measured": t, "unit": "ratio",
            "criterion": "within a factor 2 of the seed's range 1.15-1.25",
            "agrees": within(t, 1.15, 1.25, 2), "size": "main-job",
            "note": f"{fcm['time_per_step_median'] * 1e3:.3g} ms against {fem['time_per_step_median'] * 1e3:.3g} ms at "
                    f"{fem['unknowns']} unknowns each; the seed {seed[n][0]:.2f}. The FCM assembles {pts:.2f}x the "
                    "points: every background cell of a bar 2-3 cells across is cut (a cut Tet10 carries 35 "
                    "simplified points, the stabilisation folded in, against 14), where the armadillo's interior "
                    "cells are uncut."})
        rows.append({
            "id": f"slingshot.cg_fcm_over_fem.{'coarse' if n == sizes[0] else 'fine'}", "source": src,
            "quantity": f"CG iterations per step, Tet10 FCM / Tet10 FEM, {label}", "paper_value": [1.27, 1.44],
            "measured": cg[1] / cg[0], "unit": "ratio",
            "criterion": "within a factor 2 of the seed's range 1.27-1.44 (the preconditioner keeps the cut cells "
                         "from blowing the count up)",
            "agrees": within(cg[1] / cg[0], 1.27, 1.44, 2), "size": "main-job",
            "note": f"{cg[1]:.1f} against {cg[0]:.1f} iterations per step; the seed {seed[n][1]:.2f}."})
    return rows


def compression_rows(R):
    """Thesis §5.2, Fig. 9: the cantilever (2 x 0.5 x 0.5 m, E = 1e5, nu = 0.3,
    clamped at x = 0) bending under its own weight for 3 s: the root's lower
    side is compressed hardest. Verdicts from the scenes' min det F over every
    step's quadrature points and the count of elements with det F <= 0."""
    src = "thesis §5.2, Fig. 9"
    d = {m: R["scene_stats"](f"cantilever-{m}")["deformation"] for m in ("stvk", "corotated", "neohookean")}
    note = lambda m: (f"{m}: min det F {d[m]['min_det_F']:.3g} at t = {d[m]['t_of_min_det_F']:.3g} s, up to "
                      f"{d[m]['max_inverted_elements']} inverted elements, in {d[m]['steps_with_inverted_elements']} steps.")
    return [
        {"id": "thesis.fig9.stvk_inverts", "source": src, "quantity": "StVK: min det F over the run",
         "paper_value": "inverts ('local entanglement and inversion near the connection')",
         "measured": d["stvk"]["min_det_F"], "unit": "det F", "criterion": "<= 0",
         "agrees": d["stvk"]["min_det_F"] <= 0, "size": "main-job", "note": note("stvk")},
        {"id": "thesis.fig9.corotated_folds_slightly", "source": src,
         "quantity": "corotated: most elements inverted at once, against StVK's",
         "paper_value": "folds slightly", "measured": d["corotated"]["max_inverted_elements"], "unit": "elements",
         "criterion": "more than 0 and fewer than StVK's",
         "agrees": 0 < d["corotated"]["max_inverted_elements"] < d["stvk"]["max_inverted_elements"],
         "size": "main-job", "note": note("corotated") + " " + note("stvk")},
        {"id": "thesis.fig9.neohookean_resists", "source": src, "quantity": "Neo-Hookean: min det F over the run",
         "paper_value": "neither inverts nor folds (the log J term)", "measured": d["neohookean"]["min_det_F"],
         "unit": "det F", "criterion": "> 0 and no inverted element in any step",
         "agrees": d["neohookean"]["min_det_F"] > 0 and d["neohookean"]["max_inverted_elements"] == 0,
         "size": "main-job", "note": note("neohookean")},
    ]


def krylov_rows(R):
    """Thesis §5.3.2, Figs. 12-13: a fixed number of Krylov iterations per
    solve (solver.krylov_iterations) in the semi-implicit drop (a 0.5 m cube of
    6 x 6 x 6 x 6 Tet4, 343 vertices; the thesis: an armadillo, 616 vertices),
    trajectory error (surface RMS, max over frames) against the same scene
    solved by CHOLMOD (scripts/studies/drop-krylov.json)."""
    st = R["studies"]["drop-krylov"]
    runs = {r["name"]: r for r in st["runs"]}
    e = lambda n: runs[n]["metric"]
    src12, src13 = "thesis §5.3.2, Fig. 12", "thesis §5.3.2, Fig. 13"
    threshold = 1e-3
    cheapest = min((r for r in st["runs"] if r["ok"] and r["metric"] <= threshold),
                   key=lambda r: r["time_per_step_median"], default=None)
    return [
        {"id": "thesis.fig12.pcr3_like_cg12", "source": src12,
         "quantity": "trajectory error, 3 iterations of Jacobi-preconditioned CR / 12 of plain CG",
         "paper_value": "about 1 ('the error of PCR after 3 iterations is basically the same as CG after 12')",
         "measured": e("cr-jacobi-3") / e("cg-none-12"), "unit": "ratio", "criterion": "within [0.5, 2]",
         "agrees": 0.5 <= e("cr-jacobi-3") / e("cg-none-12") <= 2, "size": "main-job",
         "note": f"CR + Jacobi x3 {e('cr-jacobi-3'):.3g} m, CG x12 {e('cg-none-12'):.3g} m, CG x3 {e('cg-none-3'):.3g} m, "
                 f"CG + Jacobi x3 {e('cg-jacobi-3'):.3g} m. Our systems are SPD (the semi-implicit step projects each "
                 "point's stress derivative), where CG is optimal in the energy norm; the thesis' were not projected."},
        {"id": "thesis.fig12.cg3_differs_from_cg12", "source": src12,
         "quantity": "trajectory error, 3 / 12 iterations of plain CG",
         "paper_value": "very different deformations", "measured": e("cg-none-3") / e("cg-none-12"), "unit": "ratio",
         "criterion": ">= 3", "agrees": e("cg-none-3") / e("cg-none-12") >= 3, "size": "main-job",
         "note": f"{e('cg-none-3'):.3g} against {e('cg-none-12'):.3g} m."},
        {"id": "thesis.fig13.jacobi_beats_none", "source": src13,
         "quantity": "trajectory error after 12 CG iterations, Jacobi / no preconditioner",
         "paper_value": "< 1 (preconditioning reduces the error faster)", "measured": e("cg-jacobi-12") / e("cg-none-12"),
         "unit": "ratio", "criterion": "< 1", "agrees": e("cg-jacobi-12") < e("cg-none-12"), "size": "main-job",
         "note": f"{e('cg-jacobi-12'):.3g} against {e('cg-none-12'):.3g} m."},
        {"id": "thesis.fig13.multigrid_beats_jacobi_per_iteration", "source": src13,
         "quantity": "trajectory error after 3 CG iterations, multigrid (BoomerAMG) / Jacobi",
         "paper_value": "< 1 ('the multigrid preconditioner will be better than Jacobi')",
         "measured": e("cg-amg-3") / e("cg-jacobi-3"), "unit": "ratio", "criterion": "< 1",
         "agrees": e("cg-amg-3") < e("cg-jacobi-3"), "size": "main-job",
         "note": f"{e('cg-amg-3'):.3g} against {e('cg-jacobi-3'):.3g} m. The thesis' multigrid is geometric; "
                 "Tet4 has no coarser order for hofem's p-multigrid, so algebraic multigrid stands in."},
        {"id": "thesis.fig13.cr_beats_cg", "source": src13,
         "quantity": "trajectory error after 12 Jacobi-preconditioned iterations, CR / CG",
         "paper_value": "< 1 ('the conjugate residual is generally better')",
         "measured": e("cr-jacobi-12") / e("cg-jacobi-12"), "unit": "ratio", "criterion": "< 1",
         "agrees": e("cr-jacobi-12") < e("cg-jacobi-12"), "size": "main-job",
         "note": f"{e('cr-jacobi-12'):.3g} against {e('cg-jacobi-12'):.3g} m. The thesis credits CR with handling "
                 "indefinite Hessians; ours are projected to SPD, and there CG minimises the energy norm of the error."},
        {"id": "thesis.fig13.jacobi_best_in_time", "source": src13,
         "quantity": f"preconditioner of the cheapest run (time per step) under trajectory error {threshold:g} m",
         "paper_value": "jacobi", "measured": cheapest["family"] if cheapest else None, "unit": "solver",
         "criterion": "a Jacobi-preconditioned run is the cheapest under the threshold",
         "agrees": bool(cheapest) and cheapest["family"].endswith("+jacobi"), "size": "main-job",
         "note": (f"{cheapest['name']}: {cheapest['time_per_step_median'] * 1e3:.3g} ms per step, error "
                  f"{cheapest['metric']:.3g} m; AMG x3 {runs['cg-amg-3']['time_per_step_median'] * 1e3:.3g} ms, error "
                  f"{e('cg-amg-3'):.3g} m. Assembly dominates a step at 1,029 unknowns, so iterations cost little."
                  if cheapest else "no run under the threshold")},
    ]


def order_rows(R):
    """Thesis §5.4, Fig. 14: P1 against P2 in the semi-implicit drop, CG +
    Jacobi to convergence, trajectory error against a P2 reference on a 6^3
    mesh (scripts/studies/drop-orders.json)."""
    st = R["studies"]["drop-orders"]
    runs = {r["name"]: r for r in st["runs"]}
    p1, p2 = runs["p1-4"], runs["p2-4"]
    src = "thesis §5.4, Fig. 14"
    return [
        {"id": "thesis.fig14.p2_more_accurate", "source": src,
         "quantity": "trajectory error on the same 4^3 mesh, P1 / P2", "paper_value": "> 1 (P2 more accurate)",
         "measured": p1["metric"] / p2["metric"], "unit": "ratio", "criterion": "> 1",
         "agrees": p1["metric"] > p2["metric"], "size": "main-job",
         "note": f"P1 {p1['metric']:.3g} m ({p1['unknowns']} unknowns), P2 {p2['metric']:.3g} m ({p2['unknowns']}); "
                 f"at equal unknowns (375) P1 {runs['p1-4']['metric']:.3g} m, P2 on 2^3 {runs['p2-2']['metric']:.3g} m."},
        {"id": "thesis.fig14.p2_costlier_per_step", "source": src,
         "quantity": "time per step on the same 4^3 mesh, P2 / P1", "paper_value": "> 1 ('the cost becomes very huge')",
         "measured": p2["time_per_step_median"] / p1["time_per_step_median"], "unit": "ratio", "criterion": "> 1",
         "agrees": p2["time_per_step_median"] > p1["time_per_step_median"], "size": "main-job",
         "note": f"{p2['time_per_step_median'] * 1e3:.3g} ms against {p1['time_per_step_median'] * 1e3:.3g} ms; at equal "
                 f"unknowns P2 {runs['p2-2']['time_per_step_median'] * 1e3:.3g} ms, P1 "
                 f"{runs['p1-4']['time_per_step_median'] * 1e3:.3g} ms."},
    ]


def markdown(rows, skipped=()):
    lines = ["# The seeds' numbers beside hofem's", "",
             "Written by `scripts/paper_claims.py` from the reports (the size of each row's study is in "
             "paper_claims.json); the criterion of each row was written "
             "before the measurement it judges. " + f"{sum(r['agrees'] for r in rows)} of {len(rows)} rows agree.", "",
             "| id | source | quantity | paper | hofem | criterion | agrees | note |", "|---|---|---|---:|---:|---|---|---|"]
    for r in rows:
        fmt = lambda x: "—" if x is None else (f"{x:.4g}" if isinstance(x, float) else str(x))
        lines.append(f"| {r['id']} | {r['source']} | {r['quantity']} | {fmt(r['paper_value'])} | {fmt(r['measured'])} "
                     f"| {r['criterion']} | {'yes' if r['agrees'] else '**no**'} | {r['note']} |")
    if skipped:
        lines += ["", "Not run at this size (scripts/studies-full NAME runs one):", ""] + [f"- {s}" for s in skipped]
    return "\n".join(lines) + "\n"


# Row groups: (the study each reads, or None for the verification and scenes, the builder).
GROUPS = [("twisting-cylinder", twisting_cylinder_rows), ("twisting-cylinder", simplification_rows),
          ("hollow-ball", hollow_ball_rows), ("slingshot", slingshot_rows), (None, fig10_rows),
          (None, compression_rows), ("drop-integrators", drop_integrator_rows), ("drop-krylov", krylov_rows),
          ("drop-orders", order_rows)]


def build_rows(R, full):
    """Every group's rows; at full size only the studies' groups, each skipped
    (and named) when its study or one of its runs is absent."""
    rows, skipped = [], []
    for study, group in GROUPS:
        if not full:
            rows += group(R)
            continue
        if study is None:
            continue
        try:
            built = group(R)
        except (OSError, KeyError) as e:
            skipped.append(f"{group.__name__} ({study}): {type(e).__name__}: {e}")
            continue
        for r in built:
            r["size"] = "full"
        rows += built
    return rows, skipped


def main(argv):
    full = "--full" in argv
    reports = argv[1] if len(argv) > 1 and not argv[1].startswith("--") else "reports"
    out = argv[argv.index("--out") + 1] if "--out" in argv else os.path.join(reports, "full") if full else reports
    try:
        R = load(reports, os.path.join("full", "studies") if full else "studies")
        rows, skipped = build_rows(R, full)
        if not rows:
            raise KeyError("no full-size study has been run (scripts/studies-full): " + "; ".join(skipped))
    except (OSError, KeyError) as e:
        print(f"paper_claims: cannot build the table from {reports}: {type(e).__name__}: {e}", file=sys.stderr)
        return 1
    for r in rows:
        r["agrees"] = bool(r["agrees"])
        if isinstance(r["measured"], float) and not math.isfinite(r["measured"]):
            r["note"] = f"measured {r['measured']}; " + r["note"]
            r["measured"] = None  # JSON has no infinity
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "paper_claims.json"), "w") as f:
        json.dump({"rows": rows, "skipped": skipped}, f, indent=1)
        f.write("\n")
    with open(os.path.join(out, "paper_claims.md"), "w") as f:
        f.write(markdown(rows, skipped))
    print(f"paper_claims: {sum(r['agrees'] for r in rows)} of {len(rows)} rows agree -> {out}/paper_claims.md")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
