#!/bin/bash
# `arbor run` at N = 10^3 ... 10^7 landmarks (issue 13): FastSLAM 2.0, 100 particles, 1 thread, known
# association, starting from a surveyed map of the whole world (`arbor simulate --survey-out`, uniform world,
# 200 scans, seed 1) so that every step works in an N-landmark map. Per run result.json gives
# step_time_median_s and peak_rss_bytes. Usage: prior_map_scale.sh OUT [ARBOR_BINARY]
# (NS and MAPS override the sizes and back ends; about 4 min and 3 GB of disk for the default).
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"
mkdir -p "$out"
for n in ${NS:-1000 10000 100000 1000000 10000000}; do
  world="$out/world_$n"
  if [ ! -f "$world.csv" ]; then
    "$arbor" simulate --world uniform --landmarks "$n" --steps 200 --seed 1 --out "$world.scn" \
        --survey-out "$world.csv.partial" > /dev/null
    mv "$world.csv.partial" "$world.csv"
  fi
  for map in ${MAPS:-tree trie}; do
    dir="$out/run_${map}_$n"
    once "$dir" run --scenario "$world.scn" --prior-map "$world.csv" --map "$map" --assoc known \
        --filter fastslam2 --particles 100 --threads 1 --seed 1
    rm -f "$dir/map.csv"  # N landmarks again (1.3 GB at 10^7); result.json holds the figures
  done
done
echo "n,map,step_time_median_s,step_time_p95_s,wall_time_s,peak_rss_bytes,ate_rmse_m,landmarks" > "$out/scale.csv"
for n in ${NS:-1000 10000 100000 1000000 10000000}; do
  for map in ${MAPS:-tree trie}; do
    /usr/bin/python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); print(",".join(str(x) for x in [sys.argv[2], sys.argv[3], r["step_time_median_s"], r["step_time_p95_s"], r["wall_time_s"], r["peak_rss_bytes"], r["ate_rmse_m"], r["landmarks"]]))' \
      "$out/run_${map}_$n/result.json" "$n" "$map" >> "$out/scale.csv"
  done
done
cat "$out/scale.csv"
