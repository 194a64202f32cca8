#!/usr/bin/python3
"""Path degeneracy (`arbor run --record-lineage`): how far back a FastSLAM particle set can still revise its
path, against how long the loops it has to close are. Per configuration and world kind: the failures
(analysis/arbor_analysis/failures.py), the set's memory, and the loops it closes beyond that memory.

The memory at a scan is steps.csv's ancestor_age_s: the time back to the newest pose every particle's path
shares. Nothing older can change any more, whatever the set sees later (resampling copies whole paths: path
degeneracy; Bailey, Nieto & Nebot 2006; Doucet & Johansen 2011). Where the paths share no pose yet, the memory
is the whole run so far. A loop is a scan that measures a landmark last measured at least LOOP_S seconds before
(the scenario's true ids); it closes beyond the memory when that gap is longer than the memory at the scan: the
drift the robot built up along the loop is then in every particle's path, and the re-sighting can correct the
pose and the map, but no longer the path that the ATE scores.

Usage: /usr/bin/python3 analysis/studies/lineage.py SWEEP   (writes SWEEP/lineage.md and .csv)
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import failures  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402
from arbor_analysis import run_studies  # noqa: E402

LOOP_S = 20.0  # a landmark measured again after this long: the robot went away and came back


def loop_gaps(scenario):
    """{step index: the longest time since a landmark that step measures was last measured, when >= LOOP_S}."""
    last, gaps = {}, {}
    for k, (time_s, _, ids) in enumerate(run_studies.scenario_steps(scenario)):
        longest = max((time_s - last[i] for i in ids if i is not None and i >= 0 and i in last), default=0.0)
        if longest >= LOOP_S:
            gaps[k] = longest
        for i in ids:
            if i is not None and i >= 0:
                last[i] = time_s
    return gaps


def run_lineage(run_dir, scenario):
    """(median memory over the scans in s, loops, loops closed beyond the memory) of one run."""
    steps = ar.pd.read_csv(os.path.join(run_dir, "steps.csv"))
    if "ancestor_age_s" not in steps:
        raise ValueError(f"{run_dir}/steps.csv: no ancestor_age_s column (run it with --record-lineage)")
    scans = steps[steps["scan"] == 1]
    start = run_studies.scenario_steps(scenario)[0][0]
    memory = scans["ancestor_age_s"].fillna(scans["time_s"] - start)  # no shared pose: the whole run so far
    memory_at = dict(zip(scans["step"], memory))
    gaps = loop_gaps(scenario)
    beyond = sum(1 for k, gap in gaps.items() if k in memory_at and gap > memory_at[k])
    return float(memory.median()), len(gaps), beyond


def table(df):
    records = []
    for label, kind, g in run_studies.filter_groups(df):
        failed = g["failed"]
        records.append({
            "configuration": label, "scenarios": kind, "runs": len(g), "failures": int(failed.sum()),
            "median_ate_m": g[failures.ATE].median(), "median_memory_s": g["memory_s"].median(),
            "p90_memory_s": g["memory_s"].quantile(0.9), "loops": int(g["loops"].sum()),
            "loops_beyond": int(g["beyond"].sum()), "memory_failed_s": g.loc[failed, "memory_s"].median(),
            "memory_passed_s": g.loc[~failed, "memory_s"].median()})
    return ar.pd.DataFrame(records)


def markdown(t):
    lines = [f"| configuration | scenarios | runs | failures | median ATE (m) | memory, median of the runs' medians (s) | "
             f"p90 (s) | loops (re-sightings after ≥ {ar.fmt_num(LOOP_S)} s) | closed beyond the memory | "
             "memory of the failed runs, median (s) | of the others (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in t.itertuples():
        lines.append(f"| {ar.md_text(r.configuration)} | {r.scenarios} | {r.runs} | {r.failures} | "
                     f"{ar.fmt_num(r.median_ate_m)} | {ar.fmt_num(r.median_memory_s)} | {ar.fmt_num(r.p90_memory_s)} | "
                     f"{r.loops} | {r.loops_beyond} | {ar.fmt_num(r.memory_failed_s)} | {ar.fmt_num(r.memory_passed_s)} |")
    return "\n".join(lines)


def study(sweep, df):
    particles = df["filter"] != "smoother"
    stats = [run_lineage(os.path.join(sweep, run), run_studies.scenario_path(sweep, os.path.join(sweep, run), scenario)) if p
             else (np.nan, 0, 0)
             for run, scenario, p in zip(df["run_dir"], df["scenario"], particles)]
    df = df.assign(memory_s=[s[0] for s in stats], loops=[s[1] for s in stats], beyond=[s[2] for s in stats])
    t = table(df)
    run_studies.write_tables(sweep, "lineage", "Path degeneracy: the particle set's memory and the loops it closes",
                             "\n\n".join(__doc__.split("\n\n")[:2]), t, markdown(t))
    return 0


if __name__ == "__main__":
    sys.exit(run_studies.main(__doc__, study))
