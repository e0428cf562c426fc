#!/usr/bin/env bash
# Runs every fuzz target for a short fixed time from a temporary copy of the committed
# seed corpus (fuzz/corpus/<target>); fails on any crash. See FUZZING.md.
#
#   scripts/fuzz-smoke.sh                 # 30 s per target
#   FUZZ_SECONDS=60 scripts/fuzz-smoke.sh
#   FUZZ_TARGETS="urdf eigen" scripts/fuzz-smoke.sh
#   FUZZ_SEED=1 FUZZ_RUNS=100000 scripts/fuzz-smoke.sh   # reproducible: fixed seed and count
#                                                        # (FUZZ_SECONDS stays an upper bound)
#   FUZZ_CORPUS=/var/tmp/ppoe-corpus scripts/fuzz-smoke.sh  # fuzz from (and grow) a kept
#                                                        # corpus <dir>/<target>, seeded from the
#                                                        # committed one when it does not exist:
#                                                        # a long campaign continued in later runs
#   FUZZ_SANITIZER=none scripts/fuzz-smoke.sh   # without AddressSanitizer (default: address):
#                                                        # the fuzzed crates forbid `unsafe`; debug
#                                                        # assertions and overflow checks stay on
#                                                        # (FUZZING.md: when and why)
#
# Crash inputs are kept in fuzz/artifacts/<target>/. Prints the executions per target.
set -euo pipefail

FUZZ_SECONDS="${FUZZ_SECONDS:-30}"
FUZZ_TARGETS="${FUZZ_TARGETS:-urdf core_f64 core_f32 eigen table noise mesh}"
FUZZ_MAX_LEN="${FUZZ_MAX_LEN:-65536}"
FUZZ_SUMMARY="${FUZZ_SUMMARY:-}" # if set, "target executions rc seconds" lines are appended to it
FUZZ_SEED="${FUZZ_SEED:-}"       # libFuzzer -seed (default: random)
FUZZ_RUNS="${FUZZ_RUNS:-}"       # libFuzzer -runs (default: unbounded, time only)
FUZZ_CORPUS="${FUZZ_CORPUS:-}"   # an absolute corpus directory to keep (default: a temporary copy)
FUZZ_SANITIZER="${FUZZ_SANITIZER:-address}" # cargo fuzz --sanitizer (address or none)
extra=()
[ -n "$FUZZ_SEED" ] && extra+=("-seed=$FUZZ_SEED")
[ -n "$FUZZ_RUNS" ] && extra+=("-runs=$FUZZ_RUNS")

root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root/fuzz"

if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzz: installing cargo-fuzz" >&2
    cargo install cargo-fuzz --locked
fi
if ! rustup run nightly rustc --version >/dev/null 2>&1; then
    echo "fuzz: the nightly toolchain is needed (rustup toolchain install nightly)" >&2
    exit 2
fi

start=$(date +%s)
cargo +nightly fuzz build --sanitizer "$FUZZ_SANITIZER"

work="$(mktemp -d "${TMPDIR:-/tmp}/ppoe-fuzz.XXXXXX")"
trap 'rm -rf "$work"' EXIT

status=0
printf '%-10s %14s %8s %s\n' target executions seconds result
for target in $FUZZ_TARGETS; do
    mkdir -p "artifacts/$target"
    corpus="$work/$target"
    if [ -n "$FUZZ_CORPUS" ]; then
        corpus="$FUZZ_CORPUS/$target"
    fi
    if [ ! -d "$corpus" ]; then
        mkdir -p "$corpus"
        cp -R "corpus/$target/." "$corpus/"
    fi
    log="$work/$target.log"
    t0=$(date +%s)
    set +e
    cargo +nightly fuzz run --sanitizer "$FUZZ_SANITIZER" "$target" "$corpus" -- \
        -max_total_time="$FUZZ_SECONDS" -max_len="$FUZZ_MAX_LEN" -timeout=30 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="artifacts/$target/" \
        ${extra[@]+"${extra[@]}"} >"$log" 2>&1
    rc=$?
    set -e
    t1=$(date +%s)
    execs=$(grep -E '^stat::number_of_executed_units:' "$log" | tail -1 | awk '{print $2}')
    execs="${execs:-0}"
    if [ "$rc" -eq 0 ]; then
        result="ok"
    else
        result="CRASH (exit $rc)"
        status=1
        echo "---- $target: the failure ----" >&2
        grep -m1 -A3 "panicked at" "$log" >&2 || true
        echo "---- $target: last 60 lines of the log ----" >&2
        tail -60 "$log" >&2
        ls -1 "artifacts/$target" >&2 || true
    fi
    printf '%-10s %14s %8s %s\n' "$target" "$execs" "$((t1 - t0))" "$result"
    if [ -n "$FUZZ_SUMMARY" ]; then
        echo "$target $execs $rc $((t1 - t0))" >>"$FUZZ_SUMMARY"
    fi
done
echo "total: $(( $(date +%s) - start )) s"
exit $status
