#!/bin/sh
# Runs the map and step benchmarks and writes results/maps/<commit>_<host>_<compiler>/ (benchmark JSON, a
# README line, the complexity figure). Usage: bench/run_map_benchmarks.sh [build-dir]   (REPS=3 by default;
# ARBOR_BENCH_MAX_N=10000000 adds N = 10^7; BACKENDS='tree|trie' runs only those back ends). Each
# program's peak resident memory goes to peak_rss.txt where /usr/bin/time exists.
set -eu
build=${1:-build}
reps=${REPS:-3}
cd "$(dirname "$0")/.."
ninja -C "$build" -j2 map_benchmark step_benchmark
commit=$(git rev-parse --short=10 HEAD)
if [ -n "$(git status --porcelain --untracked-files=no)" ]; then commit="${commit}+"; fi
host=$(hostname -s)
compiler="gcc-$(c++ -dumpfullversion)"
out="results/maps/${commit}_${host}_${compiler}"
mkdir -p "$out"
filter="backend:(${BACKENDS:-naive|tree|trie})/"
timed() {  # name, command...: runs the command, appending its peak RSS to peak_rss.txt when it can
  name=$1; shift
  if [ -x /usr/bin/time ]; then /usr/bin/time -a -o "$out/peak_rss.txt" -f "$name: %M KB peak RSS, %e s wall" "$@"; else "$@"; fi
}
context="--benchmark_context=commit=${commit} --benchmark_context=host=${host} --benchmark_context=compiler=${compiler}"
# shellcheck disable=SC2086
timed map_benchmark "$build/bench/map_benchmark" --benchmark_filter="$filter" --benchmark_out="$out/map_benchmark.json" --benchmark_out_format=json \
  --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true $context
# One repetition of 100 timed steps per point (the median over steps is the figure); each point builds a
# prior map of N landmarks, which takes longer than the steps themselves at 10^6.
# shellcheck disable=SC2086
timed step_benchmark "$build/bench/step_benchmark" --benchmark_filter="$filter" --benchmark_out="$out/step_benchmark.json" --benchmark_out_format=json $context
echo "Map back ends: set/copy/query/particle memory (map_benchmark.json, median of ${reps}) and one FastSLAM step, M=100, 1 thread, process CPU time, mean (with resampling) and median of 100 steps after 20 warm-up steps (step_benchmark.json), N=1e2..${ARBOR_BENCH_MAX_N:-1000000} at 0.01 landmarks/m^2, back ends ${BACKENDS:-naive|tree|trie}; commit ${commit}, host ${host}, ${compiler}, $(nproc) cores; reproduce: REPS=${reps} ARBOR_BENCH_MAX_N=${ARBOR_BENCH_MAX_N:-1000000} BACKENDS='${BACKENDS:-naive|tree|trie}' bench/run_map_benchmarks.sh" > "$out/README"
/usr/bin/python3 analysis/studies/plot_map_complexity.py "$out" | tee "$out/slopes.txt"
