/* test_metric.c - the screen-space error metric against closed forms.
 *
 * A flat (or tilted) terrain and a "rendered" surface that is the same plane
 * shifted up by d: every rendered point P is the exact ray hit with the
 * shifted plane, so the vertical error is d everywhere and the per-pixel
 * error is d * K / |P - eye| = d * K / t, computed here independently. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "metric.h"
#include "reference.h"
#include "terrain.h"
#include "test_util.h"

#define PI 3.14159265358979323846
#define W 200u
#define H 150u
#define NPX (W * H)

static float g_pos[NPX * 4];
static float g_scratch[NPX];
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
            double e = d * cam->px_per_rad_k / tt;
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
    REQUIRE(ft_camera_init(&cam, eye, 0.2, -30.0 * PI / 180.0, 0.1, 50.0 * PI / 180.0, W, H, 1.0,
                           10000.0, NULL) == FT_OK);
    expect_stats es = synth(&t, &cam, a, b, d);
    REQUIRE(es.n > NPX / 2);
    ft_error_stats st;
    ft_error err;
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, NPX, &st, &err) == FT_OK);
    CHECK(st.terrain_px == es.n);
    CHECK(st.nonfinite_px == 0);
    CHECK(st.outside_grid_px == 0);
    CHECK(st.only_method_px == 0 && st.only_ref_px == 0);
    CHECK_NEAR(st.max_px, es.max, 0.05);
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
    REQUIRE(ft_camera_init(&cam, eye, 0.2, -30.0 * PI / 180.0, 0.1, 50.0 * PI / 180.0, W, H, 1.0,
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
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, NPX, &st, &err) == FT_OK);
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
        double dist = sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
        for (int k = 0; k < 3; ++k) g_pos[out_i * 4 + k] = (float)rel[k];
        sum += 1.5 * cam.px_per_rad_k / dist;
        ++n;
    }
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, NPX, &st, &err) == FT_OK);
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
    REQUIRE(ft_metric_compute(&t, &cam, g_pos, g_ref, g_scratch, NPX, &st, &err) == FT_OK);
    CHECK(st.terrain_px == 0 && st.nonfinite_px == 0);
    CHECK(st.max_px == 0.0 && st.mean_px == 0.0 && st.p999_px == 0.0);
    CHECK(st.only_method_px == 0 && st.only_ref_px == 0);

    /* argument errors */
    CHECK(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, NPX - 1, &st, &err) == FT_ERR_ARG);
    CHECK(ft_metric_compute(&t, &cam, g_pos, NULL, NULL, NPX, &st, &err) == FT_ERR_ARG);
    CHECK(ft_metric_compute(NULL, &cam, g_pos, NULL, g_scratch, NPX, &st, &err) == FT_ERR_ARG);
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
    REQUIRE(ft_camera_init(&cam, eye, 0.0, -PI / 2.0 + 0.01, 0.0, 1.0, W, H, 1.0, 1000.0,
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
            p[0] = 0.0f;
            p[1] = 0.0f;
            p[2] = (float)(-100.0 + dz); /* |P| = 100 - dz, height 0 */
            p[3] = 1.0f;
            list[n++] = dz * cam.px_per_rad_k / (100.0 - dz);
        }
        qsort(list, n, sizeof(double), cmp_double);
        ft_error_stats st;
        REQUIRE(ft_metric_compute(&t, &cam, g_pos, NULL, g_scratch, NPX, &st, NULL) == FT_OK);
        CHECK(st.terrain_px == n);
        if (n > 0) {
            CHECK_NEAR(st.p999_px, list[rank999(n)], 1e-5 * (1.0 + list[rank999(n)]));
            CHECK_NEAR(st.max_px, list[n - 1], 1e-5 * (1.0 + list[n - 1]));
        }
    }
    free(list);
    printf("percentile selection checked\n");
}

int main(void)
{
    check_case("flat plane, d = 20 m", 0.0, 0.0, 0.0, 0.0, 20.0);
    check_case("flat plane, d = 0.25 m, origin 1e7 m", 1e7, 1e7, 0.0, 0.0, 0.25);
    check_case("tilted plane, d = 30 m", 0.0, 0.0, 0.1, 0.05, 30.0);
    check_case("tilted plane, d = 1 m, origin 1e7 m", 1e7, 1e7, 0.1, 0.05, 1.0);
    test_coverage_and_special();
    test_percentile();
    return ft_test_result("test_metric");
}
