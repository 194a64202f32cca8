#!/usr/bin/python3
"""The table of this folder's README: on the simulator that drives straight edges (d43e3e0), JCBB, NN and the
cluttered-sensor combination with the start rule against known association without its gate, on the same runs
(world seed, filter seed), aligned and before alignment, with F1 and the confirmed landmarks per true landmark
observed (landmarks.csv). With the old simulator's figures (353f2aa_vm_gcc-12.2.0/ate_table.py) beside them.
Run from the repository root."""
import os
import pathlib
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "5b09801_vm_gcc-12.2.0"))
from filter_seeds import read  # noqa: E402  the csv format of filter_seeds.sh, defined once

HERE = os.path.relpath(os.path.dirname(os.path.abspath(__file__)))
CONDITIONS = ["rooms-c0", "rooms-c2", "rooms-c5", "clustered-c2", "clustered-c5", "uniform-c5"]
VARIANTS = ["jcbb", "nn", "rule"]


def main():
    landmarks = pd.read_csv(f"{HERE}/landmarks.csv")
    landmarks["per_true"] = landmarks.landmarks / landmarks.observed_true_landmarks
    print("| condition | runs | aligned ATE / known: JCBB, NN, rule | before alignment: JCBB, NN, rule "
          "| geometric mean of the per-run ratio before alignment: JCBB, NN, rule | F1: JCBB, NN, rule "
          "| confirmed landmarks per true one: JCBB, NN, rule |")
    print("|---|---|---|---|---|---|---|")
    for w in CONDITIONS:
        runs = read(f"{HERE}/csv/known_nogate-{w}.csv")
        for variant in VARIANTS:
            runs = runs.merge(read(f"{HERE}/csv/{variant}-{w}.csv"), on=["world_seed", "filter_seed"],
                              suffixes=("", "_" + variant))
        ratio = lambda v, col: runs[f"{col}_{v}"].mean() / runs[col].mean()
        geo = lambda v, col: np.exp(np.log(runs[f"{col}_{v}"] / runs[col]).mean())
        three = lambda f, col, fmt=".2f": ", ".join(f"{f(v, col):{fmt}}" for v in VARIANTS)
        world, clutter = w.split("-")
        here = landmarks[(landmarks.world == world) & (landmarks.clutter == int(clutter[1:]))]
        per_true = ", ".join(f"{here[here.strategy == v].per_true.mean():.3f}" for v in VARIANTS)
        print(f"| {world}, clutter {clutter[1:]} | {len(runs)} | {three(ratio, 'ate_aligned')} | {three(ratio, 'ate')} "
              f"| {three(geo, 'ate')} | {three(lambda v, _: runs[f'f1_{v}'].mean(), 'f1', '.4f')} | {per_true} |")


if __name__ == "__main__":
    main()
