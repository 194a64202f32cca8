#!/usr/bin/env bash
# The default world's median step, FastSLAM 2.0, known association, 2 threads, M = 100 and 1000, naive and
# tree maps: OLD and NEW binaries run alternately (one run of each per setting and repetition), so drift in
# the machine's load falls on both. Each runs on its own `arbor simulate` default world (the scenario format
# changed since 45d9865, so one file cannot serve both). Writes OUT/step_times.csv and prints the medians.
# Usage: experiments/scripts/step_time_alternating.sh OUT OLD_ARBOR NEW_ARBOR [REPETITIONS]   (issue 42)
set -euo pipefail
out=$(realpath -m "${1:?usage: $0 OUT OLD_ARBOR NEW_ARBOR [REPETITIONS]}")
old=$(realpath "${2:?old binary}")
new=$(realpath "${3:?new binary}")
reps=${4:-3}
mkdir -p "$out"
"$old" simulate --out "$out/world_old.scn" > /dev/null
"$new" simulate --out "$out/world_new.scn" > /dev/null
csv="$out/step_times.csv"
echo "repetition,binary,particles,map,threads,step_median_ms,wall_s" > "$csv"
for rep in $(seq 1 "$reps"); do
  for particles in 100 1000; do
    for map in naive tree; do
      for which in old new; do
        if [ "$which" = old ]; then binary=$old; else binary=$new; fi
        rm -rf "$out/run"
        # 45d9865's `run` has no --quiet; its progress goes to stderr.
        "$binary" run --scenario "$out/world_$which.scn" --filter fastslam2 --assoc known --map "$map" \
          --particles "$particles" --threads 2 --out "$out/run" > /dev/null 2>&1
        /usr/bin/python3 -c "import json, sys; r = json.load(open(sys.argv[1])); \
print(f'$rep,$which,$particles,$map,2,{r[\"step_time_median_s\"] * 1e3:.4f},{r[\"wall_time_s\"]:.3f}')" \
          "$out/run/result.json" >> "$csv"
      done
    done
  done
done
rm -rf "$out/run"
/usr/bin/python3 - "$csv" <<'PY'
import sys
import pandas as pd
rows = pd.read_csv(sys.argv[1])
print(rows.groupby(["particles", "map", "binary"])[["step_median_ms", "wall_s"]].median().unstack("binary").round(3))
PY
