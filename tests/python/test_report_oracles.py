"""The report compares strategies (issue 44): oracles (known association) and the smoother appear as references
in the per-configuration table and are never named best in "What this shows", even where they are the most
accurate; identical map back ends share one row that says so; the title is the sweep's name."""
import json
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "analysis"))

from arbor_analysis import configurations  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402

# ATE per configuration: the references are the most accurate, as they usually are.
ATE = {("smoother", None, "known"): 0.1, ("ekf", None, "known"): 0.2, ("fastslam2", "naive", "known"): 0.3,
       ("fastslam2", "tree", "known"): 0.3, ("fastslam2", "naive", "jcbb"): 0.5, ("fastslam2", "tree", "jcbb"): 0.5,
       ("fastslam2", "naive", "nn"): 0.9, ("fastslam2", "tree", "nn"): 0.9, ("ekf", None, "nn"): 0.7}


def rows(particle_counts=(10,)):
    out = []
    for (filter_, map_, assoc), ate in ATE.items():
        for seed, particles in ((s, m) for s in (1, 2, 3) for m in particle_counts):
            value = ate + 0.01 * seed
            out.append({"key": f"{filter_}-{map_}-{assoc}-{seed}-{particles}", "status": "ok", "scenario": "w.scn", "seed": seed,
                        "filter": filter_, "map": map_, "assoc": assoc,
                        "particles": None if filter_ != "fastslam2" else particles, "threads": 1,
                        "ate_rmse_m": value, "ate_aligned_rmse_m": value, "landmark_rmse_m": value,
                        "assoc_f1": 1.0 if assoc == "known" else 0.9 - value / 10, "landmarks": 50, "steps": 80,
                        "world_steps": 80, "dead_reckoning_ate_m": 5.0,
                        "step_time_median_s": 1e-4 if map_ != "tree" else 2e-4})
    return out


def write_sweep(path, name="oracle check", particle_counts=(10,)):
    path.mkdir()
    with open(path / "results.jsonl", "w", encoding="utf-8") as f:
        for r in rows(particle_counts):
            f.write(json.dumps(r) + "\n")
    (path / "spec.toml").write_text(f'[sweep]\nname = "{name}"\n', encoding="utf-8")
    return path


def test_the_summary_never_names_an_oracle_best(tmp_path):
    results = write_sweep(tmp_path / "out-folder")
    done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "report"), str(results)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    report = (results / "report" / "report.md").read_text(encoding="utf-8")
    assert report.startswith("# Arbor results: oracle check\n")  # the sweep's name, not the folder's
    summary = report.split("**What this shows**", 1)[1].split("\n\n", 2)[1]
    named = re.findall(r"\*\*([^*]+)\*\*", summary)
    assert named, summary
    for best in named:
        assert "known" not in best and "smoother" not in best and "oracle" not in best, summary
    assert "lowest SE(2)-aligned ATE RMSE: **fastslam2/jcbb**" in summary, summary
    # The table comes before the summary: the first screen holds the comparison.
    assert report.index("## Configurations") < report.index("**What this shows**")


def test_references_are_marked_and_identical_back_ends_share_a_row():
    frame = configurations.table(ar.pd.DataFrame(rows()))[0]
    roles = dict(zip(frame["filter"] + "/" + frame["assoc"], frame["role"]))
    assert roles["smoother/known"] == "reference"
    assert roles["ekf/known"] == roles["fastslam2/known"] == "oracle"
    assert roles["fastslam2/jcbb"] == roles["ekf/nn"] == "strategy"
    assert list(frame["role"]) == sorted(frame["role"], key=["strategy", "oracle", "reference"].index)
    jcbb = frame[(frame["filter"] == "fastslam2") & (frame["assoc"] == "jcbb")].iloc[0]
    assert jcbb["map"] == "naive = tree (identical)" and jcbb["runs"] == 3
    assert jcbb["time per scan (ms)"] == "naive 0.1, tree 0.2"
    ekf = frame[(frame["filter"] == "ekf") & (frame["assoc"] == "nn")].iloc[0]
    assert ekf["map"] == "–" and ekf["particles"] == "–"


def test_a_filter_without_particles_can_be_named_best(tmp_path):
    """EKF-SLAM's rows have no particle count: where it is the best real strategy, its key holds NaN, which the
    summary once failed to look up (KeyError on the main job's report)."""
    global ATE
    saved = dict(ATE)
    try:
        ATE[("ekf", None, "nn")] = 0.15
        results = write_sweep(tmp_path / "out-folder", particle_counts=(10, 100))
        done = subprocess.run([sys.executable, os.path.join(ROOT, "analysis", "report"), str(results)],
                              capture_output=True, text=True, timeout=300)
    finally:
        ATE = saved
    assert done.returncode == 0, done.stderr
    report = (results / "report" / "report.md").read_text(encoding="utf-8")
    assert "lowest SE(2)-aligned ATE RMSE: **ekf/nn**" in report, report
