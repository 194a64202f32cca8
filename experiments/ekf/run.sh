#!/usr/bin/env bash
# EKF-SLAM beside FastSLAM 2.0 and the smoother (issue 43): experiments/ekf/run.sh OUT [ARBOR_BINARY]
# Converts the real datasets into out/scenarios/ (UTIAS robots 3-5 from $UTIAS, default the workplace's
# ../shared/datasets copy), runs every spec of this folder into OUT/<spec>, and writes heldout.md (failure
# rate, median and p90 aligned ATE, NEES, F1 per configuration: analysis/studies/heldout.py) and
# consistency.md (NEES over time, the 30-run average against its band) in each. About 20 minutes on 2 cores;
# re-running resumes.
set -euo pipefail
out=$(realpath -m "${1:?usage: $0 OUT [ARBOR_BINARY]}")
arbor=$(realpath "${2:-build/bin/arbor}")
cd "$(dirname "$0")/../.."
utias=${UTIAS:-../shared/datasets/utias_mrclam/MRCLAM_Dataset6}
mkdir -p out/scenarios "$out"
for r in 3 4 5; do
  scn=out/scenarios/utias_d6_robot$r.scn
  [ -f "$scn" ] || "$arbor" convert --from utias-mrclam --input "$utias" --robot "$r" --out "$scn" > /dev/null
done
[ -f out/scenarios/victoria_park.scn ] ||
  "$arbor" convert --from victoria-park --max-gps-speed 8 --out out/scenarios/victoria_park.scn > /dev/null
[ -f out/scenarios/carpark.scn ] || "$arbor" convert --from acfr-car-park --out out/scenarios/carpark.scn > /dev/null
python=/usr/bin/python3  # Debian's, with numpy and pandas (the first python3 on PATH may lack them)
for spec in experiments/ekf/*.toml; do
  name=$(basename "$spec" .toml)
  "$arbor" sweep "$spec" --out "$out/$name" --jobs 2
  $python analysis/studies/heldout.py "$out/$name" --out "$out/$name"
  PYTHONPATH=analysis $python -m arbor_analysis.consistency "$out/$name" > "$out/$name/consistency.md" || true
done
echo "arbor: EKF study done: $out/*/heldout.md"
