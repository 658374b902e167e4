/* bench.h - `fixterrain bench`: error against run time.
 *
 *   fixterrain bench [--scene FILE] [--dem FILE] [--methods LIST] [--path NAME|FILE[,...]]
 *                    [--csv OUT.csv] [--plot OUT.png] [--report OUT.md] [--size WxH]
 *                    [--frames N] [--metric-every N] [--settings SPEC]... [--centre LAT,LON]
 *                    [--backend NAME] [--clearance M] [--plot-error max|p999]
 *                    [--ref-cache-mb N] [--quiet]
 *
 * Flies the same camera paths over the scene's DEM with every method and
 * setting, times every frame (LOD selection + draw + readback, i.e. until
 * the GPU is done: ft_app_render's select_ms + gpu_ms), measures the error
 * against the CPU reference on every Nth frame (ft_app_measure), and writes
 * a CSV row per (method, setting), a plot of error against median frame
 * time (one colour per method, the Pareto front of each method as a line)
 * and a markdown report. `fixterrain bench --help` lists the details.
 *
 * Tools code: it uses the heap (the reference cache, the PNG encoder), the
 * renderer itself still runs from its arena. Built when
 * FIXTERRAIN_WITH_REFERENCE is on. */
#ifndef FT_TOOLS_BENCH_H
#define FT_TOOLS_BENCH_H

/* argv[0] is "bench". Returns the process exit status: 0 ok, 1 error, 2 usage. */
int ft_cmd_bench(int argc, char **argv);

#endif
