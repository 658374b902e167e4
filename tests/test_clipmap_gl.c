/* test_clipmap_gl.c - the clipmap method on real contexts over a real DEM
 * (argv[2], e.g. ../shared/data/N42E001.hgt), 320 x 240, with glGetError
 * checked after every frame step (0 GL errors required).
 *
 * 1. Coverage beside brute force: for a set of views (nadir, oblique, low
 *    over a valley, towards the terrain's edge) the pixels clipmap covers
 *    and brute covers agree, except within SILHOUETTE_PX of brute's own
 *    terrain/sky boundary (a coarse level's ridge line differs from the
 *    full-resolution one by a pixel or two); at most OFF_SILHOUETTE_MAX
 *    pixels may differ elsewhere (a hole would be many more).
 * 2. Image crack test: clear colour magenta; on views the terrain covers
 *    completely not one magenta pixel, while the eye flies 60 frames across
 *    the tile with few updates a frame, so levels move, lag (valid smaller
 *    than wanted) and catch up (checked from the cache's stats). A view
 *    above the horizon must show magenta (the counter works).
 * es3 runs with float texels; es2 (run under MESA_GLES_VERSION_OVERRIDE=2.0,
 * a true ES 2.0 context) with float and with packed texels.
 *
 * Usage: test_clipmap_gl es3|es2 DEM */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "test_app_util.h"

#define W_PX 320u
#define H_PX 240u
#define SILHOUETTE_PX 2
#define OFF_SILHOUETTE_MAX 16u
#define VIEWS 8u

static ft_app g_app;
static char g_text[4096];
static uint8_t g_brute_mask[VIEWS][W_PX * H_PX];

static const char k_scene_fmt[] =
    "[scene]\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = %u\nheight_px = %u\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\nheight_format = %s\ntexture_bytes = 64M\n[metric]\nenabled = 0\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 1442401\n"
    "[clipmap]\nside = %u\nlevels = %u\nupdate_samples_max = 4096\nupdates_per_frame = %u\n"
    "transition_samples = 12\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 1M\nframe_pos_bytes = 2M\nreference_bytes = 4M\nmetric_bytes = 2M\n"
    "gpu_staging_bytes = 8M\nmethod_bytes = 8M\npng_bytes = 512K\nclip_bytes = 64K\n";

static void app_init(const char *method, const char *backend, const char *dem,
                     const char *format, uint32_t side, uint32_t levels, uint32_t per_frame)
{
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, method, backend, W_PX, H_PX, dem, format,
                   side, levels, per_frame);
    ft_test_app_init(&g_app, g_text, method);
    g_app.renderer.gl_error_checks = 1;
    ft_test_clear_magenta(&g_app);
}

static ft_pose view_of(uint32_t i)
{
    if (i < FT_TEST_COVERED_VIEWS) return ft_test_covered_view(i);
    static const double v[VIEWS - FT_TEST_COVERED_VIEWS][6] = {
        {42.30, 1.50, 3800.0, 0.0, -14.0, 0.0},   /* the pyrenees scene's view */
        {42.45, 1.30, 2200.0, 120.0, -5.0, 0.0},  /* low, the horizon in view */
        {42.10, 1.90, 5000.0, 135.0, -20.0, 0.0}, /* towards the south-east corner */
    };
    const double *a = v[i - FT_TEST_COVERED_VIEWS];
    return ft_test_pose(a[0], a[1], a[2], a[3], a[4], a[5]);
}

static void mask_of(uint8_t *m)
{
    const uint8_t *p = g_app.renderer.rgba;
    for (size_t i = 0; i < (size_t)W_PX * H_PX; ++i) {
        m[i] = !(p[4u * i] == 255u && p[4u * i + 1u] == 0u && p[4u * i + 2u] == 255u);
    }
}

/* 1 when a pixel within r of (x, y) differs from mask value at (x, y) */
static int near_edge(const uint8_t *m, int x, int y, int r)
{
    const uint8_t v = m[(size_t)y * W_PX + (size_t)x];
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= (int)W_PX || yy >= (int)H_PX) continue;
            if (m[(size_t)yy * W_PX + (size_t)xx] != v) return 1;
        }
    }
    return 0;
}

static void render(const ft_pose *p)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, p, &cam, &fs);
    CHECK(g_app.renderer.gl_errors == 0u);
}

static void brute_masks(const char *backend, const char *dem)
{
    app_init("brute", backend, dem, "auto", 256u, 5u, 8u);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        render(&p);
        mask_of(g_brute_mask[v]);
    }
    ft_app_shutdown(&g_app);
}

static void coverage(const char *backend, const char *dem, const char *format)
{
    static uint8_t mask[W_PX * H_PX];
    app_init("clipmap", backend, dem, format, 256u, 5u, 8u);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        /* twice: the first frame after a jump fills every level */
        render(&p);
        render(&p);
        mask_of(mask);
        uint32_t diff = 0, off = 0, terrain = 0;
        for (int y = 0; y < (int)H_PX; ++y) {
            for (int x = 0; x < (int)W_PX; ++x) {
                const size_t i = (size_t)y * W_PX + (size_t)x;
                terrain += g_brute_mask[v][i];
                if (mask[i] == g_brute_mask[v][i]) continue;
                ++diff;
                off += !near_edge(g_brute_mask[v], x, y, SILHOUETTE_PX);
            }
        }
        printf("%s %s view %u: brute terrain %u px, clipmap differs on %u px, %u of them "
               "off brute's silhouette (+-%d px)\n",
               backend, format, v, terrain, diff, off, SILHOUETTE_PX);
        CHECK(off <= OFF_SILHOUETTE_MAX);
        if (v < FT_TEST_COVERED_VIEWS) CHECK(ft_test_clear_pixels(&g_app) == 0u);
    }
    ft_app_shutdown(&g_app);
}

/* The eye flies across the tile looking down at 50 deg: the terrain covers
 * every frame; few updates a frame make the levels lag. */
static void fly(const char *backend, const char *dem, const char *format)
{
    app_init("clipmap", backend, dem, format, 128u, 5u, 2u);
    uint32_t cracked_frames = 0, worst = 0;
    const uint32_t frames = 60u;
    for (uint32_t f = 0; f < frames; ++f) {
        const double t = (double)f / (double)(frames - 1u);
        const ft_pose p = ft_test_pose(42.25 + 0.5 * t, 1.25 + 0.45 * t, 4200.0 - 1500.0 * t,
                                       35.0 + 40.0 * t, -50.0, 0.0);
        render(&p);
        const uint32_t c = ft_test_clear_pixels(&g_app);
        cracked_frames += (c > 0u);
        worst = (c > worst) ? c : worst;
    }
    const ft_clip_stats *cs = &g_app.renderer.method.u.clipmap.cache.stats;
    printf("%s %s flight: %u frames, %u with magenta (worst %u px); cache: %llu recentres "
           "moved, %llu updates, levels behind at most %u, %llu samples outstanding at most\n",
           backend, format, frames, cracked_frames, worst,
           (unsigned long long)cs->recentres_moved, (unsigned long long)cs->updates,
           cs->levels_behind_max, (unsigned long long)cs->samples_outstanding_max);
    CHECK(cracked_frames == 0u);
    CHECK(cs->recentres_moved >= 10u);
    CHECK(cs->levels_behind_max >= 1u); /* the lagging case was drawn */

    /* the counter works: a view above the horizon shows the clear colour */
    const ft_pose sky = ft_test_pose(42.5, 1.5, 3000.0, 0.0, 10.0, 0.0);
    render(&sky);
    CHECK(ft_test_clear_pixels(&g_app) > 1000u);
    ft_app_shutdown(&g_app);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_clipmap_gl es3|es2 DEM\n");
        return 2;
    }
    if (!ft_test_have_data(argv[2])) return FT_TEST_SKIP;
    const int es3 = strcmp(argv[1], "es3") == 0;
    const char *backend = es3 ? "egl-gles3" : "egl-gles2";
    brute_masks(backend, argv[2]);
    coverage(backend, argv[2], "float");
    fly(backend, argv[2], "float");
    if (!es3) {
        coverage(backend, argv[2], "packed");
        fly(backend, argv[2], "packed");
    }
    return ft_test_result(es3 ? "test_clipmap_gl es3" : "test_clipmap_gl es2");
}
