#!/bin/sh
# Regenerate test_data/golden/core/*.json from pytransform3d 3.17.0.
# Usage: test_data/reference/generate_core.sh [OUTPUT_DIR]
# VENV (default /tmp/venv-oracle) is created / updated as needed; needs PyPI.
set -eu
HERE=$(cd "$(dirname "$0")" && pwd)
VENV=${VENV:-/tmp/venv-oracle}
[ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"
"$VENV/bin/pip" install -q -r "$HERE/requirements.txt"
"$VENV/bin/python" "$HERE/generate_core.py" "$@"
