#!/usr/bin/env bash
# scripts/demo-check.sh -- the README's first command end to end: the seed example (release
# build) writes its three pictures into a temporary directory; each must be non-empty.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cargo run --release -p ppoe-cli -- demo --out "$out"
for f in ppoe-seed.png ppoe-seed.gif ppoe-seed.html; do
  test -s "$out/$f" || { echo "demo-check: $f missing or empty" >&2; exit 1; }
done
ls -l "$out"
