/* test_pgrid.c - the CPU pieces of method pgrid (src/lod/pgrid.h): delta, rho,
 * normalised error, error codes, row placement closed forms, region
 * min/max on a known pyramid, the budget threshold and the dilated
 * histogram. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lod/pgrid.h"
#include "terrain/pyramid.h"
#include "test_util.h"

static void test_error_terms(void)
{
    CHECK_NEAR(ft_pgrid_delta(10.0, 30.0, 25.0), 15.0, 1e-12);
    CHECK_NEAR(ft_pgrid_delta(10.0, 30.0, 12.0), 18.0, 1e-12);
    CHECK_NEAR(ft_pgrid_delta(10.0, 30.0, 40.0), 30.0, 1e-12); /* outside: still a bound */
    CHECK_NEAR(ft_pgrid_rho(500.0, 2.0, 1000.0), 1.0, 1e-12);
    CHECK_NEAR(ft_pgrid_norm_error(0.5, 1.0), 0.0, 0.0);
    CHECK_NEAR(ft_pgrid_norm_error(4.0, 1.0), 0.75, 1e-12);
    /* codes: rounded up, monotone, rho > g => code(rho) >= code(g) */
    for (double r = 0.01; r < 200.0; r *= 1.013) {
        const uint32_t c = ft_pgrid_code(r);
        CHECK(c >= 1u && c <= 255u);
        CHECK(ft_pgrid_code_rho_hi(c) >= r * (1.0 - 1e-12));
        CHECK(c == 1u || ft_pgrid_code_rho_hi(c - 1u) < r);
    }
}

static void test_rows(void)
{
    const double dep = 0.3, y0 = -0.5, y1 = 0.2;
    const uint32_t rows = 101;
    CHECK_NEAR(ft_pgrid_row_y(FT_PGRID_DIST_UNIFORM, dep, y0, y1, rows, 50.0), -0.15, 1e-12);
    /* view: ends kept, monotone, evenly spaced in asinh(d / h) */
    CHECK_NEAR(ft_pgrid_row_y(FT_PGRID_DIST_VIEW, dep, y0, y1, rows, 0.0), y0, 1e-9);
    CHECK_NEAR(ft_pgrid_row_y(FT_PGRID_DIST_VIEW, dep, y0, y1, rows, 100.0), y1, 1e-9);
    double prev = -1e9, prev_s = 0.0;
    for (uint32_t j = 0; j < rows; ++j) {
        const double y = ft_pgrid_row_y(FT_PGRID_DIST_VIEW, dep, y0, y1, rows, (double)j);
        CHECK(y > prev);
        prev = y;
        const double beta = dep - atan(y), d = 1.0 / tan(beta); /* h = 1 */
        const double s = asinh(d);
        if (j > 1u) {
            CHECK_NEAR(s - prev_s, (ft_pgrid_row_s(dep, y1) - ft_pgrid_row_s(dep, y0)) / 100.0,
                       1e-9);
        }
        prev_s = s;
    }
    /* far rows: consecutive ground distances in a constant ratio (square cells) */
    const double ya = ft_pgrid_row_y(FT_PGRID_DIST_VIEW, 0.05, -0.04, 0.04, 1001, 900.0);
    const double yb = ft_pgrid_row_y(FT_PGRID_DIST_VIEW, 0.05, -0.04, 0.04, 1001, 901.0);
    const double yc = ft_pgrid_row_y(FT_PGRID_DIST_VIEW, 0.05, -0.04, 0.04, 1001, 902.0);
    const double da = 1.0 / tan(0.05 - atan(ya)), db = 1.0 / tan(0.05 - atan(yb));
    const double dc = 1.0 / tan(0.05 - atan(yc));
    CHECK_NEAR(db / da, dc / db, 1e-6);
}

/* The column warp (src/lod/pgrid.h 1): the knots' map t -> u keeps the ends,
 * is the identity for uniform knots and continuous and increasing for any;
 * the warp gives more columns to the band whose pixels are over gamma, keeps
 * every share in [1/2, 4] (before the blend with the last one), and an
 * error buffer with nothing over gamma moves the knots back towards
 * uniform. */
static uint32_t g_band_hist[FT_PGRID_COL_BANDS][256];

static void test_columns(void)
{
    const uint32_t nb = FT_PGRID_COL_BANDS;
    float uni[FT_PGRID_COL_BANDS + 1], warped[FT_PGRID_COL_BANDS + 1];
    for (uint32_t b = 0; b <= nb; ++b) uni[b] = (float)b / (float)nb;
    for (double t = -0.1; t <= 1.1; t += 0.01) {
        CHECK_NEAR(ft_pgrid_col_u(uni, t), t, 1e-6);
    }
    /* 3000 pixels of band 5 over gamma 1 (code 140: under it at twice the
     * columns), every band with 100 under it (still under at half) */
    memset(g_band_hist, 0, sizeof g_band_hist);
    for (uint32_t b = 0; b < nb; ++b) g_band_hist[b][100] = 100u;
    g_band_hist[5][140] = 3000u;
    ft_pgrid_col_warp((const uint32_t (*)[256])g_band_hist, uni, 1.0, warped);
    CHECK(warped[0] == 0.0f && warped[nb] == 1.0f);
    for (uint32_t b = 0; b < nb; ++b) {
        const double share = (double)nb * (warped[b + 1u] - warped[b]);
        CHECK(share > 0.0);
        /* blended with the last share 1: sqrt of [1/2, 4], renormalised */
        CHECK(share >= sqrt(0.5) / 1.5 && share <= 2.0 * 1.5);
        if (b != 5u) CHECK(share < (double)nb * (warped[6] - warped[5]));
    }
    printf("column warp: band 5's share %.3f of a uniform band (the others %.3f)\n",
           (double)nb * (warped[6] - warped[5]), (double)nb * (warped[1] - warped[0]));
    CHECK((double)nb * (warped[6] - warped[5]) > 1.3);
    /* the map through warped knots: ends kept, increasing, continuous */
    CHECK_NEAR(ft_pgrid_col_u(warped, 0.0), 0.0, 1e-6);
    CHECK_NEAR(ft_pgrid_col_u(warped, 1.0), 1.0, 1e-6);
    double prev = -1.0;
    for (double t = 0.0; t <= 1.0 + 1e-9; t += 1.0 / 1024.0) {
        const double u = ft_pgrid_col_u(warped, t);
        CHECK(u > prev);
        if (prev > -1.0) CHECK(u - prev < 4.0 / 1024.0); /* no jump: share >= 1/4 */
        prev = u;
    }
    for (uint32_t b = 0; b <= nb; ++b) {
        CHECK_NEAR(ft_pgrid_col_u(warped, warped[b]), (double)b / nb, 1e-6);
    }
    /* nothing over gamma: back towards uniform (the square root of the share) */
    memset(g_band_hist, 0, sizeof g_band_hist);
    float back[FT_PGRID_COL_BANDS + 1];
    ft_pgrid_col_warp((const uint32_t (*)[256])g_band_hist, warped, 1.0, back);
    const double s5 = (double)nb * (warped[6] - warped[5]);
    const double s5_back = (double)nb * (back[6] - back[5]);
    CHECK(s5_back < s5 && s5_back > 1.0);
}

static float g_heights[9 * 9];
static float g_pyr[4096];

static void test_region(void)
{
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = t.height = 9u;
    t.cell_x_m = t.cell_y_m = 10.0;
    for (uint32_t i = 0; i < 81u; ++i) {
        g_heights[i] = (float)((i * 37u) % 23u);
    }
    t.heights_m = g_heights;
    ft_error err;
    CHECK(ft_pyramid_layout(&t, g_pyr, sizeof g_pyr, &err) == FT_OK);
    ft_pyramid_build(&t);
    /* a box of grid [1, 3] x [2, 4]: brute force over the samples it touches
     * must lie inside the pyramid bound */
    double lo, hi;
    ft_pgrid_region_minmax(&t, 10.0, 20.0, 30.0, 40.0, &lo, &hi);
    double blo = 1e9, bhi = -1e9;
    for (uint32_t y = 2; y <= 4; ++y) {
        for (uint32_t x = 1; x <= 3; ++x) {
            blo = fmin(blo, g_heights[y * 9u + x]);
            bhi = fmax(bhi, g_heights[y * 9u + x]);
        }
    }
    CHECK(lo <= blo && hi >= bhi);
    ft_pgrid_region_minmax(&t, -100.0, -100.0, 1000.0, 1000.0, &lo, &hi);
    CHECK_NEAR(lo, t.min_height_m, 0.0);
    CHECK_NEAR(hi, t.max_height_m, 0.0);
}

static uint8_t g_rgba[8 * 6 * 4], g_work[8 * 6];

static void test_budget(void)
{
    uint32_t hist[FT_PGRID_CODES];
    memset(hist, 0, sizeof hist);
    const uint32_t c1 = ft_pgrid_code(1.0);
    hist[0] = 100u;
    hist[c1 + 10u] = 50u;
    hist[c1 + 40u] = 20u;
    uint64_t n;
    int hit;
    CHECK(ft_pgrid_budget_threshold(hist, 1.0, 1000u, &n, &hit) == c1 && n == 70u && !hit);
    const uint32_t thr = ft_pgrid_budget_threshold(hist, 1.0, 30u, &n, &hit);
    CHECK(thr == c1 + 11u && n == 20u && hit);
    CHECK(ft_pgrid_budget_threshold(hist, 1.0, 0u, &n, &hit) == c1 + 41u && n == 0u && hit);
    /* dilation: one hot pixel makes a 3 x 3 block */
    memset(g_rgba, 0, sizeof g_rgba);
    g_rgba[(2u * 8u + 3u) * 4u + 1u] = 200u;
    ft_pgrid_histogram(g_rgba, 8u, 6u, g_work, hist);
    CHECK(hist[200] == 9u && hist[0] == 48u - 9u);
}

/* The residual bound (src/lod/pgrid.h 6) on a rough 65 x 65 terrain: the atlas
 * holds each node's residual; the quad bound is never under the true max
 * of |L - H| (L the quad's two triangles through its drawn corners, H the
 * bilinear surface: dense sampling), for quads from a quarter cell to 24
 * cells, axis-aligned or not, with drawn heights on or off the surface; on
 * a plane it is 0. */
static float g_rough[65 * 65];
static float g_rough_pyr[32768];
static float g_res_atlas[64 * 64];

/* How far above the dense samples' max the exact rule may lie, relative to
 * (1 m + that max): what a 1/400 step along the quad misses. */
#define EXACT_SLACK 0.01

static double bilinear(const ft_terrain *t, double x, double y)
{
    const uint32_t ix = (uint32_t)fmin(floor(x), (double)t->width - 2.0);
    const uint32_t iy = (uint32_t)fmin(floor(y), (double)t->height - 2.0);
    const double fx = x - ix, fy = y - iy;
    const float *h = t->heights_m + (size_t)iy * t->width + ix;
    return (1.0 - fy) * ((1.0 - fx) * h[0] + fx * h[1]) +
           fy * ((1.0 - fx) * h[t->width] + fx * h[t->width + 1u]);
}

static double quad_true_max(const ft_terrain *t, const ft_pgrid_quad *q, int n)
{
    const double(*g)[2] = q->g;
    const double *h = q->h_m;
    /* corners 0 (u0 v0), 1 (u1 v0), 2 (u0 v1), 3 (u1 v1); triangles 0-1-3, 0-3-2 */
    double mx = 0.0;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            const double u = (double)i / n, v = (double)j / n;
            double w0, w1, w2, w3;
            if (u >= v) { w0 = 1.0 - u; w1 = u - v; w2 = 0.0; w3 = v; }
            else { w0 = 1.0 - v; w1 = 0.0; w2 = v - u; w3 = u; }
            const double x = w0 * g[0][0] + w1 * g[1][0] + w2 * g[2][0] + w3 * g[3][0];
            const double y = w0 * g[0][1] + w1 * g[1][1] + w2 * g[2][1] + w3 * g[3][1];
            const double l = w0 * h[0] + w1 * h[1] + w2 * h[2] + w3 * h[3];
            mx = fmax(mx, fabs(l - bilinear(t, x, y)));
        }
    }
    return mx;
}

static void test_residual_bound(void)
{
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = t.height = 65u;
    t.cell_x_m = t.cell_y_m = 30.0;
    uint32_t seed = 12345u;
    for (uint32_t i = 0; i < 65u * 65u; ++i) {
        seed = seed * 1664525u + 1013904223u;
        const double x = (double)(i % 65u), y = (double)(i / 65u);
        g_rough[i] = (float)(400.0 + 80.0 * sin(x * 0.21) * cos(y * 0.17) + 3.0 * x +
                             (double)(seed >> 24) * 0.12);
    }
    t.heights_m = g_rough;
    ft_error err;
    CHECK(ft_pyramid_layout(&t, g_rough_pyr, sizeof g_rough_pyr, &err) == FT_OK);
    ft_pyramid_build(&t);
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2], aw = 0u, ah = 0u;
    ft_pgrid_residual_layout(&t, origin, &aw, &ah);
    CHECK(aw * ah <= 64u * 64u);
    if (aw * ah > 64u * 64u) return;
    ft_pgrid_residual_fill(&t, g_res_atlas, aw, ah);
    /* the atlas holds the residuals; a residual bounds |H - p| at every sample */
    for (uint32_t l = FT_PGRID_RES_L0; l < t.pyr.minmax_levels; ++l) {
        for (uint32_t j = 0; j < t.pyr.minmax[l].height; ++j) {
            for (uint32_t i = 0; i < t.pyr.minmax[l].width; ++i) {
                const double r = ft_pgrid_node_residual(&t, l, i, j);
                const float a = g_res_atlas[(origin[l][1] + j) * aw + origin[l][0] + i];
                CHECK((double)a >= r && (double)a <= r * (1.0 + 1e-6) + 1e-6);
            }
        }
    }
    double worst_ratio = 0.0, sum_bound = 0.0, sum_true = 0.0, exact_worst = 0.0;
    uint32_t exact_n = 0u;
    uint32_t under = 0u;
    for (int k = 0; k < 300; ++k) {
        seed = seed * 1664525u + 1013904223u;
        const double side = 0.25 * exp2((double)(k % 7)) * (1.0 + 0.5 * (double)(seed >> 28) / 16.0);
        const double x0 = 1.0 + (double)(seed % 1000u) / 1000.0 * (62.0 - side);
        const double y0 = 1.0 + (double)((seed >> 10) % 1000u) / 1000.0 * (62.0 - side);
        const double skew = (k % 3 == 0) ? 0.3 * side : 0.0;
        ft_pgrid_quad q = {{{x0, y0}, {x0 + side, y0 + skew}, {x0 + skew, y0 + side},
                            {x0 + side, y0 + side}}, {0.0, 0.0, 0.0, 0.0}};
        for (int c = 0; c < 4; ++c) {
            q.g[c][0] = fmin(q.g[c][0], 64.0);
            q.g[c][1] = fmin(q.g[c][1], 64.0);
            /* drawn heights: on the surface, or (a filtered level) a few m off */
            q.h_m[c] = bilinear(&t, q.g[c][0], q.g[c][1]) + ((k % 2) ? 0.0 : 4.0 * (c - 1.5));
        }
        const double b = ft_pgrid_quad_bound(&t, &q);
        const double e = quad_true_max(&t, &q, 48);
        int fits = 0;
        (void)ft_pgrid_quad_exact(&t, &q, &fits);
        if (fits) {
            /* exact: dense samples 1/400 of an edge apart reach it to within
             * what the surface changes over one step */
            ++exact_n;
            exact_worst = fmax(exact_worst, (b - quad_true_max(&t, &q, 400)) / (1.0 + e));
        }
        under += (b < e - 1e-9);
        sum_bound += b;
        sum_true += e;
        if (e > 0.0 && b / e > worst_ratio) worst_ratio = b / e;
    }
    printf("residual bound: 300 quads, %u under the true max; mean bound / mean true %.2f, "
           "worst ratio %.2f\n", under, sum_bound / sum_true, worst_ratio);
    printf("exact quads (fit %u x %u cells): %u, largest (bound - dense max) / (1 m + dense max) "
           "%.4f\n", FT_PGRID_EXACT_CELLS, FT_PGRID_EXACT_CELLS, exact_n, exact_worst);
    CHECK(under == 0u);
    CHECK(exact_n >= 100u);
    CHECK(exact_worst < EXACT_SLACK);
    /* a plane: nothing between the drawn surface and the truth */
    for (uint32_t i = 0; i < 65u * 65u; ++i) {
        g_rough[i] = (float)(100.0 + 2.0 * (double)(i % 65u) - 1.5 * (double)(i / 65u));
    }
    ft_pyramid_build(&t);
    ft_pgrid_quad q = {{{3.3, 4.1}, {20.7, 5.0}, {4.0, 18.2}, {21.9, 19.5}}, {0.0, 0.0, 0.0, 0.0}};
    for (int c = 0; c < 4; ++c) q.h_m[c] = bilinear(&t, q.g[c][0], q.g[c][1]);
    CHECK(ft_pgrid_quad_bound(&t, &q) < 1e-3);
}

/* The lower envelope's rule (src/lod/pgrid.h 3): drawn off the grid, at or
 * under the terrain's highest sample; left out over the grid above it. */
static void test_lower_envelope_rule(void)
{
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = t.height = 9u;
    t.cell_x_m = t.cell_y_m = 10.0;
    t.origin_world_x_m = 1000.0;
    t.origin_world_y_m = -500.0;
    float top = -1e9f;
    for (uint32_t i = 0; i < 81u; ++i) {
        g_heights[i] = (float)((i * 37u) % 23u);
        top = fmaxf(top, g_heights[i]);
    }
    t.heights_m = g_heights;
    t.min_height_m = 0.0f;
    t.max_height_m = top;
    ft_pgm_sampling s;
    memset(&s, 0, sizeof s);
    s.eye_m[0] = 1000.0 + 25.0;
    s.eye_m[1] = -500.0 + 35.0;
    s.eye_m[2] = (double)top + 0.01;
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 0);
    s.eye_m[2] = (double)top; /* level with the highest sample: may touch it */
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 1);
    s.eye_m[2] = (double)top - 1.0; /* above the cell under it, not above the top */
    CHECK(s.eye_m[2] > g_heights[3 * 9 + 2] && ft_pgrid_lower_envelope_needed(&t, &s) == 1);
    s.eye_m[2] = 1000.0;
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 0);
    s.eye_m[0] = 1000.0 - 0.5; /* west of the grid */
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 1);
    s.eye_m[0] = 1000.0 + 80.0; /* on the east edge */
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 0);
    s.eye_m[1] = -500.0 + 80.01; /* past the north edge */
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 1);
    s.eye_m[1] = -500.0 + 35.0;
    s.eye_m[2] = NAN;
    CHECK(ft_pgrid_lower_envelope_needed(&t, &s) == 1);
}

int main(void)
{
    test_error_terms();
    test_rows();
    test_columns();
    test_region();
    test_lower_envelope_rule();
    test_budget();
    test_residual_bound();
    return ft_test_result("test_pgrid");
}
