#!/usr/bin/python3
"""Writes the small SYNTHETIC results fixture the analysis tests read (numbers are made up from simple
models with seeded noise, shaped like a sweep's output; they are not measurements). Rerun to regenerate:
    /usr/bin/python3 tests/data/results_fixture/make_fixture.py"""

import json
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
METRICS = ["ate_rmse_m", "landmark_rmse_m", "nees_mean", "assoc_precision", "assoc_recall", "assoc_f1", "landmarks",
           "steps", "step_time_median_s", "step_time_p95_s", "wall_time_s", "peak_rss_bytes", "solve_time_s",
           "iterations", "initial_cost", "final_cost", "termination", "assoc_hypotheses_mean"]
COLUMNS = (["key", "status", "error", "dataset", "world", "world_landmarks", "world_steps", "clutter", "world_seed",
            "filter", "map", "assoc", "particles", "seed", "threads", "scenario", "run_dir"] + METRICS +
           ["commit", "host", "compiler", "build", "process_wall_s", "exit_code", "finished_at"])
rng = np.random.default_rng(7)


def row(world_landmarks, clutter, filt, mp, assoc, particles, seed, threads, status="ok", steps=100, world="uniform",
        **metrics):
    key = (f"{world}-n{world_landmarks}-t{steps}-c{clutter:g}__" +
           (f"smoother-s{seed}-t{threads}" if filt == "smoother" else f"{filt}-{mp}-{assoc}-m{particles}-s{seed}-t{threads}"))
    r = {c: None for c in COLUMNS}
    r.update(key=key, status=status, world=world, world_landmarks=world_landmarks, world_steps=steps, clutter=clutter,
             world_seed=seed, filter=filt, map=mp if filt != "smoother" else None, assoc=assoc,
             particles=particles if filt != "smoother" else None, seed=seed, threads=threads,
             scenario=f"scenarios/{world}-n{world_landmarks}-t{steps}-c{clutter:g}-s{seed}.scn", run_dir=f"runs/{key}",
             commit="fixture", host="fixture-host", compiler="gcc-12.2.0", build="release",
             process_wall_s=round(float(rng.uniform(0.1, 2.0)), 4), exit_code=0 if status == "ok" else 1,
             finished_at="2026-01-01T00:00:00Z", steps=steps)
    if status != "ok":
        r["error"] = "exit status 1: synthetic failure"
        return r
    r["landmarks"] = world_landmarks
    r.update(metrics)
    return r


rows = []
# complexity: naive grows ~N, tree/trie ~log N
for n in (100, 1000, 10000):
    for mp, base in (("naive", 2e-7 * n), ("tree", 1e-4 * (1 + 0.1 * math.log10(n))), ("trie", 8e-5 * (1 + 0.1 * math.log10(n)))):
        for seed in (1, 2):
            t = base * rng.lognormal(0, 0.05)
            rows.append(row(n, 0.0, "fastslam1", mp, "known", 100, seed, 1, step_time_median_s=t, step_time_p95_s=1.3 * t,
                            wall_time_s=100 * t, ate_rmse_m=0.3, peak_rss_bytes=int(1e6 + n * 100)))
# accuracy: error falls with particles, 2.0 better than 1.0, nn slightly worse than known
for filt, k in (("fastslam1", 1.0), ("fastslam2", 0.6)):
    for assoc, a in (("known", 1.0), ("nn", 1.2)):
        for m in (1, 10, 100):
            for seed in (1, 2, 3):
                ate = k * a * (0.2 + 2.0 / math.sqrt(m)) * rng.lognormal(0, 0.1)
                rows.append(row(100, 0.0, filt, "tree", assoc, m, seed, 1, steps=300, ate_rmse_m=ate, landmark_rmse_m=0.8 * ate,
                                nees_mean=3.0 * rng.lognormal(0, 0.2), step_time_median_s=1e-5 * m, wall_time_s=1e-3 * m,
                                assoc_f1=1.0 if assoc == "known" else 0.95))
# association: F1 falls with clutter, JCBB degrades least
for assoc, slope in (("nn", 0.08), ("jcbb", 0.03), ("locality", 0.05)):
    for clutter in (0.0, 1.0, 4.0):
        for seed in (1, 2):
            p = max(0.0, 1 - slope * clutter) * rng.uniform(0.97, 1.0)
            rc = 0.97 * rng.uniform(0.97, 1.0)
            rows.append(row(100, clutter, "fastslam2", "tree", assoc, 20, seed, 1, steps=200, assoc_precision=p, assoc_recall=rc,
                            assoc_f1=2 * p * rc / (p + rc), ate_rmse_m=0.3 + 0.05 * clutter))
# hypotheses: locality linear, unrestricted steeper
for assoc, power in (("locality", 1.0), ("itree", 1.8)):
    for n in (50, 200, 800):
        for seed in (1, 2):
            rows.append(row(n, 0.5, "fastslam2", "tree", assoc, 10, seed, 1, world="clustered",
                            assoc_hypotheses_mean=3 * n ** power * rng.lognormal(0, 0.05), assoc_f1=0.9))
# smoother vs FastSLAM on the accuracy scenarios
for seed in (1, 2, 3):
    rows.append(row(100, 0.0, "smoother", None, "known", None, seed, 1, steps=300, ate_rmse_m=0.25 * rng.lognormal(0, 0.1),
                    landmark_rmse_m=0.2, solve_time_s=0.05, iterations=12, initial_cost=1e4, final_cost=50.0,
                    termination="CONVERGENCE"))
# threads
for t in (1, 2, 4):
    for seed in (1, 2):
        rows.append(row(1000, 0.0, "fastslam2", "tree", "known", 300, seed, t, step_time_median_s=0.01 / t ** 0.8,
                        ate_rmse_m=0.3))
rows.append(row(100, 0.0, "fastslam1", "naive", "jcbb", 100, 9, 1, status="failed"))

with open(os.path.join(HERE, "results.jsonl"), "w", encoding="utf-8") as f:
    for r in rows:
        f.write(json.dumps(r, separators=(",", ":")) + "\n")
    f.write('{"key":"half-written row without newl')  # an interrupted append: readers must ignore it


def cell(v):
    return "" if v is None else str(v)


with open(os.path.join(HERE, "results.csv"), "w", encoding="utf-8") as f:
    f.write(",".join(COLUMNS) + "\n")
    for r in rows:
        f.write(",".join(cell(r[c]) for c in COLUMNS) + "\n")
with open(os.path.join(HERE, "sweep.json"), "w", encoding="utf-8") as f:
    json.dump({"format": "arbor-sweep 1", "spec_hash": "0000000000f1x7ure", "spec_name": "fixture", "shard": "0/1",
               "grid_runs": len(rows), "columns": COLUMNS}, f, indent=2)

# One run directory with a trajectory and a map over its scenario's ground truth (a circle among landmarks).
best = min((r for r in rows if r["status"] == "ok" and r["ate_rmse_m"] is not None), key=lambda r: r["ate_rmse_m"])
run_dir = os.path.join(HERE, best["run_dir"])
os.makedirs(run_dir, exist_ok=True)
os.makedirs(os.path.join(HERE, "scenarios"), exist_ok=True)
landmarks = rng.uniform(-15, 15, size=(30, 2))
angles = np.linspace(0, 2 * math.pi, 60)
with open(os.path.join(HERE, best["scenario"]), "w", encoding="utf-8") as f:
    f.write("arbor-scenario 2\n# synthetic fixture: truth only (the analysis reads step/truth/landmark lines)\n")
    for i, (x, y) in enumerate(landmarks):
        f.write(f"landmark {i} {x:.3f} {y:.3f}\n")
    for i, a in enumerate(angles):
        f.write(f"step {i * 0.1:.1f} 0 0 0\ntruth {10 * math.cos(a):.3f} {10 * math.sin(a):.3f} {a + math.pi / 2:.3f}\n")
with open(os.path.join(run_dir, "trajectory.tum"), "w", encoding="utf-8") as f:
    for i, a in enumerate(angles):
        th = a + math.pi / 2
        f.write(f"{i * 0.1:.1f} {10 * math.cos(a) + rng.normal(0, 0.2):.3f} {10 * math.sin(a) + rng.normal(0, 0.2):.3f} 0 "
                f"0 0 {math.sin(th / 2):.6f} {math.cos(th / 2):.6f}\n")
with open(os.path.join(run_dir, "map.csv"), "w", encoding="utf-8") as f:
    f.write("id,x,y,sxx,sxy,syy\n")
    for i, (x, y) in enumerate(landmarks):
        f.write(f"{i},{x + rng.normal(0, 0.2):.3f},{y + rng.normal(0, 0.2):.3f},0.01,0,0.01\n")
with open(os.path.join(run_dir, "result.json"), "w", encoding="utf-8") as f:
    json.dump({"config": {"scenario": best["scenario"]}, "ate_rmse_m": best["ate_rmse_m"]}, f)
print(f"wrote {len(rows)} rows and {best['run_dir']}")
