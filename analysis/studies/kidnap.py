#!/usr/bin/python3
"""The kidnapped-robot study (experiments/scripts/kidnap_study.sh): per run, the scans from the kidnap until
the best particle's position is first back within max(RECOVERED_M, BASELINE_FACTOR x its median error in the
BASELINE_SCANS scans before the kidnap) of the truth (none: lost), and its error ten
scans after the kidnap and at the end; the share of seeds that recover within 10 scans; relocalisations on
the runs without a kidnap (there they can only be loop closures or mistakes). Each re-seeding (the
`relocalized` column of steps.csv, written since 4eb58b0) counts as closer when the best particle's error at
its step is below the error at the step before, and as further otherwise: a loop closure or a recovery moves
the robot towards the truth, a mistake away from it.

Usage: /usr/bin/python3 analysis/studies/kidnap.py OUT   (writes OUT/kidnap.csv and OUT/kidnap.md)
"""
import csv
import os
import pathlib
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # analysis/: arbor_analysis
from arbor_analysis.results import read_result, read_scenario_truth, read_tum  # noqa: E402

RECOVERED_M = 1.0   # position error under which the robot counts as found again, or
BASELINE_FACTOR = 2.0  # this factor times its median error over the BASELINE_SCANS scans before the kidnap
BASELINE_SCANS = 20    # (some worlds' filters drift past RECOVERED_M on their own)
WITHIN_SCANS = 10   # the target: recovered within this many scans of the kidnap


def recovery(run, scenario, kidnap):
    """(scans from the kidnap to the first error under the recovery threshold or None, the error WITHIN_SCANS
    scans after the kidnap, the final error); the first two are None without a kidnap (kidnap: its time)."""
    truth = read_scenario_truth(scenario)[0]
    best = run / "trajectory_best.tum"  # the best particle's path (runs before 3f0d391: trajectory.tum)
    est = read_tum(best if best.exists() else run / "trajectory.tum")
    # Steps are matched by time to the microsecond: the trajectory holds every step with a truth pose.
    truth["key"] = truth.t.round(6)
    est["key"] = est.t.round(6)
    both = truth.merge(est[["key", "x", "y"]], on="key", suffixes=("", "_est"))
    errors = list(zip(both.t, np.hypot(both.x_est - both.x, both.y_est - both.y)))
    if kidnap is None:
        return None, None, errors[-1][1], errors
    before = sorted([e for t, e in errors if t < kidnap][-BASELINE_SCANS:])
    threshold = max(RECOVERED_M, BASELINE_FACTOR * before[len(before) // 2])
    after = [e for t, e in errors if t >= kidnap]
    scans = next((i for i, e in enumerate(after) if e <= threshold), None)
    return scans, after[WITHIN_SCANS], errors[-1][1], errors


def reseedings(run, errors):
    """(re-seedings that brought the robot closer to the truth, ones that took it further), or None when the
    run has no steps.csv or one that predates the relocalized column."""
    if not (run / "steps.csv").exists():
        return None
    with open(run / "steps.csv", newline="") as f:
        steps = list(csv.DictReader(f))
    if not steps or "relocalized" not in steps[0]:
        return None
    error_at = {round(t, 6): e for t, e in errors}
    times = sorted(error_at)
    closer = further = 0
    for s in steps:
        if s["relocalized"] != "1":
            continue
        t = round(float(s["time_s"]), 6)
        i = times.index(t)
        if i == 0:
            continue
        if error_at[t] < error_at[times[i - 1]]:
            closer += 1
        else:
            further += 1
    return closer, further


def main():
    out = pathlib.Path(sys.argv[1])
    rows = []
    for run in sorted((out / "runs").iterdir()):
        if not (run / "result.json").exists():
            continue
        world, kind, seed, mode = run.name.split("-")
        result = read_result(run)
        kidnap = result["scenario"].get("kidnap_time_s")
        scans, error_10, final_error, errors = recovery(run, out / "scenarios" / f"{world}-{kind}-{seed}.scn",
                                                        None if kidnap is None else float(kidnap))
        moves = reseedings(run, errors)
        rows.append({"world": world, "kidnap": kind == "kidnap", "seed": int(seed[1:]), "relocalize": mode == "relocalize",
                     "recovery_scans": "" if scans is None else scans,
                     "error_after_10_scans_m": "" if error_10 is None else round(error_10, 3),
                     "final_error_m": round(final_error, 3),
                     "ate_rmse_m": round(result["ate_rmse_m"], 3), "relocalizations": result.get("relocalizations", 0),
                     "assoc_f1": round(result["assoc_f1"], 4),
                     "reseedings_closer": "" if moves is None else moves[0],
                     "reseedings_further": "" if moves is None else moves[1]})
    with open(out / "kidnap.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| world | kidnap | relocalize | seeds | recovered within 10 scans | recovered at all | median scans to recover | "
             "median error 10 scans after the kidnap [m] | mean ATE [m] | runs with a relocalisation | relocalisations | "
             "closer / further |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
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
                known = [r for r in sel if r["reseedings_closer"] != ""]
                moves = (f"{sum(r['reseedings_closer'] for r in known)} / {sum(r['reseedings_further'] for r in known)}"
                         if known else "-")
                k = "yes" if kidnap else "no"
                recovered = f"{within}/{len(sel)} | {len(rec)} | {med} | {e10_text}" if kidnap else "- | - | - | -"
                lines.append(f"| {world} | {k} | {'on' if reloc else 'off'} | {len(sel)} | {recovered} | "
                             f"{ate:.2f} | {with_reloc} | {total} | {moves} |")
    (out / "kidnap.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
