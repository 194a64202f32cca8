#!/usr/bin/env bash
# Motion-noise inflation on the calibration worlds (issue 41; not kept): every `motion odometry` noise density
# of the 216 calibration scenarios scaled by K (2, 4: the standard deviations by 1.41, 2), JCBB and known
# association with the defaults otherwise, filter seed = world seed as the held-out sweeps pair them.
# Usage: run.sh SWEEP_DIR OUT [ARBOR_BINARY], where SWEEP_DIR is a finished
# `experiments/heldout/run.sh calibration-relocalize` worlds folder (its scenarios/ and its smoother and
# relocalize = false rows) and results/heldout/calibration/calibration-oracle_worlds/results.csv gives known
# association at K = 1. About 8 minutes on 2 cores. Writes OUT/runs.csv and prints the summary.
set -euo pipefail
sweep=$(realpath "${1:?usage: $0 SWEEP_DIR OUT [ARBOR_BINARY]}")
out=$(realpath -m "${2:?usage: $0 SWEEP_DIR OUT [ARBOR_BINARY]}")
arbor=$(realpath "${3:-build/bin/arbor}")
here=$(dirname "$(realpath "$0")")
for k in 2 4; do
  mkdir -p "$out/k$k"
  for f in "$sweep"/scenarios/*.scn; do
    awk -v k=$k '$1=="motion" && $2=="odometry" {printf "motion odometry"; for (i = 3; i <= NF; i++) printf " %.10g", $i * k; print ""; next} {print}' \
      "$f" > "$out/k$k/$(basename "$f")"
  done
done
for k in 2 4; do for a in jcbb known; do for f in "$out"/k$k/*.scn; do echo "$k $a $f"; done; done; done |
  while read -r k a f; do
    b=$(basename "$f" .scn)
    run=$out/runs/k$k-$a/$b
    [ -f "$run/result.json" ] || echo "$arbor run --scenario $f --assoc $a --map tree --seed ${b##*-s} --threads 1 --quiet --out $run"
  done | xargs -P2 -I{} sh -c '{} > /dev/null'
/usr/bin/python3 "$here/summarize.py" "$sweep" "$out" "$here/../calibration-oracle_worlds/results.csv"
