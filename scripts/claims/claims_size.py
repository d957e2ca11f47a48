"""How large a claims row's experiment was against the seed's, so a reader sees
which rows were measured at the seed's size and which on a scaled-down set-up.

A row's size is a list of parts (each a run it reads: what, hofem's count, the
seed's count, the unit the seed gives, unknowns or elements) and the smallest
part's fraction of the seed's count; `at_seed_size` is that fraction >= 0.5
(the bar for "the seed's size": a ladder whose runs are within a factor 2 of the
seed's). None where the seed gives no size. paper_claims.py adds `run`
("main-job" or "full": which job measured it).

The seed's counts (3 unknowns per node):
- Longva et al. 2020, Table 1 (§6.2): Hex20 FCM 2,016 cells / 11,572 nodes,
  Hex8 FCM 98,939 / 121,692, Tet4 FEM 1,633,559 / 320,000, Tet10 FEM
  17,695 / 31,805, the Tet10 reference 86,292 / 135,631;
- §6.4: the hollow ball's Tet10 reference 192 k elements / 332 k nodes (no other
  size is given);
- §6.5: the slingshot's Tet10 meshes of ~5 k and ~35 k elements;
- the thesis §5.3.2: the armadillo of 616 vertices; §5.4: its Hessian of
  5,310 (P1) and 14,172 (P2) rows; §5.3.1: the drop's 20 vertices."""

# Longva et al. 2020 Table 1: each family's resolution at the threshold (elements, nodes).
TABLE1_COUNTS = {"Hex20 FCM": (2016, 11572), "Hex8 FCM": (98939, 121692), "Tet4 FEM": (1633559, 320000),
                 "Tet10 FEM": (17695, 31805), "reference": (86292, 135631)}
# ... and its time per step (ms), with a direct solver on 2 x 14 Xeon cores.
TABLE1_MS = {"Hex20 FCM": 359.0, "Hex8 FCM": 2907.0, "Tet4 FEM": 56321.0, "Tet10 FEM": 560.0, "reference": 21157.0}
TABLE1_UNKNOWNS = {family: 3 * nodes for family, (_, nodes) in TABLE1_COUNTS.items()}
BALL_REFERENCE_UNKNOWNS = 3 * 332000
SLINGSHOT_ELEMENTS = (5000, 35000)
THESIS_ARMADILLO_UNKNOWNS = 3 * 616
THESIS_HESSIAN_ROWS = (5310, 14172)
THESIS_DROP_UNKNOWNS = 3 * 20


def cells(run):
    """A run's elements that carry unknowns: a finite-cell run's active cells, else its elements."""
    return run.get("active_cells") or run["elements"]


def part(what, measured, seed, unit="unknowns"):
    """One run a row reads: hofem's count against the seed's (None: not given)."""
    return {"what": what, "measured": int(measured), "seed": None if seed is None else int(seed), "unit": unit}


def size(*parts):
    """The row's size: its parts and the smallest fraction of the seed's count."""
    fractions = [p["measured"] / p["seed"] for p in parts if p["seed"]]
    fraction = min(fractions) if fractions else None
    return {"parts": list(parts), "fraction": fraction,
            "at_seed_size": None if fraction is None else fraction >= 0.5}


def describe(s):
    """The size column of the markdown table."""
    if s["fraction"] is None:
        return "seed gives no size" + (f" ({s['run']})" if "run" in s else "")
    unit = s["parts"][0]["unit"]
    tag = "seed's size" if s["at_seed_size"] else "scaled down"
    return f"{s['fraction']:.2g} of the seed's {unit}, {tag}" + (f" ({s['run']})" if "run" in s else "")


def timing(run):
    """How a run's time per step was measured: the median over its steps (each
    step a repeat of "one step"), their quartiles as the spread (None in a study
    written before they were recorded) and the number of steps."""
    q = run.get("time_per_step_quartiles")
    return {"run": run["name"], "median": run["time_per_step_median"], "quartiles": q, "steps": run["steps"]}


def describe_timings(timings):
    """The timings of a row for its note: median (quartiles, steps) per run;
    fewer than 3 steps is flagged, a median of fewer is no median."""
    out = []
    for t in timings:
        spread = f", quartiles {t['quartiles'][0]:.3g}-{t['quartiles'][1]:.3g}" if t["quartiles"] else ""
        few = " (fewer than 3 repeats)" if t["steps"] < 3 else ""
        out.append(f"{t['run']} {t['median']:.3g} s{spread}, {t['steps']} steps{few}")
    return "; ".join(out)
