"""The claims rows of the thesis on a high-order FEM simulator: §5.2 Fig. 9 (the
cantilever's inversion), §5.3.1 Figs. 10-11 (the drop's integrators), §5.3.2
Figs. 12-13 (fixed Krylov budgets and preconditioners) and §5.4 Fig. 14 (P1
against P2). Each function takes the loaded reports (paper_claims.load) and
returns rows; paper_claims.py says what a row holds."""
import math
import re

from claims_check import check
from claims_size import THESIS_ARMADILLO_UNKNOWNS, THESIS_DROP_UNKNOWNS, THESIS_HESSIAN_ROWS, part, size, timing

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
    sz = size(part("Tet4", imp["unknowns"], THESIS_DROP_UNKNOWNS))
    # The row's value: the failure time when the deviation grows after contact
    # and both implicit runs complete; else NaN (judged "no").
    onset = fails_at if (grows and semi["ok"] and imp["ok"]) else math.nan
    return [
        {"id": "thesis.drop.explicit_unstable_after_contact", "source": src,
         "quantity": "explicit Euler at dt = 1e-3: the time it fails by energy growth (inf: it does not)",
         "paper_value": "deviates after contact, ever more (instability)", "measured": onset, "unit": "s",
         "criterion": f"fails after the contact (t > {contact:.2f} s) or its deviation from the reference grows from "
                      "frame to frame after it; the implicit runs complete",
         "check": check(low=contact, low_open=True), "size": sz,
         "note": ex["message"] if not ex["ok"] else "completed"},
        {"id": "thesis.drop.semi_implicit_follows_implicit", "source": src,
         "quantity": "semi-implicit's deviation from the reference / implicit Euler's (surface RMS, max over frames)",
         "paper_value": "consistent trend, acceptable error", "measured": ratio, "unit": "ratio",
         "criterion": "within [0.5, 2]", "check": check(0.5, 2.0), "size": sz,
         "note": f"semi-implicit {semi['metric']:.3g}, implicit {imp['metric']:.3g} m: both first order, both damp "
                 "the bounce at this dt."},
        {"id": "thesis.drop.explicit_faster_than_semi_implicit", "source": src,
         "quantity": "time per step, semi-implicit / explicit Euler", "paper_value": round(120 / 45, 3),
         "measured": semi["time_per_step_median"] / ex["time_per_step_median"], "unit": "ratio",
         "criterion": "> 1 (the thesis: 120 against 45 frames per second)",
         "check": check(low=1.0, low_open=True), "size": sz, "timings": [timing(semi), timing(ex)],
         "note": f"{ex['time_per_step_median'] * 1e3:.3g} ms against {semi['time_per_step_median'] * 1e3:.3g} ms."},
        {"id": "thesis.drop.semi_implicit_faster_than_implicit", "source": src,
         "quantity": "time per step, implicit / semi-implicit Euler", "paper_value": round(45 / 5, 3),
         "measured": imp["time_per_step_median"] / semi["time_per_step_median"], "unit": "ratio",
         "criterion": "> 1 (the thesis: 45 against 5 frames per second)",
         "check": check(low=1.0, low_open=True), "size": sz, "timings": [timing(imp), timing(semi)],
         "note": f"{semi['time_per_step_median'] * 1e3:.3g} ms against {imp['time_per_step_median'] * 1e3:.3g} ms. "
                 "hofem's semi-implicit step projects every quadrature point's stress derivative to positive "
                 "semi-definite (a 9 x 9 eigendecomposition, ~25 % of its profile) where implicit Euler's Newton "
                 "(1.7 iterations per step here) does not, and on 48 tets OpenMP's barriers dominate both."},
    ]


def compression_rows(R):
    """Thesis §5.2, Fig. 9: the cantilever (2 x 0.5 x 0.5 m, E = 1e5, nu = 0.3,
    clamped at x = 0) bending under its own weight for 3 s: the root's lower
    side is compressed hardest. Verdicts from the scenes' min det F over every
    step's quadrature points and the count of elements with det F <= 0. The
    thesis' third claim, "Neo-Hookean neither inverts nor folds", has no row:
    hofem's Neo-Hookean energy is +inf at J <= 0, so Newton's line search can
    never accept an inverted state and the row could not fail."""
    src = "thesis §5.2, Fig. 9"
    d = {m: R["scene_stats"](f"cantilever-{m}")["deformation"] for m in ("stvk", "corotated", "neohookean")}
    note = lambda m: (f"{m}: min det F {d[m]['min_det_F']:.3g} at t = {d[m]['t_of_min_det_F']:.3g} s, up to "
                      f"{d[m]['max_inverted_elements']} inverted elements, in {d[m]['steps_with_inverted_elements']} steps.")
    return [
        {"id": "thesis.fig9.stvk_inverts", "source": src, "quantity": "StVK: min det F over the run",
         "paper_value": "inverts ('local entanglement and inversion near the connection')",
         "measured": d["stvk"]["min_det_F"], "unit": "det F", "criterion": "<= 0",
         "check": check(high=0.0), "size": size(), "note": note("stvk")},
        {"id": "thesis.fig9.corotated_folds_slightly", "source": src,
         "quantity": "corotated: most elements inverted at once, against StVK's",
         "paper_value": "folds slightly",
         "measured": d["corotated"]["max_inverted_elements"] / max(d["stvk"]["max_inverted_elements"], 1e-300),
         "unit": "ratio of inverted elements, corotated / StVK",
         "criterion": "in (0, 1): some inverted, fewer than StVK's",
         "check": check(0.0, 1.0, low_open=True, high_open=True),
         "size": size(), "note": note("corotated") + " " + note("stvk")},
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
    sz = size(part("Tet4", st["runs"][0]["unknowns"], THESIS_ARMADILLO_UNKNOWNS))
    src12, src13 = "thesis §5.3.2, Fig. 12", "thesis §5.3.2, Fig. 13"
    threshold = 1e-3
    under = [r for r in st["runs"] if r["ok"] and r["metric"] <= threshold]
    cheapest = min(under, key=lambda r: r["time_per_step_median"], default=None)
    # The cheapest Jacobi run against the cheapest other one, both under the
    # threshold: Jacobi must win by 10 %, more than the ~5 % scatter of a median
    # of repeats on this machine, so that timing noise cannot decide the row.
    best = lambda pick: min((r["time_per_step_median"] for r in under if pick(r)), default=math.inf)
    jacobi, other = best(lambda r: r["family"].endswith("+jacobi")), best(lambda r: not r["family"].endswith("+jacobi"))
    margin = other / jacobi if math.isfinite(jacobi) else math.nan

    def error_ratio(cid, src, quantity, paper_value, a, b, low, high, note=""):
        """A row judging the trajectory-error ratio of runs a / b against [low, high]."""
        m = e(a) / e(b)
        criterion = (f"within [{low:g}, {high:g}]" if low > 0 and high < math.inf else
                     f">= {low:g}" if low > 0 else f"< {high:g}")
        return {"id": cid, "source": src, "quantity": f"trajectory error, {quantity}", "paper_value": paper_value,
                "measured": m, "unit": "ratio", "criterion": criterion,
                "check": check(low if low > 0 else None, high if high < math.inf else None, high_open=True),
                "size": sz,
                "note": f"{a} {e(a):.3g} m against {b} {e(b):.3g} m. {note}".strip()}

    spd = ("Our systems are SPD (the semi-implicit step projects each point's stress derivative), and there CG "
           "minimises the energy norm of the error; the thesis credits CR with handling indefinite Hessians.")
    return [
        error_ratio("thesis.fig12.pcr3_like_cg12", src12, "3 iterations of Jacobi-preconditioned CR / 12 of plain CG",
                    "about 1 ('the error of PCR after 3 iterations is basically the same as CG after 12')",
                    "cr-jacobi-3", "cg-none-12", 0.5, 2.0,
                    f"CG x3 {e('cg-none-3'):.3g} m, CG + Jacobi x3 {e('cg-jacobi-3'):.3g} m. " + spd),
        error_ratio("thesis.fig12.cg3_differs_from_cg12", src12, "3 / 12 iterations of plain CG",
                    "very different deformations", "cg-none-3", "cg-none-12", 3.0, math.inf),
        error_ratio("thesis.fig13.jacobi_beats_none", src13, "12 CG iterations, Jacobi / no preconditioner",
                    "< 1 (preconditioning reduces the error faster)", "cg-jacobi-12", "cg-none-12", 0.0, 1.0),
        error_ratio("thesis.fig13.multigrid_beats_jacobi_per_iteration", src13,
                    "3 CG iterations, multigrid (BoomerAMG) / Jacobi",
                    "< 1 ('the multigrid preconditioner will be better than Jacobi')", "cg-amg-3", "cg-jacobi-3",
                    0.0, 1.0, "The thesis' multigrid is geometric; Tet4 has no coarser order for hofem's p-multigrid, "
                              "so algebraic multigrid stands in."),
        error_ratio("thesis.fig13.cr_beats_cg", src13, "12 Jacobi-preconditioned iterations, CR / CG",
                    "< 1 ('the conjugate residual is generally better')", "cr-jacobi-12", "cg-jacobi-12", 0.0, 1.0,
                    spd),
        {"id": "thesis.fig13.jacobi_best_in_time", "source": src13,
         "quantity": f"time per step under trajectory error {threshold:g} m, cheapest other run / cheapest Jacobi run",
         "paper_value": "> 1 (Jacobi is the cheapest)", "measured": margin, "unit": "ratio",
         "criterion": ">= 1.1: Jacobi wins by more than the timing scatter",
         "check": check(low=1.1), "size": sz,
         "timings": [timing(r) for r in under if r["time_per_step_median"] in (jacobi, other)],
         "note": (f"{cheapest['name']}: {cheapest['time_per_step_median'] * 1e3:.3g} ms per step, error "
                  f"{cheapest['metric']:.3g} m; AMG x3 {runs['cg-amg-3']['time_per_step_median'] * 1e3:.3g} ms, error "
                  f"{e('cg-amg-3'):.3g} m. Assembly dominates a step at 1,029 unknowns, so iterations cost little."
                  if cheapest else "no run under the threshold")},
    ]


def krylov_implicit_rows(R):
    """Thesis §5.3.2, Figs. 12-13 as the thesis ran them: implicit Euler, Newton
    on the Hessian as assembled (not PSD-projected), each linear solve a fixed
    budget of CG, CR or MINRES iterations (scripts/studies/full/drop-krylov-
    implicit.json: a soft 0.5 m cube, E = 1e4, dt = 0.03, 6^3 x 6 Tet4, against
    UMFPACK, which takes indefinite matrices). The thesis credits CR with
    handling the indefinite Hessian, so the first row measures that the Hessian
    is indefinite in this scene: the share of Newton iterations whose direction
    from the assembled Hessian did not descend and was replaced by the projected
    one, in the reference. The semi-implicit rows above (krylov_rows) are the
    PSD-projected variant."""
    st = R["studies"]["drop-krylov-implicit"]
    runs = {r["name"]: r for r in st["runs"]}
    ref = st["reference"]
    src12, src13 = "thesis §5.3.2, Fig. 12", "thesis §5.3.2, Fig. 13"
    sz = size(part("Tet4", ref["unknowns"], THESIS_ARMADILLO_UNKNOWNS))
    e = lambda n: runs[n]["metric"] if runs[n]["ok"] else math.inf
    share = ref["projected_directions"] / max(ref["newton_iterations"], 1)

    def ratio(cid, src, quantity, paper_value, a, b, note, high=1.0,
              criterion="< 1: the first is the more accurate"):
        """Trajectory error of a / b (a failed run: inf), judged < high."""
        m = e(a) / e(b)
        return {"id": cid, "source": src, "quantity": f"trajectory error, {quantity}", "paper_value": paper_value,
                "measured": m, "unit": "ratio", "criterion": criterion,
                "check": check(high=high, high_open=True), "size": sz,
                "note": (f"{a}: {e(a):.3g} m, {runs[a]['newton_iterations']} Newton iterations, "
                         f"{runs[a]['projected_directions']} projected; {b}: {e(b):.3g} m, "
                         f"{runs[b]['newton_iterations']} Newton, {runs[b]['projected_directions']} projected. {note}")}

    return [
        # At least 1 % of the Newton iterations: more than a single event, so
        # the comparison below is made where indefiniteness holds.
        {"id": "thesis.s5.3.2.hessian_indefinite", "source": src13,
         "quantity": "Newton iterations whose assembled (unprojected) Hessian gave no descent direction / all, "
                     "in the UMFPACK reference",
         "paper_value": "'the non-convexity of the linear system' (a non-positive-definite Hessian)",
         "measured": share, "unit": "ratio", "criterion": ">= 0.01: the Hessian is indefinite in this scene",
         "check": check(low=0.01), "size": sz,
         "note": f"{ref['projected_directions']} of {ref['newton_iterations']} Newton iterations over "
                 f"{ref['steps']} steps; at E = 1e5 and dt = 0.01 (the drop-krylov scene) it is 0 of 281."},
        ratio("thesis.fig13.implicit.cr_beats_cg", src13, "12 unpreconditioned iterations on the unprojected "
              "Hessian, CR / CG", "< 1 (CR 'is generally better than the conjugate gradient in dealing with the "
              "non-positive definite Hessian')", "cr-none-12", "cg-none-12",
              "Newton converges either way; CG's inexact directions lead it to another equilibrium path after contact."),
        ratio("thesis.fig13.implicit.minres_beats_cg", src13, "12 unpreconditioned iterations, MINRES / CG",
              "< 1 (as CR: MINRES minimises the same residual norm)", "minres-none-12", "cg-none-12",
              "CR and MINRES give the same iterates in exact arithmetic for symmetric A and an SPD preconditioner."),
        ratio("thesis.fig12.implicit.pcr3_beats_cg12", src12, "3 iterations of Jacobi-preconditioned CR / 12 of "
              "plain CG", "about 1 or less ('the error of PCR after 3 iterations is basically the same as CG after "
              "12')", "cr-jacobi-3", "cg-none-12",
              f"3 of plain CG: {'completed' if runs['cg-none-3']['ok'] else 'failed: ' + runs['cg-none-3']['message']}.",
              # "Basically the same" read as: not more than twice the error (the
              # semi-implicit row's upper bound); less is better than claimed.
              high=2.0, criterion="< 2: PCR x3 at least about as accurate as CG x12"),
    ]


def order_rows(R):
    """Thesis §5.4, Fig. 14: P1 against P2 in the semi-implicit drop, CG +
    Jacobi to convergence, trajectory error against a P2 reference on a 6^3
    mesh (scripts/studies/drop-orders.json)."""
    st = R["studies"]["drop-orders"]
    runs = {r["name"]: r for r in st["runs"]}
    p1, p2 = runs["p1-4"], runs["p2-4"]
    src = "thesis §5.4, Fig. 14"
    sz = size(part("P1", p1["unknowns"], THESIS_HESSIAN_ROWS[0]), part("P2", p2["unknowns"], THESIS_HESSIAN_ROWS[1]))
    # §5.4 builds the P2 mesh from the P1 mesh by sharing edge nodes, so the
    # Hessian grows by 1 + E / V (edges over vertices of the P1 mesh): the
    # thesis' armadillo 5,310 -> 14,172 rows (E / V = 1.67, a coarse surface-
    # dominated mesh). hofem's drop mesh is a box of n^3 cubes, each split into
    # 6 tets about a body diagonal: V = (n + 1)^3 and V + E = (2n + 1)^3 (the
    # grid at half spacing), counted here from the mesh's definition, not by
    # hofem; nodes duplicated per element or a missed edge would move the ratio.
    box = lambda r: re.findall(r"mesh\.box\.cells=\[\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*\]", " ".join(r["overrides"]))
    cells = box(p2)
    if len(cells) != 1 or len(set(cells[0])) != 1 or box(p1) != cells:
        raise KeyError(f"drop-orders: p1-4 and p2-4 must share one cubic box mesh, have {p1['overrides']} / {p2['overrides']}")
    n = int(cells[0][0])
    shared = (2 * n + 1) ** 3 / (n + 1) ** 3
    return [
        {"id": "thesis.fig14.p2_more_accurate", "source": src,
         "quantity": "trajectory error on the same 4^3 mesh, P1 / P2", "paper_value": "> 1 (P2 more accurate)",
         "measured": p1["metric"] / p2["metric"], "unit": "ratio", "criterion": "> 1",
         "check": check(low=1.0, low_open=True), "size": sz,
         "note": f"P1 {p1['metric']:.3g} m ({p1['unknowns']} unknowns), P2 {p2['metric']:.3g} m ({p2['unknowns']}); "
                 f"at equal unknowns (375) P1 {runs['p1-4']['metric']:.3g} m, P2 on 2^3 {runs['p2-2']['metric']:.3g} m."},
        {"id": "thesis.fig14.p2_costlier_per_step", "source": src,
         "quantity": "time per step on the same 4^3 mesh, P2 / P1", "paper_value": "> 1 ('the cost becomes very huge')",
         "measured": p2["time_per_step_median"] / p1["time_per_step_median"], "unit": "ratio", "criterion": "> 1",
         "check": check(low=1.0, low_open=True), "size": sz, "timings": [timing(p2), timing(p1)],
         "note": f"{p2['time_per_step_median'] * 1e3:.3g} ms against {p1['time_per_step_median'] * 1e3:.3g} ms; at equal "
                 f"unknowns P2 {runs['p2-2']['time_per_step_median'] * 1e3:.3g} ms, P1 "
                 f"{runs['p1-4']['time_per_step_median'] * 1e3:.3g} ms."},
        {"id": "thesis.s5.4.hessian_growth_shared_nodes", "source": "thesis §5.4",
         "quantity": f"Hessian rows, P2 / P1 on the same {n}^3 mesh", "paper_value": round(14172 / 5310, 3),
         "measured": p2["unknowns"] / p1["unknowns"], "unit": "ratio",
         "criterion": f"= (2n + 1)^3 / (n + 1)^3 = {shared:.6g} to 1e-12 (edge nodes shared, as §5.4 builds them; "
                      "the thesis' 2.67 is its armadillo's 1 + E / V)",
         "check": check(shared * (1 - 1e-12), shared * (1 + 1e-12)), "size": sz,
         "note": f"{p1['unknowns']} -> {p2['unknowns']} rows (the thesis: 5,310 -> 14,172 on its armadillo). "
                 f"The ratio is the mesh's 1 + E / V: this box mesh has {shared - 1:.3g} edges per vertex, the armadillo 1.67."},
    ]
