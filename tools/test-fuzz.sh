#!/bin/sh
# tools/test-fuzz.sh - the libFuzzer build and its bounded runs.
#
# Configures a clang build with FIXTERRAIN_FUZZ=ON (ASan + UBSan, libFuzzer)
# in its own directory, builds only the fuzz harnesses, and runs the
# ctest labels fuzz_regress (every seed and regression input once) and fuzz
# (each target fuzzed for FUZZ_SECONDS). A finding fails the run; its input
# is in BUILD/fuzz-artifacts/<target>/ (crash-*, timeout-*, leak-*, oom-*).
#
# Environment: FUZZ_BUILD_DIR (default <source>/build-fuzz), FUZZ_SECONDS
# (default 60 per target; 7 targets run one after the other),
# FUZZ_RSS_MB (default 2048), JOBS (build parallelism, default 2).
set -eu

src=$(cd "$(dirname "$0")/.." && pwd)
build=${FUZZ_BUILD_DIR:-$src/build-fuzz}
seconds=${FUZZ_SECONDS:-60}
rss_mb=${FUZZ_RSS_MB:-2048}
jobs=${JOBS:-2}

if ! command -v clang >/dev/null 2>&1; then
    echo "test-fuzz: clang not found (libFuzzer needs clang)" >&2
    exit 1
fi

# Core only: the parsers live in src/ and tools/, nothing needs a GPU.
cmake -S "$src" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DFIXTERRAIN_CORE_ONLY=ON -DFIXTERRAIN_BUILD_TESTS=ON -DFIXTERRAIN_FUZZ=ON \
      -DFIXTERRAIN_FUZZ_SECONDS="$seconds" -DFIXTERRAIN_FUZZ_RSS_MB="$rss_mb"
cmake --build "$build" -j "$jobs" --target fuzz_all
# Regression inputs first: a known finding fails fast, before any fuzzing.
ctest --test-dir "$build" -L '^fuzz_regress$' --output-on-failure
ctest --test-dir "$build" -L '^fuzz$' --output-on-failure
