#!/usr/bin/env python3
"""The kidnapped-robot study (experiments/scripts/kidnap_study.sh): per run, the scans from the kidnap until
the best particle's position is first back within max(RECOVERED_M, BASELINE_FACTOR x its median error in the
BASELINE_SCANS scans before the kidnap) of the truth (none: lost), and its error ten
scans after the kidnap and at the end; the share of seeds that recover within 10 scans; relocalisations on
the runs without a kidnap (there they can only be loop closures or mistakes: compare their ATE).

Usage: /usr/bin/python3 analysis/kidnap.py OUT   (writes OUT/kidnap.csv and OUT/kidnap.md)
"""
import csv
import json
import math
import pathlib
import sys

RECOVERED_M = 1.0   # position error under which the robot counts as found again, or
BASELINE_FACTOR = 2.0  # this factor times its median error over the BASELINE_SCANS scans before the kidnap
BASELINE_SCANS = 20    # (some worlds' filters drift past RECOVERED_M on their own)
WITHIN_SCANS = 10   # the target: recovered within this many scans of the kidnap


def read_truth(path):
    """Times and true (x, y) of a scenario's steps, and its kidnap time (None without one)."""
    times, truth, kidnap, t = [], [], None, None
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "meta" and parts[1] == "kidnap_time_s":
                kidnap = float(parts[2])
            elif parts[0] == "step":
                t = float(parts[1])
            elif parts[0] == "truth":
                times.append(t)
                truth.append((float(parts[1]), float(parts[2])))
    return times, truth, kidnap


def read_tum(path):
    poses = {}
    with open(path) as f:
        for line in f:
            v = line.split()
            if v and not v[0].startswith("#"):
                poses[round(float(v[0]), 6)] = (float(v[1]), float(v[2]))
    return poses


def recovery(run, scenario):
    """(scans from the kidnap to the first error under RECOVERED_M or None, the error WITHIN_SCANS scans after
    the kidnap, the final error); the first two are None without a kidnap."""
    times, truth, kidnap = read_truth(scenario)
    est = read_tum(run / "trajectory.tum")
    errors = []
    for t, (x, y) in zip(times, truth):
        e = est.get(round(t, 6))
        if e is not None:
            errors.append((t, math.hypot(e[0] - x, e[1] - y)))
    if kidnap is None:
        return None, None, errors[-1][1]
    before = sorted([e for t, e in errors if t < kidnap][-BASELINE_SCANS:])
    threshold = max(RECOVERED_M, BASELINE_FACTOR * before[len(before) // 2])
    after = [e for t, e in errors if t >= kidnap]
    scans = next((i for i, e in enumerate(after) if e <= threshold), None)
    return scans, after[WITHIN_SCANS], errors[-1][1]


def main():
    out = pathlib.Path(sys.argv[1])
    rows = []
    for run in sorted((out / "runs").iterdir()):
        if not (run / "result.json").exists():
            continue
        world, kind, seed, mode = run.name.split("-")
        result = json.loads((run / "result.json").read_text())
        scans, error_10, final_error = recovery(run, out / "scenarios" / f"{world}-{kind}-{seed}.scn")
        rows.append({"world": world, "kidnap": kind == "kidnap", "seed": int(seed[1:]), "relocalize": mode == "relocalize",
                     "recovery_scans": "" if scans is None else scans,
                     "error_after_10_scans_m": "" if error_10 is None else round(error_10, 3),
                     "final_error_m": round(final_error, 3),
                     "ate_rmse_m": round(result["ate_rmse_m"], 3), "relocalizations": result.get("relocalizations", 0),
                     "assoc_f1": round(result["assoc_f1"], 4)})
    with open(out / "kidnap.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| world | kidnap | relocalize | seeds | recovered within 10 scans | recovered at all | median scans to recover | "
             "median error 10 scans after the kidnap [m] | mean ATE [m] | runs with a relocalisation | relocalisations |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for world in sorted({r["world"] for r in rows}):
        for kidnap in (True, False):
            for reloc in (False, True):
                sel = [r for r in rows if r["world"] == world and r["kidnap"] == kidnap and r["relocalize"] == reloc]
                if not sel:
                    continue
                rec = sorted(r["recovery_scans"] for r in sel if r["recovery_scans"] != "")
                within = sum(1 for r in rec if r <= WITHIN_SCANS)
                med = rec[len(rec) // 2] if rec else "-"
                e10 = sorted(r["error_after_10_scans_m"] for r in sel if r["error_after_10_scans_m"] != "")
                e10_text = f"{e10[len(e10) // 2]:.2f}" if e10 else "-"
                ate = sum(r["ate_rmse_m"] for r in sel) / len(sel)
                with_reloc = sum(1 for r in sel if r["relocalizations"] > 0)
                total = sum(r["relocalizations"] for r in sel)
                k = "yes" if kidnap else "no"
                recovered = f"{within}/{len(sel)} | {len(rec)} | {med} | {e10_text}" if kidnap else "- | - | - | -"
                lines.append(f"| {world} | {k} | {'on' if reloc else 'off'} | {len(sel)} | {recovered} | "
                             f"{ate:.2f} | {with_reloc} | {total} |")
    (out / "kidnap.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
