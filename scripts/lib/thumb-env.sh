# scripts/lib/thumb-env.sh -- sourced (not run) by the scripts that build for Cortex-M and
# RISC-V: firmware.sh, template-check.sh, thumb-check.sh, features-check.sh. The one
# definition of the toolchain block they share: which compiler and linker (from
# scripts/setup-thumb.sh), and the cargo environment of a bare-metal build.
#
# Needs: ROOT (the repository root) set by the caller.

# thumb_toolchain SETUP [--rustup TARGET]
#   Sets THUMB_KIND THUMB_RUSTC THUMB_SYSROOT THUMB_LINKER THUMB_LINKER_FLAVOR from
#   scripts/setup-thumb.sh --env: installing what is missing when SETUP=1, only detecting
#   (and failing on anything missing) when SETUP=0 (the scripts' --no-setup).
thumb_toolchain() {
  local setup=$1; shift
  local args=(--env)
  [ "$setup" = 1 ] || args+=(--no-install)
  local out
  out=$("$ROOT/scripts/setup-thumb.sh" "${args[@]}" "$@") || return 1
  eval "$out"
}

# thumb_build_env TARGET_DIR [TRIPLE...]
#   Fills the array BUILD_ENV (for `env "${BUILD_ENV[@]}" cargo …`) and sets CARGO (the cargo
#   of the same toolchain; THUMB_CARGO overrides). Host flags are unset first: they must not
#   leak into bare-metal builds, nor into build scripts built by Debian's rustc. Debian's
#   toolchain builds core itself (build-std through the environment, never an [unstable]
#   table that would hit host builds too) and needs each TRIPLE's linker named; rustup's has
#   prebuilt targets and its own rust-lld.
thumb_build_env() {
  local td=$1 t; shift
  unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS CARGO_BUILD_RUSTFLAGS CARGO_BUILD_TARGET RUSTDOCFLAGS
  BUILD_ENV=(CARGO_TARGET_DIR="$td")
  if [ "$THUMB_KIND" = rustup ]; then
    BUILD_ENV+=(RUSTC="$THUMB_RUSTC")
    CARGO=${THUMB_CARGO:-$(env -u RUSTC rustup which cargo)}
    return 0
  fi
  BUILD_ENV+=(
    RUSTC="$THUMB_RUSTC"
    RUSTC_BOOTSTRAP=1
    CARGO_UNSTABLE_BUILD_STD=core,compiler_builtins
    CARGO_UNSTABLE_BUILD_STD_FEATURES=compiler-builtins-mem
  )
  for t in "$@"; do
    BUILD_ENV+=("CARGO_TARGET_$(tr 'a-z.-' 'A-Z__' <<<"$t")_LINKER=$THUMB_LINKER")
  done
  CARGO=${THUMB_CARGO:-/usr/bin/cargo}   # Debian's cargo: the compiler's own version
  [ -x "$CARGO" ] || CARGO=$(command -v cargo)
}
