#!/usr/bin/env bash
# Sanitizer job (also run by .ci/run): builds lcprelax with AddressSanitizer and
# UndefinedBehaviorSanitizer (-fno-sanitize-recover=all: the first report fails the test)
# in build-asan, without the benchmarks and PETSc, the library at -O1 and the tests' own code
# at -O0 under ASan only, and runs the tests that are not labelled `long` (tests/CMakeLists.txt;
# those are not built there) but one slow sweep (below). LeakSanitizer is on (suppressions: tests/lsan.supp). The allocation-counting tests are not built there (they interpose malloc).
#   scripts/sanitize.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-build-asan}"
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DLCPRELAX_SANITIZE=ON -DLCPRELAX_BUILD_BENCH=OFF -DLCPRELAX_WITH_PETSC=OFF \
  -DLCPRELAX_TEST_OPTIMIZATION=-O0 -DLCPRELAX_BUILD_LONG_TESTS=OFF -DLCPRELAX_WITH_PYTHON=OFF
cmake --build "$dir" -j2
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp"
# A numerical sweep that takes 20–28 s under the sanitizers (measured in a CI run); the
# shorter cases of the same file (BlockRecovery's others) run the same code, and the Release
# job runs it.
slow='BlockRecovery\.SweepOfInitialValues'
ctest --test-dir "$dir" --output-on-failure -j2 -LE long -E "$slow"
