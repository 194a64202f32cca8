#!/usr/bin/python3
"""The held-out protocol sweep (issue 41): per scenario group and configuration, the failure rate and the
tails of the SE(2)-aligned ATE, beside the Ceres smoother as the reference. Groups: each dataset on its own,
simulated worlds by world type and clutter rate, and all simulated worlds together. A run fails as
analysis/arbor_analysis/failures.py defines it (above 3x the smoother's aligned ATE on its scenario and seed, above dead
reckoning's, or not finished).

Columns: runs; failures (k/n and %); mean, median and p90 aligned ATE over the finished runs; median NEES; the
median consistency horizon (where the rows have it); total rejected_measurements (true pairings refused by
known association's gate); median association F1; the median aligned ATE over the smoother's median in the
same group.

Usage: /usr/bin/python3 analysis/studies/heldout.py RESULTS_DIR [--out DIR]
Writes DIR/heldout.md and DIR/heldout.csv (default DIR: RESULTS_DIR).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import failures  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402

ALL_SIMULATED = "all simulated worlds"


def simulated(df):
    return df["dataset"].isna() if "dataset" in df else ar.pd.Series(True, index=df.index)


def scenario_group(row):
    """The group a run's scenario belongs to: its dataset's name, or its world type and clutter rate."""
    dataset = row.get("dataset")
    if isinstance(dataset, str):
        return os.path.splitext(os.path.basename(dataset))[0]
    return f"{row['world']}, {ar.label(row, ['clutter'])}" if "clutter" in row else str(row["world"])


def group_rows(df):
    """(group, rows) in table order: datasets, simulated groups, then all simulated worlds together."""
    groups = ar.pd.Series([scenario_group(r) for _, r in df.iterrows()], index=df.index)
    sim = simulated(df)
    out = [(g, df[groups == g]) for g in sorted(groups[~sim].unique())]
    out += [(g, df[groups == g]) for g in sorted(groups[sim].unique())]
    if sim.any():
        out.append((ALL_SIMULATED, df[sim]))
    return out


def table(df):
    """One record per scenario group and configuration of df (rows of failures.mark_failures): summarise()'s
    numbers plus the median ATE's ratio to the smoother's median in the group."""
    configurations = failures.configurations(df)
    records = []
    for group, in_group in group_rows(df):
        stats = [(name, failures.summarise(runs[runs.index.isin(in_group.index)])) for name, runs in configurations]
        stats = [(name, s) for name, s in stats if s["runs"]]
        reference = dict(stats).get(failures.REFERENCE, {}).get("ate_aligned_median_m", np.nan)
        for name, s in stats:
            records.append({"scenarios": group, "configuration": name, **s,
                            "median_ratio_to_smoother": s["ate_aligned_median_m"] / reference})
    return records


def markdown(df, records):
    headers = [h for h, _, _ in failures.CELLS if h != "mean ATE ratio to smoother"]
    with_ratio = any(np.isfinite(r["median_ratio_to_smoother"]) for r in records)
    rows = []
    for r in records:
        row = {"scenarios": r["scenarios"], "configuration": r["configuration"], **failures.cells(r, df, headers)}
        if with_ratio:
            row["median ATE / smoother's"] = r["median_ratio_to_smoother"]
        rows.append(row)
    return ar.markdown_table(ar.pd.DataFrame(rows))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="the held-out sweep's results directory (results.jsonl) or file")
    parser.add_argument("--out", help="where heldout.md and heldout.csv go (default: the results directory)")
    args = parser.parse_args()
    out = args.out or ar.results_dir_of(args.results)
    df = ar.load_results(args.results)
    if df.empty or not ar.has_data(df, failures.ATE):
        print(f"heldout.py: no runs with {failures.ATE} in {args.results}", file=sys.stderr)
        return 1
    df = failures.mark_failures(df)
    records = table(df)
    os.makedirs(out, exist_ok=True)
    ar.pd.DataFrame(records).to_csv(os.path.join(out, "heldout.csv"), index=False)
    text = markdown(df, records)
    horizon = failures.HORIZON_NOTE + "\n\n" if ar.has_data(df, "consistency_horizon_scan") else ""
    with open(os.path.join(out, "heldout.md"), "w", encoding="utf-8") as f:
        f.write("# Held-out protocol: failures and tails per scenario group\n\n"
                f"{failures.DEFINITION} ATE: SE(2)-aligned ATE RMSE; p90: its 90th percentile over the runs. "
                "Rejected measurements: the total over the runs (true pairings refused by known association's "
                "gate). Median ATE / smoother's: the configuration's median over the smoother's median in the "
                f"same group.\n\n{horizon}{text}\n")
    print(text)
    print(f"wrote {os.path.join(out, 'heldout.md')}, heldout.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
