#!/bin/bash
# Prediction between scans (issue 11): per-scan sampling (each particle carries its predicted mean and
# covariance through every control and draws once per scan) against per-control sampling (a draw at every
# control; the FastSLAM 2.0 proposal sees only the last control's covariance), on simulated worlds whose
# odometer is read K = 1, 10, 50 times per scan, with known association. Then UTIAS MRCLAM Dataset 6, robots
# 1-5, known association, FastSLAM 2.0 and 1.0, beside the Ceres smoother (Cauchy loss); and Victoria Park
# with JCBB (GPS RMSE and wall time, 100 and 1000 particles). A run whose
# result.json exists is skipped, so an interrupted study resumes. Then:
#   /usr/bin/python3 analysis/studies/motion_sampling.py OUT
# Usage: experiments/scripts/motion_sampling_study.sh OUT [ARBOR_BINARY]
# Scale with SEEDS, KS, PARTICLES; UTIAS=DIR (default ../shared/datasets/utias_mrclam/MRCLAM_Dataset6; the
# UTIAS part is skipped when DIR lacks robot 2).
set -euo pipefail
source "$(dirname "$0")/study_setup.sh"  # $out, $arbor, the repository root as working directory, once
seeds=${SEEDS:-"1 2 3 4 5"}
ks=${KS:-"1 10 50"}
particles=${PARTICLES:-"10 100"}
utias=${UTIAS:-../shared/datasets/utias_mrclam/MRCLAM_Dataset6}
mkdir -p "$out/scenarios"

for k in $ks; do
  for s in $seeds; do
    scn=$out/scenarios/uniform-k$k-s$s.scn
    [ -f "$scn" ] || "$arbor" simulate --world uniform --landmarks 200 --steps 150 --controls-per-scan "$k" --seed "$s" --out "$scn" > /dev/null
    for m in $particles; do
      for sampling in per-scan per-control; do
        once "$out/sim/k$k-p$m-s$s-$sampling" run --scenario "$scn" --filter fastslam2 --map naive --assoc known \
          --particles "$m" --seed "$s" --threads 2 --motion-sampling "$sampling"
      done
    done
  done
done

if [ -f "$utias/Robot2_Odometry.dat" ]; then
  for r in 1 2 3 4 5; do
    scn=$out/scenarios/utias-r$r.scn
    [ -f "$scn" ] || "$arbor" convert --from utias-mrclam --input "$utias" --robot "$r" --out "$scn" > /dev/null
    once "$out/utias/r$r-smoother" smooth --scenario "$scn" --loss cauchy --max-iterations 500
    for s in 1 2 3; do
      for filter in fastslam2 fastslam1; do
        for sampling in per-scan per-control; do
          once "$out/utias/r$r-$filter-s$s-$sampling" run --scenario "$scn" --filter "$filter" --map naive --assoc known \
            --particles 100 --seed "$s" --threads 2 --motion-sampling "$sampling"
        done
      done
    done
  done
fi
vp=$out/scenarios/victoria_park.scn
[ -f "$vp" ] || "$arbor" convert --from victoria-park --max-gps-speed 8 --out "$vp" > /dev/null
for s in 1 2 3 4 5; do
  for sampling in per-scan per-control; do
    for m in 100 1000; do
      [ "$m" = 1000 ] && [ "$s" -gt 2 ] && continue
      once "$out/victoria_park/jcbb-p$m-s$s-$sampling" run --scenario "$vp" --filter fastslam2 --map naive --assoc jcbb \
        --particles "$m" --seed "$s" --threads 2 --motion-sampling "$sampling"
    done
  done
done
echo "motion sampling study: $out"
