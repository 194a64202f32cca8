"""Association figure: precision, recall and F1 of the association decisions against clutter (spurious
measurements per scan), one line per strategy, mean and 95 % CI over seeds (the individual values where there are fewer than 3).
Reads: results.jsonl columns clutter, assoc, assoc_f1 (assoc_precision, assoc_recall when present)."""

import sys

from . import results as ar

FIGURE = "association_vs_clutter.png"


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "clutter", "assoc_f1") or df["clutter"].nunique() < 2:
        return []
    df = df[df["assoc_f1"].notna()]
    metrics = [m for m in ("assoc_f1", "assoc_precision", "assoc_recall") if ar.has_data(df, m)]
    fig, axes = ar.plt.subplots(1, len(metrics), figsize=(4.6 * len(metrics), 4.0), layout="constrained",
                                squeeze=False, sharey=True)
    rows = []
    for ax, metric in zip(axes[0], metrics):
        for name, g in ar.lines_for(df, "clutter", collapse_identical_maps=True):
            s = ar.summarize(g, ["clutter"], metric)
            ax.errorbar(s["clutter"], s["mean"], yerr=ar.error_bars(s), marker="o", capsize=3, label=name)
            if metric == "assoc_f1":
                for _, r in s.iterrows():
                    rows.append({"strategy": name, "clutter (/scan)": r["clutter"], "F1": r["text"], "seeds": r["n"]})
        ax.set_xlabel("clutter (spurious measurements per scan)")
        ax.set_title({"assoc_f1": "F1", "assoc_precision": "precision", "assoc_recall": "recall"}[metric])
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("score")
    axes[0][0].legend(fontsize=8)
    return ar.figure_section(fig, out_dir, FIGURE, "Association vs clutter", rows, ar.CI_NOTE)


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
