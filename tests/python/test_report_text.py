"""The report treats text from a spec or a results file as data (issue 45): whatever a sweep's name, description
or any metadata holds, it comes out as that text, never as Markdown or HTML structure, and the report embeds
only the figures it drew itself."""
import base64
import json
import os
import random
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import results as ar  # noqa: E402
from arbor_analysis import html_report  # noqa: E402

# Pieces a careless or hostile spec could hold: newlines that start blocks, fences, images of local files,
# table bars, HTML, Markdown emphasis, escapes.
PIECES = ["\n", "\r\n", "```", "````toml", "![a](", "/etc/hostname", ")", "](", "|", "<script>alert(1)</script>",
          "<img src=x onerror=y>", "**", "`", "[", "]", "\\", "#", "# ", "- ", " ", "x", "é", "\t", "!["]


def hostile_strings(count, seed=41):
    rng = random.Random(seed)
    return ["".join(rng.choice(PIECES) for _ in range(rng.randint(1, 12))) for _ in range(count)]


def visible_text(fragment):
    """The text a browser shows for an HTML fragment (tags dropped, entities decoded)."""
    import html
    return html.unescape(re.sub(r"<[^>]+>", "", fragment))


def test_arbitrary_text_round_trips_as_text_never_as_structure(tmp_path):
    with open(tmp_path / "fig.png", "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")  # the one figure the document below draws
    for s in hostile_strings(400):
        frame = ar.pd.DataFrame([{"configuration": s, "value": 1.5}])
        markdown = "\n".join([f"# Arbor results: {ar.md_text(s)}", "", f"- sweep **{ar.md_text(s)}**", "",
                              ar.markdown_table(frame), "", ar.code_block(s, "toml"), "", "![figure](fig.png)", ""])
        page = html_report.markdown_to_html(markdown, str(tmp_path))
        assert page.count("<img") == 1, (s, page)
        assert "<script" not in page and "onerror=y>" not in page, (s, page)
        for tag in ("<h1>", "<ul>", "<table>", "<pre>"):
            assert page.count(tag) == 1, (tag, s, page)
        assert page.count("<tr>") == 2, (s, page)  # the header and one row: a "|" in s made no column
        one_line = " ".join(s.split())
        heading = re.search(r"<h1>(.*?)</h1>", page, re.S).group(1)
        assert visible_text(heading) == f"Arbor results: {one_line}".strip(), (s, heading)
        pre = re.search(r"<pre>(.*?)</pre>", page, re.S).group(1)
        assert visible_text(pre) == s, (s, pre)


def test_a_lone_image_opener_ends():
    assert html_report.markdown_to_html("before\n![", ".") == "<p>before</p>\n<p>![</p>"


def test_only_the_reports_own_figures_are_embedded(tmp_path):
    outside = tmp_path / "secret.png"
    outside.write_bytes(b"not a figure of the report")
    report = tmp_path / "report"
    report.mkdir()
    os.symlink(outside, report / "link.png")
    for path in (str(outside), "../secret.png", "link.png", "/dev/zero", "/etc/hostname"):
        page = html_report.markdown_to_html(f"![x]({path})", str(report))
        assert "<img" not in page and "not one of this report's figures" in page, path


def test_the_report_of_a_hostile_sweep_embeds_no_local_file(tmp_path):
    results = tmp_path / "results"
    shutil.copytree(os.path.join(ROOT, "tests", "data", "results_fixture"), results, symlinks=True)
    with open(results / "sweep.json", encoding="utf-8") as f:
        manifest = json.load(f)
    secret = tmp_path / "secret.png"
    secret.write_bytes(b"SECRET-BYTES-OF-A-LOCAL-FILE")
    manifest["spec_name"] = f"x\n![a]({secret})\nend ![\n"
    with open(results / "sweep.json", "w", encoding="utf-8") as f:
        json.dump(manifest, f)
    (results / "spec.toml").write_text(f'[sweep]\ndescription = """\n```\n![b]({secret})\n```\n"""\n', encoding="utf-8")
    done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "report"), str(results)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    page = (results / "report" / "report.html").read_text(encoding="utf-8")
    assert base64.b64encode(b"SECRET-BYTES-OF-A-LOCAL-FILE").decode() not in page
    figures = [n for n in os.listdir(results / "report") if n.endswith((".png", ".svg"))]
    assert page.count("<img") == len(figures)
