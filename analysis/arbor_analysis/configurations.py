"""The report's first table (issue 44): one row per configuration with the numbers a comparison needs (runs,
median and p90 ATE, F1, failure rate where the smoother ran, map size, time per scan). Oracles (known
association) and the smoother are marked as references in the row itself, so the table never reads as if one of
them were a strategy to pick; map back ends whose output agrees run for run share one row that says so.
Reads: results.jsonl columns filter, map, assoc, particles, run options, seed, ate_aligned_rmse_m or ate_rmse_m,
assoc_f1, landmarks, scan_time_median_s and scan_time_p90_s (step_time_median_s in runs from before them),
steps, scans, world_steps, and the smoother's rows for the failure rate."""

import sys

import numpy as np

from . import failures
from . import results as ar

TITLE = "Configurations"


def ate_column(df):
    """The ATE the table ranks by: SE(2)-aligned where the runs have it (a start-pose offset is no error of the
    filter), plain otherwise."""
    return "ate_aligned_rmse_m" if ar.has_data(df, "ate_aligned_rmse_m") else "ate_rmse_m"


def one_step_per_scan(df):
    """True when every run's filter step is one scan (simulated worlds without extra odometry readings between
    scans): then the step time is the time per scan. Real logs interleave many odometry steps per scan."""
    if not ar.has_data(df, "steps", "world_steps"):
        return False
    return bool((df["steps"].dropna() == df.loc[df["steps"].notna(), "world_steps"]).all())


def groups(df):
    """(configurations, maps): per configuration, in the order filter, map, assoc, particles, run options, its
    runs (each once) and all its rows (every back end's copy, for the times, which do differ); and the map back
    ends that collapsed into one configuration because their ATE agrees run for run (empty where none did)."""
    by = [c for c in ar.method_columns(df) + ["particles"] if c in df]
    keys = [c for c in ar.SCENARIO if c in df] + ["seed"]
    kept, runs = ar.drop_identical_map_backends(df, by, keys)
    maps = sorted(df["map"].dropna().unique()) if "map" in by and "map" not in kept else []
    # A configuration's key as text: NaN (EKF's particles) is not equal to itself, so it cannot key a dict.
    config = df[kept].astype(str).agg("|".join, axis=1)
    copies = {k: g for k, g in df.groupby(config, sort=False)}
    return ([(g, copies[config.loc[g.index[0]]]) for _, g in runs.groupby(kept, sort=True, dropna=False)],
            maps if len(maps) > 1 else [])


def cell(value):
    """A parameter cell: the value, or "–" where the filter has no such dimension (EKF and smoother: map,
    particles); never an empty cell."""
    if value is None or (isinstance(value, float) and value != value):
        return "–"
    return str(int(value)) if isinstance(value, float) and value.is_integer() else str(value)


def timing(df):
    """(median column, p90 column or None, unit) of the table's time: the time per scan where the runs record
    it (`arbor run` since issue 44: a scan's step and the odometry-only steps before it), else the step time,
    which is the time per scan only where every step is a scan."""
    if ar.has_data(df, "scan_time_median_s"):
        return "scan_time_median_s", "scan_time_p90_s" if ar.has_data(df, "scan_time_p90_s") else None, "scan"
    return "step_time_median_s", None, "scan" if one_step_per_scan(df) else "step"


def median_ms(rows, column):
    time = failures.median_of(rows[failures.finished(rows)], column)
    return 1e3 * time if time == time else float("nan")


def time_cell(copies, identical_maps, column):
    """The median over runs of `column`; per back end where one row stands for several (their output agrees,
    their time is what tells them apart)."""
    if not identical_maps or copies["map"].nunique() < 2:
        return median_ms(copies, column)
    return ", ".join(f"{m} {ar.fmt_num(median_ms(g, column))}" for m, g in copies.groupby("map", sort=True))


def row_for(rows, copies, shown, identical_maps, ate, times, with_failures):
    """One configuration's table row from its runs (each once) and copies (every back end's row);
    identical_maps: the back ends its map cell stands for (empty: its own)."""
    first = rows.iloc[0]
    done = rows[failures.finished(rows)]
    values = ar.finite_values(done[ate]) if ate in done else np.empty(0)
    out = {}
    backends = sorted(copies["map"].dropna().unique()) if identical_maps else []
    for c in shown:
        if c == "map" and len(backends) > 1:
            out["map"] = " = ".join(backends) + " (identical)"
        else:
            out[c] = cell(first.get(c))
    out["role"] = ar.role(first) or "strategy"
    out["runs"] = len(rows)
    out["median ATE (m)"] = float(np.median(values)) if len(values) else float("nan")
    out["p90 ATE (m)"] = float(np.percentile(values, 90)) if len(values) else float("nan")
    out["median F1"] = failures.median_of(done, "assoc_f1")
    if with_failures:
        out["failure rate"] = ("–" if first.get("filter") == "smoother"
                               else f"{ar.fmt_num(100 * rows['failed'].mean(), 2)} %")
    out["map size (landmarks)"] = failures.median_of(done, "landmarks")
    median, p90, unit = times
    out[f"time per {unit} (ms)"] = time_cell(copies, identical_maps, median)
    if p90:
        out[f"p90 time per {unit} (ms)"] = time_cell(copies, identical_maps, p90)
    return out


def table(df):
    """The table as a DataFrame (cells as numbers or text), or None when the rows name no filter."""
    if not ar.has_data(df, "filter"):
        return None
    ate = ate_column(ar.ok_rows(df))
    marked = failures.mark_failures(df)
    with_failures = ar.has_data(marked, "smoother_ate_aligned_m")
    configs, maps = groups(marked)
    by = [c for c in ("filter", "map", "assoc", "particles") if ar.has_data(df, c)]
    shown = by + [c for c in ar.varying(df, ar.run_option_columns(df)) if c not in by]
    times = timing(ar.ok_rows(df))
    frame = ar.pd.DataFrame([row_for(g, copies, shown, maps, ate, times, with_failures) for g, copies in configs])
    # References last, after the strategies a reader chooses between.
    order = frame["role"].map({"strategy": 0, "oracle": 1, "reference": 2}).fillna(3)
    frame = frame.assign(_order=order).sort_values("_order", kind="stable").drop(columns="_order")
    frame = frame.dropna(axis=1, how="all")
    return frame.reset_index(drop=True), ate, maps, times


def time_note(df, median, p90, unit):
    """What the time columns measure, and on real logs how many steps a scan stands for."""
    if unit == "step":
        return ("Time per step: the median filter step time; a real log has several odometry steps per scan, "
                "so this is not the time per scan (these runs predate `arbor run`'s scan_time_median_s).")
    if median == "step_time_median_s":
        return "Time per scan: the median filter step time, one step per scan in these worlds."
    text = ("Time per scan: for each scan, the filter's time for its step and for the odometry-only steps since "
            "the previous scan; the median over runs of each run's median" + (" (p90: of each run's 90th "
            "percentile)" if p90 else "") + ".")
    done = ar.ok_rows(df)
    if ar.has_data(done, "steps", "scans") and not one_step_per_scan(done):
        ratio = float((done["steps"] / done["scans"]).median())
        text += f" These logs have {ar.fmt_num(ratio, 3)} steps per scan: a step is mostly an odometry reading."
    return text


def make(df, out_dir, results_path=None):
    made = table(df)
    if made is None or made[0].empty:
        return []
    frame, ate, maps, (median, p90, unit) = made
    print(frame.to_string(index=False))
    notes = [("ATE: SE(2)-aligned ATE RMSE" if ate == "ate_aligned_rmse_m" else "ATE: ATE RMSE (no alignment)")
             + "; median and 90th percentile over the configuration's finished runs, pooled over scenarios and seeds."]
    notes.append("**oracle**: known association, which a real dataset does not have; **reference**: the batch "
                 "smoother over the whole log. Both bound what a strategy can reach and are never named best.")
    if maps:
        notes.append(f"The map back ends {', '.join(maps)} gave identical output run for run: one row stands for "
                     "all of them, each run counted once, with each back end's time.")
    if "failure rate" in frame:
        notes.append("Failure rate: as defined under Failures and tails (above 3× the smoother's aligned ATE, "
                     "above dead reckoning, or not finished).")
    notes.append(time_note(df, median, p90, unit))
    # The table before its notes: the first screen is for the comparison.
    return [ar.Section(TITLE, ar.markdown_table(frame) + "\n\n" + " ".join(notes) + "\n")]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
