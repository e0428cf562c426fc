#!/usr/bin/env bash
# The Python package ppoe-py/ end to end, as a newcomer installs it:
#  1. a fresh venv (target/python-check/venv) with maturin, pytest and pytransform3d 3.17.0
#     (the oracle, with numpy, scipy, lxml, matplotlib pinned as in
#     test_data/reference/requirements-ppoe.txt) from PyPI;
#  2. pytransform3d 3.17.0's sdist from PyPI (cached in target/python-check/sdist), from
#     which its own uncertainty test module is extracted;
#  3. `maturin build --release` of the abi3 wheel, `pip install` of that wheel;
#  4. pytest ppoe-py/tests (pytransform3d's own tests run against ppoe.uncertainty there,
#     through PPOE_PT3D_TEST_MODULE), then the seed example ppoe-py/examples/seed.py.
# Exits non-zero if any step fails, also if pytest collects no test (its exit 5).
# Usage: scripts/python-check.sh
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
WORK="$ROOT/target/python-check"
VENV="$WORK/venv"
PY=${PYTHON:-python3}

t0=$SECONDS
rm -rf "$VENV" "$WORK/wheels" "$WORK/pt3d-tests"
mkdir -p "$WORK/sdist" "$WORK/pt3d-tests"
"$PY" -m venv "$VENV"
"$VENV/bin/pip" install -q --disable-pip-version-check \
  -r test_data/reference/requirements-ppoe.txt maturin==1.16.0 pytest==9.2.0
echo "python-check: venv ready in $((SECONDS - t0)) s"

sdist="$WORK/sdist/pytransform3d-3.17.0.tar.gz"
if [ ! -s "$sdist" ]; then
  "$VENV/bin/pip" download -q --disable-pip-version-check --no-deps --no-binary :all: \
    pytransform3d==3.17.0 -d "$WORK/sdist"
fi
member=pytransform3d-3.17.0/pytransform3d/uncertainty/test/test_uncertainty.py
tar -xzf "$sdist" -C "$WORK/pt3d-tests" "$member"
export PPOE_PT3D_TEST_MODULE="$WORK/pt3d-tests/$member"

t1=$SECONDS
# Its own target dir under the repository's: ppoe-py is its own cargo workspace.
(cd ppoe-py && CARGO_TARGET_DIR="$ROOT/target/ppoe-py" "$VENV/bin/maturin" build --release \
  --quiet -i "$VENV/bin/python" --out "$WORK/wheels")
"$VENV/bin/pip" install -q --disable-pip-version-check "$WORK"/wheels/ppoe-*.whl
echo "python-check: wheel built and installed in $((SECONDS - t1)) s"

# From outside the source tree, so that `import ppoe` is the installed wheel.
cd "$WORK"
rc=0
"$VENV/bin/python" -m pytest -q -p no:cacheprovider "$ROOT/ppoe-py/tests" || rc=$?
if [ $rc -eq 5 ]; then
  echo "python-check: pytest collected no tests" >&2
  exit 1
elif [ $rc -ne 0 ]; then
  exit $rc
fi
"$VENV/bin/python" "$ROOT/ppoe-py/examples/seed.py" >/dev/null
echo "python-check: OK in $((SECONDS - t0)) s"
