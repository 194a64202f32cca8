"""Reading the files Arbor writes: the one reader of their formats, for `import arbor` and for analysis/ alike.

    trajectory.tum     read_tum           TUM lines: t x y z qx qy qz qw ('#' comments)
    map.csv            read_map           one landmark per row (id, x, y, covariance, log_odds, ..., truth_label)
    result.json        read_result        one run's metrics and config (sweep.json, the manifest: read_json)
    results.jsonl/csv  read_rows          a sweep's rows, one per finished run (results_file picks the file)
    *.scn              read_scenario_truth, read_scenario_steps   the scenario's ground truth (docs/scenario_format.md)

Standard library and numpy only, so the module that the build puts beside the `arbor` package (build/python)
needs nothing more; analysis/arbor_analysis imports this same file from the source tree and wraps what it
returns in pandas.
"""

import csv
import io
import json
import os

import numpy as np


def read_tum(path):
    """A TUM trajectory as N x 4: t, x, y and the planar heading 2 atan2(qz, qw) recovered from the quaternion."""
    rows = np.loadtxt(path, comments="#", ndmin=2)
    if rows.size == 0:
        return np.zeros((0, 4))
    return np.column_stack([rows[:, 0], rows[:, 1], rows[:, 2], 2.0 * np.arctan2(rows[:, 6], rows[:, 7])])


def read_map(path):
    """An estimated map as a dict of columns (numpy float arrays, nan where a cell is empty), keyed by the
    header's names."""
    columns = {}
    with open(path, newline="", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            for name, value in row.items():
                columns.setdefault(name, []).append(float(value) if value not in ("", None) else np.nan)
    return {name: np.asarray(values) for name, values in columns.items()}


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


# result.json's config keys that, before each run option had one name (issue 42), differed from the option's
# command-line name: old key -> the option's name, so a results folder from before reads as one from now.
RENAMED_CONFIG_KEYS = {
    "gate_probability": "chi2",
    "new_landmark_probability": "new_landmark_gate",
    "known_gate_probability": "known_gate",
    "log_odds_prune": "prune",
    "log_odds_confirm": "confirm",
}


def read_result(run_dir):
    """RUN_DIR/result.json as a dict, its config under the run options' own names (old keys renamed)."""
    result = read_json(os.path.join(run_dir, "result.json"))
    config = result.get("config") if isinstance(result, dict) else None
    if isinstance(config, dict):
        for old, new in RENAMED_CONFIG_KEYS.items():
            if old in config and new not in config:
                config[new] = config.pop(old)
    return result


def results_file(path):
    """The rows file of a sweep directory (results.jsonl, else results.csv), or `path` itself when it is a file."""
    if not os.path.isdir(path):
        return path
    jsonl = os.path.join(path, "results.jsonl")
    return jsonl if os.path.exists(jsonl) else os.path.join(path, "results.csv")


def read_rows(path):
    """A sweep's rows (a sweep directory, results.jsonl or results.csv) as a list of dicts, in file order.
    results.csv gives every value as its text. In results.jsonl the piece after the last newline is an
    interrupted append and is not a row; a line that is not a JSON object raises ValueError naming file and line."""
    path = results_file(path)
    with open(path, "rb") as f:
        data = f.read()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:  # either format: a bare UnicodeDecodeError named neither file nor line
        line = data.count(b"\n", 0, e.start) + 1
        raise ValueError(f"{path}:{line}: byte {e.start} is not UTF-8 text") from None
    if path.endswith(".csv"):
        return list(csv.DictReader(io.StringIO(text, newline="")))
    lines = text.split("\n")[:-1]
    rows = []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            row = json.loads(line)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}:{number}: not a JSON row ({e.msg})") from None
        if not isinstance(row, dict):
            raise ValueError(f"{path}:{number}: a row must be a JSON object")
        rows.append(row)
    return rows


def read_scenario_truth(path):
    """Ground truth from a scenario file: (poses [(t, x, y, theta)] one per truth line, at its step's time;
    landmarks [(id, x, y)]; GPS fixes [(t, x, y)])."""
    poses, landmarks, gps = [], [], []
    time = 0.0
    with open(path, encoding="utf-8") as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            kind = fields[0]
            if kind == "step":
                time = float(fields[1])
            elif kind == "truth":
                poses.append((time, float(fields[1]), float(fields[2]), float(fields[3])))
            elif kind == "landmark":
                landmarks.append((int(fields[1]), float(fields[2]), float(fields[3])))
            elif kind == "gps":
                gps.append((float(fields[1]), float(fields[2]), float(fields[3])))
    return poses, landmarks, gps


def read_scenario_steps(path):
    """Per step of a scenario file, in order: [time, true pose (x, y, theta) or None, the true id of each
    measurement (-1 for clutter, None where the file gives none)]. Step k is the step that a run's
    associations.csv calls k."""
    steps = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            if fields[0] == "step":
                steps.append([float(fields[1]), None, []])
            elif fields[0] == "truth" and steps:
                steps[-1][1] = tuple(float(v) for v in fields[1:4])
            elif fields[0] == "z":
                if len(fields) < 5:
                    raise ValueError(f"{path}:{number}: a measurement line needs 5 fields (z R PHI SIG TRUTH)")
                label = fields[4]
                steps[-1][2].append(-1 if label == "clutter" else None if label == "-" else int(label))
    return steps
