#!/bin/bash
# Relocalisation success and time per call over 12 seeds x 50 kidnappings, 10 landmarks + 2 clutter per scan:
# the locality tree without a prior, at this commit and (BEFORE, optional) at an earlier build, interleaved
# per seed so that the shared VM's load falls on both alike. Writes CSV rows with the binary and --accept.
# Usage: relocalize_seeds.sh NEW_BINARY [BEFORE_BINARY] > relocalize_seeds.csv
set -euo pipefail
new=$1; before=${2:-}
echo "binary,seed,accept,strategy,world,n,m,clutter,trials,success_rate,median_hypotheses,median_time_s,p90_time_s"
for wn in "uniform 10000" "rooms 1000" "uniform 1000" "rooms 10000" "clustered 10000"; do
  set -- $wn
  for accept in 0 0.8; do
    for seed in $(seq 1 12); do
      for label in new before; do
        bin=$new; [ $label = before ] && bin=$before
        [ -n "$bin" ] || continue
        "$bin" relocalize --world "$1" --landmarks "$2" --observations 10 --clutter 2 --trials 50 --seed "$seed" \
            --assoc locality --accept "$accept" --csv | tail -n +2 |
          awk -F, -v b=$label -v s=$seed -v a=$accept 'BEGIN{OFS=","} {if (NF == 9) $10 = ""; print b, s, a, $0}'
      done
    done
  done
done
