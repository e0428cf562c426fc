#!/usr/bin/env bash
# scripts/bench-report.sh -- regenerate BENCHMARKS.md (host criterion medians, baselines
# measured in the same run, arithmetic bound, callgrind instruction counts, Cortex-M4F
# numbers from scripts/firmware.sh). Not run by CI (noisy and slow: ~10-20 min).
#
# Steps (all results of ONE run; nothing is copied from earlier runs):
#   1. criterion, one invocation: cargo bench --bench ops -- --warm-up-time 1
#      --measurement-time 3 (medians read from <target>/criterion/**/new/estimates.json;
#      the old results are deleted first);
#   2. pytransform3d 3.17.0 baselines: scripts/bench_pytransform3d.py in a venv
#      ($PPOE_BENCH_VENV, default /tmp/venv-bench-ppoe) made from
#      test_data/reference/requirements.txt; if that fails the report says so;
#   3. flop count and scalar-peak bound: scripts/flops.py with the clock of /proc/cpuinfo;
#   4. valgrind --tool=callgrind instructions per call of every op (the bench binary's
#      PPOE_CALLGRIND mode, see benches/ops.rs);
#   5. scripts/firmware.sh (all four boards, must pass) and its M4F -icount run, plus nm /
#      objdump of the M4F firmware (code size, call graph, allocator symbols).
#
# Usage: scripts/bench-report.sh [--no-firmware] [--no-callgrind] [--no-python]
#                                [--firmware-args "ARGS"]
# Env: BENCH_TARGET_DIR (default target/bench-report), PPOE_BENCH_VENV
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
FIRMWARE=1; CALLGRIND=1; PYTHON=1; FW_ARGS=""
while [ $# -gt 0 ]; do
  case "$1" in
    --no-firmware) FIRMWARE=0 ;;
    --no-callgrind) CALLGRIND=0 ;;
    --no-python) PYTHON=0 ;;
    --firmware-args) FW_ARGS=$2; shift ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "bench-report: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
TD=${BENCH_TARGET_DIR:-$ROOT/target/bench-report}
OUT=$(mktemp -d /tmp/ppoe-bench-report.XXXXXX)
VENV=${PPOE_BENCH_VENV:-/tmp/venv-bench-ppoe}
echo "bench-report: work dir $OUT, cargo target dir $TD"

# --- machine -------------------------------------------------------------------------------
python3 - "$OUT/machine.json" <<'EOF'
import json, re, subprocess, sys, datetime
ls = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
get = lambda k: (re.search(r"^%s:\s*(.*)$" % re.escape(k), ls, re.M) or [None, "?"])[1]
mhz = (re.search(r"^cpu MHz\s*:\s*([\d.]+)", open("/proc/cpuinfo").read(), re.M) or [None, "?"])[1]
sh = lambda *a: subprocess.run(list(a), capture_output=True, text=True).stdout.strip()
git = sh("git", "describe", "--always", "--dirty")
json.dump({"model": get("Model name"), "cores": get("CPU(s)"), "mhz": mhz,
           "rustc": sh("rustc", "-V"), "git": "git " + git,
           "loadavg": " ".join(open("/proc/loadavg").read().split()[:3]),
           "date": datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M")}, open(sys.argv[1], "w"))
EOF
GHZ=$(python3 -c "import json;print(float(json.load(open('$OUT/machine.json'))['mhz'])/1000)")

# --- 1. criterion --------------------------------------------------------------------------
echo "---- criterion (one run, --warm-up-time 1 --measurement-time 3)"
rm -rf "$TD/criterion"
CARGO_TARGET_DIR=$TD cargo bench --bench ops -- --warm-up-time 1 --measurement-time 3 \
  | grep -E '^[a-z_0-9/]+ +time:' || true
[ -d "$TD/criterion" ] || { echo "bench-report: criterion produced nothing" >&2; exit 1; }
echo "$TD/criterion" >"$OUT/criterion_dir"
BIN=$(CARGO_TARGET_DIR=$TD cargo bench --bench ops --no-run --message-format=json 2>/dev/null \
  | python3 -c "import json,sys
for l in sys.stdin:
    m=json.loads(l)
    if m.get('reason')=='compiler-artifact' and m['target']['name']=='ops' and m.get('executable'): print(m['executable'])" | tail -1)

# --- 2. pytransform3d ----------------------------------------------------------------------
if [ $PYTHON = 1 ]; then
  echo "---- pytransform3d ($VENV)"
  if { [ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"; } &&
     "$VENV/bin/pip" install -q -r test_data/reference/requirements.txt &&
     "$VENV/bin/python" scripts/bench_pytransform3d.py >"$OUT/pytransform3d.json"; then
    cat "$OUT/pytransform3d.json"
  else
    echo '{"error": "the Python venv with test_data/reference/requirements.txt could not be set up or the script failed"}' >"$OUT/pytransform3d.json"
  fi
else
  echo '{"error": "skipped (--no-python)"}' >"$OUT/pytransform3d.json"
fi

# --- 3. flops ------------------------------------------------------------------------------
python3 scripts/flops.py 6 --ghz "$GHZ" >"$OUT/flops.json"

# --- 4. callgrind --------------------------------------------------------------------------
if [ $CALLGRIND = 1 ] && command -v valgrind >/dev/null; then
  echo "---- callgrind ($BIN)"
  python3 scripts/bench_report.py callgrind "$BIN" "$OUT/callgrind.json" || rm -f "$OUT/callgrind.json"
fi

# --- 5. firmware ---------------------------------------------------------------------------
if [ $FIRMWARE = 1 ]; then
  echo "---- firmware (scripts/firmware.sh $FW_ARGS)"
  FWTD=${FIRMWARE_TARGET_DIR:-$ROOT/examples/firmware/target}
  rm -f "$FWTD/firmware-logs/thumbv7em-none-eabihf-icount.txt"
  # shellcheck disable=SC2086
  if scripts/firmware.sh $FW_ARGS >"$OUT/firmware.log" 2>&1; then
    python3 scripts/bench_report.py firmware "$FWTD" "$OUT/firmware.json"
  else
    echo "bench-report: scripts/firmware.sh failed (log: $OUT/firmware.log); no firmware numbers" >&2
  fi
  sed -n '/firmware summary/,$p' "$OUT/firmware.log"
fi

# --- render --------------------------------------------------------------------------------
python3 scripts/bench_report.py render "$OUT" >BENCHMARKS.md
echo "bench-report: wrote BENCHMARKS.md (inputs kept in $OUT)"
