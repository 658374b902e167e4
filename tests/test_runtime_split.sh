#!/bin/sh
# test_runtime_split.sh - the display runtime carries no tool: `fixterrain`
# links neither GDAL nor the bench, the oracle, the flight paths nor the
# plotter, and imports no allocator function; `fixterrain-tools` has them,
# and the runtime hands `bench` and `import` over to it (beside it, else PATH)
# or says where the command lives.
# usage: test_runtime_split.sh FIXTERRAIN FIXTERRAIN-TOOLS OUTDIR
rt=$1; tools=$2; out=$3/runtime-split
. "$(dirname "$0")/expect.sh"
rm -rf "$out"; mkdir -p "$out" || exit 1

needed=$(readelf -d "$rt") || { echo "readelf failed on $rt"; exit 1; }
case "$needed" in *gdal*) fail "the runtime needs GDAL: $(echo "$needed" | grep gdal)" ;; esac

tool_syms='ft_cmd_bench|ft_cmd_import|bench_oracle_frame|flight_path_sample|plot_axis_map'
defined=$(nm "$rt") || { echo "nm failed on $rt"; exit 1; }
hits=$(echo "$defined" | grep -E " [TtDdBb] ($tool_syms)" | head -5)
[ -z "$hits" ] || fail "the runtime contains tool code: $hits"
heap=$(nm -D --undefined-only "$rt" | grep -E " (malloc|calloc|realloc|free|strdup|strndup|aligned_alloc|posix_memalign)(@|$)")
[ -z "$heap" ] || fail "the runtime imports allocator functions: $heap"

# The check above must be able to see tool code where it is.
nm "$tools" | grep -Eq " T ft_cmd_bench$" || fail "fixterrain-tools has no ft_cmd_bench: the symbol check would see nothing"

# Forwarding: beside the runtime (the build tree), then PATH, else a clear error.
expect 0 "usage: fixterrain bench" -- "$rt" bench --help
expect 0 "usage: fixterrain import" -- "$rt" import --help
cp "$rt" "$out/fixterrain" || exit 1
expect 1 "'bench' is a workstation tool, not part of the display runtime" -- \
  env PATH=/nonexistent "$out/fixterrain" bench --help
mkdir -p "$out/bin" && ln -sf "$(readlink -f "$tools")" "$out/bin/fixterrain-tools"
expect 0 "usage: fixterrain bench" -- env PATH="$out/bin" "$out/fixterrain" bench --help

[ "$fails" -eq 0 ] || { echo "$fails failure(s)"; exit 1; }
echo "runtime split: no GDAL, no tool code, no allocator imports; bench and import forwarded"
