"""The filter over time: the step time per map back end (rolling median over 25 steps) and the effective
sample size N_eff / particles (rolling median with its 10-90 % band) per filter and association strategy, on one representative run of each
configuration (the largest particle count and world, the least clutter, the first seed), with a table of
step-time quantiles, mean N_eff and how often the filter resampled.
Reads: results.jsonl (filter, map, assoc, particles, seed, run_dir) and each run's steps.csv."""

import os
import sys

from . import results as ar

FIGURE = "step_time_and_neff.png"
WINDOW = 25  # steps in the step time's rolling median: one slow step (a resample, a page fault) is not a trend


def read_steps(results_dir, run_dir):
    path = os.path.join(results_dir, str(run_dir), "steps.csv")
    if not os.path.exists(path):
        return None
    steps = ar.pd.read_csv(path)
    return steps if {"time_s", "step_time_s", "n_eff"} <= set(steps.columns) and len(steps) else None


def representative_runs(df):
    """One run per configuration: largest particle count and world, least clutter, first seed."""
    for column, pick in (("particles", max), ("world_landmarks", max), ("clutter", min), ("seed", min)):
        if ar.has_data(df, column):
            df = df[df[column] == pick(df[column].dropna())]
    return df


def preferred(values, order):
    """The first of `order` among values, else the first value."""
    return next((v for v in order if v in set(values)), sorted(values, key=str)[0])


def neff_band(ax, time_s, share, label):
    """N_eff / particles as its rolling median over WINDOW steps with the 10-90 % band around it. Drawn step by
    step it swings between resamplings every few steps, and several runs' lines fill the axes as a solid block."""
    rolling = share.rolling(WINDOW, min_periods=1, center=True)
    line, = ax.plot(time_s, rolling.median(), lw=1.2, label=label)
    ax.fill_between(time_s, rolling.quantile(0.1), rolling.quantile(0.9), color=line.get_color(), alpha=0.2, lw=0)


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
        rows.append({"configuration": ar.label(run, shown), "particles": int(run["particles"]),
                     "median step time (ms)": ar.fmt_num(1e3 * steps["step_time_s"].median()),
                     "p95 step time (ms)": ar.fmt_num(1e3 * steps["step_time_s"].quantile(0.95)),
                     "mean N_eff / particles": ar.fmt_num(float(share.mean())),
                     "steps resampled": (f"{100 * steps['resampled'].mean():.0f} %" if "resampled" in steps else "–")})
        series.append((run, steps))
    if not series:
        return []
    fig, (time_ax, neff_ax) = ar.plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    # Step time: one line per map back end, for one filter and strategy (their output is the same per back
    # end; the time is what differs). N_eff: one line per filter and strategy, for one back end.
    filter_shown = preferred([r["filter"] for r, _ in series], ["fastslam2", "fastslam1"])
    assoc_shown = preferred([r.get("assoc") for r, _ in series], ["jcbb", "nn", "locality", "known"])
    map_shown = preferred([r.get("map") for r, _ in series], ["trie", "tree", "naive"])
    for run, steps in series:
        if run["filter"] == filter_shown and run.get("assoc") == assoc_shown:
            rolling = steps["step_time_s"].rolling(WINDOW, min_periods=1).median()
            time_ax.plot(steps["time_s"], 1e3 * rolling, label=f"map = {run.get('map')}")
        if run.get("map") == map_shown:
            neff_band(neff_ax, steps["time_s"], steps["n_eff"] / run["particles"],
                      ar.label(run, [c for c in shown if c != "map"] or ["filter"]))
    time_ax.set_yscale("log")
    time_ax.set_xlabel("time (s)")
    time_ax.set_ylabel(f"step time (ms), rolling median of {WINDOW}")
    time_ax.set_title(f"{filter_shown}/{assoc_shown}: step time per map back end")
    neff_ax.set_ylim(0, 1.05)
    neff_ax.set_xlabel("time (s)")
    neff_ax.set_ylabel(f"N_eff / particles: rolling median, 10–90 % of {WINDOW} steps")
    neff_ax.set_title(f"effective sample size (map = {map_shown})")
    for ax in (time_ax, neff_ax):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    return ar.figure_section(fig, out_dir, FIGURE, "Step time and effective sample size over time", rows,
                             "One run per configuration: the largest particle count and world, the least "
                             "clutter, the first seed.")


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
