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
keys=$("$bin" keys | grep -E '^[a-z_]+\.[a-z_0-9]+$') || { echo "FAIL: fixterrain keys"; exit 1; }
n=$(printf '%s\n' "$keys" | wc -l)
[ "$n" -ge 50 ] || { echo "FAIL: fixterrain keys listed only $n keys"; exit 1; }
status=0
for scene in default pyrenees rainier; do
  f="$src/config/$scene.ini"
  grep -q -i 'every key' "$f" || { echo "FAIL: $f no longer says every key is set"; status=1; }
  missing=0
  for k in $keys; do
    sec=${k%%.*} key=${k#*.}
    awk -v s="[$sec]" -v k="$key" \
      '/^\[/ { in_s = ($0 == s) } in_s && index($0, k) == 1 && substr($0, length(k) + 1) ~ /^ *=/ { f = 1 }
       END { exit !f }' "$f" || { echo "FAIL: $f does not set $k"; missing=$((missing + 1)); }
  done
  echo "$scene.ini: $n keys, $missing missing"
  [ "$missing" -eq 0 ] || status=1
done
exit $status
