"""Summary of run.sh: failures (analysis/arbor_analysis/failures.py: aligned ATE above 3x the smoother's or dead
reckoning's), mean / median / p90 and the NEES median per inflation and association, over all 216 worlds and
per world kind; writes OUT/runs.csv.

Usage: summarize.py SWEEP_DIR OUT ORACLE_RESULTS_CSV (as run.sh calls it)."""
import glob
import json
import os
import re
import sys

import pandas as pd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), *[os.pardir] * 4, "analysis"))
from arbor_analysis import failures  # noqa: E402

KEYS = ["world", "clutter", "seed"]
COLUMNS = KEYS + ["ate_aligned_rmse_m", "dead_reckoning_ate_m", "nees_median"]


def inflated_runs(out):
    """One row per run of run.sh, its configuration named '<assoc> k<K>'."""
    rows = []
    for path in glob.glob(os.path.join(out, "runs", "*", "*", "result.json")):
        config, name = path.split(os.sep)[-3:-1]
        world, clutter, seed = re.match(r"(\w+)-n300-t600-c(\d+)-s(\d+)", name).groups()
        k, assoc = config.split("-")
        with open(path, encoding="utf-8") as f:
            result = json.load(f)
        rows.append(dict(world=world, clutter=float(clutter), seed=int(seed), cfg=f"{assoc} {k}",
                         **{c: result[c] for c in COLUMNS[3:]}))
    return pd.DataFrame(rows)


def summary(group):
    ate = group["ate_aligned_rmse_m"]
    return pd.Series(dict(n=len(group), fail=int(group["failed"].sum()), mean=ate.mean(), med=ate.median(),
                          p90=ate.quantile(0.9), nees=group["nees_median"].median()))


def main(sweep, out, oracle_csv):
    sweep_rows = pd.read_csv(os.path.join(sweep, "results.csv"))
    smoother = sweep_rows[sweep_rows["filter"] == "smoother"][KEYS + ["ate_aligned_rmse_m"]]
    smoother = smoother.rename(columns={"ate_aligned_rmse_m": "smoother_ate_aligned_m"})
    jcbb = sweep_rows[(sweep_rows["filter"] == "fastslam2") & sweep_rows["relocalize"].eq(False)][COLUMNS]
    oracle = pd.read_csv(oracle_csv)
    known = oracle[(oracle["filter"] == "fastslam2") & (oracle["assoc"] == "known")][COLUMNS]
    runs = pd.concat([jcbb.assign(cfg="jcbb k1"), known.assign(cfg="known k1"), inflated_runs(out)])
    runs = runs.merge(smoother, on=KEYS)
    runs["failed"] = failures.failed(runs)
    runs.to_csv(os.path.join(out, "runs.csv"), index=False)
    print(runs.groupby("cfg").apply(summary).round(3).to_string())
    print(runs.groupby(["world", "cfg"]).apply(summary).round(3).to_string())


if __name__ == "__main__":
    main(*sys.argv[1:4])
