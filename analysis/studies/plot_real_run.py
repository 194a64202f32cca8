#!/usr/bin/python3
"""Trajectory-and-map plot of one `arbor run` on a real dataset.

Inputs: the run directory (trajectory.tum, map.csv, result.json) and, for the ground truth overlay, the
scenario file the run used (truth poses, surveyed landmarks, GPS track; see docs/datasets.md). Writes PNG.
Usage: analysis/studies/plot_real_run.py RUN_DIR --scenario FILE --out FIG.png [--title TEXT]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import results as ar  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_dir")
    ap.add_argument("--scenario", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="")
    args = ap.parse_args()

    poses, surveyed, track = ar.read_scenario_truth(args.scenario)
    truth = poses[["t", "x", "y"]].to_numpy(dtype=float)
    landmarks = surveyed[["x", "y"]].to_numpy(dtype=float)
    gps = track[["t", "x", "y"]].to_numpy(dtype=float)
    est = ar.read_tum(f"{args.run_dir}/trajectory.tum")[["t", "x", "y"]].to_numpy(dtype=float)
    est_map = ar.read_map_csv(f"{args.run_dir}/map.csv")[["x", "y"]].to_numpy(dtype=float)
    result = ar.read_result(args.run_dir)

    fig, ax = plt.subplots(figsize=(7, 6))
    if len(gps):
        # The filter's frame is arbitrary on GPS-only data: align the estimate to GPS as the metric does.
        inside = (gps[:, 0] >= est[0, 0]) & (gps[:, 0] <= est[-1, 0])
        ex = np.interp(gps[inside, 0], est[:, 0], est[:, 1])
        ey = np.interp(gps[inside, 0], est[:, 0], est[:, 2])
        r, t = ar.align_se2(np.c_[ex, ey], gps[inside, 1:3])
        est[:, 1:3] = (r @ est[:, 1:3].T).T + t
        if len(est_map):
            est_map = (r @ est_map.T).T + t
        ax.plot(gps[:, 1], gps[:, 2], ".", ms=1.5, color="0.6", label="GPS")
    if len(truth):
        ax.plot(truth[:, 1], truth[:, 2], "-", lw=0.8, color="0.5", label="ground truth")
    ax.plot(est[:, 1], est[:, 2], "-", lw=0.8, color="C0", label="estimate (trajectory.tum)")
    if len(landmarks):
        ax.plot(landmarks[:, 0], landmarks[:, 1], "k+", ms=8, label="surveyed landmarks")
    if len(est_map):
        ax.plot(est_map[:, 0], est_map[:, 1], "o", mfc="none", color="C3", ms=4, label="estimated map")
    cfg = result.get("config", {})
    ate = result.get("ate_rmse_m")
    ate_text = f"ATE {ate:.2f} m" if ate is not None else "no ATE"
    ax.set_title(args.title or f"{cfg.get('filter', '')} / {cfg.get('assoc', '')}, {cfg.get('particles', '')} particles: {ate_text}")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(args.out, dpi=130)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
