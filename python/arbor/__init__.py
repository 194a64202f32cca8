"""Arbor from Python: the same engine, options and files as the `arbor` command line, on numpy arrays.

    import arbor
    scenario = arbor.simulate(world="clustered", landmarks=250, steps=300, clutter=2, seed=1)
    result = arbor.run(scenario, filter="fastslam2", map="trie", assoc="jcbb", particles=100, seed=1)
    print(result.ate_rmse_m, result.assoc_f1)      # every field of result.json is an attribute
    result.trajectory                              # N x 4 array: t, x, y, theta (the particles' mean path)
    result.to_dir("out/run")                       # the files `arbor run --out out/run` writes

Keyword options are the command line's, with "_" for "-" (`known_gate=0.999` is `--known-gate=0.999`); they
are parsed by the same code, so names, defaults and checks are the CLI's and a bad one raises
arbor.InputError with the CLI's message. The long calls release the GIL and run on the engine's TBB threads;
Ctrl-C ends them with KeyboardInterrupt. `smooth`, `associate`, `sweep` and `convert` run the `arbor` program
of the same build (`arbor.executable()`) and read back its files.
"""

# Imports under private names: `from arbor import *`, dir(arbor) and tab completion offer the API only.
import contextlib as _contextlib
import inspect as _inspect
import json as _json
import os as _os
import re as _re
import subprocess as _subprocess
import tempfile as _tempfile

import numpy as _np

import arbor_files as _files  # beside this package (build/python, or site-packages): shared with analysis/

from ._arbor import InputError, Scenario, association_strategies, filters, map_backends
from . import _arbor
from . import _options

__all__ = ["InputError", "Scenario", "Result", "Filter", "simulate", "run", "smooth", "associate", "sweep",
           "convert", "cli", "executable", "map_backends", "association_strategies", "filters"]

__version__ = _arbor.__version__  # PEP 440, the build's commit as the local label: 0.1+g2b1f81d


def _arguments(options):
    """Keyword options as command-line arguments: x_y=v -> --x-y=v; True -> --x-y; False and None -> left out;
    a list or tuple -> --x-y v1 v2 ..."""
    out = []
    for key, value in options.items():
        name = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            out.append(name)
        elif isinstance(value, (list, tuple, _np.ndarray)):
            out.append(name)
            out.extend(repr(float(v)) if isinstance(v, float) else str(v) for v in value)
        else:
            out.append(f"{name}={repr(value) if isinstance(value, float) else value}")
    return out


def simulate(**options):
    """A simulated scenario, as `arbor simulate` writes it (world=, landmarks=, steps=, clutter=, seed=, ...)."""
    return _arbor._simulate(_arguments(options))


def _from_arrays(times, controls, measurements=None, *, like=None, scans=None, truth_poses=None,
                 truth_landmarks=None, metadata=None):
    """A scenario from your own data.

    times (T), controls (T x 3, in the motion model of `like`); measurements: a dict of equal-length arrays
    'step' (the index into times), 'range' [m], 'bearing' [rad] and optionally 'truth_id'; scans (T bool):
    steps that end with a scan, needed only for scans without measurements; truth_poses (T x 3, NaN rows where
    unknown); truth_landmarks (L x 3: id, x, y). The motion and sensor models, the initial pose and the start
    time come from `like` (default: a simulated scenario's odometry and sensor models at the origin).
    Values outside the limits of docs/scenario_format.md raise InputError naming the array and element.
    """
    if like is None:
        like = _default_header()
    return Scenario._from_arrays(like, _np.asarray(times, dtype=float), _np.asarray(controls, dtype=float), scans,
                                 measurements, truth_poses, truth_landmarks, metadata or {})


Scenario.from_arrays = staticmethod(_from_arrays)

_header = None


def _default_header():
    global _header
    if _header is None:
        _header = simulate(steps=1, landmarks=1)
    return _header


class Result:
    """One run: `metrics` (result.json as a dict; its fields are also attributes), `trajectory` (the weighted
    mean of the particles' whole paths, what ate_rmse_m scores), `best_trajectory` (the best particle's path,
    which `map` belongs to) and `trajectory_mean` (the causal weighted mean; each N x 4: t, x, y, theta), `map` (dict: id, mean K x 2, covariance K x 2 x 2, log_odds,
    confirmed), `steps` (dict of per-step arrays: time_s, step_time_s, n_eff, resampled, landmarks,
    hypotheses, nees, scan; with record_lineage=True also ancestor_age_s, NaN where the paths share no pose
    and between scans). Arrays are copied once out of the engine."""

    def __init__(self, output):
        self._output = output
        self.metrics = _json.loads(output.result_json)
        self.trajectory = output.trajectory
        self.best_trajectory = output.best_trajectory
        self.trajectory_mean = output.trajectory_mean
        self.map = output.map
        self.steps = output.steps

    def __getattr__(self, name):
        metrics = self.__dict__.get("metrics", {})
        if name in metrics:
            return metrics[name]
        raise AttributeError(f"Result has no field {name!r}; result.json has: {', '.join(sorted(metrics))}")

    def __dir__(self):
        """The result.json fields too, so that dir() and tab completion offer them."""
        return sorted(set(super().__dir__()) | set(self.__dict__.get("metrics", {})))

    def to_dir(self, path):
        """Writes the files `arbor run --out PATH` writes (result.json last)."""
        self._output.to_dir(_os.fspath(path))

    def __repr__(self):
        m = self.metrics
        c = m.get("config", {})
        return (f"<arbor.Result {c.get('filter')}/{c.get('map')}/{c.get('assoc')} particles={c.get('particles')} "
                f"seed={c.get('seed')}: ATE {m.get('ate_rmse_m')} m, F1 {m.get('assoc_f1')}>")


@_contextlib.contextmanager
def _keyword_fields(options):
    """An InputError about an option names it as the caller spelt it: close_loops, not --close-loops's name."""
    try:
        yield
    except InputError as error:
        keyword = str(getattr(error, "field", "")).replace("-", "_")
        if keyword in options:
            error.field = keyword
        raise


def run(scenario, **options):
    """Runs FastSLAM over a Scenario (or a scenario file's path) with `arbor run`'s options (filter=, map=,
    assoc=, particles=, seed=, threads=, likelihood=, ...); returns a Result. With out=DIR it also writes the
    run's files there, as `arbor run --out DIR` does. An option left out takes the command line's default."""
    _options.check_keywords("run", options, _options.RUN_KEYWORDS)
    if not isinstance(scenario, Scenario):
        options.setdefault("scenario", _os.fspath(scenario))
        scenario = Scenario.load(_os.fspath(scenario))
    with _keyword_fields(options):
        return Result(_arbor._run(scenario, _arguments(options)))


class Filter:
    """The engine one step at a time, for your own loop or data source:

        f = arbor.Filter(scenario, filter="fastslam2", map="tree", assoc="nn", particles=50, seed=3)
        f.step(time, control, ranges, bearings)     # one control, then (if ranges) a scan
        poses, weights = f.particles()

    `scenario` supplies the motion and sensor models and the initial pose; its steps are not used."""

    def __init__(self, scenario, **options):
        """A filter over `scenario`'s models and initial pose, with arbor.run's options (but out=)."""
        _options.check_keywords("Filter", options, _options.FILTER_KEYWORDS)
        with _keyword_fields(options):
            self._filter = _arbor._Filter(scenario, _arguments(options))

    def step(self, time, control, ranges=(), bearings=(), *, scan=None, truth_pose=None):
        """Moves every particle through `control` to `time`, then, when there are measurements (or scan=True:
        a scan that saw nothing), associates and updates."""
        ranges = _np.asarray(ranges, dtype=float)
        self._filter.step(float(time), _np.asarray(control, dtype=float), ranges,
                          _np.asarray(bearings, dtype=float), bool(scan if scan is not None else ranges.size > 0),
                          truth_pose)

    def particles(self):
        """(poses M x 3, weights M), in particle order."""
        return self._filter.particles()

    def estimate(self):
        """(mean 3, covariance 3 x 3) of the particles' weighted pose."""
        return self._filter.estimate()

    def best_map(self):
        """The best particle's landmarks, provisional ones included (see `confirmed`)."""
        return self._filter.best_map()

    def best_trajectory(self):
        return self._filter.best_trajectory()

    def path_mean_trajectory(self):
        """The weighted mean of every particle's whole path under the current weights (what a run reports)."""
        return self._filter.path_mean_trajectory()

    def last_step(self):
        """What the last step did: n_eff, resampled, hypotheses, budget_exhausted, landmarks, relocalized."""
        return self._filter.last_step()


def _with_run_options(function, first, options, returns):
    """Gives `function` (which takes **options) the options' keyword signature and their docs, for help(),
    inspect.signature and the completion of editors that run the code; the stub gives type checkers the same."""
    function.__signature__ = _options.signature(first, options, returns)
    function.__doc__ = _inspect.cleandoc(function.__doc__) + "\n\n" + _options.options_doc(options)


_SCENARIO = _inspect.Parameter("scenario", _inspect.Parameter.POSITIONAL_OR_KEYWORD,
                               annotation="Scenario | str | os.PathLike")
_with_run_options(run, [_SCENARIO], _options.RUN_KEYWORDS, Result)
_with_run_options(Filter.__init__, [_inspect.Parameter("self", _inspect.Parameter.POSITIONAL_OR_KEYWORD), _SCENARIO],
                  _options.FILTER_KEYWORDS, None)


# ---- The rest of the command line, through the program of this build ---------------------------------------

def executable():
    """The `arbor` program of this module's build: $ARBOR_EXECUTABLE, else the copy `pip install` puts in the
    package, else the build tree's bin/arbor."""
    here = _os.path.dirname(_os.path.abspath(__file__))
    installed = _os.path.join(here, "bin", "arbor")
    path = _os.environ.get("ARBOR_EXECUTABLE") or (installed if _os.path.exists(installed)
                                                   else _os.path.join(here, "..", "..", "bin", "arbor"))
    return _os.path.normpath(path)


def cli(*args, check=True):
    """Runs `arbor ARGS...`; returns its CompletedProcess (stdout and stderr as text). A failure raises
    InputError (exit status 2: bad input or options) or RuntimeError (status 1) with the program's message."""
    # errors="replace": a message may quote input bytes that are not UTF-8 (a 0xFF in a scenario file).
    proc = _subprocess.run([executable(), *map(str, args)], capture_output=True, text=True, errors="replace")
    if check and proc.returncode != 0:
        message = proc.stderr.strip().removeprefix("arbor: error: ").removeprefix("arbor: failed: ")
        if proc.returncode != 2:
            raise RuntimeError(message)
        raise _input_error(message)
    return proc


# The program's error line, as core/io/input_error.h writes it: [FILE[:LINE]: ][field 'NAME': ]MESSAGE, or
# CLI11's --option: MESSAGE.
_ERROR_LINE = _re.compile(r"^(?:(?P<file>[^\n]*?)(?::(?P<line>\d+))?: )?field '(?P<field>[^']*)': |^(?P<option>--[\w-]+): ")


def _input_error(message):
    """InputError with the file, line and field the program's message names, as the in-process calls give them."""
    error = InputError(message)
    match = _ERROR_LINE.match(message)
    error.file = (match.group("file") or "") if match else ""
    error.line = int(match.group("line") or 0) if match else 0
    error.field = (match.group("field") or (match.group("option") or "").lstrip("-")) if match else ""
    return error


def _scenario_path(scenario, tmp):
    if isinstance(scenario, Scenario):
        path = _os.path.join(tmp, "scenario.scn")
        scenario.save(path)
        return path
    return _os.fspath(scenario)


def smooth(scenario, associations="known", out=None, **options):
    """The Ceres full-SLAM smoother (`arbor smooth`): associations "known", a Result's directory, or a run
    directory. Returns (result.json as a dict, trajectory N x 4, map dict of columns)."""
    with _tempfile.TemporaryDirectory() as tmp:
        out = _os.fspath(out) if out else _os.path.join(tmp, "smooth")
        cli("smooth", "--scenario", _scenario_path(scenario, tmp), "--associations", _os.fspath(associations),
            "--out", out, *_arguments(options))
        return (_files.read_result(out), _files.read_tum(_os.path.join(out, "trajectory.tum")),
                _files.read_map(_os.path.join(out, "map.csv")))


def associate(problem, assoc="jcbb", **options):
    """Solves one association problem file (`arbor associate --problem FILE`); returns the command's output."""
    return cli("associate", "--problem", _os.fspath(problem), "--assoc", assoc, *_arguments(options)).stdout


def convert(source, out, **options):
    """`arbor convert --from SOURCE --out OUT ...`; returns the Scenario it wrote."""
    cli("convert", "--from", source, "--out", _os.fspath(out), *_arguments(options))
    return Scenario.load(_os.fspath(out))


def sweep(spec, out, jobs=1, **options):
    """Runs a sweep spec (`arbor sweep SPEC --out OUT --jobs J`, resumable); returns results.csv as a list of
    dicts (analysis/arbor_analysis/results.py reads it into pandas)."""
    cli("sweep", _os.fspath(spec), "--out", _os.fspath(out), "--jobs", jobs, *_arguments(options))
    return _files.read_rows(_os.path.join(_os.fspath(out), "results.csv"))
