#!/usr/bin/env python3
"""Arbor's EKF-SLAM beside MRPT 2.5's (issue 43, item 6) on the same simulated problems, known association.

    /usr/bin/python3 experiments/peers/compare_mrpt.py OUT [--build build] [--results DIR]

Needs build/bin/arbor and build/bin/mrpt_ekf_slam (`ninja -C build arbor mrpt_ekf_slam`; the second only
builds where libmrpt-slam-dev is installed). Simulates uniform worlds (--landmarks, --steps, one per
--seeds) and one larger world for timing (--timing-landmarks, --timing-steps), runs
`arbor run --filter ekf --assoc known` and mrpt_ekf_slam on each (and MRPT once more with its stock start,
--stock-start), and writes to DIR (default results/peers/<commit>_vm_gcc-12.2.0): accuracy.csv and
timing.csv (one row per run) and comparison.md (the tables). Runs whose output exists are skipped, so an
interrupted comparison resumes.
Both programs score with Arbor's C++ metric code (ATE interpolated at the truth's times, SE(2)-aligned ATE,
pose NEES at scans), so the figures differ only where the filters do.
"""

import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
import arbor_files  # noqa: E402  (the project's one reader of trajectory.tum)

NEES_BAND = (0.2158, 9.3484)  # two-sided 95 % of chi-square(3), as core/metrics/trajectory_metrics.h


def run_once(out_dir, done_file, command):
    """Runs command (which writes out_dir) unless out_dir/done_file exists; its stderr (MRPT logs a warning
    per scan once it has blown up) goes to out_dir/stderr.log."""
    if os.path.exists(os.path.join(out_dir, done_file)):
        return
    os.makedirs(out_dir, exist_ok=True)
    # One thread for both: the comparison is of the filters, not of how MRPT's Eigen or Arbor spread work.
    env = dict(os.environ, OMP_NUM_THREADS="1")
    with open(os.path.join(out_dir, "stderr.log"), "w", encoding="utf-8") as log:
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=log, env=env)


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def read_steps(run_dir):
    """(time_s, step_time_s, landmarks) per row of RUN_DIR/steps.csv."""
    with open(os.path.join(run_dir, "steps.csv"), newline="", encoding="utf-8") as f:
        return [(float(r["time_s"]), float(r["step_time_s"]), int(r["landmarks"])) for r in csv.DictReader(f)]


def band_step_time(rows, n_ref, until_s, share=0.9):
    """Median time of the scans taken with between share * n_ref and n_ref landmarks in the map, before
    until_s: the cost at N = n_ref, which a whole run's median understates while the map grows."""
    times = [t for time_s, t, lm in rows if share * n_ref <= lm <= n_ref and time_s < until_s]
    return statistics.median(times) if times else float("nan")


def pose_gap(run_a, run_b, until_s):
    """Largest distance between two runs' trajectory.tum positions at their common times before until_s."""
    a = {round(t, 6): (x, y) for t, x, y, _ in arbor_files.read_tum(os.path.join(run_a, "trajectory.tum"))}
    gaps = [math.dist(a[round(t, 6)], (x, y)) for t, x, y, _ in
            arbor_files.read_tum(os.path.join(run_b, "trajectory.tum")) if round(t, 6) in a and t < until_s]
    return max(gaps) if gaps else float("nan")


def simulate(arbor, path, landmarks, steps, seed):
    if not os.path.exists(path):
        subprocess.run([arbor, "simulate", "--world", "uniform", "--landmarks", str(landmarks), "--steps",
                        str(steps), "--seed", str(seed), "--out", path], check=True, stdout=subprocess.DEVNULL)


def run_pair(arbor, mrpt, scenario, out, name, repeat=""):
    """Arbor's EKF, MRPT with each of its two EKF updates and (unless timing) with its stock start, on one
    scenario; returns their run folders."""
    dirs = {k: os.path.join(out, f"{k}{repeat}", name) for k in ("arbor", "mrpt", "mrpt_davison", "mrpt_stock")}
    run_once(dirs["arbor"], "result.json",
             [arbor, "run", "--scenario", scenario, "--filter", "ekf", "--assoc", "known", "--quiet", "--out",
              dirs["arbor"]])
    run_once(dirs["mrpt"], "accuracy.json", [mrpt, "--scenario", scenario, "--out", dirs["mrpt"]])
    run_once(dirs["mrpt_davison"], "accuracy.json",
             [mrpt, "--scenario", scenario, "--out", dirs["mrpt_davison"], "--davison"])
    if repeat:
        del dirs["mrpt_stock"]
    else:
        run_once(dirs["mrpt_stock"], "accuracy.json",
                 [mrpt, "--scenario", scenario, "--out", dirs["mrpt_stock"], "--stock-start"])
    return dirs


def row_of(program, name, run_dir):
    """One run's figures under common names, from Arbor's result.json or MRPT's accuracy/timing.json."""
    if program == "arbor":
        r = read_json(os.path.join(run_dir, "result.json"))
        acc, timing = r, r
    else:
        acc = read_json(os.path.join(run_dir, "accuracy.json"))
        timing = read_json(os.path.join(run_dir, "timing.json"))
    return {"scenario": name, "program": program, "ate_rmse_m": acc["ate_rmse_m"],
            "ate_aligned_rmse_m": acc["ate_aligned_rmse_m"], "landmark_rmse_m": acc["landmark_rmse_m"],
            "nees_median": acc["nees_median"], "nees_in_band_fraction": acc["nees_in_band_fraction"],
            "landmarks": timing["landmarks"], "step_time_median_s": timing["step_time_median_s"],
            "step_time_p95_s": timing["step_time_p95_s"], "diverged_at_s": acc.get("diverged_at_s"),
            "joint_covariance_indefinite_at_s": acc.get("joint_covariance_indefinite_at_s")}


def compare(rows, dirs):
    """Adds to the rows of one scenario the largest Arbor-MRPT position gap before that MRPT run blew up (if it
    did), and each program's time per scan over the same band of map sizes: the 10 % below N, the smallest of
    the final maps and of the maps at a blow-up (the later scans are not the filter's work)."""
    own = {r["program"]: math.inf if r["diverged_at_s"] is None else r["diverged_at_s"] for r in rows}
    until = min(own.values())
    steps = {r["program"]: read_steps(dirs[r["program"]]) for r in rows}
    n_ref = min(max((lm for t, _, lm in s if t < until), default=0) for s in steps.values())
    for r in rows:
        r["pose_gap_to_arbor_m"] = pose_gap(dirs["arbor"], dirs[r["program"]], own[r["program"]])
        r["band_landmarks"] = n_ref
        r["step_time_band_s"] = band_step_time(steps[r["program"]], n_ref, until)
    return rows


def write_csv(path, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def fmt(v, digits=4):
    return "–" if v is None else f"{v:.{digits}g}"


def commit_of(repo):
    return subprocess.run(["git", "-C", repo, "rev-parse", "--short", "HEAD"], check=True, capture_output=True,
                          text=True).stdout.strip()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out", help="working folder: scenarios and run folders")
    p.add_argument("--build", default="build")
    p.add_argument("--results", help="where the tables go (default results/peers/<commit>_vm_gcc-12.2.0)")
    p.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5])
    p.add_argument("--landmarks", type=int, default=200)
    p.add_argument("--steps", type=int, default=300)
    # The simulated robot explores slowly: a 2000-landmark world (the area grows with N) driven for 1500 scans
    # ends with about 500 landmarks in the map, the N the timing target names.
    p.add_argument("--timing-landmarks", type=int, default=2000)
    p.add_argument("--timing-steps", type=int, default=1500)
    p.add_argument("--timing-repeats", type=int, default=3, help="alternating Arbor/MRPT runs of the timing world")
    a = p.parse_args()
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    arbor = os.path.abspath(os.path.join(a.build, "bin", "arbor"))
    mrpt = os.path.abspath(os.path.join(a.build, "bin", "mrpt_ekf_slam"))
    for binary in (arbor, mrpt):
        if not os.access(binary, os.X_OK):
            sys.exit(f"{binary} missing: ninja -C {a.build} arbor mrpt_ekf_slam "
                     "(MRPT: apt-get install libmrpt-slam-dev)")
    results = a.results or os.path.join(repo, "results", "peers", f"{commit_of(repo)}_vm_gcc-12.2.0")
    os.makedirs(os.path.join(a.out, "scenarios"), exist_ok=True)
    os.makedirs(results, exist_ok=True)

    accuracy = []
    for seed in a.seeds:
        name = f"uniform_L{a.landmarks}_S{a.steps}_s{seed}"
        scenario = os.path.join(a.out, "scenarios", name + ".scn")
        simulate(arbor, scenario, a.landmarks, a.steps, seed)
        dirs = run_pair(arbor, mrpt, scenario, a.out, name)
        accuracy += compare([row_of(k, name, d) for k, d in dirs.items()], dirs)
        print(f"done {name}", flush=True)
    write_csv(os.path.join(results, "accuracy.csv"), accuracy)

    timing = []
    name = f"uniform_L{a.timing_landmarks}_S{a.timing_steps}_s1"
    scenario = os.path.join(a.out, "scenarios", name + ".scn")
    simulate(arbor, scenario, a.timing_landmarks, a.timing_steps, 1)
    for r in range(a.timing_repeats):
        dirs = run_pair(arbor, mrpt, scenario, a.out, name, repeat=f"_timing{r}")
        rows = [row_of(k, name, d) for k, d in dirs.items()]
        timing += [dict(row, repeat=r) for row in compare(rows, dirs)]
    write_csv(os.path.join(results, "timing.csv"), timing)

    lines = ["## Accuracy: uniform worlds, known association", "",
             f"{a.landmarks} landmarks, {a.steps} steps; SE(2)-aligned ATE [m] (unaligned in brackets), the largest "
             "distance between the two filters' positions at any scan, pose NEES median and share of scans inside "
             f"the 95 % band [{NEES_BAND[0]}, {NEES_BAND[1]}].", "",
             "| seed | Arbor EKF ATE | MRPT ATE | Arbor − MRPT aligned ATE | largest position gap [m] | "
             "MRPT Davison ATE (gap) | MRPT stock start ATE | Arbor NEES med / in band | MRPT NEES med / in band | "
             "landmarks Arbor / MRPT |", "|---|---|---|---|---|---|---|---|---|---|"]
    by = {(r["scenario"], r["program"]): r for r in accuracy}
    for seed in a.seeds:
        name = f"uniform_L{a.landmarks}_S{a.steps}_s{seed}"
        ar, mr, ms, md = (by[(name, k)] for k in ("arbor", "mrpt", "mrpt_stock", "mrpt_davison"))
        gap = ar["ate_aligned_rmse_m"] - mr["ate_aligned_rmse_m"] if mr["ate_aligned_rmse_m"] is not None else None
        lines.append(f"| {seed} | {fmt(ar['ate_aligned_rmse_m'])} ({fmt(ar['ate_rmse_m'])}) | "
                     f"{fmt(mr['ate_aligned_rmse_m'])} ({fmt(mr['ate_rmse_m'])}) | "
                     f"{'–' if gap is None else f'{gap:+.1e}'} | {mr['pose_gap_to_arbor_m']:.1e} | "
                     f"{fmt(md['ate_aligned_rmse_m'])} ({md['pose_gap_to_arbor_m']:.1e}) | "
                     f"{fmt(ms['ate_aligned_rmse_m'])} ({fmt(ms['ate_rmse_m'])}) | "
                     f"{fmt(ar['nees_median'], 3)} / {fmt(ar['nees_in_band_fraction'], 2)} | "
                     f"{fmt(mr['nees_median'], 3)} / {fmt(mr['nees_in_band_fraction'], 2)} | "
                     f"{ar['landmarks']} / {mr['landmarks']} |")
    diverged = [r for r in accuracy if r["diverged_at_s"] is not None]
    indefinite = [r for r in accuracy if r["joint_covariance_indefinite_at_s"] is not None]
    lines += ["", f"Of these {sum(r['program'] != 'arbor' for r in accuracy)} MRPT runs, {len(diverged)} blew up "
              f"(pose not finite or pose covariance indefinite) and {len(indefinite)} had an indefinite joint "
              "covariance at some checked scan."]

    t0 = timing[0]
    lines += ["", f"## Time per scan: {a.timing_landmarks}-landmark world, {a.timing_steps} scans, seed 1, "
              f"{a.timing_repeats} alternating repeats (median of the repeats)", "",
              f"Band: the scans with {math.ceil(0.9 * t0['band_landmarks'])}–{t0['band_landmarks']} landmarks in the "
              "map (the smallest of the final maps and of the maps at a blow-up).", "",
              "| program | landmarks at the end | median in the band [ms] | median over the run [ms] | p95 [ms] | "
              "aligned ATE [m] | largest position gap to Arbor [m] | covariance indefinite at / blew up at [s] |",
              "|---|---|---|---|---|---|---|---|"]
    med = {}
    for program in ("arbor", "mrpt", "mrpt_davison"):
        rows = [r for r in timing if r["program"] == program]
        m = {k: statistics.median(r[k] for r in rows) for k in
             ("step_time_band_s", "step_time_median_s", "step_time_p95_s")}
        med[program] = m
        r0 = rows[0]
        lines.append(f"| {program} | {r0['landmarks']} | {1e3 * m['step_time_band_s']:.3g} | "
                     f"{1e3 * m['step_time_median_s']:.3g} | {1e3 * m['step_time_p95_s']:.3g} | "
                     f"{fmt(r0['ate_aligned_rmse_m'])} | {r0['pose_gap_to_arbor_m']:.1e} | "
                     f"{fmt(r0['joint_covariance_indefinite_at_s'])} / {fmt(r0['diverged_at_s'])} |")
    for program in ("mrpt", "mrpt_davison"):
        lines += ["", f"{program} / Arbor time per scan in the band: "
                  f"{med[program]['step_time_band_s'] / med['arbor']['step_time_band_s']:.1f}x."]
    lines += ["", "A run that blew up has no finite ATE (–); its position gap is taken before the blow-up. The joint "
              "covariance is checked every 20 scans."]
    lines.append("")
    with open(os.path.join(results, "comparison.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
