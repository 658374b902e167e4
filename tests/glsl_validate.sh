#!/bin/sh
# Validates every assembled shader variant with glslangValidator, and first
# proves the validator is strict: an ES 3 built-in in a GLSL ES 1.00 shader
# must be rejected, or this test means nothing.
set -u
validator=$1; dir=$2; tmp=$3
cat > "$tmp/negative.vert" <<'GLSL'
#version 100
uniform sampler2D s;
void main() { gl_Position = texelFetch(s, ivec2(0), 0); }
GLSL
if "$validator" "$tmp/negative.vert" > /dev/null 2>&1; then
  echo "FAIL: validator accepted texelFetch in GLSL ES 1.00"; exit 1
fi
n=0; bad=0
for f in "$dir"/*.es2.vert "$dir"/*.es2.frag "$dir"/*.es3.vert "$dir"/*.es3.frag; do
  [ -f "$f" ] || continue
  n=$((n + 1))
  if ! out=$("$validator" "$f" 2>&1); then
    echo "FAIL: $f"; echo "$out"; bad=$((bad + 1))
  fi
done
echo "validated $n shader variants, $bad failed"
[ "$n" -ge 4 ] && [ "$bad" -eq 0 ]
