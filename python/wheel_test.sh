#!/usr/bin/env bash
# The package as a user installs it (CTest's python_wheel): builds the wheel from the source
# tree with the CMake build already made (EMNET_CMAKE_BUILD_DIR: setup.py only copies its
# targets), installs it into a fresh venv that sees Debian's numpy, pandas and Dask
# (--system-site-packages), and from another directory imports it without PYTHONPATH, checks its
# version against the command line's, runs a study, and runs the binding tests with the wheel's
# own module and `emnet` program.
# Usage: python/wheel_test.sh SOURCE_DIR BUILD_DIR PYTHON
set -euo pipefail
root=$1 build=$2 python=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

echo "==> pip wheel"
EMNET_CMAKE_BUILD_DIR=$build "$python" -m pip wheel --quiet --no-build-isolation --no-deps \
  --no-index -w "$scratch/dist" "$root"
echo "==> venv, pip install $(basename "$scratch"/dist/emnet-*.whl)"
"$python" -m venv --system-site-packages "$scratch/venv"
"$scratch/venv/bin/pip" install --quiet --no-deps --no-index "$scratch"/dist/emnet-*.whl

cd "$scratch"
unset PYTHONPATH
expected=$("$build/emnet" --version)
echo "==> import emnet from $scratch (expecting $expected)"
EMNET_EXPECTED_VERSION=$expected EMNET_SCENE=$root/netlists/fishfin.toml \
  "$scratch/venv/bin/python" - <<'PYTHON'
import os
import sys

import emnet

venv = os.path.join(os.getcwd(), "venv")
assert emnet.__file__.startswith(venv), f"emnet imported from {emnet.__file__}, not the venv"
assert f"emnet {emnet.__version__}" == os.environ["EMNET_EXPECTED_VERSION"], emnet.__version__
frame = emnet.study(os.environ["EMNET_SCENE"], vary=["beam.bending_stiffness=normal(100%,5%)"],
                    samples=20, seed=1, analyses=["modes"])
assert len(frame) == 20 and (frame["status"] == "ok").all(), frame
assert 5.0 < frame["f1_hz"].median() < 8.0, frame["f1_hz"]
print(f"emnet {emnet.__version__} from {emnet.__file__}: a 20-variant study, median f1 "
      f"{frame['f1_hz'].median():.4f} Hz")
PYTHON
"$scratch/venv/bin/emnet" --version

echo "==> the binding tests against the wheel's module and program"
EMNET_PROGRAM=$scratch/venv/bin/emnet EMNET_ROOT=$root "$scratch/venv/bin/python" -m pytest -q \
  -p no:cacheprovider "$root/python/tests/test_bindings.py" "$root/python/tests/test_same_keys.py"
