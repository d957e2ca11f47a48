#!/usr/bin/python3
"""Checks reports/index.html (scripts/report/report_index.py).

  check_report_index.py --page PAGE
      the page parses (html.parser) with balanced tags, has no http(s):// URL,
      every <img src> and local <a href> names a file that exists beside it, its
      sections come in order and it carries the image check (scripts/render-report
      runs this before Chromium).
  check_report_index.py --image-check DOM
      prints the text of #image-check in a page Chromium dumped (- = stdin);
      exit 0 only if it says that all images loaded.
  check_report_index.py --fixture DIR --work DIR --expect full|missing|bad|render
      copies the fixture DIR to WORK/reports (an empty directory for "missing"),
      runs report_index.py on it and checks the page as --page does, plus what
      the fixture makes knowable in advance (ctest report.index*,
      verification/report/CMakeLists.txt): the failing check before any group
      table, escaped text, the claims, the study's plot, a headline figure; or
      "not produced by this run" in every section; or each broken input named
      with its line or key and exit status 1; "render": as "full", then
      scripts/render-report passes on it and fails on an undecodable PNG (exit
      77 without chromium).
Prints "check_report_index: PASS ..." or the problems, one a line (exit 1)."""
import argparse
import html.parser
import os
import re
import shutil
import subprocess
import sys
import urllib.parse

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.dirname(HERE)  # scripts/, where the command render-report is
SECTIONS = ("provenance", "verification", "claims", "studies", "benchmarks", "images")
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


class Page(html.parser.HTMLParser):
    """Tags kept on a stack (a mismatched or unclosed one is a problem), the ids
    in document order with their offsets, the images and links, and the text of
    #image-check."""

    def __init__(self, text):
        super().__init__(convert_charrefs=True)
        self.stack, self.problems, self.ids, self.images, self.links = [], [], {}, [], []
        self.image_check, self._in_check = None, False
        self._lines = [0]
        for line in text.splitlines(keepends=True):
            self._lines.append(self._lines[-1] + len(line))
        self.feed(text)
        self.close()
        self.problems += [f"<{tag}> opened on line {line} is never closed" for tag, line in self.stack]

    def position(self):
        line, column = self.getpos()
        return self._lines[line - 1] + column

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            if a["id"] in self.ids:
                self.problems.append(f"line {self.getpos()[0]}: id {a['id']!r} twice")
            self.ids[a["id"]] = self.position()
        if tag == "img":
            self.images.append(a.get("src") or "")
        if tag == "a" and a.get("href") and not a["href"].startswith("#"):
            self.links.append(a["href"])
        self._in_check = a.get("id") == "image-check"
        if self._in_check:
            self.image_check = ""
        if tag not in VOID:
            self.stack.append((tag, self.getpos()[0]))

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in VOID:
            self.stack.pop()

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1][0] != tag:
            opened = f"<{self.stack[-1][0]}> of line {self.stack[-1][1]}" if self.stack else "nothing"
            self.problems.append(f"line {self.getpos()[0]}: </{tag}> closes {opened}")
            return
        self.stack.pop()
        self._in_check = False

    def handle_data(self, data):
        if self._in_check:
            self.image_check += data


def check_page(path):
    """(problems, parsed page, text) of the page at PATH."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    page = Page(text)
    problems = list(page.problems)
    problems += [f"a network URL: {u}" for u in re.findall(r"(?i)https?://[^\s\"'<>]*", text)]
    folder = os.path.dirname(os.path.abspath(path))
    for ref in dict.fromkeys(page.images + page.links):  # a picture is both an <img> and its link
        target = urllib.parse.unquote(urllib.parse.urlsplit(ref).path)
        if not target or os.path.isabs(target) or not os.path.isfile(os.path.join(folder, target)):
            problems.append(f"{ref!r}: referenced, but no such file beside the page")
    offsets = [page.ids.get(s) for s in SECTIONS]
    if None in offsets or offsets != sorted(offsets):
        problems.append(f"sections missing or out of order: {dict(zip(SECTIONS, offsets))}")
    if page.image_check is None or "naturalWidth" not in text:
        problems.append("no #image-check element or no image-checking script")
    return problems, page, text


def expect_full(page, text, status, stderr):
    """What verification/report/fixture makes knowable in advance."""
    problems = [] if status == 0 else [f"report_index.py exited with {status}: {stderr}"]
    failing = text.find("rate p2 n=8 FAILING-CHECK")
    groups = min(page.ids.get("groups", -1), text.find("<details"))
    if failing < 0 or groups < 0 or failing > groups:
        problems.append(f"the failing check (offset {failing}) is not before the group tables (offset {groups})")
    if "<script>alert(1)" in text or "&lt;script&gt;alert(1)&lt;/script&gt; &amp; 10 %" not in text:
        problems.append("the failing check's why is not escaped")
    for needle in ("fixture.agreeing-claim", "fixture.disagreeing-claim", "1 of 2 rows agree", "0123456789ab",
                   "fixture-host", "Fixture CPU", "0.25 s to L2 error 0.00075 (cg+pmg)", "4.0x faster", "321.5 GF/s",
                   "1 of 1", "p1-2", "solver_benchmarks.json: not produced by this run"):
        if needle not in text:
            problems.append(f"expected text missing: {needle!r}")
    if not re.search(r'<tr class="fail"><td>fixture\.disagreeing-claim', text):
        problems.append("the disagreeing claim is not marked")
    if sorted(page.images) != ["plot.png", "studies/tiny/work_precision.png"]:
        problems.append(f"images: {page.images}")
    return problems


def expect_missing(page, text, status, stderr):
    problems = [] if status == 0 else [f"report_index.py exited with {status}: {stderr}"]
    sections = [text[page.ids[s]:page.ids[n] if n else len(text)] for s, n in zip(SECTIONS, SECTIONS[1:] + (None,))
                if s in page.ids]
    problems += [f"section {s}: no 'not produced by this run'" for s, body in zip(SECTIONS, sections)
                 if "not produced by this run" not in body]
    return problems + ([f"images: {page.images}"] if page.images else [])


def expect_bad(page, text, status, stderr):
    problems = [] if status == 1 else [f"report_index.py exited with {status}, not 1"]
    for needle in (r"verification\.json:4:1: not valid JSON", r"paper_claims\.json: missing key 'rows'"):
        if not re.search(needle, stderr) or not re.search(needle.replace("'", "&#x27;"), text):
            problems.append(f"not named on stderr and in the page: {needle}")
    return problems


def expect_render(reports):
    """scripts/render-report on the fixture's page: passes; then with a PNG that
    exists but does not decode, fails naming it (only Chromium can tell). 77
    (ctest's skip) when chromium is not installed."""
    render = [os.path.join(SCRIPTS, "render-report"), reports]
    run = subprocess.run(render, capture_output=True, text=True)
    if run.returncode == 77:
        print("check_report_index: chromium is not installed: skipped")
        sys.exit(77)
    problems = [] if run.returncode == 0 and "image check: all 2 images loaded" in run.stdout else [
        f"render-report on the fixture: exit {run.returncode}: {run.stdout} {run.stderr}"]
    if not os.path.isfile(os.path.join(reports, "index.png")):
        problems.append("render-report wrote no index.png")
    with open(os.path.join(reports, "plot.png"), "wb") as f:
        f.write(b"not a PNG")
    run = subprocess.run(render, capture_output=True, text=True)
    if run.returncode != 1 or "1 of 2 failed: plot.png" not in run.stdout:
        problems.append(f"render-report with an undecodable plot.png: exit {run.returncode}: {run.stdout}")
    return problems


def run_fixture(args):
    reports = os.path.join(args.work, "reports")
    shutil.rmtree(reports, ignore_errors=True)
    if args.expect == "missing":
        os.makedirs(reports)
    else:
        shutil.copytree(args.fixture, reports)
    run = subprocess.run([sys.executable, os.path.join(HERE, "report_index.py"), reports], capture_output=True,
                         text=True)
    page_path = os.path.join(reports, "index.html")
    if not os.path.isfile(page_path):
        return [f"no page written (exit {run.returncode}): {run.stderr}"]
    problems, page, text = check_page(page_path)
    if args.expect == "render":
        return problems + expect_full(page, text, run.returncode, run.stderr) + expect_render(reports)
    expect = {"full": expect_full, "missing": expect_missing, "bad": expect_bad}[args.expect]
    return problems + expect(page, text, run.returncode, run.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--page")
    mode.add_argument("--image-check", metavar="DOM")
    mode.add_argument("--fixture")
    ap.add_argument("--work")
    ap.add_argument("--expect", choices=("full", "missing", "bad", "render"), default="full")
    args = ap.parse_args()
    if args.image_check:
        dom = sys.stdin.read() if args.image_check == "-" else open(args.image_check, encoding="utf-8").read()
        verdict = Page(dom).image_check
        print(f"image check: {verdict if verdict is not None else 'no #image-check element'}")
        return 0 if verdict and re.match(r"all \d+ images loaded$", verdict.strip()) else 1
    if args.fixture and not args.work:
        ap.error("--fixture needs --work")
    problems = check_page(args.page)[0] if args.page else run_fixture(args)
    for p in problems:
        print(f"check_report_index: {p}")
    if problems:
        return 1
    print(f"check_report_index: PASS ({args.page or args.expect})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
