#!/usr/bin/python3
"""Where a simulated run goes wrong, scan by scan: the best particle's position and heading error against
the truth, and each of its association decisions classed against the measurements' true landmark ids.

Classes of a measurement of a true landmark: `first` (it starts that landmark's first map landmark),
`right` (paired with that first map landmark), `duplicate` (it starts or updates another map landmark of the
same true landmark), `wrong` (paired with a map landmark started from another true landmark or from clutter),
`missed` (left unpaired). Of a clutter measurement: `clutter_paired` (paired with an existing map landmark);
the others start provisional landmarks or are dropped, which costs nothing. A map landmark belongs to the
true landmark (or clutter) of the measurement that started it; a prior map's landmarks belong to none, so
pairing them counts as `wrong`.
The pose is the best particle's lineage (trajectory_best.tum), matched to the truth by time.

Usage: trace_run.py SCENARIO RUN_DIR [--from SCAN] [--to SCAN] [--csv]
Prints one row per scan in [from, to) and a summary: the counts over the whole run, and the first scan whose
heading error exceeds 1, 2 and 5 degrees. Needs a scenario with true ids (`arbor simulate`).
"""
import argparse
import math
import os
import sys

import pandas as pd

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import results as ar  # noqa: E402

COUNTS = ["first", "right", "duplicate", "wrong", "missed", "clutter_paired"]


def classify(steps, decisions):
    """One row of counts per step that has decisions, from associations.csv rows (step, measurement, landmark)."""
    first_of = {}  # true id -> its first map landmark
    owner = {}     # map landmark -> the true id (or -1: clutter) of the measurement that started it
    rows = {}
    for step, k, lm in decisions.itertuples(index=False):
        counts = rows.setdefault(step, dict.fromkeys(COUNTS, 0))
        truth = steps[step][2][k]
        if truth is None:
            raise ValueError(f"step {step}, measurement {k}: the scenario gives no true id, so there is nothing to "
                             "compare with (run `arbor simulate` for one that does)")
        new = lm >= 0 and lm not in owner
        if new:
            owner[lm] = truth
        if truth < 0:
            counts["clutter_paired"] += lm >= 0 and not new
        elif lm < 0:
            counts["missed"] += 1
        elif truth not in first_of and new:
            first_of[truth] = lm
            counts["first"] += 1
        elif lm == first_of.get(truth):
            counts["right"] += 1
        elif owner.get(lm) == truth:
            counts["duplicate"] += 1
        else:
            counts["wrong"] += 1
    return rows


def trace(scenario, run_dir):
    steps = ar.read_scenario_steps(scenario)
    best = f"{run_dir}/trajectory_best.tum"  # the path its decisions were made along (before 3f0d391: trajectory.tum)
    estimate = ar.read_tum(best if os.path.exists(best) else f"{run_dir}/trajectory.tum")
    # The last estimate at each time: a run writes its start pose and then step 0's at the same time.
    by_time = {round(t, 9): (x, y, th) for t, x, y, th in zip(estimate.t, estimate.x, estimate.y, estimate.theta)}
    decisions = pd.read_csv(f"{run_dir}/associations.csv")
    counts = classify(steps, decisions)
    rows = []
    for index, (time, true_pose, labels) in enumerate(steps):
        if not labels:
            continue
        tx, ty, tth = true_pose or (math.nan, math.nan, math.nan)
        x, y, th = by_time.get(round(time, 9), (math.nan, math.nan, math.nan))
        heading = math.degrees(math.remainder(th - tth, 2 * math.pi))
        rows.append({"scan": index, "time_s": time, "position_error_m": math.hypot(x - tx, y - ty),
                     "heading_error_deg": heading, "measurements": len(labels),
                     "clutter": sum(label == -1 for label in labels),
                     **counts.get(index, dict.fromkeys(COUNTS, 0))})
    return pd.DataFrame(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenario")
    parser.add_argument("run_dir")
    parser.add_argument("--from", dest="first", type=int, default=0, help="first scan (step index) to list")
    parser.add_argument("--to", dest="last", type=int, default=None, help="scan (step index) to stop before")
    parser.add_argument("--csv", action="store_true", help="CSV rows instead of an aligned table")
    args = parser.parse_args()
    try:
        df = trace(args.scenario, args.run_dir)
    except (OSError, ValueError) as e:
        print(f"trace_run.py: {e}", file=sys.stderr)
        return 1
    if df.empty:
        print(f"trace_run.py: {args.scenario} has no scan with measurements", file=sys.stderr)
        return 1
    last = args.last if args.last is not None else math.inf
    shown = df[(df.scan >= args.first) & (df.scan < last)]
    if args.csv:
        print(shown.to_csv(index=False, float_format="%.4g"), end="")
    else:
        print(shown.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    totals = ", ".join(f"{c} {int(df[c].sum())}" for c in COUNTS)
    print(f"# whole run: {len(df)} scans; {totals}")
    for degrees in (1, 2, 5):
        over = df[df.heading_error_deg.abs() > degrees]
        print(f"# heading error first over {degrees} deg: " + (f"scan {int(over.scan.iloc[0])}" if len(over) else "never"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
