#!/usr/bin/python3
"""Association benchmark figures from results/association/<run>/association.csv (bench/association_benchmark.cc).

Left: median hypotheses vs n (log-log) per strategy, with fitted slopes; middle: median time per call vs m;
right: the locality tree vs the unrestricted interpretation tree (hypotheses vs n, m = 5).
Usage: /usr/bin/python3 analysis/studies/plot_association.py results/association/<run>/association.csv [out.png]
Prints every fitted slope it plots.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd


def slope(x, y):
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = (x > 0) & (y > 0)
    if keep.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log10(x[keep]), np.log10(y[keep]), 1)[0])


def hypotheses_vs_n(ax, rows, title, with_tests=False):
    """Median hypotheses per call against n, one log-log line per strategy, its fitted slope (and the time's)
    printed under `title` and in the legend; with_tests adds the compatibility tests per call."""
    for strategy, g in rows.groupby("strategy"):
        g = g.sort_values("n")
        s = slope(g.n, g.median_hypotheses)
        print(f"{title}: {strategy}: hypotheses slope {s:.2f}, time slope {slope(g.n, g.median_s):.2f}")
        ax.loglog(g.n, g.median_hypotheses, "o-", label=f"{strategy}{' hypotheses' if with_tests else ''} (slope {s:.2f})")
        if with_tests:
            ax.loglog(g.n, g.median_tests, "x--", alpha=0.6, label=f"{strategy} tests (slope {slope(g.n, g.median_tests):.2f})")


def main():
    path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else path.rsplit("/", 1)[0] + "/association.png"
    df = pd.read_csv(path, comment="#")
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))

    ax = axes[0]
    hypotheses_vs_n(ax, df[df.group == "n"], "vs n (m=10)")
    ax.set_xlabel("map landmarks n (all candidates)")
    ax.set_ylabel("median hypotheses per call")
    ax.set_title("hypotheses vs n, m = 10 + 2 clutter")
    ax.legend()

    ax = axes[1]
    for strategy, g in df[df.group == "m"].groupby("strategy"):
        g = g.sort_values("m")
        ax.semilogy(g.m, g.median_s * 1e3, "o-", label=f"{strategy} median")
        ax.semilogy(g.m, g.p90_s * 1e3, "x--", alpha=0.6, label=f"{strategy} p90")
        for _, row in g.iterrows():
            if row.m in (10, 20, 40):
                print(f"time per call: {strategy} m={row.m}: median {row.median_s * 1e3:.4f} ms, p90 {row.p90_s * 1e3:.4f} ms")
    ax.set_xlabel("true observations m (+ m/4 clutter), n = 200")
    ax.set_ylabel("time per call [ms]")
    ax.set_title("time vs m")
    ax.legend(fontsize=7)

    ax = axes[2]
    hypotheses_vs_n(ax, df[df.group == "tree_n"], "tree vs n (m=5)", with_tests=True)
    ax.set_xlabel("map landmarks n")
    ax.set_title("locality vs unrestricted tree, m = 5 + 1")
    ax.legend(fontsize=7)

    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
    design = df[df.group == "design"]
    if len(design):
        print(design[["strategy", "n", "m", "clutter", "seeds", "median_s", "p90_s", "f1", "jointly_compatible"]].to_string(index=False))


if __name__ == "__main__":
    main()
