#!/usr/bin/python3
"""ctest schema.print_defaults: `hofem run --print-defaults` against scene.schema.json.

  check_defaults.py HOFEM SCHEMA

1. The printed scene is valid for the schema and for `hofem run --check`.
2. Every value printed whose key (or an enclosing key) has a schema `default`
   equals that default; a value with no default on its path must be one of the
   required keys below, which the schema rightly gives no default.
3. Every schema `default` is printed, except under the keys that are off unless
   given or whose default depends on other keys (OFF, as scene_defaults.hpp says).
Exits 1 listing every mismatch."""
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

# Required keys: printed with the C++ struct's initial values, no schema default.
REQUIRED = {"mesh", "material.model", "material.young", "material.poisson", "integrator", "dt", "duration"}
# Not printed: off unless given (floor, embedded, krylov_iterations), default
# derived from other keys (mass, lumping, name), not a setting ($schema), or an
# alternative to the default mesh's box (mesh.tube: its "curved" default).
OFF = {"$schema", "name", "mass", "lumping", "floor", "embedded", "solver.krylov_iterations", "mesh.tube"}


def sub_schema(schema, path):
    """The schema of a dotted key path (properties only), or None."""
    node = schema
    for k in path.split("."):
        node = node.get("properties", {}).get(k)
        if node is None:
            return None
    return node


def leaves(doc, prefix=""):
    """Dotted paths of the non-object values (arrays are values)."""
    for k, v in doc.items():
        path = f"{prefix}.{k}" if prefix else k
        if isinstance(v, dict) and v:
            yield from leaves(v, path)
        else:
            yield path, v


def printed_value(doc, path):
    for k in path.split("."):
        if not isinstance(doc, dict) or k not in doc:
            return None, False
        doc = doc[k]
    return doc, True


def schema_defaults(schema, prefix=""):
    for k, node in schema.get("properties", {}).items():
        path = f"{prefix}.{k}" if prefix else k
        if "default" in node:
            yield path, node["default"]
        else:
            yield from schema_defaults(node, path)


def check(printed, schema):
    problems = []
    for path, value in leaves(printed):
        steps = path.split(".")
        default = None
        for n in range(len(steps), 0, -1):  # the innermost key with a default
            node = sub_schema(schema, ".".join(steps[:n]))
            if node is not None and "default" in node:
                default = printed_value(node["default"], ".".join(steps[n:]))[0] if n < len(steps) else node["default"]
                break
        if default is not None:
            if default != value:
                problems.append(f"{path}: printed {value!r}, schema default {default!r}")
        elif not any(path == r or path.startswith(r + ".") for r in REQUIRED):
            problems.append(f"{path}: printed {value!r} but the schema has no default for it")
    for path, default in schema_defaults(schema):
        if any(path == o or path.startswith(o + ".") for o in OFF):
            continue
        value, found = printed_value(printed, path)
        if not found:
            problems.append(f"{path}: schema default {default!r} not printed")
    return problems


def main(hofem, schema_path):
    with open(schema_path) as f:
        schema = json.load(f)
    p = subprocess.run([hofem, "run", "--print-defaults"], capture_output=True, text=True, check=True)
    printed = json.loads(p.stdout)
    problems = [f"schema: {e.message}" for e in jsonschema.validators.validator_for(schema)(schema).iter_errors(printed)]
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "defaults.json")
        with open(path, "w") as f:
            f.write(p.stdout)
        c = subprocess.run([hofem, "run", path, "--check"], capture_output=True, text=True)
        if c.returncode != 0 or "defaults.json: valid" not in c.stdout:
            problems.append(f"hofem run --check: exit {c.returncode}: {c.stderr.strip()}")
    problems += check(printed, schema)
    for p in problems:
        print("MISMATCH: " + p)
    print(f"--print-defaults: {sum(1 for _ in leaves(printed))} values, {len(problems)} mismatches")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(*sys.argv[1:]))
