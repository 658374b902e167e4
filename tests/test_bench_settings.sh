#!/bin/sh
# test_bench_settings.sh - `fixterrain bench --settings` refuses what it cannot
# honour (a 7th axis, a key given twice, a control character or a non-key that
# would write other INI lines), and its CSV quotes text fields (RFC 4180).
# usage: test_bench_settings.sh FIXTERRAIN TEST_PLOT SRCDIR OUTDIR
set -u
bin=$1; tp=$2; src=$3; out=$4/bench-settings
rm -rf "$out"; mkdir -p "$out"
. "$(dirname "$0")/expect.sh"

# a newline in a value would have written a [pose] section into the setting
nl_spec=$(printf 'bintree.tau_px=1\n[pose]\nalt_m=5')
expect 2 "byte 0x0a at offset 16 is a control character" -- "$bin" bench --settings "$nl_spec"
expect 2 "byte 0x09" -- "$bin" bench --settings "$(printf 'bintree.tau_px=1\t2')"
# '[' in a key would have opened another section
expect 2 "not a scene key" -- "$bin" bench --settings 'bintree.[pose]x=1'
# bintree has 2 default axes: the 7th was dropped silently (and left out of the label)
expect 2 "bintree already sweeps 6 axes" -- "$bin" bench --methods bintree \
  --settings 'bintree.tiles_max=1000;bintree.morph=0,1;bintree.a=1;bintree.b=1;bintree.c=1'
expect 2 "set the same key" -- "$bin" bench --settings 'bintree.tau_px=1' --settings 'bintree.tau_px=2'
expect 2 "set the same key" -- "$bin" bench --methods pgm --settings 'pgm.grid=64x64;pgm.grid_cols=32'

# --centre is a pose's lat/lon: the pose range table (scene.h) holds
expect 2 "lat_deg = 89.5 is outside [-89, 89] deg" -- "$bin" bench --centre 89.5,8
expect 2 "lon_deg = inf" -- "$bin" bench --centre 46,inf

# A tiny run (65 x 65 synthetic terrain, 32 x 24, 2 frames): 4 bintree axes all
# in the label, and a path name with a double quote quoted in the CSV.
{ cat "$src/config/default.ini"
  printf '[terrain]\nsynth_side = 65\n[budget]\nframe_pos_bytes = 1M\nreference_bytes = 1M\nmetric_bytes = 1M\n'; } > "$out/tiny.ini"
printf '0 46.5 8.0 3000 45 -20 0\n20 46.505 8.008 3000 45 -20 0\n' > "$out/q\"uote.wp"
if "$bin" bench --scene "$out/tiny.ini" --methods brute,bintree --path "$out/q\"uote.wp" \
     --size 32x24 --frames 2 --metric-every 1 --quiet \
     --settings 'bintree.template_k=2;bintree.tau_px=1;bintree.tiles_max=1000;bintree.morph=1' \
     --csv "$out/b.csv" --plot "$out/b.png" > "$out/run.log" 2>&1; then
  grep -q '^bintree,template_k=2 tau_px=1 tiles_max=1000 morph=1,"q""uote.wp",2,' "$out/b.csv" ||
    fail "CSV row not quoted as RFC 4180 wants: $(cat "$out/b.csv")"
  "$tp" --check-bench "$out/b.csv" "$out/b.png" 2 2 "brute:default" \
    "bintree:template_k=2 tau_px=1 tiles_max=1000 morph=1" || fail "test_plot --check-bench"
else
  fail "tiny bench run: $(cat "$out/run.log")"
fi

# --no-oracle: the bintree row leaves the oracle's two columns empty (the two
# before tau_achieved_max_px, bound_short_frames, the three ray-cast columns
# of the measured frames, the three cache columns, the two bound columns and
# the vertical error's two)
if "$bin" bench --scene "$out/tiny.ini" --methods bintree --path hover --size 32x24 --frames 2 \
     --quiet --no-oracle --settings 'bintree.template_k=2;bintree.tau_px=1' \
     --csv "$out/n.csv" --plot "$out/n.png" > "$out/n.log" 2>&1; then
  grep -q '^bintree,template_k=2 tau_px=1,hover,2,.*[0-9],,,[0-9.]*,[0-9]*,[0-9.]*,[0-9.]*,[0-9]*,[0-9]*,[0-9]*,[0-9.]*,[0-9]*,[0-9]*,[0-9.]*,[0-9]*$' "$out/n.csv" ||
    fail "--no-oracle: the oracle columns are not empty: $(cat "$out/n.csv")"
else
  fail "tiny bench run with --no-oracle: $(cat "$out/n.log")"
fi

# A method reading the clipmap cache: the bench runs its cache between the
# measured frames as a 60 Hz display would (--cache-hz), so on a climb whose
# 3 frames lie 150 s apart no frame is drawn with a level behind (and pgm's
# none from coarser data; clipmap's layout leaves level 0 out where its box
# has left the 30 km terrain, which it counts as coarser); with --cache-hz 0
# only the measured frames' selections move it and it is behind (the counts
# are the CSV's cache columns).
{ cat "$src/config/default.ini"
  printf '[budget]\nclip_bytes = 1M\nframe_pos_bytes = 1M\nreference_bytes = 1M\nmetric_bytes = 1M\n'; } > "$out/cache.ini"
# cache_col FILE METHOD SETTING COLUMN: the value of COLUMN in that row
cache_col() {
  awk -F, -v m="$2" -v st="$3" -v c="$4" 'NR == 1 { for (i = 1; i <= NF; ++i) h[$i] = i; next }
    $1 == m && $2 == st { print $(h[c]) }' "$1"
}
for hz in 60 0; do
  if "$bin" bench --scene "$out/cache.ini" --methods clipmap,pgm --path climb --size 64x48 \
       --frames 3 --metric-every 3 --quiet --cache-hz "$hz" \
       --settings 'clipmap.side=128;pgm.grid=64x128;pgm.heights=clipmap' \
       --csv "$out/c$hz.csv" --plot "$out/c$hz.png" > "$out/c$hz.log" 2>&1; then
    for row in "clipmap side=128" "pgm grid=64x128 heights=clipmap"; do
      m=${row%% *}; st=${row#* }
      coarser=$(cache_col "$out/c$hz.csv" "$m" "$st" cache_coarser_frames)
      behind=$(cache_col "$out/c$hz.csv" "$m" "$st" cache_behind_frames)
      echo "--cache-hz $hz $row: $coarser frames on coarser data, $behind with a level behind"
      case "$hz:$m:$coarser:$behind" in
        60:pgm:0:0|60:clipmap:*:0) ;;
        60:*) fail "--cache-hz 60 $row: $coarser frames on coarser data, $behind behind" ;;
        0:*:*:0|0:*:*:) fail "--cache-hz 0 $row: the cache was not behind ($behind)" ;;
      esac
    done
  else
    fail "cache bench run (--cache-hz $hz): $(cat "$out/c$hz.log")"
  fi
done

echo "test_bench_settings: $fails failure(s)"
[ "$fails" -eq 0 ]
