#!/usr/bin/python3
"""The README's table: JCBB, the cluttered-sensor combination (--pose-from-confirmed --close-loops --chi2 0.999)
before and with the start rule (--provisional-steer-min 3), each against known association without its gate on
the same runs (world seed, filter seed), aligned and before alignment. Run from the repository root."""
import csv
import math
import os
import statistics

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


def read(path):
    """(world seed, filter seed) -> (aligned ATE, ATE, F1) from a filter_seeds.sh csv."""
    with open(path) as f:
        return {(r[0], r[1]): (float(r[2]), float(r[3]), float(r[4])) for r in csv.reader(f)}


def main():
    print("| condition | runs | aligned ATE / known: JCBB, combination, with the rule "
          "| before alignment: JCBB, combination, with the rule | the same, geometric mean of the per-run ratio "
          "| F1: JCBB, with the rule |")
    print("|---|---|---|---|---|---|")
    for name, w, k, j, c, r in ROWS:
        known, jcbb = read(f"{k}known_nogate-{w}.csv"), read(f"{j}jcbb-{w}.csv")
        combo, rule = read(f"{c}{COMBINATION}{w}.csv"), read(f"{r}start_rule-{w}.csv")
        keys = sorted(set(known) & set(jcbb) & set(combo) & set(rule))
        mean = lambda d, i: statistics.mean(d[x][i] for x in keys)
        ratio = lambda d, i: mean(d, i) / mean(known, i)
        geo = lambda d, i: math.exp(statistics.mean(math.log(d[x][i] / known[x][i]) for x in keys))
        three = lambda f, i: ", ".join(f"{f(d, i):.2f}" for d in (jcbb, combo, rule))
        print(f"| {name} | {len(keys)} | {three(ratio, 0)} | {three(ratio, 1)} | {three(geo, 1)} "
              f"| {mean(jcbb, 2):.4f}, {mean(rule, 2):.4f} |")


if __name__ == "__main__":
    main()
