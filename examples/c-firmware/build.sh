#!/usr/bin/env bash
# examples/c-firmware/build.sh OUT_DIR [VAR=value...] -- the C side of ppoe, built and checked:
#   1. drift: ppoe-ffi/include/ppoe.h equals cbindgen's output for ppoe-ffi/src, and
#      examples/c-firmware/seed_table.h equals ppoe-build's C table of the seed robot (what
#      `ppoe table --lang c --scalar both --name SEED` prints);
#   2. the host C test: ppoe-ffi as a host staticlib (plain `cargo build --release`, linked
#      with a plain `gcc … libppoe_ffi.a -lm`, as the README documents), host.c + checks.c compiled with
#      `gcc -std=c99 -Wall -Wextra -Werror -pedantic` (which includes ppoe.h and the seed
#      table), run: every case and every status code;
#   3. the C firmware: ppoe-ffi for thumbv7em-none-eabihf (Debian's rustc + build-std, from
#      the VAR=value environment scripts/firmware.sh passes, cargo $FFI_CARGO), main.c + checks.c + startup.S
#      with arm-none-eabi-gcc and newlib -> OUT_DIR/ppoe-c-firmware.elf (run by firmware.sh).
# Fails on the first problem. --update (instead of OUT_DIR checks) rewrites the two
# committed files: examples/c-firmware/build.sh --update OUT_DIR.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
HERE=$ROOT/examples/c-firmware
FFI=$ROOT/ppoe-ffi
UPDATE=0
[ "${1:-}" = --update ] && { UPDATE=1; shift; }
OUT=${1:?usage: build.sh [--update] OUT_DIR [VAR=value...]}; shift
ENVV=("$@")
mkdir -p "$OUT/gen"
HOST_TD=${C_FIRMWARE_HOST_TARGET_DIR:-$OUT/host-target}   # host builds (gen, ppoe-ffi)
CFLAGS=(-std=c99 -Wall -Wextra -Werror -pedantic -O2)

# --- 1. generated files --------------------------------------------------------------------
echo "c-firmware: generating the seed table and the expected results (host)"
(cd "$HERE/gen" && env -u RUSTC -u RUSTC_BOOTSTRAP -u CARGO_UNSTABLE_BUILD_STD \
   CARGO_TARGET_DIR="$HOST_TD" cargo build -q --release --locked)
"$HOST_TD/release/ppoe-c-firmware-gen" "$OUT/gen"
command -v cbindgen >/dev/null || { echo "c-firmware: cbindgen missing (scripts/setup-thumb.sh installs it)" >&2; exit 1; }
(cd "$FFI" && cbindgen -q --config cbindgen.toml --output "$OUT/gen/ppoe.h")
if [ $UPDATE = 1 ]; then
  cp "$OUT/gen/ppoe.h" "$FFI/include/ppoe.h"
  cp "$OUT/gen/seed_table.h" "$HERE/seed_table.h"
  echo "c-firmware: updated ppoe-ffi/include/ppoe.h and examples/c-firmware/seed_table.h"
fi
drift=0
for pair in "$FFI/include/ppoe.h:$OUT/gen/ppoe.h" "$HERE/seed_table.h:$OUT/gen/seed_table.h"; do
  if ! diff -u "${pair%%:*}" "${pair#*:}"; then
    echo "c-firmware: ${pair%%:*} differs from its generator's output (build.sh --update)" >&2
    drift=1
  fi
done
[ $drift = 0 ] || exit 1
echo "c-firmware: ppoe.h and seed_table.h match their generators"

# --- 2. host C test ------------------------------------------------------------------------
echo "c-firmware: host C test (gcc ${CFLAGS[*]})"
# As documented (README "C API"): a plain `cargo build --release` and a plain link line.
(cd "$FFI" && env -u RUSTC -u RUSTC_BOOTSTRAP -u CARGO_UNSTABLE_BUILD_STD \
   CARGO_TARGET_DIR="$HOST_TD" cargo build -q --release --locked)
gcc "${CFLAGS[@]}" -I"$FFI/include" -I"$HERE" -I"$OUT/gen" -o "$OUT/c-api-host-test" \
  "$HERE/host.c" "$HERE/checks.c" "$HOST_TD/release/libppoe_ffi.a" -lm
"$OUT/c-api-host-test"

# --- 3. the C firmware ---------------------------------------------------------------------
echo "c-firmware: ppoe-ffi for thumbv7em-none-eabihf, firmware with arm-none-eabi-gcc"
# The target dir of the VAR=value environment (examples/firmware's): libcore is shared.
(cd "$FFI" && env "${ENVV[@]}" \
   "${FFI_CARGO:-cargo}" build -q --release --locked --target thumbv7em-none-eabihf)
THUMB_TD=$(for v in "${ENVV[@]}"; do case "$v" in CARGO_TARGET_DIR=*) echo "${v#*=}" ;; esac; done | tail -1)
THUMB_TD=${THUMB_TD:-$FFI/target}
ARM=(-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16)
arm-none-eabi-gcc "${CFLAGS[@]}" "${ARM[@]}" -g -ffunction-sections -fdata-sections \
  -I"$FFI/include" -I"$HERE" -I"$OUT/gen" -nostartfiles -T "$HERE/c-firmware.ld" \
  -o "$OUT/ppoe-c-firmware.elf" "$HERE/startup.S" "$HERE/main.c" "$HERE/checks.c" \
  "$THUMB_TD/thumbv7em-none-eabihf/release/libppoe_ffi.a" --specs=nosys.specs -lm \
  -Wl,--gc-sections
arm-none-eabi-size "$OUT/ppoe-c-firmware.elf"
