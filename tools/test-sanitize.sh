#!/bin/sh
# The unit and GL tests (every test but the VM ones, ctest label "vm") in an
# AddressSanitizer + UndefinedBehaviorSanitizer build (FIXTERRAIN_SANITIZE=ON:
# -fsanitize=address,undefined -fno-sanitize-recover=all, so any report fails
# its test). LeakSanitizer stays on for the project's code; tests/lsan.supp
# suppresses only leaks whose stack is inside the graphics driver stack.
# The compiler is gcc, the main build's compiler, whose ASan/UBSan run the
# whole suite clean with Mesa here; FT_SANITIZE_CC=clang selects clang.
#
#   tools/test-sanitize.sh [BUILD_DIR]        (default build-sanitize/)
#
# Environment: FT_SANITIZE_CC (default gcc), FT_SANITIZE_JOBS (default nproc),
# FT_SANITIZE_CTEST_ARGS (extra ctest arguments, e.g. "-R test_scene").
# Prints the build and test times.
set -eu
cd "$(dirname "$0")/.."
src=$(pwd)
dir=${1:-$src/build-sanitize}
cc=${FT_SANITIZE_CC:-gcc}
jobs=${FT_SANITIZE_JOBS:-$(nproc 2>/dev/null || echo 2)}

now_s() { date +%s; }
t0=$(now_s)
CC=$cc cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DFIXTERRAIN_SANITIZE=ON -DFIXTERRAIN_WERROR=ON -DFIXTERRAIN_BUILD_TESTS=ON \
  -DFIXTERRAIN_WITH_GDAL_TOOLS=ON
cmake --build "$dir" -j "$jobs"
t1=$(now_s)

# detect_leaks: LSan is on by default with ASan on x86-64 Linux; said here so
# it is never lost. abort_on_error/halt_on_error: a report ends the test.
# Scripts under test (tests/*.sh) run the sanitized binaries and inherit these.
ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
LSAN_OPTIONS="suppressions=$src/tests/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS

# Mesa unloads its DRI driver at eglTerminate; what the driver still holds is
# then reported as leaked from "<unknown module>", which no suppression can
# name. Preloading the driver keeps it mapped (its caches stay reachable and
# its frames keep a name). verify_asan_link_order=0: gcc's ASan runtime is a
# shared library and would otherwise refuse a preload listed before it.
if [ -z "${FT_SANITIZE_NO_PRELOAD:-}" ]; then
  arch=$(gcc -print-multiarch 2>/dev/null || echo x86_64-linux-gnu)
  dri=/usr/lib/$arch/dri/swrast_dri.so
  if [ -e "$dri" ]; then
    LD_PRELOAD="$dri${LD_PRELOAD:+ $LD_PRELOAD}"
    ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
    export LD_PRELOAD
  fi
fi

# Excluded: the VM tests (label vm, a separate CI step), the tests that
# are builds (lean_build, lean_profile: they configure and build the tree
# again without the sanitizer; tools/build-matrix.sh covers the builds) and
# pgrid_paths and bintree_paths (benches over flights, 60-100 s plain and
# about 5x that sanitized, whose C code the unit and GL tests here already
# run) and bintree_gl_bound_sub (softpipe, 80 s plain).
status=0
# shellcheck disable=SC2086  # extra ctest arguments are words on purpose
ctest --test-dir "$dir" -LE '^vm$' -E '^(lean_build|lean_profile|pgrid_paths|bintree_paths|bintree_gl_bound_sub)$' --output-on-failure -j "$jobs" \
  ${FT_SANITIZE_CTEST_ARGS:-} || status=$?
t2=$(now_s)
echo "test-sanitize: CC=$cc build $((t1 - t0)) s, tests $((t2 - t1)) s, total $((t2 - t0)) s"
if [ $status != 0 ]; then
  echo "test-sanitize: FAILED (a test failed or a sanitizer reported; see above)" >&2
fi
exit $status
