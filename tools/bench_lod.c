/* bench_lod.c - error against run time for the LOD methods, in one run.
 *
 *   fixterrain-bench-lod SCENE.ini [--frames N] [--size WxH] [--ks 2,3,4]
 *                        [--taus 0.5,1,2,4] [--methods bintree,pgm]
 *                        [--grids 200x800,430x430] [--md OUT.md]
 *
 * Flies one camera path (an orbit around the scene's pose: radius 6 km,
 * looking at the orbit centre, 10 deg down, altitude varying by +-500 m) with
 * brute force (always, first: the base of the ratios), then each method of
 * --methods (default bintree): the bintree for every (template k, tau_px)
 * pair, pgm for every grid (cols x rows) of --grids, and
 * prints one row per run: init time, frame time (median, p99, max; frame =
 * selection + draw + readback, i.e. until the GPU is done), CPU selection
 * time (median, max), triangles and tiles (mean), and the screen-space error
 * against the reference (max and mean px, measured on frames 1, 6, 11, ...). Frame
 * times are also given as a ratio to brute force measured in the same run,
 * the only comparison that carries over between machines. The first frame
 * of each run (shader compilation) is left out of the timings.
 *
 * A benchmark, not a test: nothing here passes or fails on timing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "app/frame.h"
#include "core/units.h"

#define BENCH_FRAMES_MAX 1000
#define BENCH_LIST_MAX 8
#define BENCH_SCENE_TEXT_MAX 65536

static ft_app g_app;
static char g_scene_text[BENCH_SCENE_TEXT_MAX];
static char g_gl_renderer[512];

typedef struct bench_row {
    char method[32];
    uint32_t k;
    uint32_t cols, rows; /* pgm grid */
    double tau;
    double init_ms;
    double tables_ms; /* bintree: ft_bintree_init alone (error + bound tables) */
    double frame_med_ms, frame_p99_ms, frame_max_ms;
    double select_med_ms, select_max_ms;
    double triangles_mean, tiles_mean;
    double err_max_px, err_mean_px;
    int budget_hits;
} bench_row;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* q-quantile (nearest rank) of v[0..n), sorts v */
static double quantile(double *v, int n, double q)
{
    if (n <= 0) return 0.0;
    qsort(v, (size_t)n, sizeof v[0], cmp_double);
    int r = (int)ceil(q * n) - 1;
    if (r < 0) r = 0;
    if (r >= n) r = n - 1;
    return v[r];
}

/* Times the bintree's table build on the loaded terrain, in its own arena. */
static double time_tables_ms(const ft_terrain *t, uint32_t k, uint32_t sub, uint32_t tiles_max)
{
    ft_arena a;
    ft_bintree bt;
    ft_error err;
    memset(&a, 0, sizeof a);
    ft_bintree_plan(&a, t->width, t->height, k, sub, tiles_max);
    a.pools[FT_POOL_METHOD].budget_bytes = a.pools[FT_POOL_METHOD].need_bytes;
    size_t total = ft_arena_total_budget(&a);
    total = (total + FT_ARENA_ALIGN - 1u) / FT_ARENA_ALIGN * FT_ARENA_ALIGN;
    void *mem = aligned_alloc(FT_ARENA_ALIGN, total);
    if (mem == NULL || ft_arena_bind(&a, mem, total, &err) != FT_OK) {
        free(mem);
        return NAN;
    }
    uint64_t t0 = ft_plat_monotonic_ns();
    ft_status st = ft_bintree_init(&bt, t, k, sub, FT_BT_MORPH_WIDTH, tiles_max, &a, &err);
    uint64_t t1 = ft_plat_monotonic_ns();
    free(mem);
    return st == FT_OK ? (double)(t1 - t0) * 1e-6 : NAN;
}

static ft_pose orbit_pose(const ft_pose *centre, int f, int frames)
{
    const double a = 2.0 * FT_PI * f / frames;
    const double r_m = 6000.0, m_per_deg = 111195.0797;
    ft_pose p = *centre;
    p.lat_deg = centre->lat_deg + r_m * sin(a) / m_per_deg;
    p.lon_deg = centre->lon_deg - r_m * cos(a) / (m_per_deg * cos(centre->lat_deg * FT_RAD_PER_DEG));
    p.alt_m = centre->alt_m + 500.0 * sin(3.0 * a);
    /* look back at the centre: heading from the position toward it */
    double dn = centre->lat_deg - p.lat_deg, de = centre->lon_deg - p.lon_deg;
    de *= cos(centre->lat_deg * FT_RAD_PER_DEG);
    p.heading_deg = fmod(atan2(de, dn) * FT_DEG_PER_RAD + 360.0, 360.0);
    p.pitch_deg = -10.0;
    p.roll_deg = 0.0;
    return p;
}

static int run(const ft_scene *base, const char *method, uint32_t k, double tau, uint32_t cols,
               uint32_t rows, int frames, bench_row *row)
{
    static double frame_ms[BENCH_FRAMES_MAX], select_ms[BENCH_FRAMES_MAX];
    ft_scene s = *base;
    ft_error err;
    if (!ft_method_from_name(method, &s.method)) {
        fprintf(stderr, "bench: method %s is not built in\n", method);
        return 0;
    }
    if (s.method == FT_METHOD_BINTREE) {
        s.bintree_template_k = k;
        s.bintree_tau_px = tau;
    }
    if (s.method == FT_METHOD_PGM) {
        s.pgm_grid_cols = cols;
        s.pgm_grid_rows = rows;
    }
    if (ft_scene_validate(&s, &err) != FT_OK || ft_app_init(&g_app, &s, &err) != FT_OK) {
        fprintf(stderr, "bench: %s k=%u tau=%g: %s\n", method, k, tau, err.text);
        return 0;
    }
    memset(row, 0, sizeof *row);
    (void)snprintf(row->method, sizeof row->method, "%s", method);
    row->k = k;
    row->tau = tau;
    row->cols = cols;
    row->rows = rows;
    row->init_ms = (double)g_app.init_ns * 1e-6;
    (void)snprintf(g_gl_renderer, sizeof g_gl_renderer, "%s / %s", g_app.gpu.version,
                   g_app.gpu.renderer);
    double tri = 0.0, tiles = 0.0, err_sum = 0.0;
    int timed = 0, measured = 0, ok = 1;
    ft_frame_loop loop; /* the settings as set: no degradation */
    ft_frame_loop_init(&loop, &g_app, 0);
    for (int f = 0; f <= frames && ok; ++f) {
        ft_frame fr;
        ft_pose p = orbit_pose(&base->pose, f, frames);
        if (ft_frame_step(&loop, &g_app, &p, NULL, &fr, &err) != FT_OK) {
            fprintf(stderr, "bench: frame %d: %s\n", f, err.text);
            ok = 0;
            break;
        }
        const ft_camera cam = fr.cam;
        const ft_frame_stats st = fr.stats;
        if (f == 0) continue; /* shader compilation */
        frame_ms[timed] = st.select_ms + st.gpu_ms;
        select_ms[timed] = st.select_ms;
        ++timed;
        tri += (double)st.triangles;
        tiles += st.tiles;
        row->budget_hits += st.budget_hit;
        if (s.metric_enabled && (f - 1) % 5 == 0) {
            ft_error_stats es;
            if (ft_app_measure(&g_app, &cam, &es, &err) != FT_OK) {
                fprintf(stderr, "bench: metric: %s\n", err.text);
                ok = 0;
                break;
            }
            if (es.max_px > row->err_max_px) row->err_max_px = es.max_px;
            err_sum += es.mean_px;
            ++measured;
        }
    }
    row->tables_ms = (s.method == FT_METHOD_BINTREE)
                         ? time_tables_ms(&g_app.terrain, k, s.bintree_subsample_levels, s.bintree_tiles_max)
                         : 0.0;
    ft_app_shutdown(&g_app);
    if (!ok || timed == 0) return 0;
    row->frame_max_ms = quantile(frame_ms, timed, 1.0);
    row->frame_p99_ms = quantile(frame_ms, timed, 0.99);
    row->frame_med_ms = quantile(frame_ms, timed, 0.5);
    row->select_max_ms = quantile(select_ms, timed, 1.0);
    row->select_med_ms = quantile(select_ms, timed, 0.5);
    row->triangles_mean = tri / timed;
    row->tiles_mean = tiles / timed;
    row->err_mean_px = measured ? err_sum / measured : NAN;
    if (!s.metric_enabled) row->err_max_px = NAN;
    return 1;
}

static int parse_list(const char *text, double *out, int max)
{
    int n = 0;
    const char *p = text;
    while (*p != '\0' && n < max) {
        char *end = NULL;
        out[n++] = strtod(p, &end);
        if (end == p) return 0;
        p = (*end == ',') ? end + 1 : end;
        if (*end != ',' && *end != '\0') return 0;
    }
    return n;
}

/* "200x800,430x430" -> cols[], rows[]; 0 on a malformed list. */
static int parse_grids(const char *text, uint32_t *cols, uint32_t *rows, int max)
{
    int n = 0;
    const char *p = text;
    while (*p != '\0' && n < max) {
        char *end = NULL;
        const unsigned long c = strtoul(p, &end, 10);
        if (end == p || *end != 'x') return 0;
        p = end + 1;
        const unsigned long r = strtoul(p, &end, 10);
        if (end == p || (*end != ',' && *end != '\0') || c < 2 || r < 2 || c > 8192 || r > 8192) {
            return 0;
        }
        cols[n] = (uint32_t)c;
        rows[n] = (uint32_t)r;
        ++n;
        p = (*end == ',') ? end + 1 : end;
    }
    return (*p == '\0') ? n : 0;
}

static void print_row(FILE *f, const bench_row *r, double brute_med)
{
    char setting[48];
    if (strcmp(r->method, "bintree") == 0) {
        (void)snprintf(setting, sizeof setting, "k=%u tau=%.1f", r->k, r->tau);
    } else if (strcmp(r->method, "pgm") == 0) {
        (void)snprintf(setting, sizeof setting, "grid %ux%u", r->cols, r->rows);
    } else {
        (void)snprintf(setting, sizeof setting, "-");
    }
    fprintf(f, "| %-8s | %-14s | %8.0f | %8.0f | %8.1f | %8.1f | %8.1f | %5.2f | %7.3f | %7.3f | %10.0f | "
               "%7.0f | %6.3f | %7.4f | %d |\n",
            r->method, setting, r->init_ms, r->tables_ms, r->frame_med_ms, r->frame_p99_ms, r->frame_max_ms,
            brute_med > 0.0 ? r->frame_med_ms / brute_med : NAN, r->select_med_ms,
            r->select_max_ms, r->triangles_mean, r->tiles_mean, r->err_max_px, r->err_mean_px,
            r->budget_hits);
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *md_path = NULL;
    int frames = 40;
    double ks[BENCH_LIST_MAX] = {2, 3, 4}, taus[BENCH_LIST_MAX] = {0.5, 1, 2, 4};
    int nk = 3, nt = 4;
    uint32_t gcols[BENCH_LIST_MAX] = {200, 430}, grows[BENCH_LIST_MAX] = {800, 430};
    int ng = 2, with_bintree = 1, with_pgm = 0;
    uint32_t w = 640, h = 480;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "--frames") == 0 && v) { frames = atoi(v); ++i; }
        else if (strcmp(a, "--size") == 0 && v && sscanf(v, "%ux%u", &w, &h) == 2) { ++i; }
        else if (strcmp(a, "--ks") == 0 && v) { nk = parse_list(v, ks, BENCH_LIST_MAX); ++i; }
        else if (strcmp(a, "--taus") == 0 && v) { nt = parse_list(v, taus, BENCH_LIST_MAX); ++i; }
        else if (strcmp(a, "--md") == 0 && v) { md_path = v; ++i; }
        else if (strcmp(a, "--grids") == 0 && v) { ng = parse_grids(v, gcols, grows, BENCH_LIST_MAX); ++i; }
        else if (strcmp(a, "--methods") == 0 && v) {
            /* brute always runs (the base of the ratios); listing it is allowed */
            with_bintree = strstr(v, "bintree") != NULL;
            with_pgm = strstr(v, "pgm") != NULL;
            for (const char *q = v; *q != '\0';) {
                const size_t len = strcspn(q, ",");
                if (!(len == 5 && strncmp(q, "brute", 5) == 0) &&
                    !(len == 7 && strncmp(q, "bintree", 7) == 0) &&
                    !(len == 3 && strncmp(q, "pgm", 3) == 0)) {
                    fprintf(stderr, "%s: --methods takes brute, bintree, pgm\n", argv[0]);
                    return 2;
                }
                q += len + (q[len] == ',');
            }
            ++i;
        }
        else if (a[0] != '-' && scene_path == NULL) { scene_path = a; }
        else {
            fprintf(stderr, "usage: %s SCENE.ini [--frames N] [--size WxH] [--ks 2,3,4] "
                            "[--taus 0.5,1,2,4] [--methods bintree,pgm] "
                            "[--grids 200x800,430x430] [--md OUT.md]\n", argv[0]);
            return 2;
        }
    }
    if (scene_path == NULL || frames < 2 || frames >= BENCH_FRAMES_MAX || nk <= 0 || nt <= 0 ||
        ng <= 0) {
        fprintf(stderr, "%s: need a scene file, 2 <= frames < %d, and non-empty lists\n", argv[0],
                BENCH_FRAMES_MAX);
        return 2;
    }
    FILE *sf = fopen(scene_path, "rb");
    if (sf == NULL) {
        fprintf(stderr, "%s: cannot open %s\n", argv[0], scene_path);
        return 1;
    }
    size_t n = fread(g_scene_text, 1, sizeof g_scene_text - 1u, sf);
    fclose(sf);
    g_scene_text[n] = '\0';
    ft_scene base;
    ft_error err;
    ft_scene_defaults(&base);
    if (ft_scene_parse(&base, g_scene_text, scene_path, &err) != FT_OK) {
        fprintf(stderr, "%s\n", err.text);
        return 1;
    }
    /* dem paths in a scene file are relative to the file */
    if (base.dem_path[0] != '\0' && base.dem_path[0] != '/') {
        char dir[FT_SCENE_PATH_MAX], joined[FT_SCENE_PATH_MAX * 2];
        (void)snprintf(dir, sizeof dir, "%s", scene_path);
        char *slash = strrchr(dir, '/');
        if (slash != NULL) {
            *slash = '\0';
            int len = snprintf(joined, sizeof joined, "%s/%s", dir, base.dem_path);
            if (len < 0 || (size_t)len >= sizeof base.dem_path) {
                fprintf(stderr, "%s: dem path too long\n", argv[0]);
                return 1;
            }
            memcpy(base.dem_path, joined, (size_t)len + 1u);
        }
    }
    base.width_px = w;
    base.height_px = h;

    static bench_row rows[1 + BENCH_LIST_MAX * BENCH_LIST_MAX + BENCH_LIST_MAX];
    int nrows = 0;
    printf("bench: %s, %ux%u, %d frames per run (+1 warm-up)\n", scene_path, w, h, frames);
    if (!run(&base, "brute", 0, 0.0, 0, 0, frames, &rows[nrows])) return 1;
    printf("  brute done: median %.1f ms\n", rows[nrows].frame_med_ms);
    ++nrows;
    for (int a = 0; a < nk && with_bintree; ++a) {
        for (int b = 0; b < nt; ++b) {
            if (!run(&base, "bintree", (uint32_t)ks[a], taus[b], 0, 0, frames, &rows[nrows])) {
                return 1;
            }
            printf("  bintree k=%g tau=%g done: median %.1f ms\n", ks[a], taus[b],
                   rows[nrows].frame_med_ms);
            ++nrows;
        }
    }
    for (int g = 0; g < ng && with_pgm; ++g) {
        if (!run(&base, "pgm", 0, 0.0, gcols[g], grows[g], frames, &rows[nrows])) return 1;
        printf("  pgm %ux%u done: median %.1f ms\n", gcols[g], grows[g], rows[nrows].frame_med_ms);
        ++nrows;
    }
    FILE *outs[2] = {stdout, NULL};
    if (md_path != NULL) {
        outs[1] = fopen(md_path, "w");
        if (outs[1] == NULL) {
            fprintf(stderr, "%s: cannot write %s\n", argv[0], md_path);
            return 1;
        }
    }
    for (int o = 0; o < 2; ++o) {
        FILE *f = outs[o];
        if (f == NULL) continue;
        fprintf(f, "\n%s, %ux%u, %d frames (orbit r = 6 km), renderer %s\n\n", scene_path, w, h,
                frames, g_gl_renderer);
        fprintf(f, "| method   | setting        |  init ms | tables ms | frame ms | p99 ms   | max ms   | "
                   "x brute | sel ms  | sel max | triangles  |   tiles | max px | mean px | "
                   "budget hits |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (int r = 0; r < nrows; ++r) print_row(f, &rows[r], rows[0].frame_med_ms);
    }
    if (outs[1] != NULL) fclose(outs[1]);
    return 0;
}
