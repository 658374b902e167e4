#!/bin/sh
# pgrid-report.sh - the projective grids' report: every grid size
# of the issue, uniform and view-dependent rows, ray casting off and on, with
# brute force in the same run (its frame time is the ratio's base), from
# `fixterrain bench`: a CSV row, a plot point and a report line per setting.
#
# usage: tools/pgrid-report.sh SCENE.ini OUTDIR [fixterrain bench options...]
#   e.g. tools/pgrid-report.sh config/rainier.ini report --path valley,climb --frames 20
# Environment: FIXTERRAIN (default build/fixterrain), GRIDS, GAMMA_PX
# (default 1). Writes OUTDIR/pgrid.csv, pgrid.png and pgrid.md.
set -eu
if [ $# -lt 2 ]; then
    echo "usage: $0 SCENE.ini OUTDIR [fixterrain bench options...]" >&2
    exit 2
fi
scene=$1
out=$2
shift 2
bin=${FIXTERRAIN:-build/fixterrain}
grids=${GRIDS:-150x600,200x800,430x430,300x900,600x600,400x1600}
gamma=${GAMMA_PX:-1}
if [ ! -x "$bin" ]; then
    echo "$0: $bin not found (build first, or set FIXTERRAIN)" >&2
    exit 1
fi
mkdir -p "$out"
exec "$bin" bench --scene "$scene" --methods brute,pgrid \
    --settings "pgrid.grid=$grids;pgrid.distribution=uniform,view;pgrid.ray_casting=0,1;pgrid.gamma_px=$gamma" \
    --csv "$out/pgrid.csv" --plot "$out/pgrid.png" --report "$out/pgrid.md" "$@"
