"""Accuracy figure: trajectory error (ATE RMSE) and landmark RMSE against the number of particles, as small
multiples: one panel per association strategy (oracles last), one row per metric with a shared y axis, each
line (filter, clutter, ...) named at its end; identical lines drawn once. Mean and 95 % CI over seeds (the
individual values where there are fewer than 3).
Reads: results.jsonl columns particles, ate_rmse_m, landmark_rmse_m, filter, map, assoc, seed."""

import sys

from . import multiples
from . import results as ar

FIGURE = "accuracy_vs_particles.png"
COLUMNS = {"ate_rmse_m": "ATE RMSE (m)", "landmark_rmse_m": "landmark RMSE (m)"}


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "particles", "ate_rmse_m") or df["particles"].nunique() < 2:
        return []
    metrics = [m for m in ("ate_rmse_m", "landmark_rmse_m") if ar.has_data(df, m)]
    shown, groups = ar.line_groups(df, "particles", collapse_identical_maps=True)
    if not groups:
        return []
    column, panels = multiples.panels_of(shown, groups)
    in_line = [c for c in shown if c != column]
    fig, axes = multiples.grid(len(metrics), len(panels))
    style = multiples.Styles()
    table, ends = {}, {}
    for j, (value, lines) in enumerate(panels):
        for copies in multiples.collapse_identical(lines, "particles", metrics):
            name = multiples.line_label(copies, in_line)
            full = multiples.line_label(copies, shown)
            colour, dash = style(copies, in_line)
            for i, metric in enumerate(metrics):
                s = ar.summarize(copies[0], ["particles"], metric)
                ax = axes[i][j]
                ax.errorbar(s["particles"], s["mean"], yerr=ar.error_bars(s), marker="o", ms=4, capsize=3,
                            color=colour, linestyle=dash)
                ends.setdefault((i, j), []).append((s["particles"].iloc[-1], s["mean"].iloc[-1], name, colour))
                for _, r in s.iterrows():
                    table.setdefault((full, int(r["particles"])), {})[COLUMNS[metric]] = r["text"]
                    table[(full, int(r["particles"]))]["seeds"] = int(r["n"])
        axes[0][j].set_title(multiples.panel_title(column, value), fontsize=10)
    for i, metric in enumerate(metrics):
        axes[i][0].set_ylabel(COLUMNS[metric])
        for ax in axes[i]:
            ax.set_xscale("log")
            ax.set_yscale("log")
    for ax in axes[-1]:
        ax.set_xlabel("particles")
    for (i, j), items in ends.items():
        multiples.label_ends(axes[i][j], items)
    fig.suptitle(f"Accuracy vs particles (mean; ± 95 % CI where there are ≥ {ar.MIN_VALUES_FOR_CI} seeds)")
    ar.save_figure(fig, out_dir, FIGURE)
    rows = [dict(configuration=k[0], particles=k[1], **v) for k, v in sorted(table.items())]
    frame = ar.pd.DataFrame(rows)
    print(frame.to_string(index=False))
    return [ar.Section("Accuracy vs particles",
                       f"![accuracy vs particles]({FIGURE})\n\n{ar.CI_NOTE}\n\n{ar.markdown_table(frame)}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
