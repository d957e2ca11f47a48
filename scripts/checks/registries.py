#!/usr/bin/python3
"""The registries against every list that repeats them.

hofem keeps one table per choice (materials, integrators, linear solvers,
preconditioners, BoomerAMG variants, element orders per cell); `hofem choices
--json` prints them. This checks that each place that lists names lists exactly
the registry's (none missing, none extra):
  - the scene schema's enums (core/scene/scene.schema.json),
  - SCENE_FORMAT.md's value columns (written from the schema),
  - `hofem mms --help` and `hofem run --help` (the material and solver lists),
  - README.md's layer table (every preconditioner and BoomerAMG variant named).
Exit status 1 with one line per disagreement.

Usage: registries.py HOFEM [--root DIR]
       registries.py HOFEM --self-test   each check is shown to fail on a list
                                         with one name dropped or one added
"""
import argparse
import copy
import json
import re
import subprocess
import sys
from pathlib import Path


def registry(hofem):
    out = subprocess.run([hofem, "choices", "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def enum_at(schema, path):
    node = schema
    for key in path:
        node = node["properties"][key]
    return node["enum"]


def table_values(markdown, key):
    """The backticked values of the SCENE_FORMAT.md row whose first cell is `key`."""
    for line in markdown.splitlines():
        cells = [c.strip() for c in line.split("|")]
        if len(cells) > 5 and re.fullmatch(rf"`{re.escape(key)}`( \(required\))?", cells[1]):
            return re.findall(r"`([^`]+)`", cells[4])
    return None


def compare(what, listed, expected, extra_ok=()):
    """Disagreements of one list with the registry's names, as messages."""
    if listed is None:
        return [f"{what}: not found"]
    listed_set, expected_set = set(listed), set(expected)
    missing = [n for n in expected if n not in listed_set]
    extra = [n for n in listed if n not in expected_set and n not in extra_ok]
    msgs = []
    if missing:
        msgs.append(f"{what}: misses {', '.join(missing)}")
    if extra:
        msgs.append(f"{what}: lists {', '.join(extra)}, which the registry does not have")
    return msgs


def names(rows):
    return [r["name"] for r in rows]


def checks(reg, schema, scene_format, mms_help, run_help, readme):
    """Every comparison: (what, listed, expected, names a list may have beyond the registry)."""
    krylov_pcs = sorted({pc for m in reg["linear_solver_methods"] for pc in m["preconditioners"]})
    help_words = set(re.findall(r"[a-z0-9][a-z0-9+-]*", mms_help + run_help))
    readme_words = set(re.findall(r"[a-z0-9][a-z0-9-]*", readme))
    cells = [c["cell"] for c in reg["cells"]]
    return [
        ("scene schema material.model", enum_at(schema, ["material", "model"]), names(reg["materials"]), ()),
        # "static" is a scene's choice besides the integrators: one solve, no time stepping.
        ("scene schema integrator", enum_at(schema, ["integrator"]), names(reg["integrators"]), ("static",)),
        ("scene schema solver.linear", enum_at(schema, ["solver", "linear"]), reg["linear_solvers"], ()),
        ("scene schema solver.distributed.amg", enum_at(schema, ["solver", "distributed", "amg"]),
         names(reg["boomeramg_variants"]), ()),
        ("scene schema mesh.cell", enum_at(schema, ["mesh", "cell"]), cells, ()),
        ("SCENE_FORMAT.md model", table_values(scene_format, "model"), names(reg["materials"]), ()),
        ("SCENE_FORMAT.md integrator", table_values(scene_format, "integrator"), names(reg["integrators"]),
         ("static",)),
        ("SCENE_FORMAT.md linear", table_values(scene_format, "linear"), reg["linear_solvers"], ()),
        ("SCENE_FORMAT.md amg", table_values(scene_format, "amg"), names(reg["boomeramg_variants"]), ()),
        ("hofem mms/run --help materials", [n for n in names(reg["materials"]) if n in help_words],
         names(reg["materials"]), ()),
        ("hofem mms/run --help preconditioners", [n for n in krylov_pcs if n in help_words], krylov_pcs, ()),
        ("README.md preconditioners", [n for n in names(reg["preconditioners"]) if n in readme_words],
         names(reg["preconditioners"]), ()),
    ]


def run_checks(reg, sources):
    msgs = []
    for what, listed, expected, extra_ok in checks(reg, *sources):
        msgs += compare(what, listed, expected, extra_ok)
    return msgs


def self_test(reg, sources):
    """Each check must fail when its list loses a name or gains one."""
    failures = []
    for i, (what, listed, expected, extra_ok) in enumerate(checks(reg, *sources)):
        if listed is None or not listed:
            failures.append(f"{what}: nothing to perturb")
            continue
        if not compare(what, listed[1:], expected, extra_ok):
            failures.append(f"{what}: a dropped name is not found")
        if not compare(what, listed + ["no-such-name"], expected, extra_ok) and "help" not in what and "README" not in what:
            failures.append(f"{what}: an added name is not found")
    # The registry side: a name the registry gains and no list has is found.
    grown = copy.deepcopy(reg)
    grown["materials"].append({"name": "new-material", "description": ""})
    if not any("new-material" in m for m in run_checks(grown, sources)):
        failures.append("a material the lists do not have is not found")
    return failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("hofem")
    ap.add_argument("--root", default=str(Path(__file__).resolve().parents[2]))
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    root = Path(a.root)
    reg = registry(a.hofem)
    help_text = lambda sub: subprocess.run([a.hofem, sub, "--help"], capture_output=True, text=True).stdout
    sources = (json.loads((root / "core/scene/scene.schema.json").read_text()),
               (root / "SCENE_FORMAT.md").read_text(), help_text("mms"), help_text("run"),
               (root / "README.md").read_text())
    if a.self_test:
        failures = self_test(reg, sources)
        for f in failures:
            print(f"registries self-test: FAIL: {f}")
        if failures:
            return 1
        print(f"registries: every check fails on a perturbed list ({len(checks(reg, *sources))} checks)")
        return 0
    msgs = run_checks(reg, sources)
    for m in msgs:
        print(f"registries: FAIL: {m}")
    if msgs:
        return 1
    print(f"registries: {len(checks(reg, *sources))} lists agree with the registries")
    return 0


if __name__ == "__main__":
    sys.exit(main())
