"""FastSLAM vs smoother table: for each scenario, the ATE and landmark RMSE of every FastSLAM configuration
next to the Ceres smoother's on the same scenario and seed, and the ratio (DESIGN.md §10 target: FastSLAM ATE
<= 1.3x the smoother's with true association). Reads: results.jsonl rows with filter = smoother and fastslam*."""

import sys

from . import results as ar


def make(df, out_dir, results_path=None):
    df = ar.ok_rows(df)
    if ("filter" not in df or not ar.has_data(df, "ate_rmse_m") or not (df["filter"] == "smoother").any()
            or not (df["filter"] != "smoother").any()):
        return []
    scenario = [c for c in ar.SCENARIO if c in df.columns]
    smoother = df[df["filter"] == "smoother"]
    fastslam = df[df["filter"] != "smoother"]
    metrics = [c for c in ("ate_rmse_m", "landmark_rmse_m") if c in df]  # a sweep may keep fewer metrics
    joined = fastslam.merge(smoother[scenario + ["seed"] + metrics],
                            on=scenario + ["seed"], suffixes=("", "_smoother"), how="inner")
    if joined.empty:
        return []
    joined["ate_ratio"] = joined["ate_rmse_m"] / joined["ate_rmse_m_smoother"]
    groups = [c for c in ar.method_columns(fastslam) + ["particles"] if c in joined.columns]
    groups, joined = ar.drop_identical_map_backends(joined, groups, scenario + ["seed"])
    rows = []
    for key, g in joined.groupby(groups, sort=True):
        row = {"configuration": ar.label(g.iloc[0], groups), "runs": len(g),
               "ATE (m)": g["ate_rmse_m"].mean(), "smoother ATE (m)": g["ate_rmse_m_smoother"].mean(),
               "ATE ratio": ar.fmt_mean_ci(g["ate_ratio"])}
        if "landmark_rmse_m" in metrics:
            row.update({"landmark RMSE (m)": g["landmark_rmse_m"].mean(),
                        "smoother landmark RMSE (m)": g["landmark_rmse_m_smoother"].mean()})
        rows.append(row)
    frame = ar.pd.DataFrame(rows)
    print(frame.to_string(index=False))
    return [ar.Section("FastSLAM vs smoother",
                       "Same scenarios and seeds; ratio = FastSLAM ATE / smoother ATE per run, mean ± 95 % CI (the "
                       f"individual ratios where there are fewer than {ar.MIN_VALUES_FOR_CI} runs)"
                       + ("" if "map" in groups else "; one row per configuration for all map back ends, whose "
                          "output agrees run for run") + ".\n\n"
                       f"{ar.markdown_table(frame)}\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
