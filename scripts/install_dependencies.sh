#!/usr/bin/env bash
# Installs the Debian 12 packages Arbor needs, only those missing (run as root). Safe to run repeatedly.
# --tests adds what only the tests use: munge and Slurm for the job-array test (about 13 MB installed), and
# headless Chromium to render the HTML report (about 100 MB to download).
set -euo pipefail
packages=(cmake ninja-build g++ clang libclang-rt-14-dev git libeigen3-dev libtbb-dev libceres-dev libfmt-dev libcli11-dev
          libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libtomlplusplus-dev
          python3 python3-dev python3-numpy python3-pandas python3-matplotlib pybind11-dev python3-pytest)
if [ "${1:-}" = --tests ]; then
  packages+=(munge slurmd slurmctld slurm-client chromium-headless-shell)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "arbor: installing missing packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
