#!/bin/bash
# How often known association's own gate rejects a true measurement: each world run with the true ids and
# `--known-gate G`, filter seed = world seed. A consistent filter rejects a fraction 1 - G of them. One csv
# line per run (resumable like filter_seeds.sh):
#   world_seed,gate,rejected_measurements,true_measurements,ate_aligned_rmse_m,first_rejection_scan
# first_rejection_scan is the step index (as associations.csv counts), -1 where nothing was rejected.
# Usage: gate_calibration.sh OUT WORLD CLUTTER; scale with SEEDS (default 1..40), GATES ("0.99 0.999 0.9999"),
# PARTICLES (100), ARBOR.
set -euo pipefail
out=$1 world=$2 clutter=$3
arbor=${ARBOR:-build/bin/arbor}
py=/usr/bin/python3
analysis=$(cd "$(dirname "$0")/../../../analysis" && pwd)  # arbor_results.py reads the scenarios
mkdir -p "$out/scenarios" "$out/runs"
csv=$out/$world-c$clutter.csv
: > "$csv"
for s in ${SEEDS:-$(seq -s ' ' 1 40)}; do
  scn=$out/scenarios/$world-c$clutter-s$s.scn
  [ -f "$scn" ] || "$arbor" simulate --world "$world" --landmarks 250 --clutter "$clutter" --seed "$s" --out "$scn" > /dev/null
  for g in ${GATES:-0.99 0.999 0.9999}; do
    run=$out/runs/known_gate_$g-$world-c$clutter-s$s
    [ -f "$run/result.json" ] || "$arbor" run --scenario "$scn" --filter fastslam2 --particles "${PARTICLES:-100}" \
      --assoc known --known-gate "$g" --seed "$s" --threads 2 --quiet --out "$run" > /dev/null
    "$py" - "$analysis" "$scn" "$run" "$s" "$g" >> "$csv" <<'PY'
import json, sys
analysis, scenario, run, seed, gate = sys.argv[1:]
sys.path.insert(0, analysis)
import arbor_results as ar
labels = [measured for _, _, measured in ar.read_scenario_steps(scenario)]  # true id per measurement, -1: clutter
first = -1  # a rejected true measurement is one the run left unpaired
for line in list(open(f"{run}/associations.csv"))[1:]:
    step, measurement, landmark = map(int, line.split(","))
    if landmark < 0 and labels[step][measurement] != -1:
        first = step
        break
r = json.load(open(f"{run}/result.json"))
true = sum(label != -1 for step in labels for label in step)
print(seed, gate, r["rejected_measurements"], true, r["ate_aligned_rmse_m"], first, sep=",")
PY
  done
done
echo "$csv"
