"""Accuracy on real datasets: one table per dataset with, per configuration (filter, association, map back
end, particles, run options), the trajectory error against the dataset's reference (its GPS track or motion
capture, as the scenario names it), dead reckoning's error on the same reference, landmark RMSE and
association F1 where the dataset has landmark ground truth or ids, and the run time against the data's own
duration. Reads results.jsonl and each run's result.json (runs/<key>/result.json)."""

import os
import sys

from . import results as ar

# result.json fields a dataset table shows besides the results row's own columns.
EXTRA = ["scenario_duration_s", "dead_reckoning_ate_m", "ate_aligned", "scenario"]
# result.json's "scenario" is the scenario's metadata (source, citation, reference track), not its path.


def with_run_details(df, results_dir):
    """The rows with EXTRA read from each run's result.json (missing files leave the fields empty); a field the
    rows already hold (a sweep may keep dead_reckoning_ate_m as a metric) is not read again."""
    fields = [k for k in EXTRA if k == "scenario" or k not in df]  # the rows' "scenario" is the file's path
    details = []
    for run_dir in df["run_dir"]:
        try:
            result = ar.read_result(os.path.join(results_dir, str(run_dir)))
        except (OSError, ValueError):
            result = {}
        details.append({("scenario_metadata" if k == "scenario" else k): result.get(k) for k in fields})
    return df.reset_index(drop=True).join(ar.pd.DataFrame(details))


def reference_text(scenario):
    """Where the dataset and its reference come from, from the scenario's metadata."""
    meta = scenario if isinstance(scenario, dict) else {}
    parts = []
    if meta.get("truth_track"):
        parts.append(f"reference trajectory {ar.md_text(meta['truth_track'])}")
    if meta.get("source"):
        parts.append(f"source {ar.md_text(meta['source'])}")
    if meta.get("citation"):
        parts.append(f"citation {ar.md_text(meta['citation'])}")
    return "; ".join(parts) or "reference: the scenario's ground truth"


def table_for(rows):
    columns = [c for c in ar.method_columns(rows) + ["particles"] if c in rows.columns]
    shown = ar.varying(rows, columns) or ["filter"]
    out = []
    for _, g in rows.groupby(columns, sort=True, dropna=False):
        row = {"configuration": ar.label(g.iloc[0], shown), "seeds": int(g["seed"].nunique())}
        # SE(2)-aligned ATE (as evo and the TUM benchmark compute it) is the headline on real data, plain ATE
        # beside it; where the reference is GPS the plain figure is already aligned and stands alone.
        if ar.has_data(g, "ate_aligned_rmse_m") and not g["ate_aligned_rmse_m"].equals(g["ate_rmse_m"]):
            row["aligned ATE (m)"] = ar.fmt_mean_ci(g["ate_aligned_rmse_m"])
        row["ATE RMSE (m)"] = ar.fmt_mean_ci(g["ate_rmse_m"])
        if g["dead_reckoning_ate_m"].notna().any():
            row["dead reckoning ATE (m)"] = ar.fmt_num(float(g["dead_reckoning_ate_m"].mean()))
        if ar.has_data(g, "landmark_rmse_m"):
            row["landmark RMSE (m)"] = ar.fmt_mean_ci(g["landmark_rmse_m"])
        if ar.has_data(g, "assoc_f1"):
            row["association F1"] = ar.fmt_mean_ci(g["assoc_f1"])
        row["landmarks"] = ar.fmt_num(float(g["landmarks"].mean())) if ar.has_data(g, "landmarks") else "–"
        if not ar.has_data(g, "wall_time_s"):  # a sweep's `metrics` may leave it out
            out.append(row)
            continue
        row["wall time (s)"] = ar.fmt_num(float(g["wall_time_s"].mean()))
        duration = g["scenario_duration_s"].dropna() if "scenario_duration_s" in g else ar.pd.Series(dtype=float)
        if not duration.empty:
            row["faster than real time"] = f"{ar.fmt_num(float(duration.iloc[0] / g['wall_time_s'].mean()), 3)}×"
        out.append(row)
    return ar.pd.DataFrame(out)


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if not ar.has_data(df, "dataset", "ate_rmse_m") or results_path is None:
        return []
    results_dir = ar.results_dir_of(results_path)
    df = with_run_details(df[df["dataset"].notna() & df["ate_rmse_m"].notna()], results_dir)
    sections = []
    for dataset, rows in df.groupby("dataset", sort=True):
        name = os.path.splitext(os.path.basename(str(dataset)))[0]
        duration = rows["scenario_duration_s"].dropna()
        frame = table_for(rows)
        print(frame.to_string(index=False))
        text = (f"{reference_text(rows['scenario_metadata'].iloc[0])}"
                + (f"; {ar.fmt_num(float(duration.iloc[0]), 4)} s of data" if not duration.empty else "")
                + ". ATE: RMSE of the estimate against the reference"
                + (" after alignment" if rows["ate_aligned"].eq(True).all() else "")
                + "; dead reckoning: the odometry alone on the same reference. "
                + ar.CI_NOTE + "\n\n" + ar.markdown_table(frame) + "\n")
        sections.append(ar.Section(f"Accuracy on {name}", text))
    return sections


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
