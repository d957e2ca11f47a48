#!/usr/bin/python3
"""Writes SCENE_FORMAT.md, the reference of the scene and study file formats,
from their JSON Schemas (core/scene/scene.schema.json, core/study/study.schema.json):
a table per JSON object (key, type, default, range or choices, description).

  schema_docs.py            rewrite SCENE_FORMAT.md
  schema_docs.py --check    exit 1 if SCENE_FORMAT.md differs from what would be written
                            (ctest schema.docs_fresh)

Only the standard library: the schemas are read as plain JSON."""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # scripts/checks/ -> the repository
SCHEMAS = [("Scene files", "core/scene/scene.schema.json", "scene"),
           ("Study files", "core/study/study.schema.json", "study")]
OUTPUT = "SCENE_FORMAT.md"


def resolve(node, schema):
    """A property's schema with a local "$ref" merged in (its own keys win)."""
    if "$ref" not in node:
        return node
    target = schema
    for part in node["$ref"].lstrip("#/").split("/"):
        target = target[part]
    merged = dict(resolve(target, schema))
    merged.update({k: v for k, v in node.items() if k != "$ref"})
    return merged


def number(v):
    return json.dumps(v).replace("e+", "e")  # 1e300, as the C++ bounds are written


def type_of(node, schema):
    node = resolve(node, schema)
    if "const" in node:
        return "string" if isinstance(node["const"], str) else "value"
    if "enum" in node:
        return "string"
    if "oneOf" in node:
        return " or ".join(type_of(alt, schema) for alt in node["oneOf"])
    t = node.get("type", "any")
    if t == "array":
        items = node.get("prefixItems") or [node.get("items", {})]
        inner = resolve(items[0], schema).get("type", "value") if items and isinstance(items[0], dict) else "value"
        count = f"{node['minItems']} " if node.get("minItems") == node.get("maxItems") and "minItems" in node else ""
        return f"array of {count}{inner}s"
    return t


def interval(node):
    lo, hi = node.get("minimum", node.get("exclusiveMinimum")), node.get("maximum", node.get("exclusiveMaximum"))
    if lo is None and hi is None:
        return ""
    left = "[" if "minimum" in node else "("
    right = "]" if "maximum" in node else ")"
    return f"{left}{number(lo) if lo is not None else '-inf'}, {number(hi) if hi is not None else 'inf'}{right}"


def range_of(node, schema):
    node = resolve(node, schema)
    parts = []
    if "enum" in node:
        parts.append(", ".join(f"`{v}`" for v in node["enum"]))
    if "const" in node:
        parts.append(f"`{node['const']}`")
    if "oneOf" in node:
        parts += [r for r in (range_of(alt, schema) for alt in node["oneOf"]) if r]
    if interval(node):
        parts.append(interval(node))
    if "prefixItems" in node:
        parts.append("; ".join(interval(i) for i in node["prefixItems"]))
    elif isinstance(node.get("items"), dict) and interval(node["items"]):
        parts.append("each " + interval(node["items"]))
    if node.get("type") == "array" and node.get("minItems", 0) > 0 and node.get("minItems") != node.get("maxItems"):
        parts.append(f"at least {node['minItems']} item(s)")
    if node.get("type") == "array" and "maxItems" in node and node.get("minItems") != node.get("maxItems"):
        parts.append(f"at most {node['maxItems']} items")
    if "pattern" in node:
        parts.append(f"pattern `{node['pattern']}`")
    if node.get("minLength"):
        parts.append("not empty")
    return "; ".join(parts)


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def objects(node, schema, path):
    """(path, object schema) of every object with properties, depth first."""
    node = resolve(node, schema)
    if "properties" in node:
        yield path, node
        for key, sub in node["properties"].items():
            yield from objects(sub, schema, f"{path}.{key}" if path else key)
    for alt in node.get("oneOf", []):
        yield from objects(alt, schema, path)
    if isinstance(node.get("items"), dict):
        yield from objects(node["items"], schema, f"{path}[]")


def table(path, node, schema, document):
    title = f"`{path}`" if path else f"The {document} (top level)"
    lines = [f"### {title}", ""]
    if node.get("description") and path:
        lines += [cell(node["description"]), ""]
    required = set(node.get("required", []))
    lines += ["| key | type | default | range or choices | description |", "|---|---|---|---|---|"]
    for key, sub in node["properties"].items():
        sub_r = resolve(sub, schema)
        name = f"`{key}`" + (" (required)" if key in required else "")
        default = f"`{json.dumps(sub_r['default'])}`" if "default" in sub_r else ""
        lines.append(f"| {name} | {cell(type_of(sub, schema))} | {cell(default)} | {cell(range_of(sub, schema))} | "
                     f"{cell(sub_r.get('description', ''))} |")
    return lines + [""]


def render():
    out = ["# Scene and study file format", "",
           "<!-- Generated by scripts/checks/schema_docs.py from the JSON Schemas; do not edit: run the script. -->", "",
           "Scenes (`hofem run SCENE`) and studies (`hofem study STUDY`) are JSON files. Their schemas,",
           "[core/scene/scene.schema.json](core/scene/scene.schema.json) and",
           "[core/study/study.schema.json](core/study/study.schema.json), give every key below; put",
           "`\"$schema\": \"<path to the schema>\"` at the top of a file for an editor's completion and checks.",
           "hofem's own parser is the authority at run time: it also checks what a schema cannot",
           "(marked \"checked by hofem only\", e.g. that a mesh file exists or that max > min).",
           "`hofem run SCENE --check` validates a scene without running it, `hofem run --print-defaults`",
           "prints every key with its default, and `--set key.path=VALUE` (repeatable) overrides a key",
           "before validation, as a study's `overrides` do. Ranges: `[a, b]` includes a bound, `(a, b)` excludes it.", ""]
    for heading, rel, document in SCHEMAS:
        with open(os.path.join(ROOT, rel)) as f:
            schema = json.load(f)
        out += [f"## {heading}", "", cell(schema.get("description", "")), ""]
        for path, node in objects(schema, schema, ""):
            out += table(path, node, schema, document)
    return "\n".join(out).rstrip("\n") + "\n"


def main(argv):
    text = render()
    path = os.path.join(ROOT, OUTPUT)
    if argv == ["--check"]:
        current = open(path).read() if os.path.exists(path) else ""
        if current != text:
            print(f"{OUTPUT} is not what scripts/checks/schema_docs.py generates from the schemas: run scripts/checks/schema_docs.py")
            return 1
        print(f"{OUTPUT} is up to date")
        return 0
    if argv:
        print(__doc__, file=sys.stderr)
        return 2
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)  # atomic: a reader never sees half a file
    print(f"wrote {OUTPUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
