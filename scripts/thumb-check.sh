#!/usr/bin/env bash
# scripts/thumb-check.sh -- prove the core crate `ppoe` builds for Cortex-M.
#
# Builds the library of package `ppoe` only (release; no tests, examples or dev-dependencies,
# no other workspace member) for each thumb target with Debian's rustc-web and
# `-Z build-std=core,compiler_builtins`. Only `core` is built for the target, so any use of
# `std` or `alloc` anywhere in ppoe or its dependencies fails the build. Warnings in ppoe
# itself are errors (set THUMB_ALLOW_WARNINGS=1 to relax).
#
# Output goes to a separate target dir ($THUMB_TARGET_DIR, default target/thumb) so host
# builds are not disturbed. build-std is passed through the environment only for these
# commands (an [unstable] table in .cargo/config.toml would hit host builds too).
#
# Usage: scripts/thumb-check.sh [--no-setup] [--host-nostd] [TARGET...]
#   --no-setup     do not run scripts/setup-thumb.sh (packages already installed)
#   --host-nostd   also run the cheap host-side no_std check: a #![no_std] staticlib with its
#                  own #[panic_handler] that depends on ppoe, built for the host with rustup's
#                  toolchain; fails (E0152 duplicate `panic_impl`) if anything pulls in std
#   TARGET...      default: thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabihf
#                           thumbv8m.main-none-eabihf
# Env: THUMB_CARGO (force a cargo binary), THUMB_TARGET_DIR, THUMB_RUSTFLAGS,
#      THUMB_ALLOW_WARNINGS=1
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

SETUP=1; HOST_NOSTD=0; TARGETS=(); LOCKED=()
for a in "$@"; do
  case "$a" in
    --no-setup) SETUP=0 ;;
    --host-nostd) HOST_NOSTD=1 ;;
    -h|--help) sed -n '2,23p' "$0"; exit 0 ;;
    -*) echo "thumb-check: unknown option $a" >&2; exit 2 ;;
    *) TARGETS+=("$a") ;;
  esac
done
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabihf thumbv8m.main-none-eabihf)

TD=${THUMB_TARGET_DIR:-$ROOT/target/thumb}
mkdir -p "$TD"
now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
fmt_s() { printf '%d.%01d s' $(( $1 / 1000 )) $(( ($1 % 1000) / 100 )); }

# --- Toolchain (scripts/lib/thumb-env.sh): Debian's, whose build-std builds only core -------
. "$ROOT/scripts/lib/thumb-env.sh"
thumb_toolchain $SETUP
thumb_build_env "$TD"
[ -n "${THUMB_RUSTFLAGS:-}" ] && BUILD_ENV+=(RUSTFLAGS="$THUMB_RUSTFLAGS")

# Cargo: Debian's (same version as the compiler and library sources) if it can read our
# lockfile as it is; otherwise rustup's, with RUSTC pointing at Debian's compiler.
if [ -n "${THUMB_CARGO:-}" ]; then
  CARGO=$THUMB_CARGO; why="THUMB_CARGO"
elif [ -x /usr/bin/cargo ] && env "${BUILD_ENV[@]}" /usr/bin/cargo tree -q --locked -p ppoe \
       -e normal --target all >/dev/null 2>"$TD/cargo-probe.err"; then
  # --locked: a cargo of another version than the host's must never rewrite Cargo.lock
  CARGO=/usr/bin/cargo; why="resolves Cargo.lock"; LOCKED=(--locked)
else
  CARGO=$(command -v cargo || true)
  [ -n "$CARGO" ] && [ "$CARGO" != /usr/bin/cargo ] \
    || { echo "thumb-check: Debian's cargo cannot use Cargo.lock and there is no rustup cargo:" >&2
         cat "$TD/cargo-probe.err" >&2; exit 1; }
  why="Debian's cargo cannot use Cargo.lock as is: $(head -c 300 "$TD/cargo-probe.err" | tr '\n' ' ')"
fi
echo "thumb-check: rustc $("$THUMB_RUSTC" -V)"
echo "thumb-check: cargo $CARGO ($(env "${BUILD_ENV[@]}" "$CARGO" -V)) -- $why"
echo "thumb-check: target dir $TD"

# --- Thumb builds ---------------------------------------------------------------------------
EXTRA=(); [ "${THUMB_ALLOW_WARNINGS:-0}" = 1 ] || EXTRA=(-- -D warnings)
FAILED=(); SUMMARY=()
T_ALL=$(now_ms)
# 1) All targets in one cargo invocation: the libcore builds (most of the time) of two
#    targets run side by side on two cores. A failure here is attributed in 2).
if [ ${#TARGETS[@]} -gt 1 ]; then
  echo "---- ppoe (lib, release), all targets at once: ${TARGETS[*]}"
  TARGET_ARGS=(); for t in "${TARGETS[@]}"; do TARGET_ARGS+=(--target "$t"); done
  t0=$(now_ms); rc=0
  env "${BUILD_ENV[@]}" "$CARGO" build "${LOCKED[@]}" -p ppoe --lib --release "${TARGET_ARGS[@]}" || rc=$?
  dt=$(( $(now_ms) - t0 ))
  SUMMARY+=("$(printf '  %-28s %-7s %9s   (core + deps + ppoe, all targets)' "batch build" \
                "$([ $rc -eq 0 ] && echo ok || echo failed)" "$(fmt_s $dt)")")
  [ $rc -eq 0 ] || echo "thumb-check: batch build failed (exit $rc); building each target alone to see which" >&2
fi
# 2) Per target (cheap once 1) is done): `cargo rustc` so that `-D warnings` reaches ppoe
#    only, not core or the dependencies; gives a per-target verdict.
for t in "${TARGETS[@]}"; do
  echo "---- ppoe (lib, release) for $t"
  t0=$(now_ms); rc=0
  env "${BUILD_ENV[@]}" "$CARGO" rustc "${LOCKED[@]}" -p ppoe --lib --release --target "$t" "${EXTRA[@]}" || rc=$?
  dt=$(( $(now_ms) - t0 ))
  rlib=$TD/$t/release/libppoe.rlib
  if [ $rc -eq 0 ] && [ -f "$rlib" ]; then
    SUMMARY+=("$(printf '  %-28s ok      %9s   rlib %s bytes' "$t" "$(fmt_s $dt)" "$(stat -c %s "$rlib")")")
  else
    FAILED+=("$t"); SUMMARY+=("$(printf '  %-28s FAILED  %9s   (exit %s)' "$t" "$(fmt_s $dt)" "$rc")")
  fi
done

# --- Optional: host-side no_std check -------------------------------------------------------
if [ $HOST_NOSTD = 1 ]; then
  echo "---- host no_std check (#![no_std] staticlib + #[panic_handler] depending on ppoe)"
  H=$TD/host-nostd
  mkdir -p "$H/src"
  cat > "$H/Cargo.toml" <<EOF
# generated by scripts/thumb-check.sh --host-nostd
[package]
name = "ppoe-host-nostd-check"
version = "0.0.0"
edition = "2021"
publish = false
[lib]
crate-type = ["staticlib"]
path = "src/lib.rs"
[dependencies]
ppoe = { path = "$ROOT" }
[profile.dev]
panic = "abort"
[profile.release]
panic = "abort"
[workspace]
EOF
  cat > "$H/src/lib.rs" <<'EOF'
//! If ppoe or any of its dependencies links `std`, std's `panic_impl` lang item clashes
//! with the handler below: error E0152.
#![no_std]
extern crate ppoe;
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
EOF
  cp "$ROOT/Cargo.lock" "$H/Cargo.lock"   # same dependency versions as the workspace
  t0=$(now_ms); rc=0
  (cd "$H" && env -u RUSTC -u RUSTC_BOOTSTRAP CARGO_TARGET_DIR="$H/target" cargo build -q --release) || rc=$?
  dt=$(( $(now_ms) - t0 ))
  if [ $rc -eq 0 ]; then SUMMARY+=("$(printf '  %-28s ok      %9s' "host no_std staticlib" "$(fmt_s $dt)")")
  else FAILED+=("host-nostd"); SUMMARY+=("$(printf '  %-28s FAILED  %9s   (exit %s)' "host no_std staticlib" "$(fmt_s $dt)" "$rc")"); fi
fi

echo "---- thumb-check summary (total $(fmt_s $(( $(now_ms) - T_ALL ))))"
printf '%s\n' "${SUMMARY[@]}"
if [ ${#FAILED[@]} -gt 0 ]; then
  echo "thumb-check: FAILED: ${FAILED[*]}" >&2
  exit 1
fi
echo "thumb-check: OK"
