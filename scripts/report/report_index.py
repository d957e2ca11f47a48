#!/usr/bin/python3
"""reports/index.html: one static page with what the main job found, to open in
a browser from the file system (no server, no network: inline CSS and script,
relative links only). In this order:

1. provenance (the `context` block of verification.json, core/provenance) and
   the main job's seconds per stage (run_timings.json);
2. the verification summary: the failed checks first (measured, threshold,
   why), then the groups' counts, then each group's checks in a <details>;
3. the seeds' claims table (paper_claims.json, scripts/claims/paper_claims.py);
4. each study's work-precision plot and summary (studies/NAME/);
5. the benchmark headline figures (scripts/report/report_headlines.py);
6. every other PNG under the directory, in a grid.

A section whose input is absent says "not produced by this run"; an input that
exists but cannot be read (bad JSON, a missing key) is named in its section and
on stderr, and the exit status is 1 (the page is written all the same). An
inline script checks that every image loaded and writes the verdict into the
element #image-check, which scripts/render-report reads from headless Chromium.

Usage: report_index.py REPORTS_DIR   (writes REPORTS_DIR/index.html)
Standard library only; Debian's /usr/bin/python3 or any Python 3.9+."""
import os
import sys
import time
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# claims_size describes a claims row's size; it lives with the claims table in scripts/claims/.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "claims"))
from claims_size import describe as describe_size  # noqa: E402
from report_headlines import fastest_solver_rows, floor_rows, scene_rows, time_to_error_rows  # noqa: E402
from report_html import InputError, esc, load_json, markdown, missing, num, table  # noqa: E402

# The main job's budget after the build (DEVELOPERS.md, "Budgets").
BUDGET_SECONDS = 900
PAGE_NAME = "index.html"
SCREENSHOT_NAME = "index.png"  # scripts/render-report's picture of this page: not one of the report's images

CSS = """
body { font: 14px/1.4 system-ui, sans-serif; margin: 1.5em auto; max-width: 1240px; color: #222; padding: 0 1em; }
h1 { font-size: 1.6em; } h2 { border-bottom: 2px solid #ccc; margin-top: 2em; } h3 { margin-top: 1.4em; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 2px 6px; vertical-align: top; text-align: left; }
th { background: #f0f0f0; } td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.fail td, .fail { background: #fde0dc; } .ok { color: #1b5e20; }
p.missing, p.error { color: #8a4b00; font-style: italic; }
p.error { color: #b00020; } .wide { overflow-x: auto; } code { background: #f4f4f4; padding: 0 2px; }
details { margin: 2px 0; } summary { cursor: pointer; } details.group { margin-left: 1.5em; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(380px, 1fr)); gap: 12px; align-items: start; }
table.groups { width: 100%; margin: 0; } table.claims { table-layout: fixed; width: 100%; overflow-wrap: anywhere; }
table.claims th:nth-child(1) { width: 13%; } table.claims th:nth-child(2) { width: 8%; }
table.claims th:nth-child(3), table.claims th:nth-child(7) { width: 15%; } table.claims th:nth-child(8) { width: 5.5%; }
table.claims th:nth-child(4), table.claims th:nth-child(5), table.claims th:nth-child(6) { width: 6%; }
figure { margin: 0; border: 1px solid #ddd; padding: 4px; } figure img, .study img { max-width: 100%; }
figcaption { font-size: 12px; color: #555; word-break: break-all; } nav a { margin-right: 1em; }
"""

# After every image has loaded or failed (the window's load event), count those
# that have pixels (naturalWidth > 0) and write the verdict where a reader and
# scripts/render-report (Chromium's --dump-dom) can see it.
IMAGE_CHECK = """<script>
window.addEventListener("load", function () {
  var images = Array.prototype.slice.call(document.images);
  var failed = images.filter(function (im) { return !(im.complete && im.naturalWidth > 0); });
  var out = document.getElementById("image-check");
  out.textContent = failed.length === 0 ? "all " + images.length + " images loaded"
    : failed.length + " of " + images.length + " failed: "
      + failed.map(function (im) { return im.getAttribute("src"); }).join(", ");
  out.className = failed.length === 0 ? "ok" : "fail";
});
</script>"""

SECTIONS = (("provenance", "Provenance and timing"), ("verification", "Verification"),
            ("claims", "The seeds' claims"), ("studies", "Studies: work against precision"),
            ("benchmarks", "Benchmark headline figures"), ("images", "All other plots and pictures"))


def src(relative):
    """A relative URL for a file under the reports directory (the page sits at its top)."""
    return esc(urllib.parse.quote(relative.replace(os.sep, "/")))


def link_if_present(reports, relative, text=None):
    if not os.path.isfile(os.path.join(reports, relative)):
        return esc(text or relative)
    return f'<a href="{src(relative)}">{esc(text or relative)}</a>'


def provenance_section(reports, shown, errors):
    out = []
    report = load_json(reports, "verification.json")
    ctx = report.get("context") if report else None
    if not ctx:
        out.append(missing("provenance (the context block of verification.json)"))
    else:
        commit = ctx["commit"][:12] + (" (dirty: uncommitted changes)" if ctx["dirty"] else "")
        fields = (("commit", commit), ("hofem version", ctx["hofem_version"]), ("date (UTC)", ctx["date"]),
                  ("build type", ctx["build_type"]), ("compiler", ctx["compiler"]), ("flags", ctx["flags"]),
                  ("machine", f"{ctx['hostname']}: {ctx['cpu']}, {ctx['cores']} cores"),
                  ("threads", ctx["threads"]), ("convergence preset", ctx["preset"]))
        out.append(table(("what", "value"), [(esc(k), esc(v)) for k, v in fields], cls="provenance"))
    timings = load_json(reports, "run_timings.json")
    if timings is None:
        out.append(missing("the main job's timing (run_timings.json)"))
    else:
        total = timings["total"]
        stages = [(esc(k), num(v)) for k, v in timings.items() if k != "total"]
        out.append(f"<p>Main job after the build: <strong>{num(total)} s</strong> (budget {BUDGET_SECONDS} s, "
                   f"DEVELOPERS.md){' <span class=fail>over budget</span>' if total > BUDGET_SECONDS else ''}.</p>")
        out.append(table(("stage", "seconds"), stages, numeric={1}))
    return "\n".join(out)


def verification_section(reports, shown, errors):
    report = load_json(reports, "verification.json")
    if report is None:
        return missing("the verification report (verification.json)")
    rows = report["rows"]
    failed = [r for r in rows if not r["pass"]]
    groups = {}
    for r in rows:
        groups.setdefault(r["group"], []).append(r)

    def check_cells(r):
        return (esc(r["name"]), num(r["measured"]), esc(r["compare"]) + " " + num(r["threshold"]),
                esc("pass" if r["pass"] else "FAIL"), esc(r["why"]))

    out = [f"<p><strong>{len(rows)} checks: {len(rows) - len(failed)} passed, {len(failed)} failed</strong> "
           f"({link_if_present(reports, 'verification.json')}).</p>", '<h3 id="failures">Failed checks</h3>']
    if failed:
        out.append(table(("group", "check", "measured", "threshold", "verdict", "why"),
                         [(esc(r["group"]),) + check_cells(r) for r in failed], numeric={2, 3}, cls="failures"))
    else:
        out.append('<p class="ok">No check failed.</p>')
    return "\n".join(out + group_tables(groups, check_cells))


def group_tables(groups, check_cells):
    """Groups by family (the group's first part: basis, mms, ...), families and
    groups with failures first: a small table of counts per family side by side,
    then each family's groups in a <details>, each group's checks in another."""
    out = []
    families = {}
    for g in groups:
        families.setdefault(g.split(".")[0], []).append(g)
    failures = lambda names: sum(not r["pass"] for g in names for r in groups[g])
    order = sorted(families, key=lambda f: (-failures(families[f]), f))
    for f in order:
        families[f].sort(key=lambda g: (-failures([g]), g))
    out.append('<h3>Groups</h3><div class="grid" id="groups">')
    for f in order:
        counts = [(f'<a href="#group-{esc(g)}">{esc(g)}</a>', num(len(groups[g])),
                   num(len(groups[g]) - failures([g])), num(failures([g]))) for g in families[f]]
        out.append(table(("group", "checks", "passed", "failed"), counts, numeric={1, 2, 3}, cls="groups",
                         row_classes=["fail" if c[3] != "0" else None for c in counts]))
    out.append("</div>")
    for f in order:
        names = families[f]
        checks_in = sum(len(groups[g]) for g in names)
        out.append(f'<details class="family"{" open" if failures(names) else ""}><summary>{esc(f)}: {len(names)} '
                   f"groups, {checks_in} checks, {failures(names)} failed</summary>")
        for g in names:
            checks = sorted(groups[g], key=lambda r: r["pass"])  # stable: the failures first, then file order
            bad = failures([g])
            out.append(f'<details class="group" id="group-{esc(g)}"{" open" if bad else ""}><summary>{esc(g)}: '
                       f"{len(checks)} checks, {bad} failed</summary>")
            out.append(table(("check", "measured", "threshold", "verdict", "why"), [check_cells(r) for r in checks],
                             numeric={1, 2}, row_classes=[None if r["pass"] else "fail" for r in checks]))
            out.append("</details>")
        out.append("</details>")
    return out


def size_note(size):
    """A claims row's size for its note (claims_size.py; a table written before
    sizes were recorded says only which job ran it)."""
    if isinstance(size, dict):
        return f" Size: {describe_size(size)}."
    return f" Size: {size}." if size else ""


def claims_section(reports, shown, errors):
    claims = load_json(reports, "paper_claims.json")
    if claims is None:
        return missing("the seeds' claims table (paper_claims.json)")
    rows = claims["rows"]
    agree = sum(bool(r["agrees"]) for r in rows)
    full = os.path.isfile(os.path.join(reports, "full", "paper_claims.md"))
    out = [f"<p><strong>{agree} of {len(rows)} rows agree</strong> with the seeds "
           f"({link_if_present(reports, 'paper_claims.md')}; each criterion was written before its measurement, "
           "scripts/claims/paper_claims.py)"
           + (f"; the full-size studies' rows: {link_if_present(reports, 'full/paper_claims.md')}" if full else "")
           + ".</p>"]
    cells = [(esc(r["id"]), esc(r["source"]), esc(r["quantity"]), num(r["paper_value"]), num(r["measured"]),
              esc(r["unit"]), esc(r["criterion"]), esc("yes" if r["agrees"] else "no"),
              esc(r["note"] + size_note(r.get("size")))) for r in rows]
    out.append('<div class="wide">' + table(("id", "source", "quantity", "paper", "hofem", "unit", "criterion",
                                             "agrees", "note"), cells, numeric={3, 4}, cls="claims",
                                            row_classes=[None if r["agrees"] else "fail" for r in rows]) + "</div>")
    if claims.get("skipped"):
        out.append(f"<p>Skipped: {esc(', '.join(map(str, claims['skipped'])))}.</p>")
    return "\n".join(out)


def studies_section(reports, shown, errors):
    root = os.path.join(reports, "studies")
    names = sorted(n for n in os.listdir(root) if os.path.isdir(os.path.join(root, n))) if os.path.isdir(root) else []
    if not names:
        return missing("the studies (studies/NAME/)")
    out = []
    for name in names:
        out.append(f'<div class="study"><h3 id="study-{esc(name)}">{esc(name)}</h3>')
        picture = f"studies/{name}/work_precision.png"
        if os.path.isfile(os.path.join(reports, picture)):
            shown.add(picture)
            out.append(f'<a href="{src(picture)}"><img src="{src(picture)}" alt="{esc(name)}: work-precision"></a>')
        else:
            out.append(missing(picture))
        summary = os.path.join(reports, "studies", name, "summary.md")
        if os.path.isfile(summary):
            with open(summary, encoding="utf-8") as f:
                out.append(markdown(f.read(), heading_offset=3))
        else:
            out.append(missing(f"studies/{name}/summary.md"))
        out.append("</div>")
    return "\n".join(out)


def benchmarks_section(reports, shown, errors):
    rows, out = [], []
    for source, rows_of in (("time_to_error.json", time_to_error_rows), ("solver_benchmarks.json", fastest_solver_rows),
                            ("benchmarks.json", floor_rows), ("scenes/*/stats.json", scene_rows)):
        try:  # one broken file leaves the other figures standing
            found = rows_of(reports)
        except InputError as e:
            errors.append(str(e))
            out.append(f'<p class="error">{esc(e)}</p>')
            continue
        except (KeyError, TypeError, ValueError, ZeroDivisionError) as e:
            errors.append(f"{os.path.join(reports, source)}: {describe(e)}")
            out.append(f'<p class="error">{esc(errors[-1])}</p>')
            continue
        if not found:
            out.append(missing(source))
        rows += found
    if rows:
        out.insert(0, table(("figure", "value", "against / context", "file"),
                            [tuple(esc(c) for c in r) for r in rows], cls="headlines"))
    return "\n".join(out)


def images_section(reports, shown, errors):
    pictures = []
    for folder, dirs, files in os.walk(reports):
        dirs.sort()
        for f in sorted(files):
            relative = os.path.relpath(os.path.join(folder, f), reports).replace(os.sep, "/")
            if f.lower().endswith(".png") and relative not in shown and relative != SCREENSHOT_NAME:
                pictures.append(relative)
    if not pictures:
        return missing("plots and pictures (*.png)")
    figures = [f'<figure><a href="{src(p)}"><img src="{src(p)}" alt="{esc(p)}"></a><figcaption>{esc(p)}'
               "</figcaption></figure>" for p in pictures]
    return f"<p>{len(pictures)} pictures.</p>\n" + '<div class="grid">' + "\n".join(figures) + "</div>"


BUILDERS = {"provenance": provenance_section, "verification": verification_section, "claims": claims_section,
            "studies": studies_section, "benchmarks": benchmarks_section, "images": images_section}
SOURCES = {"provenance": "verification.json, run_timings.json", "verification": "verification.json",
           "claims": "paper_claims.json", "studies": "studies/", "benchmarks": "the benchmark files",
           "images": "*.png"}


def describe(error):
    """What was wrong with a file's content: the missing key by name."""
    if isinstance(error, KeyError):
        return f"missing key {error.args[0]!r}"
    return f"unexpected content: {type(error).__name__}: {error}"


def build_page(reports):
    """The page's HTML and the list of input errors."""
    shown, errors, parts = set(), [], []
    for key, title in SECTIONS:
        try:
            body = BUILDERS[key](reports, shown, errors)
        except InputError as e:
            errors.append(str(e))
            body = f'<p class="error">{esc(e)}</p>'
        except (KeyError, TypeError, ValueError, AttributeError) as e:
            message = f"{os.path.join(reports, SOURCES[key])}: {describe(e)}"
            errors.append(message)
            body = f'<p class="error">{esc(message)}</p>'
        parts.append(f'<section id="{key}"><h2>{esc(title)}</h2>\n{body}\n</section>')
    nav = " ".join(f'<a href="#{key}">{esc(title)}</a>' for key, title in SECTIONS)
    page = ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>hofem: the main job's report</title><style>{CSS}</style></head><body>\n"
            "<h1>hofem: the main job's report</h1>\n"
            "<p>Written by scripts/report/report_index.py from the files beside this page. "
            "Images: <span id=\"image-check\">not checked (the check needs JavaScript)</span>.</p>\n"
            f"<nav>{nav}</nav>\n" + "\n".join(parts) + f"\n{IMAGE_CHECK}\n</body></html>\n")
    return page, errors


def main(argv):
    if len(argv) != 2 or argv[1].startswith("-"):
        print("usage: report_index.py REPORTS_DIR   (writes REPORTS_DIR/index.html)", file=sys.stderr)
        return 2
    reports = argv[1]
    if not os.path.isdir(reports):
        print(f"report_index: {reports}: no such directory", file=sys.stderr)
        return 2
    start = time.monotonic()
    page, errors = build_page(reports)
    out = os.path.join(reports, PAGE_NAME)
    partial = f"{out}.partial-{os.getpid()}"  # renamed when complete: a killed run leaves no half page
    with open(partial, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(partial, out)
    errors = list(dict.fromkeys(errors))  # a file two sections read is named once
    for e in errors:
        print(f"report_index: error: {e}", file=sys.stderr)
    print(f"report_index: wrote {out} ({len(page) / 1e3:.0f} kB, {page.count('<img ')} images, "
          f"{len(errors)} unreadable inputs) in {time.monotonic() - start:.2f} s")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
