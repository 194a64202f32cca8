"""Association figure: F1, precision and recall of the association decisions against clutter (spurious
measurements per scan), as small multiples: one panel per strategy (oracles last), one row per score, every
panel on the same 0-1 axis, each line (filter, particles, ...) named at its end; identical lines drawn once.
Mean and 95 % CI over seeds (the individual values where there are fewer than 3).
Reads: results.jsonl columns clutter, assoc, assoc_f1 (assoc_precision, assoc_recall when present)."""

import sys

from . import multiples
from . import results as ar

FIGURE = "association_vs_clutter.png"
NAMES = {"assoc_f1": "F1", "assoc_precision": "precision", "assoc_recall": "recall"}


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "clutter", "assoc_f1") or df["clutter"].nunique() < 2:
        return []
    df = df[df["assoc_f1"].notna()]
    metrics = [m for m in NAMES if ar.has_data(df, m)]
    shown, groups = ar.line_groups(df, "clutter", collapse_identical_maps=True)
    if not groups:
        return []
    column, panels = multiples.panels_of(shown, groups)
    in_line = [c for c in shown if c != column]
    fig, axes = multiples.grid(len(metrics), len(panels), height=2.4, sharey=True)
    style = multiples.Styles()
    rows, ends = [], {}
    for j, (value, lines) in enumerate(panels):
        for copies in multiples.collapse_identical(lines, "clutter", metrics):
            name = multiples.line_label(copies, in_line)
            colour, dash = style(copies, in_line)
            for i, metric in enumerate(metrics):
                s = ar.summarize(copies[0], ["clutter"], metric)
                axes[i][j].errorbar(s["clutter"], s["mean"], yerr=ar.error_bars(s), marker="o", ms=4, capsize=3,
                                    color=colour, linestyle=dash)
                ends.setdefault((i, j), []).append((s["clutter"].iloc[-1], s["mean"].iloc[-1], name, colour))
                if metric == "assoc_f1":
                    for _, r in s.iterrows():
                        rows.append({"strategy": multiples.line_label(copies, shown), "clutter (/scan)": r["clutter"],
                                     "F1": r["text"], "seeds": r["n"]})
        axes[0][j].set_title(multiples.panel_title(column, value), fontsize=10)
    for i, metric in enumerate(metrics):
        axes[i][0].set_ylabel(NAMES[metric])
    for ax in axes[-1]:
        ax.set_xlabel("clutter (spurious measurements per scan)")
    for (i, j), items in ends.items():
        multiples.label_ends(axes[i][j], items)
    fig.suptitle(f"Association vs clutter (mean; ± 95 % CI where there are ≥ {ar.MIN_VALUES_FOR_CI} seeds)")
    return ar.figure_section(fig, out_dir, FIGURE, "Association vs clutter", rows, ar.CI_NOTE)


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
