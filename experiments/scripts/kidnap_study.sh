#!/bin/bash
# The kidnapped robot (issue 12, deliverable 4): uniform and rooms worlds of 200 landmarks, 500 scans, the
# robot carried at 150 s back to where it was at 75 s, unseen by its odometer; FastSLAM 2.0 with JCBB, 100
# particles, with and without --relocalize, seeds 1-20. Also the same worlds without a kidnap, to count
# relocalisations that should not happen. A run whose result.json exists is skipped. Then:
#   /usr/bin/python3 analysis/studies/kidnap.py OUT
# Usage: experiments/scripts/kidnap_study.sh OUT [ARBOR_BINARY]
# Scale with SEEDS, WORLDS; RELOCALIZE_ARGS is added to the relocalising runs (e.g. "--relocalize-min-pairings 4").
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"  # $out, $arbor, the repository root as working directory, once
KEEP_STEPS=1  # analysis/studies/kidnap.py reads which scans re-seeded from steps.csv
seeds=${SEEDS:-$(seq 1 20)}
worlds=${WORLDS:-"uniform rooms"}
read -r -a relocalize_args <<< "${RELOCALIZE_ARGS:-}"
mkdir -p "$out/scenarios"

for w in $worlds; do
  for s in $seeds; do
    for kind in kidnap plain; do
      scn=$out/scenarios/$w-$kind-s$s.scn
      kidnap=()
      [ "$kind" = kidnap ] && kidnap=(--kidnap 150)
      [ -f "$scn" ] || "$arbor" simulate --world "$w" --landmarks 200 --seed "$s" "${kidnap[@]}" --out "$scn" > /dev/null
      common=(--scenario "$scn" --filter fastslam2 --map naive --assoc jcbb --particles 100 --seed "$s" --threads 2)
      once "$out/runs/$w-$kind-s$s-off" run "${common[@]}"
      once "$out/runs/$w-$kind-s$s-relocalize" run "${common[@]}" --relocalize "${relocalize_args[@]}"
    done
  done
done
