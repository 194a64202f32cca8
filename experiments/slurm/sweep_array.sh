#!/bin/bash
# Spreads one sweep over a Slurm job array: task I of N runs `arbor sweep --shard I/N` into its own
# directory; a final job (submitted with a dependency, see below) merges the shards.
#
#   sbatch --array=0-15 experiments/slurm/sweep_array.sh experiments/sweeps/accuracy.toml results/accuracy
#   # after all tasks finished (or: sbatch --dependency=afterok:<array job id> ... merge):
#   build/bin/arbor merge results/accuracy/shard-* --out results/accuracy/merged
#
# A task that is preempted or times out can be resubmitted unchanged (sbatch --array=7 ...): the sweep
# resumes from its results.jsonl and skips every run already recorded. Shard directories must live on a
# filesystem every node can reach; each shard appends only to its own files, so no cross-node locking is needed.
#SBATCH --job-name=arbor-sweep
#SBATCH --cpus-per-task=4
#SBATCH --mem=8G
#SBATCH --time=04:00:00
#SBATCH --output=arbor-sweep-%A_%a.out

set -euo pipefail
SPEC=${1:?usage: sbatch --array=0-(N-1) sweep_array.sh SPEC OUT_DIR}
OUT=${2:?usage: sbatch --array=0-(N-1) sweep_array.sh SPEC OUT_DIR}
ARBOR=${ARBOR:-build/bin/arbor}
TASK=${SLURM_ARRAY_TASK_ID:?not running inside a Slurm job array}
# SLURM_ARRAY_TASK_COUNT is the number of tasks; arrays given as 0-(N-1) number them like --shard does.
COUNT=${SLURM_ARRAY_TASK_COUNT:?not running inside a Slurm job array}

mkdir -p "$OUT"
# Each run uses --threads from the spec; give the node's CPUs to parallel runs.
exec "$ARBOR" sweep "$SPEC" --out "$OUT/shard-$TASK" --shard "$TASK/$COUNT" --jobs "${SLURM_CPUS_PER_TASK:-1}"
