#!/usr/bin/env python3
"""The sources the libFuzzer targets compile, their content hash, and whether
reports/fuzz.json was recorded on them.

The files: each target's verification/fuzz/fuzz_<target>.cpp, the project sources
verification/fuzz/sources.txt lists (the list verification/fuzz/CMakeLists.txt
builds the targets from) and every project header they include, transitively
(#include "..." resolved as the fuzz build does: the including file's directory,
core/, cli/, verification/fuzz/), kept to the parsers' folders (PARSER_DIRS). The hash is over the files' content, not a
commit: sha256 of the lines "<sha256 of the file>  <path>\\n" in path order, so
it holds for uncommitted changes as well as after they are committed.

usage: fuzz_sources.py list  [--root DIR]          the files, one per line
       fuzz_sources.py json  [--root DIR]          {"sha256", "files": {path: sha256}}
       fuzz_sources.py check REPORT [--root DIR]   REPORT's "sources" against DIR's files
check prints "fuzz_sources: REPORT is current: ..." and exits 0, or
"fuzz_sources: FAIL: ..." with the files changed since the fuzz run (and a recorded
run that crashed or did not run a target), and exits 1.
"""
import argparse
import hashlib
import json
import os
import re
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
LIST = "verification/fuzz/sources.txt"
INCLUDE_DIRS = ["core", "cli", "verification/fuzz"]  # verification/fuzz/CMakeLists.txt's include path
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)
# The parsers' own code: what reads untrusted input (the Gmsh reader and input
# caps, the scene reader, the command line). The hash keeps to these folders, so
# a change to, say, a material's stress or a solver header - compiled into the
# targets but not parsing anything - does not ask for a new fuzz run.
PARSER_DIRS = ("core/io/", "core/scene/", "cli/", "verification/fuzz/")


def targets(root):
    """The fuzz targets: verification/fuzz/fuzz_<target>.cpp."""
    return sorted(f[len("fuzz_"):-len(".cpp")] for f in os.listdir(os.path.join(root, "verification/fuzz"))
                  if f.startswith("fuzz_") and f.endswith(".cpp"))


def listed(root):
    """The project sources of sources.txt, in its order."""
    paths = []
    with open(os.path.join(root, LIST)) as f:
        for line in f:
            path = line.split("#")[0].strip()
            if path:
                paths.append(path)
    return paths


def files(root):
    """Sorted relative paths: the fuzz targets' sources and their project headers."""
    start = [f"verification/fuzz/fuzz_{t}.cpp" for t in targets(root)] + listed(root)
    seen, stack = set(), list(start)
    while stack:
        path = stack.pop()
        if path in seen:
            continue
        full = os.path.join(root, path)
        if not os.path.isfile(full):
            raise SystemExit(f"fuzz_sources: {path} (from {LIST}) does not exist")
        seen.add(path)
        with open(full, errors="replace") as f:
            text = f.read()
        for name in INCLUDE.findall(text):
            for d in [os.path.dirname(path)] + INCLUDE_DIRS:
                candidate = os.path.normpath(os.path.join(d, name))
                if os.path.isfile(os.path.join(root, candidate)):
                    stack.append(candidate)
                    break
            # Not found: a system or generated header (none is parsed input code).
    return sorted(p for p in seen if p.startswith(PARSER_DIRS))


def sha256_file(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def combined(file_hashes):
    text = "".join(f"{h}  {p}\n" for p, h in sorted(file_hashes.items()))
    return hashlib.sha256(text.encode()).hexdigest()


def current(root):
    hashes = {p: sha256_file(os.path.join(root, p)) for p in files(root)}
    return {"sha256": combined(hashes), "files": hashes}


def check(report_path, root):
    name = os.path.relpath(report_path, root) if os.path.isabs(report_path) else report_path
    try:
        with open(report_path) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        print(f"fuzz_sources: FAIL: cannot read {name}: {e}")
        return 1
    problems = []
    recorded = report.get("sources") or {}
    now = current(root)
    redo = "run scripts/fuzz (60 s per target plus the build) and commit reports/fuzz.json"
    if not recorded.get("files"):
        problems.append(f"{name} records no hash of the sources it was fuzzed on (a report older than the "
                        f"hash, commit {report.get('context', {}).get('commit', '?')}): {redo}")
    elif recorded.get("sha256") != now["sha256"]:
        old = recorded.get("files") or {}
        changed = sorted(p for p in now["files"] if p in old and old[p] != now["files"][p])
        added = sorted(p for p in now["files"] if p not in old)
        removed = sorted(p for p in old if p not in now["files"])
        lines = [f"the fuzz targets' sources differ from those {name} was recorded on "
                 f"(commit {report.get('context', {}).get('commit', '?')}): {redo}"]
        lines += [f"  changed since the fuzz run: {p}" for p in changed]
        lines += [f"  not fuzzed (new to the targets): {p}" for p in added]
        lines += [f"  no longer compiled into the targets: {p}" for p in removed]
        if not (changed or added or removed):
            lines.append("  (the recorded hash does not match its own file list)")
        problems.append("\n".join(lines))
    # The recorded run itself: every target ran and none crashed.
    runs = {t.get("name"): t for t in report.get("targets", [])}
    for target in targets(root):
        t = runs.get(target)
        if t is None:
            problems.append(f"{name} has no run of the target {target}: {redo}")
        elif t.get("exit_status") != 0 or t.get("crashes") or not t.get("executions"):
            problems.append(f"{name}: the run of {target} failed (exit status {t.get('exit_status')}, "
                            f"{t.get('crashes')} crashes, {t.get('executions')} executions): fix it, then {redo}")
    if problems:
        print("fuzz_sources: FAIL: " + "\n".join(problems))
        return 1
    print(f"fuzz_sources: {name} is current: {len(now['files'])} files, sha256 {now['sha256'][:16]}, "
          f"{len(runs)} targets without crashes")
    return 0


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("command", choices=["list", "json", "check"])
    ap.add_argument("report", nargs="?", help="check: the fuzz report (reports/fuzz.json)")
    ap.add_argument("--root", default=ROOT, help="repository root (default: this checkout)")
    a = ap.parse_args(argv)
    if a.command == "list":
        print("\n".join(files(a.root)))
    elif a.command == "json":
        print(json.dumps(current(a.root), indent=1))
    else:
        if not a.report:
            ap.error("check needs the report's path")
        return check(a.report, a.root)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
