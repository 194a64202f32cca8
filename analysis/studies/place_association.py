#!/usr/bin/python3
"""Association errors by place (issue 41): of the pairings a run made with landmarks whose true id is known,
how many name the wrong true landmark but one within RADIUS metres of the right one, and how many a wrong
place. MRCLAM's 15 landmarks stand in clusters of two or three 0.18-0.25 m apart, closer than the camera's range
noise (sigma 0.11-0.19 m), so a geometric strategy (JCBB, NN) cannot tell a cluster's members apart and its
F1 against the barcodes counts those as false matches; the place count says what it got wrong otherwise.
Pairings with landmarks the run later dropped are not in its map.csv and are left out.
Usage: analysis/studies/place_association.py RUN_DIR... [--radius 0.3]   (run directories of `arbor run`)"""

import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import results as ar  # noqa: E402


def truth_positions(scenario_path):
    """True landmark id -> position, from the scenario's `landmark ID X Y` lines."""
    landmarks = ar.read_scenario_truth(scenario_path)[1]
    return {int(i): np.array([x, y]) for i, x, y in zip(landmarks["id"], landmarks["x"], landmarks["y"])}


def count(run_dir, radius):
    """(pairings scored, wrong id in the right place, wrong place) for one run directory."""
    scenario = ar.read_result(run_dir)["config"]["scenario"]
    steps = ar.read_scenario_steps(scenario)
    where = truth_positions(scenario)
    landmarks = ar.read_map_csv(os.path.join(run_dir, "map.csv"))
    label = {int(i): int(t) for i, t in zip(landmarks["id"], landmarks["truth_label"])}
    scored = near = far = 0
    with open(os.path.join(run_dir, "associations.csv"), encoding="utf-8") as f:
        for r in csv.DictReader(f):
            landmark = int(r["landmark"])
            truth = steps[int(r["step"])][2][int(r["measurement"])]
            if landmark < 0 or landmark not in label or truth is None or truth < 0:
                continue
            scored += 1
            guess = label[landmark]
            if guess == truth:
                continue
            close = guess in where and truth in where and np.linalg.norm(where[guess] - where[truth]) < radius
            near += close
            far += not close
    return scored, near, far


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--radius", type=float, default=0.3)
    args = parser.parse_args()
    total = np.zeros(3, dtype=int)
    for run in args.runs:
        total += count(run, args.radius)
    scored, near, far = total
    print(f"{len(args.runs)} runs, {scored} pairings scored: {near} ({100 * near / max(scored, 1):.1f} %) name another "
          f"landmark within {args.radius} m, {far} ({100 * far / max(scored, 1):.1f} %) a wrong place")


if __name__ == "__main__":
    main()
