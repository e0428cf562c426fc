#!/usr/bin/env bash
# scripts/setup-thumb.sh -- install (if missing) what building ppoe for Cortex-M needs.
#
# rustup cannot add thumb targets on our machines (only the registries are reachable), so we
# use Debian's rustc-web (bookworm-security) together with its own library sources and
# `-Z build-std` (see scripts/thumb-check.sh and shared/embedded/RECIPE.md):
#   rustc-web cargo-web rust-web-src libstd-rust-web-dev  -> /usr/bin/rustc, /usr/bin/cargo,
#                                                            library sources for build-std
#   binutils-arm-none-eabi                                -> arm-none-eabi-{ld,size,nm,objdump}
#   qemu-system-arm                                       -> running Cortex-M firmware
#   qemu-system-misc                                      -> qemu-system-riscv32 (RISC-V firmware)
#   gcc-arm-none-eabi libnewlib-arm-none-eabi             -> the C firmware (examples/c-firmware)
# and, from crates.io, cbindgen (a pinned version: ppoe-ffi's header is checked against it).
# Debian's rustc has no rust-lld: we use rustup's (~/.rustup/toolchains/*/lib/rustlib/<host>/bin/
# rust-lld) and fall back to arm-none-eabi-ld.
#
# rustup first, where it is enough: `--rustup TARGET` tries `rustup target add TARGET` before
# anything else and, when it works, reports THUMB_KIND=rustup (the toolchain a user of the
# firmware template has: rustup's compiler, its prebuilt libcore, its rust-lld). The firmware
# budgets (firmware-budgets.toml) were measured with Debian's compiler and a libcore built by
# build-std with the firmware's own profile, and the core-only thumb builds rely on build-std
# building *only* core (a prebuilt target also ships alloc); so scripts/firmware.sh,
# thumb-check.sh and features-check.sh ask for Debian's toolchain (no --rustup) on purpose.
#
# Idempotent: installs nothing (and runs no `apt-get update`) when everything is present.
# Needs root (or password-less sudo) only when something must be installed.
#
# Usage: scripts/setup-thumb.sh [--env] [--no-install] [--rustup TARGET]
#   (none)          install if missing, report what is used (on stderr)
#   --env           also print shell assignments on stdout:
#                     eval "$(scripts/setup-thumb.sh --env)"
#                   -> THUMB_KIND (debian|rustup) THUMB_RUSTC THUMB_SYSROOT THUMB_LINKER
#                      THUMB_LINKER_FLAVOR
#   --no-install    install nothing: fail if a package is missing (the scripts' --no-setup)
#   --rustup TARGET rustup's toolchain if it has or can add TARGET (`rustup target add`,
#                   also with --no-install: it is the user's toolchain, not a system package),
#                   else Debian's
# The scripts source scripts/lib/thumb-env.sh, which calls this and builds the cargo
# environment from its answer (one definition of the toolchain block).
set -euo pipefail

PRINT_ENV=0; INSTALL=1; RUSTUP_TARGET=""
while [ $# -gt 0 ]; do
  case "$1" in
    --env) PRINT_ENV=1 ;;
    --no-install) INSTALL=0 ;;
    --rustup) RUSTUP_TARGET=${2:?--rustup needs a target}; shift ;;
    -h|--help) sed -n '2,36p' "$0"; exit 0 ;;
    *) echo "setup-thumb: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done

log() { echo "setup-thumb: $*" >&2; }
die() { echo "setup-thumb: ERROR: $*" >&2; exit 1; }

# --- rustup first, when asked for one target ---------------------------------------------
if [ -n "$RUSTUP_TARGET" ] && command -v rustup >/dev/null; then
  if env -u RUSTC rustup target list --installed 2>/dev/null | grep -qx "$RUSTUP_TARGET" \
     || timeout 120 env -u RUSTC rustup target add "$RUSTUP_TARGET" >&2; then
    RUSTC_RUSTUP=$(env -u RUSTC rustup which rustc)
    SYSROOT_RUSTUP=$("$RUSTC_RUSTUP" --print sysroot)
    LLD=$SYSROOT_RUSTUP/lib/rustlib/$(uname -m)-unknown-linux-gnu/bin/rust-lld
    if [ -x "$LLD" ]; then
      log "rustup: $RUSTC_RUSTUP ($("$RUSTC_RUSTUP" -V)) has $RUSTUP_TARGET; linker $LLD"
      if [ $PRINT_ENV = 1 ]; then
        printf 'THUMB_KIND=rustup\nTHUMB_RUSTC=%q\nTHUMB_SYSROOT=%q\nTHUMB_LINKER=%q\nTHUMB_LINKER_FLAVOR=rust-lld\n' \
          "$RUSTC_RUSTUP" "$SYSROOT_RUSTUP" "$LLD"
      fi
      exit 0
    fi
  fi
  log "rustup cannot provide $RUSTUP_TARGET here: Debian's rustc-web with build-std instead"
fi

PKGS=(rustc-web cargo-web rust-web-src libstd-rust-web-dev binutils-arm-none-eabi qemu-system-arm
      qemu-system-misc gcc-arm-none-eabi libnewlib-arm-none-eabi)

is_installed() {  # dpkg's view: "install ok installed"
  [ "$(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null || true)" = installed ]
}

MISSING=()
for p in "${PKGS[@]}"; do is_installed "$p" || MISSING+=("$p"); done

if [ ${#MISSING[@]} -gt 0 ] && [ $INSTALL = 0 ]; then
  die "missing: ${MISSING[*]}: run scripts/setup-thumb.sh (without --no-install)"
elif [ ${#MISSING[@]} -gt 0 ]; then
  command -v apt-get >/dev/null || die "apt-get not found (Debian 12 expected); missing: ${MISSING[*]}"
  SUDO=()
  if [ "$(id -u)" != 0 ]; then
    if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then SUDO=(sudo -n)
    else die "need root (or password-less sudo) to install: ${MISSING[*]}"; fi
  fi
  export DEBIAN_FRONTEND=noninteractive
  APT=("${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -q -o DPkg::Lock::Timeout=300)
  t0=$SECONDS
  # Always refresh the lists once before installing: a stale list on a fresh machine offers
  # bookworm's old rustc-web (1.85) instead of bookworm-security's current one.
  log "missing: ${MISSING[*]} -> apt-get update"
  "${APT[@]}" update >/dev/null
  log "apt-get install ${MISSING[*]}"
  if ! "${APT[@]}" install -y --no-install-recommends "${MISSING[@]}" >/dev/null; then
    log "install failed; retrying once after a fresh apt-get update"
    sleep 5
    "${APT[@]}" update >/dev/null
    "${APT[@]}" install -y --no-install-recommends "${MISSING[@]}" >/dev/null \
      || die "apt-get install ${MISSING[*]} failed"
  fi
  log "installed in $((SECONDS - t0)) s"
else
  log "all packages present (${PKGS[*]})"
fi

# --- cbindgen (the C header of ppoe-ffi is generated and checked against it) -----------------
CBINDGEN_VERSION=0.29.4
if [ $INSTALL = 1 ] && { ! command -v cbindgen >/dev/null || [ "$(cbindgen --version 2>/dev/null)" != "cbindgen $CBINDGEN_VERSION" ]; }; then
  log "cargo install cbindgen $CBINDGEN_VERSION (the C header check needs this exact version)"
  env -u RUSTC -u RUSTC_BOOTSTRAP cargo install -q --locked cbindgen --version "$CBINDGEN_VERSION" >&2 \
    || die "cargo install cbindgen failed"
fi

# --- Debian's compiler and its library sources -------------------------------------------
THUMB_RUSTC=/usr/bin/rustc
[ -x "$THUMB_RUSTC" ] || die "$THUMB_RUSTC missing after install"
THUMB_SYSROOT=$("$THUMB_RUSTC" --print sysroot)
LIBSRC=$THUMB_SYSROOT/lib/rustlib/src/rust/library
[ -f "$LIBSRC/core/Cargo.toml" ] || die "library sources for build-std not found at $LIBSRC (rust-web-src)"
TARGET_LIST=$("$THUMB_RUSTC" --print target-list)
for t in thumbv6m-none-eabi thumbv7m-none-eabi thumbv7em-none-eabi thumbv7em-none-eabihf \
         thumbv8m.main-none-eabihf riscv32imac-unknown-none-elf riscv32imafc-unknown-none-elf; do
  grep -qx "$t" <<<"$TARGET_LIST" || die "$THUMB_RUSTC does not know target $t"
done

# --- Linker (only needed for firmware binaries; a library build does not link) ----------
HOST_TRIPLE=$(uname -m)-unknown-linux-gnu
RUSTUP_DIR=${RUSTUP_HOME:-$HOME/.rustup}
THUMB_LINKER=""
# Prefer the default rustup toolchain's rust-lld, then any toolchain's.
if command -v rustc >/dev/null && [ "$(command -v rustc)" != /usr/bin/rustc ]; then
  cand=$(env -u RUSTC rustc --print sysroot 2>/dev/null)/lib/rustlib/$HOST_TRIPLE/bin/rust-lld
  [ -x "$cand" ] && THUMB_LINKER=$cand
fi
if [ -z "$THUMB_LINKER" ]; then
  for cand in "$RUSTUP_DIR"/toolchains/*/lib/rustlib/"$HOST_TRIPLE"/bin/rust-lld; do
    [ -x "$cand" ] && { THUMB_LINKER=$cand; break; }
  done
fi
if [ -n "$THUMB_LINKER" ]; then
  THUMB_LINKER_FLAVOR=rust-lld
elif command -v arm-none-eabi-ld >/dev/null; then
  THUMB_LINKER=$(command -v arm-none-eabi-ld); THUMB_LINKER_FLAVOR=gnu-ld
else
  die "no linker for thumb targets: neither rustup's rust-lld nor arm-none-eabi-ld"
fi

# --- Report -------------------------------------------------------------------------------
ver() { dpkg-query -W -f='${Version}' "$1" 2>/dev/null || echo '?'; }
first_line() { local out; out=$("$@" 2>/dev/null) || { echo missing; return 0; }; echo "${out%%$'\n'*}"; }
log "rustc:   $THUMB_RUSTC ($("$THUMB_RUSTC" -V), package rustc-web $(ver rustc-web))"
log "sysroot: $THUMB_SYSROOT (build-std sources: $LIBSRC)"
log "cargo:   /usr/bin/cargo ($(first_line /usr/bin/cargo -V)); rustup's: $(first_line env -u RUSTC cargo -V)"
log "linker:  $THUMB_LINKER ($THUMB_LINKER_FLAVOR)"
log "binutils: $(first_line arm-none-eabi-size --version)"
log "qemu:    $(first_line qemu-system-arm --version); $(first_line qemu-system-riscv32 --version)"
log "gcc:     $(first_line arm-none-eabi-gcc --version)"
log "cbindgen: $(first_line cbindgen --version)"

if [ $PRINT_ENV = 1 ]; then
  printf 'THUMB_KIND=debian\nTHUMB_RUSTC=%q\nTHUMB_SYSROOT=%q\nTHUMB_LINKER=%q\nTHUMB_LINKER_FLAVOR=%q\n' \
    "$THUMB_RUSTC" "$THUMB_SYSROOT" "$THUMB_LINKER" "$THUMB_LINKER_FLAVOR"
fi
