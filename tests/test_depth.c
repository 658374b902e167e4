/* test_depth.c - depth precision: the near-plane rule, and what it buys.
 *
 * usage: test_depth rule
 *        test_depth order BACKEND     (egl-gles3, egl-gles2, osmesa)
 *
 * rule (no GPU):
 * 1. Conservative: for eyes all over two grids (square cells and 64 x 93 m
 *    cells), 1 m to 3 km above the surface, under it, outside the grid,
 *    with no curvature, the sphere's and an exaggerated one (a 1 km drop at
 *    10 km), ft_camera_terrain_clearance_m is <= the least distance to
 *    every cell's box [x] x [y] x [zmin - k dmax^2, zmax - k dmin^2] (brute
 *    force over all cells) and <= the distance to every point of a 3 x 3
 *    sampling of each cell's bilinear surface as drawn (lowered by k d^2);
 *    so near / corner_cos <= the true nearest terrain point / 2. Every such
 *    point's distance is inside the far plane.
 * 2. Useful: an eye 300 m above a valley floor, below a 4000 m peak 6 km
 *    away, gets a near plane > 50 m (the global rule gives 0.25 m).
 * 3. Without a pyramid the rule is the global one; the depth step formula.
 *
 * order (a real context, brute force):
 *    A grid 33 x 11894 samples of 250 m x 7 m (metres): flat ground at 0 m,
 *    a 4000 m cone 1.75 km east of the eye (at 1500 m: the eye is below the
 *    tile's highest point, so the global rule puts the near plane at
 *    0.25 m), and 81 km south two ridges across the grid: the near ridge A
 *    1200 m high, one row wide, then two rows of floor, then the far ridge
 *    B 2400 m high. Along a ray that meets A's face the ray would meet B's
 *    face 17.5 m (at A's crest) to 21 m (at its foot) farther. Looking
 *    south, A must hide B's lower part; B shows above A's crest. Brute force
 *    draws rows south to north, so here B is drawn first: with depth steps
 *    coarser than the gap, equal depths keep B (GL_LESS) and B's face shows
 *    through A. B's face is shaded differently from A's at the same height
 *    (its vertex normals tilt over 2400 m, A's over 1200 m), so the wrong
 *    order shows in the colour image, which GLES 2 has too.
 *    The same view over the same grid without B is the expected image: on
 *    every pixel where it shows terrain (A or the ground in front of it)
 *    the two frames must agree; the normals of the floor row next to B
 *    differ between the two grids, but that floor is hidden behind A.
 *    Also: B does show above A (the view holds both), the frame reports a
 *    depth step at 81 km below half the gap, and the near plane > 10 m.
 *    Measured with the global rule (near 0.25 m): the order check fails on
 *    every backend (see the README's depth section). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/camera.h"
#include "core/units.h"
#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "terrain/terrain_file.h"
#include "test_util.h"
#include "test_terrain_util.h"
#if FT_DEPTH_GL
#include "app/app.h"
#include "gpu/shade.h"
#include "test_app_util.h"
#endif


/* ---- rule ------------------------------------------------------------------------- */

#define VALLEY_X0 0.0
#define VALLEY_Y0 0.0
/* a valley floor at 1000 m, ridges of 600 m, a 4000 m peak at (6000, 3000) */
static double valley_height(double x, double y, uint32_t ix, uint32_t iy)
{
    (void)ix;
    (void)iy;
    const double px = x - 6000.0, py = y - 3000.0;
    const double peak = 3000.0 * exp(-(px * px + py * py) / (1200.0 * 1200.0));
    const double ridges = 600.0 * pow(sin(x * 0.00041) * cos(y * 0.00057), 2.0);
    return 1000.0 + peak + ridges * (x > 1500.0 || y > 1500.0 ? 1.0 : 0.0);
}

static double rough_height(double x, double y, uint32_t ix, uint32_t iy)
{
    /* a needle and a cliff on hills: cells whose boxes are far from flat */
    double h = 300.0 + 250.0 * sin(x * 0.0021) * cos(y * 0.0013) + 40.0 * sin(x * 0.05 + y * 0.03);
    if (ix == 60u && iy == 40u) h += 1500.0;
    if (ix > 90u) h += 400.0;
    return h;
}

/* Bilinear height of cell (ix, iy) at local (u, v) in [0, 1]. */
static double bilinear(const ft_terrain *t, uint32_t ix, uint32_t iy, double u, double v)
{
    const float *r0 = t->heights_m + (size_t)iy * t->width + ix;
    const float *r1 = r0 + t->width;
    return (1 - v) * ((1 - u) * r0[0] + u * r0[1]) + v * ((1 - u) * r1[0] + u * r1[1]);
}

/* Brute force over every cell: the least box distance (with the curvature
 * widening) and the least distance to a 3 x 3 sampling of the drawn
 * surface; the most distance (for the far plane). */
static void brute_force(const ft_terrain *t, const double eye[3], double k, double *box_min,
                        double *surf_min, double *surf_max)
{
    double bmin = INFINITY, smin = INFINITY, smax = 0.0;
    for (uint32_t iy = 0; iy + 1u < t->height; ++iy) {
        for (uint32_t ix = 0; ix + 1u < t->width; ++ix) {
            const double x0 = t->origin_world_x_m + ix * t->cell_x_m, x1 = x0 + t->cell_x_m;
            const double y0 = t->origin_world_y_m + iy * t->cell_y_m, y1 = y0 + t->cell_y_m;
            const float *r0 = t->heights_m + (size_t)iy * t->width + ix;
            const float *r1 = r0 + t->width;
            const double zmin = fmin(fmin(r0[0], r0[1]), fmin(r1[0], r1[1]));
            const double zmax = fmax(fmax(r0[0], r0[1]), fmax(r1[0], r1[1]));
            const double dx = eye[0] < x0 ? x0 - eye[0] : (eye[0] > x1 ? eye[0] - x1 : 0.0);
            const double dy = eye[1] < y0 ? y0 - eye[1] : (eye[1] > y1 ? eye[1] - y1 : 0.0);
            const double fx = fmax(fabs(eye[0] - x0), fabs(eye[0] - x1));
            const double fy = fmax(fabs(eye[1] - y0), fabs(eye[1] - y1));
            const double lo = zmin - k * (fx * fx + fy * fy), hi = zmax - k * (dx * dx + dy * dy);
            const double dz = eye[2] < lo ? lo - eye[2] : (eye[2] > hi ? eye[2] - hi : 0.0);
            const double d = sqrt(dx * dx + dy * dy + dz * dz);
            if (d < bmin) bmin = d;
            for (int sv = 0; sv <= 2; ++sv) {
                for (int su = 0; su <= 2; ++su) {
                    const double u = 0.5 * su, v = 0.5 * sv;
                    const double px = x0 + u * t->cell_x_m - eye[0];
                    const double py = y0 + v * t->cell_y_m - eye[1];
                    const double pz =
                        bilinear(t, ix, iy, u, v) - k * (px * px + py * py) - eye[2];
                    const double dd = sqrt(px * px + py * py + pz * pz);
                    if (dd < smin) smin = dd;
                    if (dd > smax) smax = dd;
                }
            }
        }
    }
    *box_min = bmin;
    *surf_min = smin;
    *surf_max = smax;
}

static double corner_cos_for(double fovy_deg, double aspect)
{
    const double ty = tan(0.5 * fovy_deg * FT_PI / 180.0), tx = ty * aspect;
    return 1.0 / sqrt(1.0 + tx * tx + ty * ty);
}

static void check_conservative(const ft_terrain *t, const char *name)
{
    static const double ks[3] = {0.0, 1.0 / (2.0 * FT_EARTH_RADIUS_M), 1.0e-5};
    static const double agl[6] = {1.0, 5.0, 40.0, 300.0, 3000.0, -30.0};
    static const double where[7][2] = {{0.5, 0.5}, {0.02, 0.03}, {0.97, 0.6},  {0.3, 0.99},
                                       {0.6, 0.4}, {-0.2, 0.5},  {1.4, -0.3}};
    const double cc = corner_cos_for(60.0, 4.0 / 3.0);
    const double wx = t->cell_x_m * (t->width - 1u), wy = t->cell_y_m * (t->height - 1u);
    int n = 0, tight = 0, bad = 0;
    double worst_ratio = 1.0;
    for (size_t ki = 0; ki < 3; ++ki) {
        for (size_t wi = 0; wi < 7; ++wi) {
            for (size_t ai = 0; ai < 6; ++ai) {
                double eye[3] = {t->origin_world_x_m + where[wi][0] * wx,
                                 t->origin_world_y_m + where[wi][1] * wy, 0.0};
                eye[2] = ft_terrain_height_at(t, eye[0], eye[1]) + agl[ai];
                const double k = ks[ki];
                const double c = ft_camera_terrain_clearance_m(t, eye, k);
                double bmin, smin, smax;
                brute_force(t, eye, k, &bmin, &smin, &smax);
                double nr, fr;
                ft_camera_depth_range_for_terrain(t, eye, cc, k, &nr, &fr);
                ++n;
                if (!(c <= bmin + 1e-6 && c <= smin + 1e-6)) {
                    ++bad;
                    fprintf(stderr, "%s: eye (%.3f, %.3f) %+.0f m, k %.3g: clearance %.4f > "
                                    "brute force box %.4f / surface %.4f\n",
                            name, where[wi][0], where[wi][1], agl[ai], k, c, bmin, smin);
                }
                CHECK(c <= bmin + 1e-6);
                CHECK(c <= smin + 1e-6);
                /* near / corner_cos is at most half the true nearest point,
                 * unless the 0.25 m floor holds it */
                CHECK(nr / cc <= fmax(0.25 / cc, 0.5 * smin) + 1e-9);
                /* the far plane holds every surface point (depth <= distance) */
                CHECK(fr >= smax);
                CHECK(nr > 0.0 && fr > nr);
                if (bmin > 0.0) {
                    const double ratio = c / bmin;
                    if (ratio < worst_ratio) worst_ratio = ratio;
                    tight += ratio > 0.5;
                }
            }
        }
    }
    printf("%s: %d eyes x curvatures: clearance above brute force in %d; >= half the brute "
           "force box bound in %d, worst ratio %.3f\n",
           name, n, bad, tight, worst_ratio);
}

static int run_rule(void)
{
    ft_terrain t;
    /* 1. conservative on square cells and on cells like Rainier's */
    terrain_make(&t, 161, 121, 50.0, 50.0, VALLEY_X0, VALLEY_Y0, valley_height);
    check_conservative(&t, "valley 161x121, 50 m cells");
    terrain_free(&t);
    terrain_make(&t, 129, 97, 64.0, 93.0, 5.0e5, 5.2e6, rough_height);
    check_conservative(&t, "rough 129x97, 64 x 93 m cells");
    terrain_free(&t);

    /* 2. useful: 300 m above the valley floor, below a 4000 m peak 6 km away */
    terrain_make(&t, 161, 121, 50.0, 50.0, VALLEY_X0, VALLEY_Y0, valley_height);
    const double cc = corner_cos_for(60.0, 4.0 / 3.0);
    const double eye[3] = {600.0, 600.0, 1300.0};
    double n_new, f_new, n_old, f_old, bmin, smin, smax;
    ft_camera_depth_range_for_terrain(&t, eye, cc, 0.0, &n_new, &f_new);
    const double bmin_box[2] = {0.0, 0.0}, bmax_box[2] = {8000.0, 6000.0};
    ft_camera_pick_depth_range(eye, t.min_height_m, t.max_height_m, bmin_box, bmax_box, cc, &n_old,
                               &f_old);
    brute_force(&t, eye, 0.0, &bmin, &smin, &smax);
    printf("valley eye 300 m above the floor, peak %.0f m: near %.2f m (global rule %.2f m), "
           "far %.0f m (%.0f), nearest terrain %.1f m\n",
           (double)t.max_height_m, n_new, n_old, f_new, f_old, smin);
    CHECK(t.max_height_m > 3900.0f && eye[2] < t.max_height_m);
    CHECK(n_old == 0.25);
    CHECK(n_new > 50.0);
    CHECK(n_new <= 0.5 * smin * cc);
    CHECK(f_new == f_old); /* the far plane did not change with k = 0 */

    /* 3. no pyramid: the global rule */
    t.pyr.minmax_levels = 0;
    double n_fb, f_fb;
    ft_camera_depth_range_for_terrain(&t, eye, cc, 0.0, &n_fb, &f_fb);
    CHECK(n_fb == n_old && f_fb == f_old);
    terrain_free(&t);

    /* depth step: 2^-D (f - n) z^2 / (f n); 32F = 24-bit at the far plane */
    const double n = 100.0, f = 1.0e5;
    const double s24 = ft_camera_depth_step_m(n, f, 24u, 0, f);
    CHECK_NEAR(s24, (f - n) * f / n / 16777216.0, 1e-12);
    CHECK_NEAR(ft_camera_depth_step_m(n, f, 16u, 0, f), 256.0 * s24, 1e-9);
    CHECK_NEAR(ft_camera_depth_step_m(n, f, 32u, 1, f), s24, 1e-12);
    /* float is finer than 24-bit only close to the near plane */
    CHECK(ft_camera_depth_step_m(n, f, 32u, 1, 1.5 * n) < ft_camera_depth_step_m(n, f, 24u, 0, 1.5 * n));
    CHECK(isinf(ft_camera_depth_step_m(0.0, f, 24u, 0, f)));
    return ft_test_result("depth rule");
}

/* ---- order ------------------------------------------------------------------------ */

#if FT_DEPTH_GL

#define ORD_W 33u
#define ORD_DX 250.0
#define ORD_DY 7.0
#define ORD_ROW_B 20u                 /* far ridge's crest row */
#define ORD_ROW_A (ORD_ROW_B + 3u)    /* near ridge's crest row: two floor rows between */
#define ORD_DIST_M 81000.0            /* eye to A, north to south */
#define ORD_ROW_EYE (ORD_ROW_A + 11571u)
#define ORD_H (ORD_ROW_EYE + 300u)
#define ORD_COL_EYE 16u
#define ORD_EYE_ALT 1500.0
#define ORD_HA 1200.0
#define ORD_HB 2400.0
#define ORD_X0 500000.0
#define ORD_Y0 4900000.0

static int g_with_b;

static double ridge_height(double x, double y, uint32_t ix, uint32_t iy)
{
    (void)ix;
    if (iy == ORD_ROW_A) return ORD_HA;
    if (iy == ORD_ROW_B && g_with_b) return ORD_HB;
    /* the cone: 4000 m, radius 1500 m, centred 1750 m east of the eye */
    const double cx = ORD_X0 + (ORD_COL_EYE + 7u) * ORD_DX, cy = ORD_Y0 + ORD_ROW_EYE * ORD_DY;
    const double r = sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy));
    return r < 1500.0 ? 4000.0 * (1.0 - r / 1500.0) : 0.0;
}

static void write_ridges(const char *path, int with_b)
{
    ft_terrain t;
    g_with_b = with_b;
    terrain_make(&t, ORD_W, ORD_H, ORD_DX, ORD_DY, ORD_X0, ORD_Y0, ridge_height);
    terrain_write_ftt(&t, path);
    terrain_free(&t);
}

static ft_app g_app;
static char g_text[2048];
#define ORD_PX (320u * 240u)
static uint8_t g_both[ORD_PX * 4u], g_only_a[ORD_PX * 4u];

static const char k_order_scene[] =
    "[scene]\nname = depth-order\nmethod = brute\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 8\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 16M\n[metric]\nenabled = 0\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 200000000\n"
    "[budget]\nheights_bytes = 2M\npyramids_bytes = 8M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 512K\ngpu_staging_bytes = 2M\nmethod_bytes = 128K\npng_bytes = 512K\n";

/* Renders the view south at the ridges over dem into out. */
static void render(const char *backend, const char *dem, uint8_t *out, ft_frame_stats *fs)
{
    (void)snprintf(g_text, sizeof g_text, k_order_scene, backend, dem);
    ft_test_app_init(&g_app, g_text, dem);
    const ft_terrain *t = &g_app.terrain;
    /* the eye above sample (ORD_COL_EYE, ORD_ROW_EYE), as a pose */
    const double m_per_deg = FT_EARTH_RADIUS_M * FT_PI / 180.0;
    const double ex = ORD_X0 + ORD_COL_EYE * ORD_DX, ey = ORD_Y0 + ORD_ROW_EYE * ORD_DY;
    ft_pose p = {t->anchor_lat_deg + (ey - ORD_Y0) / m_per_deg,
                 t->anchor_lon_deg + (ex - ORD_X0) / (m_per_deg * cos(t->anchor_lat_deg * FT_PI / 180.0)),
                 ORD_EYE_ALT, 180.0, -0.2, 0.0};
    ft_camera cam;
    ft_error err;
    ft_status st = ft_app_render(&g_app, &p, &cam, fs, &err);
    if (st != FT_OK) fprintf(stderr, "frame: %s\n", err.text);
    REQUIRE(st == FT_OK);
    CHECK(fabs(cam.eye_m[0] - ex) < 0.01 && fabs(cam.eye_m[1] - ey) < 0.01);
    printf("%s: %s, %s, depth %u-bit %s, near %.2f m, far %.0f m, step at far %.3f m, at "
           "the ridges %.3f m\n",
           backend, dem, g_app.gpu.version, fs->depth_bits, fs->depth_float ? "float" : "fixed",
           fs->near_m, fs->far_m, fs->depth_res_far_m,
           ft_camera_depth_step_m(fs->near_m, fs->far_m, fs->depth_bits, fs->depth_float,
                                  ORD_DIST_M));
    memcpy(out, g_app.renderer.rgba, (size_t)ORD_PX * 4u);
    ft_app_shutdown(&g_app);
}

static int is_sky(const uint8_t *p)
{
    const int r = (int)(FT_SKY_R * 255.0f + 0.5f), g = (int)(FT_SKY_G * 255.0f + 0.5f),
              b = (int)(FT_SKY_B * 255.0f + 0.5f);
    return abs(p[0] - r) <= 1 && abs(p[1] - g) <= 1 && abs(p[2] - b) <= 1;
}

static int run_order(const char *backend)
{
    char both[512], only_a[512];
    (void)snprintf(both, sizeof both, "%s/depth_ridges_ab.ftt", FT_TEST_OUT_DIR);
    (void)snprintf(only_a, sizeof only_a, "%s/depth_ridges_a.ftt", FT_TEST_OUT_DIR);
    write_ridges(both, 1);
    write_ridges(only_a, 0);
    ft_frame_stats fs_both, fs_a;
    render(backend, both, g_both, &fs_both);
    render(backend, only_a, g_only_a, &fs_a);

    /* the gap along a ray from A's face to B's face: 2.5 to 3 rows */
    const double gap_m = 2.5 * ORD_DY;
    const double step_at_ridges = ft_camera_depth_step_m(
        fs_both.near_m, fs_both.far_m, fs_both.depth_bits, fs_both.depth_float, ORD_DIST_M);
    CHECK(fs_both.near_m > 10.0);
    CHECK(step_at_ridges < 0.5 * gap_m);
    CHECK(fs_both.near_m == fs_a.near_m && fs_both.far_m == fs_a.far_m);

    uint32_t terrain_a = 0, wrong = 0, b_above = 0, worst = 0;
    for (uint32_t i = 0; i < ORD_PX; ++i) {
        const uint8_t *pb = g_both + 4u * i, *pa = g_only_a + 4u * i;
        if (is_sky(pa)) {
            b_above += !is_sky(pb); /* B over A's crest: only in the two-ridge frame */
            continue;
        }
        ++terrain_a;
        uint32_t d = 0;
        for (int c = 0; c < 3; ++c) {
            const uint32_t e = (uint32_t)abs(pb[c] - pa[c]);
            d = e > d ? e : d;
        }
        if (d > 2u) ++wrong;
        if (d > worst) worst = d;
    }
    printf("%s: %u pixels of terrain without B, %u of them differ with B behind (max %u "
           "levels); B shows above A on %u pixels\n",
           backend, terrain_a, wrong, worst, b_above);
    CHECK(terrain_a > ORD_PX / 8u);
    CHECK(b_above > 2000u); /* B is in the view: about 25 rows x 170 columns */
    CHECK(wrong <= terrain_a / 1000u);
    if (g_ft_test_failures) {
        char path[512];
        (void)snprintf(path, sizeof path, "%s/depth_order_%s.rgba", FT_TEST_OUT_DIR, backend);
        FILE *f = fopen(path, "wb");
        if (f != NULL) {
            (void)fwrite(g_both, 1, sizeof g_both, f);
            (void)fclose(f);
            printf("the two-ridge frame (320x240 RGBA) is in %s\n", path);
        }
    }
    return ft_test_result("depth order");
}
#endif

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "rule") == 0) {
        return run_rule();
    }
#if FT_DEPTH_GL
    if (argc >= 3 && strcmp(argv[1], "order") == 0) {
        return run_order(argv[2]);
    }
#endif
    fprintf(stderr, "usage: test_depth rule | order BACKEND\n");
    return 2;
}
