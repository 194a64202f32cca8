"""Trajectory-and-map figure of one run: estimated trajectory (trajectory.tum) and map (map.csv) over the
scenario's ground truth (poses, landmarks, GPS). Usage: PYTHONPATH=analysis /usr/bin/python3 -m arbor_analysis.trajectory RUN_DIR [--scenario FILE] [--out PNG].
The scenario is taken from RUN_DIR/result.json (config.scenario) unless given."""

import argparse
import os
import sys

from . import results as ar


def find_scenario(run_dir, sweep_dir=None):
    """The scenario file of a run: result.json's config.scenario, tried as written, relative to the run's
    sweep directory and relative to the run directory."""
    try:
        path = ar.read_result(run_dir).get("config", {}).get("scenario")
    except (OSError, ValueError):
        return None
    if not path:
        return None
    for base in ("", sweep_dir or "", run_dir, os.path.dirname(os.path.dirname(run_dir))):
        candidate = os.path.join(base, path) if base else path
        if os.path.exists(candidate):
            return candidate
    # A sweep passes paths like OUT/scenarios/x.scn; the sweep may have moved since.
    candidate = os.path.join(os.path.dirname(os.path.dirname(run_dir)), "scenarios", os.path.basename(path))
    return candidate if os.path.exists(candidate) else None


def plot_run(run_dir, out_png, scenario=None, title=None):
    fig, ax = ar.new_figure(6.4, 6.0)
    scenario = scenario or find_scenario(run_dir)
    if scenario:
        poses, landmarks, gps = ar.read_scenario_truth(scenario)
        if not landmarks.empty:
            ax.scatter(landmarks["x"], landmarks["y"], marker="x", s=18, color="black", label="true landmarks")
        if not poses.empty:
            ax.plot(poses["x"], poses["y"], color="black", linewidth=1.0, label="true trajectory")
        if not gps.empty:
            ax.scatter(gps["x"], gps["y"], s=4, color="grey", label="GPS")
    tum = os.path.join(run_dir, "trajectory.tum")
    if os.path.exists(tum):
        est = ar.read_tum(tum)
        ax.plot(est["x"], est["y"], color="tab:blue", linewidth=1.2, label="estimated trajectory")
    map_csv = os.path.join(run_dir, "map.csv")
    if os.path.exists(map_csv):
        m = ar.read_map_csv(map_csv)
        ax.scatter(m["x"], m["y"], s=14, facecolors="none", edgecolors="tab:red", label="estimated landmarks")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title or os.path.basename(os.path.normpath(run_dir)), fontsize=8)
    ax.legend(fontsize=7, loc="best")
    ar.save_figure(fig, os.path.dirname(out_png) or ".", os.path.basename(out_png))
    return out_png


def make(df, out_dir, results_path=None):
    """For the report: the best and the worst run by ATE among those whose run directory is present."""
    if results_path is None or not os.path.isdir(results_path):
        return []
    df = ar.ok_rows(df)
    if "run_dir" not in df or not ar.has_data(df, "ate_rmse_m"):
        return []
    df = df[df["run_dir"].map(lambda d: isinstance(d, str) and os.path.exists(os.path.join(results_path, d, "trajectory.tum")))]
    df = df[df["ate_rmse_m"].notna()].sort_values("ate_rmse_m")
    if df.empty:
        return []
    picks = [("best", df.iloc[0])] + ([("worst", df.iloc[-1])] if len(df) > 1 else [])
    text = []
    for tag, row in picks:
        name = f"trajectory_{tag}.png"
        plot_run(os.path.join(results_path, row["run_dir"]), os.path.join(out_dir, name),
                 title=f"{tag} ATE {row['ate_rmse_m']:.3g} m: {row['key']}")
        text.append(f"![{tag} run]({name})")
    return [ar.Section("Trajectories and maps", "Best and worst run by ATE.\n\n" + "\n".join(text) + "\n")]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("run_dir")
    parser.add_argument("--scenario", help="scenario file with the ground truth (default: from result.json)")
    parser.add_argument("--out", help="output PNG (default: RUN_DIR/trajectory.png)")
    args = parser.parse_args()
    out = args.out or os.path.join(args.run_dir, "trajectory.png")
    print(plot_run(args.run_dir, out, args.scenario))
    return 0


if __name__ == "__main__":
    sys.exit(main())
