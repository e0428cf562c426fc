#!/usr/bin/env bash
# Renders the interactive HTML views in headless Chromium and checks the screenshots show
# the robot and the surface (not a blank page, not a script error):
#  1. `ppoe demo` (seed robot with its URDF visuals): enough pixels of the seed's blue and
#     orange links and of the surface's teal;
#  2. `ppoe render --format html` on the seed's kinematic-only URDF (no visuals): enough
#     pixels of the grey stick figure and of the surface.
# The demo runs its full 200 frames, so the script also checks the GIF's size budget
# (at most 2.5 MB) in a release build.
# Installs the Debian package `chromium` with apt-get when it is missing.
# Usage: scripts/html-check.sh [--keep DIR]   (DIR keeps the pages and screenshots)
set -euo pipefail
cd "$(dirname "$0")/.."

keep=""
if [[ "${1:-}" == "--keep" ]]; then keep="${2:?--keep needs a directory}"; fi

if ! command -v chromium >/dev/null 2>&1; then
  echo "html-check: installing chromium (apt-get)" >&2
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cargo build --release -q -p ppoe-cli
ppoe="$PWD/target/release/ppoe"

shoot() { # shoot PAGE.html OUT.png [FRAGMENT]
  local profile
  profile="$(mktemp -d "$work/profile.XXXX")"
  timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --screenshot="$2" --window-size=1000,800 \
    "file://$1#${3:-paused}" >"$work/chromium.log" 2>&1 || { cat "$work/chromium.log" >&2; return 1; }
  [[ -s "$2" ]] || { echo "html-check: no screenshot $2" >&2; return 1; }
}

"$ppoe" demo --out "$work/demo" >/dev/null
gif_bytes="$(stat -c %s "$work/demo/ppoe-seed.gif")"
echo "html-check: ppoe-seed.gif (200 frames) is $gif_bytes bytes"
if (( gif_bytes > 2500000 )); then
  echo "html-check: ppoe-seed.gif is over 2.5 MB" >&2
  exit 1
fi
shoot "$work/demo/ppoe-seed.html" "$work/demo.png"
# Another frame seen from another side: the camera and the frame change the picture.
shoot "$work/demo/ppoe-seed.html" "$work/demo-turned.png" "paused&frame=100&az=140&el=35"

printf '{"cases":[{"thetas":[-0.5,-0.5,-0.5,0,-0.5,0],"covs":[%s]}]}\n' "$(python3 - <<'PY'
import json
z = [[0.0] * 6 for _ in range(6)]
def c(k):
    m = [r[:] for r in z]
    if k is not None:
        m[k][k] = 0.05
    return m
print(",".join(json.dumps(c(k)) for k in [2, 1, 1, None, 1, None]))
PY
)" >"$work/cases.json"
"$ppoe" render --urdf test_data/urdf/seed.urdf --base linkmount --tip tcp \
  --input "$work/cases.json" --format html --out "$work/render" >/dev/null
shoot "$work/render/ppoe-render.html" "$work/render.png"

python3 scripts/html_check.py "$work/demo.png" visuals "$work/demo-turned.png" visuals \
  "$work/render.png" skeleton
python3 scripts/html_check.py --differ "$work/demo.png" "$work/demo-turned.png"

if [[ -n "$keep" ]]; then
  mkdir -p "$keep"
  cp "$work/demo/ppoe-seed.html" "$work/demo.png" "$work/demo-turned.png" \
    "$work/render/ppoe-render.html" "$work/render.png" "$keep/"
fi
echo "html-check: ok"
