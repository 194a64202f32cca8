"""Thread-scaling figure: speed-up of the median step time over the 1-thread run of the same configuration,
against the thread count, with the ideal line. Reads: results.jsonl columns threads, step_time_median_s
(wall_time_s when the step time is missing)."""

import sys

import numpy as np

from . import results as ar

FIGURE = "thread_scaling.png"


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    metric = "step_time_median_s" if ar.has_data(df, "step_time_median_s") else "wall_time_s"
    if not ar.has_data(df, "threads", metric) or df["threads"].nunique() < 2 or 1 not in set(df["threads"]):
        return []
    fig, ax = ar.new_figure()
    rows = []
    for name, g in ar.lines_for(df, "threads"):
        s = ar.summarize(g, ["threads"], metric)
        base = s.loc[s["threads"] == 1, "mean"]
        if base.empty:
            continue
        speedup = base.iloc[0] / s["mean"]
        ax.plot(s["threads"], speedup, marker="o", label=name)
        for (_, r), sp in zip(s.iterrows(), speedup):
            rows.append({"configuration": name, "threads": r["threads"], {"step_time_median_s": "median step time (s)", "wall_time_s": "wall time (s)"}[metric]: r["mean"], "speed-up": sp})
    t = np.array(sorted(df["threads"].unique()))
    ax.plot(t, t, linestyle="--", color="grey", label="ideal")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log", base=2)
    ax.set_xlabel("threads")
    ax.set_ylabel(f"speed-up of {metric.replace('_', ' ')}")
    ax.set_title("Thread scaling")
    ax.legend(fontsize=8)
    return ar.figure_section(fig, out_dir, FIGURE, "Thread scaling", rows)


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
