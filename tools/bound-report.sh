#!/bin/sh
# bound-report.sh: the bounded methods' error over many DEMs, one table.
#
# Flies `fixterrain bench`'s paths over every DEM listed (default: the
# tiles in ../shared/data) with bintree (tau 0.5 / 1 / 2) and pgrid
# (gamma 0.5 / 1 / 2, the paper's 1024x512 grid, ray casting with a budget
# of every pixel) and prints, per DEM, method and bound, the worst measured
# frame's error split in two:
#   - vertical: the largest screen displacement of a drawn point (what the
#     bound is about: a method whose vertical error is over its bound is
#     broken);
#   - occlusion: the largest distance to the nearest pixel where the frame
#     and the truth show the same surface (metric.h), which also counts
#     pixels where sub-pixel displacements change which of several crests
#     stacked within a pixel is seen (at the horizon of flat terrain).
# and the measured frames over the bound by all of it / by the vertical
# error alone. A report, not a test: it exits 0 when every bench ran.
#
#   tools/bound-report.sh [-b FIXTERRAIN] [-d DATA_DIR] [-o OUT_DIR] [-s WxH]
#                         [-f FRAMES] [NAME=FILE@LAT,LON ...]
#
# FILE is a .hgt, .ftt or anything `fixterrain import` reads (imported into
# OUT_DIR); LAT,LON the paths' start (--centre). GALLIUM_DRIVER passes
# through (softpipe: no llvmpipe silhouette artefacts, README "bintree").
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$here/build/fixterrain
data=$here/../shared/data
out=${TMPDIR:-/tmp}/fixterrain-bound-report
size=640x480
frames=8
while getopts b:d:o:s:f: opt; do
  case $opt in
    b) bin=$OPTARG ;; d) data=$OPTARG ;; o) out=$OPTARG ;; s) size=$OPTARG ;;
    f) frames=$OPTARG ;;
    *) echo "usage: $0 [-b FIXTERRAIN] [-d DATA_DIR] [-o OUT_DIR] [-s WxH] [-f FRAMES] [NAME=FILE@LAT,LON ...]" >&2
       exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ -x "$bin" ] || { echo "$0: no fixterrain binary at $bin (-b)" >&2; exit 2; }
if [ $# -eq 0 ]; then
  # the shared tiles, each flown from a point with relief on it (a tile's
  # centre can be sea: N43E007's is)
  set -- \
    "N42E001=$data/N42E001.hgt@42.30,1.50" \
    "Rainier=$data/rainier_N46W122_srtm3.tif@46.70,-121.76" \
    "Everest=$data/everest_N27E086_srtm3.tif@27.95,86.90" \
    "N43E007=$data/N43E007.hgt@43.75,7.30" \
    "N41E001=$data/N41E001.hgt@41.40,1.50" \
    "N49E011=$data/N49E011.hgt@49.50,11.50" \
    "N50E011=$data/N50E011.hgt@50.50,11.50" \
    "N52E008=$data/N52E008.hgt@52.50,8.50"
fi
mkdir -p "$out"
px=$(( ${size%x*} * ${size#*x} )) # pgrid's ray-casting budget: every pixel
# the shipped scene budgets for its own method (pgrid): room for the bintree's
sed 's/^method_bytes = .*/method_bytes = 48M/; s/^tiles_max = .*/tiles_max = 65536/' \
  "$here/config/pyrenees.ini" > "$out/scene.ini"

status=0
printf '| DEM | method | bound px | max px | vertical max px | occlusion max px | p99.9 px | frames over (all / vertical) of measured |\n'
printf '|---|---|---:|---:|---:|---:|---:|---|\n'
for item in "$@"; do
  name=${item%%=*}
  rest=${item#*=}
  file=${rest%@*}
  centre=${rest##*@}
  if [ ! -f "$file" ]; then
    echo "$0: $name: no file $file (skipped)" >&2
    continue
  fi
  case $file in
    *.hgt|*.ftt) dem=$file ;;
    *) dem=$out/$name.ftt
       "$bin" import "$file" "$dem" > "$out/$name.import.log" 2>&1 || {
         echo "$0: $name: import failed (see $out/$name.import.log)" >&2; status=1; continue; } ;;
  esac
  for m in bintree pgrid; do
    if [ $m = bintree ]; then
      paths=valley,climb,turn360,dive,hover,orbit
      settings='bintree.tau_px=0.5,1,2;bintree.subsample_levels=4;bintree.template_k=3;bintree.morph_width=0.25'
      key=tau_px
    else
      paths=valley,climb,orbit
      settings='pgrid.grid=1024x512;pgrid.gamma_px=0.5,1,2;pgrid.error_bound=residual;pgrid.ray_casting=1;pgrid.raycast_max_px='$px
      key=gamma_px
    fi
    csv=$out/$name.$m.csv
    if ! "$bin" bench --scene "$out/scene.ini" --dem "$dem" --centre "$centre" --methods $m \
         --path $paths --size "$size" --frames "$frames" --metric-every 2 --no-oracle \
         --settings "$settings" --csv "$csv" --plot "$out/$name.$m.png" --quiet \
         > "$out/$name.$m.log" 2>&1; then
      echo "$0: $name $m: bench failed (see $out/$name.$m.log)" >&2
      status=1
      continue
    fi
    awk -F, -v dem="$name" -v m=$m -v key=$key '
      NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
      {
        b = "?"
        if (match($2, key "=[0-9.]+") > 0) b = substr($2, RSTART + length(key) + 1, RLENGTH - length(key) - 1)
        printf "| %s | %s | %s | %.3f | %.3f | %.3f | %.3f | %d / %d of %d |\n", dem, m, b,
               $(c["err_max_px"]), $(c["err_max_vertical_px"]), $(c["occlusion_err_max_px"]),
               $(c["err_p999_px"]), $(c["bound_over_frames"]), $(c["bound_over_vertical_frames"]),
               $(c["measured_frames"])
      }' "$csv"
  done
done
exit $status
