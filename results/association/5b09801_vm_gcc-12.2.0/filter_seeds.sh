#!/bin/bash
# One strategy's runs over world seeds x filter seeds, so that a comparison between strategies is not a
# comparison between particle lineages: each world is run with the filter seeds s + OFFSET. A run whose
# result.json exists is skipped (an interrupted study resumes). One csv line per run:
#   world_seed,filter_seed,ate_aligned_rmse_m,ate_rmse_m,assoc_f1,nees_median
# Usage: filter_seeds.sh OUT NAME WORLD CLUTTER [arbor run options...]
# Scale with SEEDS (default 1..40), OFFSETS (default "0 1000 2000 3000 4000"), PARTICLES (100), ARBOR.
set -euo pipefail
out=$1 name=$2 world=$3 clutter=$4; shift 4
arbor=${ARBOR:-build/bin/arbor}
seeds=${SEEDS:-$(seq -s ' ' 1 40)}
offsets=${OFFSETS:-"0 1000 2000 3000 4000"}
py=/usr/bin/python3
mkdir -p "$out/scenarios" "$out/runs" "$out/csv"
csv=$out/csv/$name-$world-c$clutter.csv
: > "$csv"
for s in $seeds; do
  scn=$out/scenarios/$world-c$clutter-s$s.scn
  [ -f "$scn" ] || "$arbor" simulate --world "$world" --landmarks 250 --clutter "$clutter" --seed "$s" --out "$scn" > /dev/null
  for o in $offsets; do
    fs=$((s + o)) run=$out/runs/$name-$world-c$clutter-s$s-f$fs
    [ -f "$run/result.json" ] || "$arbor" run --scenario "$scn" --filter fastslam2 --particles "${PARTICLES:-100}" \
      --seed "$fs" --threads 2 --quiet --out "$run" "$@" > /dev/null
    "$py" -c "import json,sys; r = json.load(open(sys.argv[1]))
print($s, $fs, r['ate_aligned_rmse_m'], r['ate_rmse_m'], r['assoc_f1'], r['nees_median'], sep=',')" "$run/result.json" >> "$csv"
  done
done
echo "$csv"
