#!/bin/bash
# The cluttered-sensor combination with the start rule (--provisional-steer-min 3, the default), on every
# condition of the table; ate_table.py compares it with the committed JCBB, combination and known-association
# runs of the same world and filter seeds. Usage: start_rule.sh OUT (from the repository root; ARBOR=binary).
set -euo pipefail
out=$1
run=results/association/5b09801_vm_gcc-12.2.0/filter_seeds.sh
flags=(--assoc jcbb --pose-from-confirmed --close-loops --chi2 0.999)
"$run" "$out" start_rule rooms 5 "${flags[@]}"
"$run" "$out" start_rule clustered 5 "${flags[@]}"
OFFSETS="0 1000" "$run" "$out" start_rule rooms 0 "${flags[@]}"
OFFSETS="0 1000" "$run" "$out" start_rule rooms 2 "${flags[@]}"
OFFSETS="0 1000" "$run" "$out" start_rule clustered 2 "${flags[@]}"
OFFSETS="0 1000" "$run" "$out" start_rule uniform 5 "${flags[@]}"
SEEDS="$(seq -s ' ' 41 80)" OFFSETS="0 1000" "$run" "$out/fresh" start_rule rooms 5 "${flags[@]}"
SEEDS="$(seq -s ' ' 41 80)" OFFSETS="0 1000" "$run" "$out/fresh" start_rule clustered 5 "${flags[@]}"
