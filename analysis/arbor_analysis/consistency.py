"""Consistency figure: the pose NEES of FastSLAM runs over time against its chi-square band.

A consistent 3-dof estimator's single-run NEES lies in the two-sided 95 % band of chi-square(3),
[0.216, 9.348], at 95 % of steps; the average of n independent runs' NEES lies in chi-square(3n)/n's band,
[2.19, 3.93] for n = 30 (Bar-Shalom, Li & Kirubarajan 2001, §5.4.2). The report shows, per configuration
(filter, association, particles; map back ends are identical), the median NEES over its runs at every scan,
each run's share of scans inside the single-run band, and, where a configuration has at least 30 seeds on
the same world, the 30-seed average against its band. The NEES mean is not shown: a few collapse episodes
dominate it.
Reads: results.jsonl columns nees_in_band_fraction, nees_median; each run's steps.csv for the curves.
Usage: PYTHONPATH=analysis /usr/bin/python3 -m arbor_analysis.consistency RESULTS_DIR (prints the section; the report calls make())."""

import os
import sys

import numpy as np
import pandas as pd

from . import multiples
from . import results as ar

SINGLE_RUN_BAND = (0.2158, 9.3484)
FIGURE = "nees_over_time.png"
AVERAGE_SCANS = 200  # the scans the 30-run average is scored on (issue 43's target: inside the band at >= 80 %)


def chi2_band(dof, q):
    """The q-quantile of chi-square(dof), by the Wilson-Hilferty approximation (error < 1e-3 for dof >= 3)."""
    from statistics import NormalDist
    z = NormalDist().inv_cdf(q)
    return dof * (1 - 2 / (9 * dof) + z * np.sqrt(2 / (9 * dof))) ** 3


def scan_nees(run_dir):
    """The NEES column of one run's steps.csv (every step with a truth pose), or None."""
    path = os.path.join(run_dir, "steps.csv")
    if not os.path.exists(path):
        return None
    s = pd.read_csv(path)
    # The start is known exactly: its NEES is 0/0 (written as ~0), not a sample of the statistic.
    s = s[s["nees"].notna() & (s["time_s"] > s["time_s"].min())]
    return s[["step", "time_s", "nees"]].reset_index(drop=True)


def median_nees_figure(curves, keys, out_dir):
    """The median NEES over each configuration's runs at every scan, as small multiples: one panel per
    strategy (or filter), all on one log axis with the single-run band, each curve named at its end."""
    groups = [g for g, _ in curves]
    series_of = {id(g): series for g, series in curves}
    shown = ar.varying(pd.concat(groups), keys) or ["filter"]
    column, panels = multiples.panels_of(shown, groups)
    in_line = [c for c in shown if c != column]
    fig, axes = multiples.grid(1, len(panels), width=4.2, height=3.6, sharey=True)
    style = multiples.Styles()
    ends = []
    for ax, (value, lines) in zip(axes[0], panels):
        ax.axhspan(*SINGLE_RUN_BAND, color="tab:green", alpha=0.12)
        ends.append([])
        for g in lines:
            series = series_of[id(g)]
            n = min(len(s) for s in series)
            t = series[0]["time_s"].to_numpy()[:n]
            median = np.median(np.vstack([s["nees"].to_numpy()[:n] for s in series]), axis=0)
            colour, dash = style([g], in_line)
            ax.plot(t, median, linewidth=1.0, color=colour, linestyle=dash)
            runs = f"{len(series)} run{'s' if len(series) > 1 else ''}"
            ends[-1].append((t[-1], median[-1], f"{multiples.line_label([g], in_line)} ({runs})", colour))
        ax.set_yscale("log")
        ax.set_xlabel("time (s)")
        ax.set_title(multiples.panel_title(column, value), fontsize=10)
    for ax, panel_ends in zip(axes[0], ends):  # once every panel is drawn: they share the y axis
        multiples.label_ends(ax, panel_ends)
    axes[0][0].set_ylabel("pose NEES, median over runs")
    fig.suptitle("Pose NEES over time; green: the single-run 95 % band of χ²(3)")
    ar.save_figure(fig, out_dir, FIGURE)


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "nees_in_band_fraction"):
        return []
    df = df[df["nees_in_band_fraction"].notna()]
    keys = [c for c in ("filter", "assoc") if c in df.columns] + ar.run_option_columns(df)
    keys += [c for c in ("particles", "clutter", "dataset") if c in df.columns]
    _, df = ar.drop_identical_map_backends(df, keys + ["map"], ["seed", "scenario"])
    rows, curves = [], []
    groups = df.groupby(keys, dropna=False)
    few = groups.ngroups <= 6
    for name, g in groups:
        values = name if isinstance(name, tuple) else (name,)
        label = ", ".join(f"{k} = {int(v) if isinstance(v, float) and v.is_integer() else v}"
                          for k, v in zip(keys, values) if not (isinstance(v, float) and np.isnan(v)))
        inband = g["nees_in_band_fraction"]
        row = {"configuration": label, "runs": len(g),
               "share of scans in the 95 % band (per run)": ar.fmt_num(inband.median()) + " median, "
               + ar.fmt_num(inband.min()) + "–" + ar.fmt_num(inband.max())}
        if "nees_median" in g:
            row["NEES median (per run, median over runs)"] = ar.fmt_num(g["nees_median"].median())
        rows.append(row)
        # The figure shows the least clutter, and of each filter and strategy the largest particle count
        # unless there are few configurations; a filter without particles (EKF, smoother) always.
        plotted = (few or all(g[c].iloc[0] == df[c].max() or np.isnan(g[c].iloc[0]) for c in ("particles",) if c in g)) \
            and all(g[c].iloc[0] == df[c].min() for c in ("clutter",) if c in g and g[c].notna().all())
        if plotted and results_path and "run_dir" in g:
            series = [scan_nees(os.path.join(results_path, d)) for d in g["run_dir"] if isinstance(d, str)]
            series = [s for s in series if s is not None and len(s)]
            if series:
                curves.append((g, label, series))
    text = ["Share of scans whose pose NEES lies in the two-sided 95 % χ²(3) band [0.216, 9.348] "
            "(a consistent filter: 0.95).", "", ar.markdown_table(pd.DataFrame(rows)), ""]
    if curves:
        median_nees_figure([(g, series) for g, _, series in curves], keys, out_dir)
        text.append(f"![NEES over time]({FIGURE})")
        many = [(g, label, series) for g, label, series in curves if len(series) >= 30]
        if many:
            fig, ax = ar.new_figure(7.0, 4.4)
            for _, label, series in many:
                n_runs = len(series)
                n = min(len(s) for s in series)
                mean = np.mean(np.vstack([s["nees"].to_numpy()[:n] for s in series]), axis=0)
                ax.plot(series[0]["time_s"].to_numpy()[:n], mean, linewidth=1.0, label=f"{label} ({n_runs} runs)")
            n_runs = min(len(s) for _, s in many)
            lo, hi = chi2_band(3 * n_runs, 0.025) / n_runs, chi2_band(3 * n_runs, 0.975) / n_runs
            inside = []
            for _, label, series in many:  # the average over the first 30 runs, scan by scan
                n = min(min(len(s) for s in series), AVERAGE_SCANS)
                mean = np.mean(np.vstack([s["nees"].to_numpy()[:n] for s in series[:30]]), axis=0)
                inside.append({"configuration": label, "scans": n, "average NEES median": ar.fmt_num(np.median(mean)),
                               f"share of scans in [{lo:.2f}, {hi:.2f}]": ar.fmt_num(np.mean((mean >= lo) & (mean <= hi)))})
            text += ["", f"The 30-run average NEES over the first {AVERAGE_SCANS} scans against its band "
                     "(a consistent filter: about 0.95 of scans inside):", "", ar.markdown_table(pd.DataFrame(inside))]
            ax.axhspan(lo, hi, color="tab:green", alpha=0.15, label=f"{n_runs}-run average band [{lo:.2f}, {hi:.2f}]")
            ax.set_yscale("log")
            ax.set_xlabel("time (s)")
            ax.set_ylabel(f"average pose NEES over {n_runs} runs")
            ax.legend(fontsize=6, loc="upper left")
            ar.save_figure(fig, out_dir, "nees_average.png")
            text.append("\n![average NEES](nees_average.png)")
        else:
            text.append("\nNo configuration has 30 or more runs, so the average-NEES band is not drawn.")
    return [ar.Section("Consistency (pose NEES)", "\n".join(text) + "\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
