#!/usr/bin/env bash
# The README's first command: installs what is missing, builds (Release), and runs the default study: every
# map back end and association strategy on a cluttered simulated world and on Victoria Park, then a report
# with figures for each. A few minutes on 2 cores. Re-running resumes (finished runs are skipped).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_dependencies.sh
scripts/build.sh build -DCMAKE_BUILD_TYPE=Release
out=out/main
mkdir -p out/scenarios "$out"
[ -f out/scenarios/victoria_park.scn ] ||
  build/bin/arbor convert --from victoria-park --max-gps-speed 8 --out out/scenarios/victoria_park.scn
for study in default default_locality default_victoria_park; do
  build/bin/arbor sweep "experiments/sweeps/$study.toml" --out "$out/$study" --jobs 2
  analysis/report "$out/$study"
done
echo
echo "arbor: the default study is done. Reports:"
for study in default default_locality default_victoria_park; do
  echo "  $out/$study/report/report.md  (and report.html, one self-contained page)"
done
