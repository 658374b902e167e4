#!/bin/sh
# test_pictures.sh - the README's pictures (docs/pictures) still show what the
# renderer draws: tools/render-pictures.sh renders them again and each must
# match its committed picture: at most 0.5% of the pixels may differ by more
# than 8 levels in any channel (bit-identical on the Mesa they were made
# with; the tolerance is for another Mesa/LLVM). A missing data directory
# skips the Rainier pictures only (exit 77 when nothing could be compared).
# usage: test_pictures.sh SRC_DIR BUILD_DIR OUT_DIR DATA_DIR COMPARE
src=$1; build=$2; out=$3/pictures; data=$4; compare=$5
rm -rf "$out"; mkdir -p "$out"
sh "$src/tools/render-pictures.sh" "$build" "$out" "$data"; rc=$?
[ "$rc" -eq 0 ] || [ "$rc" -eq 77 ] || { echo "FAIL: render-pictures exited $rc"; exit 1; }
fails=0; n=0
for f in "$out"/*.png; do
  name=$(basename "$f")
  ref="$src/docs/pictures/$name"
  [ -f "$ref" ] || { echo "FAIL: $name has no committed picture in docs/pictures"; fails=$((fails + 1)); continue; }
  n=$((n + 1))
  "$compare" "$ref" "$f" 8 0.005 || { echo "FAIL: $name differs from docs/pictures/$name"; fails=$((fails + 1)); }
done
for ref in "$src"/docs/pictures/*.png; do
  [ -f "$out/$(basename "$ref")" ] || [ "$rc" -eq 77 ] \
    || { echo "FAIL: docs/pictures/$(basename "$ref") is no longer rendered"; fails=$((fails + 1)); }
done
[ "$fails" -eq 0 ] || exit 1
echo "pictures: $n compared"
[ "$rc" -eq 0 ] || exit 77
