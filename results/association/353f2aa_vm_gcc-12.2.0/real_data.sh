#!/bin/bash
# Real data: JCBB, the cluttered-sensor combination, and the combination with the start rule (the default
# --provisional-steer-min 3; 0 gives the combination as it was). FastSLAM 2.0, 100 particles, seeds 1-5
# (Victoria Park 1-20). Writes real_data.csv to stdout. Usage: real_data.sh OUT UTIAS_DIR (MRCLAM_Dataset6 with
# all five robots; data/ ships robot 1). From the repository root; ARBOR=binary.
set -euo pipefail
out=$1 utias=$2 arbor=${ARBOR:-build/bin/arbor}
mkdir -p "$out"
for r in 1 2 3 4 5; do
  [ -f "$out/utias$r.scn" ] || "$arbor" convert --from utias-mrclam --robot $r --input "$utias" --out "$out/utias$r.scn" > /dev/null
done
[ -f "$out/cp.scn" ] || "$arbor" convert --from acfr-car-park --out "$out/cp.scn" > /dev/null
[ -f "$out/vp.scn" ] || "$arbor" convert --from victoria-park --max-gps-speed 8 --out "$out/vp.scn" > /dev/null
combination=(--pose-from-confirmed --close-loops --chi2 0.999)
echo "scenario,variant,seed,ate_rmse_m,ate_aligned_rmse_m,landmarks,loop_closures"
for scn in utias1 utias2 utias3 utias4 utias5 cp vp; do
  seeds=$(seq 1 5); [ $scn = vp ] && seeds=$(seq 1 20)
  for variant in jcbb combination start_rule; do
    for s in $seeds; do
      case $variant in
        jcbb) opts=() ;;
        combination) opts=("${combination[@]}" --provisional-steer-min 0) ;;
        start_rule) opts=("${combination[@]}") ;;
      esac
      d=$out/runs/$scn-$variant-s$s
      [ -f "$d/result.json" ] || "$arbor" run --scenario "$out/$scn.scn" --particles 100 --seed $s --threads 2 --quiet \
        --assoc jcbb "${opts[@]}" --out "$d" > /dev/null
      /usr/bin/python3 -c "import json, sys; r = json.load(open(sys.argv[1]))
print('$scn,$variant,$s', r['ate_rmse_m'], r['ate_aligned_rmse_m'], r['landmarks'], r['loop_closures'], sep=',')" "$d/result.json"
    done
  done
done
