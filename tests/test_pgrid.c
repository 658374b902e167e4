/* test_pgrid.c - the CPU pieces of method pgrid (src/pgrid.h): delta, rho,
 * normalised error, error codes, row placement closed forms, region
 * min/max on a known pyramid, the budget threshold and the dilated
 * histogram. */
#include <math.h>
#include <string.h>

#include "pgrid.h"
#include "pyramid.h"
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

int main(void)
{
    test_error_terms();
    test_rows();
    test_region();
    test_budget();
    return ft_test_result("test_pgrid");
}
