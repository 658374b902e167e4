#!/bin/sh
# The whole test suite, as CI runs it (.ci/run; the README's test command
# after tools/install-deps.sh all). Steps, each one failing the run:
#   1. the main build (gcc, every option on, warnings as errors) and every
#      test: unit, GL on llvmpipe/OSMesa, CLI, soak, VM (vcan, gpio-sim, KMS);
#   2. the build matrix: {gcc, clang} x {Debug, Release, RelWithDebInfo,
#      MinSizeRel} without a warning (builds only);
#   3. the unit and GL tests again in an ASan + UBSan build (leaks checked);
#   4. each libFuzzer target for FUZZ_SECONDS (default 30) after its
#      regression inputs.
# Each step prints its wall time; the total is printed at the end.
set -eu
cd "$(dirname "$0")/.."
now_s() { date +%s; }
t_start=$(now_s)
step() {
  name=$1
  shift
  t0=$(now_s)
  echo "== test-all: $name"
  "$@"
  echo "== test-all: $name: $(( $(now_s) - t0 )) s"
}
main_suite() {
  cmake -S . -B build -DFIXTERRAIN_WITH_GDAL_TOOLS=ON -DFIXTERRAIN_BUILD_TESTS=ON \
        -DFIXTERRAIN_WERROR=ON
  cmake --build build -j2
  ctest --test-dir build --output-on-failure -j2
}
step "main build and tests" main_suite
step "build matrix" tools/build-matrix.sh
step "sanitizers" tools/test-sanitize.sh
FUZZ_SECONDS=${FUZZ_SECONDS:-30}
export FUZZ_SECONDS
step "fuzzing (${FUZZ_SECONDS} s a target)" tools/test-fuzz.sh
echo "== test-all: passed in $(( $(now_s) - t_start )) s"
