#!/usr/bin/env bash
# scripts/accuracy.sh -- regenerate ACCURACY.md at the repository root: the PPOE covariance
# against Monte Carlo on the seed and test robots (2nd order and the 4th-order option, joint
# noise x1/16 ... x16), the Barfoot & Furgale two-pose compounding sweep, and f32 against
# f64 over the golden set (examples/accuracy.rs), then the noise-model fit section
# (ppoe-fit/examples/fit_accuracy.rs). In release; fixed seeds, so the output
# is the same on every run.
#
# Usage: scripts/accuracy.sh [--samples N]    (default N = 100000 per Monte Carlo row)
# Extra arguments are passed to the example (see `cargo run --example accuracy -- --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
cargo run --release --quiet --example accuracy -- --out ACCURACY.md "$@"
echo "ACCURACY.md written in $(( $(date +%s) - start )) s" >&2
# Section 4, the noise-model fit (`ppoe fit`): appended by its own example (fixed seeds).
cargo run --release --quiet -p ppoe-fit --example fit_accuracy -- --append ACCURACY.md
echo "ACCURACY.md section 4 (noise model fit) written in $(( $(date +%s) - start )) s" >&2
