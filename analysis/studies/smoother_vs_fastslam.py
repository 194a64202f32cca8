#!/usr/bin/python3
"""Smoother vs FastSLAM: the accuracy table and plot of issue 6 (DESIGN.md §5, §10), from the result.json
files that experiments/scripts/smoother_comparison.sh writes under OUT/<dataset>/<run>/.

Rows are (dataset, method), with the simulated worlds pooled. "vs reference" is each FastSLAM run's ATE over
the reference on the same data, averaged over runs: the smoother with true association where the dataset
has it (simulation, UTIAS), else the smoother given that very run's decisions (Victoria Park). The DESIGN.md
§10 target is <= 1.3 with true association.

Usage: /usr/bin/python3 analysis/studies/smoother_vs_fastslam.py OUT
Writes OUT/smoother_vs_fastslam.csv (one row per run), OUT/smoother_vs_fastslam.md and .png.
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis import results as ar  # noqa: E402

FILTER_NAMES = {"fastslam1": "FastSLAM 1.0", "fastslam2": "FastSLAM 2.0"}


def family(dataset):
    return "simulated" if dataset.startswith("simulated") else dataset


def describe(run_dir, result):
    """Method label, kind, and the run whose decisions a smoother used (None for true association)."""
    c = result["config"]
    if c.get("smoother"):
        source = c.get("associations", "known")
        loss = "" if c.get("loss", "none") == "none" else f", {c['loss']} loss"
        if source == "known":
            return "smoother, true association" + loss, "smoother", None
        # The source run sits beside this one (result.json holds the absolute path where it was run, which a
        # copied results folder no longer has).
        name = os.path.basename(os.path.normpath(source))
        s = ar.read_result(os.path.join(os.path.dirname(run_dir), name))["config"]
        label = f"smoother on {FILTER_NAMES[s['filter']]}+{s['assoc']} M={s['particles']} decisions{loss}"
        return label, "smoother", name
    return f"{FILTER_NAMES[c['filter']]}, {c['assoc']}, M={c['particles']}", "fastslam", None


def load(root):
    rows = []
    for path in sorted(glob.glob(os.path.join(root, "*", "*", "result.json"))):
        run_dir = os.path.dirname(path)
        dataset = os.path.basename(os.path.dirname(run_dir))
        r = ar.read_json(path)
        method, kind, source = describe(run_dir, r)
        rows.append({"dataset": dataset, "family": family(dataset), "run": os.path.basename(run_dir),
                     "method": method, "kind": kind, "source": source,
                     "seed": r["config"].get("seed"), "ate_m": r.get("ate_rmse_m"),
                     "ate_aligned_m": r.get("ate_aligned_rmse_m"), "landmark_rmse_m": r.get("landmark_rmse_m"),
                     "gps_aligned": r.get("ate_aligned"), "wall_s": r.get("wall_time_s"),
                     "solve_s": r.get("solve_time_s"), "iterations": r.get("iterations"),
                     "termination": r.get("termination")})
    return pd.DataFrame(rows)


def add_reference(df):
    truth = df[df.method == "smoother, true association"].set_index("dataset")["ate_m"]
    own = df[(df.kind == "smoother") & df.source.notna() & ~df.method.str.contains("loss")]
    own = own.set_index(["dataset", "source"])["ate_m"]

    def reference(row):
        if row.kind != "fastslam":
            return None
        if row.dataset in truth.index:
            return truth[row.dataset]
        return own.get((row.dataset, row.run))

    df["reference_ate_m"] = df.apply(reference, axis=1)
    df["vs_reference"] = df.ate_m / df.reference_ate_m
    return df


def summarize(df):
    rows = []
    for (fam, method), g in df.groupby(["family", "method"], sort=False):
        rows.append({"data": fam, "method": method, "runs": len(g), "ATE (m)": g.ate_m.mean(),
                     "ATE min-max (m)": f"{g.ate_m.min():.3f}-{g.ate_m.max():.3f}",
                     "aligned ATE (m)": g.ate_aligned_m.mean(), "landmark RMSE (m)": g.landmark_rmse_m.mean(),
                     "vs reference": g.vs_reference.mean(), "wall (s)": g.wall_s.mean(),
                     "not converged": int((g.termination.fillna("") == "NO_CONVERGENCE").sum())})
    return pd.DataFrame(rows)


def markdown(table):
    def cell(v):
        if isinstance(v, float):
            return "" if pd.isna(v) else f"{v:.3f}"
        return str(v)
    lines = ["| " + " | ".join(table.columns) + " |", "|" + "---|" * len(table.columns)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in table.itertuples(index=False)]
    return "\n".join(lines)


def plot(df, path):
    """One panel per dataset: every run as a dot, the mean as a bar, on a linear axis from zero."""
    families = list(dict.fromkeys(df.family))
    heights = [df[df.family == f].method.nunique() for f in families]
    fig, axes = plt.subplots(len(families), 1, figsize=(9, 0.32 * sum(heights) + 1.2 * len(families)),
                             gridspec_kw={"height_ratios": heights}, squeeze=False)
    for ax, fam in zip(axes[:, 0], families):
        runs = df[df.family == fam]
        methods = list(dict.fromkeys(runs.sort_values(["kind", "method"], ascending=[False, True]).method))
        for y, method in enumerate(methods):
            g = runs[runs.method == method]
            color = "tab:red" if g.kind.iloc[0] == "smoother" else "tab:blue"
            ax.barh(y, g.ate_m.mean(), color=color, alpha=0.35)
            ax.plot(g.ate_m, [y] * len(g), "o", color=color, markersize=4)
        ax.set_yticks(range(len(methods)), methods, fontsize=8)
        ax.invert_yaxis()
        ax.set_xlim(left=0)
        gps = bool(runs.gps_aligned.any())
        ax.set_title(f"{fam}: ATE RMSE [m]" + (" against GPS, SE(2)-aligned" if gps else ""), fontsize=10)
        ax.grid(axis="x", alpha=0.3)
    fig.suptitle("FastSLAM (blue) beside the Ceres smoother (red) on the same data; dots: runs, bars: mean")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    df = load(root)
    if df.empty:
        sys.exit(f"no OUT/<dataset>/<run>/result.json under {root}")
    df = add_reference(df)
    df.to_csv(os.path.join(root, "smoother_vs_fastslam.csv"), index=False)
    table = summarize(df)
    text = markdown(table)
    with open(os.path.join(root, "smoother_vs_fastslam.md"), "w") as f:
        f.write(text + "\n")
    print(text)
    plot(df, os.path.join(root, "smoother_vs_fastslam.png"))
    print(f"\nwrote {root}/smoother_vs_fastslam.csv, .md and .png")


if __name__ == "__main__":
    main()
