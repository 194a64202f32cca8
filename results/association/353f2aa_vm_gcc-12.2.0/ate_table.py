#!/usr/bin/python3
"""The README's table: JCBB, the cluttered-sensor combination (--pose-from-confirmed --close-loops --chi2 0.999)
before and with the start rule (--provisional-steer-min 3), each against known association without its gate on
the same runs (world seed, filter seed), aligned and before alignment. Run from the repository root."""
import os
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "5b09801_vm_gcc-12.2.0"))
from filter_seeds import read  # noqa: E402  the csv format of filter_seeds.sh, defined once

HERE = os.path.relpath(os.path.dirname(os.path.abspath(__file__)))
A = "results/association/"
U5, U14, F14 = A + "5c07acf_vm_gcc-12.2.0/csv/unseen/", A + "14b904b_vm_gcc-12.2.0/csv/unseen/", A + "14b904b_vm_gcc-12.2.0/csv/fresh/"
K61, J5B, C14 = A + "61e6ed5_vm_gcc-12.2.0/csv/", A + "5b09801_vm_gcc-12.2.0/csv/", A + "14b904b_vm_gcc-12.2.0/csv/"
COMBINATION = "chi2_999_pose_from_confirmed_close_loops-"
# condition, world-clutter, known reference, JCBB, the combination, the combination with the start rule
ROWS = [
    ("rooms, clutter 0", "rooms-c0", K61, J5B, C14, HERE + "/csv/"),
    ("rooms, clutter 2", "rooms-c2", U5, U5, U14, HERE + "/csv/"),
    ("rooms, clutter 5", "rooms-c5", K61, J5B, C14, HERE + "/csv/"),
    ("clustered, clutter 2", "clustered-c2", U14, U14, U14, HERE + "/csv/"),
    ("clustered, clutter 5", "clustered-c5", K61, J5B, C14, HERE + "/csv/"),
    ("uniform, clutter 5", "uniform-c5", U5, U5, U14, HERE + "/csv/"),
    ("worlds 41-80: rooms, clutter 5", "rooms-c5", F14, F14, F14, HERE + "/csv/fresh/"),
    ("worlds 41-80: clustered, clutter 5", "clustered-c5", F14, F14, F14, HERE + "/csv/fresh/"),
]
VARIANTS = ["jcbb", "combination", "rule"]


def main():
    print("| condition | runs | aligned ATE / known: JCBB, combination, with the rule "
          "| before alignment: JCBB, combination, with the rule | the same, geometric mean of the per-run ratio "
          "| F1: JCBB, with the rule |")
    print("|---|---|---|---|---|---|")
    for name, w, k, j, c, r in ROWS:
        runs = read(f"{k}known_nogate-{w}.csv")
        for variant, path in zip(VARIANTS, (f"{j}jcbb-{w}.csv", f"{c}{COMBINATION}{w}.csv", f"{r}start_rule-{w}.csv")):
            runs = runs.merge(read(path), on=["world_seed", "filter_seed"], suffixes=("", "_" + variant))
        ratio = lambda v, col: runs[f"{col}_{v}"].mean() / runs[col].mean()
        geo = lambda v, col: np.exp(np.log(runs[f"{col}_{v}"] / runs[col]).mean())
        three = lambda f, col: ", ".join(f"{f(v, col):.2f}" for v in VARIANTS)
        print(f"| {name} | {len(runs)} | {three(ratio, 'ate_aligned')} | {three(ratio, 'ate')} | {three(geo, 'ate')} "
              f"| {runs.f1_jcbb.mean():.4f}, {runs.f1_rule.mean():.4f} |")


if __name__ == "__main__":
    main()
