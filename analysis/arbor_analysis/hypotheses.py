"""Hypotheses figure: association hypotheses visited against map size, per strategy (locality-restricted
vs unrestricted interpretation tree), log-log with fitted slopes (Ge & Lewis 2006: linear in n with locality).
Reads: results.jsonl columns world_landmarks (or landmarks), assoc, and the first present of
assoc_hypotheses_mean / hypotheses_mean / hypotheses (per step, divided by steps) / assoc_hypotheses."""

import sys

from . import results as ar

FIGURE = "hypotheses_vs_map_size.png"
CANDIDATES = ["assoc_hypotheses_mean", "hypotheses_mean", "hypotheses_per_step", "assoc_hypotheses", "hypotheses"]


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if ar.has_data(df, "hypotheses", "steps"):  # `arbor run` reports the run's total; per step compares runs
        df["hypotheses_per_step"] = df["hypotheses"] / df["steps"]
    metric = next((c for c in CANDIDATES if ar.has_data(df, c)), None)
    x_col = ar.map_size_column(df)
    if metric is None or not ar.has_data(df, x_col) or df[x_col].nunique() < 2:
        return []
    df = df[df[metric].notna()]
    # A line needs two map sizes within one configuration; runs on one dataset each give a single point per
    # configuration, and an empty figure would say nothing.
    lines = list(ar.lines_for(df, x_col))
    if not lines:
        return []
    fig, ax = ar.new_figure()
    rows = []
    for name, slope, ci, n, s in ar.plot_loglog_lines(ax, lines, x_col, metric):
        rows.append({"strategy": name, "log-log slope": slope, "slope 95 % CI ±": ci, "points": n, f"{metric.replace('_', ' ')} at the largest map": s["mean"].iloc[-1]})
        print(f"hypotheses: {name}: log-log slope {slope:.3f} ± {ci:.3f}")
    ax.set_xlabel("landmarks")
    ax.set_ylabel(metric.replace("_", " "))
    ax.set_title("Association hypotheses vs map size")
    ax.legend(fontsize=8)
    ar.save_figure(fig, out_dir, FIGURE)
    return [ar.Section("Hypotheses vs map size",
                       f"![hypotheses vs map size]({FIGURE})\n\n{ar.markdown_table(ar.pd.DataFrame(rows))}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
