"""The report as one self-contained HTML file (report.html beside report.md): figures embedded as data URIs,
tables sortable by a click on their header with a few lines of inline script, no network and nothing but the
standard library. It renders the subset of Markdown the report's sections use: headings, paragraphs, bullet
lists, pipe tables, fenced code, images, **bold** and `code`."""

import base64
import html
import os
import re

STYLE = """
body { font-family: sans-serif; max-width: 72em; margin: 2em auto; padding: 0 1em; line-height: 1.4; color: #222; }
h1 { border-bottom: 2px solid #446; } h2 { border-bottom: 1px solid #ccd; margin-top: 2em; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccd; padding: 0.25em 0.6em; text-align: left; }
th { background: #eef; cursor: pointer; user-select: none; } th:hover { background: #dde; }
tr:nth-child(even) td { background: #f8f8fc; }
img { max-width: 100%; display: block; margin: 1em 0; }
code { background: #f2f2f6; padding: 0 0.2em; }
pre { background: #f2f2f6; padding: 0.5em 1em; overflow-x: auto; font-size: 0.85em; }
"""

# Records on <body> how many figures the browser decoded and how many tables are empty, and sorts a table by
# the clicked column: numerically where both cells start with a number, else as text; a second click reverses.
SCRIPT = """
window.addEventListener('load', function () {
  // What a browser test reads back (tests/experiments/analysis_test.cc): figures decoded, tables not empty.
  var images = Array.prototype.slice.call(document.images);
  var loaded = images.filter(function (img) { return img.complete && img.naturalWidth > 0; }).length;
  document.body.dataset.imagesLoaded = loaded;
  document.body.dataset.imagesBroken = images.length - loaded;
  document.body.dataset.emptyTables = Array.prototype.slice.call(document.querySelectorAll('table'))
    .filter(function (t) { return !t.tBodies.length || t.tBodies[0].rows.length === 0; }).length;
});
document.querySelectorAll('table').forEach(function (table) {
  table.querySelectorAll('th').forEach(function (th, column) {
    th.title = 'sort by this column';
    th.addEventListener('click', function () {
      var body = table.tBodies[0], rows = Array.prototype.slice.call(body.rows);
      var up = th.dataset.order !== 'up'; th.dataset.order = up ? 'up' : 'down';
      var key = function (row) { var t = row.cells[column].textContent.trim(); var n = parseFloat(t);
                                 return isNaN(n) ? t : n; };
      rows.sort(function (a, b) { var x = key(a), y = key(b);
        var c = (typeof x === 'number' && typeof y === 'number') ? x - y : String(x).localeCompare(String(y));
        return up ? c : -c; });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
"""


# A backslash escape of Markdown (results.md_text writes them): the character as text.
ESCAPE = re.compile(r"\\([\\`*\[\]!|<>])")
# The report embeds only the figures it drew: image files inside its own directory, of bounded size.
FIGURE_KINDS = {".png": "png", ".svg": "svg+xml"}
MAX_FIGURE_BYTES = 16 << 20


def inline(text):
    """Escapes text and renders **bold** and `code`; a backslash-escaped character is text, never markup."""
    parts = ESCAPE.split(text)  # even indices: text with markup; odd: escaped characters
    out = []
    for k, part in enumerate(parts):
        if k % 2:
            out.append(html.escape(part, quote=False))
            continue
        part = html.escape(part, quote=False)
        part = re.sub(r"`([^`]+)`", r"<code>\1</code>", part)
        out.append(re.sub(r"\*\*([^*]+)\*\*", r"<strong>\1</strong>", part))
    return "".join(out)


def own_figure(path, base_dir):
    """The file `path` names when it is one of the report's figures (a PNG or SVG file inside base_dir, links
    resolved, under MAX_FIGURE_BYTES), else None."""
    root = os.path.realpath(base_dir)
    full = os.path.realpath(os.path.join(root, path))
    if os.path.commonpath([root, full]) != root or os.path.splitext(full)[1].lower() not in FIGURE_KINDS:
        return None
    if not os.path.isfile(full) or os.path.getsize(full) > MAX_FIGURE_BYTES:
        return None
    return full


def image(alt, path, base_dir):
    """An <img> with the figure embedded; anything else is said in words (never a broken image, never a file
    that is not the report's own figure)."""
    full = own_figure(path, base_dir)
    if full is None:
        return f"<p><em>(figure {html.escape(path)} is missing or not one of this report's figures)</em></p>"
    with open(full, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    kind = FIGURE_KINDS[os.path.splitext(full)[1].lower()]
    return f'<img alt="{html.escape(alt)}" src="data:image/{kind};base64,{data}">'


def fence_of(line):
    """The backtick run that opens a code fence on this line ("" if none): three or more."""
    run = len(line) - len(line.lstrip("`"))
    return line[:run] if run >= 3 else ""


def table(lines):
    cells = [[c.strip() for c in line.strip().strip("|").split("|")] for line in lines]
    head, body = cells[0], [r for r in cells[2:]]
    out = ["<table><thead><tr>" + "".join(f"<th>{inline(c)}</th>" for c in head) + "</tr></thead><tbody>"]
    out += ["<tr>" + "".join(f"<td>{inline(c)}</td>" for c in row) + "</tr>" for row in body]
    return "\n".join(out + ["</tbody></table>"])


def markdown_to_html(text, base_dir):
    """The report's Markdown subset as HTML."""
    out, lines, i = [], text.split("\n"), 0
    while i < len(lines):
        line = lines[i]
        if not line.strip():
            i += 1
        elif fence_of(line):
            # Closed only by a line of backticks at least as long as the opening (CommonMark), so a spec whose
            # text holds a fence of its own (results.code_block) cannot close it.
            fence = fence_of(line)
            j = i + 1
            while j < len(lines) and not (lines[j].strip().startswith(fence) and set(lines[j].strip()) == {"`"}):
                j += 1
            out.append("<pre>" + html.escape("\n".join(lines[i + 1:j]), quote=False) + "</pre>")
            i = j + 1
        elif line.startswith("#"):
            level = len(line) - len(line.lstrip("#"))
            out.append(f"<h{level}>{inline(line[level:].strip())}</h{level}>")
            i += 1
        elif line.startswith("|"):
            j = i
            while j < len(lines) and lines[j].startswith("|"):
                j += 1
            out.append(table(lines[i:j]))
            i = j
        elif re.fullmatch(r"!\[[^\]]*\]\([^)]+\)", line.strip()):
            alt, path = re.fullmatch(r"!\[([^\]]*)\]\(([^)]+)\)", line.strip()).groups()
            out.append(image(alt, path, base_dir))
            i += 1
        elif line.startswith("- "):
            items = []
            while i < len(lines) and lines[i].startswith("- "):
                items.append(f"<li>{inline(lines[i][2:])}</li>")
                i += 1
            out.append("<ul>" + "".join(items) + "</ul>")
        else:
            j = i + 1  # a paragraph holds at least its first line (a lone "![" once looped forever here)
            while j < len(lines) and lines[j].strip() and not lines[j].startswith(("#", "|", "- ", "![", "```")):
                j += 1
            out.append("<p>" + inline(" ".join(lines[i:j])) + "</p>")
            i = j
    return "\n".join(out)


def write(markdown, out_dir, title):
    """Writes out_dir/report.html from the report's Markdown (figure paths relative to out_dir)."""
    page = (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{html.escape(title)}</title>"
            f"<style>{STYLE}</style></head><body>\n{markdown_to_html(markdown, out_dir)}\n"
            f"<script>{SCRIPT}</script></body></html>\n")
    path = os.path.join(out_dir, "report.html")
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)
    return path
