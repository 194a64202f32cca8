"""Accuracy figure: trajectory error (ATE RMSE) and landmark RMSE against the number of particles, one line per
filter / map back end / association strategy, mean and 95 % CI over seeds (the individual values where there are fewer than 3).
Reads: results.jsonl columns particles, ate_rmse_m, landmark_rmse_m, filter, map, assoc, seed."""

import sys

from . import results as ar

FIGURE = "accuracy_vs_particles.png"
COLUMNS = {"ate_rmse_m": "ATE RMSE (m)", "landmark_rmse_m": "landmark RMSE (m)"}


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "particles", "ate_rmse_m") or df["particles"].nunique() < 2:
        return []
    metrics = [m for m in ("ate_rmse_m", "landmark_rmse_m") if ar.has_data(df, m)]
    fig, axes = ar.plt.subplots(1, len(metrics), figsize=(5.2 * len(metrics), 4.2), layout="constrained", squeeze=False)
    table = {}
    for ax, metric in zip(axes[0], metrics):
        for name, g in ar.lines_for(df, "particles", collapse_identical_maps=True):
            s = ar.summarize(g, ["particles"], metric)
            ax.errorbar(s["particles"], s["mean"], yerr=ar.error_bars(s), marker="o", capsize=3, label=name)
            for _, r in s.iterrows():
                table.setdefault((name, int(r["particles"])), {})[COLUMNS[metric]] = r["text"]
                table[(name, int(r["particles"]))]["seeds"] = int(r["n"])
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.set_xlabel("particles")
        ax.set_ylabel({"ate_rmse_m": "ATE RMSE (m)", "landmark_rmse_m": "landmark RMSE (m)"}[metric])
    axes[0][0].legend(fontsize=8)
    fig.suptitle(f"Accuracy vs particles (mean; ± 95 % CI where there are ≥ {ar.MIN_VALUES_FOR_CI} seeds)")
    ar.save_figure(fig, out_dir, FIGURE)
    rows = [dict(configuration=k[0], particles=k[1], **v) for k, v in sorted(table.items())]
    frame = ar.pd.DataFrame(rows)
    print(frame.to_string(index=False))
    return [ar.Section("Accuracy vs particles",
                       f"![accuracy vs particles]({FIGURE})\n\n{ar.CI_NOTE}\n\n{ar.markdown_table(frame)}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
