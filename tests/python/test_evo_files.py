"""The TUM files of a run directory as evo reads them (docs/evo.md): trajectory.tum, trajectory_best.tum,
trajectory_mean.tum and reference.tum meet evo's rules (tum_rules.py), and reference.tum is the reference result.json's ATE uses."""
import pathlib

import numpy as np
import pytest

import arbor
import arbor_files
from tum_rules import tum_violations

REPO = pathlib.Path(__file__).resolve().parents[2]


def test_the_rules_refuse_what_evo_refuses():
    """The checker below must be able to fail: each file here is one evo refuses."""
    assert tum_violations("# t x y z qx qy qz qw\n0 1 2 0 0 0 0 1\n0.5 1 2 0 0 0 0.6 0.8\n") == []
    refused = {
        "a repeated time (issue 44's two rows at t = 0)": "0 0 0 0 0 0 0 1\n0 1 0 0 0 0 0 1\n",
        "time going back": "1 0 0 0 0 0 0 1\n0.5 0 0 0 0 0 0 1\n",
        "seven fields": "0 0 0 0 0 0 1\n",
        "a trailing space": "0 0 0 0 0 0 0 1 \n",
        "a double space": "0  0 0 0 0 0 0 1\n",
        "tabs": "0\t0\t0\t0\t0\t0\t0\t1\n",
        "commas": "0,0,0,0,0,0,0,1\n",
        "a word": "0 x 0 0 0 0 0 1\n",
        "nan": "0 nan 0 0 0 0 0 1\n",
        "a blank line": "0 0 0 0 0 0 0 1\n\n1 0 0 0 0 0 0 1\n",
        "a quaternion that is not unit": "0 0 0 0 0 0 0 2\n",
        "a comment not at the line's start": " # note\n0 0 0 0 0 0 0 1\n",
        "no pose": "# t x y z qx qy qz qw\n",
    }
    for why, text in refused.items():
        assert tum_violations(text), why


def assert_evo_reads(directory, *names):
    for name in names:
        assert tum_violations((directory / name).read_text(), name) == [], name


def aligned_rmse(estimate, reference):
    """RMSE of the positions after the least-squares rigid fit of estimate onto reference (what evo_ape -a
    computes, Umeyama's alignment, reduced to the plane); both N x 2, paired row by row."""
    a, b = estimate - estimate.mean(axis=0), reference - reference.mean(axis=0)
    theta = np.arctan2(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), np.sum(a * b))
    rotation = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    return np.sqrt(np.mean(np.sum((a @ rotation.T - b) ** 2, axis=1)))


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    path = tmp_path_factory.mktemp("evo") / "sim.scn"
    arbor.cli("simulate", "--world", "clustered", "--landmarks", 60, "--steps", 60, "--clutter", 1, "--seed", 7,
              "--out", path)
    return path


def test_a_run_writes_evo_ready_trajectories_and_the_reference(simulated, tmp_path):
    """trajectory.tum had two rows at t = 0 (the initial pose and the first scan's), which evo refuses, and no
    reference was written, so evo_ape could not be run on a result directory."""
    scenario = arbor.Scenario.load(simulated)
    assert scenario.times[0] == scenario.start_time  # the case that wrote t = 0 twice
    out = tmp_path / "run"
    arbor.cli("run", "--scenario", simulated, "--assoc", "nn", "--particles", 10, "--seed", 1, "--out", out,
              "--quiet")
    assert_evo_reads(out, "trajectory.tum", "trajectory_best.tum", "trajectory_mean.tum", "reference.tum")

    reference = arbor_files.read_tum(out / "reference.tum")
    np.testing.assert_allclose(reference[:, 0], scenario.times)
    np.testing.assert_allclose(reference[:, 1:], scenario.truth_poses, atol=1e-12)

    # evo_ape pairs equal times: without -a that is result.json's ATE, with -a its aligned ATE (docs/evo.md).
    estimate = arbor_files.read_tum(out / "trajectory.tum")
    paired = np.isin(estimate[:, 0], reference[:, 0])
    assert paired.sum() == len(reference)
    errors = estimate[paired, 1:3] - reference[:, 1:3]
    result = arbor_files.read_result(out)
    assert np.sqrt(np.mean(np.sum(errors ** 2, axis=1))) == pytest.approx(result["ate_rmse_m"], rel=1e-6)
    assert aligned_rmse(estimate[paired, 1:3], reference[:, 1:3]) == pytest.approx(result["ate_aligned_rmse_m"],
                                                                                     rel=1e-6)
    best = arbor_files.read_tum(out / "trajectory_best.tum")
    assert aligned_rmse(best[np.isin(best[:, 0], reference[:, 0]), 1:3], reference[:, 1:3]) == pytest.approx(
        result["ate_best_aligned_rmse_m"], rel=1e-6)


def test_the_python_run_and_the_smoother_write_the_reference_too(simulated, tmp_path):
    arbor.run(simulated, assoc="nn", particles=5, seed=1).to_dir(tmp_path / "py")
    assert_evo_reads(tmp_path / "py", "trajectory.tum", "trajectory_mean.tum", "reference.tum")
    arbor.smooth(simulated, out=tmp_path / "smooth")
    assert_evo_reads(tmp_path / "smooth", "trajectory.tum", "reference.tum")
    assert (tmp_path / "smooth" / "reference.tum").read_bytes() == (tmp_path / "py" / "reference.tum").read_bytes()


def test_the_reference_of_real_data_is_its_gps_track(tmp_path):
    """Victoria Park has no truth poses; its reference is the GPS track, the ATE's too, without a heading."""
    arbor.cli("convert", "--from", "victoria-park", "--input", REPO / "tests" / "data" / "victoria_park",
              "--out", tmp_path / "vp.scn")
    scenario = arbor.Scenario.load(tmp_path / "vp.scn")
    assert len(scenario.gps) > 0 and np.isnan(scenario.truth_poses).all()
    arbor.cli("run", "--scenario", tmp_path / "vp.scn", "--assoc", "nn", "--particles", 5, "--out",
              tmp_path / "run", "--quiet")
    assert_evo_reads(tmp_path / "run", "trajectory.tum", "trajectory_mean.tum", "reference.tum")
    reference = np.loadtxt(tmp_path / "run" / "reference.tum", comments="#", ndmin=2)
    times, last = np.unique(scenario.gps[:, 0][::-1], return_index=True)  # the last fix of a repeated time
    np.testing.assert_allclose(reference[:, :3], np.column_stack([times, scenario.gps[::-1][last, 1:]]))
    np.testing.assert_array_equal(reference[:, 3:], np.tile([0, 0, 0, 0, 1], (len(reference), 1)))


def test_a_scenario_without_a_reference_leaves_none_behind(simulated, tmp_path):
    """A directory reused for a scenario without truth must not keep the previous scenario's reference."""
    scenario = arbor.Scenario.load(simulated)
    out = tmp_path / "run"
    arbor.run(scenario, assoc="nn", particles=5).to_dir(out)
    assert (out / "reference.tum").exists()
    no_truth = arbor.Scenario.from_arrays(scenario.times, scenario.controls, scenario.measurements, like=scenario)
    arbor.run(no_truth, assoc="nn", particles=5).to_dir(out)
    assert not (out / "reference.tum").exists()
    assert_evo_reads(out, "trajectory.tum", "trajectory_mean.tum")
