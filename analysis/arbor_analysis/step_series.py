"""The filter over time: the time per scan per map back end (the step time in runs whose steps.csv does not mark
the scans), as a rolling median over 25, and the effective sample size N_eff / particles (rolling median with
its 10-90 % band) per filter and association strategy, each line named at its end, on one representative run of
each configuration (the largest particle count and world, the least clutter, the first seed), with a table of
time-per-scan quantiles (and step-time ones where a step is not a scan), mean N_eff and how often the filter
resampled. Reads: results.jsonl (filter, map, assoc, particles, seed, run_dir) and each run's steps.csv."""

import os
import sys

from . import multiples
from . import results as ar

FIGURE = "step_time_and_neff.png"
WINDOW = 25  # steps in the step time's rolling median: one slow step (a resample, a page fault) is not a trend
POINTS_ACROSS = 300  # the most rolling windows the N_eff band spans across its axes


def read_steps(results_dir, run_dir):
    path = os.path.join(results_dir, str(run_dir), "steps.csv")
    if not os.path.exists(path):
        return None
    steps = ar.pd.read_csv(path)
    return steps if {"time_s", "step_time_s", "n_eff"} <= set(steps.columns) and len(steps) else None


def per_scan_times(steps):
    """The time per scan from steps.csv's scan column, as `arbor run` computes its scan_time_median_s: per
    scan, its step's time and that of the odometry-only steps since the previous scan (steps after the last
    scan are no scan's work). A frame of time_s (the scan's) and scan_time_s, or None for a steps.csv that
    predates the column."""
    if "scan" not in steps:
        return None
    scan = steps["scan"].fillna(0).astype(int).to_numpy()
    owner = ar.np.cumsum(scan[::-1])[::-1]  # per step, how many scans remain from it on: one number per scan
    times = steps["step_time_s"].groupby(owner).sum()
    at = steps.loc[scan == 1, "time_s"].to_numpy()
    return ar.pd.DataFrame({"time_s": at, "scan_time_s": times.loc[owner[scan == 1]].to_numpy()})


def representative_runs(df):
    """One run per configuration: largest particle count and world, least clutter, first seed."""
    for column, pick in (("particles", max), ("world_landmarks", max), ("clutter", min), ("seed", min)):
        if ar.has_data(df, column):
            df = df[df[column] == pick(df[column].dropna())]
    return df


def preferred(values, order):
    """The first of `order` among values, else the first value."""
    return next((v for v in order if v in set(values)), sorted(values, key=str)[0])


def neff_window(length):
    """Samples in the N_eff band's rolling window: WINDOW, or more on a long log, so that the band has at most
    POINTS_ACROSS windows across the axes; with 7,000 scans a 25-scan window still swings too fast to read."""
    return max(WINDOW, length // POINTS_ACROSS)


def neff_band(ax, time_s, share, label):
    """N_eff / particles as its rolling median with the 10-90 % band around it. Drawn sample by sample it swings
    between resamplings every few steps, and several runs' lines fill the axes as a solid block."""
    rolling = share.rolling(neff_window(len(share)), min_periods=1, center=True)
    median = rolling.median()
    line, = ax.plot(time_s, median, lw=1.2)
    ax.fill_between(time_s, rolling.quantile(0.1), rolling.quantile(0.9), color=line.get_color(), alpha=0.2, lw=0)
    return time_s.iloc[-1], median.iloc[-1], label, line.get_color()


def at_scans(steps):
    """The steps that carried a scan, where steps.csv marks them: between scans N_eff does not change, so on a
    real log the odometry steps would only repeat each scan's value ten times over."""
    return steps[steps["scan"] == 1] if "scan" in steps and (steps["scan"] == 1).any() else steps


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if results_path is None or not ar.has_data(df, "run_dir", "particles", "filter"):
        return []
    results_dir = ar.results_dir_of(results_path)
    runs = representative_runs(df[df["filter"] != "smoother"])
    groups = [c for c in ar.method_columns(runs) if c in runs.columns]
    shown = ar.varying(runs, groups) or ["filter"]
    rows, series = [], []
    for _, g in runs.groupby(groups, sort=True, dropna=False):
        steps = read_steps(results_dir, g["run_dir"].iloc[0])
        if steps is None:
            continue
        run = g.iloc[0]
        share = steps["n_eff"] / run["particles"]
        scans = per_scan_times(steps)
        row = {"configuration": ar.label(run, shown), "particles": int(run["particles"])}
        if scans is not None and len(scans):  # the time that keeping up with the sensor takes
            row["median time per scan (ms)"] = ar.fmt_num(1e3 * scans["scan_time_s"].median())
            row["p90 time per scan (ms)"] = ar.fmt_num(1e3 * scans["scan_time_s"].quantile(0.9))
        if scans is None or len(scans) < len(steps):  # a step is not a scan: its own time, for older runs too
            row["median step time (ms)"] = ar.fmt_num(1e3 * steps["step_time_s"].median())
            row["p95 step time (ms)"] = ar.fmt_num(1e3 * steps["step_time_s"].quantile(0.95))
        row["mean N_eff / particles"] = ar.fmt_num(float(share.mean()))
        row["steps resampled"] = f"{100 * steps['resampled'].mean():.0f} %" if "resampled" in steps else "–"
        rows.append(row)
        series.append((run, steps, scans))
    if not series:
        return []
    # Time: one line per map back end, for one filter and strategy (their output is the same per back end; the
    # time is what differs), per scan where the runs mark their scans. N_eff: one panel per strategy, one band
    # per filter in it, for one back end: several bands on one axes fill it as a block. Lines named at their end.
    filter_shown = preferred([r["filter"] for r, _, _ in series], ["fastslam2", "fastslam1"])
    assoc_shown = preferred([r.get("assoc") for r, _, _ in series], ["jcbb", "nn", "locality", "known"])
    map_shown = preferred([r.get("map") for r, _, _ in series], ["trie", "tree", "naive"])
    strategies = sorted({str(r.get("assoc")) for r, _, _ in series if r.get("map") == map_shown},
                        key=lambda a: (a == ar.ORACLE_ASSOC, a))
    fig, axes = ar.plt.subplots(1, 1 + len(strategies), figsize=(5.4 + 3.4 * len(strategies), 4.2),
                                layout="constrained", squeeze=False)
    time_ax, neff_axes = axes[0][0], dict(zip(strategies, axes[0][1:]))
    per_scan = all(scans is not None and len(scans) for _, _, scans in series)
    time_ends, neff_ends = [], {a: [] for a in strategies}
    in_line = [c for c in shown if c not in ("map", "assoc")] or ["filter"]
    for run, steps, scans in series:
        if run["filter"] == filter_shown and run.get("assoc") == assoc_shown:
            t, cost = (scans["time_s"], scans["scan_time_s"]) if per_scan else (steps["time_s"], steps["step_time_s"])
            rolling = 1e3 * cost.rolling(WINDOW, min_periods=1).median()
            line, = time_ax.plot(t, rolling)
            time_ends.append((t.iloc[-1], rolling.iloc[-1], f"map = {run.get('map')}", line.get_color()))
        if run.get("map") == map_shown:
            assoc = str(run.get("assoc"))
            sampled = at_scans(steps)
            samples = "scans" if len(sampled) < len(steps) else "steps"
            window = neff_window(len(sampled))
            neff_ends[assoc].append(neff_band(neff_axes[assoc], sampled["time_s"], sampled["n_eff"] / run["particles"],
                                              ar.label(run, in_line)))
    time_ax.set_yscale("log")
    time_ax.set_xlabel("time (s)")
    what = "time per scan" if per_scan else "step time"
    time_ax.set_ylabel(f"{what} (ms), rolling median of {WINDOW}")
    time_ax.set_title(f"{filter_shown}/{assoc_shown}: {what} per map back end")
    for assoc, ax in neff_axes.items():
        ax.set_ylim(0, 1.05)
        ax.set_xlabel("time (s)")
        role = ar.role({"assoc": assoc})
        ax.set_title(f"N_eff: {assoc}{f' ({role})' if role else ''}, map = {map_shown}", fontsize=10)
        if ax is not axes[0][1]:
            ax.sharey(axes[0][1])
            ax.tick_params(labelleft=False)
    axes[0][1].set_ylabel(f"N_eff / particles: rolling median, 10–90 % of {window} {samples}")
    time_ax.grid(True, alpha=0.3)
    multiples.label_ends(time_ax, time_ends)
    for assoc, ax in neff_axes.items():
        ax.grid(True, alpha=0.3)
        multiples.label_ends(ax, neff_ends[assoc])
    note = ("One run per configuration: the largest particle count and world, the least clutter, the first seed."
            + (" Time per scan: a scan's step and the odometry-only steps before it." if per_scan else ""))
    return ar.figure_section(fig, out_dir, FIGURE, "Time per scan and effective sample size over time" if per_scan
                             else "Step time and effective sample size over time", rows, note)


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
