#!/bin/sh
# render-pictures.sh - the README's pictures: the embedded default scene, and
# Mount Rainier (SRTM3, ../shared/data) in each palette and colouring, with
# the conformal horizon and haze where a crew's display would have them.
#
# usage: tools/render-pictures.sh BUILD_DIR OUT_DIR [DATA_DIR]
#   BUILD_DIR  a build with fixterrain and fixterrain-tools (GDAL import)
#   OUT_DIR    where the PNGs go (docs/pictures to update the README's)
#   DATA_DIR   default: ../shared/data beside the repository
# Each picture: 480x320, the scene's own method (pgrid), llvmpipe. The test
# `pictures` renders them again and compares them with docs/pictures.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=$1; out=$2; data=${3:-$here/../shared/data}
bin="$build/fixterrain"; tools="$build/fixterrain-tools"
mkdir -p "$out"
tmp="$out/.work"; mkdir -p "$tmp"

"$bin" render --size 480x320 --out "$out/default.png" --quiet

dem="$data/rainier_N46W122_srtm3.tif"
[ -f "$dem" ] || { echo "render-pictures: $dem missing: Rainier pictures skipped" >&2; exit 77; }
"$tools" import "$dem" "$tmp/rainier.ftt" > "$tmp/import.log"
# name  colouring  palette  horizon  haze_km
while read -r name colouring palette horizon haze; do
  { cat "$here/config/rainier.ini"
    printf '[presentation]\ncolouring = %s\npalette = %s\nhorizon = %s\nhaze_km = %s\n' \
      "$colouring" "$palette" "$horizon" "$haze"; } > "$tmp/$name.ini"
  "$bin" render --scene "$tmp/$name.ini" --dem "$tmp/rainier.ftt" --size 480x320 \
    --out "$out/$name.png" --quiet
done <<'LIST'
rainier-day-absolute absolute day 0 0
rainier-day-relative relative day 1 60
rainier-night-absolute absolute night 0 0
rainier-night-relative relative night 1 60
LIST
rm -rf "$tmp"
echo "render-pictures: 5 pictures in $out"
