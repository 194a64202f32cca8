#!/bin/bash
# Relocalisation over 12 seeds x 50 kidnappings per world, 10 landmarks + 2 clutter per scan, NN and JCBB with
# a wrong prior and the locality tree without one, at --accept 0 and 0.8: both success rates (all pairings
# right; the implied pose within 0.6 m and 0.09 rad) and the time per call. The seeds and trials are those of
# 6e76df1_vm_gcc-12.2.0/relocalize_seeds.sh, so its strict rates are reproduced here.
# Usage: relocalize_pose.sh BINARY > relocalize_pose.csv
set -euo pipefail
bin=$1
echo "seed,accept,strategy,world,n,m,clutter,trials,success_rate,median_hypotheses,median_time_s,p90_time_s,pose_success_rate,median_position_error_m"
for wn in "uniform 10000" "rooms 1000" "uniform 1000" "rooms 10000" "clustered 10000"; do
  set -- $wn
  for accept in 0 0.8; do
    for seed in $(seq 1 12); do
      "$bin" relocalize --world "$1" --landmarks "$2" --observations 10 --clutter 2 --trials 50 --seed "$seed" \
          --accept "$accept" --csv | tail -n +2 | sed "s/^/$seed,$accept,/"
    done
  done
done
