/* test_metric.c - the screen-space error metric against closed forms.
 *
 * A flat (or tilted) terrain and a "rendered" surface that is the same plane
 * shifted up by d: every rendered point P is the exact ray hit with the
 * shifted plane, so its pixel is the pixel whose ray it lies on, and the
 * per-pixel error is the image distance from there to the projection of
 * P - (0, 0, d), computed here independently through the camera's float
 * view-projection matrix (the GPU's). Then: the old vertical formula
 * d K / |P - eye| as an approximation on the axis only, the occlusion
 * error of a ridge the drawn surface lacks, no false occlusion on a rough
 * surface drawn exactly, and the curved sea horizon. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/camera.h"
#include "core/units.h"
#include "measure/metric.h"
#include "measure/reference.h"
#include "terrain/terrain.h"
#include "test_util.h"

#define W 200u
#define H 150u
#define NPX (W * H)

static float g_pos[NPX * 4];
/* ft_metric_scratch_bytes(W, H): 9 bytes a pixel and 20 a line */
static double g_scratch[(NPX * 9u + 1024u * 20u) / sizeof(double) + 1u];
#define SCRATCH_BYTES sizeof g_scratch
static ft_ref_pixel g_ref[NPX];
static double g_expect[NPX];

static uint64_t g_rng = 0x243F6A8885A308D3ull;
static double rnd(void)
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 7;
    g_rng ^= g_rng << 17;
    return (double)(g_rng >> 11) * (1.0 / 9007199254740992.0);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* independent rank: smallest k with (k + 1) / n >= 0.999 */
static size_t rank999(size_t n)
{
    size_t k = 0;
    while ((k + 1) * 1000u < 999u * n) ++k;
    return k;
}

/* terrain z = a x + b y (grid-relative metres), exact in float */
static void make_plane(ft_terrain *t, float *heights, uint32_t n, double ox, double oy, double a,
                       double b)
{
    memset(t, 0, sizeof *t);
    t->width = t->height = n;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = t->spacing_y = 10.0;
    t->origin_x = ox;
    t->origin_y = oy;
    REQUIRE(ft_terrain_derive_frame(t, NULL) == FT_OK);
    for (uint32_t j = 0; j < n; ++j) {
        for (uint32_t i = 0; i < n; ++i) {
            heights[j * n + i] = (float)(a * 10.0 * i + b * 10.0 * j);
        }
    }
    t->heights_m = heights;
}

typedef struct expect_stats {
    size_t n;
    double max, mean, p999;
} expect_stats;

/* Image position (px, py; py = 0 the top) of camera-relative point p through
 * the camera's own column-major view_proj matrix; 0 if not in front. */
static int project(const ft_camera *cam, const double p[3], double *px, double *py)
{
    const float *m = cam->view_proj;
    double clip[4];
    for (int r = 0; r < 4; ++r) {
        clip[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    }
    if (!(clip[3] > 0.0)) return 0;
    *px = (clip[0] / clip[3] + 1.0) * 0.5 * cam->width_px;
    *py = (1.0 - clip[1] / clip[3]) * 0.5 * cam->height_px;
    return 1;
}

/* Pixel distance between the projections of p and of p lowered by d. */
static double lowered_px(const ft_camera *cam, const double p[3], double d)
{
    double q[3] = {p[0], p[1], p[2] - d}, ax, ay, bx, by;
    REQUIRE(project(cam, p, &ax, &ay) && project(cam, q, &bx, &by));
    return hypot(ax - bx, ay - by);
}

/* Fills g_pos with hits on z = a x + b y + d (positions inside the grid),
 * g_expect with the closed-form error of each terrain pixel. */
static expect_stats synth(const ft_terrain *t, const ft_camera *cam, double a, double b, double d)
{
    expect_stats es = {0, 0.0, 0.0, 0.0};
    double *list = malloc(sizeof(double) * NPX);
    REQUIRE(list != NULL);
    /* eye relative to the grid origin */
    double ex = cam->eye_m[0] - t->origin_world_x_m, ey = cam->eye_m[1] - t->origin_world_y_m;
    double ez = cam->eye_m[2];
    double sum = 0.0;
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + x;
            double r[3];
            ft_camera_pixel_ray(cam, x + 0.5, y + 0.5, r);
            double den = r[2] - a * r[0] - b * r[1];
            double tt = (a * ex + b * ey + d - ez) / den;
            double hx = ex + r[0] * tt, hy = ey + r[1] * tt;
            float *p = &g_pos[i * 4];
            g_expect[i] = -1.0;
            if (!(den < 0.0) || !(tt > 0.0) || hx < 1.0 || hy < 1.0 ||
                hx > (t->width - 1) * 10.0 - 1.0 || hy > (t->height - 1) * 10.0 - 1.0) {
                p[0] = p[1] = p[2] = 0.0f;
                p[3] = 0.0f;
                continue;
            }
            p[0] = (float)(r[0] * tt);
            p[1] = (float)(r[1] * tt);
            p[2] = (float)(r[2] * tt);
            p[3] = 1.0f;
            double pe[3] = {r[0] * tt, r[1] * tt, r[2] * tt};
            double e = lowered_px(cam, pe, d);
            g_expect[i] = e;
            list[es.n++] = e;
            sum += e;
            if (e > es.max) es.max = e;
        }
    }
    if (es.n > 0) {
        es.mean = sum / (double)es.n;
        qsort(list, es.n, sizeof(double), cmp_double);
        es.p999 = list[rank999(es.n)];
    }
    free(list);
    return es;
}

static void check_case(const char *name, double ox, double oy, double a, double b, double d)
{
    static float heights[257 * 257];
    ft_terrain t;
    make_plane(&t, heights, 257, ox, oy, a, b);
    ft_camera cam;
    double eye[3] = {ox + 1280.0, oy - 200.0, 0.0};
    eye[2] = a * 1280.0 + b * -200.0 + 300.0;
    REQUIRE(ft_camera_init(&cam, eye, 0.2, -30.0 * FT_PI / 180.0, 0.1, 50.0 * FT_PI / 180.0, W, H, 1.0,
                           10000.0, NULL) == FT_OK);
    expect_stats es = synth(&t, &cam, a, b, d);
    REQUIRE(es.n > NPX / 2);
    ft_error_stats st;
    ft_error err;
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, SCRATCH_BYTES, &st, &err) == FT_OK);
    CHECK(st.terrain_px == es.n);
    CHECK(st.nonfinite_px == 0);
    CHECK(st.outside_grid_px == 0);
    CHECK(st.only_method_px == 0 && st.only_ref_px == 0);
    CHECK_NEAR(st.max_px, es.max, 0.05);
    CHECK(st.vertical_max_px == st.max_px); /* no reference: no occlusion term */
    CHECK_NEAR(st.mean_px, es.mean, 0.05);
    CHECK_NEAR(st.p999_px, es.p999, 0.05);
    /* much tighter in fact: float positions only */
    CHECK_NEAR(st.max_px, es.max, 1e-3 * es.max);
    CHECK_NEAR(st.mean_px, es.mean, 1e-3 * es.mean);
    CHECK_NEAR(st.p999_px, es.p999, 1e-3 * es.p999);
    printf("%s: %zu terrain px, max %.4f (cf %.4f) p99.9 %.4f (cf %.4f) mean %.4f (cf %.4f) px\n",
           name, es.n, st.max_px, es.max, st.p999_px, es.p999, st.mean_px, es.mean);
}

static void test_coverage_and_special(void)
{
    static float heights[257 * 257];
    ft_terrain t;
    make_plane(&t, heights, 257, 0.0, 0.0, 0.0, 0.0);
    ft_camera cam;
    double eye[3] = {1280.0, -200.0, 300.0};
    REQUIRE(ft_camera_init(&cam, eye, 0.2, -30.0 * FT_PI / 180.0, 0.1, 50.0 * FT_PI / 180.0, W, H, 1.0,
                           10000.0, NULL) == FT_OK);
    expect_stats es = synth(&t, &cam, 0.0, 0.0, 1.5);
    ft_error_stats st;
    ft_error err;

    /* reference = the method's coverage, then 10 + 7 hand-made mismatches */
    for (size_t i = 0; i < NPX; ++i) {
        memset(&g_ref[i], 0, sizeof g_ref[i]);
        g_ref[i].hit = g_pos[i * 4 + 3] > 0.5f;
    }
    int only_m = 0, only_r = 0;
    for (size_t i = 0; i < NPX && (only_m < 10 || only_r < 7); i += 37) {
        if (g_ref[i].hit && only_m < 10) {
            g_ref[i].hit = 0;
            ++only_m;
        } else if (!g_ref[i].hit && only_r < 7) {
            g_ref[i].hit = 1;
            ++only_r;
        }
    }
    REQUIRE(only_m == 10 && only_r == 7);
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, SCRATCH_BYTES, &st, &err) == FT_OK);
    CHECK(st.only_method_px == 10);
    CHECK(st.only_ref_px == 7);
    CHECK(st.terrain_px == es.n);

    /* a NaN and an infinite position: counted apart, max infinite, mean and
     * p99.9 over the finite pixels (never NaN) */
    size_t nan_i = 0, inf_i = 0, out_i = 0;
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < NPX; ++i) {
        if (g_expect[i] < 0.0) continue;
        if (nan_i == 0) {
            nan_i = i;
        } else if (inf_i == 0) {
            inf_i = i;
        } else if (out_i == 0) {
            out_i = i;
        } else {
            sum += g_expect[i];
            ++n;
        }
    }
    g_pos[nan_i * 4 + 0] = NAN;
    g_pos[inf_i * 4 + 2] = -INFINITY;
    /* a point outside the grid (west of it, 1.5 m above the flat terrain) */
    {
        double rel[3] = {-100.0 - eye[0], 50.0 - eye[1], 1.5 - eye[2]};
        for (int k = 0; k < 3; ++k) g_pos[out_i * 4 + k] = (float)rel[k];
        sum += lowered_px(&cam, rel, 1.5);
        ++n;
    }
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, SCRATCH_BYTES, &st, &err) == FT_OK);
    CHECK(st.nonfinite_px == 2);
    CHECK(isinf(st.max_px) && st.max_px > 0.0);
    CHECK(isfinite(st.mean_px) && isfinite(st.p999_px));
    CHECK(st.terrain_px == es.n);
    CHECK(st.outside_grid_px == 1);
    CHECK_NEAR(st.mean_px, sum / (double)n, 1e-3);

    /* all sky: zero terrain pixels, zero stats, no NaN */
    for (size_t i = 0; i < NPX; ++i) {
        g_pos[i * 4 + 0] = g_pos[i * 4 + 1] = g_pos[i * 4 + 2] = 0.0f;
        g_pos[i * 4 + 3] = (i % 2) ? 0.0f : NAN; /* NaN w is sky */
        g_ref[i].hit = 0;
    }
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, SCRATCH_BYTES, &st, &err) == FT_OK);
    CHECK(st.terrain_px == 0 && st.nonfinite_px == 0);
    CHECK(st.max_px == 0.0 && st.mean_px == 0.0 && st.p999_px == 0.0);
    CHECK(st.only_method_px == 0 && st.only_ref_px == 0);

    /* argument errors */
    CHECK(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, ft_metric_scratch_bytes(W, H) - 1u, &st, &err) == FT_ERR_ARG);
    CHECK(ft_metric_compute(&t, &cam, g_pos, NULL, NULL, SCRATCH_BYTES, &st, &err) == FT_ERR_ARG);
    CHECK(ft_metric_compute(NULL, &cam, g_pos, NULL, g_scratch, SCRATCH_BYTES, &st, &err) == FT_ERR_ARG);
    printf("coverage/nan/sky cases done\n");
}

/* quickselect vs sort, with many duplicate errors and odd sizes */
static void test_percentile(void)
{
    static float heights[65 * 65];
    ft_terrain t;
    make_plane(&t, heights, 65, 0.0, 0.0, 0.0, 0.0);
    ft_camera cam;
    double eye[3] = {320.0, 320.0, 100.0};
    REQUIRE(ft_camera_init(&cam, eye, 0.0, -FT_PI / 2.0 + 0.01, 0.0, 1.0, W, H, 1.0, 1000.0,
                           NULL) == FT_OK);
    double *list = malloc(sizeof(double) * NPX);
    REQUIRE(list != NULL);
    CHECK(ft_metric_p999_rank(1) == 0);
    CHECK(ft_metric_p999_rank(1000) == 998);
    CHECK(ft_metric_p999_rank(1001) == 999);
    CHECK(ft_metric_p999_rank(2000) == 1997);
    CHECK(ft_metric_p999_rank(NPX) == rank999(NPX));
    for (int trial = 0; trial < 40; ++trial) {
        size_t n = 0;
        int levels = 1 + trial % 5; /* few distinct errors -> many ties */
        for (size_t i = 0; i < NPX; ++i) {
            float *p = &g_pos[i * 4];
            int on = (trial % 7 == 0) ? (i < (size_t)trial + 1) : (rnd() < 0.7);
            if (!on) {
                p[3] = 0.0f;
                continue;
            }
            double dz = (double)(int)(rnd() * levels); /* 0..levels-1 m off */
            p[0] = 30.0f;
            p[1] = 0.0f;
            p[2] = (float)(-100.0 + dz); /* height dz over the flat ground */
            p[3] = 1.0f;
            double pd[3] = {p[0], p[1], p[2]};
            list[n++] = lowered_px(&cam, pd, dz);
        }
        qsort(list, n, sizeof(double), cmp_double);
        ft_error_stats st;
        REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, SCRATCH_BYTES, &st, NULL) == FT_OK);
        CHECK(st.terrain_px == n);
        if (n > 0) {
            CHECK_NEAR(st.p999_px, list[rank999(n)], 1e-5 * (1.0 + list[rank999(n)]));
            CHECK_NEAR(st.max_px, list[n - 1], 1e-5 * (1.0 + list[n - 1]));
        }
    }
    free(list);
    printf("percentile selection checked\n");
}

/* One terrain pixel: the corner pixel's ray meets a tilted plane shifted up
 * by d; the metric must give the projected displacement there (0.01 px),
 * and the old centre-K formula under-reports it. At the centre the old
 * formula is a first-order approximation (within its cos factor). */
static void test_corner_and_centre(void)
{
    static float heights[257 * 257];
    ft_terrain t;
    const double a = 0.1, b = 0.05, d = 2.0;
    make_plane(&t, heights, 257, 0.0, 0.0, a, b);
    ft_camera cam;
    double eye[3] = {1280.0, 600.0, 0.0};
    eye[2] = a * eye[0] + b * eye[1] + 150.0;
    const double pix[2][2] = {{0.5, H - 0.5}, {W * 0.5, H * 0.5}}; /* bottom-left, centre */
    for (int c = 0; c < 2; ++c) {
        /* the corner of a wide, nearly level view; the centre of a 35 deg dive */
        const double pitch_deg = (c == 0) ? -12.0 : -35.0, fov_deg = (c == 0) ? 100.0 : 60.0;
        REQUIRE(ft_camera_init(&cam, eye, 0.3, pitch_deg * FT_PI / 180.0, 0.0, fov_deg * FT_PI / 180.0,
                               W, H, 1.0, 10000.0, NULL) == FT_OK);
        double r[3];
        ft_camera_pixel_ray(&cam, pix[c][0], pix[c][1], r);
        double den = r[2] - a * r[0] - b * r[1];
        double tt = (a * eye[0] + b * eye[1] + d - eye[2]) / den;
        REQUIRE(den < 0.0 && tt > 0.0);
        double pe[3] = {r[0] * tt, r[1] * tt, r[2] * tt};
        for (size_t i = 0; i < NPX * 4u; ++i) g_pos[i] = 0.0f;
        size_t at = (size_t)(pix[c][1] - 0.5) * W + (size_t)(pix[c][0] - 0.5);
        for (int k = 0; k < 3; ++k) g_pos[at * 4u + (size_t)k] = (float)pe[k];
        g_pos[at * 4u + 3u] = 1.0f;
        ft_error_stats st;
        REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, SCRATCH_BYTES, &st, NULL) ==
                FT_OK);
        double expect = lowered_px(&cam, pe, d);
        double old = d * cam.px_per_rad_k / tt;
        CHECK(st.terrain_px == 1u);
        CHECK_NEAR(st.max_px, expect, 0.01);
        if (c == 0) {
            CHECK(st.max_px > 1.3 * old); /* the old formula looked away here */
        } else {
            /* on the axis: old = d K / t bounds it, and d K cos(pitch) / t
             * (the offset's part across the ray) is its first-order value */
            CHECK(st.max_px <= old * 1.001);
            CHECK_NEAR(st.max_px, old * cos(35.0 * FT_PI / 180.0), 0.02 * old);
        }
        printf("%s pixel: exact %.4f px (independent %.4f), old formula %.4f px\n",
               c == 0 ? "corner" : "centre", st.max_px, expect, old);
    }
}

/* Flat ground at z = 0 with a ridge (150 m, rows 30..32 of a 10 m grid) 300 m
 * ahead of an eye at 100 m looking level; FOV 30 deg, so the ridge runs from
 * below the image's bottom edge to 9.5 deg up. The drawn surface lacks the
 * ridge: below the horizon it shows the ground behind the ridge (occlusion
 * mismatches), above it sky (coverage). The nearest agreeing pixels are the
 * sky above the ridge: the bottom row's error is the ridge's screen height. */
static void test_ridge_removed(void)
{
    static float heights[129 * 129];
    ft_terrain t;
    make_plane(&t, heights, 129, 0.0, 0.0, 0.0, 0.0);
    for (uint32_t j = 30; j <= 32; ++j) {
        for (uint32_t i = 0; i < 129; ++i) heights[j * 129 + i] = 150.0f;
    }
    ft_camera cam;
    double eye[3] = {640.0, 0.0, 100.0}; /* the ridge's front top edge is 300 m ahead */
    REQUIRE(ft_camera_init(&cam, eye, 0.0, 0.0, 0.0, 30.0 * FT_PI / 180.0, W, H, 1.0, 10000.0,
                           NULL) == FT_OK);
    ft_error err;
    REQUIRE(ft_reference_render(&t, &cam, g_ref, NPX, &err) == FT_OK);
    uint32_t below = 0;
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + x;
            double r[3];
            ft_camera_pixel_ray(&cam, x + 0.5, y + 0.5, r);
            float *p = &g_pos[i * 4];
            p[0] = p[1] = p[2] = p[3] = 0.0f;
            if (r[2] < 0.0) { /* the ridge-less ground */
                double tt = -eye[2] / r[2];
                p[0] = (float)(r[0] * tt);
                p[1] = (float)(r[1] * tt);
                p[2] = (float)(r[2] * tt);
                p[3] = 1.0f;
                ++below;
            }
        }
    }
    ft_error_stats st;
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, SCRATCH_BYTES, &st, &err) ==
            FT_OK);
    const double top_y = H * 0.5 - cam.px_per_rad_k * (50.0 / 300.0); /* ridge top, image rows */
    const double screen_h = (double)H - top_y;
    printf("ridge removed: %u occlusion px of %u below the horizon, worst %.2f px (ridge %.2f px "
           "high), coverage %u + %u, max %.2f px\n",
           st.occlusion_px, below, st.occlusion_max_px, screen_h, st.only_method_px,
           st.only_ref_px, st.max_px);
    CHECK(st.occlusion_px >= below - W * 3u); /* all but the ridge's own footprint rows */
    CHECK(st.occlusion_px <= below);
    CHECK_NEAR(st.occlusion_max_px, screen_h, 1.0);
    CHECK(st.max_px >= st.occlusion_max_px);
    CHECK(st.max_px >= st.vertical_max_px);
    CHECK(st.only_method_px == 0u && st.only_ref_px > 0u);
}

/* A rough surface drawn exactly (the reference's own hits as the frame):
 * no pixel may count as an occlusion mismatch, and every error is ~0. */
static void test_exact_frame_has_no_occlusion(void)
{
    static float heights[257 * 257];
    ft_terrain t;
    make_plane(&t, heights, 257, 0.0, 0.0, 0.0, 0.0);
    for (uint32_t j = 0; j < 257; ++j) {
        for (uint32_t i = 0; i < 257; ++i) {
            heights[j * 257 + i] = (float)(120.0 * sin(i * 0.21) * cos(j * 0.17) +
                                           40.0 * sin(i * 0.9 + j * 1.3) + 200.0 * rnd());
        }
    }
    ft_camera cam;
    double eye[3] = {1280.0, -300.0, 260.0};
    REQUIRE(ft_camera_init(&cam, eye, 0.1, -8.0 * FT_PI / 180.0, 0.05, 60.0 * FT_PI / 180.0, W, H, 1.0,
                           10000.0, NULL) == FT_OK);
    REQUIRE(ft_reference_render(&t, &cam, g_ref, NPX, NULL) == FT_OK);
    for (size_t i = 0; i < NPX; ++i) {
        for (int k = 0; k < 3; ++k) g_pos[i * 4 + (size_t)k] = g_ref[i].pos_rel_eye_m[k];
        g_pos[i * 4 + 3] = g_ref[i].hit ? 1.0f : 0.0f;
    }
    ft_error_stats st;
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, SCRATCH_BYTES, &st, NULL) ==
            FT_OK);
    printf("exact frame over rough terrain: %u terrain px, occlusion %u, max %.4f px\n",
           st.terrain_px, st.occlusion_px, st.max_px);
    CHECK(st.terrain_px > NPX / 3u);
    CHECK(st.occlusion_px == 0u);
    CHECK(st.max_px < 0.01);
    CHECK(st.vertical_max_px == st.max_px);
}

/* Eye 10 km over a flat sea with earth curvature: the reference's horizon
 * lies at the depression acos(R / (R + h)) (within 0.05 deg); on a flat
 * earth it would be the grid's far edge. */
static void test_sea_horizon(void)
{
    enum { SEA = 1025, HW = 64, HH = 512 };
    static float heights[SEA * SEA];
    static ft_ref_pixel ref[HW * HH];
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = t.height = SEA;
    t.unit = FT_UNIT_METRE;
    t.spacing_x = t.spacing_y = 800.0; /* 819 km square */
    REQUIRE(ft_terrain_derive_frame(&t, NULL) == FT_OK);
    for (size_t i = 0; i < (size_t)SEA * SEA; ++i) heights[i] = 0.0f;
    t.heights_m = heights;
    t.curv_drop_per_m2 = ft_terrain_curvature_drop(FT_CURVATURE_SPHERE, FT_UNIT_METRE);
    CHECK(t.curv_drop_per_m2 == 1.0 / (2.0 * FT_EARTH_RADIUS_M));
    CHECK(ft_terrain_curvature_drop(FT_CURVATURE_AUTO, FT_UNIT_DEGREE) == t.curv_drop_per_m2);
    CHECK(ft_terrain_curvature_drop(FT_CURVATURE_AUTO, FT_UNIT_METRE) == 0.0);
    CHECK(ft_terrain_curvature_drop(FT_CURVATURE_FLAT, FT_UNIT_DEGREE) == 0.0);
    const double h = 10000.0, R = FT_EARTH_RADIUS_M;
    const double dep_deg = acos(R / (R + h)) * 180.0 / FT_PI;
    ft_camera cam;
    double eye[3] = {409600.0, 409600.0, h};
    const double fov_deg = 4.0; /* 0.0078 deg a row */
    const double pitch_deg = -3.0; /* the horizon falls 27 rows under the centre */
    REQUIRE(ft_camera_init(&cam, eye, 0.0, pitch_deg * FT_PI / 180.0, 0.0, fov_deg * FT_PI / 180.0, HW,
                           HH, 1.0, 1e6, NULL) == FT_OK);
    REQUIRE(ft_reference_render(&t, &cam, ref, (size_t)HW * HH, NULL) == FT_OK);
    uint32_t first = HH; /* first sea row in the middle column */
    for (uint32_t y = 0; y < HH && first == HH; ++y) {
        if (ref[(size_t)y * HW + HW / 2].hit) first = y;
    }
    REQUIRE(first > 0u && first < HH);
    /* the boundary lies between the centres of rows first - 1 and first */
    double yb = (double)first;
    double elev_deg = pitch_deg + atan((HH * 0.5 - yb) / cam.px_per_rad_k) * 180.0 / FT_PI;
    printf("sea horizon from 10 km: at %.4f deg, expected %.4f deg\n", elev_deg, -dep_deg);
    CHECK_NEAR(elev_deg, -dep_deg, 0.05);
    /* the hit at the horizon row lies about sqrt(2 R h) = 357 km away */
    CHECK_NEAR(ref[(size_t)first * HW + HW / 2].dist_m, sqrt(2.0 * R * h), 30000.0);
    /* a flat earth puts the horizon at the grid's edge, 0.9 deg higher */
    t.curv_drop_per_m2 = 0.0;
    REQUIRE(ft_reference_render(&t, &cam, ref, (size_t)HW * HH, NULL) == FT_OK);
    uint32_t flat_first = HH;
    for (uint32_t y = 0; y < HH && flat_first == HH; ++y) {
        if (ref[(size_t)y * HW + HW / 2].hit) flat_first = y;
    }
    CHECK(flat_first + 50u < first);
}

int main(void)
{
    check_case("flat plane, d = 20 m", 0.0, 0.0, 0.0, 0.0, 20.0);
    check_case("flat plane, d = 0.25 m, origin 1e7 m", 1e7, 1e7, 0.0, 0.0, 0.25);
    check_case("tilted plane, d = 30 m", 0.0, 0.0, 0.1, 0.05, 30.0);
    check_case("tilted plane, d = 1 m, origin 1e7 m", 1e7, 1e7, 0.1, 0.05, 1.0);
    test_coverage_and_special();
    test_percentile();
    test_corner_and_centre();
    test_ridge_removed();
    test_exact_frame_has_no_occlusion();
    test_sea_horizon();
    return ft_test_result("test_metric");
}
