#!/usr/bin/env bash
# The held-out protocol (issue 41): experiments/heldout/run.sh calibration|evaluation OUT [ARBOR_BINARY]
# (or calibration-move|evaluation-move: the resample-move study, apart because it takes about 25 minutes;
# calibration-assoc|evaluation-assoc: every real association strategy, where `arbor run`'s default is chosen;
# evaluation-roughen: roughened resampling, left off on calibration data, on the evaluation set;
# calibration-resample: the resampling threshold, with EKF-SLAM beside it;
# calibration-kidnap|evaluation-kidnap: --relocalize on kidnapped and plain worlds, about 2 minutes;
# calibration-gates|evaluation-gates: JCBB's compatibility and new-landmark gates;
# calibration-loops|evaluation-loops: --close-loops and --pose-from-confirmed with JCBB;
# calibration-lineage|evaluation-lineage: how far back the particle set can revise its path, at 100 and 1000
# particles, with analysis/studies/lineage.py;
# calibration-tempering|evaluation-tempering: tempered weights, --weight-exponent;
# calibration-estimate|evaluation-estimate: the reported path, the mean of the particles' paths or the best one;
# evaluation-1000: known association at 1000 particles with the defaults, about 15 minutes;
# calibration-oracle|evaluation-oracle: known association reaching beyond the query box;
# calibration-existence|evaluation-existence: the level below which negative evidence drops a landmark, with
# JCBB, on the robots, the worlds and outdoor data (the Car Park calibrates, Victoria Park evaluates);
# calibration-relocalize: --relocalize as loop closure after a gap, with JCBB;
# calibration-tempered1000|evaluation-tempered1000: JCBB at 1000 particles, weight exponent 1 or 0.1)
# Converts (again, so the loader's defaults are this build's) the MRCLAM Dataset 6 robots of the chosen set into out/scenarios/ (from $UTIAS, default the
# workplace's ../shared/datasets copy, which holds all five robots), runs that set's sweeps into OUT, and writes
# OUT/heldout.md with analysis/studies/heldout.py. Calibration: robots 1-2 and simulated seeds 1-4, where options are
# chosen. Evaluation: robots 3-5 and simulated seeds 10000-10011, the figures docs/results.md reports; about
# 10 minutes on 2 cores. Re-running resumes (finished runs are skipped).
set -euo pipefail
set_name=${1:?usage: $0 SET OUT [ARBOR_BINARY]}
out=$(realpath -m "${2:?usage: $0 SET OUT [ARBOR_BINARY]}")
arbor=$(realpath "${3:-build/bin/arbor}")
cd "$(dirname "$0")/../.."
python=/usr/bin/python3  # Debian's, with numpy and pandas (the first python3 on PATH may lack them)
# Relocalisation, whose thresholds were chosen on seeds 1-40 (results/association/d43e3e0_vm_gcc-12.2.0):
# uniform, rooms and clustered worlds, each kidnapped and plain, with and without --relocalize.
if [[ $set_name == *-kidnap ]]; then
  case $set_name in
    calibration-kidnap) seeds=$(seq 1 20) ;;
    evaluation-kidnap) seeds=$(seq 10000 10019) ;;
    *) echo "arbor: unknown set '$set_name' (calibration-kidnap, evaluation-kidnap)" >&2; exit 2 ;;
  esac
  SEEDS="$seeds" WORLDS="uniform rooms clustered" experiments/scripts/kidnap_study.sh "$out/$set_name" "$arbor"
  $python analysis/studies/kidnap.py "$out/$set_name"
  echo "arbor: held-out $set_name set done: $out/$set_name/kidnap.md"
  exit 0
fi
# A set is its sweep specs, experiments/heldout/SET_*.toml; calibration sets run robots 1-2, evaluation sets 3-5.
shopt -s nullglob
specs=(experiments/heldout/"${set_name}"_*.toml)
case $set_name in
  calibration*) robots="1 2" ;;
  evaluation*) robots="3 4 5" ;;
  *) specs=() ;;
esac
if [ ${#specs[@]} -eq 0 ]; then
  known=$(for f in experiments/heldout/*_*.toml; do f=${f##*/}; echo "${f%%_*}"; done | sort -u | tr '\n' ' ')
  echo "arbor: unknown set '$set_name' (the sets: ${known}calibration-kidnap evaluation-kidnap)" >&2
  exit 2
fi
utias=${UTIAS:-../shared/datasets/utias_mrclam/MRCLAM_Dataset6}
mkdir -p out/scenarios "$out"
for r in $robots; do
  scn=out/scenarios/utias_d6_robot$r.scn
  "$arbor" convert --from utias-mrclam --input "$utias" --robot "$r" --out "$scn" > /dev/null
done
# Outdoor data for the sets that have an _outdoor sweep: the Car Park calibrates, Victoria Park evaluates.
if [ -f "experiments/heldout/${set_name}_outdoor.toml" ]; then
  "$arbor" convert --from acfr-car-park --out out/scenarios/carpark.scn > /dev/null
  "$arbor" convert --from victoria-park --max-gps-speed 8 --out out/scenarios/victoria_park.scn > /dev/null
fi
for spec in "${specs[@]}"; do
  name=$(basename "$spec" .toml)
  "$arbor" sweep "$spec" --out "$out/$name" --jobs 2
  $python analysis/studies/heldout.py "$out/$name" --out "$out/$name"
  [[ $set_name == *-lineage ]] && $python analysis/studies/lineage.py "$out/$name" > /dev/null
  [[ $set_name == *-estimate || $set_name == *-oracle ]] && $python analysis/studies/path_estimates.py "$out/$name" > /dev/null
done
# A study set (calibration-move, evaluation-gates, ...) ends here; the plain sets go on.
[[ $set_name == *-* ]] && { echo "arbor: held-out $set_name set done: $out/*/heldout.md"; exit 0; }
# The smoother without its robust loss on the same robots: the reference before issue 41 made Cauchy the
# default on real data.
for r in $robots; do
  dir=$out/smoother_no_loss/robot$r
  [ -f "$dir/result.json" ] || "$arbor" smooth --scenario out/scenarios/utias_d6_robot$r.scn --loss none --quiet --out "$dir"
done
echo "arbor: held-out $set_name set done: $out/*/heldout.md"
