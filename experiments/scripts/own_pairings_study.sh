#!/bin/bash
# The smoother given a filter's own pairings (issue 41): for every finished run of a sweep folder that paired
# by itself (not --assoc known, not the smoother), the Ceres full-SLAM solve with that run's association
# decisions (its associations.csv), started from its trajectory and map: `arbor smooth --associations RUN`.
# It separates what the failure test counts: a run whose smoothed twin passes failed for its path alone, which a
# filter cannot revise; one whose twin fails too paired wrongly. Writes SWEEP/own_pairings/KEY/ (resumes), then:
#   /usr/bin/python3 analysis/studies/own_pairings.py SWEEP
# Usage: experiments/scripts/own_pairings_study.sh SWEEP [ARBOR_BINARY]   (ONLY: a regular expression the run
# keys must match, e.g. 'chi2-0.99_new-landmark-gate-0.999$')
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"  # $out (the sweep folder), $arbor, the repository root, once
sweep=$out
/usr/bin/python3 - "$sweep" "${ONLY:-}" > "$sweep/own_pairings.todo" <<'PY'
import json, re, sys
sweep, only = sys.argv[1], sys.argv[2]
for line in open(f"{sweep}/results.jsonl"):
    r = json.loads(line)
    if r["status"] != "ok" or r["filter"] == "smoother" or r["assoc"] == "known":
        continue
    if only and not re.search(only, r["key"]):
        continue
    print(r["key"], r["run_dir"], r["scenario"])
PY
while read -r key run scenario; do
  # A solve that fails leaves its folder without result.json: analysis/studies/own_pairings.py counts the twin
  # as failed.
  once "$sweep/own_pairings/$key" smooth --scenario "$sweep/$scenario" --associations "$sweep/$run" ||
    { echo "arbor: the smoother failed on $key" >&2; mkdir -p "$sweep/own_pairings/$key"; }
done < "$sweep/own_pairings.todo"
rm -f "$sweep/own_pairings.todo"
echo "arbor: smoothed $(ls "$sweep/own_pairings" | wc -l) runs' own pairings into $sweep/own_pairings/"
