#!/bin/sh
# Builds fixterrain with every option off (must build; render must say what
# is missing) and a minimal profile (EGL + brute, no OSMesa/PNG/reference/
# GDAL), which must render. Prints both binary sizes.
set -eu
src=$1; dir=$2; cc=$3
rm -rf "$dir"; mkdir -p "$dir"
off="-DFIXTERRAIN_WITH_EGL=OFF -DFIXTERRAIN_WITH_X11=OFF -DFIXTERRAIN_WITH_KMS=OFF -DFIXTERRAIN_WITH_OSMESA=OFF -DFIXTERRAIN_WITH_METHOD_BRUTE=OFF
     -DFIXTERRAIN_WITH_METHOD_BINTREE=OFF -DFIXTERRAIN_WITH_METHOD_PGM=OFF -DFIXTERRAIN_WITH_CAN=OFF -DFIXTERRAIN_WITH_GPIO=OFF
     -DFIXTERRAIN_WITH_REFERENCE=OFF -DFIXTERRAIN_WITH_PNG=OFF -DFIXTERRAIN_WITH_GDAL_TOOLS=OFF
     -DFIXTERRAIN_BUILD_TESTS=OFF"
# shellcheck disable=SC2086
cmake -S "$src" -B "$dir/off" -DCMAKE_C_COMPILER="$cc" $off > "$dir/off.log"
cmake --build "$dir/off" -j2 >> "$dir/off.log" 2>&1 || { cat "$dir/off.log"; exit 1; }
if "$dir/off/fixterrain" render --out "$dir/x.png" > "$dir/off-run.log" 2>&1; then
  echo "FAIL: a build without backends rendered"; exit 1
fi
grep -q "left out of this build" "$dir/off-run.log" || { cat "$dir/off-run.log"; exit 1; }

# shellcheck disable=SC2086
cmake -S "$src" -B "$dir/min" -DCMAKE_C_COMPILER="$cc" $off -DFIXTERRAIN_WITH_EGL=ON \
      -DFIXTERRAIN_WITH_METHOD_BRUTE=ON > "$dir/min.log"
cmake --build "$dir/min" -j2 >> "$dir/min.log" 2>&1 || { cat "$dir/min.log"; exit 1; }
"$dir/min/fixterrain" render --size 160x120 --out "$dir/min.png" > "$dir/min-run.log" 2>&1 \
  || { cat "$dir/min-run.log"; exit 1; }
grep -q "triangles" "$dir/min-run.log" || { cat "$dir/min-run.log"; exit 1; }
echo "binary sizes: all options off $(stat -c %s "$dir/off/fixterrain") bytes," \
     "minimal (EGL + brute) $(stat -c %s "$dir/min/fixterrain") bytes"
