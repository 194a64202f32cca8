#!/usr/bin/env bash
# `pip install .` into a fresh virtual environment, offline, as a user would (setup.py, packaging the build
# given here), then `import arbor` from elsewhere, with no PYTHONPATH: the installed package, its stub and its
# `arbor` program must be complete on their own. Exit 77 (skipped, with the reason) where the interpreter lacks
# what an offline install needs. Usage: pip_install_test.sh SOURCE_DIR BUILD_DIR [PYTHON]
set -euo pipefail
source_dir=$1
build_dir=$2
python=${3:-/usr/bin/python3}

skip() {
  echo "skipped: $*"
  exit 77
}
"$python" -c "import setuptools, wheel" 2>/dev/null ||
  skip "$python has no setuptools or wheel (Debian: apt install python3-setuptools python3-wheel)"
"$python" -c "import ensurepip, venv" 2>/dev/null || skip "$python cannot make a venv (Debian: apt install python3-venv)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# --system-site-packages: numpy comes from Debian, as no package index is reachable.
"$python" -m venv --system-site-packages "$work/venv"
ARBOR_BUILD_DIR=$build_dir "$work/venv/bin/python" -m pip install --quiet --no-build-isolation --no-index \
  --disable-pip-version-check "$source_dir"

cd "$work"
env -u PYTHONPATH -u ARBOR_EXECUTABLE "$work/venv/bin/python" - "$work/venv" <<'PY'
import importlib.metadata
import os
import sys

import arbor

venv = sys.argv[1]
here = os.path.dirname(arbor.__file__)
assert here.startswith(venv), f"imported {arbor.__file__}, not the installed package"
for name in ["__init__.pyi", "py.typed", "_options.py"]:
    assert os.path.exists(os.path.join(here, name)), f"{name} was not installed"
assert arbor.executable().startswith(venv), arbor.executable()
assert arbor.__version__.split("+")[0] == importlib.metadata.version("arbor"), arbor.__version__
scenario = arbor.simulate(world="uniform", landmarks=20, steps=15, seed=1)
result = arbor.run(scenario, assoc="nn", particles=5, seed=1)
assert result.steps["n_eff"].size == len(scenario)
assert "usage" in arbor.cli("run", "--help").stdout.lower()  # the installed program runs
print(f"installed arbor {arbor.__version__}: ATE {result.ate_rmse_m:.3f} m")
PY
