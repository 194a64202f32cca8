#!/bin/bash
# Association in clutter (issue 12): FastSLAM 2.0, 100 particles, on clustered and rooms worlds of 250
# landmarks with 0, 2 and 5 spurious measurements per scan, seeds 1-5, for every strategy. Also JCBB with the
# landmark existence bookkeeping off (--confirm 1 --provisional-scans 0: every new landmark counts at once and
# only negative evidence removes it), the ablation of deliverable 1; and known association without its
# chi-square gate (--known-gate 1), the stronger reference where the noise has no outliers. Locality runs on
# LOCALITY_SEEDS (default: every seed). A run whose result.json exists is skipped, so an interrupted study
# resumes. Then:
#   /usr/bin/python3 analysis/studies/clutter.py OUT
# Usage: experiments/scripts/clutter_study.sh OUT [ARBOR_BINARY]
# Scale with SEEDS, CLUTTER, WORLDS, LOCALITY_SEEDS, and FILTER_OFFSETS (default 0): each world is also run
# with the filter seeds s + OFFSET. A ratio such as JCBB's ATE over known association's is a comparison of
# particle lineages when each world runs once: on rooms, clutter 5, one filter seed per world read 1.81 where
# five read 1.58 (results/association/5b09801_vm_gcc-12.2.0).
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"  # $out, $arbor, the repository root as working directory, once
seeds=${SEEDS:-"1 2 3 4 5"}
clutter=${CLUTTER:-"0 2 5"}
worlds=${WORLDS:-"clustered rooms"}
locality_seeds=${LOCALITY_SEEDS:-$seeds}
offsets=${FILTER_OFFSETS:-0}
mkdir -p "$out/scenarios"

for w in $worlds; do
  for c in $clutter; do
    for s in $seeds; do
      scn=$out/scenarios/$w-c$c-s$s.scn
      [ -f "$scn" ] || "$arbor" simulate --world "$w" --landmarks 250 --clutter "$c" --seed "$s" --out "$scn" > /dev/null
      for o in $offsets; do
        fs=$((s + o))
        run=$out/runs/$w-c$c-s$s$([ "$o" = 0 ] || echo "-f$fs")  # offset 0 keeps the names of earlier studies
        common=(--scenario "$scn" --filter fastslam2 --map naive --particles 100 --seed "$fs" --threads 2)
        for a in known nn jcbb; do
          once "$run-$a" run "${common[@]}" --assoc "$a"
        done
        once "$run-jcbb_no_existence" run "${common[@]}" --assoc jcbb --confirm 1 --provisional-scans 0
        once "$run-known_no_gate" run "${common[@]}" --assoc known --known-gate 1
        for l in $locality_seeds; do
          [ "$l" = "$s" ] && once "$run-locality" run "${common[@]}" --assoc locality
        done
      done
    done
  done
done
echo "done: $out"
