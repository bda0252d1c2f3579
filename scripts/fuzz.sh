#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, -fsanitize=fuzzer,address,undefined) in
# build-fuzz/ and runs each for SECONDS (default 60) with -rss_limit_mb=2048 -timeout=1.
#
#   scripts/fuzz.sh [SECONDS]
#
# Environment: FUZZ_BUILD_DIR (default <repo>/build-fuzz), FUZZ_TARGETS (space-separated
# subset of the targets), FUZZ_JOBS (parallel build jobs, default 2), FUZZ_RUNS (also stop a
# target after this many executions, e.g. 1000000; default: time only), FUZZ_TIMEOUT
# (seconds per input taken as a hang, default 1; a loaded machine may need 3), FUZZ_PARALLEL
# (targets run at the same time, default 1). A FUZZ_BUILD_DIR that is already configured
# with LCPRELAX_FUZZ=ON is used as it is: only the fuzz targets are built there.
# Corpora live in $FUZZ_BUILD_DIR/corpus/<target>/ (seeded from tests/data on each run, and
# kept between runs); crashes in $FUZZ_BUILD_DIR/artifacts/, logs in $FUZZ_BUILD_DIR/logs/.
# Prints the executions of each target and exits 1 if any target found a crash, a hang
# (> 1 s per input), a leak or an allocation above 2 GB. tests/fuzz/README.md has the details.
set -euo pipefail

SECONDS_PER_TARGET=${1:-60}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${FUZZ_BUILD_DIR:-$ROOT/build-fuzz}
JOBS=${FUZZ_JOBS:-2}
RUNS=${FUZZ_RUNS:--1}
TIMEOUT=${FUZZ_TIMEOUT:-1}
ALL_TARGETS="fuzz_qps fuzz_siconos_lcp fuzz_siconos_fc2d fuzz_matrix_market fuzz_scene_json fuzz_trajectory_csv fuzz_qp_solve"
TARGETS=${FUZZ_TARGETS:-$ALL_TARGETS}

PARALLEL=${FUZZ_PARALLEL:-1}

if ! grep -q '^LCPRELAX_FUZZ:BOOL=ON' "$BUILD/CMakeCache.txt" 2>/dev/null; then
  cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DLCPRELAX_FUZZ=ON \
    -DLCPRELAX_BUILD_TESTS=OFF -DLCPRELAX_BUILD_BENCH=OFF -DLCPRELAX_BUILD_APPS=OFF \
    -DLCPRELAX_WITH_OPENMP=OFF -DLCPRELAX_WITH_PETSC=OFF -DLCPRELAX_WITH_CAIRO=OFF >/dev/null
fi
# shellcheck disable=SC2086
cmake --build "$BUILD" -j "$JOBS" --target $TARGETS

DATA=$ROOT/tests/data
# seed TARGET FILE...: copies the files (those under 64 KiB) into the target's corpus.
seed() {
  local dir=$BUILD/corpus/$1
  shift
  mkdir -p "$dir"
  for f in "$@"; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] && cp "$f" "$dir/$(basename "$f")" || true
  done
}
seed fuzz_qps "$DATA"/qps/*.qps "$DATA"/qps/malformed/*.qps "$DATA"/maros_meszaros/*.qps "$DATA"/fuzz/*.qps
seed fuzz_qp_solve "$DATA"/qps/*.qps "$DATA"/maros_meszaros/HS*.qps "$DATA"/maros_meszaros/GENHS28.qps \
  "$DATA"/maros_meszaros/QAFIRO.qps "$DATA"/maros_meszaros/TAME.qps "$DATA"/maros_meszaros/ZECEVIC2.qps "$DATA"/fuzz/*.qps
seed fuzz_siconos_lcp "$DATA"/siconos/lcp/*.dat "$DATA"/siconos/handmade/lcp_*.dat "$DATA"/siconos/malformed/lcp_*.dat "$DATA"/fuzz/lcp_*.dat
seed fuzz_siconos_fc2d "$DATA"/siconos/fc2d/*.dat "$DATA"/siconos/handmade/fc2d_*.dat "$DATA"/siconos/malformed/fc2d_*.dat "$DATA"/fuzz/fc2d_*.dat
seed fuzz_matrix_market "$DATA"/fuzz/seeds/*.mtx "$DATA"/fuzz/*.mtx
seed fuzz_scene_json "$DATA"/scenes/*.json "$DATA"/fuzz/*.json
seed fuzz_trajectory_csv "$DATA"/fuzz/seeds/*.csv "$DATA"/block/*.csv "$DATA"/fuzz/*.csv

dict_of() {
  case $1 in
    fuzz_qps | fuzz_qp_solve) echo qps.dict ;;
    fuzz_siconos_lcp | fuzz_siconos_fc2d) echo siconos.dict ;;
    fuzz_matrix_market) echo matrix_market.dict ;;
    fuzz_scene_json) echo scene_json.dict ;;
    fuzz_trajectory_csv) echo csv.dict ;;
  esac
}

mkdir -p "$BUILD/artifacts" "$BUILD/logs"
# run TARGET: runs one target; its verdict goes to logs/TARGET.result.
run() {
  local t=$1 log=$BUILD/logs/$1.log max_len=65536
  [ "$t" = fuzz_qp_solve ] && max_len=8192
  if "$BUILD/tests/fuzz/$t" "$BUILD/corpus/$t" -dict="$ROOT/tests/fuzz/$(dict_of "$t")" \
      -max_total_time="$SECONDS_PER_TARGET" -runs="$RUNS" -rss_limit_mb=2048 -timeout="$TIMEOUT" -max_len=$max_len \
      -artifact_prefix="$BUILD/artifacts/$t-" -print_final_stats=1 >"$log" 2>&1; then
    echo ok >"$BUILD/logs/$t.result"
  else
    echo FAILED >"$BUILD/logs/$t.result"
  fi
}
echo "== ${SECONDS_PER_TARGET} s per target, $PARALLEL at a time: $TARGETS"
running=0
for t in $TARGETS; do
  rm -f "$BUILD/logs/$t.result"
  run "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$PARALLEL" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait
status=0
for t in $TARGETS; do
  result=$(cat "$BUILD/logs/$t.result" 2>/dev/null || echo FAILED)
  [ "$result" = ok ] || status=1
  execs=$(grep -m1 'stat::number_of_executed_units' "$BUILD/logs/$t.log" | awk '{print $2}' || true)
  echo "   $t: $result, ${execs:-?} executions (log: $BUILD/logs/$t.log)"
  if [ "$result" != ok ]; then tail -n 30 "$BUILD/logs/$t.log"; fi
done
exit $status
