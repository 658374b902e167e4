#!/bin/sh
# A DEM given without a pose is seen from its default view (terrain covers
# at least a third of the image, measured by the CPU reference), and a pose
# that does not lie over the terrain is a warning naming both, or an error
# under --strict.
# usage: test_default_view.sh FIXTERRAIN OUT_DIR SHARED_DATA_DIR
set -u
bin=$1
out=$2/default_view
data=$3
mkdir -p "$out"
fail=0
say() { echo "test_default_view: $*"; }
bad() { say "FAIL: $*"; fail=1; }

# The embedded default scene's keys, a small view, bintree (fast), the
# metric on so the stats count the terrain pixels of the reference image.
cat > "$out/dv.ini" <<'INI'
[scene]
name = default-view
method = bintree
[view]
width_px = 160
height_px = 120
[metric]
enabled = 1
[budget]
frame_pos_bytes = 1M
reference_bytes = 1M
metric_bytes = 1M
INI
pixels=$((160 * 120))

# coverage NAME [render args...]: default view, a third of the image at least
coverage() {
    name=$1
    shift
    "$bin" render --scene "$out/dv.ini" --quiet --out "$out/$name.png" \
        --stats "$out/$name.json" "$@" 2> "$out/$name.err"
    rc=$?
    if [ $rc -ne 0 ]; then bad "$name: render exit $rc: $(cat "$out/$name.err")"; return; fi
    grep -q 'default view' "$out/$name.err" || bad "$name: no 'default view' note on stderr"
    px=$(sed -n 's/.*"terrain_px": \([0-9]*\).*/\1/p' "$out/$name.json")
    if [ -z "$px" ]; then bad "$name: no terrain_px in stats"; return; fi
    if [ $((px * 3)) -lt $pixels ]; then
        bad "$name: terrain covers $px of $pixels px (< 1/3)"
    else
        say "$name: terrain covers $px of $pixels px"
    fi
}

coverage synthetic
if [ -d "$data" ]; then
    for f in "$data"/*.hgt; do
        [ -e "$f" ] || continue
        coverage "$(basename "$f" .hgt)" --dem "$f"
    done
    for f in "$data"/*.tif; do
        [ -e "$f" ] || continue
        n=$(basename "$f" .tif)
        if "$bin" import "$f" "$out/$n.ftt" > "$out/$n.import.log" 2>&1; then
            coverage "$n" --dem "$out/$n.ftt"
        else
            say "$n: import not available here ($(tail -1 "$out/$n.import.log")): skipped"
        fi
    done

    # An explicit pose off the terrain: drawn with a warning naming both...
    dem="$data/N42E001.hgt"
    if [ -e "$dem" ]; then
        "$bin" render --scene "$out/dv.ini" --quiet --out "$out/off.png" --dem "$dem" \
            --pose 46.5,8.2,3000,0,-20,0 2> "$out/off.err"
        rc=$?
        [ $rc -eq 0 ] || bad "pose off the terrain: exit $rc, expected 0 (a warning)"
        grep -q 'warning.*does not lie over the terrain .*N42E001' "$out/off.err" ||
            bad "pose off the terrain: no warning naming pose and terrain: $(cat "$out/off.err")"
        # ...refused under --strict...
        "$bin" render --scene "$out/dv.ini" --quiet --strict --out "$out/off2.png" \
            --dem "$dem" --pose 46.5,8.2,3000,0,-20,0 2> "$out/off2.err"
        rc=$?
        [ $rc -eq 2 ] || bad "pose off the terrain under --strict: exit $rc, expected 2"
        grep -q 'error.*does not lie over the terrain' "$out/off2.err" ||
            bad "--strict: no error message: $(cat "$out/off2.err")"
        # ...and a pose over it is drawn as given, silently.
        "$bin" render --scene "$out/dv.ini" --quiet --strict --out "$out/on.png" \
            --dem "$dem" --pose 42.5,1.5,3000,0,-20,0 2> "$out/on.err"
        rc=$?
        [ $rc -eq 0 ] || bad "pose over the terrain: exit $rc"
        [ -s "$out/on.err" ] && bad "pose over the terrain: unexpected stderr: $(cat "$out/on.err")"
    fi
else
    say "no $data: only the synthetic terrain checked"
fi
exit $fail
