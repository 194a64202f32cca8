#!/usr/bin/python3
"""The smoother given a filter's own pairings (experiments/scripts/own_pairings_study.sh): per configuration and
world kind, how many runs fail (analysis/arbor_analysis/failures.py: aligned ATE above 3x the reference
smoother's, which pairs by the true ids, or above dead reckoning's), and how many of their smoothed twins, the
Ceres solve with the run's own association decisions started from its trajectory and map, fail too.

A failed run whose twin passes lost only its path: its pairings were good enough, and revising past poses, which
no filter does, would have saved it. A failed run whose twin fails too paired wrongly (or left the solve a
minimum it cannot leave), and no path revision alone would save it. Per run it also counts the landmarks mapped
twice (a true landmark whose measurements went to more than one of the run's landmarks, each run landmark owned
by the true id most of its measurements have) and of those the copies started more than GAP_SCANS scans after
the true landmark was last measured: a loop the run did not close, which the association's F1 barely shows.

Usage: /usr/bin/python3 analysis/studies/own_pairings.py SWEEP   (writes SWEEP/own_pairings.md and .csv)
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import failures  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402
from arbor_analysis import run_studies  # noqa: E402


def twin_ate(sweep, key):
    """The smoothed twin's aligned ATE, or NaN where it did not finish."""
    path = os.path.join(sweep, "own_pairings", key, "result.json")
    if not os.path.exists(path):
        return np.nan
    with open(path, encoding="utf-8") as f:
        return json.load(f).get(failures.ATE, np.nan)


GAP_SCANS = 50  # a copy started this many scans after its landmark was last measured: a loop not closed


def mapped_twice(run_dir, scenario):
    """(true landmarks mapped more than once, copies started more than GAP_SCANS scans after the landmark's
    previous measurement) in one run, from its associations.csv and the scenario's true ids."""
    steps = run_studies.scenario_steps(scenario)
    votes, last_measured, late_copies = {}, {}, 0
    with open(os.path.join(run_dir, "associations.csv"), encoding="utf-8") as f:
        next(f)
        for line in f:
            step, measurement, landmark = (int(v) for v in line.split(","))
            truth = steps[step][2][measurement]
            if landmark < 0 or truth is None or truth < 0:
                continue
            if landmark not in votes and truth in last_measured and step - last_measured[truth] > GAP_SCANS:
                late_copies += 1
            votes.setdefault(landmark, {}).setdefault(truth, 0)
            votes[landmark][truth] += 1
            last_measured[truth] = step
    owners = {}
    for landmark, counts in votes.items():
        owner = max(counts, key=counts.get)
        owners[owner] = owners.get(owner, 0) + 1
    return sum(n - 1 for n in owners.values()), late_copies


def table(df):
    records = []
    for label, kind, g in run_studies.filter_groups(df):
        ref = g["smoother_ate_aligned_m"]
        # The twin judged as failures.py judges a run: in the run's place, unfinished where it left no ATE.
        twin = g["twin_ate_m"]
        as_run = g.assign(**{failures.ATE: twin, "status": np.where(twin.isna(), "failed", "ok")})
        twin_failed = failures.failed(as_run)
        records.append({
            "configuration": label, "scenarios": kind, "runs": len(g),
            "failures": int(g["failed"].sum()), "twin_failures": int(twin_failed.sum()),
            "path_only": int((g["failed"] & ~twin_failed).sum()),
            "both": int((g["failed"] & twin_failed).sum()),
            "twin_only": int((~g["failed"] & twin_failed).sum()),
            "median_ate_m": g[failures.ATE].median(), "median_twin_ate_m": g["twin_ate_m"].median(),
            "median_reference_m": ref.median(),
            "median_f1": g["assoc_f1"].median() if "assoc_f1" in g else np.nan,
            "median_mapped_twice": g["mapped_twice"].median(), "median_late_copies": g["late_copies"].median()})
    return ar.pd.DataFrame(records)


def markdown(t):
    lines = ["| configuration | scenarios | runs | failures | twins failing | failed, twin passes (path only) | "
             "both fail | only the twin fails | median ATE (m) | twins' median (m) | reference's median (m) | median F1 | "
             f"landmarks mapped twice, median | of them started after a gap of > {GAP_SCANS} scans |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in t.itertuples():
        lines.append(f"| {ar.md_text(r.configuration)} | {r.scenarios} | {r.runs} | {r.failures} | {r.twin_failures} | "
                     f"{r.path_only} | {r.both} | {r.twin_only} | {ar.fmt_num(r.median_ate_m)} | "
                     f"{ar.fmt_num(r.median_twin_ate_m)} | {ar.fmt_num(r.median_reference_m)} | {ar.fmt_num(r.median_f1)} | "
                     f"{ar.fmt_num(r.median_mapped_twice)} | {ar.fmt_num(r.median_late_copies)} |")
    return "\n".join(lines)


def study(sweep, df):
    # The runs the study smoothed (all, or those ONLY picked): each has its folder, with a result.json where
    # the twin finished.
    smoothed = df["key"].map(lambda k: os.path.isdir(os.path.join(sweep, "own_pairings", k)))
    df = df[(df["filter"] == "smoother") | smoothed]
    df = df.assign(twin_ate_m=[twin_ate(sweep, k) if f != "smoother" else np.nan for k, f in zip(df["key"], df["filter"])])
    counts = [mapped_twice(os.path.join(sweep, run), run_studies.scenario_path(sweep, os.path.join(sweep, run), scenario))
              if f != "smoother" else (np.nan, np.nan)
              for run, scenario, f in zip(df["run_dir"], df["scenario"], df["filter"])]
    df = df.assign(mapped_twice=[c[0] for c in counts], late_copies=[c[1] for c in counts])
    t = table(df)
    paragraphs = __doc__.split("\n\n")
    run_studies.write_tables(sweep, "own_pairings", "The smoother given each run's own pairings",
                             paragraphs[0].split(": ", 1)[1] + "\n\n" + paragraphs[1], t, markdown(t))
    return 0


if __name__ == "__main__":
    sys.exit(run_studies.main(__doc__, study))
