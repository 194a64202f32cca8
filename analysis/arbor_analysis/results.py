"""The helpers the report's sections and the studies share: a sweep's rows and one run's files as pandas frames
(read by arbor_files, python/arbor_files.py, the reader `import arbor` uses too), the statistics, tables and figures."""

import glob
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")  # files only, never a window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import arbor_files  # noqa: E402


def _grid_columns():
    """The sweep's grid columns as (name, type, roles), from the one list the sweep compiles in."""
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                        "experiments", "sweep", "grid_columns.inc")
    with open(path, encoding="utf-8") as f:
        return [(name, kind, roles.split()) for name, kind, roles in
                re.findall(r'^\{"([^"]+)", "([^"]+)", "([^"]*)"\},$', f.read(), re.MULTILINE)]


GRID_COLUMNS = _grid_columns()
PARAMS = [name for name, _, _ in GRID_COLUMNS]
# The columns that tell two method configurations apart in a figure's legend.
METHOD = [name for name, _, roles in GRID_COLUMNS if "method" in roles]
# Everything else a sweep may vary; a figure draws one line per combination that varies in the results.
CONTEXT = [name for name, _, roles in GRID_COLUMNS if "context" in roles]
# The columns that name a scenario: with the seed they identify the smoother's run a filter run compares with.
SCENARIO = [name for name, _, roles in GRID_COLUMNS if "scenario" in roles]
# The text columns of a row: the grid's, and the run's identity, status and provenance.
TEXT_COLUMNS = {name for name, kind, _ in GRID_COLUMNS if kind == "text"} | {
    "key", "status", "error", "scenario", "run_dir", "commit", "host", "compiler", "build", "finished_at",
    "termination"}


def load_results(path):
    """All rows of a sweep directory (or of a results.jsonl / results.csv file) as a DataFrame.
    A trailing line without newline is an interrupted append and is ignored; a key recorded twice keeps its
    last row (what --retry-failed appends)."""
    path = arbor_files.results_file(path)
    if path.endswith(".csv"):
        try:
            df = pd.read_csv(path)  # arbor_files gives the CSV's cells as text; pandas types its columns
        except ValueError as e:  # pandas' parser errors (and UnicodeDecodeError, one of them) lack the file
            raise ValueError(f"{path}: not a results table ({e})") from None
    else:
        df = pd.DataFrame(arbor_files.read_rows(path))
    if df.empty:
        return df
    if "key" not in df:
        raise ValueError(f"{path}: no 'key' column: not an arbor sweep's results")
    df = df.drop_duplicates(subset="key", keep="last").reset_index(drop=True)
    options = run_option_columns(df)
    for c in df.columns:
        if c in options:
            continue  # option values stay as the child got them ("student-t", "0.95", "true")
        if c not in TEXT_COLUMNS:
            df[c] = pd.to_numeric(df[c], errors="coerce")
    return df


def run_option_columns(df):
    """The further `arbor run` options a sweep's grid names (likelihood, chi2, relocalize, ...): the rows put
    them between threads and scenario."""
    cols = list(df.columns)
    if "threads" not in cols or "scenario" not in cols:
        return []
    i, j = cols.index("threads"), cols.index("scenario")
    return cols[i + 1:j]


def method_columns(df):
    """The columns that tell two method configurations apart: filter, map, assoc, and any run option."""
    return METHOD + run_option_columns(df)


def map_size_column(df):
    """The column that gives a run's map size on a complexity figure's x axis, or None when the rows do not vary
    it: the swept world_landmarks, else the estimated map's own size where it spans a factor of 4 or more
    (runs on datasets of different sizes). Seeds on one dataset give maps of 201 and 202 landmarks, which is
    no complexity axis."""
    if has_data(df, "world_landmarks") and df["world_landmarks"].nunique() > 1:
        return "world_landmarks"
    if has_data(df, "landmarks") and df["landmarks"].min() > 0 and df["landmarks"].max() >= 4 * df["landmarks"].min():
        return "landmarks"
    return None


def ok_rows(df):
    return df[df["status"] == "ok"].copy() if "status" in df else df


def has_data(df, *columns):
    """True when every column exists and has at least one value."""
    return all(c in df.columns and df[c].notna().any() for c in columns)


def varying(df, columns):
    """The columns (of `columns`) that take more than one value in df: the ones a legend must show."""
    return [c for c in columns if c in df.columns and df[c].nunique(dropna=True) > 1]


def line_groups(df, x, min_points=2, collapse_identical_maps=False):
    """The groups of rows that make one line each in a figure with x on the horizontal axis: rows grouped by
    every method and context column that varies (except x), keeping groups with at least min_points distinct
    x values. Returns (shown, groups): the columns that differ between the kept lines, and the rows of each.
    With collapse_identical_maps, one line stands for all map back ends where their ATE agrees run for run."""
    df = df[df[x].notna()]
    by = [c for c in varying(df, method_columns(df) + CONTEXT) if c != x]
    if collapse_identical_maps:  # for accuracy figures only: timings do differ between back ends
        by, df = drop_identical_map_backends(df, by, [x, "seed"])
    if not by:
        return [], ([df] if df[x].nunique() >= min_points else [])
    kept = [g for _, g in df.groupby(by if len(by) > 1 else by[0], sort=True, dropna=False) if g[x].nunique() >= min_points]
    if not kept:
        return [], []
    return varying(pd.concat(kept), by) or ["filter"], kept


def lines_for(df, x, min_points=2, collapse_identical_maps=False):
    """line_groups as (label, rows) per line; the label names only the columns that differ between lines."""
    shown, groups = line_groups(df, x, min_points, collapse_identical_maps)
    for g in groups:
        yield (label(g.iloc[0], shown) if shown else "all runs"), g


def drop_identical_map_backends(df, by, keys):
    """Map back ends give bit-identical filter output (a tested property); when the results confirm it, one
    line stands for all of them instead of one per back end. `keys`: the columns besides `by` that tell one
    run from another (x, seed, scenario). Returns (by, rows): the rows then hold each run once, because
    copies of a run are not independent samples (counting them would shrink every CI)."""
    if "map" not in by or "ate_rmse_m" not in df:
        return by, df
    rest = [c for c in by if c != "map"] + [c for c in dict.fromkeys(keys) if c in df and c not in by]
    same = df.groupby(rest, dropna=False)["ate_rmse_m"].nunique(dropna=False).max() <= 1 if rest else False
    if not same:
        return by, df
    return [c for c in by if c != "map"], df.drop_duplicates(subset=rest)


# Configurations that bound what a strategy can reach rather than being one: known association reads the
# simulator's landmark ids (a real dataset has none), and the smoother solves the whole log at once. A report
# shows them as references and never names one of them best.
ORACLE_ASSOC = "known"
REFERENCE_FILTER = "smoother"


def role(row):
    """"reference" for the smoother, "oracle" for known association, "" for a real strategy."""
    if row.get("filter") == REFERENCE_FILTER:
        return "reference"
    if row.get("assoc") == ORACLE_ASSOC:
        return "oracle"
    return ""


def is_reference(df):
    """Per row of df: whether it is an oracle or the smoother (role() is not empty)."""
    mask = pd.Series(False, index=df.index)
    if "filter" in df:
        mask |= df["filter"] == REFERENCE_FILTER
    if "assoc" in df:
        mask |= df["assoc"] == ORACLE_ASSOC
    return mask


# How a label names each dimension that is not a method: "name = value unit", so that a label part can never
# be clutter in one table and particles in another. Method columns (filter, map, assoc, run options' values
# aside) are names already and stay bare: "fastslam2/jcbb, particles = 100, clutter = 2 /scan".
DIMENSIONS = {"world_landmarks": ("landmarks", ""), "world_steps": ("scans", ""), "clutter": ("clutter", " /scan"),
              "world_seed": ("world seed", "")}


def label(row, columns):
    bare, named = [], []
    for c in columns:
        v = row[c]
        if v is None or (isinstance(v, float) and v != v):  # a dimension this filter lacks (EKF: particles, map)
            continue
        text = str(int(v)) if isinstance(v, float) and float(v).is_integer() else str(v)
        if c in METHOD:
            bare.append(text)
        else:
            name, unit = DIMENSIONS.get(c, (c, ""))
            named.append(f"{name} = {text}{unit}")
    parts = (["/".join(bare)] if bare else []) + named
    return ", ".join(parts) if parts else "all runs"


# Two-sided 95 % Student-t quantiles t(0.975, dof) for dof 1..30, from the standard tables; beyond 30 the
# Cornish-Fisher expansion is within 0.001 of them.
T_975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131,
         2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042]


def t_quantile(dof, q=0.975):
    """Student-t quantile; scipy when present, else (q = 0.975 only) the table above and a Cornish-Fisher
    expansion past it."""
    try:
        from scipy import stats
        return float(stats.t.ppf(q, dof))
    except ImportError:
        if q != 0.975:
            raise
        if dof <= 0:
            return float("inf")
        if dof <= len(T_975):
            return T_975[int(dof) - 1]
        z = 1.959963984540054
        return z + (z ** 3 + z) / (4 * dof) + (5 * z ** 5 + 16 * z ** 3 + 3 * z) / (96 * dof ** 2)


# A 95 % interval is shown only from this many values on. With two, the t quantile is 12.7, so "1.23 ± 10"
# reads like a result and is noise; with fewer, tables list the individual values instead.
MIN_VALUES_FOR_CI = 3


CI_NOTE = (f"Cells read mean ± 95 % CI over seeds where there are at least {MIN_VALUES_FOR_CI}, and the "
           "individual values (a / b) where there are fewer.")


def finite_values(values):
    return np.asarray([x for x in values if x is not None and np.isfinite(x)], dtype=float)


def mean_ci(values):
    """Mean and the half-width of its 95 % confidence interval (t distribution); the half-width is nan with
    fewer than MIN_VALUES_FOR_CI values."""
    v = finite_values(values)
    if len(v) == 0:
        return float("nan"), float("nan")
    if len(v) < MIN_VALUES_FOR_CI:
        return float(v.mean()), float("nan")
    return float(v.mean()), float(t_quantile(len(v) - 1) * v.std(ddof=1) / math.sqrt(len(v)))


def fmt_mean_ci(values, digits=3):
    """"mean ± ci" over values, or the values themselves ("0.31 / 0.40") where there are too few for an
    interval."""
    v = finite_values(values)
    if len(v) == 0:
        return "–"
    if len(v) < MIN_VALUES_FOR_CI:
        return " / ".join(fmt_num(float(x), digits) for x in v)
    m, ci = mean_ci(v)
    return f"{fmt_num(m, digits)} ± {fmt_num(ci, 2)}"


def fit_loglog(x, y):
    """Least-squares fit of log10 y = a + b log10 x. Returns (b, b_ci95_halfwidth, a, n). The interval is the
    t-based 95 % interval of the slope (needs at least 3 points; nan otherwise)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    keep = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    lx, ly = np.log10(x[keep]), np.log10(y[keep])
    n = len(lx)
    if n < 2 or np.ptp(lx) == 0:
        return float("nan"), float("nan"), float("nan"), n
    b, a = np.polyfit(lx, ly, 1)
    if n < 3:
        return float(b), float("nan"), float(a), n
    residual = ly - (a + b * lx)
    se = math.sqrt(float(residual @ residual) / (n - 2) / float(((lx - lx.mean()) ** 2).sum()))
    return float(b), float(t_quantile(n - 2) * se), float(a), n


def align_se2(a, b):
    """Least-squares rotation and translation taking points a onto b (2-D Procrustes, Umeyama 1991)."""
    ac, bc = a.mean(0), b.mean(0)
    h = (a - ac).T @ (b - bc)
    th = np.arctan2(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1])
    r = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    return r, bc - r @ ac


def plot_loglog_lines(ax, lines, x, metric):
    """One line per (label, rows) of `lines` on log-log axes: the mean +- 95 % CI over seeds at each x, and the
    fitted slope (fit_loglog) drawn through them. Returns (label, slope, ci95, points, summary) per line."""
    fits = []
    for name, g in lines:
        slope, ci, intercept, n = fit_loglog(g[x], g[metric])
        s = summarize(g, [x], metric)
        line = ax.errorbar(s[x], s["mean"], yerr=error_bars(s), marker="o", capsize=3, linestyle="none",
                           label=f"{name}: slope {slope:.2f} ± {ci:.2f}" if np.isfinite(ci) else f"{name}: slope {slope:.2f}")
        if np.isfinite(slope):
            xs = np.logspace(np.log10(s[x].min()), np.log10(s[x].max()), 50)
            ax.plot(xs, 10 ** (intercept + slope * np.log10(xs)), color=line[0].get_color(), alpha=0.6)
        fits.append((name, slope, ci, n, s))
    ax.set_xscale("log")
    ax.set_yscale("log")
    return fits


def summarize(df, by, metric):
    """Per group of `by` (sorted): mean, ci (95 % half-width; nan with fewer than MIN_VALUES_FOR_CI values),
    n, and text (fmt_mean_ci: the mean and interval, or the individual values)."""
    rows = []
    for key, group in df.groupby(by if len(by) > 1 else by[0], dropna=False, sort=True):
        values = group[metric].to_numpy(dtype=float)
        m, ci = mean_ci(values)
        key = key if isinstance(key, tuple) else (key,)
        rows.append(dict(zip(by, key), mean=m, ci=ci, n=int(group[metric].notna().sum()), text=fmt_mean_ci(values)))
    return pd.DataFrame(rows)


def error_bars(summary):
    """The yerr of a summarize() frame for errorbar(): no bar where there is no interval."""
    return summary["ci"].fillna(0.0)


def fmt_num(v, digits=3):
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return "–"
    if isinstance(v, (int, np.integer)) or (isinstance(v, float) and float(v).is_integer() and abs(v) < 1e6):
        return str(int(v))
    return f"{v:.{digits}g}"


# Characters with a meaning in Markdown's inline syntax or in its tables (and in html_report's subset of it);
# "_" and "#" are left alone: html_report renders neither inline, and GitHub's Markdown takes no intraword "_".
MARKDOWN_SPECIAL = re.compile(r"([\\`*\[\]!|<>])")


def md_text(value):
    """Text from a spec or a results file as Markdown that renders as that text and as nothing else: on one
    line (a newline would start a block: a heading, an image, a code fence) and with every character that
    means something in Markdown escaped (html_report.inline undoes the escapes). Data never becomes structure."""
    return MARKDOWN_SPECIAL.sub(r"\\\1", " ".join(str(value).split()))


def code_block(text, info=""):
    """text verbatim in a fenced code block whose fence is longer than any backtick run in it, so the text
    cannot close it (CommonMark's rule, which html_report follows)."""
    longest = max((len(m) for m in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, longest + 1)
    return f"{fence}{info}\n{text}\n{fence}"


def markdown_table(df, digits=3):
    """A GitHub Markdown table (no dependency on tabulate); text cells and headers are data (md_text)."""
    cols = list(df.columns)
    out = ["| " + " | ".join(md_text(c) for c in cols) + " |", "|" + "---|" * len(cols)]
    for _, r in df.iterrows():
        out.append("| " + " | ".join(fmt_num(r[c], digits) if not isinstance(r[c], str) else md_text(r[c])
                                     for c in cols) + " |")
    return "\n".join(out)


def new_figure(width=6.4, height=4.2):
    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    ax.grid(True, which="both", alpha=0.3)
    return fig, ax


def save_figure(fig, out_dir, name):
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def figure_section(fig, out_dir, figure, title, rows, note=""):
    """Saves fig as `figure`, prints `rows` as a table, and returns the report section: the figure, the note,
    then the table."""
    save_figure(fig, out_dir, figure)
    frame = pd.DataFrame(rows)
    print(frame.to_string(index=False))
    note = f"{note}\n\n" if note else ""
    return [Section(title, f"![{title.lower()}]({figure})\n\n{note}{markdown_table(frame)}\n")]


def read_study_runs(pattern, regex, fields):
    """The result.json files of a study script's runs (glob pattern), one row each: the named groups of
    regex, matched against the run's directory name (digits become ints), and the listed result fields.
    Directories whose name does not match are skipped."""
    rows = []
    for path in sorted(glob.glob(pattern)):
        m = re.fullmatch(regex, os.path.basename(os.path.dirname(path)))
        if not m:
            continue
        r = arbor_files.read_json(path)
        row = {k: (int(v) if v and v.isdigit() else v) for k, v in m.groupdict().items()}
        for field in fields:
            row[field] = r.get(field)
        rows.append(row)
    return pd.DataFrame(rows)


# --- one run's files -------------------------------------------------------------------------------------

def read_tum(path):
    """A TUM trajectory: columns t, x, y and theta (the planar heading recovered from the quaternion)."""
    return pd.DataFrame(arbor_files.read_tum(path), columns=["t", "x", "y", "theta"])


def read_map_csv(path):
    """An estimated map: one landmark per row. Positions are the columns x, y (or the first two numeric
    columns after an id column when the header names them otherwise)."""
    df = pd.DataFrame(arbor_files.read_map(path))
    lower = {c.lower().strip(): c for c in df.columns}
    for xs, ys in (("x", "y"), ("mean_x", "mean_y"), ("mu_x", "mu_y"), ("x_m", "y_m")):
        if xs in lower and ys in lower:
            return df.rename(columns={lower[xs]: "x", lower[ys]: "y"})
    numeric = [c for c in df.columns if pd.api.types.is_numeric_dtype(df[c])]
    if len(numeric) >= 3:
        return df.rename(columns={numeric[1]: "x", numeric[2]: "y"})
    raise ValueError(f"{path}: cannot find landmark x, y columns in {list(df.columns)}")


def read_scenario_truth(path):
    """Ground truth from a scenario file (docs/scenario_format.md): poses per step, landmarks, GPS track."""
    poses, landmarks, gps = arbor_files.read_scenario_truth(path)
    return (pd.DataFrame(poses, columns=["t", "x", "y", "theta"]),
            pd.DataFrame(landmarks, columns=["id", "x", "y"]),
            pd.DataFrame(gps, columns=["t", "x", "y"]))


read_scenario_steps = arbor_files.read_scenario_steps
read_json = arbor_files.read_json
read_result = arbor_files.read_result


def results_dir_of(path):
    """The sweep directory of a results path (the directory itself, or the one holding a results file)."""
    return path if os.path.isdir(path) else os.path.dirname(path)


def main_for(make, description):
    """The command line every figure script shares: SCRIPT RESULTS_DIR [--out DIR]."""
    import argparse
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("results", help="a sweep results directory (results.jsonl) or a results file")
    parser.add_argument("--out", help="where figures go (default: RESULTS/report)")
    args = parser.parse_args()
    out = args.out or os.path.join(results_dir_of(args.results), "report")
    df = load_results(args.results)
    sections = make(df, out, args.results)
    if not sections:
        print(f"{os.path.basename(sys.argv[0])}: nothing to plot in {args.results} (the columns this figure needs "
              "do not vary or are missing)", file=sys.stderr)
    for s in sections:
        print(s.text)
    return 0


class Section:
    """One part of the report: a title and Markdown text (figure links relative to the report)."""

    def __init__(self, title, text):
        self.title = title
        self.text = text
