#!/usr/bin/env bash
# The Python API's overhead against the command line (issue 16) on the default simulated world, run as the
# committed study ran it (known association and the naive map, the defaults then, named since): `arbor run`
# as a process, arbor.run inside Python, and a whole python3 process, median of 5 each; then checks that
# both wrote the same trajectory and map bytes. Usage: experiments/scripts/python_overhead.sh [BUILD_DIR]
set -euo pipefail
build=$(realpath "${1:-build}")
work=$(mktemp -d)
cd "$work"
median() { sort -n | sed -n 3p; }
"$build/bin/arbor" simulate --out s.scn > /dev/null
for i in 1 2 3 4 5; do
  /usr/bin/time -f "%e" -o "cli_$i.time" "$build/bin/arbor" run --scenario s.scn --assoc known --map naive --out "cli_$i" --quiet > /dev/null
done
echo "arbor run, whole process: $(cat cli_*.time | median) s"
echo "arbor run, its wall_time_s: $(for i in 1 2 3 4 5; do /usr/bin/python3 -c "import json; print(json.load(open('cli_$i/result.json'))['wall_time_s'])"; done | median) s"
PYTHONPATH="$build/python" /usr/bin/python3 - <<'PY'
import statistics, time
import arbor
t = []
for i in range(5):
    start = time.perf_counter()
    arbor.run(arbor.Scenario.load("s.scn"), assoc="known", map="naive", out=f"py_{i}")
    t.append(time.perf_counter() - start)
print(f"arbor.run(Scenario.load(...), assoc=..., map=..., out=...) inside Python: {statistics.median(t):.3f} s")
PY
for i in 1 2 3 4 5; do
  /usr/bin/time -f "%e" -o "py_$i.time" env PYTHONPATH="$build/python" /usr/bin/python3 -c \
    "import arbor; arbor.run(arbor.Scenario.load('s.scn'), assoc='known', map='naive', out='pyp_$i')"
done
echo "python3 process (interpreter, import, load, run, files): $(cat py_*.time | median) s"
cmp cli_1/trajectory.tum py_0/trajectory.tum && cmp cli_1/map.csv py_0/map.csv && echo "trajectory.tum and map.csv identical"
rm -rf "$work"
