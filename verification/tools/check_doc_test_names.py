#!/usr/bin/env python3
"""Fails when a document quotes a ctest name that ctest does not list.

A quoted test name is a word of an inline code span (`...`; in fenced code blocks,
a word of a line that runs ctest) of the form PREFIX.REST where PREFIX is the part
before the first dot of some ctest name (cli, layers, verify, GoogleTest suites...,
computed from `ctest --show-only=json-v1`), so file names (`reports/verification.json`,
`study.json`, `<mpi.h>`) are not taken for tests. A name with * or ? is a pattern:
it must match at least one test. A name that is a group of the verification rows
(reports/verification.json: `mms.solver_switch`) names rows, not a test, and passes.

usage: check_doc_test_names.py --build DIR [--ctest CTEST] [--groups REPORT] DOC...
       check_doc_test_names.py --json FILE [--groups REPORT] DOC...   (that output, saved or fabricated)
Prints "check_doc_test_names: N quoted test names in DOC..., all among the M tests"
and exits 0, or "check_doc_test_names: FAIL: ..." with each missing name and where
it is quoted, and exits 1.
"""
import argparse
import fnmatch
import json
import os
import re
import sys

import ctest_list

# A word that ends in one of these is a file name, whatever its prefix.
FILE_EXTENSIONS = {"c", "cc", "cpp", "h", "hpp", "json", "jsonl", "md", "py", "sh", "txt", "msh", "yml", "yaml",
                   "png", "svg", "html", "vtu", "pvd", "csv", "cmake", "dict", "state", "mtx", "log", "xml"}
WORD = re.compile(r"^[A-Za-z][\w/]*\.[\w.*?/\-]*[\w*?]$")
FENCE = re.compile(r"^\s*(```|~~~)")


def quoted_words(text):
    """(line number, word) of every inline code span's words and of ctest lines in fenced blocks."""
    found = []
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            if re.search(r"\bctest\b", line):
                found += [(number, w) for w in line.split("#")[0].split()]
            continue
        for span in re.findall(r"`([^`]+)`", line):
            found += [(number, w) for w in span.split()]
    return [(n, w.strip("()[]{},;:'\"")) for n, w in found]


def test_names(words, prefixes):
    names = []
    for number, word in words:
        if not WORD.match(word):
            continue
        if word.split(".")[0] not in prefixes:
            continue
        if word.rsplit(".", 1)[1].lower() in FILE_EXTENSIONS:
            continue
        names.append((number, word))
    return names


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("docs", nargs="+", help="Markdown files to check")
    ctest_list.add_arguments(ap)
    ap.add_argument("--groups", help="reports/verification.json: its row groups are not test names")
    a = ap.parse_args(argv)
    entries, error = ctest_list.load_tests(ap, a, "check_doc_test_names")
    if error:
        print(error)
        return 1
    tests = [t["name"] for t in entries]
    known = set(tests)
    prefixes = {t.split(".")[0] for t in tests if "." in t}
    groups = set()
    if a.groups:
        with open(a.groups) as f:
            groups = {r["group"] for r in json.load(f).get("rows", [])}

    quoted, missing, rows = 0, [], 0
    for path in a.docs:
        with open(path) as f:
            names = test_names(quoted_words(f.read()), prefixes)
        for number, name in names:
            quoted += 1
            if any(c in name for c in "*?"):
                ok = bool(fnmatch.filter(tests, name))
                if not ok and fnmatch.filter(groups, name):
                    ok, rows = True, rows + 1
            elif name in known:
                ok = True
            elif name in groups:
                ok, rows = True, rows + 1
            else:
                ok = False
            if not ok:
                missing.append(f"{os.path.basename(path)}:{number}: {name}")
    docs = ", ".join(os.path.basename(p) for p in a.docs)
    if missing:
        print(f"check_doc_test_names: FAIL: {len(missing)} of {quoted} test names quoted in {docs} are not "
              f"among the {len(tests)} tests of ctest --show-only (rename them to the test meant, or reword):")
        for m in missing:
            print(f"  {m}")
        return 1
    also = f" ({rows} of them verification row groups)" if rows else ""
    print(f"check_doc_test_names: {quoted} quoted test names in {docs}, all among the {len(tests)} tests{also}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
