#!/bin/bash
# Runs the smoother and FastSLAM (1.0/2.0, several particle counts) with true association on the same
# simulated worlds, keeping result.json, trajectory.tum and the truth track (truth.tum) of each, for
# analysis/smoother_vs_fastslam.py. Usage: experiments/scripts/smoother_comparison.sh OUT_DIR [ARBOR_BINARY]
set -euo pipefail
out=${1:?usage: $0 OUT_DIR [ARBOR_BINARY]}
arbor=${2:-build/bin/arbor}
seeds=${SEEDS:-"1 2 3"}
particles=${PARTICLES:-"10 100"}
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for seed in $seeds; do
  name=uniform200_s${seed}
  scenario=$work/$name.txt
  "$arbor" simulate --world uniform --landmarks 200 --steps 500 --seed "$seed" --out "$scenario" > /dev/null
  mkdir -p "$out/$name"
  # Truth positions in TUM form (identity rotation), so the analysis needs no scenario file.
  awk '$1 == "step" { t = $2 } $1 == "truth" { printf "%s %s %s 0 0 0 0 1\n", t, $2, $3 }' "$scenario" \
    > "$out/$name/truth.tum"
  "$arbor" smooth --scenario "$scenario" --quiet --out "$work/sm"
  mkdir -p "$out/$name/smoother" && cp "$work/sm/result.json" "$work/sm/trajectory.tum" "$out/$name/smoother/"
  for filter in fastslam1 fastslam2; do
    for m in $particles; do
      "$arbor" run --scenario "$scenario" --filter "$filter" --particles "$m" --seed 1 --threads 2 --quiet \
        --out "$work/fs" > /dev/null
      dir=$out/$name/${filter}_m$m
      mkdir -p "$dir" && cp "$work/fs/result.json" "$work/fs/trajectory.tum" "$dir/"
    done
  done
  echo "done $name"
done
