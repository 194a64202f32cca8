#!/usr/bin/python3
"""The association ablation (experiments/sweeps/association.toml, results/ablations/association) driven from
Python through `import arbor` instead of `arbor sweep`: F1 of each association strategy inside FastSLAM 2.0 as
clutter grows. It simulates the sweep's worlds with the sweep's seeds and runs the same grid, so with
--check SWEEP_DIR (an `arbor sweep experiments/sweeps/association.toml --out SWEEP_DIR` of the same build) every
F1 must equal the sweep's digit for digit.

Usage: PYTHONPATH=build/python /usr/bin/python3 analysis/studies/api_association_ablation.py OUT [--check SWEEP_DIR]
Writes OUT/api_association.csv and OUT/api_association.png.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import arbor  # noqa: E402

CLUTTER = [0.0, 0.5, 1.0, 2.0, 4.0]  # spurious measurements per scan
STRATEGIES = ["nn", "jcbb", "locality"]
SEEDS = [1, 2, 3]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--check", metavar="SWEEP_DIR", help="compare with an arbor sweep of association.toml")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    rows = []
    for clutter in CLUTTER:
        for seed in SEEDS:
            world = arbor.simulate(world="uniform", landmarks=100, steps=200, clutter=clutter, seed=seed)
            for assoc in STRATEGIES:
                r = arbor.run(world, filter="fastslam2", map="tree", assoc=assoc, particles=20, seed=seed, threads=1)
                rows.append(dict(clutter=clutter, seed=seed, assoc=assoc, assoc_f1=r.assoc_f1,
                                 ate_rmse_m=r.ate_rmse_m, landmarks=r.landmarks))
    df = pd.DataFrame(rows)
    df.to_csv(os.path.join(args.out, "api_association.csv"), index=False)

    fig, ax = plt.subplots(figsize=(6, 4))
    for assoc, g in df.groupby("assoc"):
        m = g.groupby("clutter")["assoc_f1"].agg(["mean", "min", "max"])
        ax.errorbar(m.index, m["mean"], yerr=[m["mean"] - m["min"], m["max"] - m["mean"]], marker="o",
                    capsize=3, label=f"assoc = {assoc}")
    ax.set_xlabel("clutter [spurious measurements / scan]")
    ax.set_ylabel(f"association F1 (mean, min-max over {len(SEEDS)} seeds)")
    ax.set_title("FastSLAM 2.0, 20 particles, 100 landmarks, 200 scans")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "api_association.png"), dpi=120)
    print(df.groupby(["assoc", "clutter"])["assoc_f1"].mean().unstack().round(3).to_string())

    if args.check:
        # round_trip: the default parser may be one ulp off the text, and the check is digit for digit
        sweep = pd.read_csv(os.path.join(args.check, "results.csv"), float_precision="round_trip")
        merged = df.merge(sweep, on=["clutter", "seed", "assoc"], suffixes=("", "_sweep"))
        if len(merged) != len(df):
            sys.exit(f"{len(df) - len(merged)} runs have no counterpart in {args.check}/results.csv")
        differ = merged[merged["assoc_f1"] != merged["assoc_f1_sweep"]]
        if len(differ):
            sys.exit(f"{len(differ)} runs differ from the sweep:\n{differ.to_string()}")
        print(f"all {len(merged)} runs equal the sweep's, digit for digit")


if __name__ == "__main__":
    main()
