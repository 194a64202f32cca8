"""arbor_files (python/arbor_files.py), the one reader of Arbor's files: `import arbor` and analysis/ read
through the same source, and the copy the build puts in build/python is that source."""
import filecmp
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import results as ar  # noqa: E402  (puts python/ on the path where build/python is not)
import arbor_files  # noqa: E402

RUN = os.path.join(ROOT, "tests", "data", "results_fixture", "runs", "uniform-n100-t300-c0__smoother-s1-t1")


def test_the_module_imported_is_the_source_file_or_its_current_copy():
    source = os.path.join(ROOT, "python", "arbor_files.py")
    assert filecmp.cmp(arbor_files.__file__, source, shallow=False), f"{arbor_files.__file__} is stale"


def test_analysis_frames_hold_what_the_reader_returns():
    tum = arbor_files.read_tum(os.path.join(RUN, "trajectory.tum"))
    assert tum.shape[1] == 4 and np.allclose(tum[0], [0.0, 10.314, 0.193, np.pi / 2])
    assert np.array_equal(ar.read_tum(os.path.join(RUN, "trajectory.tum")).to_numpy(), tum)
    columns = arbor_files.read_map(os.path.join(RUN, "map.csv"))
    frame = ar.read_map_csv(os.path.join(RUN, "map.csv"))
    assert np.array_equal(frame["x"].to_numpy(), columns["x"]) and list(frame.columns) == list(columns)


def test_rows_of_a_cut_log_end_at_the_last_newline(tmp_path):
    (tmp_path / "results.jsonl").write_text('{"key": "a", "ate_rmse_m": 1.5}\n{"key": "b", "ate_', encoding="utf-8")
    assert arbor_files.read_rows(str(tmp_path)) == [{"key": "a", "ate_rmse_m": 1.5}]
    assert list(ar.load_results(str(tmp_path))["key"]) == ["a"]


def test_a_result_from_before_issue_42_reads_under_the_options_own_names(tmp_path):
    (tmp_path / "result.json").write_text('{"config": {"gate_probability": 0.95, "log_odds_confirm": 2.0, '
                                          '"seed": 3}, "ate_rmse_m": 0.5}', encoding="utf-8")
    config = arbor_files.read_result(str(tmp_path))["config"]
    assert config == {"chi2": 0.95, "confirm": 2.0, "seed": 3}
