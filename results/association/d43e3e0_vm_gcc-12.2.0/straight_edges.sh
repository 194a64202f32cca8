#!/bin/bash
# Issue 12's association figures again on the simulator that drives straight edges (d43e3e0): known
# association without its gate (the reference), JCBB, NN, and JCBB with the cluttered-sensor combination
# (--pose-from-confirmed --close-loops --chi2 0.999, with the start rule, the default), 40 worlds x 2 filter
# seeds per condition, with 5b09801's filter_seeds.sh. Worlds 1-40 again, but their trajectories are new:
# nothing here was tuned on them. Usage: straight_edges.sh OUT [CONDITION...] (from the repository root;
# ARBOR=binary). Default conditions: all six.
set -euo pipefail
out=$1; shift
run=results/association/5b09801_vm_gcc-12.2.0/filter_seeds.sh
conditions=("$@")
[ ${#conditions[@]} -gt 0 ] || conditions=("rooms 0" "rooms 2" "rooms 5" "clustered 2" "clustered 5" "uniform 5")
export OFFSETS=${OFFSETS:-"0 1000"}
for c in "${conditions[@]}"; do
  set -- $c
  "$run" "$out" known_nogate "$1" "$2" --assoc known --known-gate 1
  "$run" "$out" jcbb "$1" "$2" --assoc jcbb
  "$run" "$out" nn "$1" "$2" --assoc nn
  "$run" "$out" rule "$1" "$2" --assoc jcbb --pose-from-confirmed --close-loops --chi2 0.999
done
