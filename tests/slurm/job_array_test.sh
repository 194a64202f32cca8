#!/bin/bash
# The Slurm job-array example (experiments/slurm/sweep_array.sh) under a real single-node Slurm: a private
# cluster (experiments/slurm/local_cluster.sh) runs a 12-run sweep as a 3-task array, `arbor merge` joins the
# shards, and the merged rows must equal an unsharded sweep of the same spec, key for key and digit for digit
# in the recorded metrics. Exit 77 (ctest: skipped) with the reason where the daemons cannot run here.
# Usage: job_array_test.sh BUILD_DIR
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
build=$(realpath "${1:?usage: job_array_test.sh BUILD_DIR}")
work=$build/slurm_test
rm -rf "$work"
mkdir -p "$work"
cluster=$work/cluster

set +e
"$source_dir/experiments/slurm/local_cluster.sh" start "$cluster" 2> "$work/start.log"
status=$?
set -e
if [ $status -ne 0 ]; then
  echo "SKIPPED: no single-node Slurm here: $(tail -1 "$work/start.log")"
  tail -5 "$cluster"/log/*.log 2>/dev/null || true
  "$source_dir/experiments/slurm/local_cluster.sh" stop "$cluster"
  exit 77
fi
trap '"$source_dir/experiments/slurm/local_cluster.sh" stop "$cluster"' EXIT
export SLURM_CONF=$cluster/slurm.conf

# The sweep tests' 12 tiny runs: 3 array tasks of 4.
cp "$source_dir/tests/data/sweeps/tiny.toml" "$work/spec.toml"
# The script's own #SBATCH requests (4 CPUs, 8 GB) are for a cluster node; one CPU each fits this machine.
ARBOR=$build/bin/arbor timeout 300 sbatch --wait --array=0-2 --cpus-per-task=1 --mem=200M \
  --chdir="$source_dir" --output="$work/task-%a.out" \
  "$source_dir/experiments/slurm/sweep_array.sh" "$work/spec.toml" "$work/array"
"$build/bin/arbor" merge "$work"/array/shard-* --out "$work/merged"
"$build/bin/arbor" sweep "$work/spec.toml" --out "$work/unsharded" --jobs 1 > "$work/unsharded.log"

python3 - "$work/merged/results.jsonl" "$work/unsharded/results.jsonl" <<'PY'
import json, sys
fields = ["key", "status", "world", "world_landmarks", "world_steps", "clutter", "world_seed", "filter", "map",
          "assoc", "particles", "seed", "threads", "ate_rmse_m", "landmarks", "steps"]
def rows(path):
    with open(path) as f:
        return {r["key"]: tuple(r.get(c) for c in fields) for r in map(json.loads, f) if r}
merged, unsharded = rows(sys.argv[1]), rows(sys.argv[2])
assert len(unsharded) == 12, f"the unsharded sweep has {len(unsharded)} rows, not 12"
assert merged == unsharded, "merged shards differ from the unsharded sweep: " + str(
    sorted(set(merged.items()) ^ set(unsharded.items()))[:4])
print(f"the 3 array tasks' {len(merged)} merged rows equal the unsharded sweep's")
PY
