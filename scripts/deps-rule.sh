#!/usr/bin/env bash
# scripts/deps-rule.sh -- the core crate's normal dependencies: its direct ones must be exactly
# approx, heapless, libm and num-traits (heapless brings its own: hash32, byteorder,
# stable_deref_trait; num-traits brings libm). Prints the full normal tree, fails otherwise.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

want="approx heapless libm num-traits"
echo "full normal dependency tree of ppoe (all targets):"
cargo tree -p ppoe -e normal --target all
got=$(cargo tree -p ppoe -e normal --target all --depth 1 --prefix depth --format '{p}' \
      | sed -n 's/^1\([^ ]*\) .*/\1/p' | sort -u | tr '\n' ' ')
got=${got% }
echo "direct normal dependencies: $got"
if [ "$got" != "$want" ]; then
  echo "ERROR: ppoe's direct normal dependencies must be exactly: $want" >&2
  exit 1
fi
