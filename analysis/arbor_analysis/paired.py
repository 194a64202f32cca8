"""Paired comparisons: "A beats B" as a statement with a test behind it. Where runs share their scenario and
seed and differ in one method dimension (association strategy, filter version, particle count, a run option),
each metric's per-pair difference A - B, its mean and 95 % CI (t, over pairs; only from 3 pairs on), and
whether the interval excludes zero. Pairing removes what the seed and the world contribute to both runs,
which unpaired intervals over seeds carry in full.
Reads: results.jsonl columns scenario, seed, the method columns and ate_rmse_m, landmark_rmse_m, assoc_f1."""

import itertools
import sys

from . import results as ar

# (column, name in the table, unit, True when lower is better)
METRICS = [("ate_rmse_m", "ATE RMSE", "m", True), ("landmark_rmse_m", "landmark RMSE", "m", True),
           ("assoc_f1", "association F1", "", False)]
LOWER_IS_BETTER = {m[0]: m[3] for m in METRICS}
# Dimensions compared: the method columns and run options, and the particle count; never the map back end
# (its output is identical by construction) or threads (identical too).
NOT_COMPARED = {"map", "threads"}
# A dimension with more values than this is a sweep axis, not a set of alternatives: its pairs are left out.
MAX_VALUES = 5


def run_keys(df):
    """The columns that identify one run apart from the method: scenario, seed, and every context column."""
    return [c for c in ["scenario", "seed"] + ar.CONTEXT if c in df.columns]


def collapse_identical(df, column, metric):
    """Keeps one of each run where `column` (map back end, threads) varies without changing `metric`."""
    if column not in df.columns or df[column].nunique() < 2:
        return df
    rest = [c for c in run_keys(df) + ar.method_columns(df) if c in df.columns and c != column]
    if df.groupby(rest, dropna=False)[metric].nunique(dropna=False).max() <= 1:
        return df.drop_duplicates(subset=rest)
    return df


def difference(a, b, lower_is_better):
    """a - b over paired values: the pairs, the mean and its 95 % CI half-width (nan below 3 pairs), and the
    pairs where a is better and where b is."""
    diff = (a - b).to_numpy(dtype=float)
    mean, ci = ar.mean_ci(diff)
    a_better = (diff < 0) if lower_is_better else (diff > 0)
    b_better = (diff > 0) if lower_is_better else (diff < 0)
    return dict(pairs=len(diff), mean=mean, ci=ci, a_better=int(a_better.sum()), b_better=int(b_better.sum()))


def compare(df, dimension, metric):
    """Rows of the table for one dimension and metric: one per pair of its values that share runs."""
    keys = [c for c in run_keys(df) + ar.method_columns(df) if c in df.columns and c != dimension]
    data = df[df[metric].notna()].copy()
    data[keys] = data[keys].astype(object).fillna("")  # an absent dataset or world is still a key
    values = sorted(data[dimension].dropna().unique(), key=str)
    if not 2 <= len(values) <= MAX_VALUES:
        return []
    wide = data.pivot_table(index=keys, columns=dimension, values=metric, aggfunc="first", dropna=False)
    rows = []
    for a, b in itertools.combinations(values, 2):
        if a not in wide or b not in wide:
            continue
        both = wide[[a, b]].dropna()
        if len(both) == 0:
            continue
        d = difference(both[a], both[b], LOWER_IS_BETTER[metric])
        rows.append(dict(dimension=dimension, a=a, b=b, metric=metric, **d,
                         significant=bool(d["ci"] == d["ci"] and abs(d["mean"]) > d["ci"])))
    return rows


def value_text(dimension, value):
    """The value as a label, marked where it is an oracle or the reference (never to be read as a strategy)."""
    role = ar.role({dimension: value})
    return ar.label({dimension: value}, [dimension]) + (f" ({role})" if role else "")


def sentence(r):
    """What a significant row says, in words."""
    column, name, unit, lower_better = next(m for m in METRICS if m[0] == r["metric"])
    a, b = ar.md_text(value_text(r["dimension"], r["a"])), ar.md_text(value_text(r["dimension"], r["b"]))
    better, worse = (a, b) if (r["mean"] < 0) == lower_better else (b, a)
    unit = f" {unit}" if unit else ""
    return (f"- **{better}** beats {worse} on {name}: difference {ar.fmt_num(abs(r['mean']))}{unit} "
            f"± {ar.fmt_num(r['ci'], 2)}{unit} (95 % CI) over {r['pairs']} paired runs.")


def comparisons(df):
    """Every paired comparison the rows allow: one dict per dimension, pair of values and metric."""
    df = ar.ok_rows(df)
    if "seed" not in df.columns or "scenario" not in df.columns:
        return []
    dimensions = [c for c in ar.varying(df, ar.method_columns(df) + ["particles"]) if c not in NOT_COMPARED]
    rows = []
    for column, *_ in METRICS:
        if not ar.has_data(df, column):
            continue
        runs = collapse_identical(collapse_identical(df, "map", column), "threads", column)
        for dimension in dimensions:
            rows.extend(compare(runs, dimension, column))
    return rows


def involves_reference(r):
    return bool(ar.role({r["dimension"]: r["a"]}) or ar.role({r["dimension"]: r["b"]}))


def significant_sentences(df, with_references=True):
    """The significant comparisons in words; without those against an oracle or the smoother if asked."""
    return [sentence(r) for r in comparisons(df) if r["significant"] and (with_references or not involves_reference(r))]


def make(df, out_dir, results_path=None):
    rows = comparisons(df)
    if not rows:
        return []
    table = ar.pd.DataFrame([{
        "comparison": f"{value_text(r['dimension'], r['a'])} − {value_text(r['dimension'], r['b'])}",
        "metric": next(m[1] for m in METRICS if m[0] == r["metric"]),
        "pairs": r["pairs"],
        "mean difference": ar.fmt_num(r["mean"]),
        "95 % CI": "–" if r["ci"] != r["ci"] else f"± {ar.fmt_num(r['ci'], 2)}",
        "pairs where A / B is better": f"{r['a_better']} / {r['b_better']}",
        "significant": "yes" if r["significant"] else "no"} for r in rows])
    print(table.to_string(index=False))
    significant = [sentence(r) for r in rows if r["significant"]]
    others = ", ".join(sorted(set(ar.varying(ar.ok_rows(df), ar.CONTEXT)) - {"particles", "threads"})) or "nothing else"
    text = ("Each pair is two runs on the same scenario and seed that differ only in the compared dimension; "
            f"pairs are pooled over what else the sweep varies ({others}). A difference is significant when its "
            f"95 % interval excludes zero; there is no interval below {ar.MIN_VALUES_FOR_CI} pairs.\n\n"
            + ("\n".join(significant) if significant else "No difference is significant at 95 %.")
            + "\n\n" + ar.markdown_table(table) + "\n")
    return [ar.Section("Paired comparisons", text)]


if __name__ == "__main__":
    sys.exit(ar.main_for(make, __doc__))
