"""The Python API (python/arbor): the same engine, options, files and errors as the command line."""
import os
import subprocess
import threading
import time
import _thread

import numpy as np
import pytest

import arbor

RUN = dict(filter="fastslam2", map="trie", assoc="jcbb", particles=20, seed=3)


@pytest.fixture(scope="module")
def scenario():
    return arbor.simulate(world="clustered", landmarks=60, steps=60, clutter=1, seed=7)


def read(path):
    with open(path, "rb") as f:
        return f.read()


def without_step_time(path):
    """steps.csv without its step_time_s column (wall-clock time differs from run to run)."""
    return [line.split(",")[:2] + line.split(",")[3:] for line in read(path).decode().splitlines()]


def test_variant_names_are_the_command_lines(scenario):
    help_text = arbor.cli("run", "--help").stdout
    assert arbor.map_backends() == ["naive", "tree", "trie"]
    assert "Map back end: " + ", ".join(arbor.map_backends()) in help_text
    assert "Data association: " + ", ".join(arbor.association_strategies()) in help_text


def test_simulate_writes_the_same_scenario_as_the_cli(scenario, tmp_path):
    arbor.cli("simulate", "--world", "clustered", "--landmarks", 60, "--steps", 60, "--clutter", 1, "--seed", 7,
              "--out", tmp_path / "cli.scn")
    scenario.save(tmp_path / "py.scn")
    assert read(tmp_path / "py.scn") == read(tmp_path / "cli.scn")


def test_run_writes_the_same_bytes_as_arbor_run(scenario, tmp_path):
    scenario.save(tmp_path / "s.scn")
    arbor.cli("run", "--scenario", tmp_path / "s.scn", "--out", tmp_path / "cli", "--quiet",
              *arbor._arguments(RUN))
    result = arbor.run(scenario, **RUN)
    result.to_dir(tmp_path / "py")
    for name in ["trajectory.tum", "trajectory_mean.tum", "map.csv", "associations.csv"]:
        assert read(tmp_path / "py" / name) == read(tmp_path / "cli" / name), name
    assert without_step_time(tmp_path / "py" / "steps.csv") == without_step_time(tmp_path / "cli" / "steps.csv")
    assert result.landmarks == len(result.map["id"]) > 0
    assert result.trajectory.shape == (len(scenario) + 1, 4)
    assert len(result.steps["n_eff"]) == len(scenario)


def test_the_lineage_is_a_step_array_only_when_asked_for(tmp_path):
    scenario = arbor.simulate(world="uniform", landmarks=60, steps=200, seed=7)  # long enough for paths to meet
    plain, recorded = arbor.run(scenario, **RUN), arbor.run(scenario, record_lineage=True, **RUN)
    assert "ancestor_age_s" not in plain.steps
    assert np.array_equal(plain.trajectory, recorded.trajectory)
    ages, scans = recorded.steps["ancestor_age_s"], recorded.steps["scan"]
    assert np.isnan(ages[~scans]).all()
    known = ages[~np.isnan(ages)]
    assert len(known) > 0
    assert (known >= 0).all() and (known <= recorded.steps["time_s"][-1]).all()
    recorded.to_dir(tmp_path / "run")
    csv = read(tmp_path / "run" / "steps.csv").decode().splitlines()
    assert csv[0].endswith(",scan,ancestor_age_s")
    cells = [line.split(",")[-1] for line in csv[1:]]
    assert [cell == "" for cell in cells] == list(np.isnan(ages))
    assert [float(cell) for cell in cells if cell] == list(known)


def test_results_do_not_depend_on_the_thread_count(scenario):
    one, two = arbor.run(scenario, threads=1, **RUN), arbor.run(scenario, threads=2, **RUN)
    assert np.array_equal(one.trajectory, two.trajectory)
    assert np.array_equal(one.map["covariance"], two.map["covariance"])


def test_the_step_interface_reproduces_a_run(scenario):
    result = arbor.run(scenario, **RUN)
    f = arbor.Filter(scenario, **RUN)
    z = scenario.measurements
    for k, (t, u, scan) in enumerate(zip(scenario.times, scenario.controls, scenario.scans)):
        mine = z["step"] == k
        f.step(t, u, z["range"][mine], z["bearing"][mine], scan=scan)
    assert np.array_equal(f.path_mean_trajectory(), result.trajectory)
    assert np.array_equal(f.best_trajectory(), result.best_trajectory)
    confirmed = f.best_map()["confirmed"]
    assert np.array_equal(f.best_map()["mean"][confirmed], result.map["mean"])
    poses, weights = f.particles()
    assert poses.shape == (RUN["particles"], 3) and weights.sum() == pytest.approx(1.0)
    assert f.last_step()["landmarks"] == len(confirmed)


def test_a_scenario_from_arrays_runs_like_the_original(scenario):
    copy = arbor.Scenario.from_arrays(scenario.times, scenario.controls, scenario.measurements, like=scenario,
                                      scans=scenario.scans, truth_poses=scenario.truth_poses,
                                      truth_landmarks=scenario.truth_landmarks)
    a, b = arbor.run(scenario, **RUN), arbor.run(copy, **RUN)
    assert np.array_equal(a.trajectory, b.trajectory)
    assert a.ate_rmse_m == b.ate_rmse_m and a.assoc_f1 == b.assoc_f1


def test_bad_input_raises_input_error_naming_the_field(scenario, tmp_path):
    with pytest.raises(arbor.InputError, match="particles"):
        arbor.run(scenario, particles=0)
    with pytest.raises(arbor.InputError, match="moon"):
        arbor.simulate(world="moon")
    with pytest.raises(arbor.InputError, match="no_such_option"):
        arbor.run(scenario, no_such_option=1)
    z = dict(scenario.measurements)
    z["range"] = z["range"].copy()
    z["range"][5] = -1.0
    with pytest.raises(arbor.InputError, match=r"measurements\['range'\]\[5\]"):
        arbor.Scenario.from_arrays(scenario.times, scenario.controls, z, like=scenario)
    bad = tmp_path / "bad.scn"
    bad.write_text(read_text_with_a_bad_range(scenario, tmp_path))
    with pytest.raises(arbor.InputError) as error:
        arbor.Scenario.load(bad)
    assert error.value.file == str(bad) and error.value.line > 0 and error.value.field == "range"


def test_a_bad_keyword_is_named_as_the_field(scenario, tmp_path):
    """A misspelt keyword was reported as "--asoc=jcbb", filter=True as "--scenario=- not in {...}" and help=True
    with CLI11's internal message, each with an empty field; a garbage prior map passed to Filter was ignored."""
    for options, field, message in [(dict(asoc="jcbb"), "asoc", "did you mean assoc="),
                                    (dict(filter=True), "filter", "needs a value"),
                                    (dict(help=True), "help", "not an option"),
                                    (dict(chi2=2), "chi2", "chi2"),
                                    (dict(assoc="known", close_loops=True), "close_loops", "does not apply")]:
        with pytest.raises(arbor.InputError, match=message) as error:
            arbor.run(scenario, **options)
        assert error.value.field == field, options
        with pytest.raises(arbor.InputError) as error:
            arbor.Filter(scenario, **options)
        assert error.value.field == field, options
    garbage = tmp_path / "map.csv"
    garbage.write_text("not a map\n")
    with pytest.raises(arbor.InputError) as error:
        arbor.Filter(scenario, prior_map=str(garbage), **RUN)
    assert error.value.file == str(garbage) and error.value.line == 1


def test_the_program_backed_calls_name_file_line_and_field(scenario, tmp_path):
    """arbor.smooth, convert and the other calls that run the program raised InputError with its message only;
    they now carry the file, line and field it names, as the in-process calls do."""
    bad = tmp_path / "bad.scn"
    bad.write_text(read_text_with_a_bad_range(scenario, tmp_path))
    with pytest.raises(arbor.InputError) as error:
        arbor.smooth(bad)
    assert error.value.file == str(bad) and error.value.line > 0 and error.value.field == "range"
    with pytest.raises(arbor.InputError) as error:
        arbor.cli("simulate", "--landmarks", "0", "--out", tmp_path / "s.scn")
    assert error.value.field == "landmarks", str(error.value)


def test_a_byte_that_is_not_utf8_is_an_input_error(scenario, tmp_path):
    """A 0xFF byte in a scenario file raised UnicodeDecodeError: the error quoted the line, and the quote could
    not become a Python string."""
    scenario.save(tmp_path / "good.scn")
    data = (tmp_path / "good.scn").read_bytes()
    cut = data.index(b"\nz ") + 1
    (tmp_path / "bad.scn").write_bytes(data[:cut] + b"\xff\xfe garbage\n" + data[cut:])
    with pytest.raises(arbor.InputError) as error:
        arbor.Scenario.load(tmp_path / "bad.scn")
    assert error.value.file == str(tmp_path / "bad.scn") and error.value.line > 1
    with pytest.raises(arbor.InputError) as error:  # the program-backed calls too
        arbor.smooth(tmp_path / "bad.scn")
    assert error.value.file == str(tmp_path / "bad.scn") and error.value.line > 1


def test_every_listed_filter_runs(scenario):
    """arbor.filters() is the filter list of the build (variants/filter_list.h), as `arbor run --filter` offers it."""
    help_text = arbor.cli("run", "--help").stdout
    for name in arbor.filters():
        assert name in help_text
        try:  # a filter without particles or map back ends (EKF-SLAM) refuses those options by name
            result = arbor.run(scenario, **dict(RUN, filter=name, assoc="known", particles=5))
        except arbor.InputError as e:
            assert "does not apply to --filter " + name in str(e)
            result = arbor.run(scenario, filter=name, assoc="known", seed=3)
        assert result.config["filter"] == name


def read_text_with_a_bad_range(scenario, tmp_path):
    scenario.save(tmp_path / "good.scn")
    lines = (tmp_path / "good.scn").read_text().splitlines(keepends=True)
    i = next(i for i, line in enumerate(lines) if line.startswith("z "))
    lines[i] = "z -3 0.1 - 4\n"
    return "".join(lines)


@pytest.fixture(scope="module")
def long_scenario():
    """A run of it takes minutes (4000 scans, 100 particles, JCBB in clutter)."""
    return arbor.simulate(world="clustered", landmarks=400, steps=4000, clutter=2, seed=1)


LONG_RUN = dict(filter="fastslam2", map="tree", assoc="jcbb", particles=100, seed=1)


def test_long_calls_release_the_gil():
    about_a_second = arbor.simulate(world="clustered", landmarks=400, steps=300, clutter=2, seed=1)
    ticks = 0
    worker = threading.Thread(target=lambda: arbor.run(about_a_second, **LONG_RUN, threads=1))
    worker.start()
    # Ticks counted only while the run is still going. Holding the GIL through the run would let this loop
    # tick at most once or twice before the run ends, however fast or loaded the machine. (It used to wait for
    # 100 ticks of 1 ms, which a loaded machine's sleeps could stretch past the run itself.)
    while worker.is_alive() and ticks < 20:
        time.sleep(0.001)
        ticks += worker.is_alive()
    worker.join()
    assert ticks >= 20


def test_ctrl_c_interrupts_a_long_run(long_scenario, tmp_path):
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        arbor.run(long_scenario, **LONG_RUN, out=tmp_path / "run")
    timer.cancel()
    # Interrupted inside the run: a run that finished and was interrupted afterwards would have written it.
    assert not (tmp_path / "run" / "result.json").exists()


def test_smooth_and_sweep_run_the_program_of_the_same_build(scenario, tmp_path):
    result, trajectory, landmarks = arbor.smooth(scenario)
    assert trajectory.shape[1] == 4 and len(landmarks["id"]) > 0 and result["ate_rmse_m"] < 1.0
    spec = tmp_path / "tiny.toml"
    spec.write_text('[sweep]\nname = "tiny"\n[scenarios]\nworld = "uniform"\nlandmarks = 30\nsteps = 20\n'
                    '[grid]\nfilter = "fastslam2"\nmap = ["naive", "trie"]\nassoc = "nn"\nparticles = 5\n'
                    'seed = [1, 2]\nthreads = 1\n')
    rows = arbor.sweep(spec, out=tmp_path / "sweep", jobs=2)
    assert len(rows) == 4 and all(r["status"] == "ok" for r in rows)
    # A run of the sweep is the run the API makes with the same options.
    row = next(r for r in rows if r["map"] == "trie" and r["seed"] == "2")
    mine = arbor.run(tmp_path / "sweep" / row["scenario"], filter="fastslam2", map="trie", assoc="nn",
                     particles=5, seed=2)
    assert float(row["ate_rmse_m"]) == pytest.approx(mine.ate_rmse_m, rel=1e-12)


def test_the_step_interface_refuses_what_a_scenario_file_would(scenario):
    """Filter.step reads its arguments with the scenario format's limits: NaN or 1e300 controls made every pose
    and landmark NaN, and a NaN time let time go backwards afterwards."""
    f = arbor.Filter(scenario, **RUN)
    u, r, b = np.zeros(3), np.array([5.0]), np.array([0.1])
    cases = [
        (dict(time=1.0, control=[np.nan, 0, 0], ranges=r, bearings=b), "control[0]"),
        (dict(time=1.0, control=[0, 1e300, 0], ranges=r, bearings=b), "control[1]"),
        (dict(time=np.nan, control=u, ranges=r, bearings=b), "time"),
        (dict(time=1.0, control=u, ranges=np.full(20000, 5.0), bearings=np.zeros(20000)), "ranges"),
        (dict(time=1.0, control=u, ranges=r, bearings=np.array([1e300])), "bearings[0]"),
        (dict(time=1.0, control=u, ranges=r, bearings=b, truth_pose=[np.inf, 0, 0]), "truth_pose[0]"),
    ]
    for kwargs, field in cases:
        with pytest.raises(arbor.InputError) as error:
            f.step(**kwargs)
        assert error.value.field == field, kwargs
    f.step(1.0, u, r, b)  # nothing refused changed the filter
    assert np.isfinite(f.best_trajectory()).all()


def test_a_numerical_breakdown_is_an_input_error_naming_the_step(tmp_path):
    """Motion noise at the format's limit (1e6) made FastSLAM 2.0's weights NaN and aborted the interpreter
    (hostile A1); arbor.run and Filter.step raise InputError naming the step instead."""
    arbor.cli("simulate", "--landmarks", 20, "--steps", 10, "--odometry-noise", *[1e6] * 5, "--out", tmp_path / "n.scn")
    noisy = arbor.Scenario.load(tmp_path / "n.scn")
    options = dict(filter="fastslam2", assoc="nn", particles=5, seed=1)
    with pytest.raises(arbor.InputError) as error:
        arbor.run(noisy, **options)
    assert error.value.field == "step"
    f = arbor.Filter(noisy, **options)
    z = noisy.measurements
    with pytest.raises(arbor.InputError) as error:
        for k, (t, u, scan) in enumerate(zip(noisy.times, noisy.controls, noisy.scans)):
            mine = z["step"] == k
            f.step(t, u, z["range"][mine], z["bearing"][mine], scan=scan)
    assert error.value.field == "step" and "arithmetic broke down" in str(error.value)


def test_from_arrays_refuses_ids_that_are_not_ids(scenario):
    """NaN truth ids became -2147483648 and 1.5 became 1; duplicate landmark ids and bearings of 999 passed,
    and only `save` refused the scenario afterwards."""
    def with_measurement(key, value):
        z = {k: v.copy() for k, v in scenario.measurements.items()}
        z[key] = z[key].astype(float)
        z[key][0] = value
        return z

    for key, value, field in [("truth_id", np.nan, "measurements['truth_id'][0]"),
                              ("truth_id", 1.5, "measurements['truth_id'][0]"),
                              ("bearing", 999.0, "measurements['bearing'][0]")]:
        with pytest.raises(arbor.InputError) as error:
            arbor.Scenario.from_arrays(scenario.times, scenario.controls, with_measurement(key, value), like=scenario)
        assert error.value.field == field
    landmarks = scenario.truth_landmarks.copy()
    landmarks[1, 0] = landmarks[0, 0]
    with pytest.raises(arbor.InputError) as error:
        arbor.Scenario.from_arrays(scenario.times, scenario.controls, scenario.measurements, like=scenario,
                                   truth_landmarks=landmarks)
    assert error.value.field == "truth_landmarks[1, 0]"
