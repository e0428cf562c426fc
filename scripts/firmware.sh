#!/usr/bin/env bash
# scripts/firmware.sh -- build the ppoe test firmware (examples/firmware, Rust; and
# examples/c-firmware, C) for every core below, run it in QEMU, check its results and its
# figures against firmware-budgets.toml; fails if any board or budget fails.
#
#   label (= target unless noted)   core                          QEMU board
#   thumbv6m-none-eabi              Cortex-M0 (no FPU)            microbit     (16K RAM)
#   thumbv7m-none-eabi              Cortex-M3 (no FPU)            lm3s6965evb
#   thumbv7em-none-eabi             Cortex-M4, soft float         mps2-an386
#   thumbv7em-none-eabihf           Cortex-M4F (f32 FPU)          mps2-an386
#   cortex-m7 (thumbv7em-none-eabihf, -C target-cpu=cortex-m7: f64 FPU)   mps2-an500
#   thumbv8m.main-none-eabihf       Cortex-M33 (f32 FPU)          mps2-an505
#   riscv32imac-unknown-none-elf    RV32IMAC (soft float)         virt (qemu-system-riscv32)
#   riscv32imafc-unknown-none-elf   RV32IMAFC (f32 FPU)           virt
#   c-m4f (examples/c-firmware: C + the ppoe-ffi staticlib, arm-none-eabi-gcc + newlib)
#                                   Cortex-M4F                    mps2-an386
#
# The firmware's build.rs generates the seed robot's tables (f32, f64) from
# test_data/urdf/seed.urdf with ppoe-build and computes the expected PPOE results on the
# host in f64; on the device the PPOE runs in f64 and f32 and is compared with them (f64
# <= 1e-12, f32 <= 1e-5 relative). The rank-one PPOE (`ppoe_rank1`, one variance per joint
# value) runs on the same joint values and is compared the same way with the host's dense
# PPOE of the equivalent screw-noise covariances (examples/firmware/rank1_cases.rs; not in
# the C firmware). The firmware prints a summary over semihosting and exits QEMU with a
# non-zero status on any mismatch or panic.
#
# Every run is under `-icount shift=0`, where one guest instruction takes 1 ns: the mps2
# SysTick (25 MHz on an386/an500, 20 MHz on an505) ticks every 40 (50) instructions and the
# RISC-V `instret` counts them, so the firmware's counter per PPOE call gives instructions
# per call (microbit and lm3s6965evb clock SysTick otherwise: no count there). The runs'
# output is kept in $FIRMWARE_TARGET_DIR/firmware-logs/LABEL.txt (the M4F's also as
# thumbv7em-none-eabihf-icount.txt, which scripts/bench_report.py reads).
#
# Checks after the runs:
#   - soft vs hard float: the f32 results of thumbv7em-none-eabi and -eabihf (and of
#     riscv32imac and -imafc) agree within 1e-5 (scripts/fw_budgets.py --compare-bits);
#   - budgets: instructions per PPOE, PPOE-path code size and stack per target and scalar,
#     dense and rank-one, against firmware-budgets.toml (fail above budget x 1.10;
#     scripts/fw_budgets.py); Markdown tables of the figures (and of rank-one vs dense, with
#     the ratio) go to $FIRMWARE_TARGET_DIR/firmware-figures.md;
#   - panic-freedom (M4F): the bin `panic_never` (feature panic-never) calls every public
#     entry point of the core crate in f32 and f64; its panic handler references an undefined
#     symbol, so the link fails if any panic path survives optimisation.
#
# Toolchain: scripts/setup-thumb.sh (Debian's rustc-web + its library sources, -Z build-std
# through the environment, rustup's rust-lld or arm-none-eabi-ld). Release builds; output
# in examples/firmware/target (or $FIRMWARE_TARGET_DIR).
#
# Usage: scripts/firmware.sh [--no-setup] [--no-panic-check] [--no-budgets] [LABEL...]
#   --no-setup        do not run scripts/setup-thumb.sh (packages already installed)
#   --no-panic-check  skip the panic-never link check
#   --no-budgets      report the figures without failing on a budget
#   --no-icount       accepted for compatibility (every run counts instructions now)
#   LABEL...     default: all of the above
# Env: FIRMWARE_TARGET_DIR, FIRMWARE_TIMEOUT (seconds per QEMU run, default 60),
#      THUMB_CARGO (force a cargo binary; default Debian's /usr/bin/cargo)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
FW=$ROOT/examples/firmware
BUDGETS=$ROOT/firmware-budgets.toml

SETUP=1; PANIC_CHECK=1; BUDGET_CHECK=1; LABELS=()
for a in "$@"; do
  case "$a" in
    --no-setup) SETUP=0 ;;
    --no-icount) ;;
    --no-panic-check) PANIC_CHECK=0 ;;
    --no-budgets) BUDGET_CHECK=0 ;;
    -h|--help) sed -n '2,56p' "$0"; exit 0 ;;
    -*) echo "firmware: unknown option $a" >&2; exit 2 ;;
    *) LABELS+=("$a") ;;
  esac
done
ALL=(thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabi thumbv7em-none-eabihf cortex-m7
     thumbv8m.main-none-eabihf riscv32imac-unknown-none-elf riscv32imafc-unknown-none-elf c-m4f)
[ ${#LABELS[@]} -gt 0 ] || LABELS=("${ALL[@]}")

# label -> rust target, QEMU machine, instructions per counter tick under -icount shift=0
# (0: the board's counter does not count instructions), extra rustflags.
declare -A TRIPLE=(
  [thumbv6m-none-eabi]=thumbv6m-none-eabi [thumbv7m-none-eabi]=thumbv7m-none-eabi
  [thumbv7em-none-eabi]=thumbv7em-none-eabi [thumbv7em-none-eabihf]=thumbv7em-none-eabihf
  [cortex-m7]=thumbv7em-none-eabihf [thumbv8m.main-none-eabihf]=thumbv8m.main-none-eabihf
  [riscv32imac-unknown-none-elf]=riscv32imac-unknown-none-elf
  [riscv32imafc-unknown-none-elf]=riscv32imafc-unknown-none-elf
  [c-m4f]=thumbv7em-none-eabihf
)
declare -A BOARD=(
  [thumbv6m-none-eabi]=microbit [thumbv7m-none-eabi]=lm3s6965evb
  [thumbv7em-none-eabi]=mps2-an386 [thumbv7em-none-eabihf]=mps2-an386 [cortex-m7]=mps2-an500
  [thumbv8m.main-none-eabihf]=mps2-an505 [riscv32imac-unknown-none-elf]=virt
  [riscv32imafc-unknown-none-elf]=virt [c-m4f]=mps2-an386
)
declare -A PER_TICK=(
  [thumbv6m-none-eabi]=0 [thumbv7m-none-eabi]=0 [thumbv7em-none-eabi]=40
  [thumbv7em-none-eabihf]=40 [cortex-m7]=40 [thumbv8m.main-none-eabihf]=50
  [riscv32imac-unknown-none-elf]=1 [riscv32imafc-unknown-none-elf]=1 [c-m4f]=40
)
for l in "${LABELS[@]}"; do
  [ -n "${BOARD[$l]:-}" ] || { echo "firmware: unknown label $l (known: ${ALL[*]})" >&2; exit 2; }
done
has() { [[ " ${LABELS[*]} " == *" $1 "* ]]; }

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
fmt_s() { printf '%d.%01d s' $(( $1 / 1000 )) $(( ($1 % 1000) / 100 )); }
T_ALL=$(now_ms)

# --- Toolchain (scripts/lib/thumb-env.sh: Debian's, the one the budgets were measured with) ---
. "$ROOT/scripts/lib/thumb-env.sh"
thumb_toolchain $SETUP
command -v qemu-system-arm >/dev/null || { echo "firmware: qemu-system-arm missing: run scripts/setup-thumb.sh" >&2; exit 1; }
# Absolute: the builds run in $FW, the runs and checks here.
TD=$(realpath -m "${FIRMWARE_TARGET_DIR:-$FW/target}")
thumb_build_env "$TD" "${TRIPLE[@]}"
echo "firmware: rustc $("$THUMB_RUSTC" -V); cargo $CARGO ($(env "${BUILD_ENV[@]}" "$CARGO" -V))"
echo "firmware: linker $THUMB_LINKER; target dir $TD"

# ELF of a label's Rust firmware (the M7 build has its own target dir: same triple as the M4F,
# other codegen flags).
elf_of() {
  case "$1" in
    cortex-m7) echo "$TD/m7/thumbv7em-none-eabihf/release/ppoe-firmware" ;;
    c-m4f) echo "$TD/c-firmware/ppoe-c-firmware.elf" ;;
    *) echo "$TD/${TRIPLE[$1]}/release/ppoe-firmware" ;;
  esac
}

# --- Build: one cargo invocation for the plain targets (host build deps and build.rs are
# shared, the per-target libcore builds run side by side), one for the M7 ----------------
FAILED=(); SUMMARY=()
TARGET_ARGS=()
for l in "${LABELS[@]}"; do
  case "$l" in cortex-m7|c-m4f) ;; *) TARGET_ARGS+=(--target "${TRIPLE[$l]}") ;; esac
done
echo "---- build (release): ${LABELS[*]}"
t0=$(now_ms)
if [ ${#TARGET_ARGS[@]} -gt 0 ]; then
  (cd "$FW" && env "${BUILD_ENV[@]}" "$CARGO" build --release "${TARGET_ARGS[@]}")
fi
if has cortex-m7; then
  # RUSTFLAGS reach the target crates only (with --target, build scripts are built without).
  (cd "$FW" && env "${BUILD_ENV[@]}" CARGO_TARGET_DIR="$TD/m7" \
     RUSTFLAGS="-C target-cpu=cortex-m7" "$CARGO" build --release --target thumbv7em-none-eabihf)
fi
if has c-m4f; then
  FFI_CARGO="$CARGO" "$ROOT/examples/c-firmware/build.sh" "$TD/c-firmware" "${BUILD_ENV[@]}"
fi
T_BUILD=$(( $(now_ms) - t0 ))
echo "firmware: built in $(fmt_s $T_BUILD)"

# --- Panic-freedom of the core's public entry points (M4F, f32 and f64) ---------------------
# bin panic_never: its panic handler calls an undefined symbol, so linking fails if any panic
# path survives optimisation. Then run it (must exit 0).
if [ $PANIC_CHECK = 1 ] && has thumbv7em-none-eabihf; then
  echo "---- panic-never link check (thumbv7em-none-eabihf, every public entry point, f32 + f64)"
  rc=0
  (cd "$FW" && env "${BUILD_ENV[@]}" "$CARGO" build --release --target thumbv7em-none-eabihf \
      --features panic-never --bin panic_never) || rc=$?
  if [ $rc -eq 0 ]; then
    timeout "${FIRMWARE_TIMEOUT:-60}" qemu-system-arm -machine mps2-an386 -nographic \
      -semihosting-config enable=on,target=native \
      -kernel "$TD/thumbv7em-none-eabihf/release/panic_never" || rc=$?
  fi
  if [ $rc -eq 0 ]; then msg="ok (links and runs: no panic path in the public entry points)"
  else msg="FAILED (exit $rc; an undefined ppoe_panic_path_survived_optimisation means a panic path)"
       FAILED+=("panic-never"); fi
  echo "panic-never: $msg"
  SUMMARY+=("$(printf '  %-30s %s' "panic-never (M4F)" "$msg")")
fi

# --- Run (every board under -icount shift=0, see the header) --------------------------------
TIMEOUT=${FIRMWARE_TIMEOUT:-60}
LOGDIR=$TD/firmware-logs; mkdir -p "$LOGDIR"
RUNS=()
for l in "${LABELS[@]}"; do
  elf=$(elf_of "$l"); board=${BOARD[$l]}; log=$LOGDIR/$l.txt
  echo "---- $l on $board"
  if [ "$board" = virt ]; then
    QEMU=(qemu-system-riscv32 -machine virt -bios none)
  else
    QEMU=(qemu-system-arm -machine "$board")
  fi
  t0=$(now_ms); rc=0
  timeout "$TIMEOUT" "${QEMU[@]}" -nographic -semihosting-config enable=on,target=native \
    -icount shift=0 -kernel "$elf" >"$log" 2>&1 || rc=$?
  dt=$(( $(now_ms) - t0 ))
  grep -v '^f32 bits' "$log" || true
  [ "$l" = thumbv7em-none-eabihf ] && cp "$log" "$LOGDIR/thumbv7em-none-eabihf-icount.txt"
  summary=$(grep '^summary:' "$log" | sed 's/^summary: //' || true)
  if [ $rc -eq 0 ] && grep -q '^RESULT: PASS' "$log"; then
    status=ok
  else
    status="FAILED (exit $rc$([ $rc -eq 124 ] && echo ', timeout'))"; FAILED+=("$l")
  fi
  SUMMARY+=("$(printf '  %-30s %-12s %-8s %6s  %s' "$l" "$board" "$status" "$(fmt_s $dt)" "${summary:-no summary}")")
  RUNS+=("$l:$elf:$log:${PER_TICK[$l]}")
done

# --- Soft vs hard float: the same f32 results within 1e-5 ----------------------------------
cross() {
  local a=$1 b=$2 out rc=0
  has "$a" && has "$b" || return 0
  out=$(python3 "$ROOT/scripts/fw_budgets.py" --compare-bits "$LOGDIR/$a.txt" "$LOGDIR/$b.txt" 1e-5) || rc=$?
  echo "$out"
  SUMMARY+=("$(printf '  %-30s %s' "$a vs $b" "${out#f32 cross-check: }")")
  [ $rc -eq 0 ] || FAILED+=("cross-check $a/$b")
}
echo "---- soft vs hard float (f32 results of the same cases)"
cross thumbv7em-none-eabi thumbv7em-none-eabihf
cross riscv32imac-unknown-none-elf riscv32imafc-unknown-none-elf

# --- Budgets ----------------------------------------------------------------------------------
rc=0
python3 "$ROOT/scripts/fw_budgets.py" "$BUDGETS" --markdown "$TD/firmware-figures.md" \
  --json "$TD/firmware-figures.json" "${RUNS[@]}" || rc=$?
if [ $rc -ne 0 ]; then
  if [ $BUDGET_CHECK = 1 ]; then FAILED+=("budgets"); else echo "firmware: budgets not enforced (--no-budgets)"; fi
fi
echo "firmware: figures as Markdown in $TD/firmware-figures.md"

echo "---- firmware summary (build $(fmt_s $T_BUILD), total $(fmt_s $(( $(now_ms) - T_ALL ))))"
printf '%s\n' "${SUMMARY[@]}"
if [ ${#FAILED[@]} -gt 0 ]; then
  echo "firmware: FAILED: ${FAILED[*]}" >&2
  exit 1
fi
echo "firmware: OK"
