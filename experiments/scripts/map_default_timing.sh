#!/usr/bin/env bash
# Which map back end `arbor run` should default to (issue 44): the three back ends at the default particle
# count (100) and strategy (JCBB) on the maps the shipped scenarios build, run alternately within each
# repetition so that drift in the machine's load falls on all three. Writes OUT/cpu_1thread.csv (process CPU
# time, 1 thread, 5 repetitions; the default world, the README's quick-start world, a held-out world kind and
# Victoria Park) and OUT/wall_default_threads.csv (wall and CPU time at the default thread count, every core).
# The maps of 10^3 landmarks and more are the map benchmarks' (bench/run_map_benchmarks.sh).
# Usage: experiments/scripts/map_default_timing.sh OUT [ARBOR_BINARY]   (from the repository root; ~10 min;
# REPS=N for another number of repetitions)
set -euo pipefail
out=$(realpath -m "${1:?usage: $0 OUT [ARBOR_BINARY]}")
arbor=$(realpath "${2:-build/bin/arbor}")
reps=${REPS:-5}
mkdir -p "$out"
[ -f "$out/default.scn" ] || "$arbor" simulate --out "$out/default.scn" > /dev/null
[ -f "$out/quick.scn" ] || "$arbor" simulate --world clustered --landmarks 200 --steps 300 --clutter 2 --seed 1 \
  --out "$out/quick.scn" > /dev/null
[ -f "$out/heldout.scn" ] || "$arbor" simulate --world clustered --landmarks 300 --steps 600 --clutter 2 \
  --seed 10000 --out "$out/heldout.scn" > /dev/null
[ -f "$out/vp.scn" ] || "$arbor" convert --from victoria-park --max-gps-speed 8 --out "$out/vp.scn" > /dev/null

# one SCENARIO MAP REP [arbor run options...]: prints one CSV row
one() {
  local scn=$1 map=$2 rep=$3; shift 3
  /usr/bin/time -f "%U %S %e" -o "$out/time.txt" "$arbor" run --scenario "$out/$scn.scn" --assoc jcbb --map "$map" \
    --particles 100 --seed 1 --quiet --out "$out/run" "$@" > /dev/null
  read -r user sys wall < "$out/time.txt"
  /usr/bin/python3 -c "import json, sys; r = json.load(open(sys.argv[1]))
print('$scn,$map,$rep,%.3f,$wall,%.4f,%d,%d' % ($user + $sys, 1e3 * r['step_time_median_s'],
      r['map_bytes_per_particle'], r['landmarks']))" "$out/run/result.json"
}
header=scenario,map,rep,cpu_s,wall_s,step_median_ms,map_bytes_per_particle,landmarks
echo "$header" > "$out/cpu_1thread.csv"
for rep in $(seq "$reps"); do
  for scn in default quick heldout vp; do
    for map in naive tree trie; do one "$scn" "$map" "$rep" --threads 1 >> "$out/cpu_1thread.csv"; done
  done
done
echo "$header" > "$out/wall_default_threads.csv"
for rep in $(seq "$reps"); do
  for scn in default heldout quick; do
    for map in naive trie tree; do one "$scn" "$map" "$rep" >> "$out/wall_default_threads.csv"; done
  done
done
/usr/bin/python3 - "$out" <<'PY'
import sys
import pandas as pd
for name in ("cpu_1thread", "wall_default_threads"):
    d = pd.read_csv(f"{sys.argv[1]}/{name}.csv")
    print(name, "(medians over the repetitions)")
    print(d.groupby(["scenario", "map"])[["cpu_s", "wall_s", "step_median_ms", "map_bytes_per_particle"]]
          .median().to_string())
PY
