#!/usr/bin/env bash
# The README's first command: installs what is missing, builds (Release), and runs the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_dependencies.sh
scripts/build.sh build -DCMAKE_BUILD_TYPE=Release
out=${ARBOR_OUT:-out/main}
mkdir -p "$out"
build/bin/arbor simulate --world uniform --landmarks 200 --steps 500 --clutter 0 --seed 1 --out "$out/world.scn"
build/bin/arbor run --scenario "$out/world.scn" --filter fastslam2 --map naive --assoc known --particles 100 \
  --seed 1 --out "$out/run"
echo "arbor: results in $out/run (result.json, trajectory.tum, map.csv, steps.csv)"
