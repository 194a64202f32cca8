"""Failures and tails (issue 41): per configuration, how many runs failed and how the SE(2)-aligned ATE spreads
(mean, median, 90th percentile), beside the Ceres smoother's runs as the reference. A mean alone hides a
configuration that is good on most seeds and lost on a few; the failure rate counts those runs instead.
Reads: results.jsonl columns status, ate_aligned_rmse_m, dead_reckoning_ate_m, nees_median and, where present,
consistency_horizon_scan, rejected_measurements, assoc_f1; the smoother's rows of the same scenarios and seeds."""

import sys

import numpy as np

from . import results as ar

ATE = "ate_aligned_rmse_m"
# A run whose aligned ATE is above this multiple of the smoother's on the same scenario and seed has failed.
# DESIGN.md §10 asks for 1.3x with true association; 3x is far enough past it that a run beyond is lost, not
# merely less accurate than the batch solution.
SMOOTHER_FACTOR = 3.0
REFERENCE = "smoother (reference)"
DEFINITION = (f"A run **fails** when its SE(2)-aligned ATE is above {ar.fmt_num(SMOOTHER_FACTOR)}× the smoother's "
              "on the same scenario and seed (where the smoother ran) or above dead reckoning's ATE (odometry "
              "alone does better), or when it did not finish (failed, crashed, timeout). Failures count every run; "
              "the ATE, NEES and horizon columns are over the runs that finished.")


def finished(df):
    return df["status"] == "ok" if "status" in df else ar.pd.Series(True, index=df.index)


def with_smoother_reference(df):
    """df (index reset) with smoother_ate_aligned_m, the smoother's aligned ATE on the row's scenario and seed,
    and ate_ratio_to_smoother on every finished non-smoother row; NaN elsewhere and where no smoother ran."""
    df = df.reset_index(drop=True)
    df["smoother_ate_aligned_m"] = np.nan
    if ar.has_data(df, "filter", ATE) and "seed" in df:
        keys = [c for c in ar.SCENARIO if c in df] + ["seed"]
        smoother = df[finished(df) & (df["filter"] == "smoother")].dropna(subset=[ATE])
        # At most one smoother run per scenario and seed; dropping repeats keeps the left merge one row per row.
        smoother = smoother.drop_duplicates(subset=keys, keep="last")
        matched = df[keys].merge(smoother[keys + [ATE]], on=keys, how="left")[ATE]  # null keys match null keys
        judged = finished(df) & (df["filter"] != "smoother")
        df["smoother_ate_aligned_m"] = matched.where(judged).to_numpy()
    df["ate_ratio_to_smoother"] = (df[ATE] if ATE in df else np.nan) / df["smoother_ate_aligned_m"]
    return df


def failed(df):
    """Per row of with_smoother_reference(df): whether the run failed (DEFINITION). A comparison with a missing
    value is False, so a run is judged only against the references it has."""
    ate = df[ATE] if ATE in df else ar.pd.Series(np.nan, index=df.index)
    above_smoother = ate > SMOOTHER_FACTOR * df["smoother_ate_aligned_m"]
    above_dead_reckoning = ate > df["dead_reckoning_ate_m"] if "dead_reckoning_ate_m" in df else False
    return ~finished(df) | above_smoother | above_dead_reckoning


def mark_failures(df):
    """df with the smoother reference columns and a boolean `failed` per row."""
    df = with_smoother_reference(df)
    df["failed"] = failed(df)
    return df


def configurations(df):
    """(label, rows) per configuration: the smoother's rows first, as the reference, then one per combination of
    the method columns and particles. Map back ends whose output agrees run for run are one configuration,
    each run once: their copies of a run are not further runs."""
    out = []
    if "filter" not in df:
        return [("all runs", df)]
    smoother = df[df["filter"] == "smoother"]
    if not smoother.empty:
        out.append((REFERENCE, smoother))
    filters = df[df["filter"] != "smoother"]
    by = [c for c in ar.method_columns(df) + ["particles"] if c in df]
    by, filters = ar.drop_identical_map_backends(filters, by, [c for c in ar.SCENARIO if c in df] + ["seed"])
    shown = ar.varying(filters, by) or ["filter"]
    for _, rows in filters.groupby(by, sort=True, dropna=False):
        out.append((ar.label(rows.iloc[0], shown), rows))
    return out


def median_of(df, column):
    return float(df[column].median()) if ar.has_data(df, column) else float("nan")


def summarise(runs):
    """The statistics of one configuration's runs (rows of mark_failures), as numbers."""
    done = runs[finished(runs)]
    ate = ar.finite_values(done[ATE]) if ATE in done else np.empty(0)
    horizon = done["consistency_horizon_scan"] if "consistency_horizon_scan" in done else ar.pd.Series(dtype=float)
    return {"runs": len(runs), "finished": len(done), "failures": int(runs["failed"].sum()),
            "failure_rate": runs["failed"].mean() if len(runs) else float("nan"),
            "ate_aligned_mean_m": float(ate.mean()) if len(ate) else float("nan"),
            "ate_aligned_median_m": float(np.median(ate)) if len(ate) else float("nan"),
            "ate_aligned_p90_m": float(np.percentile(ate, 90)) if len(ate) else float("nan"),
            "nees_median": median_of(done, "nees_median"),
            "consistency_horizon_median_scan": median_of(done, "consistency_horizon_scan"),
            "consistency_horizon_runs": int(horizon.notna().sum()),
            "rejected_measurements": (float(done["rejected_measurements"].sum(min_count=1))
                                      if "rejected_measurements" in done else float("nan")),
            "assoc_f1_median": median_of(done, "assoc_f1"),
            "ratio_to_smoother_mean": float(done["ate_ratio_to_smoother"].mean())}


# Table cells of a summarise() dict: header, the fields it needs data in (else the column is left out), text.
CELLS = [
    ("runs", [], lambda s: s["runs"]),
    ("failures", [], lambda s: f"{s['failures']}/{s['runs']} ({ar.fmt_num(100 * s['failure_rate'], 2)} %)"),
    ("mean ATE (m)", [ATE], lambda s: s["ate_aligned_mean_m"]),
    ("median ATE (m)", [ATE], lambda s: s["ate_aligned_median_m"]),
    ("p90 ATE (m)", [ATE], lambda s: s["ate_aligned_p90_m"]),
    ("median NEES", ["nees_median"], lambda s: s["nees_median"]),
    ("consistency horizon (scan)", ["consistency_horizon_scan"],
     lambda s: (f"{ar.fmt_num(s['consistency_horizon_median_scan'])} ({s['consistency_horizon_runs']} of "
                f"{s['finished']})") if s["consistency_horizon_runs"] else "–"),
    ("rejected measurements", ["rejected_measurements"], lambda s: s["rejected_measurements"]),
    ("median F1", ["assoc_f1"], lambda s: s["assoc_f1_median"]),
    ("mean ATE ratio to smoother", ["smoother_ate_aligned_m"], lambda s: s["ratio_to_smoother_mean"]),
]
HORIZON_NOTE = ("Consistency horizon: the median scan after which a run's rolling NEES stays out of its band, over "
                "the runs where it does (how many, of those finished); the others stay consistent or have no truth.")


def cells(stats, df, headers):
    """The listed columns of one table row, leaving out those whose fields df has no data in."""
    return {h: text(stats) for h, fields, text in CELLS if h in headers and ar.has_data(df, *fields)}


def make(df, out_dir, results_path=None):
    if not ar.has_data(ar.ok_rows(df), "filter", ATE):
        return []
    df = mark_failures(df)
    headers = [h for h, _, _ in CELLS if h not in ("rejected measurements", "median F1")]
    frame = ar.pd.DataFrame([{"configuration": name, **cells(summarise(runs), df, headers)}
                             for name, runs in configurations(df)])
    print(frame.to_string(index=False))
    ratio = ("The ratio is each run's aligned ATE over the smoother's on its scenario and seed, averaged. "
             if ar.has_data(df, "smoother_ate_aligned_m") else "")
    horizon = HORIZON_NOTE + " " if ar.has_data(df, "consistency_horizon_scan") else ""
    return [ar.Section("Failures and tails",
                       f"{DEFINITION} ATE: SE(2)-aligned ATE RMSE; p90: its 90th percentile over the runs. {ratio}"
                       f"{horizon}\n\n{ar.markdown_table(frame)}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
