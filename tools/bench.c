/* bench.c - `fixterrain bench`: error against run time (see bench.h).
 *
 * One run = one (method, setting): a fresh ft_app (terrain, GPU context,
 * method tables), one untimed warm-up frame (shader compilation), then every
 * path's frames. The settings of a method are the product of its axes
 * (default: bintree template_k x tau_px, pgm grid sizes; --settings replaces
 * an axis or adds one); each setting becomes a few INI lines parsed over the
 * scene, so any key of the method's section can be swept.
 *
 * The reference (CPU ray caster) depends only on the camera, so the first
 * run that measures a frame keeps its reference pixels and later runs only
 * draw their position pass and compute the metric against the copy (up to
 * --ref-cache-mb; a frame whose camera differs is recomputed).
 *
 * Bintree runs also time an oracle per frame (bench_oracle.h): the frame's
 * triangles as a pre-transformed mesh with a trivial vertex shader, the
 * floor for that triangle set; the row reports its median and the row's
 * median over it. */
#define _POSIX_C_SOURCE 200809L
#include "bench.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "app/cli.h"
#include "app/frame.h"
#include "bench_oracle.h"
#include "core/platform_api.h"
#include "measure/metric.h"
#include "terrain/default_view.h"
#include "flight_path.h"
#include "plot.h"

#define BENCH_EXIT_OK FT_CLI_OK
#define BENCH_EXIT_ERROR FT_CLI_ERROR
#define BENCH_EXIT_USAGE FT_CLI_USAGE

#define BENCH_METHODS_MAX 8
#define BENCH_AXES_MAX 6
#define BENCH_VALUES_MAX 16
#define BENCH_NAME_LEN 32
#define BENCH_VALUE_LEN 32
#define BENCH_USER_AXES_MAX 16
#define BENCH_SETTINGS_MAX 96
/* pgrid's ray-cast fraction on a frame that shows a sliver of terrain (the
 * tops of a far ridge along the image's edge) is its silhouette band: such
 * frames (terrain under 2% of the image) are counted apart */
#define BENCH_RC_SHARE_MIN 0.02
/* a frame is over its reported bound by more than the metric's rounding
 * (the bound tests' own margin) */
#define BENCH_BOUND_SLACK_PX 0.05
#define BENCH_ROWS_MAX 256
#define BENCH_LABEL_LEN 96
#define BENCH_INI_LEN 512
#define BENCH_PATHS_MAX 8
#define BENCH_FRAMES_MAX 1000
#define BENCH_MEASURED_MAX BENCH_FRAMES_MAX
#define BENCH_WAYPOINT_TEXT_MAX (FLIGHT_WAYPOINTS_MAX * FLIGHT_LINE_MAX)
#define BENCH_SIZE_DEFAULT "640x480" /* the view, unless --size */
#define BENCH_PLOT_W 800u
#define BENCH_PLOT_H 600u
#define BENCH_CLEARANCE_M 50.0  /* default: every pose this far above the ground near it */
#define BENCH_CLEAR_RADIUS_M 250.0 /* "near it": the highest ground within this radius */
#define BENCH_HOVER_AGL_M 1000.0 /* nadir hover height above the ground */
#define BENCH_CLIMB_DURATION_S 300.0
/* A method reading the clipmap cache gets its cache run between measured
 * frames as a display would run it (--cache-hz, default 60: a selection and
 * half a frame of spare time per display frame, untimed); at a path's start
 * it settles (at most BENCH_CACHE_SETTLE_MAX display frames) */
#define BENCH_CACHE_HZ 60.0
#define BENCH_CACHE_SETTLE_MAX 4096

/* ---- settings ------------------------------------------------------------------ */

typedef struct bench_axis {
    char method[BENCH_NAME_LEN]; /* scene section = method name */
    char key[BENCH_NAME_LEN];    /* key, or "grid" = grid_cols x grid_rows */
    char values[BENCH_VALUES_MAX][BENCH_VALUE_LEN];
    int count;
    int user; /* from --settings (else a default axis) */
} bench_axis;

typedef struct bench_setting {
    char label[BENCH_LABEL_LEN];       /* "template_k=3 tau_px=1", "default" */
    char short_label[BENCH_LABEL_LEN]; /* "k3 tau1" (plot) */
    char ini[BENCH_INI_LEN];           /* "[bintree]\ntemplate_k = 3\n..." */
} bench_setting;

typedef struct bench_method {
    char name[BENCH_NAME_LEN];
    ft_method_kind kind;
    bench_axis axes[BENCH_AXES_MAX];
    int axis_count;
} bench_method;

/* Defaults: tau and gamma in {0.5, 1, 2, 4}, the bintree's template sizes,
 * pgm's grid sizes (cols x rows), and pgrid on the paper's wide and tall
 * grids (1024x512, 400x1900: where its ray-cast share is judged) beside
 * 200x800 (other pgrid keys: the scene's), and clipmap's level side (its
 * level count and transition: the scene's). */
static const struct {
    const char *method, *key, *values;
} k_default_axes[] = {
    {"bintree", "template_k", "2,3,4"},
    {"bintree", "tau_px", "0.5,1,2,4"},
    {"pgm", "grid", "150x600,200x800,430x430,300x900,600x600,400x1600"},
    {"pgrid", "grid", "200x800,1024x512,400x1900"},
    {"pgrid", "gamma_px", "0.5,1,2,4"},
    {"clipmap", "side", "128,256,512"},
};

/* Short names for plot labels ("" = the value alone). */
static const struct {
    const char *key, *abbrev;
} k_abbrev[] = {
    {"template_k", "k"}, {"tau_px", "tau"}, {"gamma_px", "gamma"}, {"grid", ""},
};

/* ---- results ------------------------------------------------------------------- */

typedef struct bench_row {
    char method[BENCH_NAME_LEN];
    bench_setting setting;
    int ok;
    char note[200]; /* why a run failed */
    int frames, measured;
    double init_ms;
    double t_med_ms, t_p99_ms, t_max_ms, sel_med_ms;
    double err_max_px, err_p999_px, err_mean_px;
    char err_max_where[56]; /* "valley frame 12": %.32s + " frame " + an int */
    uint32_t cov_max_px;
    double cov_mean_px;
    uint32_t occl_max_px;     /* occlusion-mismatch pixels, worst frame */
    double occl_mean_px;      /* ... mean over the measured frames */
    double occl_err_max_px;   /* worst occlusion error (already inside err_max_px) */
    uint64_t nonfinite_px;
    double tri_mean;
    int budget_hits;
    /* pgrid: ray-cast pixels over the error buffer's terrain pixels, mean and
     * largest over the frames with terrain (0 for the other methods; above 1
     * when the silhouette's one-pixel widening adds more sky than is left out) */
    double rc_frac_mean, rc_frac_max;
    int rc_frames;
    /* the same over the measured frames: the largest, the largest where the
     * terrain covers at least BENCH_RC_SHARE_MIN of the image, and how many
     * measured frames show less terrain than that */
    double rc_frac_max_measured, rc_frac_max_view;
    int rc_small_frames;
    /* methods reading the clipmap cache: frames whose eye surroundings were
     * drawn from a level past 0 (the cache behind), frames with a level
     * behind, and the largest error of the measured frames not on coarser
     * data */
    int coarser_frames, behind_frames;
    double err_max_fine_px;
    double path_t_med_ms[BENCH_PATHS_MAX], path_err_max_px[BENCH_PATHS_MAX];
    double path_err_p999_px[BENCH_PATHS_MAX];
    /* bintree: the oracle's frames (bench_oracle.h), their median time; NAN
     * (empty in the CSV) for other methods or with --no-oracle */
    int oracle_frames;
    double oracle_med_ms;
    /* the largest bound a frame reported, and (bintree) the frames whose bound
     * was over the selection's target: a leaf tile near the eye over tau */
    double tau_achieved_max_px;
    int bound_short_frames;
    /* a method that reports a bound (bintree, pgrid, clipmap: > 0): the
     * measured frames whose max error is over it (by the metric's
     * resolution: over max(bound, FT_METRIC_FLIP_PX) + BENCH_BOUND_SLACK_PX),
     * and those whose bound is infinite (none: a clipmap level finer than
     * the data, a lagging cache) */
    int bound_over_frames, bound_none_frames;
    /* the worst vertical error alone (a drawn point's screen displacement, what
     * a bound is about; err_max_px adds the occlusion errors) and the measured
     * frames whose vertical error is over the bound by the same rule */
    double err_max_vertical_px;
    int bound_over_vertical_frames;
} bench_row;

typedef struct bench_path {
    char name[64];
    char desc[200];
    int is_file, is_hover;
    int builtin; /* flight_builtin_kind */
    int raised;  /* poses lifted to the clearance above the ground */
    ft_pose pose[BENCH_FRAMES_MAX];
} bench_path;

typedef struct ref_cache_entry {
    ft_ref_pixel *ref;
    double eye[3], fwd[3], up[3], fovy, near_m, far_m;
} ref_cache_entry;

typedef struct bench_opts {
    const char *scene_path, *dem, *methods, *paths, *csv, *plot, *report, *size, *backend;
    const char *centre, *plot_error;
    int frames, every, quiet, no_oracle;
    double ref_cache_mb, clearance_m, cache_hz;
    const char *settings[BENCH_USER_AXES_MAX];
    int settings_count;
} bench_opts;

static ft_app g_app;
static char g_scene_text[FT_SCENE_TEXT_MAX];
static char g_wp_text[BENCH_WAYPOINT_TEXT_MAX];
static flight_path g_fp[BENCH_PATHS_MAX];
static bench_path g_paths[BENCH_PATHS_MAX];
static int g_path_count;
static int g_poses_ready;
static bench_method g_methods[BENCH_METHODS_MAX];
static int g_method_count;
static bench_axis g_user_axes[BENCH_USER_AXES_MAX];
static int g_user_axis_count;
static bench_setting g_settings[BENCH_SETTINGS_MAX];
static bench_row g_rows[BENCH_ROWS_MAX];
static int g_row_count;
static double g_frame_ms[BENCH_PATHS_MAX * BENCH_FRAMES_MAX];
static double g_select_ms[BENCH_PATHS_MAX * BENCH_FRAMES_MAX];
static double g_oracle_ms[BENCH_PATHS_MAX * BENCH_FRAMES_MAX];
static bench_oracle g_oracle;
static ref_cache_entry g_cache[BENCH_PATHS_MAX][BENCH_MEASURED_MAX];
static size_t g_cache_bytes, g_cache_cap_bytes;
static uint8_t g_plot_rgba[BENCH_PLOT_W * BENCH_PLOT_H * 4u];
static char g_renderer_name[600];
static int g_tty;

/* ---- small helpers ------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* q-quantile (nearest rank) of v[0..n), sorts v */
static double quantile(double *v, int n, double q)
{
    if (n <= 0) return NAN;
    qsort(v, (size_t)n, sizeof v[0], cmp_double);
    int r = (int)ceil(q * n - 1e-9) - 1;
    if (r < 0) r = 0;
    if (r >= n) r = n - 1;
    return v[r];
}

/* Copies src, cut to cap - 1 characters. */
static void set_str(char *dst, size_t cap, const char *src)
{
    size_t n = strlen(src);
    if (n >= cap) n = cap - 1u;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

static int copy_str(char *dst, size_t cap, const char *src, size_t len)
{
    if (len >= cap) return 0;
    memcpy(dst, src, len);
    dst[len] = '\0';
    return 1;
}

/* Appends printf text; returns 0 when it does not fit. */
static int append(char *buf, size_t cap, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

static int append(char *buf, size_t cap, const char *fmt, ...)
{
    size_t len = strlen(buf);
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + len, cap - len, fmt, ap);
    va_end(ap);
    return n >= 0 && (size_t)n < cap - len;
}

static int method_built(ft_method_kind k)
{
    switch (k) {
    case FT_METHOD_BRUTE: return FT_WITH_METHOD_BRUTE;
    case FT_METHOD_BINTREE: return FT_WITH_METHOD_BINTREE;
    case FT_METHOD_PGM: return FT_WITH_METHOD_PGM;
    case FT_METHOD_PGRID: return FT_WITH_METHOD_PGRID;
    default: return 1; /* a newer method: ft_app_init says if it is missing */
    }
}

static void built_methods_text(char *buf, size_t cap)
{
    buf[0] = '\0';
    for (int m = 0; m < FT_METHOD_COUNT; ++m) {
        if (method_built((ft_method_kind)m)) {
            (void)append(buf, cap, "%s%s", buf[0] ? ", " : "", ft_method_name((ft_method_kind)m));
        }
    }
}

/* Splits "a,b,c" into values; 0 on an empty or too long item. */
static int split_values(const char *text, char out[][BENCH_VALUE_LEN], int max, int *count)
{
    *count = 0;
    const char *p = text;
    for (;;) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == 0 || *count >= max || !copy_str(out[*count], BENCH_VALUE_LEN, p, len)) return 0;
        ++*count;
        if (e == NULL) return 1;
        p = e + 1;
    }
}

/* "CxR" -> cols, rows */
static int parse_grid(const char *v, unsigned *cols, unsigned *rows)
{
    char tail;
    return sscanf(v, "%ux%u%c", cols, rows, &tail) == 2;
}

/* ---- settings -------------------------------------------------------------------- */

/* A setting becomes INI lines parsed over the scene: a control character
 * (a newline) in it could start a line of its own, e.g. a [pose] section. */
static int settings_text_ok(const char *spec)
{
    for (size_t i = 0; spec[i] != '\0'; ++i) {
        const unsigned char c = (unsigned char)spec[i];
        if (c < 0x20u || c > 0x7eu) {
            fprintf(stderr, "fixterrain bench: --settings: byte 0x%02x at offset %zu is %s; a "
                            "setting is printable ASCII (METHOD.KEY=V1,V2,...)\n",
                    c, i, c < 0x20u || c == 0x7fu ? "a control character" : "not ASCII");
            return 0;
        }
    }
    return 1;
}

/* A scene key: lower-case letters, digits and '_' (so no '[' or '=' either). */
static int key_name_ok(const char *k)
{
    if (k[0] == '\0') return 0;
    for (const char *p = k; *p != '\0'; ++p) {
        if (!((*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9') || *p == '_')) return 0;
    }
    return 1;
}

/* One --settings SPEC: "method.key=v1,v2[;method.key=...]". */
static int parse_settings_spec(const char *spec)
{
    if (!settings_text_ok(spec)) return 0;
    const char *p = spec;
    while (*p != '\0') {
        const char *e = strchr(p, ';');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        char item[BENCH_INI_LEN];
        if (!copy_str(item, sizeof item, p, len)) {
            fprintf(stderr, "fixterrain bench: --settings item too long\n");
            return 0;
        }
        p = e ? e + 1 : p + len;
        if (item[0] == '\0') continue;
        char *dot = strchr(item, '.'), *eq = strchr(item, '=');
        if (dot == NULL || eq == NULL || dot > eq) {
            fprintf(stderr, "fixterrain bench: --settings '%s': expected METHOD.KEY=V1,V2,...\n",
                    item);
            return 0;
        }
        *dot = '\0';
        *eq = '\0';
        ft_method_kind k;
        if (!ft_method_from_name(item, &k)) {
            fprintf(stderr, "fixterrain bench: --settings: '%s' is not a method\n", item);
            return 0;
        }
        if (g_user_axis_count >= BENCH_USER_AXES_MAX) {
            fprintf(stderr, "fixterrain bench: at most %d --settings keys\n", BENCH_USER_AXES_MAX);
            return 0;
        }
        bench_axis *a = &g_user_axes[g_user_axis_count];
        memset(a, 0, sizeof *a);
        if (!copy_str(a->method, sizeof a->method, item, strlen(item)) ||
            !copy_str(a->key, sizeof a->key, dot + 1, strlen(dot + 1)) || a->key[0] == '\0' ||
            !split_values(eq + 1, a->values, BENCH_VALUES_MAX, &a->count)) {
            fprintf(stderr, "fixterrain bench: --settings %s.%s: bad key or values (at most %d "
                            "values of %d characters)\n",
                    item, dot + 1, BENCH_VALUES_MAX, BENCH_VALUE_LEN - 1);
            return 0;
        }
        if (!key_name_ok(a->key)) {
            fprintf(stderr, "fixterrain bench: --settings %s.%s: not a scene key (a-z, 0-9, _)\n",
                    item, a->key);
            return 0;
        }
        a->user = 1;
        ++g_user_axis_count;
    }
    return 1;
}

/* The scene keys an axis writes ("grid" writes grid_cols and grid_rows). */
static int axis_writes(const bench_axis *a, const char *scene_key)
{
    if (strcmp(a->key, "grid") == 0) {
        return strcmp(scene_key, "grid_cols") == 0 || strcmp(scene_key, "grid_rows") == 0 ||
               strcmp(scene_key, "grid") == 0;
    }
    return strcmp(a->key, scene_key) == 0 ||
           (strcmp(scene_key, "grid") == 0 &&
            (strcmp(a->key, "grid_cols") == 0 || strcmp(a->key, "grid_rows") == 0));
}

/* Adds axis a to bm; an axis of --settings replaces (narrows) a default axis
 * that writes the same scene key. Two --settings axes writing one key, or
 * more than BENCH_AXES_MAX axes, cannot be honoured: 0 with the reason. */
static int add_axis(bench_method *bm, const bench_axis *a)
{
    for (int i = 0; i < bm->axis_count; ++i) {
        if (!axis_writes(&bm->axes[i], a->key)) continue;
        if (bm->axes[i].user && a->user) {
            fprintf(stderr, "fixterrain bench: --settings %s.%s and %s.%s set the same key: "
                            "give its values once\n",
                    bm->name, bm->axes[i].key, bm->name, a->key);
            return 0;
        }
        bm->axes[i] = *a;
        return 1;
    }
    if (bm->axis_count >= BENCH_AXES_MAX) {
        char have[BENCH_AXES_MAX * (BENCH_NAME_LEN + 1)] = "";
        for (int i = 0; i < bm->axis_count; ++i) {
            (void)append(have, sizeof have, "%s%s", i ? ", " : "", bm->axes[i].key);
        }
        fprintf(stderr, "fixterrain bench: --settings %s.%s: %s already sweeps %d axes (%s; "
                        "defaults included), the most a method has\n",
                bm->name, a->key, bm->name, bm->axis_count, have);
        return 0;
    }
    bm->axes[bm->axis_count++] = *a;
    return 1;
}

static int method_axes(bench_method *bm)
{
    bm->axis_count = 0;
    for (size_t i = 0; i < sizeof k_default_axes / sizeof k_default_axes[0]; ++i) {
        if (strcmp(k_default_axes[i].method, bm->name) != 0) continue;
        bench_axis a;
        memset(&a, 0, sizeof a);
        set_str(a.method, sizeof a.method, bm->name);
        set_str(a.key, sizeof a.key, k_default_axes[i].key);
        (void)split_values(k_default_axes[i].values, a.values, BENCH_VALUES_MAX, &a.count);
        if (!add_axis(bm, &a)) return 0;
    }
    for (int i = 0; i < g_user_axis_count; ++i) {
        if (strcmp(g_user_axes[i].method, bm->name) == 0 && !add_axis(bm, &g_user_axes[i])) {
            return 0;
        }
    }
    return 1;
}

static const char *abbrev(const char *key)
{
    for (size_t i = 0; i < sizeof k_abbrev / sizeof k_abbrev[0]; ++i) {
        if (strcmp(k_abbrev[i].key, key) == 0) return k_abbrev[i].abbrev;
    }
    return key;
}

/* Every setting of a method (product of its axes, the first axis slowest).
 * Returns the count, -1 on a bad value (message printed). */
static int method_settings(const bench_method *bm, bench_setting *out, int cap)
{
    int idx[BENCH_AXES_MAX] = {0};
    int n = 0;
    for (;;) {
        if (n >= cap) {
            fprintf(stderr, "fixterrain bench: %s: more than %d settings\n", bm->name, cap);
            return -1;
        }
        bench_setting *s = &out[n];
        memset(s, 0, sizeof *s);
        (void)snprintf(s->ini, sizeof s->ini, "[%.31s]\n", bm->name);
        for (int a = 0; a < bm->axis_count; ++a) {
            const bench_axis *ax = &bm->axes[a];
            const char *v = ax->values[idx[a]];
            int fits = append(s->label, sizeof s->label, "%s%s=%s", a ? " " : "", ax->key, v) &&
                       append(s->short_label, sizeof s->short_label, "%s%s%s", a ? " " : "",
                              abbrev(ax->key), v);
            if (strcmp(ax->key, "grid") == 0) {
                unsigned c, r;
                if (!parse_grid(v, &c, &r)) {
                    fprintf(stderr, "fixterrain bench: %s.grid '%s': expected COLSxROWS\n",
                            bm->name, v);
                    return -1;
                }
                fits = fits && append(s->ini, sizeof s->ini, "grid_cols = %u\ngrid_rows = %u\n",
                                      c, r);
            } else {
                fits = fits && append(s->ini, sizeof s->ini, "%s = %s\n", ax->key, v);
            }
            if (!fits) {
                fprintf(stderr, "fixterrain bench: %s: setting text too long\n", bm->name);
                return -1;
            }
        }
        if (bm->axis_count == 0) {
            (void)snprintf(s->label, sizeof s->label, "default");
            s->short_label[0] = '\0';
        }
        ++n;
        int a = bm->axis_count - 1;
        while (a >= 0 && ++idx[a] >= bm->axes[a].count) {
            idx[a] = 0;
            --a;
        }
        if (a < 0) return n;
    }
}

/* ---- paths ------------------------------------------------------------------------ */

static int read_text_file(const char *path, char *buf, size_t cap, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) return 0;
    size_t n = fread(buf, 1, cap - 1u, f);
    int big = (n == cap - 1u && fgetc(f) != EOF);
    fclose(f);
    if (big) return 0;
    buf[n] = '\0';
    *len = n;
    return 1;
}

/* Phase 1 (before any run): names and waypoint files are checked. */
static int prepare_path(const char *spec, const ft_scene *base, bench_path *bp, flight_path *fp)
{
    memset(bp, 0, sizeof *bp);
    set_str(bp->name, sizeof bp->name, spec);
    if (strcmp(spec, "hover") == 0) {
        bp->is_hover = 1;
        (void)snprintf(bp->desc, sizeof bp->desc,
                       "nadir hover: constant pose %g m above the ground, looking straight down",
                       BENCH_HOVER_AGL_M);
        return 1;
    }
    ft_error err;
    memset(&err, 0, sizeof err);
    int k = flight_builtin_from_name(spec);
    if (k >= 0) {
        flight_builtin_params prm;
        flight_builtin_defaults(&prm, (flight_builtin_kind)k);
        prm.centre_lat_deg = base->pose.lat_deg;
        prm.centre_lon_deg = base->pose.lon_deg;
        /* the default climb (900 s at 130 m/s) leaves a 1 deg tile */
        if (k == FLIGHT_CLIMB) prm.duration_s = BENCH_CLIMB_DURATION_S;
        if (flight_path_builtin(fp, &prm, &err) != FT_OK) {
            fprintf(stderr, "fixterrain bench: path %s: %s\n", spec, err.text);
            return 0;
        }
        bp->builtin = k;
        const flight_waypoint *w0 = &fp->wp[0];
        (void)snprintf(bp->desc, sizeof bp->desc,
                       "built-in %.16s, %.0f s, heading %03.0f at the start, altitudes above the "
                       "ground at the start (%.0f m at t0)",
                       spec, flight_path_duration_s(fp), w0->heading_deg, w0->alt_m);
        return 1;
    }
    size_t len = 0;
    if (!read_text_file(spec, g_wp_text, sizeof g_wp_text, &len)) {
        fprintf(stderr, "fixterrain bench: --path %s: not a built-in path (valley, climb, "
                        "turn360, dive, hover, orbit) and not a readable waypoint file of at "
                        "most %u bytes\n",
                spec, (unsigned)sizeof g_wp_text - 1u);
        return 0;
    }
    if (flight_path_parse_waypoints(fp, g_wp_text, len, spec, &err) != FT_OK) {
        fprintf(stderr, "fixterrain bench: %s\n", err.text);
        return 0;
    }
    bp->is_file = 1;
    const char *slash = strrchr(spec, '/');
    set_str(bp->name, sizeof bp->name, slash ? slash + 1 : spec);
    (void)snprintf(bp->desc, sizeof bp->desc, "waypoint file %.100s: %u waypoints, %.1f s, altitudes "
                   "as given (m)", spec, fp->count, flight_path_duration_s(fp));
    return 1;
}

static double ground_m(const ft_terrain *t, double lat, double lon)
{
    double x, y;
    ft_terrain_geo_to_world(t, lat, lon, &x, &y);
    return ft_terrain_height_at(t, x, y);
}

/* Highest ground at the point and on a 9 x 9 lattice within r metres of it. */
static double ground_max_m(const ft_terrain *t, double lat, double lon, double r)
{
    double x, y, h = -INFINITY;
    ft_terrain_geo_to_world(t, lat, lon, &x, &y);
    for (int i = -4; i <= 4; ++i) {
        for (int j = -4; j <= 4; ++j) {
            if (i * i + j * j > 16) continue;
            h = fmax(h, ft_terrain_height_at(t, x + r * i / 4.0, y + r * j / 4.0));
        }
    }
    return h;
}

/* The pose of a (non-hover) path at path time tt: lifted to the clearance
 * above the ground near it (returns 1 when it was). */
static int pose_at(const bench_path *bp, const flight_path *fp, const ft_scene *base,
                   const ft_terrain *t, double tt, double clearance_m, ft_pose *p)
{
    const double g0 = ground_m(t, base->pose.lat_deg, base->pose.lon_deg);
    flight_sample s;
    flight_path_sample(fp, tt, &s);
    p->lat_deg = s.lat_deg;
    p->lon_deg = s.lon_deg;
    p->alt_m = s.alt_m + (bp->is_file ? 0.0 : g0);
    p->heading_deg = s.heading_deg;
    p->pitch_deg = s.pitch_deg;
    p->roll_deg = s.roll_deg;
    const double floor_m =
        ground_max_m(t, p->lat_deg, p->lon_deg, BENCH_CLEAR_RADIUS_M) + clearance_m;
    if (p->alt_m < floor_m) {
        p->alt_m = floor_m;
        return 1;
    }
    return 0;
}

/* Path time of frame i of frames. */
static double frame_time_s(const flight_path *fp, int i, int frames)
{
    return flight_path_t0_s(fp) +
           flight_path_duration_s(fp) * (frames > 1 ? (double)i / (frames - 1) : 0.0);
}

/* Phase 2 (terrain loaded): the frames' poses. */
static void sample_path(bench_path *bp, const flight_path *fp, const ft_scene *base,
                        const ft_terrain *t, int frames, double clearance_m)
{
    const double lat0 = base->pose.lat_deg, lon0 = base->pose.lon_deg;
    const double g0 = ground_m(t, lat0, lon0);
    bp->raised = 0;
    for (int i = 0; i < frames; ++i) {
        ft_pose *p = &bp->pose[i];
        if (bp->is_hover) {
            p->lat_deg = lat0;
            p->lon_deg = lon0;
            p->alt_m = g0 + BENCH_HOVER_AGL_M;
            p->heading_deg = base->pose.heading_deg;
            p->pitch_deg = -90.0;
            p->roll_deg = 0.0;
            continue;
        }
        bp->raised += pose_at(bp, fp, base, t, frame_time_s(fp, i, frames), clearance_m, p);
    }
}

/* One display frame of the cache at pose: the method's selection, then
 * half a display frame of spare time (untimed by the bench). */
static void cache_step(const ft_pose *pose, double hz)
{
    ft_camera cam;
    ft_error err;
    if (ft_renderer_camera(&g_app.renderer, pose, &cam, &err) != FT_OK) {
        return; /* the measured frame reports it */
    }
    ft_method_select(&g_app.renderer.method, &g_app.terrain, &cam);
    const uint64_t t0 = ft_plat_monotonic_ns();
    ft_method_spare(&g_app.renderer.method, ft_plat_monotonic_ns,
                    t0 + (uint64_t)(0.5e9 / hz));
}

/* Before frame i of path p: the display frames since the previous measured
 * frame (their poses on the path, every 1 / hz s of path time), or at a
 * path's first frame the display settling there (the bench jumps between
 * paths; a display would have flown there). */
static void cache_catch_up(int p, int i, const bench_opts *o, const ft_scene *base)
{
    const ft_method *m = &g_app.renderer.method;
    const ft_clip_cache *c = ft_method_cache(m);
    if (c == NULL || !(o->cache_hz > 0.0)) {
        return;
    }
    const bench_path *bp = &g_paths[p];
    if (i == 0 || bp->is_hover) {
        for (int k = 0; k < BENCH_CACHE_SETTLE_MAX && (k < 2 || c->stats.levels_behind > 0u);
             ++k) {
            cache_step(&bp->pose[i], o->cache_hz);
        }
        return;
    }
    const flight_path *fp = &g_fp[p];
    const double ta = frame_time_s(fp, i - 1, o->frames), tb = frame_time_s(fp, i, o->frames);
    const double steps = floor((tb - ta) * o->cache_hz);
    /* bounded: a path lasts minutes, at most hz x its duration steps */
    for (double k = 1.0; k < steps; k += 1.0) {
        ft_pose pose;
        (void)pose_at(bp, fp, base, &g_app.terrain, ta + k / o->cache_hz, o->clearance_m, &pose);
        cache_step(&pose, o->cache_hz);
    }
}

/* ---- one run ----------------------------------------------------------------------- */

static int cam_matches(const ref_cache_entry *c, const ft_camera *cam)
{
    for (int i = 0; i < 3; ++i) {
        if (c->eye[i] != cam->eye_m[i] || c->fwd[i] != cam->forward[i] || c->up[i] != cam->up[i])
            return 0;
    }
    return c->fovy == cam->fovy_rad && c->near_m == cam->near_m && c->far_m == cam->far_m;
}

static ft_status measure(int path, int slot, const ft_camera *cam, ft_error_stats *es,
                         ft_error *err)
{
    const size_t px = (size_t)g_app.scene.width_px * g_app.scene.height_px;
    ref_cache_entry *c = (slot < BENCH_MEASURED_MAX) ? &g_cache[path][slot] : NULL;
    if (c != NULL && c->ref != NULL && cam_matches(c, cam)) {
        ft_status s = ft_renderer_draw_positions(&g_app.renderer, cam, err);
        if (s != FT_OK) return s;
        const ft_terrain *truth = NULL;
        s = ft_app_truth(&g_app, cam, &truth, err);
        if (s != FT_OK) return s;
        return ft_metric_compute(truth, cam, g_app.renderer.pos, c->ref,
                                 g_app.metric_scratch,
                                 ft_metric_scratch_bytes(cam->width_px, cam->height_px), es, err);
    }
    ft_status s = ft_app_measure(&g_app, cam, es, err);
    if (s != FT_OK || c == NULL) return s;
    const size_t bytes = px * sizeof(ft_ref_pixel);
    if (c->ref == NULL && g_cache_bytes + bytes <= g_cache_cap_bytes) {
        c->ref = malloc(bytes);
        if (c->ref != NULL) g_cache_bytes += bytes;
    }
    if (c->ref != NULL) {
        memcpy(c->ref, g_app.ref, bytes);
        for (int i = 0; i < 3; ++i) {
            c->eye[i] = cam->eye_m[i];
            c->fwd[i] = cam->forward[i];
            c->up[i] = cam->up[i];
        }
        c->fovy = cam->fovy_rad;
        c->near_m = cam->near_m;
        c->far_m = cam->far_m;
    }
    return FT_OK;
}

static void progress(const bench_opts *o, int run, int runs, const bench_row *row,
                     const char *path, int i, int n)
{
    if (o->quiet) return;
    if (g_tty) {
        fprintf(stderr, "\rbench [%d/%d] %s %s: %s frame %d/%d   ", run, runs, row->method,
                row->setting.label, path, i, n);
    } else {
        int q = n >= 4 ? n / 4 : 1;
        if (i == 1 || i % q == 0 || i == n) {
            fprintf(stderr, "bench [%d/%d] %s %s: %s frame %d/%d\n", run, runs, row->method,
                    row->setting.label, path, i, n);
        }
    }
    (void)fflush(stderr);
}

static void run_one(const bench_opts *o, const ft_scene *base, const bench_method *bm,
                    const bench_setting *set, int run, int runs, bench_row *row)
{
    ft_scene s = *base;
    ft_error err;
    memset(&err, 0, sizeof err);
    memset(row, 0, sizeof *row);
    set_str(row->method, sizeof row->method, bm->name);
    row->setting = *set;
    row->oracle_med_ms = NAN;
    s.method = bm->kind;
    if (ft_scene_parse(&s, set->ini, "bench setting", &err) != FT_OK) {
        (void)snprintf(row->note, sizeof row->note, "setting: %.180s", err.text);
        return;
    }
    if (ft_app_init(&g_app, &s, &err) != FT_OK) {
        (void)snprintf(row->note, sizeof row->note, "init: %.180s", err.text);
        return; /* a failed init has released what it took */
    }
    row->init_ms = (double)g_app.init_ns * 1e-6;
    (void)snprintf(g_renderer_name, sizeof g_renderer_name, "%s / %s", g_app.gpu.version,
                   g_app.gpu.renderer);
    if (!g_poses_ready) {
        for (int p = 0; p < g_path_count; ++p) {
            sample_path(&g_paths[p], &g_fp[p], base, &g_app.terrain, o->frames, o->clearance_m);
        }
        g_poses_ready = 1;
    }
    /* the settings as set: no degradation */
    ft_frame_loop loop;
    ft_frame_loop_init(&loop, &g_app, 0);
    ft_frame fr;
    int ok = ft_frame_step(&loop, &g_app, &g_paths[0].pose[0], NULL, &fr, &err) == FT_OK; /* warm-up */
    ft_camera cam = fr.cam;
    ft_frame_stats st;
    const char *fail_what = "frame";
    int oracle = 0;
    if (ok && bm->kind == FT_METHOD_BINTREE && !o->no_oracle) {
        ft_error oerr;
        memset(&oerr, 0, sizeof oerr);
        if (bench_oracle_init(&g_oracle, &g_app.renderer, &oerr) == FT_OK) {
            oracle = 1;
            double ms;
            /* its own untimed warm-up (shader compilation) */
            ok = bench_oracle_prepare(&g_oracle, &g_app.renderer, &cam, &err) == FT_OK &&
                 bench_oracle_frame(&g_oracle, &g_app.renderer, &cam, &ms, &err) == FT_OK;
            if (!ok) fail_what = "oracle";
        } else {
            fprintf(stderr, "bench: %s %s: no oracle: %s\n", bm->name, set->label, oerr.text);
        }
    }
    double tri = 0.0, err_sum = 0.0, cov_sum = 0.0, occl_sum = 0.0;
    int timed = 0;
    row->err_max_px = 0.0;
    for (int p = 0; p < g_path_count && ok; ++p) {
        const int path_first = timed;
        row->path_err_max_px[p] = row->path_err_p999_px[p] = 0.0;
        for (int i = 0; i < o->frames && ok; ++i) {
            progress(o, run, runs, row, g_paths[p].name, i + 1, o->frames);
            cache_catch_up(p, i, o, base);
            if (ft_frame_step(&loop, &g_app, &g_paths[p].pose[i], NULL, &fr, &err) != FT_OK) {
                ok = 0;
                break;
            }
            cam = fr.cam;
            st = fr.stats;
            g_frame_ms[timed] = st.select_ms + st.gpu_ms;
            g_select_ms[timed] = st.select_ms;
            if (oracle) {
                /* the same frame's triangles: mirrored and uploaded (not
                 * timed), then drawn and read back (timed) */
                if (bench_oracle_prepare(&g_oracle, &g_app.renderer, &cam, &err) != FT_OK ||
                    bench_oracle_frame(&g_oracle, &g_app.renderer, &cam,
                                       &g_oracle_ms[row->oracle_frames], &err) != FT_OK) {
                    ok = 0;
                    fail_what = "oracle";
                    break;
                }
                ++row->oracle_frames;
            }
            ++timed;
            row->coarser_frames += st.cache_coarser != 0;
            row->behind_frames += st.cache_levels_behind > 0u;
            tri += (double)st.triangles;
            row->budget_hits += st.budget_hit != 0;
            row->tau_achieved_max_px = fmax(row->tau_achieved_max_px, st.tau_achieved_px);
            row->bound_short_frames +=
                (st.tau_target_px > 0.0 && st.tau_achieved_px > st.tau_target_px);
            /* pgrid's counts come one frame late (src/lod/pgrid.h 5): these
             * are frame i - 1's; the path's first frame holds the previous
             * path's last (not counted) and its last frame is never counted */
            if (i > 0 && st.terrain_px > 0u) {
                const double frac = (double)st.raycast_px / (double)st.terrain_px;
                row->rc_frac_mean += frac; /* a sum until the run ends */
                row->rc_frac_max = fmax(row->rc_frac_max, frac);
                row->rc_frames += 1;
                if ((i - 1) % o->every == 0) {
                    const double share = (double)st.terrain_px /
                                         ((double)g_app.scene.width_px * g_app.scene.height_px);
                    row->rc_frac_max_measured = fmax(row->rc_frac_max_measured, frac);
                    if (share >= BENCH_RC_SHARE_MIN) {
                        row->rc_frac_max_view = fmax(row->rc_frac_max_view, frac);
                    } else {
                        row->rc_small_frames += 1;
                    }
                }
            }
            if (i % o->every != 0) continue;
            ft_error_stats es;
            if (measure(p, i / o->every, &cam, &es, &err) != FT_OK) {
                ok = 0;
                break;
            }
            if (!st.cache_coarser) {
                row->err_max_fine_px = fmax(row->err_max_fine_px, es.max_px);
            }
            if (st.tau_achieved_px > 0.0 && isinf(st.tau_achieved_px)) {
                row->bound_none_frames += 1;
            } else if (st.tau_achieved_px > 0.0) {
                const double allowed =
                    fmax(st.tau_achieved_px, FT_METRIC_FLIP_PX) + BENCH_BOUND_SLACK_PX;
                row->bound_over_frames += es.max_px > allowed;
                row->bound_over_vertical_frames += es.vertical_max_px > allowed;
            }
            row->err_max_vertical_px = fmax(row->err_max_vertical_px, es.vertical_max_px);
            if (row->measured == 0 || es.max_px > row->err_max_px) {
                row->err_max_px = es.max_px;
                (void)snprintf(row->err_max_where, sizeof row->err_max_where, "%.32s frame %d",
                               g_paths[p].name, i);
            }
            if (row->measured == 0 || es.p999_px > row->err_p999_px) row->err_p999_px = es.p999_px;
            uint32_t cov = es.only_method_px + es.only_ref_px;
            if (cov > row->cov_max_px) row->cov_max_px = cov;
            cov_sum += cov;
            if (es.occlusion_px > row->occl_max_px) row->occl_max_px = es.occlusion_px;
            occl_sum += es.occlusion_px;
            row->occl_err_max_px = fmax(row->occl_err_max_px, es.occlusion_max_px);
            err_sum += es.mean_px;
            row->nonfinite_px += es.nonfinite_px;
            ++row->measured;
            row->path_err_max_px[p] = fmax(row->path_err_max_px[p], es.max_px);
            row->path_err_p999_px[p] = fmax(row->path_err_p999_px[p], es.p999_px);
        }
        /* sorts this path's slice; the whole-run quantiles below do not care */
        row->path_t_med_ms[p] = quantile(g_frame_ms + path_first, timed - path_first, 0.5);
    }
    if (!ok) {
        (void)snprintf(row->note, sizeof row->note, "%s: %.180s", fail_what, err.text);
    }
    if (oracle) bench_oracle_shutdown(&g_oracle);
    ft_app_shutdown(&g_app);
    if (o->quiet == 0 && g_tty) fputc('\n', stderr);
    if (!ok || timed == 0) return;
    row->ok = 1;
    row->frames = timed;
    row->tri_mean = tri / timed;
    if (row->rc_frames > 0) {
        row->rc_frac_mean /= (double)row->rc_frames;
    }
    row->t_max_ms = quantile(g_frame_ms, timed, 1.0);
    row->t_p99_ms = quantile(g_frame_ms, timed, 0.99);
    row->t_med_ms = quantile(g_frame_ms, timed, 0.5);
    row->sel_med_ms = quantile(g_select_ms, timed, 0.5);
    if (row->oracle_frames > 0) {
        row->oracle_med_ms = quantile(g_oracle_ms, row->oracle_frames, 0.5);
    }
    row->err_mean_px = row->measured ? err_sum / row->measured : NAN;
    row->cov_mean_px = row->measured ? cov_sum / row->measured : NAN;
    row->occl_mean_px = row->measured ? occl_sum / row->measured : NAN;
    if (row->measured == 0) row->err_max_px = row->err_p999_px = NAN;
}

/* ---- outputs ----------------------------------------------------------------------- */

static double brute_median(void)
{
    for (int r = 0; r < g_row_count; ++r) {
        if (g_rows[r].ok && strcmp(g_rows[r].method, "brute") == 0) return g_rows[r].t_med_ms;
    }
    return NAN;
}

static void paths_text(char *buf, size_t cap)
{
    buf[0] = '\0';
    for (int p = 0; p < g_path_count; ++p) {
        (void)append(buf, cap, "%s%s", p ? "+" : "", g_paths[p].name);
    }
}

/* A text field, quoted as RFC 4180 wants when it holds , " CR or LF. */
static void csv_text(FILE *f, const char *text, int first)
{
    char q[600]; /* the paths text (256) with every byte doubled, and quotes */
    if (!first) fputc(',', f);
    if (plot_csv_field(q, sizeof q, text)) fputs(q, f);
    else fputs("\"(too long)\"", f);
}

static void csv_num(FILE *f, double v, int decimals)
{
    if (isnan(v)) fputs(",", f);
    else if (isinf(v)) fputs(",inf", f);
    else fprintf(f, ",%.*f", decimals, v);
}

static int write_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "fixterrain bench: cannot write %s\n", path);
        return 0;
    }
    char paths[256];
    paths_text(paths, sizeof paths);
    const double bm = brute_median();
    fputs("method,setting,paths,frames,time_median_ms,time_p99_ms,time_max_ms,ratio_to_brute,"
          "select_median_ms,err_max_px,err_p999_px,err_mean_px,coverage_mismatch_px,"
          "coverage_mismatch_mean_px,nonfinite_px,measured_frames,triangles_mean,budget_hits,"
          "init_ms,occlusion_mismatch_px,occlusion_mismatch_mean_px,occlusion_err_max_px,"
          "raycast_fraction_mean,raycast_fraction_max,oracle_median_ms,x_oracle,"
          "tau_achieved_max_px,bound_short_frames,raycast_fraction_max_measured,"
          "raycast_fraction_max_measured_view,raycast_small_terrain_frames,"
          "cache_coarser_frames,cache_behind_frames,err_max_fine_px,bound_over_frames,"
          "bound_none_frames,err_max_vertical_px,bound_over_vertical_frames\n",
          f);
    for (int r = 0; r < g_row_count; ++r) {
        const bench_row *w = &g_rows[r];
        if (!w->ok) continue;
        csv_text(f, w->method, 1);
        csv_text(f, w->setting.label, 0);
        csv_text(f, paths, 0);
        fprintf(f, ",%d", w->frames);
        csv_num(f, w->t_med_ms, 3);
        csv_num(f, w->t_p99_ms, 3);
        csv_num(f, w->t_max_ms, 3);
        csv_num(f, bm > 0.0 ? w->t_med_ms / bm : NAN, 4);
        csv_num(f, w->sel_med_ms, 3);
        csv_num(f, w->err_max_px, 4);
        csv_num(f, w->err_p999_px, 4);
        csv_num(f, w->err_mean_px, 5);
        fprintf(f, ",%u", w->cov_max_px);
        csv_num(f, w->cov_mean_px, 1);
        fprintf(f, ",%llu,%d", (unsigned long long)w->nonfinite_px, w->measured);
        csv_num(f, w->tri_mean, 0);
        fprintf(f, ",%d", w->budget_hits);
        csv_num(f, w->init_ms, 1);
        fprintf(f, ",%u", w->occl_max_px);
        csv_num(f, w->occl_mean_px, 1);
        csv_num(f, w->occl_err_max_px, 2);
        csv_num(f, w->rc_frac_mean, 4);
        csv_num(f, w->rc_frac_max, 4);
        csv_num(f, w->oracle_med_ms, 3);
        csv_num(f, w->oracle_med_ms > 0.0 ? w->t_med_ms / w->oracle_med_ms : NAN, 4);
        csv_num(f, w->tau_achieved_max_px, 4);
        fprintf(f, ",%d", w->bound_short_frames);
        csv_num(f, w->rc_frac_max_measured, 4);
        csv_num(f, w->rc_frac_max_view, 4);
        fprintf(f, ",%d", w->rc_small_frames);
        fprintf(f, ",%d,%d", w->coarser_frames, w->behind_frames);
        csv_num(f, w->err_max_fine_px, 4);
        fprintf(f, ",%d,%d", w->bound_over_frames, w->bound_none_frames);
        csv_num(f, w->measured > 0 ? w->err_max_vertical_px : NAN, 4);
        fprintf(f, ",%d", w->bound_over_vertical_frames);
        fputc('\n', f);
    }
    int ok = fclose(f) == 0;
    if (!ok) fprintf(stderr, "fixterrain bench: write failed: %s\n", path);
    return ok;
}

static double plot_err(const bench_opts *o, const bench_row *w)
{
    return (o->plot_error != NULL && strcmp(o->plot_error, "p999") == 0) ? w->err_p999_px
                                                                           : w->err_max_px;
}

static int write_plot(const bench_opts *o, const ft_scene *base, const char *path)
{
    static double xs[BENCH_METHODS_MAX][BENCH_ROWS_MAX], ys[BENCH_METHODS_MAX][BENCH_ROWS_MAX];
    static const char *labels[BENCH_METHODS_MAX][BENCH_ROWS_MAX];
    static const plot_rgba colours[] = {{31, 119, 180, 255}, {214, 39, 40, 255},
                                        {44, 160, 44, 255},  {255, 127, 14, 255},
                                        {148, 103, 189, 255}, {140, 86, 75, 255},
                                        {227, 119, 194, 255}, {23, 190, 207, 255}};
    plot_chart ch;
    memset(&ch, 0, sizeof ch);
    char paths[256];
    char title[FT_SCENE_NAME_MAX + 32 + sizeof paths]; /* name, " WxH: ", paths: never cut */
    paths_text(paths, sizeof paths);
    (void)snprintf(title, sizeof title, "%.63s %ux%u: %.100s", base->name, base->width_px,
                   base->height_px, paths);
    ch.title = title;
    ch.x_label = "median frame time, ms (LOD selection + draw + readback)";
    ch.y_label = (o->plot_error != NULL && strcmp(o->plot_error, "p999") == 0)
                     ? "error p99.9, px (worst measured frame)"
                     : "max error, px (worst measured frame)";
    ch.y_log = 1;
    ch.y_floor = 1e-3;
    ch.hline[0] = 1.0;
    ch.hline[1] = 2.0;
    ch.hline_count = 2;
    double tmin = INFINITY, tmax = 0.0;
    for (int m = 0; m < g_method_count && ch.series_count < PLOT_SERIES_MAX; ++m) {
        plot_series *se = &ch.series[ch.series_count];
        size_t n = 0;
        for (int r = 0; r < g_row_count; ++r) {
            const bench_row *w = &g_rows[r];
            if (!w->ok || strcmp(w->method, g_methods[m].name) != 0) continue;
            xs[m][n] = w->t_med_ms;
            ys[m][n] = plot_err(o, w);
            labels[m][n] = w->setting.short_label;
            tmin = fmin(tmin, w->t_med_ms);
            tmax = fmax(tmax, w->t_med_ms);
            ++n;
        }
        if (n == 0) continue;
        se->name = g_methods[m].name;
        se->colour = colours[ch.series_count % (int)(sizeof colours / sizeof colours[0])];
        se->marker = (plot_marker_kind)(ch.series_count % PLOT_MARKER_COUNT);
        se->x = xs[m];
        se->y = ys[m];
        se->labels = labels[m];
        se->n = n;
        ++ch.series_count;
    }
    ch.x_log = tmin > 0.0 && tmax / tmin > 20.0;
    plot_image im = {g_plot_rgba, BENCH_PLOT_W, BENCH_PLOT_H};
    (void)plot_chart_draw(&im, &ch, NULL, NULL);
    char err[256];
    if (plot_write_png(path, &im, err, sizeof err) != 0) {
        fprintf(stderr, "fixterrain bench: %s\n", err);
        return 0;
    }
    return 1;
}

/* Fastest (median) setting of method m with max error (p99.9 when p999)
 * <= bound; -1 if none. */
static int fastest_within(const char *method, double bound, int p999)
{
    int best = -1;
    for (int r = 0; r < g_row_count; ++r) {
        const bench_row *w = &g_rows[r];
        const double e = p999 ? w->err_p999_px : w->err_max_px;
        if (!w->ok || strcmp(w->method, method) != 0 || !(e <= bound)) continue;
        if (best < 0 || w->t_med_ms < g_rows[best].t_med_ms) best = r;
    }
    return best;
}

static void bound_cell(FILE *f, int r, double bm)
{
    if (r < 0) {
        fputs(" none |", f);
        return;
    }
    const bench_row *w = &g_rows[r];
    fprintf(f, " %s: %.2f ms", w->setting.label, w->t_med_ms);
    if (bm > 0.0) fprintf(f, " (%.2fx brute)", w->t_med_ms / bm);
    fprintf(f, ", max %.3f px, p99.9 %.3f px |", w->err_max_px, w->err_p999_px);
}

static int write_report(const bench_opts *o, const ft_scene *base, const char *path,
                        double run_s)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "fixterrain bench: cannot write %s\n", path);
        return 0;
    }
    const double bm = brute_median();
    fprintf(f, "# fixterrain bench: %s\n\n", base->name);
    fprintf(f, "- scene `%s`, terrain `%s`, %ux%u, fovy %.0f deg\n",
            o->scene_path ? o->scene_path : "(embedded default)",
            base->dem_path[0] ? base->dem_path : "(synthetic)", base->width_px, base->height_px,
            base->fovy_deg);
    fprintf(f, "- renderer: %s\n", g_renderer_name);
    fprintf(f, "- %d frames per path, error against the reference on every %d%s frame "
               "(frames 0, %d, ...), one untimed warm-up frame per run\n",
            o->frames, o->every, o->every == 1 ? "st" : o->every == 2 ? "nd" : o->every == 3 ? "rd" : "th",
            o->every);
    fprintf(f, "- oracle (bintree rows, --no-oracle: none): per frame, the same frame's "
               "triangles as a static pre-transformed mesh (positions, normals and heights "
               "computed on the CPU and uploaded outside the timing) drawn with a trivial vertex "
               "shader and the same fragment shader, target and readback: the floor for that "
               "triangle set; `oracle ms (x)` = its median frame time (draw + readback) and the "
               "row's median over it\n");
    fprintf(f, "- coarser frames (methods reading the clipmap cache): frames whose eye "
               "surroundings came from a level past 0 because the cache was behind (the bench "
               "gives it no spare time, and its frames are far apart on a path); the max error "
               "of the measured frames without them beside it\n");
    fprintf(f, "- frame time = LOD selection + draw + readback (until the GPU is done); "
               "error = worst measured frame (max, p99.9), mean of the frames' means; coverage "
               "= pixels terrain in one image and sky in the other (worst frame); occlusion = pixels "
               "terrain in both but on different surfaces (worst frame; their error, the "
               "distance to the nearest agreeing pixel, is inside max and p99.9)\n");
    fprintf(f, "- bench run time: %.1f s\n\nPaths (centre %.4f, %.4f; every pose at least "
               "%.0f m above the highest ground within %.0f m):\n\n",
            run_s, base->pose.lat_deg, base->pose.lon_deg, o->clearance_m, BENCH_CLEAR_RADIUS_M);
    for (int p = 0; p < g_path_count; ++p) {
        fprintf(f, "- `%s`: %s; %d of %d poses raised to the floor\n", g_paths[p].name,
                g_paths[p].desc, g_paths[p].raised, o->frames);
    }
    fprintf(f, "\n| method | setting | median ms | p99 ms | max ms | x brute | oracle ms (x) | "
               "max px | p99.9 px | mean px | coverage px | occlusion px | triangles | ray cast "
               "%% mean / max | coarser frames (max px without) | bound: largest px, frames over "
               "/ without | worst frame |\n"
               "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int r = 0; r < g_row_count; ++r) {
        const bench_row *w = &g_rows[r];
        if (!w->ok) continue;
        char oracle[48] = "";
        if (w->oracle_med_ms > 0.0) {
            (void)snprintf(oracle, sizeof oracle, "%.2f (%.2fx)", w->oracle_med_ms,
                           w->t_med_ms / w->oracle_med_ms);
        }
        char bound[64] = "none reported";
        if (w->tau_achieved_max_px > 0.0) {
            (void)snprintf(bound, sizeof bound, "%.3f, %d / %d", w->tau_achieved_max_px,
                           w->bound_over_frames, w->bound_none_frames);
        }
        fprintf(f,
                "| %s | %s | %.2f | %.2f | %.2f | %.2f | %s | %.3f | %.3f | %.4f | %u | %u | %.0f "
                "| %.1f / %.1f | %d (%.3f) | %s | %s |\n",
                w->method, w->setting.label, w->t_med_ms, w->t_p99_ms, w->t_max_ms,
                bm > 0.0 ? w->t_med_ms / bm : NAN, oracle, w->err_max_px, w->err_p999_px,
                w->err_mean_px, w->cov_max_px, w->occl_max_px, w->tri_mean,
                100.0 * w->rc_frac_mean, 100.0 * w->rc_frac_max, w->coarser_frames,
                w->err_max_fine_px, bound, w->err_max_where);
    }
    if (g_path_count > 1) {
        fprintf(f, "\nPer path: median frame time ms / max error px / p99.9 px\n\n"
                   "| method | setting |");
        for (int p = 0; p < g_path_count; ++p) fprintf(f, " %s |", g_paths[p].name);
        fprintf(f, "\n|---|---|");
        for (int p = 0; p < g_path_count; ++p) fprintf(f, "---:|");
        fputc('\n', f);
        for (int r = 0; r < g_row_count; ++r) {
            const bench_row *w = &g_rows[r];
            if (!w->ok) continue;
            fprintf(f, "| %s | %s |", w->method, w->setting.label);
            for (int p = 0; p < g_path_count; ++p) {
                fprintf(f, " %.2f / %.3f / %.3f |", w->path_t_med_ms[p], w->path_err_max_px[p],
                        w->path_err_p999_px[p]);
            }
            fputc('\n', f);
        }
    }
    fprintf(f, "\n## Fastest setting by error bound (median frame time; error of the worst "
               "measured frame)\n\n"
               "| method | max error <= 1 px | max error <= 2 px | p99.9 <= 1 px | p99.9 <= 2 px "
               "|\n|---|---|---|---|---|\n");
    for (int m = 0; m < g_method_count; ++m) {
        fprintf(f, "| %s |", g_methods[m].name);
        bound_cell(f, fastest_within(g_methods[m].name, 1.0, 0), bm);
        bound_cell(f, fastest_within(g_methods[m].name, 2.0, 0), bm);
        bound_cell(f, fastest_within(g_methods[m].name, 1.0, 1), bm);
        bound_cell(f, fastest_within(g_methods[m].name, 2.0, 1), bm);
        fputc('\n', f);
    }
    if (g_path_count > 1) {
        fprintf(f, "\nPer path: the fastest setting (that path's median frame time) whose max "
                   "error on that path is <= 1 px / <= 2 px\n\n| path | method | <= 1 px | <= 2 px "
                   "|\n|---|---|---|---|\n");
        for (int p = 0; p < g_path_count; ++p) {
            for (int m = 0; m < g_method_count; ++m) {
                fprintf(f, "| %s | %s |", g_paths[p].name, g_methods[m].name);
                for (int b = 1; b <= 2; ++b) {
                    int best = -1;
                    for (int r = 0; r < g_row_count; ++r) {
                        const bench_row *w = &g_rows[r];
                        if (!w->ok || strcmp(w->method, g_methods[m].name) != 0 ||
                            !(w->path_err_max_px[p] <= (double)b)) {
                            continue;
                        }
                        if (best < 0 || w->path_t_med_ms[p] < g_rows[best].path_t_med_ms[p]) best = r;
                    }
                    if (best < 0) fprintf(f, " none |");
                    else fprintf(f, " %s: %.2f ms, max %.3f px |", g_rows[best].setting.label,
                                 g_rows[best].path_t_med_ms[p], g_rows[best].path_err_max_px[p]);
                }
                fputc('\n', f);
            }
        }
    }
    int failed = 0;
    for (int r = 0; r < g_row_count; ++r) failed += !g_rows[r].ok;
    if (failed) {
        fprintf(f, "\n## Runs that failed\n\n");
        for (int r = 0; r < g_row_count; ++r) {
            if (!g_rows[r].ok) {
                fprintf(f, "- %s %s: %s\n", g_rows[r].method, g_rows[r].setting.label,
                        g_rows[r].note);
            }
        }
    }
    int ok = fclose(f) == 0;
    if (!ok) fprintf(stderr, "fixterrain bench: write failed: %s\n", path);
    return ok;
}

/* ---- command line ------------------------------------------------------------------- */

static void print_help(void)
{
    char built[128];
    built_methods_text(built, sizeof built);
    printf(
        "usage: fixterrain bench [--scene FILE] [--dem FILE] [--methods LIST] [--path P[,P...]]\n"
        "                        [--csv OUT.csv] [--plot OUT.png] [--report OUT.md]\n"
        "                        [--size WxH] [--frames N] [--metric-every N]\n"
        "                        [--settings SPEC]... [--centre LAT,LON] [--backend NAME]\n"
        "                        [--clearance M] [--plot-error max|p999] [--ref-cache-mb N]\n"
        "                        [--no-oracle] [--quiet]\n"
        "Error against run time: flies the same camera paths over the scene's DEM with\n"
        "every method and setting; per frame the time (LOD selection + draw + readback),\n"
        "on every Nth frame the error against the CPU reference (max, p99.9, mean px,\n"
        "coverage mismatch). Writes a CSV row per (method, setting), a plot of error\n"
        "against median frame time (Pareto front per method) and a markdown report.\n\n"
        "  --scene FILE       scene file (default: the embedded default scene)\n"
        "  --dem FILE         terrain instead of the scene's terrain.dem\n"
        "  --methods LIST     comma-separated (default: every built method: %s);\n"
        "                     a method not built is skipped with a message\n"
        "  --path P,...       valley | climb | turn360 | dive | hover | orbit | a waypoint\n"
        "                     file (tools/flight_path.h), or 'all' (valley, climb, turn360,\n"
        "                     dive, hover); default valley. Built-in paths start at the\n"
        "                     scene pose's lat/lon (--centre), their altitudes are above\n"
        "                     the ground there; waypoint altitudes are absolute. Every pose\n"
        "                     is raised, if needed, to --clearance M (default %.0f) above the\n"
        "                     highest ground within %.0f m. hover: %.0f m above the ground,\n"
        "                     pitch -90.\n"
        "  --clearance M      see --path (0..10000 m)\n"
        "  --cache-hz HZ      a method reading the clipmap cache (clipmap; pgm and pgrid\n"
        "                     with heights = clipmap) gets its cache run between measured\n"
        "                     frames as a display at HZ would (a selection and half a\n"
        "                     display frame of spare time per display frame along the\n"
        "                     path, untimed; settled at each path's start); default 60,\n"
        "                     0 = only the measured frames' selections\n"
        "  --size WxH         view size (default 640x480)\n"
        "  --frames N         frames per path (default 60, at most %d)\n"
        "  --metric-every N   error on frames 0, N, 2N, ... (default 5)\n"
        "  --settings SPEC    METHOD.KEY=V1,V2[;...]: replaces (narrows) or adds a sweep\n"
        "                     axis; settings are the product of a method's axes. Defaults:\n"
        "                     bintree.template_k=2,3,4 bintree.tau_px=0.5,1,2,4\n"
        "                     pgm.grid=150x600,200x800,430x430,300x900,600x600,400x1600\n"
        "                     pgrid.grid=200x800,1024x512,400x1900 pgrid.gamma_px=0.5,1,2,4\n"
        "                     clipmap.side=128,256,512\n"
        "                     (grid = COLSxROWS: METHOD.grid_cols, .grid_rows). Any key of\n"
        "                     the method's scene section can be swept. Repeatable. At\n"
        "                     most 6 axes per method (defaults included), each key once;\n"
        "                     printable ASCII only (a control character is refused).\n"
        "  --csv, --plot, --report   outputs (default bench.csv, bench.png; no report)\n"
        "  --plot-error KIND  max (default) or p999 on the plot's y axis (log scale)\n"
        "  --ref-cache-mb N   keep reference images for reuse across runs (default 2048)\n"
        "  --no-oracle        no oracle for bintree rows. By default each bintree frame is\n"
        "                     drawn once more as a static pre-transformed mesh (the same\n"
        "                     triangles; positions, normals, heights from the CPU, uploaded\n"
        "                     untimed) with a trivial vertex shader and the same fragment\n"
        "                     shader and readback: the floor for that triangle set. CSV\n"
        "                     oracle_median_ms and x_oracle (median / oracle median).\n"
        "  --quiet            no progress on stderr\n"
        "Exit status: 0 when every run succeeded, 1 when a run failed (its row is left\n"
        "out; the outputs are still written) or on an error, 2 for a usage error.\n",
        built, BENCH_CLEARANCE_M, BENCH_CLEAR_RADIUS_M, BENCH_HOVER_AGL_M, BENCH_FRAMES_MAX);
}

/* The scene as every command loads it (src/app/cli.h), at the bench's own
 * view size unless --size gives one (the scene's view is its display's). */
static int resolve_scene(const bench_opts *o, ft_scene *s)
{
    ft_error err;
    memset(&err, 0, sizeof err);
    ft_cli_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.command = "bench";
    sd.scene_path = o->scene_path;
    sd.dem = o->dem;
    sd.backend = o->backend;
    sd.size = o->size != NULL ? o->size : BENCH_SIZE_DEFAULT;
    sd.text = g_scene_text;
    sd.text_cap = sizeof g_scene_text;
    const int rc = ft_cli_scene_load(&sd, s, NULL);
    if (rc != BENCH_EXIT_OK) {
        return rc;
    }
    if (o->centre != NULL) {
        double lat, lon;
        char tail;
        if (sscanf(o->centre, "%lf,%lf%c", &lat, &lon, &tail) != 2) {
            fprintf(stderr, "fixterrain bench: --centre wants LAT,LON\n");
            return BENCH_EXIT_USAGE;
        }
        /* the pose range table (scene.h), as for pose.lat_deg/lon_deg in a scene */
        const ft_pose_field fields[2] = {FT_POSE_LAT, FT_POSE_LON};
        const double values[2] = {lat, lon};
        for (int i = 0; i < 2; ++i) {
            const ft_pose_range *r = ft_pose_range_of(fields[i]);
            if (!ft_pose_field_ok(fields[i], values[i])) {
                fprintf(stderr, "fixterrain bench: --centre '%.80s': %s = %g is outside [%g, %g] %s "
                                "(pose.%s)\n",
                        o->centre, r->key, values[i], r->min, r->max, r->unit, r->key);
                return BENCH_EXIT_USAGE;
            }
        }
        s->pose.lat_deg = lat;
        s->pose.lon_deg = lon;
    }
    s->display = FT_DISPLAY_NONE; /* offscreen: present is not part of the timing */
    s->metric_enabled = 1;
    /* The measurement is the bench's own work, not the scene's: the pools it
     * needs (position readback, reference image, metric scratch) and the
     * colour readback are sized here for the bench's view, over whatever the
     * scene budgets for its display. */
    {
        const size_t px = (size_t)s->width_px * s->height_px;
        const struct { ft_pool_id pool; size_t bytes; } need[4] = {
            {FT_POOL_FRAME_RGBA, px * 4u},
            {FT_POOL_FRAME_POS, px * 4u * sizeof(float)},
            {FT_POOL_REFERENCE, px * sizeof(ft_ref_pixel)},
            {FT_POOL_METRIC, ft_metric_scratch_bytes(s->width_px, s->height_px)},
        };
        for (int i = 0; i < 4; ++i) {
            /* the arena rounds every take up to its alignment */
            const size_t bytes = (need[i].bytes + FT_ARENA_ALIGN - 1u) &
                                 ~(size_t)(FT_ARENA_ALIGN - 1u);
            if (s->budget_bytes[need[i].pool] < bytes) {
                s->budget_bytes[need[i].pool] = bytes;
            }
        }
    }
    /* Built-in paths start at the scene's pose: one that does not lie over
     * the terrain (a scene written for another DEM, or the embedded default
     * with --dem) would fly over nothing. Then the paths are centred on the
     * terrain, and the bench says so; --centre always wins. */
    if (o->centre == NULL) {
        ft_terrain t;
        if (ft_app_probe_terrain(s, &t, &err) != FT_OK) {
            fprintf(stderr, "fixterrain bench: terrain: %s\n", err.text);
            return BENCH_EXIT_ERROR;
        }
        if (!ft_pose_over_terrain(&t, &s->pose)) {
            double lat, lon;
            ft_terrain_centre_geo(&t, &lat, &lon);
            fprintf(stderr,
                    "fixterrain bench: the scene's pose (lat %.6f, lon %.6f) does not lie over "
                    "the terrain %s: paths centred on the terrain's centre (--centre %.6f,%.6f)\n",
                    s->pose.lat_deg, s->pose.lon_deg,
                    s->dem_path[0] != '\0' ? s->dem_path : "(synthetic terrain)", lat, lon);
            s->pose.lat_deg = lat;
            s->pose.lon_deg = lon;
        }
    }
    if (ft_scene_validate(s, &err) != FT_OK) {
        fprintf(stderr, "fixterrain bench: scene: %s\n", err.text);
        return BENCH_EXIT_ERROR;
    }
    return BENCH_EXIT_OK;
}

static ft_status take_plot_error(const char *value, void *dst, ft_error *err)
{
    if (strcmp(value, "max") != 0 && strcmp(value, "p999") != 0) {
        return ft_fail(err, FT_ERR_ARG, "--plot-error wants max or p999");
    }
    *(const char **)dst = value;
    return FT_OK;
}

/* --settings is repeatable: each one is kept (parsed after the command line). */
static ft_status take_settings(const char *value, void *dst, ft_error *err)
{
    bench_opts *o = dst;
    if (o->settings_count >= BENCH_USER_AXES_MAX) {
        return ft_fail(err, FT_ERR_ARG, "too many --settings");
    }
    o->settings[o->settings_count++] = value;
    return FT_OK;
}

static int parse_args(int argc, char **argv, bench_opts *o)
{
    memset(o, 0, sizeof *o);
    uint32_t frames = 60, every = 5, ref_cache_mb = 2048;
    o->clearance_m = BENCH_CLEARANCE_M;
    o->cache_hz = BENCH_CACHE_HZ;
    o->csv = "bench.csv";
    o->plot = "bench.png";
    o->paths = "valley";
    /* the help is print_help's: it formats the built methods and defaults in */
    const ft_cli_opt opts[] = {
        FT_CLI_OPT_FLAG("--quiet", &o->quiet, NULL),
        FT_CLI_OPT_FLAG("--no-oracle", &o->no_oracle, NULL),
        FT_CLI_OPT_STRING("--scene", &o->scene_path, NULL),
        FT_CLI_OPT_STRING("--dem", &o->dem, NULL),
        FT_CLI_OPT_STRING("--methods", &o->methods, NULL),
        FT_CLI_OPT_STRING("--path", &o->paths, NULL),
        FT_CLI_OPT_STRING("--csv", &o->csv, NULL),
        FT_CLI_OPT_STRING("--plot", &o->plot, NULL),
        FT_CLI_OPT_STRING("--report", &o->report, NULL),
        FT_CLI_OPT_STRING("--size", &o->size, NULL),
        FT_CLI_OPT_STRING("--backend", &o->backend, NULL),
        FT_CLI_OPT_STRING("--centre", &o->centre, NULL),
        FT_CLI_OPT_CUSTOM("--plot-error", take_plot_error, &o->plot_error, NULL),
        FT_CLI_OPT_U32("--frames", &frames, 1u, BENCH_FRAMES_MAX, NULL),
        FT_CLI_OPT_U32("--metric-every", &every, 1u, BENCH_FRAMES_MAX, NULL),
        FT_CLI_OPT_DOUBLE("--clearance", &o->clearance_m, 0.0, 10000.0, "m", NULL),
        FT_CLI_OPT_DOUBLE("--cache-hz", &o->cache_hz, 0.0, 1000.0, "Hz", NULL),
        FT_CLI_OPT_U32("--ref-cache-mb", &ref_cache_mb, 0u, 1u << 20, NULL),
        FT_CLI_OPT_CUSTOM("--settings", take_settings, o, NULL),
    };
    const ft_cli_desc cli = {"bench", opts, sizeof opts / sizeof opts[0]};
    const int rc = ft_cli_parse(&cli, argc, argv, NULL);
    if (rc == FT_CLI_HELP) {
        print_help();
        return -1;
    }
    /* each at most BENCH_FRAMES_MAX or 2^20: an int holds them */
    o->frames = (int)frames;
    o->every = (int)every;
    o->ref_cache_mb = ref_cache_mb;
    return rc;
}

static int setup_methods(const bench_opts *o)
{
    char list[512];
    if (o->methods == NULL || strcmp(o->methods, "all") == 0) {
        list[0] = '\0';
        for (int m = 0; m < FT_METHOD_COUNT; ++m) {
            (void)append(list, sizeof list, "%s%s", list[0] ? "," : "",
                         ft_method_name((ft_method_kind)m));
        }
    } else if (!copy_str(list, sizeof list, o->methods, strlen(o->methods))) {
        fprintf(stderr, "fixterrain bench: --methods too long\n");
        return 0;
    }
    char names[BENCH_METHODS_MAX][BENCH_VALUE_LEN];
    int n = 0;
    if (!split_values(list, names, BENCH_METHODS_MAX, &n)) {
        fprintf(stderr, "fixterrain bench: --methods: empty name or more than %d methods\n",
                BENCH_METHODS_MAX);
        return 0;
    }
    char built[128];
    built_methods_text(built, sizeof built);
    g_method_count = 0;
    for (int i = 0; i < n; ++i) {
        ft_method_kind k;
        if (!ft_method_from_name(names[i], &k) || !method_built(k)) {
            fprintf(stderr, "fixterrain bench: method '%s' is not built in this binary (built: "
                            "%s): skipped\n",
                    names[i], built);
            continue;
        }
        int dup = 0;
        for (int m = 0; m < g_method_count; ++m) dup |= g_methods[m].kind == k;
        if (dup) continue;
        bench_method *bm = &g_methods[g_method_count++];
        memset(bm, 0, sizeof *bm);
        set_str(bm->name, sizeof bm->name, names[i]);
        bm->kind = k;
        if (!method_axes(bm)) return 0;
    }
    for (int i = 0; i < g_user_axis_count; ++i) {
        int used = 0;
        for (int m = 0; m < g_method_count; ++m) used |= strcmp(g_methods[m].name, g_user_axes[i].method) == 0;
        if (!used) {
            fprintf(stderr, "fixterrain bench: --settings %s.%s: method %s is not benchmarked: "
                            "ignored\n",
                    g_user_axes[i].method, g_user_axes[i].key, g_user_axes[i].method);
        }
    }
    if (g_method_count == 0) {
        fprintf(stderr, "fixterrain bench: no method to run\n");
        return 0;
    }
    return 1;
}

static int setup_paths(const bench_opts *o, const ft_scene *base)
{
    char list[1024];
    const char *text = strcmp(o->paths, "all") == 0 ? "valley,climb,turn360,dive,hover" : o->paths;
    if (!copy_str(list, sizeof list, text, strlen(text))) {
        fprintf(stderr, "fixterrain bench: --path too long\n");
        return 0;
    }
    g_path_count = 0;
    char *p = list;
    for (;;) {
        char *e = strchr(p, ',');
        if (e != NULL) *e = '\0';
        if (*p == '\0' || g_path_count >= BENCH_PATHS_MAX) {
            fprintf(stderr, "fixterrain bench: --path: empty name or more than %d paths\n",
                    BENCH_PATHS_MAX);
            return 0;
        }
        if (!prepare_path(p, base, &g_paths[g_path_count], &g_fp[g_path_count])) return 0;
        ++g_path_count;
        if (e == NULL) break;
        p = e + 1;
    }
    return 1;
}

static void free_cache(void)
{
    for (int p = 0; p < BENCH_PATHS_MAX; ++p) {
        for (int i = 0; i < BENCH_MEASURED_MAX; ++i) {
            free(g_cache[p][i].ref);
            g_cache[p][i].ref = NULL;
        }
    }
    g_cache_bytes = 0;
}

int ft_cmd_bench(int argc, char **argv)
{
    bench_opts o;
    int rc = parse_args(argc, argv, &o);
    if (rc != BENCH_EXIT_OK) return rc < 0 ? BENCH_EXIT_OK : rc;
    g_user_axis_count = 0;
    for (int i = 0; i < o.settings_count; ++i) {
        if (!parse_settings_spec(o.settings[i])) return BENCH_EXIT_USAGE;
    }
    static ft_scene base;
    rc = resolve_scene(&o, &base);
    if (rc != BENCH_EXIT_OK) return rc;
    if (!setup_methods(&o)) return BENCH_EXIT_USAGE;
    if (!setup_paths(&o, &base)) return BENCH_EXIT_USAGE;

    /* every setting must parse before anything runs */
    static int first_setting[BENCH_METHODS_MAX + 1];
    int total = 0;
    for (int m = 0; m < g_method_count; ++m) {
        first_setting[m] = total;
        int n = method_settings(&g_methods[m], &g_settings[total], BENCH_SETTINGS_MAX - total);
        if (n < 0) return BENCH_EXIT_USAGE;
        for (int k = 0; k < n; ++k) {
            static ft_scene check;
            ft_error err;
            memset(&err, 0, sizeof err);
            check = base;
            check.method = g_methods[m].kind;
            if (ft_scene_parse(&check, g_settings[total + k].ini, "bench setting", &err) != FT_OK) {
                fprintf(stderr, "fixterrain bench: %s %s: %s\n", g_methods[m].name,
                            g_settings[total + k].label, err.text);
                return BENCH_EXIT_USAGE;
            }
        }
        total += n;
    }
    first_setting[g_method_count] = total;
    if (total > BENCH_ROWS_MAX) {
        fprintf(stderr, "fixterrain bench: more than %d runs\n", BENCH_ROWS_MAX);
        return BENCH_EXIT_USAGE;
    }

    g_tty = isatty(2);
    g_cache_cap_bytes = (size_t)(o.ref_cache_mb * 1048576.0);
    g_poses_ready = 0;
    g_row_count = 0;
    if (!o.quiet) {
        char paths[256];
        paths_text(paths, sizeof paths);
        fprintf(stderr, "bench: %s, %ux%u, %d runs x %d paths (%s) x %d frames, error every %d "
                        "frames\n",
                base.name, base.width_px, base.height_px, total, g_path_count, paths, o.frames,
                o.every);
    }
    const uint64_t t_start = ft_plat_monotonic_ns();
    int failed = 0;
    for (int m = 0; m < g_method_count; ++m) {
        for (int k = first_setting[m]; k < first_setting[m + 1]; ++k) {
            bench_row *row = &g_rows[g_row_count++];
            run_one(&o, &base, &g_methods[m], &g_settings[k], g_row_count, total, row);
            if (!row->ok) {
                ++failed;
                fprintf(stderr, "bench [%d/%d] %s %s FAILED: %s\n", g_row_count, total,
                        row->method, row->setting.label, row->note);
            } else if (!o.quiet) {
                char oracle[64] = "";
                if (row->oracle_med_ms > 0.0) {
                    (void)snprintf(oracle, sizeof oracle, ", oracle %.2f ms (x%.2f)",
                                   row->oracle_med_ms, row->t_med_ms / row->oracle_med_ms);
                }
                fprintf(stderr, "bench [%d/%d] %s %s: median %.2f ms, p99 %.2f ms, max error "
                                "%.3f px, p99.9 %.3f px%s\n",
                        g_row_count, total, row->method, row->setting.label, row->t_med_ms,
                        row->t_p99_ms, row->err_max_px, row->err_p999_px, oracle);
            }
        }
    }
    free_cache();
    const double run_s = (double)(ft_plat_monotonic_ns() - t_start) * 1e-9;

    int ok = 1;
    if (o.csv != NULL && o.csv[0] != '\0') ok &= write_csv(o.csv);
    if (o.plot != NULL && o.plot[0] != '\0') ok &= write_plot(&o, &base, o.plot);
    if (o.report != NULL) ok &= write_report(&o, &base, o.report, run_s);

    /* summary on stdout */
    const double bm = brute_median();
    printf("bench: %d runs in %.1f s; %d failed\n", g_row_count, run_s, failed);
    for (int m = 0; m < g_method_count; ++m) {
        const int best[2] = {fastest_within(g_methods[m].name, 1.0, 0),
                             fastest_within(g_methods[m].name, 2.0, 0)};
        printf("  %-8s", g_methods[m].name);
        for (int k = 0; k < 2; ++k) {
            const int r = best[k];
            printf("%s max error <= %d px: ", k == 0 ? "" : ";", k + 1);
            if (r < 0) {
                printf("none");
                continue;
            }
            printf("%s %.2f ms", g_rows[r].setting.label, g_rows[r].t_med_ms);
            /* a ratio only when brute force ran in this bench */
            if (bm > 0.0) printf(" (%.2fx brute)", g_rows[r].t_med_ms / bm);
        }
        printf("\n");
    }
    if (!ok) return BENCH_EXIT_ERROR;
    return failed ? BENCH_EXIT_ERROR : BENCH_EXIT_OK;
}
