#!/usr/bin/env bash
# scripts/publish-check.sh -- can every publishable crate be published, and used from its
# package alone (no repository around it)?
#
#  1. `cargo publish --dry-run` of all publishable workspace members together (each is
#     packaged, then built from its package against the packages of the others);
#  2. every .crate is below crates.io's 10 MB limit and ships LICENSE-APACHE and LICENSE-MIT
#     identical to the repository's (the full Apache-2.0 text, the MIT text with its
#     copyright line);
#  3. each .crate is unpacked into a temporary directory outside the repository and
#     `cargo test` runs there, with [patch.crates-io] pointing every publishable crate at its
#     unpacked package (they are not on crates.io yet);
#  4. the `ppoe` command is installed from the unpacked ppoe-cli package
#     (`cargo install --path`) and runs: `ppoe table` on the seed URDF the package ships,
#     and `ppoe demo` (the build-time table, the embedded font, the pictures).
#
# The publishable crates are the workspace members whose `publish` is not false
# (`cargo metadata`), so new crates are checked without editing this script.
#
# Usage: scripts/publish-check.sh
# Env: PUBLISH_CHECK_TARGET_DIR  cargo target dir for steps 3-4 (default: the repository's
#                                target/, so the dependencies already built are reused)
#      PUBLISH_CHECK_KEEP=1      keep the temporary directory (its path is printed)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

log() { echo "publish-check: $*" >&2; }
die() { echo "publish-check: ERROR: $*" >&2; exit 1; }

TMP=$(mktemp -d "${TMPDIR:-/tmp}/ppoe-publish-check.XXXXXX")
if [ "${PUBLISH_CHECK_KEEP:-0}" = 1 ]; then
  log "keeping $TMP"
else
  trap 'rm -rf "$TMP"' EXIT
fi
export CARGO_TARGET_DIR="${PUBLISH_CHECK_TARGET_DIR:-$ROOT/target}"

# name<TAB>version of each publishable workspace member.
mapfile -t CRATES < <(cargo metadata --no-deps --format-version 1 | python3 -c '
import json, sys
m = json.load(sys.stdin)
for p in m["packages"]:
    if p["id"] in m["workspace_members"] and p["publish"] != []:
        print(p["name"] + "\t" + p["version"])
')
[ "${#CRATES[@]}" -gt 0 ] || die "no publishable crate found"
PKG_ARGS=()
for c in "${CRATES[@]}"; do PKG_ARGS+=(-p "${c%%$'\t'*}"); done
log "publishable: ${PKG_ARGS[*]}"

# The dry run builds each package against the others' packages from a temporary
# registry. Cargo treats registry packages as immutable: it reuses a package it unpacked
# under $CARGO_HOME/registry/src/ before, and the build of it in the target directory,
# when the version is the same, so a second run would build stale sources. Remove both.
CARGO_HOME_DIR="${CARGO_HOME:-$HOME/.cargo}"
for c in "${CRATES[@]}"; do
  name=${c%%$'\t'*}; version=${c#*$'\t'}
  rm -rf "$CARGO_HOME_DIR"/registry/src/*/"$name-$version" \
    "$CARGO_HOME_DIR"/registry/cache/*/"$name-$version.crate" \
    "$CARGO_TARGET_DIR"/debug/.fingerprint/"$name"-*
done

# 1. Package and verify together. --allow-dirty: the check is about the package's contents,
#    which cargo takes from the work tree either way.
cargo publish --dry-run --allow-dirty "${PKG_ARGS[@]}"

# 2. Size and licences; unpack. (The dry run keeps its .crate files in temporary places:
#    write them to target/package/ again, unverified since step 1 verified the same files.)
cargo package --no-verify --allow-dirty "${PKG_ARGS[@]}"
PATCH="$TMP/patch.toml"
echo "[patch.crates-io]" >"$PATCH"
for c in "${CRATES[@]}"; do
  name=${c%%$'\t'*}; version=${c#*$'\t'}
  crate="$CARGO_TARGET_DIR/package/$name-$version.crate"
  [ -f "$crate" ] || die "$crate was not written"
  size=$(stat -c %s "$crate")
  [ "$size" -lt 10000000 ] || die "$crate is $size bytes (crates.io accepts < 10 MB)"
  tar -xzf "$crate" -C "$TMP"
  dir="$TMP/$name-$version"
  for lic in LICENSE-APACHE LICENSE-MIT; do
    [ -f "$dir/$lic" ] || die "$name: $lic is not in the package"
    cmp -s "$dir/$lic" "$ROOT/$lic" || die "$name: $lic differs from the repository's"
  done
  grep -q "END OF TERMS AND CONDITIONS" "$dir/LICENSE-APACHE" \
    || die "$name: LICENSE-APACHE is not the full Apache-2.0 text"
  grep -q "^Copyright (c) " "$dir/LICENSE-MIT" || die "$name: LICENSE-MIT has no copyright line"
  grep -q "^Permission is hereby granted" "$dir/LICENSE-MIT" \
    || die "$name: LICENSE-MIT is not the MIT text"
  echo "$name = { path = \"$dir\" }" >>"$PATCH"
  log "$name $version: $size bytes, licences ok"
done

# 3. Each package's own tests, from the unpacked package.
for c in "${CRATES[@]}"; do
  name=${c%%$'\t'*}; version=${c#*$'\t'}
  log "cargo test in the unpacked $name-$version"
  (cd "$TMP/$name-$version" && cargo test --config "$PATCH")
done

# 4. Install the command from its package and run it.
cli=""
for c in "${CRATES[@]}"; do [ "${c%%$'\t'*}" = ppoe-cli ] && cli="$TMP/ppoe-cli-${c#*$'\t'}"; done
if [ -n "$cli" ]; then
  log "cargo install --path $cli"
  cargo install --path "$cli" --root "$TMP/root" --config "$PATCH"
  ppoe="$TMP/root/bin/ppoe"
  "$ppoe" table --urdf "$cli/assets/seed.urdf" --base linkmount --tip tcp --name SEED \
    >"$TMP/seed_table.rs"
  grep -q "pub const SEED: ppoe::chain::Chain<f64, 6>" "$TMP/seed_table.rs" \
    || die "the installed 'ppoe table' printed no SEED table"
  mkdir "$TMP/demo"
  (cd "$TMP/demo" && "$ppoe" demo >"$TMP/demo.txt")
  for f in ppoe-seed.png ppoe-seed.gif; do
    [ -s "$TMP/demo/$f" ] || die "the installed 'ppoe demo' wrote no $f"
  done
  log "installed ppoe: table and demo ok"
fi
log "ok: ${#CRATES[@]} crates package, verify, test from their packages and ship the licences"
