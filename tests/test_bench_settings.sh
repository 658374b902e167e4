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
# of the measured frames and the three cache columns)
if "$bin" bench --scene "$out/tiny.ini" --methods bintree --path hover --size 32x24 --frames 2 \
     --quiet --no-oracle --settings 'bintree.template_k=2;bintree.tau_px=1' \
     --csv "$out/n.csv" --plot "$out/n.png" > "$out/n.log" 2>&1; then
  grep -q '^bintree,template_k=2 tau_px=1,hover,2,.*[0-9],,,[0-9.]*,[0-9]*,[0-9.]*,[0-9.]*,[0-9]*,[0-9]*,[0-9]*,[0-9.]*$' "$out/n.csv" ||
    fail "--no-oracle: the oracle columns are not empty: $(cat "$out/n.csv")"
else
  fail "tiny bench run with --no-oracle: $(cat "$out/n.log")"
fi

echo "test_bench_settings: $fails failure(s)"
[ "$fails" -eq 0 ]
