#!/usr/bin/env bash
# Long fuzzing run: every target for FUZZ_SECONDS (default 3600 = 1 h) or FUZZ_RUNS
# executions, whichever comes first, from a temporary copy of the seed corpus, then one line
# per target appended to the table at the end of FUZZING.md (date, target, commit, measured
# seconds, executions, crashes). Fails on any crash (the table then records the crash count
# 1 for that target; see fuzz/artifacts/<target>/).
#
#   scripts/fuzz-long.sh
#   FUZZ_SECONDS=600 FUZZ_TARGETS="core_f64" scripts/fuzz-long.sh
#   FUZZ_RUNS=10000000 FUZZ_SECONDS=7200 FUZZ_TARGETS="urdf" scripts/fuzz-long.sh
#   FUZZ_SANITIZER=none ...   # no AddressSanitizer; the rows then say so
set -uo pipefail

export FUZZ_SECONDS="${FUZZ_SECONDS:-3600}"
root="$(cd "$(dirname "$0")/.." && pwd)"
summary="$(mktemp "${TMPDIR:-/tmp}/ppoe-fuzz-summary.XXXXXX")"
trap 'rm -f "$summary"' EXIT

FUZZ_SUMMARY="$summary" "$root/scripts/fuzz-smoke.sh"
status=$?

day="$(date -u +%Y-%m-%d)"
commit="$(git -C "$root" describe --always --dirty 2>/dev/null || echo unknown)"
while read -r target execs rc secs; do
    crashes=0
    [ "$rc" -ne 0 ] && crashes=1
    label="$target"
    [ "${FUZZ_SANITIZER:-address}" != address ] && label="$target (sanitizer ${FUZZ_SANITIZER})"
    printf '| %s | %s | %s | %s | %s | %s |\n' "$day" "$label" "$commit" "$secs" "$execs" "$crashes" \
        >>"$root/FUZZING.md"
done <"$summary"
exit $status
