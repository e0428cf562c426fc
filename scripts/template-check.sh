#!/usr/bin/env bash
# scripts/template-check.sh -- build the firmware template (examples/firmware-template), run
# it in QEMU (mps2-an386, Cortex-M4F) and check what it prints against the host.
#
# A user builds the template with rustup (`rustup target add thumbv7em-none-eabihf`, the
# default linker rust-lld). So does this script when rustup can add the target here
# (scripts/setup-thumb.sh --rustup); where it cannot, it builds with the fallback toolchain
# of scripts/firmware.sh: Debian's rustc-web with `-Z build-std` (through the environment
# only; the template's own files are used unchanged) and rustup's rust-lld (or
# arm-none-eabi-ld) named as the linker.
#
# Checks:
#  1. the build uses the template's Cargo.lock unchanged (--locked);
#  2. the firmware exits QEMU with status 0 and prints "ppoe-firmware-template: ok";
#  3. its tool pose (4×4) and covariance (6×6), computed in f32 on the device, match
#     `ppoe eval` on the host in f64 for the same URDF, joint angles and noise:
#     max|a−b| / max(1, max|b|) <= 1e-5 (the project's f32 bound, README "Accuracy") for
#     each, and, since the covariance entries are ~1e-4, also max|a−b| <= 1e-4·max|b| for it.
#
# Usage: scripts/template-check.sh [--no-setup]
# Env: TEMPLATE_TARGET_DIR (default examples/firmware-template/target), TEMPLATE_TIMEOUT
#      (seconds for the QEMU run, default 60), THUMB_CARGO (default: the toolchain's cargo)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
TPL=$ROOT/examples/firmware-template
TARGET=thumbv7em-none-eabihf

SETUP=1
for a in "$@"; do
  case "$a" in
    --no-setup) SETUP=0 ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "template-check: unknown argument $a" >&2; exit 2 ;;
  esac
done
log() { echo "template-check: $*" >&2; }
die() { echo "template-check: ERROR: $*" >&2; exit 1; }

# --- Toolchain: rustup's if it has the target (the user's path), else Debian's ----------------
. "$ROOT/scripts/lib/thumb-env.sh"
thumb_toolchain $SETUP --rustup "$TARGET"
command -v qemu-system-arm >/dev/null || die "qemu-system-arm missing: run scripts/setup-thumb.sh"
TD=${TEMPLATE_TARGET_DIR:-$TPL/target}
thumb_build_env "$TD" "$TARGET"
log "$THUMB_KIND toolchain: rustc $("$THUMB_RUSTC" -V); linker $THUMB_LINKER"

# --- 1. Build ----------------------------------------------------------------------------------
(cd "$TPL" && env "${BUILD_ENV[@]}" "$CARGO" build --release --locked)
ELF=$TD/$TARGET/release/ppoe-firmware-template
[ -f "$ELF" ] || die "$ELF was not built"

# --- 2. Run in QEMU (the runner of the template's .cargo/config.toml) --------------------------
OUT=$(mktemp)
trap 'rm -f "$OUT" "$OUT.in" "$OUT.host"' EXIT
rc=0
timeout "${TEMPLATE_TIMEOUT:-60}" qemu-system-arm -machine mps2-an386 -nographic \
  -semihosting-config enable=on,target=native -kernel "$ELF" >"$OUT" 2>&1 || rc=$?
cat "$OUT"
[ $rc -eq 0 ] || die "the firmware exited with status $rc"
grep -q "^ppoe-firmware-template: ok$" "$OUT" || die "the firmware did not print its ok line"

# --- 3. Against the host: ppoe eval in f64 -----------------------------------------------------
EVAL=(cargo run --quiet --release -p ppoe-cli --manifest-path "$ROOT/Cargo.toml" -- eval
      --urdf "$TPL/robot.urdf" --base base_link --tip tool0)
# The chain's screw axes first (zero noise), then the firmware's case: its printed angles and
# 1e-4·S·Sᵀ per joint (screw_noise with ENCODER_VARIANCE in src/main.rs).
python3 - "$OUT" >"$OUT.in" <<'EOF'
import json, re, sys
text = open(sys.argv[1]).read()
thetas = json.loads(re.search(r"^thetas: (\[.*\])$", text, re.M).group(1))
print(json.dumps({"cases": [{"thetas": thetas, "covs": [[[0.0] * 6] * 6] * len(thetas)}]}))
EOF
"${EVAL[@]}" --input "$OUT.in" >"$OUT.host"
python3 - "$OUT" "$OUT.host" "$TPL/src/main.rs" <<'EOF' | "${EVAL[@]}" >"$OUT.host.2"
import json, re, sys
text, host, src = (open(p).read() for p in sys.argv[1:4])
var = float(re.search(r"const ENCODER_VARIANCE: f32 = ([0-9.e+-]+);", src).group(1))
thetas = json.loads(re.search(r"^thetas: (\[.*\])$", text, re.M).group(1))
axes = json.loads(host)["chain"]["screw_axes"]
covs = [[[var * s[i] * s[j] for j in range(6)] for i in range(6)] for s in axes]
print(json.dumps({"cases": [{"thetas": thetas, "covs": covs}]}))
EOF
python3 - "$OUT" "$OUT.host.2" <<'EOF'
import json, sys
text = open(sys.argv[1]).read().splitlines()
res = json.load(open(sys.argv[2]))["results"][0]
dev_pose = [[float(x) for x in l.split()[1:]] for l in text if l.startswith("pose: ")]
dev_cov = [[float(x) for x in l.split()[1:]] for l in text if l.startswith("cov: ")]
assert len(dev_pose) == 4 and len(dev_cov) == 6, "the firmware printed no full pose/cov"
def err(a, b):
    d = max(abs(x - y) for ra, rb in zip(a, b) for x, y in zip(ra, rb))
    m = max(abs(y) for rb in b for y in rb)
    return d, m
ok = True
for name, a, b in (("pose", dev_pose, res["pose"]), ("cov", dev_cov, res["cov"])):
    d, m = err(a, b)
    rel = d / max(1.0, m)
    print(f"template-check: {name}: max|f32 device - f64 host| = {d:.3e}, "
          f"/max(1,max|host|) = {rel:.3e}, /max|host| = {d / m if m else 0:.3e}")
    ok &= rel <= 1e-5
    if name == "cov":
        ok &= m > 0 and d <= 1e-4 * m
sys.exit(0 if ok else "template-check: ERROR: the device's PPOE differs from the host's")
EOF
rm -f "$OUT.host.2"
log "ok: the template builds, runs in QEMU and matches the host"
