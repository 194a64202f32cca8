#!/usr/bin/python3
"""Issue 12's ATE ratio over 40 worlds x 5 filter seeds on the straight-edge simulator: d43e3e0's runs (filter
seeds s and s + 1000) together with this folder's (s + 2000, 3000, 4000), each strategy over known association
without its gate on the same runs, aligned and before alignment, with 95 % bootstrap intervals over worlds
(a world's runs resampled together, as filter_seeds.py does). Run from the repository root."""
import os
import pathlib
import sys

import numpy as np
import pandas as pd

HERE = pathlib.Path(os.path.relpath(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, str(HERE.parent / "5b09801_vm_gcc-12.2.0"))
from filter_seeds import read  # noqa: E402  the csv format of filter_seeds.sh, defined once

EARLIER = HERE.parent / "d43e3e0_vm_gcc-12.2.0" / "csv"
CONDITIONS = ["rooms-c2", "rooms-c5", "clustered-c2", "clustered-c5"]
VARIANTS = ["jcbb", "nn", "rule"]


def runs_of(name):
    return pd.concat([read(EARLIER / f"{name}.csv"), read(HERE / "csv" / f"{name}.csv")], ignore_index=True)


def ratio_with_interval(runs, column, draws=2000):
    per_world = runs.groupby("world_seed")[[column, column + "_ref"]].mean()
    ratio = lambda w: w[column].mean() / w[column + "_ref"].mean()
    rng = np.random.default_rng(0)
    values = [ratio(per_world.iloc[rng.integers(0, len(per_world), len(per_world))]) for _ in range(draws)]
    low, high = np.percentile(values, [2.5, 97.5])
    return f"{ratio(per_world):.2f} ({low:.2f}-{high:.2f})"


def main():
    print("| condition | strategy | runs | aligned ATE / known (95 %) | before alignment | F1 |")
    print("|---|---|---|---|---|---|")
    for condition in CONDITIONS:
        reference = runs_of(f"known_nogate-{condition}")
        for variant in VARIANTS:
            runs = runs_of(f"{variant}-{condition}").merge(reference, on=["world_seed", "filter_seed"],
                                                           suffixes=("", "_ref"))
            print(f"| {condition} | {variant} | {len(runs)} | {ratio_with_interval(runs, 'ate_aligned')} "
                  f"| {ratio_with_interval(runs, 'ate')} | {runs.f1.mean():.4f} |")


if __name__ == "__main__":
    main()
