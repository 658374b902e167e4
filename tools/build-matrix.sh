#!/bin/sh
# Builds every release configuration with warnings as errors:
# {gcc, clang} x {Debug, Release, RelWithDebInfo, MinSizeRel}, all options ON
# (every row of tools/build_options.cmake, tests included). Builds only; no
# test is run.
#
#   tools/build-matrix.sh [--keep-going] [SCRATCH_DIR]
#
# SCRATCH_DIR (default build-matrix/ in the repository root) holds one build
# directory and one log per configuration; a second run rebuilds incrementally.
# The first failing configuration stops the script (exit 1) with its name and
# the first errors from its log; --keep-going builds the rest and lists every
# failing configuration at the end (and keeps each build going past its
# first error, so one run shows every warning). A configuration also fails when its log
# has a compiler/linker "warning:" or a "CMake Warning" that -Werror did not
# turn into an error. Prints the time of each configuration and the total.
# Environment: FT_MATRIX_COMPILERS (default "gcc clang"), FT_MATRIX_TYPES
# (default the four CMake build types), FT_MATRIX_JOBS (default nproc).
set -eu
cd "$(dirname "$0")/.."
src=$(pwd)

keep_going=0
if [ "${1:-}" = "--keep-going" ]; then
  keep_going=1
  shift
fi
case "${1:-}" in
  -*) echo "usage: $0 [--keep-going] [SCRATCH_DIR]" >&2; exit 2 ;;
esac
scratch=${1:-$src/build-matrix}
compilers=${FT_MATRIX_COMPILERS:-gcc clang}
types=${FT_MATRIX_TYPES:-Debug Release RelWithDebInfo MinSizeRel}
jobs=${FT_MATRIX_JOBS:-$(nproc 2>/dev/null || echo 2)}
# Ninja when present (faster no-op rebuilds); Unix Makefiles otherwise.
# --keep-going also keeps each build going past its first error, so one run
# shows every warning.
if command -v ninja >/dev/null 2>&1; then
  gen="Ninja"
  kflag="-k 0"
else
  gen="Unix Makefiles"
  kflag="-k"
fi
[ $keep_going = 1 ] || kflag=""

for cc in $compilers; do
  if ! command -v "$cc" >/dev/null 2>&1; then
    echo "build-matrix: compiler '$cc' not found (tools/install-deps.sh all installs clang)" >&2
    exit 1
  fi
done
mkdir -p "$scratch"
# every FIXTERRAIN_WITH_* option ON, from the one table of them
allon=$(cmake -DFT_OPTIONS_VALUE=ON -P "$src/tools/build_options.cmake")

now_ms() { echo $(($(date +%s%N) / 1000000)); }
fmt_s() { printf '%d.%01d s' $(($1 / 1000)) $((($1 % 1000) / 100)); }

failed=""
t_all=$(now_ms)
for cc in $compilers; do
  for bt in $types; do
    name="$cc $bt"
    dir="$scratch/$cc-$bt"
    log="$scratch/$cc-$bt.log"
    printf 'build-matrix: %-24s ' "$name"
    t0=$(now_ms)
    ok=1
    # shellcheck disable=SC2086  # $kflag and $allon are empty or words on purpose
    # --fresh: the cache always matches this configuration (compiler, type).
    if ! CC=$cc cmake --fresh -S "$src" -B "$dir" -G "$gen" -DCMAKE_BUILD_TYPE="$bt" \
          -DFIXTERRAIN_WERROR=ON -DFIXTERRAIN_BUILD_TESTS=ON $allon >"$log" 2>&1; then
      ok=0
    elif ! cmake --build "$dir" -j "$jobs" ${kflag:+--} $kflag >>"$log" 2>&1; then
      ok=0
    elif grep -q -e 'warning:' -e 'CMake Warning' "$log"; then
      ok=0
    fi
    dt=$(($(now_ms) - t0))
    if [ $ok = 1 ]; then
      echo "ok      $(fmt_s $dt)"
      continue
    fi
    echo "FAILED  $(fmt_s $dt)"
    echo "build-matrix: configuration '$name' failed (CC=$cc CMAKE_BUILD_TYPE=$bt); log: $log" >&2
    grep -m 20 -E 'error:|warning:|CMake (Error|Warning)|FAILED:|Error [0-9]' "$log" >&2 || tail -n 20 "$log" >&2
    failed="$failed
  $name"
    if [ $keep_going = 0 ]; then
      echo "build-matrix: stopped at '$name' (--keep-going builds the rest)" >&2
      exit 1
    fi
  done
done
echo "build-matrix: total $(fmt_s $(($(now_ms) - t_all))) ($gen, -j$jobs)"
if [ -n "$failed" ]; then
  echo "build-matrix: failing configurations:$failed" >&2
  exit 1
fi
echo "build-matrix: all configurations built without a warning"
