#!/bin/sh
# The shipped scenes that say "every key set explicitly" do set every key the
# schema has (`fixterrain keys`), each in its own section: a key added to the
# schema without a line in these files would leave their readers guessing at
# a default (the DEM scenes once ran the bintree without sub-sample levels,
# out of its bound near the ground, because the key was not in them).
# config/minimal.ini is a lean profile and sets only what it needs.
# usage: test_scene_keys.sh FIXTERRAIN SOURCE_DIR
set -u
bin=$1 src=$2
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
"$bin" keys | grep -E '^[a-z_]+\.[a-z_0-9]+$' | sort -u > "$tmp/schema" \
  || { echo "FAIL: fixterrain keys"; exit 1; }
n=$(wc -l < "$tmp/schema")
[ "$n" -ge 50 ] || { echo "FAIL: fixterrain keys listed only $n keys"; exit 1; }
status=0
for scene in default pyrenees rainier; do
  f="$src/config/$scene.ini"
  grep -q -i 'every key' "$f" || { echo "FAIL: $f no longer says every key is set"; status=1; }
  # section.key of every line that sets a key
  awk '/^\[[a-z_]+\]/ { s = substr($0, 2, index($0, "]") - 2) }
       /^[a-z_0-9]+ *=/ { k = $0; sub(/ *=.*/, "", k); print s "." k }' "$f" | sort -u > "$tmp/set"
  comm -23 "$tmp/schema" "$tmp/set" > "$tmp/missing"
  sed "s|^|FAIL: $f does not set |" "$tmp/missing"
  missing=$(wc -l < "$tmp/missing")
  echo "$scene.ini: $n keys, $missing missing"
  [ "$missing" -eq 0 ] || status=1
done
exit $status
