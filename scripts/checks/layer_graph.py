#!/usr/bin/env python3
"""The core's layer graph, three ways, checked to agree.

1. Declared: the CMake targets (core/CMakeLists.txt's hofem_layer calls),
   written by CMake as build/core/layers.txt, "layer: dependency ...".
2. Used: the layers each layer's sources include ("linalg/krylov.hpp" is the
   layer solver), read from core/.
3. Documented: the block of README.md between the layer-graph markers.

It also checks that MPI stays behind parallel/: no header of another layer
includes <mpi.h> (they get MPI_Comm from parallel/'s headers).

The build enforces used <= declared (an undeclared include does not compile);
this script adds declared <= used (no dependency kept after its last include
went) and README == declared. With --write it rewrites README's block.

  layer_graph.py --layers build/core/layers.txt [--readme README.md] [--core core] [--write]
"""
import argparse
import pathlib
import re
import sys

BEGIN = "<!-- layer graph: written by scripts/checks/layer_graph.py --write from the CMake targets; ctest layers.graph checks it -->"
END = "<!-- end of layer graph -->"
ROOT = pathlib.Path(__file__).resolve().parents[2]  # the repository (this file is scripts/checks/layer_graph.py)


def read_declared(path):
    graph = {}
    for number, line in enumerate(pathlib.Path(path).read_text().splitlines(), 1):
        if not line.strip():
            continue
        name, sep, deps = line.partition(":")
        if not sep:
            sys.exit(f"layer_graph: {path}:{number}: expected 'layer: dependency ...', got {line!r}")
        graph[name.strip()] = deps.split()
    return graph


def read_used(core, layers):
    include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/[^"]+"', re.M)
    used = {name: set() for name in layers}
    for name in layers:
        for source in sorted((core / name).glob("*.[ch]pp")):
            for target in include.findall(source.read_text()):
                if target != name and target in layers:
                    used[name].add(target)
    return used


def mpi_outside_parallel(core):
    """Headers outside core/parallel/ that include <mpi.h> themselves."""
    pattern = re.compile(r"^\s*#\s*include\s*<mpi\.h>", re.M)
    return [str(h.relative_to(core)) for h in sorted(core.glob("*/*.hpp"))
            if h.parent.name != "parallel" and pattern.search(h.read_text())]


def check(declared, used, core):
    problems = []
    for name, deps in declared.items():
        for extra in sorted(set(deps) - used[name]):
            problems.append(f"core/CMakeLists.txt: layer {name} links {extra}, but no source of core/{name}/ includes it")
        for missing in sorted(used[name] - set(deps)):
            problems.append(f"core/{name}/ includes {missing}/, which layer {name} does not link")
    for header in mpi_outside_parallel(core):
        problems.append(f"core/{header} includes <mpi.h>: only parallel/'s headers may")
    return problems


def levels(graph):
    depth = {}

    def level(name):
        if name not in depth:
            depth[name] = 1 + max((level(d) for d in graph[name]), default=-1)
        return depth[name]

    for name in graph:
        level(name)
    return depth


def render(graph):
    depth = levels(graph)
    lines = [BEGIN, "", "```"]
    for d in range(max(depth.values()) + 1):
        names = [n for n in graph if depth[n] == d]
        lines.append(f"level {d}: " + "  ".join(names))
    lines += ["```", "", "| layer | links (its code includes these layers, and no others) |", "|---|---|"]
    for name, deps in graph.items():
        lines.append(f"| `{name}` | {', '.join(deps) if deps else '—'} |")
    lines += ["", END]
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--layers", required=True)
    p.add_argument("--readme", default=str(ROOT / "README.md"))
    p.add_argument("--core", default=str(ROOT / "core"))
    p.add_argument("--write", action="store_true")
    a = p.parse_args()
    declared = read_declared(a.layers)
    core = pathlib.Path(a.core)
    problems = check(declared, read_used(core, declared), core)
    block = render(declared)
    readme = pathlib.Path(a.readme)
    text = readme.read_text()
    if BEGIN not in text or END not in text:
        problems.append(f"{readme}: no layer-graph block (the markers {BEGIN!r} ... {END!r})")
    else:
        start, stop = text.index(BEGIN), text.index(END) + len(END)
        if text[start:stop] != block:
            if a.write:
                readme.write_text(text[:start] + block + text[stop:])
                print(f"layer_graph: rewrote the graph in {readme}")
            else:
                problems.append(f"{readme}: the layer graph differs from the CMake targets (scripts/checks/layer_graph.py --write)")
    for problem in problems:
        print(f"layer_graph: {problem}", file=sys.stderr)
    if problems:
        return 1
    print(f"layer_graph: {len(declared)} layers, {sum(map(len, declared.values()))} dependencies: "
          "CMake targets, includes and README agree; <mpi.h> only in parallel/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
