"""The report's comparison figures are small multiples with direct labels (issue 44): one panel per strategy,
no legend box, identical lines drawn once under one label; and on real logs it times scans, not odometry
steps."""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import accuracy, configurations, step_series  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402


def accuracy_rows():
    """fastslam2 with nn and known association on a clean and a cluttered world: known association ignores
    clutter, so its two lines hold the same values seed by seed."""
    out = []
    for assoc in ("nn", "known"):
        for clutter in (0.0, 1.0):
            for particles in (10, 100):
                for seed in (1, 2, 3):
                    ate = (0.2 if assoc == "known" else 0.5 + clutter) * 10 / particles + 0.01 * seed
                    out.append({"key": f"{assoc}-{clutter}-{particles}-{seed}", "status": "ok", "filter": "fastslam2",
                                "map": "tree", "assoc": assoc, "particles": particles, "clutter": clutter, "seed": seed,
                                "scenario": f"w{clutter}.scn", "ate_rmse_m": ate, "landmark_rmse_m": ate / 2})
    return ar.pd.DataFrame(out)


def drawn(module, df, tmp_path, monkeypatch):
    """The figure module.make draws, kept open, with the sections it returns."""
    figures = []
    save = ar.save_figure
    monkeypatch.setattr(ar, "save_figure", lambda fig, out, name: figures.append(fig) or save(fig, out, name))
    monkeypatch.setattr(ar.plt, "close", lambda fig=None: None)
    sections = module.make(df, str(tmp_path))
    return figures[0], sections


def test_accuracy_draws_one_panel_per_strategy_labelled_at_the_line_ends(tmp_path, monkeypatch):
    fig, sections = drawn(accuracy, accuracy_rows(), tmp_path, monkeypatch)
    panels = [ax for ax in fig.axes if ax.get_title()]
    assert [ax.get_title() for ax in panels] == ["nn", "known (oracle)"]  # the oracle last, and marked
    assert all(ax.get_legend() is None for ax in fig.axes)
    labels = {ax.get_title(): sorted(t.get_text().replace("\n", " ") for t in ax.texts) for ax in panels}
    assert labels["nn"] == ["clutter = 0 /scan", "clutter = 1 /scan"]
    # The two known-association lines are one, and its label says for which worlds.
    assert labels["known (oracle)"] == ["clutter = 0, 1 /scan (identical)"]
    assert "known, clutter = 0, 1 /scan (identical)" in sections[0].text
    # Panels compare on one axis: the ATE row shares its y range.
    assert panels[0].get_ylim() == panels[1].get_ylim()


def test_per_scan_time_adds_the_odometry_steps_before_each_scan():
    steps = ar.pd.DataFrame({"time_s": [0.1, 0.2, 0.3, 0.4, 0.5], "step_time_s": [1.0, 2.0, 4.0, 8.0, 16.0],
                             "scan": [0, 0, 1, 1, 0]})
    scans = step_series.per_scan_times(steps)
    assert scans["time_s"].tolist() == [0.3, 0.4]
    assert scans["scan_time_s"].tolist() == [7.0, 8.0]  # the last step follows every scan: no scan's work
    assert step_series.per_scan_times(steps.drop(columns="scan")) is None


def real_log_rows():
    """Two back ends on a log with ten steps per scan, as `arbor run` records them since the scan column."""
    return ar.pd.DataFrame([{"key": m, "status": "ok", "filter": "fastslam2", "map": m, "assoc": "nn", "particles": 10,
                             "seed": 1, "scenario": "park.scn", "dataset": "park.scn", "ate_rmse_m": 3.0,
                             "steps": 1000, "scans": 100, "step_time_median_s": 1e-5, "scan_time_median_s": t,
                             "scan_time_p90_s": 2 * t, "run_dir": f"runs/{m}"}
                            for m, t in (("tree", 1e-3), ("naive", 3e-3))])


def test_the_table_gives_the_time_per_scan_on_a_real_log():
    frame, _, _, _ = configurations.table(real_log_rows())
    assert "time per step (ms)" not in frame
    # The back ends agree (one row), and each one's time per scan is given, not the 0.01 ms per step.
    assert frame["time per scan (ms)"].tolist() == ["naive 3, tree 1"]
    assert frame["p90 time per scan (ms)"].tolist() == ["naive 6, tree 2"]
    text = configurations.make(real_log_rows(), "unused")[0].text
    assert "These logs have 10 steps per scan" in text


def test_the_step_series_times_scans_where_steps_csv_marks_them(tmp_path):
    df = real_log_rows()
    for m in ("tree", "naive"):
        run = tmp_path / "runs" / m
        run.mkdir(parents=True)
        lines = ["step,time_s,step_time_s,n_eff,resampled,landmarks,hypotheses,nees,relocalized,scan"]
        for k in range(40):  # a scan every fourth step, whose step takes 3 ms after three of 1 ms
            scan = k % 4 == 3
            lines.append(f"{k},{0.1 * k},{0.003 if scan else 0.001},5,0,3,0,,0,{int(scan)}")
        (run / "steps.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    (tmp_path / "results.jsonl").write_text("".join(json.dumps(r) + "\n" for r in df.to_dict("records")))
    sections = step_series.make(ar.load_results(str(tmp_path)), str(tmp_path), str(tmp_path))
    assert sections[0].title == "Time per scan and effective sample size over time"
    assert "| tree | 10 | 6 | 6 | 1 | 3 |" in sections[0].text  # 6 ms a scan; 1 ms the median step, 3 its p95


def test_the_nees_curves_are_one_panel_per_strategy_sharing_one_axis(tmp_path, monkeypatch):
    from arbor_analysis import consistency
    rows = []
    for filter_ in ("fastslam1", "fastslam2"):
        for assoc, growth in (("nn", 10.0), ("known", 1.0)):
            key = f"{filter_}-{assoc}"
            run = tmp_path / key
            run.mkdir()
            nees = "\n".join(f"{k},{0.1 * k},{1 + growth * k / 10}" for k in range(10))
            (run / "steps.csv").write_text("step,time_s,nees\n" + nees + "\n", encoding="utf-8")
            rows.append({"key": key, "status": "ok", "filter": filter_, "assoc": assoc, "particles": 10, "seed": 1,
                         "scenario": "w.scn", "run_dir": key, "nees_in_band_fraction": 0.9, "nees_median": 2.0})
    figures = []
    monkeypatch.setattr(ar, "save_figure", lambda fig, out, name: figures.append(fig))
    consistency.make(ar.pd.DataFrame(rows), str(tmp_path), str(tmp_path))
    panels = [ax for ax in figures[0].axes if ax.get_title()]
    assert [ax.get_title() for ax in panels] == ["nn", "known (oracle)"]
    assert panels[0].get_ylim() == panels[1].get_ylim()  # nn's larger NEES is on known's axis too
    assert all(ax.get_legend() is None for ax in panels)
    assert sorted(t.get_text() for t in panels[1].texts) == ["fastslam1 (1 run)", "fastslam2 (1 run)"]
