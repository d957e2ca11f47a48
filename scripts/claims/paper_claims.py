#!/usr/bin/python3
"""The seeds' reported numbers beside hofem's: reads the main job's reports
(studies, verification.json) and writes reports/paper_claims.json and
reports/paper_claims.md. Each row: id, source (document, section, table or
figure), quantity, paper_value, measured, unit, criterion (written here, before
any measurement it judges) in words and as `check`, the interval of agreeing
values (claims_check.py), agrees (computed from check here, in one place), size
(the runs it reads against the seed's, their smallest fraction of the seed's
unknowns or elements, whether that is the seed's size, and which job ran it:
claims_size.py), note. Rows a builder cannot judge (a family that never
crosses the threshold) are listed as skipped with the reason; checks of a study's
own reference are kept apart from the claims ("reference_checks").

Sources: Longva et al. 2020, "Higher-order finite elements for embedded
simulation" (Table 1, §6.2-6.5, Fig. 10: scripts/claims/claims_longva.py), and the
thesis on a high-order FEM simulator (§5.2 Fig. 9, §5.3.1 Figs. 10-11, §5.3.2
Figs. 12-13, §5.4 Fig. 14: scripts/claims/claims_thesis.py). Each row's function says
how its experiment is scaled to this machine.

Usage: paper_claims.py [REPORTS] [--out DIR] [--full] (default REPORTS and DIR:
reports). Exits 1 if a source file is missing (the row would be silent garbage).
--full builds the rows of the full-size studies instead (REPORTS/full/studies,
written by scripts/studies-full; default DIR: REPORTS/full), size "full"; a
study that was not run at full size leaves its rows out and is listed as
skipped (exit 1 only if none was run)."""
import json
import math
import os
import sys

from claims_longva import (fig10_rows, hollow_ball_rows, seed_simplification_rows, simplification_rows, slingshot_rows,
                           twisting_cylinder_rows)
from claims_table1_seed import (table1_at_seed_resolution, table1_decomposition, table1_explanation, table1_seed_rows,
                                table1_side_by_side)
from claims_check import judge
from claims_size import describe, describe_timings
from claims_thesis import compression_rows, drop_integrator_rows, krylov_implicit_rows, krylov_rows, order_rows


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


def interval(c):
    low = "" if c["low"] is None else f"{c['low']:.4g} {'<' if c['low_open'] else '<='} "
    high = "" if c["high"] is None else f" {'<' if c['high_open'] else '<='} {c['high']:.4g}"
    return f"{low}x{high}"


def timings(r):
    """The row's timings for its note: median per step, quartiles, steps."""
    return f" Timings: {describe_timings(r['timings'])}." if r.get("timings") else ""


def markdown(rows, skipped=(), reference_checks=(), explanation=()):
    lines = ["# The seeds' numbers beside hofem's", "",
             "Written by `scripts/claims/paper_claims.py` from the reports (size: the smallest fraction of the seed's "
             "unknowns or elements among the runs a row reads, \"seed's size\" at >= 0.5; the parts are in "
             "paper_claims.json); the criterion of each row was written "
             "before the measurement it judges. " + f"{sum(r['agrees'] for r in rows)} of {len(rows)} rows agree.", "",
             "| id | source | quantity | paper | hofem | criterion | agrees | size | note |",
             "|---|---|---|---:|---:|---|---|---|---|"]
    for r in rows:
        fmt = lambda x: "—" if x is None else (f"{x:.4g}" if isinstance(x, float) else str(x))
        lines.append(f"| {r['id']} | {r['source']} | {r['quantity']} | {fmt(r['paper_value'])} | {fmt(r['measured'])} "
                     f"| {r['criterion']} (`{interval(r['check'])}`) | {'yes' if r['agrees'] else '**no**'} | {describe(r['size'])} "
                     f"| {r['note']}{timings(r)} |")
    if reference_checks:
        lines += ["", "Checks of the studies' own references (not claims of the seeds):", ""]
        lines += [f"- {r['id']}: {r['quantity']} = {fmt(r['measured'])}, `{interval(r['check'])}`: "
                  f"{'holds' if r['agrees'] else '**fails**'}. {r['note']}" for r in reference_checks]
    lines += list(explanation)
    if skipped:
        lines += ["", "Not judged (a study not run at this size, or a row hofem can only bound):", ""] + [f"- {s}" for s in skipped]
    return "\n".join(lines) + "\n"


# Row groups: (the study each reads, or None for the verification and scenes, the builder).
GROUPS = [("twisting-cylinder", twisting_cylinder_rows), ("twisting-cylinder", simplification_rows),
          ("hollow-ball", hollow_ball_rows), ("slingshot", slingshot_rows), (None, fig10_rows),
          (None, compression_rows), ("drop-integrators", drop_integrator_rows), ("drop-krylov", krylov_rows),
          ("drop-krylov-implicit", krylov_implicit_rows),
          ("drop-orders", order_rows), ("twisting-cylinder-seed", table1_seed_rows),
          ("twisting-cylinder-seed-simplification", seed_simplification_rows)]


# The full-size study files (scripts/studies-full runs each).
FULL_STUDIES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studies", "full")


def build_rows(R, full):
    """Every group's rows; at full size only the studies' groups, each skipped
    (and named) when its study or one of its runs is absent."""
    rows, skipped = [], []
    for study, group in GROUPS:
        if not full:
            if study is None or study in R["studies"]:  # the seed-size studies exist only at full size
                rows += group(R)
            continue
        if study is None:
            continue
        if not os.path.exists(os.path.join(FULL_STUDIES, study + ".json")):
            skipped.append(f"{group.__name__}: the study {study} has no full-size set-up (scripts/studies/full/); "
                           "its rows are judged on the main job's page, reports/paper_claims.md")
            continue
        try:
            built = group(R)
        except (OSError, KeyError) as e:
            skipped.append(f"{group.__name__} ({study}): {type(e).__name__}: {e}")
            continue
        rows += built
    skipped += [r["skipped"] for r in rows if "skipped" in r]
    for r in rows:
        if "size" in r:
            r["size"]["run"] = "full" if full else "main-job"
    return [r for r in rows if "skipped" not in r], skipped


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
        r["agrees"] = judge(r["measured"], r["check"])
        if isinstance(r["measured"], float) and not math.isfinite(r["measured"]):
            r["note"] = f"measured {r['measured']}; " + r["note"]
            r["measured"] = None  # JSON has no infinity
    reference_checks = [r for r in rows if r.pop("reference_check", False)]
    rows = [r for r in rows if r not in reference_checks]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "paper_claims.json"), "w") as f:
        json.dump({"rows": rows, "reference_checks": reference_checks, "skipped": skipped}, f, indent=1)
        f.write("\n")
    with open(os.path.join(out, "paper_claims.md"), "w") as f:
        tables = (table1_side_by_side(R) + table1_at_seed_resolution(R) + table1_explanation(R)
                  + table1_decomposition(R)) if full else ()
        f.write(markdown(rows, skipped, reference_checks, tables))
    print(f"paper_claims: {sum(r['agrees'] for r in rows)} of {len(rows)} rows agree -> {out}/paper_claims.md")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
