#!/bin/sh
# test_profile.sh - the lean build reads its scene (-DFIXTERRAIN_PROFILE) with
# the runtime's own parser: a scene `fixterrain render --scene` refuses fails
# the configure with the runtime's message, and every value means what it
# means at run time. Configures only (no build).
# usage: test_profile.sh SRCDIR OUTDIR CC FIXTERRAIN
set -u
src=$1; dir=$2; cc=$3; bin=$4
rm -rf "$dir"; mkdir -p "$dir"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
configure() { # configure SCENE: exit status of a configure with that profile
  cmake -S "$src" -B "$dir/b" -DCMAKE_C_COMPILER="$cc" -DFIXTERRAIN_BUILD_TESTS=OFF \
        -DFIXTERRAIN_PROFILE="$1" > "$dir/configure.log" 2>&1
}
option() { sed -n "s/^FIXTERRAIN_WITH_$1:BOOL=//p" "$dir/b/CMakeCache.txt"; }
# refused SCENE: the configure fails and says what the runtime says
refused() {
  if configure "$1"; then
    fail "configure accepted $1, which the runtime refuses"; return
  fi
  msg=$("$bin" render --scene "$1" --out "$dir/x.png" 2>&1) && fail "the runtime accepted $1"
  grep -qF "$msg" "$dir/configure.log" ||
    fail "configure of $1 lacks the runtime's message '$msg': $(cat "$dir/configure.log")"
}
# chosen SCENE OPT=VALUE...: the configure succeeds with those options
chosen() {
  s=$1; shift
  configure "$s" || { fail "configure of $s failed: $(cat "$dir/configure.log")"; return; }
  for kv in "$@"; do
    [ "$(option "${kv%%=*}")" = "${kv#*=}" ] || fail "$s: FIXTERRAIN_WITH_${kv%%=*} is $(option "${kv%%=*}"), want ${kv#*=}"
  done
}

# a NUL byte before [view]: CMake's reader skipped it, the runtime refuses it
printf '[scene]\nmethod = bintree\n\000\n[view]\nwidth_px = 64\n' > "$dir/nul.ini"
refused "$dir/nul.ini"
grep -q "contains a NUL byte" "$dir/configure.log" || fail "no NUL byte message"

# metric.enabled: 0 or 1 as at run time, not CMake truthiness
printf '[scene]\nmethod = brute\n[metric]\nenabled = 1\n' > "$dir/m1.ini"
chosen "$dir/m1.ini" REFERENCE=ON METHOD_BRUTE=ON METHOD_BINTREE=OFF
printf '[scene]\nmethod = brute\n[metric]\nenabled = 0\n' > "$dir/m0.ini"
chosen "$dir/m0.ini" REFERENCE=OFF
for v in yes on TRUE 2; do
  printf '[metric]\nenabled = %s\n' "$v" > "$dir/m-$v.ini"
  refused "$dir/m-$v.ini"
  grep -q "metric.enabled = '$v': expected 0 or 1" "$dir/configure.log" || fail "metric.enabled = $v"
done

# build.inputs: whole words of a comma list, not a regex match anywhere
printf '[build]\ninputs = replay,gpio\n' > "$dir/gpio.ini"
chosen "$dir/gpio.ini" CAN=OFF GPIO=ON
printf '[build]\ninputs = can\npng = 0\n' > "$dir/can.ini"
chosen "$dir/can.ini" CAN=ON GPIO=OFF PNG=OFF
printf '[build]\ninputs = replay,scan\n' > "$dir/scan.ini"
refused "$dir/scan.ini"
printf '[build]\ninputs = replay,gpiochip\n' > "$dir/gpiochip.ini"
refused "$dir/gpiochip.ini"
# [can_map] defaults = 1 after [build] keeps build.* (the runtime's rule)
printf '[build]\ninputs = replay\npng = 0\n[can_map]\ndefaults = 1\n' > "$dir/map.ini"
chosen "$dir/map.ini" CAN=OFF GPIO=OFF PNG=OFF
# keys absent: the runtime's defaults (pgrid, EGL, replay+can+gpio, PNG, no metric)
printf '[view]\nwidth_px = 64\n' > "$dir/empty.ini"
chosen "$dir/empty.ini" METHOD_PGRID=ON METHOD_BRUTE=OFF EGL=ON OSMESA=OFF CAN=ON GPIO=ON PNG=ON REFERENCE=OFF GDAL_TOOLS=OFF \
  RELATIVE_COLOURING=OFF HORIZON=OFF HAZE=OFF GROUND_GRID=OFF NIGHT_PALETTE=OFF
# each presentation part where the scene uses it, and only there
printf '[presentation]\nhorizon = 1\nhaze_km = 20\n' > "$dir/pres1.ini"
chosen "$dir/pres1.ini" HORIZON=ON HAZE=ON GROUND_GRID=OFF NIGHT_PALETTE=OFF RELATIVE_COLOURING=OFF
printf '[presentation]\ngrid_m = 100\npalette = night\ncolouring = relative\n' > "$dir/pres2.ini"
chosen "$dir/pres2.ini" HORIZON=OFF HAZE=OFF GROUND_GRID=ON NIGHT_PALETTE=ON RELATIVE_COLOURING=ON
# a GPIO line that switches to night needs the night palette in a day scene
printf '[gpio]\nnight_line = 3\n' > "$dir/night-line.ini"
chosen "$dir/night-line.ini" NIGHT_PALETTE=ON HORIZON=OFF
# any other error the runtime finds: same message
printf '[view]\nwidht_px = 64\n' > "$dir/typo.ini"
refused "$dir/typo.ini"

echo "test_profile: $fails failure(s)"
[ "$fails" -eq 0 ]
