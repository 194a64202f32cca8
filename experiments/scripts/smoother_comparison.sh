#!/bin/bash
# The smoother beside FastSLAM on the same data (issue 6, DESIGN.md §5): simulated worlds and UTIAS MRCLAM
# robot 1 with true association (the smoother as the accuracy reference), and Victoria Park, which has no
# true association, with the smoother given each FastSLAM run's own decisions ("how far is FastSLAM+JCBB
# from the optimum given its associations?"). Writes OUT/<dataset>/<run>/result.json; a run whose
# result.json exists is skipped, so an interrupted comparison resumes. Then:
#   /usr/bin/python3 analysis/studies/smoother_vs_fastslam.py OUT
# Usage: experiments/scripts/smoother_comparison.sh OUT [ARBOR_BINARY]
# Scale with WORLDS (simulated world seeds), SEEDS (FastSLAM seeds on the real data), PARTICLES.
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"  # $out, $arbor, the repository root as working directory, once
worlds=${WORLDS:-"1 2 3"}
seeds=${SEEDS:-"1 2 3"}
particles=${PARTICLES:-"10 100 1000"}
scenarios=out/scenarios     # shared with scripts/main.sh, which converts Victoria Park the same way
mkdir -p "$out" "$scenarios"

# FastSLAM runs of FILTER x ASSOC x PARTICLES x SEEDS on SCENARIO into OUT/DATASET.
fastslam() {
  local dataset=$1 scenario=$2 filter=$3 assoc=$4 seed_list=$5
  for m in $particles; do
    for seed in $seed_list; do
      once "$out/$dataset/${filter}_${assoc}_m${m}_s${seed}" run --scenario "$scenario" --filter "$filter" --map naive \
        --assoc "$assoc" --particles "$m" --seed "$seed" --threads 2
    done
  done
}

# The smoother on the decisions of every FastSLAM run of ASSOC with 100 particles, without and with a
# robust loss (a wrong decision is an outlier to least squares).
smoother_on_decisions() {
  local dataset=$1 scenario=$2 assoc=$3 seed_list=$4
  for seed in $seed_list; do
    local source=$out/$dataset/fastslam2_${assoc}_m100_s${seed}
    [ -d "$source" ] || continue
    once "$out/$dataset/smoother_${assoc}_m100_s${seed}" smooth --scenario "$scenario" --associations "$source"
    once "$out/$dataset/smoother_${assoc}_m100_s${seed}_cauchy" smooth --scenario "$scenario" \
      --associations "$source" --loss cauchy
  done
}

for w in $worlds; do
  dataset=simulated_w$w
  scenario=$scenarios/$dataset.scn
  [ -f "$scenario" ] || "$arbor" simulate --seed "$w" --clutter 1 --out "$scenario" > /dev/null
  once "$out/$dataset/smoother_known" smooth --scenario "$scenario"
  for filter in fastslam1 fastslam2; do fastslam $dataset "$scenario" $filter known 1; done
  particles=100 fastslam $dataset "$scenario" fastslam2 jcbb 1
  smoother_on_decisions $dataset "$scenario" jcbb 1
  echo "done $dataset"
done

scenario=$scenarios/utias1.scn
[ -f "$scenario" ] || "$arbor" convert --from utias-mrclam --robot 1 --out "$scenario" > /dev/null
once "$out/utias1/smoother_known" smooth --scenario "$scenario"
for filter in fastslam1 fastslam2; do fastslam utias1 "$scenario" $filter known "$seeds"; done
echo "done utias1"

scenario=$scenarios/victoria_park.scn
[ -f "$scenario" ] || "$arbor" convert --from victoria-park --max-gps-speed 8 --out "$scenario" > /dev/null
for assoc in nn jcbb; do
  fastslam victoria_park "$scenario" fastslam2 $assoc "$seeds"
  smoother_on_decisions victoria_park "$scenario" $assoc "$seeds"
done
particles=100 fastslam victoria_park "$scenario" fastslam1 jcbb "$seeds"
echo "done victoria_park"
