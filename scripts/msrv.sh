#!/usr/bin/env bash
# scripts/msrv.sh -- check the declared minimum Rust version (`rust-version` in Cargo.toml).
#
#  1. Every publishable workspace member declares the same rust-version (and so do ppoe-ffi
#     and ppoe-py, each a workspace of its own), and no crate in its
#     normal or build dependency graph (as locked in Cargo.lock) declares a higher one: a
#     cheap check that needs no old toolchain and fails as soon as a dependency update raises
#     the floor.
#  2. With a compiler of exactly that version (major.minor), using the committed Cargo.lock:
#     `cargo build` and `cargo test` of the core crate `ppoe` (library, all its tests,
#     doctests) and `cargo build` of the other publishable members. This is the proof behind the
#     declaration: the version declared is one a toolchain we have builds, not a guess.
#
# Toolchain search, first match wins: a rustup toolchain named after the version
# (`1.95.0`, `1.95`), rustup's `stable` if it is that version, Debian's /usr/bin/rustc
# (rustc-web, scripts/setup-thumb.sh) if it is that version. None: the script fails and says
# which toolchain to install.
#
# Usage: scripts/msrv.sh
# Env: MSRV_TARGET_DIR (default: target/; artifacts of different compilers do not collide)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

log() { echo "msrv: $*" >&2; }
die() { echo "msrv: ERROR: $*" >&2; exit 1; }

# --- 1. Declarations --------------------------------------------------------------------------
# Prints the declared version, or fails listing the disagreements.
MSRV=$(cargo metadata --format-version 1 --locked | python3 -c '
import json, sys
m = json.load(sys.stdin)
pk = {p["id"]: p for p in m["packages"]}
nodes = {n["id"]: n for n in m["resolve"]["nodes"]}
def ver(v):
    return tuple(int(x) for x in v.split("."))
members = [pk[i] for i in m["workspace_members"] if pk[i]["publish"] != []]
declared = {p["name"]: p["rust_version"] for p in members}
if None in declared.values() or len(set(declared.values())) != 1:
    sys.exit("msrv: ERROR: the publishable crates must declare one rust-version: %s" % declared)
msrv = next(iter(declared.values()))
bad = []
for p in members:
    seen, todo = set(), [p["id"]]
    while todo:
        i = todo.pop()
        for d in nodes[i]["deps"]:
            if any(k["kind"] in (None, "build") for k in d["dep_kinds"]) and d["pkg"] not in seen:
                seen.add(d["pkg"]); todo.append(d["pkg"])
    for i in seen:
        rv = pk[i]["rust_version"]
        if rv and ver(rv) > ver(msrv):
            bad.append("%s needs %s %s (rust-version %s)" % (p["name"], pk[i]["name"], pk[i]["version"], rv))
if bad:
    sys.exit("msrv: ERROR: declared rust-version %s, but\n  " % msrv + "\n  ".join(sorted(set(bad))))
print(msrv)
')
MM=$(cut -d. -f1,2 <<<"$MSRV")
log "declared rust-version $MSRV; no locked normal/build dependency needs more"
# The crates with a workspace of their own (the C API, the Python package) build the core
# crate, so they cannot need less; they declare the same version.
for manifest in ppoe-ffi/Cargo.toml ppoe-py/Cargo.toml; do
  own=$(sed -n 's/^rust-version = "\(.*\)"$/\1/p' "$manifest")
  [ "$own" = "$MSRV" ] || die "$manifest declares rust-version '${own}', the workspace $MSRV"
done

# --- 2. Build and test with that compiler -------------------------------------------------------
matches() { "$@" -V 2>/dev/null | grep -q "^rustc $MM\.[0-9]"; }
CARGO=(); RUSTC_ENV=(); RUSTC_V=""
if command -v rustup >/dev/null; then
  for tc in "$MM.0" "$MM" stable; do
    if matches rustc "+$tc"; then CARGO=(cargo "+$tc"); RUSTC_V=$(rustc "+$tc" -V); break; fi
  done
fi
if [ ${#CARGO[@]} -eq 0 ] && [ -x /usr/bin/cargo ] && matches /usr/bin/rustc; then
  CARGO=(/usr/bin/cargo); RUSTC_ENV=(RUSTC=/usr/bin/rustc); RUSTC_V=$(/usr/bin/rustc -V)
fi
[ ${#CARGO[@]} -gt 0 ] || die "no rustc $MM.x found (rustup toolchain install $MM.0)"
log "toolchain: ${CARGO[*]} with $RUSTC_V"

# Host flags of other steps must not leak in (a newer compiler's flags may not exist here).
unset RUSTFLAGS CARGO_ENCODED_RUSTFLAGS CARGO_BUILD_RUSTFLAGS RUSTDOCFLAGS
export CARGO_TARGET_DIR="${MSRV_TARGET_DIR:-$ROOT/target}"
PKGS=()
while read -r name; do [ "$name" = ppoe ] || PKGS+=(-p "$name"); done < <(
  cargo metadata --no-deps --format-version 1 | python3 -c '
import json, sys
m = json.load(sys.stdin)
for p in m["packages"]:
    if p["id"] in m["workspace_members"] and p["publish"] != []:
        print(p["name"])
')
run() { log "+ $*"; env "${RUSTC_ENV[@]}" "${CARGO[@]}" "$@"; }
run build --locked -p ppoe
run test --locked -p ppoe
[ ${#PKGS[@]} -eq 0 ] || run build --locked "${PKGS[@]}"
log "ok: rust-version $MSRV builds and the core crate's tests pass with rustc $MM"
