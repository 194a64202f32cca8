# The typed stub of `import arbor`, for type checkers and editors. Written by hand, but for the blocks between
# "# generated: NAME" and "# end generated: NAME", which scripts/generate_python_stub.py writes from arbor.__all__
# and the run option descriptors of experiments/options/run_options.cc (tests/python/test_typing.py checks they
# are current). The docstrings of __init__.py are not copied here: editors read them from the source beside it.
import os
import subprocess
from typing import Any, Literal, TypedDict

from typing_extensions import Unpack  # in typing from Python 3.11; the package supports 3.10

import numpy as np
from numpy.typing import ArrayLike, NDArray

# generated: exports
__all__ = [
    "InputError", "Scenario", "Result", "Filter", "simulate", "run", "smooth", "associate", "sweep",
    "convert", "cli", "executable", "map_backends", "association_strategies", "filters",
]
# end generated: exports
__version__: str

_Path = str | os.PathLike[str]


class InputError(ValueError):
    """Bad input or options: the message, and the file, line and field it names (empty or 0 where none)."""
    file: str
    line: int
    field: str


class Scenario:
    """A scenario: controls, scans and (where known) ground truth (docs/scenario_format.md)."""
    @staticmethod
    def load(path: _Path) -> Scenario: ...
    def save(self, path: _Path) -> None: ...
    @staticmethod
    def from_arrays(times: ArrayLike, controls: ArrayLike, measurements: dict[str, ArrayLike] | None = None, *,
                    like: Scenario | None = None, scans: ArrayLike | None = None,
                    truth_poses: ArrayLike | None = None, truth_landmarks: ArrayLike | None = None,
                    metadata: dict[str, str] | None = None) -> Scenario: ...
    def __len__(self) -> int: ...
    @property
    def times(self) -> NDArray[np.float64]: ...
    @property
    def controls(self) -> NDArray[np.float64]: ...
    @property
    def scans(self) -> NDArray[np.bool_]: ...
    @property
    def truth_poses(self) -> NDArray[np.float64]: ...
    @property
    def measurements(self) -> dict[str, NDArray[Any]]: ...
    @property
    def truth_landmarks(self) -> NDArray[np.float64]: ...
    @property
    def gps(self) -> NDArray[np.float64]: ...
    @property
    def metadata(self) -> dict[str, str]: ...
    @property
    def sensor(self) -> dict[str, float]: ...
    @property
    def motion(self) -> str: ...
    @property
    def initial_pose(self) -> list[float]: ...
    @property
    def start_time(self) -> float: ...


class Result:
    """One run. Every field of result.json is an attribute; those below are always there (None where the
    scenario has no ground truth), the others are typed Any."""
    metrics: dict[str, Any]
    trajectory: NDArray[np.float64]
    best_trajectory: NDArray[np.float64]
    trajectory_mean: NDArray[np.float64]
    map: dict[str, NDArray[Any]]
    steps: dict[str, NDArray[Any]]
    config: dict[str, Any]
    ate_rmse_m: float | None
    landmark_rmse_m: float | None
    nees_mean: float | None
    assoc_precision: float | None
    assoc_recall: float | None
    assoc_f1: float | None
    landmarks: int
    step_time_median_s: float
    step_time_p95_s: float
    wall_time_s: float
    peak_rss_bytes: int
    def to_dir(self, path: _Path) -> None: ...
    def __getattr__(self, name: str) -> Any: ...


def simulate(**options: Any) -> Scenario: ...


def run(scenario: Scenario | _Path, **options: Unpack[_RunOptions]) -> Result: ...


class Filter:
    def __init__(self, scenario: Scenario, **options: Unpack[_FilterOptions]) -> None: ...
    def step(self, time: float, control: ArrayLike, ranges: ArrayLike = (), bearings: ArrayLike = (), *,
             scan: bool | None = None, truth_pose: ArrayLike | None = None) -> None: ...
    def particles(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def estimate(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def best_map(self) -> dict[str, NDArray[Any]]: ...
    def best_trajectory(self) -> NDArray[np.float64]: ...
    def path_mean_trajectory(self) -> NDArray[np.float64]: ...
    def last_step(self) -> dict[str, Any]: ...


def smooth(scenario: Scenario | _Path, associations: _Path = "known", out: _Path | None = None,
           **options: Any) -> tuple[dict[str, Any], Any, Any]: ...
def associate(problem: _Path, assoc: str = "jcbb", **options: Any) -> str: ...
def convert(source: str, out: _Path, **options: Any) -> Scenario: ...
def sweep(spec: _Path, out: _Path, jobs: int = 1, **options: Any) -> list[dict[str, Any]]: ...
def cli(*args: Any, check: bool = True) -> subprocess.CompletedProcess[str]: ...
def executable() -> str: ...
def map_backends() -> list[str]: ...
def association_strategies() -> list[str]: ...
def filters() -> list[str]: ...


# generated: run options
class _FilterOptions(TypedDict, total=False):
    """arbor.Filter's keywords: `arbor run`'s options, with "_" for "-" (known_gate=0.999 is --known-gate=0.999).
    One left out takes the command line's default."""
    filter: Literal["fastslam1", "fastslam2", "ekf"]
    """The filter: fastslam1 (FastSLAM 1.0: particles sampled from the motion model); fastslam2 (FastSLAM 2.0:
    particles drawn from the measurement-informed proposal); ekf (EKF-SLAM: one Gaussian over pose and map
    with the full joint covariance, O(N^2) an update; deterministic, no particles and no map back end). A
    batch filter (the smoother) runs with `arbor smooth` (default "fastslam2")"""
    map: Literal["naive", "tree", "trie"]
    """Map back end: naive, tree, trie (naive copies a particle's whole map at each resampling; tree and trie
    share it); results do not depend on it (default "trie")"""
    assoc: Literal["known", "nn", "nn-independent", "jcbb", "locality"]
    """Data association: known, nn, nn-independent, jcbb, locality (known: the oracle, pairing by the
    scenario's true ids) (default "jcbb")"""
    particles: int
    """Number of particles M (default 100)"""
    seed: int
    """Seed of every random draw of the filter (default 1)"""
    threads: int
    """Worker threads (0 = all cores); results do not depend on it (default 0)"""
    resample_threshold: float
    """Resample when N_eff < threshold * particles (default 0.5)"""
    chi2: float
    """Chi-square gate probability of the association tests (default 0.99)"""
    new_landmark_gate: float
    """A measurement outside this chi-square gate of every landmark starts a new one (default 0.999)"""
    motion_sampling: Literal["per-scan", "per-control"]
    """per-scan: carry each particle's predicted mean and covariance through every control and draw once per
    scan (the FastSLAM 2.0 proposal and the association see the whole prediction); per-control: draw at every
    control (the proposal sees only the last control's covariance; an ablation) (default "per-scan")"""
    likelihood: Literal["gaussian", "student-t"]
    """Measurement likelihood in the weights, the proposal and the landmark updates: gaussian or student-t
    (heavy tails: an outlier pulls and weighs less) (default "gaussian")"""
    student_dof: float
    """Degrees of freedom of the Student-t likelihood (default 4.0)"""
    known_gate: float
    """With --assoc known, reject (and count) a measurement outside this chi-square gate of the landmark its
    id names; 1 (the default) disables the gate: known association is the oracle (default 1.0)"""
    gate_covariance: Literal["particle", "set"]
    """Innovation covariance of every gate: particle (each particle's own) or set (plus the weighted spread of
    the landmark's predicted measurement over the particle set: the drift of a gap) (default "particle")"""
    roughen: float
    """Regularised resampling: after a resampling each particle's prediction gains the kernel (roughen *
    h_opt)^2 times the set's pose covariance (Musso et al. 2001); 0 = off, 1 = h_opt (default 0.0)"""
    weight_exponent: float
    """Tempered weights: raise each scan's importance weight to this power (1 = the paper's weights); below 1
    the set selects as if the measurements were noisier, resamples less and stays consistent (the proposal and
    the landmark updates keep the real noise). 0 = the default: 0.1 for fastslam2 with --assoc known (chosen
    on held-out calibration data), else 1 (a real strategy's wrong pairings are weeded out by the weights;
    fastslam1's weights are all that corrects its poses) (default 0.0)"""
    move_window: int
    """Resample-move: after each resampling every particle revises the poses of its last N scans by
    Metropolis-Hastings, pairings fixed and landmarks recomputed (Gilks & Berzuini 2001); 0 = off (default
    0)"""
    move_steps: int
    """Resample-move: proposals per particle and resampling (default 4)"""
    move_scale: float
    """Resample-move: the first proposal's step in prediction standard deviations (halved at each next)
    (default 1.0)"""
    max_hypotheses: int
    """Search budget of JCBB and the interpretation trees per particle and scan; a search that reaches it
    answers with its best hypothesis so far and is counted in result.json budget_exhausted (default
    1000000)"""
    max_work: int
    """Their work budget per particle and scan, in multiply-adds and candidate scans (a tree's compatibility
    test counts 16); reaching it is counted as above (default 1073741824)"""
    prune: float
    """Drop landmarks whose existence log-odds fall below this (default 0.0)"""
    confirm: float
    """A new landmark is provisional until its existence log-odds reach this (start 1, +1 per sighting, -0.5
    per miss); only confirmed landmarks make the reported map (1: every landmark at once) (default 2.0)"""
    provisional_scans: int
    """Drop a landmark still provisional this many scans after the one that started it (0: never); not with
    --assoc known (default 10)"""
    pose_from_confirmed: bool
    """Only confirmed landmarks steer the pose: a measurement paired with a provisional landmark updates it,
    but moves the pose and weighs the particle as an unpaired measurement would (for cluttered sensors); not
    with --assoc known (default False)"""
    provisional_steer_min: int
    """With --pose-from-confirmed, a scan that pairs no confirmed landmark but at least this many provisional
    ones lets them steer the pose (the second sighting of an unmapped area, above all the start; 0: never)
    (default 3)"""
    relocalize: bool
    """Relocalise a lost robot: when the best particle pairs under half a scan, search its settled map with
    the pose-free locality tree; a pose that pairs more, found again at the next scan, re-seeds every particle
    (a kidnapped robot, or a loop closure the gates miss) (default False)"""
    relocalize_min_pairings: int
    """Pairings a relocalised pose must explain (default 5)"""
    relocalize_accept: float
    """The relocalising search stops at the first pose that explains this fraction of the scan (0: it searches
    to its bound and keeps the best) (default 0.0)"""
    close_loops: bool
    """Close loops by re-sighting: a landmark confirmed inside the gate of exactly one dormant landmark
    (unpaired for --dormant-scans scans), widened by --loop-drift-m, is that landmark's drifted copy, and
    later measurements of the copy update the original; not with --assoc known (default False)"""
    dormant_scans: int
    """Scans unpaired after which a landmark is dormant (default 30)"""
    loop_drift_m: float
    """Position drift (standard deviation per axis) a loop may have built up, for --close-loops (default
    1.0)"""
    record_lineage: bool
    """Record at each scan how far back the particles' paths share one pose (steps.csv's ancestor_age_s; empty
    while they share none): the set can revise nothing older. Costs M times that depth a scan, outside the
    step's time (default False)"""
    prior_map: _Path | None
    """Start every particle from this map (map.csv: a run's map, or `arbor simulate --survey-out`):
    localisation in a known map; its landmarks count as confirmed, new ones get ids above its largest"""


class _RunOptions(_FilterOptions, total=False):
    """arbor.run's keywords: arbor.Filter's, and out=."""
    out: _Path | None
    """Output directory (result.json, trajectory.tum, map.csv, associations.csv, steps.csv; reference.tum
    where the scenario has a ground truth or GPS track)"""
# end generated: run options
