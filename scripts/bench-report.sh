#!/usr/bin/env bash
# scripts/bench-report.sh -- regenerate BENCHMARKS.md (host criterion medians, baselines
# measured in the same run, arithmetic bound, callgrind instruction counts, Cortex-M4F
# numbers from scripts/firmware.sh). Not run by CI (noisy and slow: ~10-15 min).
#
# Steps (all results of ONE run; nothing is copied from earlier runs, except the
# "Firmware targets" section, kept from the current BENCHMARKS.md as it stands):
#   1. criterion, one invocation: cargo bench --bench ops --bench rank1 -- --warm-up-time 1
#      --measurement-time 3 (medians read from <target>/criterion/**/new/estimates.json;
#      the old results are deleted first);
#  1b. the batch benchmarks again built with -C target-cpu=x86-64-v3, if the CPU has it
#      (reported beside the default target's, not a target);
#  1c. the batch benchmarks built with the core in one codegen unit, alternating with the
#      default build in rounds (reported, not a target);
#   2. Pinocchio's forwardKinematics on the seed robot and test_data/urdf/arm7.urdf: pip
#      package `pin` in a venv ($PPOE_PIN_VENV, default <target>/pin-venv), the ops binary
#      writes the robots as a C++ header (PPOE_PINOCCHIO_EXPORT), benches/pinocchio/
#      fk_bench.cpp is built with g++ -O3 (default target, as ours) and checks Pinocchio's
#      tip pose against ppoe's FK before timing (a mismatch fails the run); without pip, g++
#      or the package the section says why and is skipped;
#   3. pytransform3d 3.17.0 baselines: scripts/bench_pytransform3d.py in a venv
#      ($PPOE_BENCH_VENV, default /tmp/venv-bench-ppoe) made from
#      test_data/reference/requirements.txt; if that fails the report says so;
#   4. the fit benchmark: cargo run --release -p ppoe-fit --example fit_bench (skipped
#      with a message if the example is not in the tree);
#   5. flop count and scalar-peak bound: scripts/flops.py with the clock of /proc/cpuinfo;
#   6. valgrind --tool=callgrind instructions per call of every op (the bench binary's
#      PPOE_CALLGRIND mode, see benches/ops.rs);
#   7. scripts/firmware.sh (all four boards, must pass) and its M4F -icount run, plus nm /
#      objdump of the M4F firmware (code size, call graph, allocator symbols).
#
# Usage: scripts/bench-report.sh [--no-firmware] [--no-callgrind] [--no-python]
#                                [--no-pinocchio] [--no-fit] [--firmware-args "ARGS"]
#                                [--criterion-args "ARGS"]
#   --criterion-args  replaces "--warm-up-time 1 --measurement-time 3" (e.g. a filter and
#                     shorter times for a quick check; the report then covers less)
# Env: BENCH_TARGET_DIR (default target/bench-report), PPOE_BENCH_VENV, PPOE_PIN_VENV
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
FIRMWARE=1; CALLGRIND=1; PYTHON=1; PINOCCHIO=1; FIT=1; FW_ARGS=""
CRIT_ARGS="--warm-up-time 1 --measurement-time 3"
while [ $# -gt 0 ]; do
  case "$1" in
    --no-firmware) FIRMWARE=0 ;;
    --no-callgrind) CALLGRIND=0 ;;
    --no-python) PYTHON=0 ;;
    --no-pinocchio) PINOCCHIO=0 ;;
    --no-fit) FIT=0 ;;
    --criterion-args) CRIT_ARGS=$2; shift ;;
    --firmware-args) FW_ARGS=$2; shift ;;
    -h|--help) sed -n '2,33p' "$0"; exit 0 ;;
    *) echo "bench-report: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
TD=${BENCH_TARGET_DIR:-$ROOT/target/bench-report}
OUT=$(mktemp -d /tmp/ppoe-bench-report.XXXXXX)
VENV=${PPOE_BENCH_VENV:-/tmp/venv-bench-ppoe}
PIN_VENV=${PPOE_PIN_VENV:-$TD/pin-venv}
STATUS=0
echo "bench-report: work dir $OUT, cargo target dir $TD"
# The firmware-targets section is kept as BENCHMARKS.md has it now (read before rewriting).
sed -n '/^## Firmware targets/,$p' BENCHMARKS.md >"$OUT/firmware_targets.md" || true

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
# The path of the ops benchmark's binary, built with cargo arguments "$@".
ops_exe() {
  CARGO_TARGET_DIR=$TD cargo bench "$@" --bench ops --no-run --message-format=json 2>/dev/null \
    | python3 -c "import json,sys
for l in sys.stdin:
    m=json.loads(l)
    if m.get('reason')=='compiler-artifact' and m['target']['name']=='ops' and m.get('executable'): print(m['executable'])" | tail -1
}
echo "---- criterion (one run, $CRIT_ARGS)"
rm -rf "$TD/criterion"
# shellcheck disable=SC2086
CARGO_TARGET_DIR=$TD cargo bench --bench ops --bench rank1 -- $CRIT_ARGS \
  | grep -E '^[a-z_0-9/]+ +time:' || true
[ -d "$TD/criterion" ] || { echo "bench-report: criterion produced nothing" >&2; exit 1; }
echo "$TD/criterion" >"$OUT/criterion_dir"
echo "$CRIT_ARGS" >"$OUT/criterion_args"
BIN=$(ops_exe)

# --- 1a. f32/f64 interleaved in one process (benches/lanes_ratio.rs) -------------------------
# Criterion times f32 and f64 seconds apart, so load from other work can favour either; this
# alternates short f32 and f64 batches round by round and prints the median per-round ratio;
# then, the same way, f64 ppoe against the two nalgebra ports on the dense cases (`ports`).
echo "---- f32/f64 interleaved (cargo bench --bench lanes_ratio -- 201 2000)"
CARGO_TARGET_DIR=$TD cargo bench -q --bench lanes_ratio -- 201 2000 >"$OUT/lanes_ratio.txt" ||
  echo "error: cargo bench --bench lanes_ratio failed" >"$OUT/lanes_ratio.txt"
cat "$OUT/lanes_ratio.txt"

# --- 1b. the batch benchmarks built for x86-64-v3 (reported, not a target) -----------------
# Same criterion arguments, the batch_ benchmarks only, their own target dir; only where the
# CPU has the v3 features (AVX2, FMA, BMI2, MOVBE: the binary would not run otherwise). Rust
# contracts no a·b + c into an FMA, so the results are the default build's bits.
if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo && grep -qw bmi2 /proc/cpuinfo &&
   grep -qw movbe /proc/cpuinfo; then
  echo "---- criterion, batch_ benchmarks, -C target-cpu=x86-64-v3"
  rm -rf "$TD-v3/criterion"
  # shellcheck disable=SC2086
  RUSTFLAGS="-C target-cpu=x86-64-v3" CARGO_TARGET_DIR=$TD-v3 cargo bench --bench ops -- $CRIT_ARGS batch_ \
    | grep -E '^[a-z_0-9/]+ +time:' || true
  echo "$TD-v3/criterion" >"$OUT/criterion_v3_dir"
else
  echo "bench-report: this CPU lacks an x86-64-v3 feature; no v3 section" >&2
fi

# --- 1c. the core compiled in one codegen unit (reported, not a target) -------------------
# Cargo's release and bench profiles compile a crate in 16 codegen units, which rustc's
# crate-local ThinLTO then optimises once more; a project that sets codegen-units = 1 gets
# one optimisation pipeline. The ops benchmark again with the ppoe package (the core and
# its benchmarks) in one unit, in the same target dir (only those two rebuild), the two
# binaries alternating round by round on the batch_ benchmarks (batch and single call).
CGU_ROUNDS=5
BIN_CGU1=$(ops_exe --config 'profile.bench.package.ppoe.codegen-units=1')
if [ -x "$BIN_CGU1" ] && [ "$BIN_CGU1" != "$BIN" ]; then
  echo "---- batch_ benchmarks, default against codegen-units = 1, $CGU_ROUNDS alternating rounds"
  for r in $(seq 1 $CGU_ROUNDS); do
    echo "round $r"
    for build in default one_unit; do
      exe=$BIN; [ $build = one_unit ] && exe=$BIN_CGU1
      echo "build $build"
      CRITERION_HOME="$OUT/criterion-cgu" "$exe" --bench --warm-up-time 0.3 --measurement-time 0.5 \
        'batch_(seed|7dof)/(batch|single)/' 2>/dev/null | grep -E '^[a-z_0-9/]+ +time:' || true
    done
  done >"$OUT/codegen_units.txt"
  cat "$OUT/codegen_units.txt"
else
  echo "error: the one-codegen-unit build failed" >"$OUT/codegen_units.txt"
fi

# --- 2. Pinocchio -------------------------------------------------------------------------
# Prints why it cannot run (return 2) or the harness's lines; any other failure (the check
# against ppoe's FK, a crash) returns another non-zero status.
pinocchio_step() {
  local prefix
  command -v g++ >/dev/null || { echo "g++ is not installed"; return 2; }
  if [ ! -x "$PIN_VENV/bin/python" ] && ! python3 -m venv "$PIN_VENV" >/dev/null 2>&1; then
    echo "python3 -m venv failed"; return 2
  fi
  "$PIN_VENV/bin/pip" install -q "pin==4.1.0" "cmeel-eigen==3.4.1" >"$OUT/pin-install.log" 2>&1 ||
    { echo "pip install pin cmeel-eigen failed (log: $OUT/pin-install.log)"; return 2; }
  prefix=$(echo "$PIN_VENV"/lib/python3*/site-packages/cmeel.prefix)
  [ -f "$prefix/include/pinocchio/algorithm/kinematics.hpp" ] ||
    { echo "no Pinocchio headers under $prefix"; return 2; }
  mkdir -p "$OUT/pinocchio"
  PPOE_PINOCCHIO_EXPORT=$OUT/pinocchio "$BIN" >/dev/null || { echo "header export failed"; return 1; }
  # The definitions of Pinocchio's CMake interface; header-only (no PINOCCHIO_ENABLE_
  # TEMPLATE_INSTANTIATION), so forwardKinematics is compiled with these flags, as ours is.
  g++ -O3 -std=c++17 -DNDEBUG -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -I"$OUT/pinocchio" -I"$prefix/include" \
    -I"$prefix/include/eigen3" benches/pinocchio/fk_bench.cpp -o "$OUT/pinocchio/fk_bench" \
    -Wl,-rpath,"$prefix/lib" >"$OUT/pinocchio/build.log" 2>&1 ||
    { echo "g++ failed (log: $OUT/pinocchio/build.log)"; return 2; }
  echo "versions pin=$("$PIN_VENV/bin/python" -c 'import pinocchio; print(pinocchio.__version__)' 2>/dev/null) gxx=$(g++ -dumpfullversion)"
  "$OUT/pinocchio/fk_bench" 101 20000 || return
  if [ $CALLGRIND = 1 ] && command -v valgrind >/dev/null; then
    python3 scripts/bench_report.py pinocchio-ir "$OUT/pinocchio/fk_bench" ||
      echo "pinocchio_ir: callgrind of the harness failed (no instruction counts)"
  fi
}
if [ $PINOCCHIO = 1 ]; then
  echo "---- Pinocchio ($PIN_VENV)"
  rc=0; pinocchio_step >"$OUT/pinocchio.txt" 2>&1 || rc=$?
  cat "$OUT/pinocchio.txt"
  if [ $rc = 2 ]; then
    echo "bench-report: Pinocchio section skipped: $(cat "$OUT/pinocchio.txt")" >&2
    echo "error: skipped: $(tr '\n' ' ' <"$OUT/pinocchio.txt")" >"$OUT/pinocchio.txt"
  elif [ $rc != 0 ]; then
    echo "bench-report: the Pinocchio step FAILED (status $rc, see above)" >&2; STATUS=1
    echo "error: FAILED (status $rc; the check against ppoe's FK or the harness): $(tr '\n' ' ' <"$OUT/pinocchio.txt")" >"$OUT/pinocchio.txt"
  fi
else
  echo "error: skipped (--no-pinocchio)" >"$OUT/pinocchio.txt"
fi

# --- 2a. the batch against Pinocchio in alternating rounds ---------------------------------
# The criterion medians and the harness above are timed minutes apart, and the load from
# other work on a shared machine drifts in between (the seed's batch/Pinocchio ratio went
# from 0.90 to 1.33 between two runs of the same binaries). Here the two alternate round by
# round: the harness with 21 batches, then criterion's batch_ f64 benchmarks for 1 s each;
# the report takes the median of the rounds' own ratios.
ALT_ROUNDS=11
if [ -x "$OUT/pinocchio/fk_bench" ] && ! grep -q '^error' "$OUT/pinocchio.txt"; then
  echo "---- batch / Pinocchio FK, $ALT_ROUNDS alternating rounds"
  for r in $(seq 1 $ALT_ROUNDS); do
    echo "round $r"
    "$OUT/pinocchio/fk_bench" 21 20000 | grep '^pinocchio_batch' || true
    CRITERION_HOME="$OUT/criterion-alternating" "$BIN" --bench --warm-up-time 0.5 \
      --measurement-time 1 'batch_(seed|7dof)/batch/f64' 2>/dev/null | grep -E '^[a-z_0-9/]+ +time:' || true
  done >"$OUT/batch_alternating.txt"
  cat "$OUT/batch_alternating.txt"
else
  echo "error: not measured (no Pinocchio harness in this run)" >"$OUT/batch_alternating.txt"
fi

# --- 3. pytransform3d ----------------------------------------------------------------------
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

# --- 3b. the Python package's batch (the wheel of scripts/python-check.sh) -------------------
PY_CHECK_VENV=$ROOT/target/python-check/venv
if [ $PYTHON = 1 ] && [ -x "$PY_CHECK_VENV/bin/python" ] &&
   "$PY_CHECK_VENV/bin/python" -c "import ppoe, pytransform3d" 2>/dev/null; then
  echo "---- Python package batch (ppoe-py/benches/batch.py)"
  "$PY_CHECK_VENV/bin/python" ppoe-py/benches/batch.py >"$OUT/python_batch.json" ||
    echo '{"error": "ppoe-py/benches/batch.py failed"}' >"$OUT/python_batch.json"
  cat "$OUT/python_batch.json"
else
  echo '{"error": "no wheel venv: run scripts/python-check.sh first (or --no-python)"}' >"$OUT/python_batch.json"
fi

# --- 4. fit benchmark ----------------------------------------------------------------------
if [ $FIT = 0 ]; then
  echo "error: skipped (--no-fit)" >"$OUT/fit_bench.txt"
elif [ -f ppoe-fit/examples/fit_bench.rs ]; then
  echo "---- fit benchmark (cargo run --release -p ppoe-fit --example fit_bench)"
  if CARGO_TARGET_DIR=$TD cargo run -q --release -p ppoe-fit --example fit_bench >"$OUT/fit_bench.txt"; then
    grep '^fit_bench ' "$OUT/fit_bench.txt" || true
  else
    echo "bench-report: the fit benchmark failed" >&2; STATUS=1
    echo "error: cargo run --release -p ppoe-fit --example fit_bench failed" >"$OUT/fit_bench.txt"
  fi
else
  echo "bench-report: ppoe-fit/examples/fit_bench.rs is not in this tree; no fit section" >&2
  echo "error: ppoe-fit/examples/fit_bench.rs is not in this tree" >"$OUT/fit_bench.txt"
fi

# --- 5. flops ------------------------------------------------------------------------------
python3 scripts/flops.py 6 --ghz "$GHZ" >"$OUT/flops.json"

# --- 6. callgrind --------------------------------------------------------------------------
if [ $CALLGRIND = 1 ] && command -v valgrind >/dev/null; then
  echo "---- callgrind ($BIN)"
  python3 scripts/bench_report.py callgrind "$BIN" "$OUT/callgrind.json" || rm -f "$OUT/callgrind.json"
fi

# --- 7. firmware ---------------------------------------------------------------------------
if [ $FIRMWARE = 1 ]; then
  echo "---- firmware (scripts/firmware.sh $FW_ARGS)"
  FWTD=${FIRMWARE_TARGET_DIR:-$ROOT/examples/firmware/target}
  rm -f "$FWTD/firmware-logs/thumbv7em-none-eabihf-icount.txt"
  # shellcheck disable=SC2086
  if scripts/firmware.sh $FW_ARGS >"$OUT/firmware.log" 2>&1; then
    python3 scripts/bench_report.py firmware "$FWTD" "$OUT/firmware.json"
    cp "$FWTD/firmware-figures.md" "$OUT/firmware_figures_this_run.md" 2>/dev/null || true
  else
    echo "bench-report: scripts/firmware.sh failed (log: $OUT/firmware.log); no firmware numbers" >&2
  fi
  sed -n '/firmware summary/,$p' "$OUT/firmware.log"
fi

# --- render --------------------------------------------------------------------------------
# Written whole, then renamed: an interrupted run leaves the old BENCHMARKS.md.
python3 scripts/bench_report.py render "$OUT" >"$OUT/BENCHMARKS.md"
cp "$OUT/BENCHMARKS.md" BENCHMARKS.md.tmp && mv BENCHMARKS.md.tmp BENCHMARKS.md
echo "bench-report: wrote BENCHMARKS.md (inputs kept in $OUT)"
exit $STATUS
