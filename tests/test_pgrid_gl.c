/* test_pgrid_gl.c - the error-bounded projective grid (method 'pgrid',
 * src/lod/pgrid.h) on a real GPU context over a real DEM (argv[2], e.g.
 * ../shared/data/N42E001.hgt). Views are 256 x 192 with a ray-casting budget
 * of every pixel, so the budget is never what limits the bound.
 *
 * es3:
 * 1. Error bound with ray casting: along an 8-frame flight, for gamma_px in
 *    {0.5, 1, 2}, on every frame whose budget was not hit the foundation
 *    metric's max screen-space error (against the bilinear reference) is
 *        es.max_px <= gamma_px + TOL_PX
 *    (TOL_PX and its derivation: below), and the coverage mismatch
 *    (only_method_px + only_ref_px) is at most COVER_PX_PER_GAMMA x gamma_px;
 *    with pgrid.error_bound = relief and = residual (src/lod/pgrid.h 6).
 * 2. Row distribution: ray casting off, the same flight, the same grid
 *    (same vertex count): the view-dependent rows give a lower mean error
 *    than uniform rows (summed over the flight, and on most frames).
 * 3. Sweep: pitch -90..+90 deg, FOV 1..170 deg, heights 1 m .. 100 km
 *    above the ground, ray casting on and off: no non-finite position
 *    (es.nonfinite_px == 0), terrain present whenever the reference has some,
 *    and with ray casting the coverage mismatch at most SWEEP_COVER_MAX_PX.
 * 4. Image crack test: clear colour magenta (never a terrain colour); views
 *    the terrain covers completely show no magenta pixel and the position
 *    pass is terrain at every pixel (a ray-cast miss would show there),
 *    ray casting on and off; a view with sky shows magenta (the counter
 *    works).
 * 5. Lower envelope: drawn only with the eye off the grid or not above the
 *    terrain's highest sample (src/lod/pgrid.h 3); on views where the rule
 *    leaves it out, drawing it changes no pixel's ray-cast decision, and
 *    leaving it out where the rule draws it changes some.
 * 6. Ray-cast tiles: the tile pass's texels equal each tile's largest code
 *    over the tile and a one-pixel border, computed from the error buffer
 *    read back, at tile sides 4, 13 (tiles cut by the image's edges) and 64;
 *    the pictures are the same byte for byte at every side, and some tiles
 *    are left out and some drawn on every frame (the test is not vacuous).
 * 8. Columns moved by the error (pgrid.columns = error): the bound holds on
 *    the flight of part 1, the knots leave uniform, and the vertex pass puts
 *    the bottom row's vertices where the knots say (ft_pgrid_col_u).
 * es2 (run with MESA_GLES_VERSION_OVERRIDE=2.0, backend egl-gles2):
 *    init with ray_casting = 1 succeeds and runs without ray casting (no
 *    pixel ray cast, budget not hit), the reported bound is the mesh's own
 *    (positive, finite: above gamma_px on these views), frames render and the
 *    crack test passes.
 *
 * sweep: part 3 alone over another DEM, around LAT LON.
 *
 * Usage: test_pgrid_gl es3|es2 DEM | test_pgrid_gl sweep DEM LAT LON */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "test_app_util.h"

#define W_PX 256u
#define H_PX 192u

static ft_app g_app;
static char g_text[4096];

static const char k_scene_fmt[] =
    "[scene]\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = %u\nheight_px = %u\nfovy_deg = %.1f\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 64M\n[metric]\nenabled = %d\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 1442401\n"
    "[pgrid]\ngrid_cols = %u\ngrid_rows = %u\ndistribution = %s\nray_casting = %d\n"
    "gamma_px = %.3f\nraycast_max_px = %u\nerror_bound = %s\nraycast_tile_px = %u\n"
    "columns = %s\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 1M\nframe_pos_bytes = 2M\nreference_bytes = 4M\nmetric_bytes = 2M\n"
    "gpu_staging_bytes = 8M\nmethod_bytes = 16M\npng_bytes = 512K\n";

typedef struct setup {
    const char *method, *backend, *dem;
    double fovy_deg;
    uint32_t cols, rows;
    int view_dist, ray_casting;
    double gamma;
    int metric;
    int residual; /* pgrid.error_bound = residual (src/lod/pgrid.h 6) */
    uint32_t tile_px; /* pgrid.raycast_tile_px; 0: 16 */
} setup;

/* pgrid.columns for the next app_init (part 8 sets it) */
static int g_columns_error;

static void app_init(const setup *c)
{
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, c->method, c->backend, W_PX, H_PX,
                   c->fovy_deg, c->dem, c->metric, c->cols, c->rows,
                   c->view_dist ? "view" : "uniform", c->ray_casting, c->gamma, W_PX * H_PX,
                   c->residual ? "residual" : "relief", c->tile_px ? c->tile_px : 16u,
                   g_columns_error ? "error" : "uniform");
    ft_test_app_init(&g_app, g_text, c->method);
}

/* Per-pixel split of the last measured frame (pgrid): the largest metric
 * error over the ray-cast pixels (dilated code >= threshold, src/lod/pgrid.h 4)
 * and over the mesh pixels, and the largest error / rho_hi(code) ratio of the
 * mesh pixels (how tight the per-pixel bound is). */
typedef struct split {
    double rc_max, mesh_max;
    uint32_t rc_x, rc_y;
    double rc_dist;
} split;

static double pixel_error(const ft_camera *cam, const float *q, double *dist)
{
    double d = sqrt((double)q[0] * q[0] + (double)q[1] * q[1] + (double)q[2] * q[2]);
    *dist = d;
    if (d < cam->near_m) d = cam->near_m;
    return fabs(cam->eye_m[2] + q[2] -
                ft_terrain_height_at(&g_app.terrain, cam->eye_m[0] + q[0], cam->eye_m[1] + q[1])) *
           cam->px_per_rad_k / d;
}

/* The largest code of the error buffer's 3 x 3 pixels around (x, gy), gy in
 * the buffer's rows (0 = bottom): the dilated code of src/lod/pgrid.h 4. */
static uint32_t dilated_code(const ft_pgrid_method *m, int x, int gy)
{
    uint32_t code = 0u;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = gy + dy;
            if (xx < 0 || yy < 0 || xx >= (int)W_PX || yy >= (int)H_PX) continue;
            const uint32_t c = m->readback[4u * ((uint32_t)yy * W_PX + (uint32_t)xx) + 1u];
            if (c > code) code = c;
        }
    }
    return code;
}

static split split_errors(const ft_camera *cam)
{
    const float *pos = g_app.renderer.pos;
    const ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    split r = {0.0, 0.0, 0u, 0u, 0.0};
    for (uint32_t y = 0; y < H_PX; ++y) {
        for (uint32_t x = 0; x < W_PX; ++x) {
            const float *q = pos + 4u * (y * W_PX + x);
            if (!(q[3] > 0.5f)) continue;
            double dist;
            const double e = pixel_error(cam, q, &dist);
            /* error buffer rows: 0 = bottom */
            const uint32_t code = dilated_code(m, (int)x, (int)(H_PX - 1u - y));
            if (code >= m->thr) {
                if (e > r.rc_max) {
                    if (getenv("PGRID_DEBUG") != NULL) {
                        const ft_ref_pixel *rp = &g_app.ref[y * W_PX + x];
                        fprintf(stderr, "rc px (%u,%u) e %.4f: gpu (%.3f %.3f %.3f) ref (%.3f %.3f "
                                "%.3f) hit %u\n", x, y, e, q[0], q[1], q[2], rp->pos_rel_eye_m[0],
                                rp->pos_rel_eye_m[1], rp->pos_rel_eye_m[2], rp->hit);
                    }
                    r.rc_max = e;
                    r.rc_x = x;
                    r.rc_y = y;
                    r.rc_dist = dist;
                }
            } else if (e > r.mesh_max) {
                r.mesh_max = e;
            }
        }
    }
    return r;
}

/* ---- 1. error bound with ray casting ------------------------------------------ */

#define PATH_FRAMES 8
#define GRID_COLS 200u
#define GRID_ROWS 800u

static ft_pose path_pose(int f)
{
    const double s = (double)f / (PATH_FRAMES - 1);
    return ft_test_pose(42.30 + 0.30 * s, 1.25 + 0.45 * s, 3500.0 + 1500.0 * s, 40.0 + 25.0 * f,
                   -8.0 - 4.0 * f, (f % 3) * 8.0 - 8.0);
}

/* TOL_PX: the metric's own accuracy (0.05 px, as in test_bintree_gl) plus
 * what the GPU ray caster's float32 hit adds against the CPU reference's
 * double one: measured at <= 0.063 px over these frames (about 1 m along the
 * steepest, nearest rays at the bottom of the view, ~2.7 km away; elsewhere
 * 0.000 px), so 0.05 + 0.05. The mesh pixels (under gamma, not ray cast) are
 * bounded by rho (a convex bound, src/lod/pgrid.h 2) and measured well under it:
 * max - gamma <= -0.3 px on every frame. COVER_PX_PER_GAMMA: silhouette pixels the
 * bound allows to differ (a mesh silhouette under gamma may be off by up to
 * gamma px along the skyline, so the allowance grows with gamma: 24 gamma
 * px; measured 0 / 2 / 10 at gamma 0.5 / 1 / 2 with the relief envelopes, 40
 * at gamma 2 without them, 0 / 4 / 28-30 with the residual bound's thinner
 * envelopes). */
#define TOL_PX 0.10
#define COVER_PX_PER_GAMMA 24.0

/* Frame f of the flight, drawn and measured against the reference. */
static void fly_measured(int f, ft_camera *cam, ft_frame_stats *fs, ft_error_stats *es)
{
    ft_pose p = path_pose(f);
    ft_test_frame(&g_app, &p, cam, fs);
    ft_test_measure(&g_app, cam, es);
}

static void test_error_bound(const char *dem, int residual)
{
    double brute_max[PATH_FRAMES], brute_mean[PATH_FRAMES];
    setup cb = {"brute", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 0, 1.0, 1, 0, 0u};
    app_init(&cb);
    for (int f = 0; f < PATH_FRAMES; ++f) {
        ft_camera cam;
        ft_frame_stats fs;
        ft_error_stats es;
        fly_measured(f, &cam, &fs, &es);
        brute_max[f] = es.max_px;
        brute_mean[f] = es.mean_px;
    }
    ft_app_shutdown(&g_app);

    static const double gammas[] = {0.5, 1.0, 2.0};
    printf("error bound (%s), ray casting on, %ux%u view rows, %d-frame flight "
           "(max/mean px, cover mismatch, px ray cast; brute max/mean in brackets):\n",
           residual ? "residual" : "relief", GRID_COLS, GRID_ROWS, PATH_FRAMES);
    for (size_t gi = 0; gi < sizeof gammas / sizeof gammas[0]; ++gi) {
        const double gamma = gammas[gi];
        setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, gamma, 1,
                   residual, 0u};
        app_init(&c);
        CHECK(g_app.renderer.method.u.pgrid.tight == residual);
        double worst_over = -INFINITY;
        uint32_t worst_cover = 0;
        int held = 0;
        for (int f = 0; f < PATH_FRAMES; ++f) {
            ft_camera cam;
            ft_frame_stats fs;
            ft_error_stats es;
            fly_measured(f, &cam, &fs, &es);
            const uint32_t cover = es.only_method_px + es.only_ref_px;
            printf("  gamma %.1f f%d: max %.3f mean %.4f cover %u+%u rc %u achieved %.3f%s "
                   "[%.3f/%.4f]\n",
                   gamma, f, es.max_px, es.mean_px, es.only_method_px, es.only_ref_px,
                   (uint32_t)fs.raycast_px,
                   fs.tau_achieved_px, fs.budget_hit ? " BUDGET" : "", brute_max[f],
                   brute_mean[f]);
            CHECK(es.nonfinite_px == 0u);
            CHECK(es.terrain_px > 1000u);
            const split sp = split_errors(&cam);
            printf("    ray-cast pixels max %.3f px (worst at (%u, %u), %.0f m), mesh pixels max "
                   "%.3f px\n", sp.rc_max, sp.rc_x, sp.rc_y, sp.rc_dist, sp.mesh_max);
            if (fs.budget_hit) continue;
            ++held;
            if (es.max_px - gamma > worst_over) worst_over = es.max_px - gamma;
            if (cover > worst_cover) worst_cover = cover;
            CHECK(es.max_px <= gamma + TOL_PX);
            CHECK(cover <= COVER_PX_PER_GAMMA * gamma);
            CHECK(fs.tau_achieved_px <= gamma);
        }
        printf("  gamma %.1f: %d of %d frames inside the budget; worst max - gamma %.3f px "
               "(allowed %.2f); worst cover mismatch %u px (allowed %u)\n",
               gamma, held, PATH_FRAMES, worst_over, TOL_PX, worst_cover,
               (uint32_t)(COVER_PX_PER_GAMMA * gamma));
        CHECK(held == PATH_FRAMES);
        ft_app_shutdown(&g_app);
    }
}

/* ---- 2. view-dependent rows against uniform rows ------------------------------ */

static void test_distribution(const char *dem)
{
    static const uint32_t grids[][2] = {{200u, 800u}, {430u, 430u}};
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
        double mean[2][PATH_FRAMES], maxe[2][PATH_FRAMES], sum[2] = {0.0, 0.0};
        for (int d = 0; d < 2; ++d) {
            setup c = {"pgrid", "egl-gles3", dem, 60.0, grids[g][0], grids[g][1], d, 0, 1.0, 1,
                       0, 0u};
            app_init(&c);
            for (int f = 0; f < PATH_FRAMES; ++f) {
                ft_camera cam;
                ft_frame_stats fs;
                ft_error_stats es;
                ft_pose p = path_pose(f);
                ft_test_frame(&g_app, &p, &cam, &fs);
                ft_test_measure(&g_app, &cam, &es);
                CHECK(es.nonfinite_px == 0u);
                CHECK(fs.raycast_px == 0u);
                mean[d][f] = es.mean_px;
                maxe[d][f] = es.max_px;
                sum[d] += es.mean_px;
            }
            ft_app_shutdown(&g_app);
        }
        int better = 0;
        printf("distribution %ux%u, ray casting off (mean/max px, uniform -> view):",
               grids[g][0], grids[g][1]);
        for (int f = 0; f < PATH_FRAMES; ++f) {
            printf(" %.3f/%.2f->%.3f/%.2f", mean[0][f], maxe[0][f], mean[1][f], maxe[1][f]);
            better += (mean[1][f] < mean[0][f]);
        }
        printf("\n  flight mean: uniform %.4f px, view %.4f px; view lower on %d of %d frames\n",
               sum[0] / PATH_FRAMES, sum[1] / PATH_FRAMES, better, PATH_FRAMES);
        CHECK(sum[1] < sum[0]);
        CHECK(better >= PATH_FRAMES - 1);
    }
}

/* ---- 3. sweep ----------------------------------------------------------------- */

/* With ray casting (budget not hit) a pixel left to the mesh has rho <
 * gamma = 1 px in true pixels (src/lod/pgrid.h 3: the cos^2 stretch, the
 * envelopes), so mesh and reference skylines differ by under a pixel: only
 * pixel centres a skyline or the DEM's edge passes between can differ, a few
 * along a 256-px view (measured <= 10: the whole tile's edge seen from
 * 100 km; before the envelopes and the stretch, 2953 at FOV 150). */
#define SWEEP_COVER_MAX_PX 16u

static void test_sweep(const char *dem, double lat, double lon)
{
    static const double fovs[] = {1.0, 10.0, 60.0, 150.0, 170.0};
    static const double pitches[] = {-90.0, -60.0, -30.0, -10.0, -3.0, 0.0, 10.0, 60.0, 90.0};
    static const double clear_m[] = {1.0, 30.0, 3000.0, 100000.0};
    uint32_t frames = 0, nonfinite = 0, absent = 0, cover_bad = 0;
    for (int rc = 0; rc <= 1; ++rc) {
        for (size_t fi = 0; fi < sizeof fovs / sizeof fovs[0]; ++fi) {
            setup c = {"pgrid", "egl-gles3", dem, fovs[fi], GRID_COLS, GRID_ROWS, 1, rc, 1.0, 1,
                       0, 0u};
            app_init(&c);
            /* the ground under the eye, from a probe frame's camera */
            ft_camera cam;
            ft_frame_stats fs;
            ft_pose probe = ft_test_pose(lat, lon, 5000.0, 30.0, -30.0, 0.0);
            ft_test_frame(&g_app, &probe, &cam, &fs);
            const double ground = ft_terrain_height_at(&g_app.terrain, cam.eye_m[0], cam.eye_m[1]);
            uint32_t worst_cover = 0;
            for (size_t pi = 0; pi < sizeof pitches / sizeof pitches[0]; ++pi) {
                for (size_t hi = 0; hi < sizeof clear_m / sizeof clear_m[0]; ++hi) {
                    ft_error_stats es;
                    ft_pose p = ft_test_pose(lat, lon, ground + clear_m[hi], 30.0, pitches[pi],
                                        (pi % 2) ? 10.0 : 0.0);
                    ft_test_frame(&g_app, &p, &cam, &fs);
                    ft_test_measure(&g_app, &cam, &es);
                    ++frames;
                    const uint32_t ref_hits = es.terrain_px - es.only_method_px + es.only_ref_px;
                    /* the reported bound: never NaN; +inf is the documented "over
                     * 256 px" without ray casting (src/lod/pgrid.c, saturated code) */
                    const int bad_bound = isnan(fs.tau_achieved_px) ||
                                          (rc && !fs.budget_hit && !(fs.tau_achieved_px <= 1.0));
                    if (es.nonfinite_px != 0u || bad_bound) {
                        fprintf(stderr, "sweep rc %d fov %.0f pitch %.0f +%.0f m: %u non-finite, bound %g\n",
                                rc, fovs[fi], pitches[pi], clear_m[hi], es.nonfinite_px,
                                fs.tau_achieved_px);
                        ++nonfinite;
                    }
                    if (ref_hits > 0u && es.terrain_px == 0u) {
                        fprintf(stderr, "sweep rc %d fov %.0f pitch %.0f +%.0f m: reference has "
                                "%u terrain px, the frame none\n", rc, fovs[fi], pitches[pi],
                                clear_m[hi], ref_hits);
                        ++absent;
                    }
                    const uint32_t cover = es.only_method_px + es.only_ref_px;
                    if (cover > worst_cover) worst_cover = cover;
                    if (rc && cover > SWEEP_COVER_MAX_PX) {
                        fprintf(stderr, "sweep rc 1 fov %.0f pitch %.0f +%.0f m: cover mismatch "
                                "%u+%u px (allowed %u), budget hit %d\n", fovs[fi], pitches[pi],
                                clear_m[hi], es.only_method_px, es.only_ref_px,
                                SWEEP_COVER_MAX_PX, fs.budget_hit);
                        ++cover_bad;
                    }
                }
            }
            printf("sweep ray casting %d, fov %.0f: ground %.0f m, worst cover mismatch %u px\n",
                   rc, fovs[fi], ground, worst_cover);
            ft_app_shutdown(&g_app);
        }
    }
    printf("sweep: %u frames (pitch -90..90, fov 1..170, 1 m..100 km above ground, ray casting "
           "off/on): %u with non-finite positions, %u without terrain the reference sees, %u "
           "over %u px of coverage mismatch with ray casting\n",
           frames, nonfinite, absent, cover_bad, SWEEP_COVER_MAX_PX);
    CHECK(nonfinite == 0u);
    CHECK(absent == 0u);
    CHECK(cover_bad == 0u);
}

/* ---- 4. image crack test -------------------------------------------------------- */

static void test_cracks(const char *backend, const char *dem)
{
    const int es2 = strcmp(backend, "egl-gles2") == 0;
    static const uint32_t grids[][2] = {{150u, 600u}, {430u, 430u}};
    uint32_t worst = 0, worst_pos = 0;
    for (int rc = 0; rc <= 1; ++rc) {
        for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
            for (int d = 0; d <= 1; ++d) {
                const double gamma = 1.0;
                /* the residual bound with the view rows (GLES 3), the relief
                 * bound with uniform rows */
                setup c = {"pgrid", backend, dem, 60.0, grids[g][0], grids[g][1], d, rc, gamma,
                           !es2, d, 0u};
                app_init(&c);
                if (es2) CHECK(strstr(g_app.gpu.version, "OpenGL ES 2.0") != NULL);
                ft_test_clear_magenta(&g_app);
                double bound_min = INFINITY, bound_max = 0.0;
                uint32_t rc_px = 0;
                for (uint32_t v = 0; v < FT_TEST_COVERED_VIEWS; ++v) {
                    const ft_pose view = ft_test_covered_view(v);
                    ft_camera cam;
                    ft_frame_stats fs;
                    ft_test_frame(&g_app, &view, &cam, &fs);
                    const uint32_t n = ft_test_clear_pixels(&g_app);
                    if (n > 0u) {
                        fprintf(stderr, "%s rc %d %ux%u %s view %u: %u clear-colour pixels\n",
                                backend, rc, grids[g][0], grids[g][1], d ? "view" : "uniform", v,
                                n);
                    }
                    if (n > worst) worst = n;
                    CHECK(n == 0u);
                    CHECK(fs.triangles > 0u);
                    CHECK(isfinite(fs.tau_achieved_px) && fs.tau_achieved_px > 0.0);
                    if (fs.tau_achieved_px < bound_min) bound_min = fs.tau_achieved_px;
                    if (fs.tau_achieved_px > bound_max) bound_max = fs.tau_achieved_px;
                    rc_px += (uint32_t)fs.raycast_px;
                    if (es2 || !rc) {
                        /* no ray casting: nothing ray cast, the mesh's bound reported */
                        CHECK(fs.raycast_px == 0u);
                        CHECK(!fs.budget_hit);
                    } else {
                        CHECK(!fs.budget_hit);
                        CHECK(fs.tau_achieved_px <= gamma);
                    }
                    if (!es2) {
                        /* the position pass too: terrain at every pixel */
                        ft_error_stats es;
                        ft_test_measure(&g_app, &cam, &es);
                        const uint32_t miss = W_PX * H_PX - es.terrain_px;
                        if (miss > worst_pos) worst_pos = miss;
                        CHECK(miss == 0u);
                        CHECK(es.nonfinite_px == 0u);
                    }
                }
                if (es2 && rc) {
                    /* asked for ray casting, ran without: the bound is the mesh's */
                    CHECK(!g_app.renderer.method.u.pgrid.ray_casting);
                    CHECK(bound_max > gamma);
                }
                ft_camera cam;
                ft_frame_stats fs;
                const ft_pose sky = ft_test_pose(42.5, 1.5, 4000.0, 0.0, 5.0, 0.0);
                ft_test_frame(&g_app, &sky, &cam, &fs);
                CHECK(ft_test_clear_pixels(&g_app) > 1000u); /* the counter works */
                printf("cracks %s ray casting %d %ux%u %s: no clear pixel in %zu covered views; "
                       "reported bound %.3f..%.3f px; %u px ray cast\n",
                       backend, rc, grids[g][0], grids[g][1], d ? "view" : "uniform",
                       (size_t)FT_TEST_COVERED_VIEWS, bound_min, bound_max, rc_px);
                ft_app_shutdown(&g_app);
            }
        }
    }
    printf("image crack test (%s): most clear-colour pixels in a covered view %u, most "
           "position-pass sky pixels %u\n", backend, worst, worst_pos);
}

/* ---- 5. the residual bound's shader against its CPU rule --------------------- */

static float g_vtx[4u * GRID_COLS * GRID_ROWS];
static float g_quad[4u * GRID_COLS * GRID_ROWS];
static float g_shape[4u * GRID_COLS * GRID_ROWS];

/* One frame with error_bound = residual; the vertex pass, the quad-bound
 * pass and the vertex-bound pass read back (RGBA32F). For every 97th quad
 * the CPU rule (ft_pgrid_quad_bound) on the read-back corners, plus the
 * chord, must lie under the shader's bound, which adds a margin for float
 * arithmetic (shaders/pgrid_quad.frag.glsl: 0.005 m + 4e-6 x height; the
 * quad pass evaluates planes through heights of ~2000 m in float32:
 * measured 0.006 m at most), and over it by at most twice the margin. Every
 * vertex's bound (the vertex-bound pass) must be the largest of its <= 4
 * quads' exactly, and the quad bound it hands on the bound of the quad
 * whose triangles end at it. */
#define QUAD_TOL_M(h_m) (0.005 + 4e-6 * (h_m))

static void test_residual_mirror(const char *dem)
{
    setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, 1.0, 0, 1, 0u};
    app_init(&c);
    const ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    REQUIRE(m->tight);
    ft_camera cam;
    ft_frame_stats fs;
    ft_pose p = path_pose(3);
    ft_test_frame(&g_app, &p, &cam, &fs);
    const ft_gl *gl = &g_app.gpu.gl;
    const uint32_t cols = m->pgm.cols, rows = m->pgm.rows;
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->vtx_fbo);
    gl->ReadPixels(0, 0, (GLsizei)cols, (GLsizei)rows, GL_RGBA, GL_FLOAT, g_vtx);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->quad_fbo);
    gl->ReadPixels(0, 0, (GLsizei)(cols - 1u), (GLsizei)(rows - 1u), GL_RGBA, GL_FLOAT, g_quad);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->shape_fbo);
    gl->ReadPixels(0, 0, (GLsizei)cols, (GLsizei)rows, GL_RGBA, GL_FLOAT, g_shape);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(ft_gl_check(gl, "reading the residual passes back", NULL) == FT_OK);
    const ft_terrain *t = &g_app.terrain;
    const double lo_x = t->origin_world_x_m - cam.eye_m[0];
    const double lo_y = t->origin_world_y_m - cam.eye_m[1];
    uint32_t n = 0u, bad = 0u;
    double sum = 0.0, worst = 0.0;
    for (uint32_t k = 0; k < (cols - 1u) * (rows - 1u); k += 97u) {
        const uint32_t i = k % (cols - 1u), j = k / (cols - 1u);
        ft_pgrid_quad q;
        double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
        double hmax = 0.0;
        for (int c4 = 0; c4 < 4; ++c4) {
            const float *v = g_vtx + 4u * ((j + (uint32_t)(c4 / 2)) * cols + i + (uint32_t)(c4 % 2));
            /* in float, as the shader computes it (the window's choice
             * must see the same corners) */
            q.g[c4][0] = (double)((v[0] - (float)lo_x) * (1.0f / (float)t->cell_x_m));
            q.g[c4][1] = (double)((v[1] - (float)lo_y) * (1.0f / (float)t->cell_y_m));
            q.h_m[c4] = (double)v[2];
            hmax = fmax(hmax, fabs((double)v[2]));
            xmin = fmin(xmin, v[0]);
            xmax = fmax(xmax, v[0]);
            ymin = fmin(ymin, v[1]);
            ymax = fmax(ymax, v[1]);
        }
        const double chord = 0.25 * t->curv_drop_per_m2 *
                             ((xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin));
        const double cpu = ft_pgrid_quad_bound(t, &q) + chord;
        const double gpu = (double)g_quad[4u * (j * (cols - 1u) + i)];
        const double d = fabs(gpu - cpu - QUAD_TOL_M(hmax));
        if (gpu < cpu || d > QUAD_TOL_M(hmax)) {
            if (bad < 5u) {
                int fits = 0;
                const double ex = ft_pgrid_quad_exact(t, &q, &fits);
                printf("  quad (%u, %u): shader %.4f m, CPU %.4f m (exact %.4f, fits %d; "
                       "corners %.4f,%.4f %.4f,%.4f %.4f,%.4f %.4f,%.4f)\n", i, j, gpu, cpu, ex,
                       fits, q.g[0][0], q.g[0][1], q.g[1][0], q.g[1][1], q.g[2][0], q.g[2][1],
                       q.g[3][0], q.g[3][1]);
            }
            ++bad;
        }
        worst = fmax(worst, d);
        sum += cpu;
        ++n;
    }
    printf("residual bound, shader vs CPU rule: %u quads, %u under the CPU's or over it by more "
           "than twice the float margin (largest difference from CPU + margin %.5f m), mean "
           "bound %.2f m\n", n, bad, worst, sum / (double)n);
    CHECK(n > 1000u);
    CHECK(bad == 0u);
    /* the vertex bounds: the largest of the <= 4 quads around each vertex */
    uint32_t vbad = 0u;
    for (uint32_t j = 0; j < rows; ++j) {
        for (uint32_t i = 0; i < cols; ++i) {
            float want = 0.0f;
            for (uint32_t dj = 0; dj < 2u; ++dj) {
                for (uint32_t di = 0; di < 2u; ++di) {
                    const uint32_t qi = (i >= di) ? i - di : 0u, qj = (j >= dj) ? j - dj : 0u;
                    const uint32_t ci = qi < cols - 2u ? qi : cols - 2u;
                    const uint32_t cj = qj < rows - 2u ? qj : rows - 2u;
                    want = fmaxf(want, g_quad[4u * (cj * (cols - 1u) + ci)]);
                }
            }
            vbad += (g_shape[4u * (j * cols + i) + 2u] != want);
            /* and the bound of the quad whose triangles end at it */
            if (i > 0u && j > 0u) {
                vbad += (g_shape[4u * (j * cols + i) + 3u] !=
                         g_quad[4u * ((j - 1u) * (cols - 1u) + i - 1u)]);
            }
        }
    }
    printf("vertex bounds: %u of %u differ from the largest of their quads' bounds\n", vbad,
           cols * rows);
    CHECK(vbad == 0u);
    ft_app_shutdown(&g_app);
}

/* ---- 2. the error buffer written by the picture pass -------------------------- */

/* On GLES 3 the picture pass writes the error buffer as its second colour
 * attachment and the envelopes test against the picture's depth. The same
 * frames drawn the other way (the error buffer on its own, with its own
 * depth: m->mrt = 0) must give the same codes. Without ray casting the
 * decision reads this frame's buffer; with it the readback is a frame late,
 * so each pose is drawn twice and the second frame's readback compared.
 * Allowed: pixels where the two depth buffers (the picture's, the error
 * buffer's 24-bit one) could order a silhouette differently (measured 0 of
 * 29,000-37,000 terrain pixels a frame, with and without the envelopes; a
 * picture pass that does not write its second output differs on 17,000-
 * 37,000). */
#define MRT_FRAMES 4
#define MRT_DIFF_PER_MILLE 5u

static uint8_t g_codes[2][W_PX * H_PX];

static void error_codes(int ray_casting, int mrt, int f, uint8_t *codes)
{
    ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    m->mrt = mrt;
    ft_pose p = path_pose(f);
    for (int k = 0; k < (ray_casting ? 2 : 1); ++k) {
        ft_camera cam;
        ft_frame_stats fs;
        ft_test_frame(&g_app, &p, &cam, &fs);
    }
    for (uint32_t k = 0; k < W_PX * H_PX; ++k) codes[k] = m->readback[4u * k + 1u];
    m->mrt = 1;
}

static void test_error_buffer_mrt(const char *dem)
{
    for (int rc = 0; rc <= 1; ++rc) {
        setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, rc, 1.0, 0, rc, 0u};
        app_init(&c);
        CHECK(g_app.renderer.method.u.pgrid.mrt == 1);
        for (int f = 0; f < MRT_FRAMES; ++f) {
            error_codes(rc, 1, f, g_codes[0]);
            error_codes(rc, 0, f, g_codes[1]);
            uint32_t terrain = 0u, differ = 0u, over = 0u, terrain_alone = 0u;
            for (uint32_t k = 0; k < W_PX * H_PX; ++k) {
                terrain_alone += (g_codes[1][k] != 0u);
                terrain += (g_codes[0][k] != 0u);
                differ += (g_codes[0][k] != g_codes[1][k]);
                over += (g_codes[0][k] > ft_pgrid_code(1.0));
            }
            printf("error buffer, picture pass vs its own pass (%s) f%d: %u terrain px "
                   "(%u over gamma 1; on its own %u), %u differ (allowed %u)\n",
                   rc ? "ray casting, envelopes" : "no ray casting", f, terrain, over,
                   terrain_alone, differ,
                   terrain * MRT_DIFF_PER_MILLE / 1000u);
            CHECK(terrain > W_PX * H_PX / 10u);
            CHECK(over > 0u);
            CHECK(differ <= terrain * MRT_DIFF_PER_MILLE / 1000u);
        }
        ft_app_shutdown(&g_app);
    }
}

/* ---- 5. the lower envelope only where the surface may be seen from below ------- */

/* src/lod/pgrid.h 3: with the eye over the grid and above the terrain's
 * highest sample, the lower envelope is not drawn; drawn anyway
 * (lower_envelope_force 1) it must change no pixel's ray-cast decision
 * (dilated code >= code(gamma)), and where the rule draws it, leaving it out
 * (-1) must change some. Views: the flight of part 1 (3.5-5 km, above the
 * tile's highest sample), and where it is drawn: low views 20-60 m above the
 * ground, 15 m under it, and off the grid west of it looking east. */
#define LOWER_VIEWS (PATH_FRAMES + 5)

static ft_pose lower_view(int v, int *must_draw)
{
    *must_draw = 0;
    if (v < PATH_FRAMES) {
        const ft_pose p = path_pose(v);
        CHECK(p.alt_m > (double)g_app.terrain.max_height_m);
        return p;
    }
    static const double low[4][5] = {
        /* lat, lon, height over the ground (m; < 0 under it), heading, pitch */
        {42.45, 1.55, 20.0, 200.0, 0.0},
        {42.60, 1.30, 60.0, 10.0, 6.0},
        {42.35, 1.80, 35.0, 120.0, -3.0},
        {42.45, 1.55, -15.0, 200.0, 5.0},
    };
    if (v < PATH_FRAMES + 4) {
        const double *a = low[v - PATH_FRAMES];
        double x, y;
        ft_terrain_geo_to_world(&g_app.terrain, a[0], a[1], &x, &y);
        *must_draw = 1;
        return ft_test_pose(a[0], a[1], ft_terrain_height_at(&g_app.terrain, x, y) + a[2], a[3],
                            a[4], 0.0);
    }
    *must_draw = 1;
    return ft_test_pose(42.5, 0.97, 2500.0, 90.0, -4.0, 0.0); /* west of the grid */
}

/* The frame's ray-cast decision per pixel (1: dilated code >= code(gamma)),
 * after drawing the pose twice (the readback is a frame late). */
static uint32_t lower_decisions(const ft_pose *p, int force, uint8_t *decide,
                                uint32_t *envelopes)
{
    ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    m->lower_envelope_force = force;
    ft_frame_stats fs;
    for (int k = 0; k < 2; ++k) {
        ft_camera cam;
        ft_test_frame(&g_app, p, &cam, &fs);
    }
    *envelopes = fs.envelopes;
    const uint32_t thr = ft_pgrid_code(1.0);
    uint32_t marked = 0u;
    for (int y = 0; y < (int)H_PX; ++y) {
        for (int x = 0; x < (int)W_PX; ++x) {
            const uint32_t code = dilated_code(m, x, y);
            decide[(uint32_t)y * W_PX + (uint32_t)x] = (uint8_t)(code >= thr);
            marked += (code >= thr);
        }
    }
    m->lower_envelope_force = 0;
    return marked;
}

static void test_lower_envelope(const char *dem)
{
    for (int residual = 0; residual <= 1; ++residual) {
        setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, 1.0, 0, residual, 0u};
        app_init(&c);
        uint32_t skipped = 0u, drawn = 0u, lost = 0u;
        for (int v = 0; v < LOWER_VIEWS; ++v) {
            int must_draw;
            const ft_pose p = lower_view(v, &must_draw);
            uint32_t env_rule, env_always;
            const uint32_t marked = lower_decisions(&p, 0, g_codes[0], &env_rule);
            (void)lower_decisions(&p, 1, g_codes[1], &env_always);
            uint32_t differ = 0u, without = 0u;
            for (uint32_t k = 0; k < W_PX * H_PX; ++k) differ += (g_codes[0][k] != g_codes[1][k]);
            if (must_draw) {
                uint32_t env_never;
                (void)lower_decisions(&p, -1, g_codes[0], &env_never);
                CHECK(env_never == 1u);
                for (uint32_t k = 0; k < W_PX * H_PX; ++k) {
                    without += (g_codes[0][k] != g_codes[1][k]);
                }
                lost += without;
            }
            printf("lower envelope (%s) view %d: %u envelopes by the rule (must draw it: %d), "
                   "%u px marked, %u decisions differ from always drawing it (%u without it)\n",
                   residual ? "residual" : "relief", v, env_rule, must_draw, marked, differ,
                   without);
            CHECK(env_always == 2u);
            CHECK(env_rule == (must_draw ? 2u : 1u));
            if (env_rule == 1u) {
                CHECK(differ == 0u);
                ++skipped;
            } else {
                ++drawn;
            }
        }
        CHECK(skipped == PATH_FRAMES);
        CHECK(drawn == LOWER_VIEWS - PATH_FRAMES);
        CHECK(lost > 0u); /* the comparison sees what the lower envelope marks */
        ft_app_shutdown(&g_app);
    }
}

/* ---- 6. the ray caster's tiles (src/lod/pgrid.h 4) ---------------------------- */

#define TILE_FRAMES 4
#define TILE_SIDES 3

static uint8_t g_tile_pic[TILE_SIDES][TILE_FRAMES][W_PX * H_PX * 4u];
static uint8_t g_err_rgba[W_PX * H_PX * 4u];
static uint8_t g_tile_rgba[W_PX * H_PX * 4u]; /* at most W x H tiles */

static void test_tiles(const char *dem)
{
    static const uint32_t sides[TILE_SIDES] = {4u, 13u, 64u};
    for (int k = 0; k < TILE_SIDES; ++k) {
        setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, 1.0, 0, 1,
                   sides[k]};
        app_init(&c);
        const ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
        REQUIRE(m->tile_px == sides[k]);
        REQUIRE(m->tiles_w == (W_PX + sides[k] - 1u) / sides[k]);
        const ft_gl *gl = &g_app.gpu.gl;
        for (int f = 0; f < TILE_FRAMES; ++f) {
            ft_camera cam;
            ft_frame_stats fs;
            ft_pose p = path_pose(2 * f);
            ft_test_frame(&g_app, &p, &cam, &fs);
            memcpy(g_tile_pic[k][f], g_app.renderer.rgba, sizeof g_tile_pic[k][f]);
            gl->BindFramebuffer(GL_FRAMEBUFFER, m->err_fbo);
            gl->ReadPixels(0, 0, (GLsizei)W_PX, (GLsizei)H_PX, GL_RGBA, GL_UNSIGNED_BYTE,
                           g_err_rgba);
            gl->BindFramebuffer(GL_FRAMEBUFFER, m->tile_fbo);
            gl->ReadPixels(0, 0, (GLsizei)m->tiles_w, (GLsizei)m->tiles_h, GL_RGBA,
                           GL_UNSIGNED_BYTE, g_tile_rgba);
            gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
            CHECK(ft_gl_check(gl, "reading the error buffer and the tiles back", NULL) == FT_OK);
            uint32_t wrong = 0u, drawn = 0u;
            for (uint32_t ty = 0; ty < m->tiles_h; ++ty) {
                for (uint32_t tx = 0; tx < m->tiles_w; ++tx) {
                    uint32_t want = 0u;
                    const int x0 = (int)(tx * m->tile_px) - 1, y0 = (int)(ty * m->tile_px) - 1;
                    for (int y = y0; y <= y0 + (int)m->tile_px + 1; ++y) {
                        for (int x = x0; x <= x0 + (int)m->tile_px + 1; ++x) {
                            const int cx = x < 0 ? 0 : (x >= (int)W_PX ? (int)W_PX - 1 : x);
                            const int cy = y < 0 ? 0 : (y >= (int)H_PX ? (int)H_PX - 1 : y);
                            const uint32_t code = g_err_rgba[4u * ((uint32_t)cy * W_PX +
                                                                   (uint32_t)cx) + 1u];
                            if (code > want) want = code;
                        }
                    }
                    const uint32_t got = g_tile_rgba[4u * (ty * m->tiles_w + tx)];
                    wrong += (got != want);
                    drawn += (got >= m->thr);
                }
            }
            const uint32_t tiles = m->tiles_w * m->tiles_h;
            printf("ray-cast tiles of %u px, frame %d: %u of %u drawn (threshold %u), %u wrong\n",
                   m->tile_px, f, drawn, tiles, m->thr, wrong);
            CHECK(wrong == 0u);
            if (m->tile_px < 64u) {
                CHECK(drawn > 0u && drawn < tiles);
            }
            if (k > 0) {
                uint32_t differ = 0u;
                for (uint32_t i = 0; i < W_PX * H_PX * 4u; ++i) {
                    differ += (g_tile_pic[k][f][i] != g_tile_pic[0][f][i]);
                }
                printf("  picture against tiles of %u px: %u bytes differ\n", sides[0], differ);
                CHECK(differ == 0u);
            }
        }
        ft_app_shutdown(&g_app);
    }
}

/* ---- 8. columns moved by the error (src/lod/pgrid.h 1) ----------------------- */

/* pgrid.columns = error on the flight of part 1, gamma 1: the bound holds on
 * every frame as in part 1; the knots leave uniform (some band's share off
 * by more than 5%); and the vertex pass places the columns where the knots
 * say: along the grid's bottom row (a base-plane line along the sampling
 * camera's right vector, so the share of the row's length up to a vertex is
 * its u) each vertex's u equals ft_pgrid_col_u(knots, i / (cols - 1)). */
static void test_columns(const char *dem)
{
    g_columns_error = 1;
    setup c = {"pgrid", "egl-gles3", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, 1.0, 1, 1, 0u};
    app_init(&c);
    g_columns_error = 0;
    const ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    REQUIRE(m->tight && m->col_warp);
    const ft_gl *gl = &g_app.gpu.gl;
    const uint32_t cols = m->pgm.cols;
    double worst_share = 0.0, worst_u = 0.0;
    uint32_t rows_checked = 0u;
    for (int f = 0; f < PATH_FRAMES; ++f) {
        ft_camera cam;
        ft_frame_stats fs;
        ft_error_stats es;
        fly_measured(f, &cam, &fs, &es);
        const uint32_t cover = es.only_method_px + es.only_ref_px;
        double share_off = 0.0;
        for (uint32_t b = 0; b < FT_PGRID_COL_BANDS; ++b) {
            const double share = FT_PGRID_COL_BANDS * (double)(m->col_t[b + 1u] - m->col_t[b]);
            share_off = fmax(share_off, fabs(share - 1.0));
        }
        worst_share = fmax(worst_share, share_off);
        /* the bottom row as the vertex pass placed it */
        gl->BindFramebuffer(GL_FRAMEBUFFER, m->vtx_fbo);
        gl->ReadPixels(0, 0, (GLsizei)cols, 1, GL_RGBA, GL_FLOAT, g_vtx);
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        const double *r = m->pgm.sampling.right;
        const double len = (g_vtx[4u * (cols - 1u)] - g_vtx[0]) * r[0] +
                           (g_vtx[4u * (cols - 1u) + 1u] - g_vtx[1]) * r[1];
        /* a row clamped into the grid at either end is not on its line */
        const ft_terrain *t = &g_app.terrain;
        const double lo_x = t->origin_world_x_m - cam.eye_m[0];
        const double hi_x = lo_x + (t->width - 1u) * t->cell_x_m;
        const double lo_y = t->origin_world_y_m - cam.eye_m[1];
        const double hi_y = lo_y + (t->height - 1u) * t->cell_y_m;
        int clamped = 0;
        for (uint32_t i = 0; i < cols; ++i) {
            const float *v = g_vtx + 4u * i;
            clamped |= (v[0] <= lo_x + 1.0 || v[0] >= hi_x - 1.0 || v[1] <= lo_y + 1.0 ||
                        v[1] >= hi_y - 1.0);
        }
        double row_worst = 0.0;
        if (!clamped && fabs(len) > 1.0) {
            for (uint32_t i = 0; i < cols; ++i) {
                const float *v = g_vtx + 4u * i;
                const double u = ((v[0] - g_vtx[0]) * r[0] + (v[1] - g_vtx[1]) * r[1]) / len;
                const double want = ft_pgrid_col_u(m->col_t, (double)i / (double)(cols - 1u));
                row_worst = fmax(row_worst, fabs(u - want));
            }
            worst_u = fmax(worst_u, row_worst);
            ++rows_checked;
        }
        printf("columns by the error f%d: max %.3f px, cover %u, %.1f%% of the terrain ray cast; "
               "largest band share off uniform %.3f; bottom row %s, worst |u - knots| %.2g\n",
               f, es.max_px, cover,
               fs.terrain_px ? 100.0 * (double)fs.raycast_px / (double)fs.terrain_px : 0.0,
               share_off, clamped ? "clamped (not checked)" : "on its line", row_worst);
        CHECK(es.nonfinite_px == 0u);
        CHECK(!fs.budget_hit);
        CHECK(es.max_px <= 1.0 + TOL_PX);
        CHECK(cover <= COVER_PX_PER_GAMMA);
    }
    CHECK(worst_share > 0.05);
    CHECK(rows_checked >= PATH_FRAMES / 2u);
    CHECK(worst_u < 1e-3);
    ft_app_shutdown(&g_app);
}

int main(int argc, char **argv)
{
    REQUIRE(argc >= 3);
    const char *mode = argv[1], *dem = argv[2];
    if (!ft_test_have_data(dem)) return FT_TEST_SKIP;
    if (strcmp(mode, "sweep") == 0) {
        /* the sweep over another DEM, around (argv[3], argv[4]) */
        REQUIRE(argc >= 5);
        test_sweep(dem, atof(argv[3]), atof(argv[4]));
        return ft_test_result("test_pgrid_gl sweep");
    }
    if (strcmp(mode, "es2") == 0) {
        /* columns = error needs the ray caster's error buffer: uniform here */
        g_columns_error = 1;
        setup c = {"pgrid", "egl-gles2", dem, 60.0, GRID_COLS, GRID_ROWS, 1, 1, 1.0, 0, 1, 0u};
        app_init(&c);
        g_columns_error = 0;
        CHECK(g_app.renderer.method.u.pgrid.col_warp == 0);
        ft_app_shutdown(&g_app);
        test_cracks("egl-gles2", dem);
        return ft_test_result("test_pgrid_gl es2");
    }
    const char *only = getenv("PGRID_ONLY"); /* a single part, for diagnosis */
    if (only == NULL || strcmp(only, "bound") == 0) test_error_bound(dem, 0);
    if (only == NULL || strcmp(only, "residual") == 0) {
        test_residual_mirror(dem);
        test_error_bound(dem, 1);
    }
    if (only == NULL || strcmp(only, "mrt") == 0) test_error_buffer_mrt(dem);
    if (only == NULL || strcmp(only, "lower") == 0) test_lower_envelope(dem);
    if (only == NULL || strcmp(only, "dist") == 0) test_distribution(dem);
    if (only == NULL || strcmp(only, "sweep") == 0) test_sweep(dem, 42.45, 1.55);
    if (only == NULL || strcmp(only, "cracks") == 0) test_cracks("egl-gles3", dem);
    if (only == NULL || strcmp(only, "tiles") == 0) test_tiles(dem);
    if (only == NULL || strcmp(only, "columns") == 0) test_columns(dem);
    return ft_test_result("test_pgrid_gl es3");
}
