#!/usr/bin/env bash
# scripts/features-check.sh -- the optional interoperability features of the core crate.
#
# 1. The default build depends on exactly num-traits, libm, heapless and approx
#    (`cargo tree -p ppoe -e normal --depth 1`), and so does --no-default-features.
# 2. Each feature builds on its own: `cargo check -p ppoe --no-default-features --features F`
#    (lib, -D warnings on ppoe only, via `cargo rustc --profile check`), F in mint serde defmt nalgebra arbitrary; then all at once.
# 3. Each feature's tests: tests/interop_F.rs and the doc examples of src/interop/F.rs.
# 4. defmt (with the other no_std features mint, serde, nalgebra) builds for
#    thumbv7em-none-eabihf with Debian's rustc-web and -Z build-std, as
#    scripts/thumb-check.sh does (arbitrary needs std: host only).
#
# Usage: scripts/features-check.sh [--no-thumb]
# Env: THUMB_TARGET_DIR (default target/thumb, shared with thumb-check.sh)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

THUMB=1
for a in "$@"; do
  case "$a" in
    --no-thumb) THUMB=0 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "features-check: unknown argument $a" >&2; exit 2 ;;
  esac
done

FEATURES=(mint serde defmt nalgebra arbitrary)
step() { echo "---- features-check: $*"; }

# --- 1. The default dependency rule --------------------------------------------------------
expected="approx heapless libm num-traits"
for flags in "" "--no-default-features"; do
  # shellcheck disable=SC2086 # $flags is one word or empty
  deps=$(cargo tree -q -p ppoe -e normal --depth 1 --prefix none $flags \
           | awk 'NR > 1 { print $1 }' | sort | tr '\n' ' ' | sed 's/ $//')
  step "normal dependencies (${flags:-default features}): $deps"
  if [ "$deps" != "$expected" ]; then
    echo "features-check: expected exactly: $expected" >&2
    exit 1
  fi
done

# --- 2. Each feature on its own, then all ---------------------------------------------------
for f in "${FEATURES[@]}"; do
  step "cargo check --no-default-features --features $f"
  cargo rustc -q -p ppoe --lib --profile check --no-default-features --features "$f" -- -D warnings
done
step "cargo check --all-features"
cargo rustc -q -p ppoe --lib --profile check --all-features -- -D warnings

# --- 3. Tests of each feature ---------------------------------------------------------------
for f in "${FEATURES[@]}"; do
  step "tests of feature $f (tests/interop_$f.rs and the doc examples of src/interop/$f.rs)"
  cargo test -q -p ppoe --features "$f" --test "interop_$f"
  cargo test -q -p ppoe --features "$f" --doc "interop::$f"
done

# --- 4. defmt (and the other no_std features) for Cortex-M4F --------------------------------
if [ $THUMB = 1 ]; then
  target=thumbv7em-none-eabihf
  step "ppoe --features defmt,mint,serde,nalgebra for $target (build-std)"
  . "$ROOT/scripts/lib/thumb-env.sh"
  thumb_toolchain 1
  thumb_build_env "${THUMB_TARGET_DIR:-$ROOT/target/thumb}"
  env "${BUILD_ENV[@]}" "$CARGO" rustc --locked -p ppoe --lib --release --target "$target" \
      --no-default-features --features defmt,mint,serde,nalgebra -- -D warnings
fi
echo "features-check: OK"
