#!/usr/bin/python3
"""Which path a FastSLAM run reports (experiments/heldout/*-estimate_*.toml): per configuration and scenario kind,
failures (analysis/arbor_analysis/failures.py) and the spread of the aligned ATE for the reported path, the
weighted mean of the particles' whole paths (ate_aligned_rmse_m), and for the best particle's path beside it
(ate_best_aligned_rmse_m), judged against the same smoother runs.

Usage: /usr/bin/python3 analysis/studies/path_estimates.py SWEEP   (writes SWEEP/path_estimates.md and .csv)
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import failures  # noqa: E402
from arbor_analysis import results as ar  # noqa: E402
from arbor_analysis import run_studies  # noqa: E402

BEST = "ate_best_aligned_rmse_m"
ESTIMATES = [("mean path", failures.ATE), ("best particle", BEST)]


def spread(ate):
    ate = ate.dropna()
    return [ate.mean(), ate.median(), ate.quantile(0.9)] if len(ate) else [np.nan] * 3


def study(sweep, df):
    if BEST not in df:
        print(f"{sweep}: no {BEST} column (a sweep from before the mean path, or without the metric)", file=sys.stderr)
        return 1
    best_as_headline = df.copy()
    best_as_headline[failures.ATE] = best_as_headline[BEST].where(best_as_headline["filter"] != "smoother",
                                                                  best_as_headline[failures.ATE])
    judged = {"mean path": df, "best particle": failures.mark_failures(best_as_headline)}
    rows = []
    for label, kind, g in run_studies.filter_groups(df):
        row = {"configuration": label, "scenarios": kind, "runs": len(g)}
        for name, column in ESTIMATES:
            marked = judged[name].loc[g.index]
            row[f"{name}: failures"] = int(marked["failed"].sum())
            row[f"{name}: mean"], row[f"{name}: median"], row[f"{name}: p90"] = spread(marked[failures.ATE])
        rows.append(row)
    table = ar.pd.DataFrame(rows)
    lines = ["| configuration | scenarios | runs | failures: mean path / best particle | mean / median / p90 aligned ATE (m): mean path | the same: best particle |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        cells = [f"{ar.fmt_num(r[f'{n}: mean'])} / {ar.fmt_num(r[f'{n}: median'])} / {ar.fmt_num(r[f'{n}: p90'])}"
                 for n, _ in ESTIMATES]
        lines.append(f"| {r['configuration']} | {r['scenarios']} | {r['runs']} | "
                     f"{r['mean path: failures']} / {r['best particle: failures']} | {cells[0]} | {cells[1]} |")
    run_studies.write_tables(sweep, "path_estimates", "The reported path: the particles' mean path or the best one",
                             failures.DEFINITION, table, "\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(run_studies.main(__doc__, study))
