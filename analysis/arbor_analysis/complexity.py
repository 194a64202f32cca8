"""Complexity figure: FastSLAM step time against the number of landmarks, log-log, one line per map back end,
with the fitted slope and its 95 % confidence interval (DESIGN.md §3: tree/trie <= 0.15, naive ~ 1).
Reads: results.jsonl columns world_landmarks (or landmarks), step_time_median_s, map."""

import sys

from . import results as ar

FIGURE = "complexity_step_time.png"


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    x_col = ar.map_size_column(df)
    if not ar.has_data(df, x_col, "step_time_median_s", "map") or df[x_col].nunique() < 2:
        return []
    df = df[df["step_time_median_s"].notna()]
    # A line needs two map sizes within one configuration; runs on one dataset each give a single point per
    # configuration, and an empty figure would say nothing.
    lines = list(ar.lines_for(df, x_col))
    if not lines:
        return []
    fig, ax = ar.new_figure()
    rows = []
    for name, slope, ci, n, s in ar.plot_loglog_lines(ax, lines, x_col, "step_time_median_s"):
        rows.append({"configuration": name, "log-log slope": slope, "slope 95 % CI ±": ci, "points": n,
                     "N min": s[x_col].min(), "N max": s[x_col].max(),
                     "step time at N max (s)": s["mean"].iloc[-1]})
        print(f"complexity: {name}: log-log slope {slope:.3f} ± {ci:.3f} (95 % CI, {n} points)")
    ax.set_xlabel("landmarks in the world (constant density)" if x_col == "world_landmarks" else "landmarks in the map")
    ax.set_ylabel("median FastSLAM step time (s)")
    ax.set_title("Step time vs map size")
    ax.legend(fontsize=8)
    ar.save_figure(fig, out_dir, FIGURE)
    table = ar.markdown_table(ar.pd.DataFrame(rows))
    return [ar.Section("Complexity: step time vs map size",
                       f"![step time vs landmarks]({FIGURE})\n\nLog–log least-squares slopes with 95 % t intervals "
                       f"(points: every run; markers: mean ± 95 % CI over seeds).\n\n{table}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
