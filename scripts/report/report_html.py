"""HTML building blocks of reports/index.html (scripts/report/report_index.py): escaped
text, tables, number formatting, a small Markdown subset (the studies'
summary.md), and reading the JSON inputs so that a missing file and a broken
one are told apart. Standard library only (/usr/bin/python3, no network).

Every piece of text that comes from a file goes through esc() (html.escape with
quotes), so a check's "why" or a claim's note cannot inject markup."""
import html
import json
import math
import os
import re

NOT_PRODUCED = "not produced by this run"


class InputError(Exception):
    """A file that exists but cannot be used: the message names the file and the
    line (JSON syntax) or key (missing field)."""


def esc(value):
    return html.escape(str(value), quote=True)


def num(value, digits=4):
    """A measured value for a table: 4 significant digits; the strings C++ writes
    for NaN and infinities (verification.schema.json) are shown as they are."""
    if isinstance(value, bool) or value is None:
        return esc("—" if value is None else value)
    if isinstance(value, int):
        return str(value)  # counts in full, not 1.234e+04
    if isinstance(value, float):
        if not math.isfinite(value):
            return esc(str(value))
        return esc(f"{value:.{digits}g}")
    if isinstance(value, list):
        return esc("[" + ", ".join(f"{v:.{digits}g}" if isinstance(v, (int, float)) else str(v) for v in value) + "]")
    return esc(value)


def load_json(reports, relative):
    """The parsed file REPORTS/RELATIVE, None if it does not exist; InputError
    (file and line) if it is not valid JSON."""
    path = os.path.join(reports, relative)
    if not os.path.isfile(path):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}:{e.lineno}:{e.colno}: not valid JSON: {e.msg}") from e
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot be read: {e}") from e


def missing(what):
    """The paragraph a section shows when its input is absent."""
    return f'<p class="missing">{esc(what)}: {NOT_PRODUCED}.</p>'


def table(headers, rows, numeric=(), cls=None, row_classes=None):
    """A <table>: HEADERS as text; ROWS of cells that are already HTML (use esc()
    or num()); column indices in NUMERIC right-aligned; ROW_CLASSES optional,
    one class (or None) per row."""
    attr = f' class="{esc(cls)}"' if cls else ""
    out = [f"<table{attr}><thead><tr>"]
    out += [f'<th{" class=num" if i in numeric else ""}>{esc(h)}</th>' for i, h in enumerate(headers)]
    out.append("</tr></thead><tbody>")
    for k, row in enumerate(rows):
        rc = row_classes[k] if row_classes else None
        out.append(f'<tr class="{esc(rc)}">' if rc else "<tr>")
        out += [f'<td{" class=num" if i in numeric else ""}>{cell}</td>' for i, cell in enumerate(row)]
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def inline_markdown(text):
    """**bold** and `code` on escaped text (escaping first, so the tags added
    here are the only markup)."""
    t = esc(text)
    t = re.sub(r"`([^`]+)`", r"<code>\1</code>", t)
    return re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", t)


def _markdown_table(lines):
    cells = [[c.strip() for c in line.strip().strip("|").split("|")] for line in lines]
    header, align = cells[0], cells[1] if len(cells) > 1 else []
    numeric = {i for i, a in enumerate(align) if a.endswith(":")}
    body = [[inline_markdown(c) for c in row] for row in cells[2:]]
    return '<div class="wide">' + table(header, body, numeric=numeric) + "</div>"


def markdown(text, heading_offset=2):
    """The Markdown that hofem's scripts write (summary.md): headings, pipe
    tables, "- " lists and paragraphs; headings shifted down HEADING_OFFSET
    levels to sit under the page's own."""
    out, block, kind = [], [], None

    def flush():
        nonlocal block, kind
        if kind == "table":
            out.append(_markdown_table(block))
        elif kind == "list":
            out.append("<ul>" + "".join(f"<li>{inline_markdown(b[2:])}</li>" for b in block) + "</ul>")
        elif kind == "para":
            out.append("<p>" + inline_markdown(" ".join(block)) + "</p>")
        block, kind = [], None

    for line in text.splitlines():
        stripped = line.strip()
        heading = re.match(r"^(#{1,6})\s+(.*)$", stripped)
        new_kind = ("table" if stripped.startswith("|") else "list" if stripped.startswith("- ")
                    else None if not stripped or heading else "para")
        if new_kind != kind or heading or not stripped:
            flush()
        if heading:
            level = min(6, len(heading.group(1)) + heading_offset)
            out.append(f"<h{level}>{inline_markdown(heading.group(2))}</h{level}>")
        elif new_kind:
            kind = new_kind
            block.append(stripped)
    flush()
    return "\n".join(out)
