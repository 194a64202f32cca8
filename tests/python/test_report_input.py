"""analysis/report on results it cannot read (issue 45): a cut row, a byte that is not UTF-8 or a missing
directory is an error naming the file (and line), exit 2, and the previous report does not stay behind looking
current; a sweep that kept only some metrics still gets its report."""
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import results as ar  # noqa: E402
from arbor_analysis import dataset_accuracy  # noqa: E402


def report(results):
    return subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "report"), str(results)],
                          capture_output=True, text=True, timeout=300)


def fixture_copy(tmp_path):
    results = tmp_path / "results"
    shutil.copytree(os.path.join(ROOT, "tests", "data", "results_fixture"), results, symlinks=True)
    (results / "report").mkdir()
    (results / "report" / "report.html").write_text("<p>an old report</p>", encoding="utf-8")
    return results


def test_a_cut_row_names_its_line_and_leaves_no_old_report(tmp_path):
    results = fixture_copy(tmp_path)
    rows = (results / "results.jsonl").read_text(encoding="utf-8").split("\n")
    rows[2] = rows[2][: len(rows[2]) // 2]  # a row cut in the middle, with rows after it
    (results / "results.jsonl").write_text("\n".join(rows), encoding="utf-8")
    done = report(results)
    assert done.returncode == 2, done.stderr
    assert "results.jsonl:3: not a JSON row" in done.stderr and "Traceback" not in done.stderr
    assert not (results / "report" / "report.html").exists()


def test_a_byte_that_is_not_utf8_is_an_error_not_a_traceback(tmp_path):
    results = fixture_copy(tmp_path)
    with open(results / "results.jsonl", "ab") as f:
        f.write(b'{"key": "\xff"}\n')
    done = report(results)
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert "results" in done.stderr


def test_a_missing_directory_is_an_error_not_a_traceback(tmp_path):
    done = report(tmp_path / "nowhere")
    assert done.returncode == 2 and "Traceback" not in done.stderr and "nowhere" in done.stderr, done.stderr


def test_a_dataset_table_needs_no_wall_time():
    rows = ar.pd.DataFrame([{"filter": "fastslam2", "map": "tree", "assoc": "jcbb", "particles": 100, "seed": s,
                             "ate_rmse_m": 1.0 + s, "dead_reckoning_ate_m": 9.0} for s in (1, 2, 3)])
    table = dataset_accuracy.table_for(rows)
    assert len(table) == 1 and "wall time (s)" not in table.columns
