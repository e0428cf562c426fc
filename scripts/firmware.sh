#!/usr/bin/env bash
# scripts/firmware.sh -- build the ppoe test firmware (examples/firmware) for four Cortex-M
# cores and run it in QEMU; fails if any board fails.
#
#   target                      core                        QEMU board
#   thumbv6m-none-eabi          Cortex-M0 (no FPU)          microbit     (16K RAM)
#   thumbv7m-none-eabi          Cortex-M3 (no FPU)          lm3s6965evb
#   thumbv7em-none-eabihf       Cortex-M4F (f32 FPU)        mps2-an386
#   thumbv8m.main-none-eabihf   Cortex-M33 (f32 FPU)        mps2-an505
#
# The firmware's build.rs generates the seed robot's tables (f32, f64) from
# test_data/urdf/seed.urdf with ppoe-build and computes the expected PPOE results on the
# host in f64; on the device the PPOE runs in f64 and f32 and is compared with them (f64
# <= 1e-12, f32 <= 1e-5 relative). The firmware prints a summary over semihosting and exits
# QEMU with a non-zero status on any mismatch or panic.
#
# Toolchain: scripts/setup-thumb.sh (Debian's rustc-web + its library sources, -Z build-std
# through the environment, rustup's rust-lld or arm-none-eabi-ld). Release builds; output
# in examples/firmware/target (or $FIRMWARE_TARGET_DIR).
#
# After the runs, the M4F firmware runs once more under `-icount shift=0`, where one guest
# instruction takes 1 ns and the mps2 SysTick (25 MHz) ticks every 40 instructions: the
# firmware's SysTick count per PPOE call gives instructions per call (resolution ~40/reps);
# likewise for se3 exp/log and the second-order concat (64 calls each; reported only, never
# a failure). The run's output is kept in $FIRMWARE_TARGET_DIR/firmware-logs/*-icount.txt.
#
# Panic-freedom: with the M4F among the targets, the bin `panic_never` (feature panic-never)
# is built too: it calls the f32 and f64 PPOE and its panic handler references an undefined
# symbol, so the link fails if any panic path of the PPOE survives optimisation.
#
# Usage: scripts/firmware.sh [--no-setup] [--no-icount] [--no-panic-check] [TARGET...]
#   --no-setup        do not run scripts/setup-thumb.sh (packages already installed)
#   --no-icount       skip the instruction-count run
#   --no-panic-check  skip the panic-never link check
#   TARGET...     default: all four above
# Env: FIRMWARE_TARGET_DIR, FIRMWARE_TIMEOUT (seconds per QEMU run, default 60),
#      THUMB_CARGO (force a cargo binary; default Debian's /usr/bin/cargo)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
FW=$ROOT/examples/firmware

SETUP=1; ICOUNT=1; PANIC_CHECK=1; TARGETS=()
for a in "$@"; do
  case "$a" in
    --no-setup) SETUP=0 ;;
    --no-icount) ICOUNT=0 ;;
    --no-panic-check) PANIC_CHECK=0 ;;
    -h|--help) sed -n '2,39p' "$0"; exit 0 ;;
    -*) echo "firmware: unknown option $a" >&2; exit 2 ;;
    *) TARGETS+=("$a") ;;
  esac
done
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabihf thumbv8m.main-none-eabihf)

declare -A BOARD=(
  [thumbv6m-none-eabi]=microbit
  [thumbv7m-none-eabi]=lm3s6965evb
  [thumbv7em-none-eabihf]=mps2-an386
  [thumbv8m.main-none-eabihf]=mps2-an505
)
for t in "${TARGETS[@]}"; do
  [ -n "${BOARD[$t]:-}" ] || { echo "firmware: unknown target $t (known: ${!BOARD[*]})" >&2; exit 2; }
done

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
fmt_s() { printf '%d.%01d s' $(( $1 / 1000 )) $(( ($1 % 1000) / 100 )); }
T_ALL=$(now_ms)

# --- Toolchain ------------------------------------------------------------------------------
if [ $SETUP = 1 ]; then
  eval "$("$ROOT/scripts/setup-thumb.sh" --env)"
else
  THUMB_RUSTC=/usr/bin/rustc
  THUMB_LINKER=$(ls "${RUSTUP_HOME:-$HOME/.rustup}"/toolchains/*/lib/rustlib/"$(uname -m)"-unknown-linux-gnu/bin/rust-lld 2>/dev/null | head -1 || true)
  [ -n "$THUMB_LINKER" ] || THUMB_LINKER=$(command -v arm-none-eabi-ld || true)
fi
[ -x "$THUMB_RUSTC" ] || { echo "firmware: $THUMB_RUSTC missing: run scripts/setup-thumb.sh" >&2; exit 1; }
[ -n "$THUMB_LINKER" ] || { echo "firmware: no linker (rust-lld or arm-none-eabi-ld)" >&2; exit 1; }
command -v qemu-system-arm >/dev/null || { echo "firmware: qemu-system-arm missing: run scripts/setup-thumb.sh" >&2; exit 1; }

# Host flags must not leak into the thumb builds (nor into build scripts built by Debian's rustc).
unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS CARGO_BUILD_RUSTFLAGS CARGO_BUILD_TARGET RUSTDOCFLAGS
TD=${FIRMWARE_TARGET_DIR:-$FW/target}
BUILD_ENV=(
  RUSTC="$THUMB_RUSTC"
  RUSTC_BOOTSTRAP=1
  CARGO_UNSTABLE_BUILD_STD=core,compiler_builtins
  CARGO_UNSTABLE_BUILD_STD_FEATURES=compiler-builtins-mem
  CARGO_TARGET_DIR="$TD"
)
TARGET_ARGS=()
for t in "${TARGETS[@]}"; do
  up=$(tr 'a-z.-' 'A-Z__' <<<"$t")
  BUILD_ENV+=("CARGO_TARGET_${up}_LINKER=$THUMB_LINKER")
  TARGET_ARGS+=(--target "$t")
done
CARGO=${THUMB_CARGO:-/usr/bin/cargo}   # Debian's cargo: same version as the compiler
[ -x "$CARGO" ] || CARGO=$(command -v cargo)
echo "firmware: rustc $("$THUMB_RUSTC" -V); cargo $CARGO ($(env "${BUILD_ENV[@]}" "$CARGO" -V))"
echo "firmware: linker $THUMB_LINKER; target dir $TD"

# --- Build: one cargo invocation for all targets (host build deps and build.rs are shared) -
echo "---- build (release): ${TARGETS[*]}"
t0=$(now_ms)
(cd "$FW" && env "${BUILD_ENV[@]}" "$CARGO" build --release "${TARGET_ARGS[@]}")
T_BUILD=$(( $(now_ms) - t0 ))
echo "firmware: built in $(fmt_s $T_BUILD)"

# --- Panic-freedom of the PPOE path (M4F, f32 and f64) -----------------------------------------
# bin panic_never: its panic handler calls an undefined symbol, so linking fails if any panic
# path of the PPOE survives optimisation. Then run it (must exit 0).
PANIC_NEVER=""
if [ $PANIC_CHECK = 1 ] && [[ " ${TARGETS[*]} " == *" thumbv7em-none-eabihf "* ]]; then
  echo "---- panic-never link check (thumbv7em-none-eabihf, f32 + f64 PPOE)"
  rc=0
  (cd "$FW" && env "${BUILD_ENV[@]}" "$CARGO" build --release --target thumbv7em-none-eabihf \
      --features panic-never --bin panic_never) || rc=$?
  if [ $rc -eq 0 ]; then
    timeout "${FIRMWARE_TIMEOUT:-60}" qemu-system-arm -machine mps2-an386 -nographic \
      -semihosting-config enable=on,target=native \
      -kernel "$TD/thumbv7em-none-eabihf/release/panic_never" || rc=$?
  fi
  if [ $rc -eq 0 ]; then PANIC_NEVER="ok (links and runs: no panic path in the PPOE)"
  else PANIC_NEVER="FAILED (exit $rc; an undefined ppoe_panic_path_survived_optimisation means a panic path)"; fi
  echo "panic-never: $PANIC_NEVER"
fi

# --- Run --------------------------------------------------------------------------------------
TIMEOUT=${FIRMWARE_TIMEOUT:-60}
QEMU_ARGS=(-nographic -semihosting-config enable=on,target=native)
FAILED=(); SUMMARY=()
if [ -n "$PANIC_NEVER" ]; then
  SUMMARY+=("$(printf '  %-26s %s' "panic-never (M4F)" "$PANIC_NEVER")")
  [[ $PANIC_NEVER == ok* ]] || FAILED+=("panic-never")
fi
LOGDIR=$TD/firmware-logs; mkdir -p "$LOGDIR"
for t in "${TARGETS[@]}"; do
  elf=$TD/$t/release/ppoe-firmware
  board=${BOARD[$t]}
  log=$LOGDIR/$t.txt
  echo "---- $t on $board"
  t0=$(now_ms); rc=0
  timeout "$TIMEOUT" qemu-system-arm -machine "$board" "${QEMU_ARGS[@]}" -kernel "$elf" >"$log" 2>&1 || rc=$?
  dt=$(( $(now_ms) - t0 ))
  cat "$log"
  summary=$(grep '^summary:' "$log" | sed 's/^summary: //' || true)
  if [ $rc -eq 0 ] && grep -q '^RESULT: PASS' "$log"; then
    status=ok
  else
    status="FAILED (exit $rc$([ $rc -eq 124 ] && echo ', timeout'))"; FAILED+=("$t")
  fi
  size=$(arm-none-eabi-size "$elf" 2>/dev/null | awk 'NR==2 {print "text " $1 " B, data+bss " $2+$3 " B"}' || true)
  SUMMARY+=("$(printf '  %-26s %-12s %-8s %6s  %s' "$t" "$board" "$status" "$(fmt_s $dt)" "${summary:-no summary}")")
  [ -n "$size" ] && SUMMARY+=("$(printf '  %-26s %s' "" "$size")")
done

# --- Instructions per PPOE call on the M4F (-icount shift=0: 1 SysTick tick = 40 insns) -----
if [ $ICOUNT = 1 ] && [[ " ${TARGETS[*]} " == *" thumbv7em-none-eabihf "* ]]; then
  echo "---- instructions per 6-DOF PPOE call, thumbv7em-none-eabihf on mps2-an386 (-icount shift=0)"
  rc=0
  out=$(timeout "$TIMEOUT" qemu-system-arm -machine mps2-an386 "${QEMU_ARGS[@]}" -icount shift=0 \
          -kernel "$TD/thumbv7em-none-eabihf/release/ppoe-firmware" 2>&1) || rc=$?
  printf '%s\n' "$out" >"$LOGDIR/thumbv7em-none-eabihf-icount.txt"
  line=$(grep '^systick ticks per PPOE call' <<<"$out" || true)
  if [ $rc -eq 0 ] && [ -n "$line" ]; then
    read -r f32t f64t < <(sed 's/.*f32 \([0-9]*\) f64 \([0-9]*\).*/\1 \2/' <<<"$line")
    msg="f32 ~$((f32t * 40)) instructions, f64 ~$((f64t * 40)) instructions per call (SysTick x 40)"
    echo "$msg"
    SUMMARY+=("$(printf '  %-26s %s' "M4F icount" "$msg")")
    # The small ops (measurements only, never a failure): ticks per 64 calls x 40 / 64.
    while read -r op f32t f64t; do
      msg="$op: f32 ~$((f32t * 40 / 64)), f64 ~$((f64t * 40 / 64)) instructions per call"
      echo "$msg"
      SUMMARY+=("$(printf '  %-26s %s' "" "$msg")")
    done < <(sed -n 's/^systick ticks per 64 calls of \([a-z0-9_]*\): f32 \([0-9]*\) f64 \([0-9]*\).*/\1 \2 \3/p' <<<"$out")
    stack=$(grep '^stack per PPOE call' <<<"$out" | sed 's/^stack per PPOE call[^:]*: //' || true)
    [ -n "$stack" ] && SUMMARY+=("$(printf '  %-26s %s' "" "stack per PPOE call: $stack")")
  else
    echo "firmware: icount run failed (exit $rc)"; FAILED+=("icount")
  fi
fi

echo "---- firmware summary (build $(fmt_s $T_BUILD), total $(fmt_s $(( $(now_ms) - T_ALL ))))"
printf '%s\n' "${SUMMARY[@]}"
if [ ${#FAILED[@]} -gt 0 ]; then
  echo "firmware: FAILED: ${FAILED[*]}" >&2
  exit 1
fi
echo "firmware: OK"
