"""Strategy over reference, with each world run under several filter seeds (filter_seeds.sh).

For each csv after the reference: the ratio of mean SE(2)-aligned ATE to the reference's over the same runs,
with a 95 % bootstrap interval over worlds (a world's runs are resampled together), the ratio on world seeds
1-20 and 21-40 apart, and the ratio from the filter seed = world seed runs alone (what a one-seed-per-world
study sees). With --profile OUT, also the mean position error of the best particle's trajectory every 25
steps and at the last, as it is and after the SE(2) alignment the ATE uses, which shows where in the run two strategies part, and per 100 steps the duplicates the best particle
started (a landmark begun from a true landmark that already had one) and the share of its pairings of true
landmarks that went to such a duplicate rather than to the first landmark of that true landmark.
Usage: /usr/bin/python3 filter_seeds.py [--profile OUT] REF.csv OTHER.csv...
"""
import argparse
import pathlib
import sys

import numpy as np
import pandas as pd

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[3] / "analysis"))
import arbor_results as ar  # noqa: E402

COLUMNS = ["world_seed", "filter_seed", "ate_aligned", "ate", "f1", "nees_median"]


def read(path):
    return pd.read_csv(path, header=None, names=COLUMNS)


def ratio(runs):
    return runs.ate_aligned.mean() / runs.ate_aligned_ref.mean()


def bootstrap(runs, draws=2000):
    worlds = runs.groupby("world_seed")
    per_world = worlds[["ate_aligned", "ate_aligned_ref"]].mean()
    rng = np.random.default_rng(0)
    values = [ratio(per_world.iloc[rng.integers(0, len(per_world), len(per_world))]) for _ in range(draws)]
    return np.percentile(values, [2.5, 97.5])


def duplicate_counts(run, steps, window=100):
    """Per window of steps: [duplicates started, pairings with a duplicate, pairings with the original].
    steps: ar.read_scenario_steps of the run's scenario (true id per measurement, -1 for clutter)."""
    label, original = {}, {}
    counts = np.zeros(((len(steps) - 1) // window + 1, 3), dtype=int)
    for line in (run / "associations.csv").read_text().splitlines()[1:]:
        step, measurement, landmark = map(int, line.split(","))
        truth, row = steps[step][2][measurement], counts[step // window]
        if landmark < 0 or truth == -1:
            label.setdefault(landmark, truth)
            continue
        if landmark not in label:
            label[landmark] = truth
            row[0] += truth in original
            original.setdefault(truth, landmark)
        elif label[landmark] == truth:
            row[1 if original[truth] != landmark else 2] += 1
    return counts


def error_profile(out, name):
    """Mean position error per step over NAME's runs, unaligned and aligned, their count, and their summed
    duplicate_counts."""
    errors, errors_aligned, duplicates = [], [], 0
    world, clutter = name.rsplit("-", 2)[1:]  # csv stems are STRATEGY-WORLD-cC, runs STRATEGY-WORLD-cC-sS-fF
    for run in sorted((out / "runs").glob(f"{name}-s*")):
        seed = run.name[len(name) + 1:].split("-")[0]
        scenario = out / "scenarios" / f"{world}-{clutter}-{seed}.scn"
        # trajectory.tum starts at the initial pose, the scenario's truth after the first step.
        path = ar.read_tum(run / "trajectory.tum")[["x", "y"]].to_numpy()[1:]
        steps = ar.read_scenario_steps(scenario)
        truth = np.array([pose[:2] for _, pose, _ in steps if pose is not None])
        rotation, translation = ar.align_se2(path, truth)
        errors.append(np.hypot(*(path - truth).T))
        errors_aligned.append(np.hypot(*(path @ rotation.T + translation - truth).T))
        duplicates = duplicates + duplicate_counts(run, steps)
    return np.mean(errors, axis=0), np.mean(errors_aligned, axis=0), len(errors), duplicates


def sampled(profile, every=25):
    """Every `every`-th step of a per-step profile, and its last step."""
    return np.append(profile[::every], profile[-1]) if (len(profile) - 1) % every else profile[::every]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--profile", type=pathlib.Path)
    parser.add_argument("ref")
    parser.add_argument("others", nargs="+")
    args = parser.parse_args()
    ref = read(args.ref)
    print("| strategy | runs | mean aligned ATE (m) | median | ratio to reference (95 % interval) "
          "| worlds 1-20 | worlds 21-40 | filter seed = world seed only | F1 | NEES median |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for path in args.others:
        runs = read(path).merge(ref, on=["world_seed", "filter_seed"], suffixes=("", "_ref"))
        low, high = bootstrap(runs)
        first, second = runs[runs.world_seed <= 20], runs[runs.world_seed > 20]
        same = runs[runs.filter_seed == runs.world_seed]
        print(f"| {pathlib.Path(path).stem} | {len(runs)} | {runs.ate_aligned.mean():.3f} | "
              f"{runs.ate_aligned.median():.3f} | {ratio(runs):.2f} ({low:.2f}-{high:.2f}) | {ratio(first):.2f} | "
              f"{ratio(second):.2f} | {ratio(same):.2f} | {runs.f1.mean():.4f} | {runs.nees_median.median():.0f} |")
    if args.profile:
        profiles = {pathlib.Path(p).stem: error_profile(args.profile, pathlib.Path(p).stem) for p in [args.ref] + args.others}
        print("\nmean position error (m) of the best particle at steps 0, 25, ... and the last")
        for name, (profile, _, count, _) in profiles.items():
            print(f"{name:28s} n={count:3d} " + " ".join(f"{e:.2f}" for e in sampled(profile)))
        print("\nthe same after SE(2) alignment of each run")
        for name, (_, profile, count, _) in profiles.items():
            print(f"{name:28s} n={count:3d} " + " ".join(f"{e:.2f}" for e in sampled(profile)))
        print("\nper 100 steps: duplicates started per run / share of true pairings made with a duplicate")
        for name, (_, _, count, dup) in profiles.items():
            share = dup[:, 1] / np.maximum(dup[:, 1] + dup[:, 2], 1)
            print(f"{name:28s} " + "  ".join(f"{d / count:.1f}/{s:.3f}" for d, s in zip(dup[:, 0], share)))


if __name__ == "__main__":
    main()
