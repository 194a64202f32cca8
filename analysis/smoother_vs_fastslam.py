#!/usr/bin/python3
"""Smoother vs FastSLAM accuracy table and plot from result.json files alone (DESIGN.md §5, §8).

Reads every result.json under the given directories (with trajectory.tum and a truth.tum one level up, as
experiments/scripts/smoother_comparison.sh writes them, the aligned ATE is computed where a result lacks it) (default: results/smoothing/*/comparison), groups runs by
scenario, and prints one row per (scenario, method): ATE RMSE (as stored, and SE(2)-aligned where present),
landmark RMSE, and the ratio of FastSLAM's aligned ATE to the smoother's on the same scenario (DESIGN.md §10
target: <= 1.3). Writes the table as CSV and a bar plot beside the first input directory.

Usage: /usr/bin/python3 analysis/smoother_vs_fastslam.py [DIR...]
"""
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402


def method_of(result):
    c = result["config"]
    if c.get("smoother"):
        return "smoother"
    return f'{c["filter"]} M={c["particles"]}'


def read_tum(path):
    import numpy as np
    data = np.loadtxt(path, comments="#", ndmin=2)
    return data[:, 0], data[:, 1:3]


def aligned_ate(trajectory_path, truth_path):
    """SE(2)-aligned position RMSE (closed-form 2-D Procrustes, Umeyama 1991 without scale) of the estimate
    interpolated at the truth's times: the same definition as core/metrics' absolute_trajectory_error."""
    import numpy as np
    te, pe = read_tum(trajectory_path)
    tt, pt = read_tum(truth_path)
    keep = (tt >= te[0]) & (tt <= te[-1])
    tt, pt = tt[keep], pt[keep]
    a = np.column_stack([np.interp(tt, te, pe[:, 0]), np.interp(tt, te, pe[:, 1])])
    ma, mb = a.mean(0), pt.mean(0)
    u, _, vt = np.linalg.svd((a - ma).T @ (pt - mb))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    rot = vt.T @ np.diag([1.0, d]) @ u.T
    err = (a - ma) @ rot.T + mb - pt
    return float(np.sqrt((err ** 2).sum(1).mean()))


def load(dirs):
    rows = []
    for d in dirs:
        for path in sorted(glob.glob(os.path.join(d, "**", "result.json"), recursive=True)):
            with open(path) as f:
                r = json.load(f)
            c = r["config"]
            aligned = r.get("ate_aligned_rmse_m")
            here = os.path.dirname(path)
            truth = os.path.join(os.path.dirname(here), "truth.tum")
            if aligned is None and os.path.exists(truth) and os.path.exists(os.path.join(here, "trajectory.tum")):
                aligned = aligned_ate(os.path.join(here, "trajectory.tum"), truth)
            rows.append({
                "scenario": os.path.basename(c.get("scenario") or c.get("isam") or "?"),
                "method": method_of(r),
                "seed": c.get("seed"),
                "ate_m": r.get("ate_rmse_m"),
                "ate_aligned_m": aligned,
                "landmark_rmse_m": r.get("landmark_rmse_m"),
                "wall_s": r.get("wall_time_s"),
                "path": path,
            })
    return pd.DataFrame(rows)


def main():
    dirs = sys.argv[1:] or sorted(glob.glob("results/smoothing/*/comparison"))
    if not dirs:
        sys.exit("no result directories given or found under results/smoothing/*/comparison")
    df = load(dirs)
    if df.empty:
        sys.exit("no result.json files found")
    smoother = df[df.method == "smoother"].set_index("scenario")
    for col in ("ate_m", "ate_aligned_m"):
        df[col + "_vs_smoother"] = df.apply(
            lambda r: r[col] / smoother.loc[r.scenario, col]
            if r.scenario in smoother.index and r[col] is not None and smoother.loc[r.scenario, col] else None,
            axis=1)
    table = df.drop(columns=["path"]).sort_values(["scenario", "method"])
    pd.set_option("display.width", 200)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    summary = table.groupby("method")[["ate_m", "ate_aligned_m", "landmark_rmse_m", "ate_aligned_m_vs_smoother"]].median()
    print("\nmedian over scenarios:")
    print(summary.to_string(float_format=lambda v: f"{v:.3f}"))
    out = dirs[0]
    table.to_csv(os.path.join(out, "smoother_vs_fastslam.csv"), index=False)
    pivot = table.pivot_table(index="scenario", columns="method", values="ate_aligned_m")
    ax = pivot.plot.bar(figsize=(8, 4), rot=0)
    ax.set_ylabel("SE(2)-aligned ATE RMSE [m]")
    ax.set_title("FastSLAM beside the Ceres smoother (true association)")
    plt.tight_layout()
    plt.savefig(os.path.join(out, "smoother_vs_fastslam.png"), dpi=120)
    print(f"\nwrote {out}/smoother_vs_fastslam.csv and .png")


if __name__ == "__main__":
    main()
