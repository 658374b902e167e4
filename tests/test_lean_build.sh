#!/bin/sh
# Builds fixterrain with every option off (must build; render must say what
# is missing) and a minimal profile (EGL + brute, no OSMesa/PNG/reference/
# GDAL), which must render. Prints both binary sizes.
set -eu
src=$1; dir=$2; cc=$3; full=${4:-}
rm -rf "$dir"; mkdir -p "$dir"
# every FIXTERRAIN_WITH_* option OFF, named by the one table of them
# (tools/build_options.cmake), so a new option cannot stay ON here
alloff=$(cmake -DFT_OPTIONS_VALUE=OFF -P "$src/tools/build_options.cmake")
case $alloff in -DFIXTERRAIN_WITH_*) ;; *) echo "FAIL: no option list: '$alloff'"; exit 1 ;; esac
off="$alloff -DFIXTERRAIN_BUILD_TESTS=OFF -DFIXTERRAIN_WERROR=${FT_WERROR:-OFF}"
# shellcheck disable=SC2086
cmake -S "$src" -B "$dir/off" -DCMAKE_C_COMPILER="$cc" $off > "$dir/off.log"
if grep '^FIXTERRAIN_WITH_[A-Z0-9_]*:BOOL=ON' "$dir/off/CMakeCache.txt"; then
  echo "FAIL: an option is ON in the every-option-OFF build (not a row of tools/build_options.cmake?)"
  exit 1
fi
cmake --build "$dir/off" -j2 >> "$dir/off.log" 2>&1 || { cat "$dir/off.log"; exit 1; }
if "$dir/off/fixterrain" render --out "$dir/x.png" > "$dir/off-run.log" 2>&1; then
  echo "FAIL: a build without backends rendered"; exit 1
fi
grep -q "left out of this build" "$dir/off-run.log" || { cat "$dir/off-run.log"; exit 1; }

# shellcheck disable=SC2086
cmake -S "$src" -B "$dir/min" -DCMAKE_C_COMPILER="$cc" $off -DFIXTERRAIN_WITH_EGL=ON \
      -DFIXTERRAIN_WITH_METHOD_BRUTE=ON > "$dir/min.log"
cmake --build "$dir/min" -j2 >> "$dir/min.log" 2>&1 || { cat "$dir/min.log"; exit 1; }
"$dir/min/fixterrain" render --method brute --size 160x120 --out "$dir/min.png" > "$dir/min-run.log" 2>&1 \
  || { cat "$dir/min-run.log"; exit 1; }
grep -q "triangles" "$dir/min-run.log" || { cat "$dir/min-run.log"; exit 1; }

# The lean build sized to a scene: config/minimal.ini (bintree, EGL offscreen,
# replay input only, no metric) must build, render its scene and replay,
# and leave out what it does not use.
# shellcheck disable=SC2086
cmake -S "$src" -B "$dir/profile" -DCMAKE_C_COMPILER="$cc" -DFIXTERRAIN_BUILD_TESTS=OFF \
      -DFIXTERRAIN_WERROR="${FT_WERROR:-OFF}" \
      -DFIXTERRAIN_PROFILE="$src/config/minimal.ini" > "$dir/profile.log"
cmake --build "$dir/profile" -j2 >> "$dir/profile.log" 2>&1 || { cat "$dir/profile.log"; exit 1; }
pbin="$dir/profile/fixterrain"
"$pbin" render --scene "$src/config/minimal.ini" --size 160x120 --out "$dir/profile.png" \
  > "$dir/profile-run.log" 2>&1 || { cat "$dir/profile-run.log"; exit 1; }
grep -q "bintree:" "$dir/profile-run.log" || { cat "$dir/profile-run.log"; exit 1; }
printf '(1700000000.000000) vcan0 137#0102000040A00000\n' > "$dir/one.log"
"$pbin" replay --scene "$src/config/minimal.ini" --size 64x48 --log "$dir/one.log" \
  > "$dir/profile-replay.log" 2>&1 || { cat "$dir/profile-replay.log"; exit 1; }
for left_out in "run --frames 1" "render --method brute"; do
  # shellcheck disable=SC2086
  if "$pbin" $left_out --out "$dir/x.png" > "$dir/left.log" 2>&1; then
    echo "FAIL: the minimal profile has '$left_out'"; exit 1
  fi
done
"$pbin" budget --scene "$src/config/minimal.ini" > "$dir/profile-budget.txt" 2>&1 \
  || { cat "$dir/profile-budget.txt"; exit 1; }
# The optional presentation parts are not in the minimal scene: the profile
# binary holds none of their shader text or code, the full build holds all of
# it (so the checks can see), and a scene that asks for a part is refused by
# its key and its build option. One row a part (a second for a second key):
#   option | text only its shader or code carries ("-": none) |
#   symbols only its code defines ("-": none) | scene lines asking for it |
#   the refusal's start
carries() { # carries BINARY TEXT SYMBOLS: 0 when it has the text or any symbol
  if [ "$2" != - ] && grep -q "$2" "$1"; then return 0; fi
  [ "$3" = - ] && return 1
  for sym in $3; do nm "$1" | grep -q " [A-Za-z] $sym\$" && return 0; done
  return 1
}
carries_all() { # carries_all BINARY TEXT SYMBOLS: 0 when it has the text and every symbol
  if [ "$2" != - ] && ! grep -q "$2" "$1"; then return 1; fi
  [ "$3" = - ] && return 0
  for sym in $3; do nm "$1" | grep -q " [A-Za-z] $sym\$" || return 1; done
  return 0
}
while IFS='|' read -r opt text syms ask says; do
  if carries "$pbin" "$text" "$syms"; then
    echo "FAIL: the minimal profile contains $opt ($text / $syms)"; exit 1
  fi
  if [ -n "$full" ] && ! carries_all "$full" "$text" "$syms"; then
    echo "FAIL: the full build lacks $opt ($text / $syms): the check above sees nothing"; exit 1
  fi
  { cat "$src/config/minimal.ini"; printf '%b\n' "$ask"; } > "$dir/part.ini"
  if "$pbin" render --scene "$dir/part.ini" --size 64x48 --out "$dir/x.png" > "$dir/part.log" 2>&1 \
     || ! grep -qF "$says was left out of this build (FIXTERRAIN_WITH_$opt=OFF)" "$dir/part.log"; then
    echo "FAIL: the minimal profile did not refuse '$ask' by name:"; cat "$dir/part.log"; exit 1
  fi
done <<'PARTS'
RELATIVE_COLOURING|u_band_rgba|ft_shade_bands_gpu|[presentation]\ncolouring = relative|presentation.colouring = relative
HORIZON|-|ft_camera_horizon_px ft_overlay_draw_line|[presentation]\nhorizon = 1|presentation.horizon = 1
HAZE|u_haze|-|[presentation]\nhaze_km = 20|presentation.haze_km = 20
GROUND_GRID|u_ground_grid|ft_shade_grid_weight|[presentation]\ngrid_m = 100|presentation.grid_m = 100
NIGHT_PALETTE|-|k_palette_night|[presentation]\npalette = night|presentation.palette = night
NIGHT_PALETTE|-|k_palette_night|[gpio]\nnight_line = 3|gpio.night_line = 3
PARTS
grep -q "left out: FT_SHADE_RELATIVE FT_SHADE_GRID FT_SHADE_HAZE)" "$dir/profile-budget.txt" \
  || { echo "FAIL: budget does not list the colour parts left out"; cat "$dir/profile-budget.txt"; exit 1; }
grep -q "shader variants: bintree.vert.glsl" "$dir/profile-budget.txt" \
  || { echo "FAIL: budget lists no shader variants"; cat "$dir/profile-budget.txt"; exit 1; }
sizes() { size "$1" | awk 'NR == 2 { printf "text %d, data %d, bss %d bytes", $1, $2, $3 }'; }
echo "binary sizes (text/data/bss, debug info aside):"
echo "  all options off:            $(sizes "$dir/off/fixterrain")"
echo "  EGL + brute:                $(sizes "$dir/min/fixterrain")"
echo "  profile config/minimal.ini: $(sizes "$pbin")"
[ -n "$full" ] && echo "  full build:                 $(sizes "$full")"
echo "static memory of the minimal scene (arena, reserved once at init):"
grep -E "^total|GPU memory" "$dir/profile-budget.txt"
