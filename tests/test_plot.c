/* test_plot.c - tools/plot.c (the bench plot): the Pareto front, the
 * rasteriser (lines, markers, text, clipping), axes and the PNG writer.
 *
 *   test_plot                      unit tests
 *   test_plot --check-bench CSV PNG FRAMES MEASURED ROW...
 *                                  checks the outputs of a `fixterrain bench`
 *                                  run (tests/bench.cmake): the CSV header, one
 *                                  row per ROW ("method:setting"), sane numbers,
 *                                  and that PNG is an 800x600 RGBA PNG with the
 *                                  plot drawn in it. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "gpu/font5x7.h"
#include "plot.h"
#include "test_util.h"

static const plot_rgba k_red = {255, 0, 0, 255};
static const plot_rgba k_white = {255, 255, 255, 255};

#define IMG_W 64u
#define IMG_H 48u
static uint8_t g_px[IMG_W * IMG_H * 4u];

static plot_image small_image(void)
{
    plot_image im = {g_px, IMG_W, IMG_H};
    plot_clear(&im, k_white);
    return im;
}

static int is_red(const plot_image *im, int x, int y)
{
    const uint8_t *p = im->rgba + ((size_t)y * im->w + (size_t)x) * 4u;
    return p[0] == 255 && p[1] == 0 && p[2] == 0;
}

static int count_red(const plot_image *im)
{
    int n = 0;
    for (uint32_t y = 0; y < im->h; ++y) {
        for (uint32_t x = 0; x < im->w; ++x) n += is_red(im, (int)x, (int)y);
    }
    return n;
}

/* ---- Pareto front -------------------------------------------------------------- */

static void test_pareto(void)
{
    /* time, error: 0 (1, 5) front; 1 (2, 3) front; 2 (3, 4) dominated by 1;
     * 3 (4, 1) front; 4 (5, 1) dominated by 3 (equal error, slower);
     * 5 (2, 3) equal to 1: kept once (lowest index); 6 NaN error: ignored;
     * 7 (0.5, 9) front (fastest); 8 (1, 6): same time as 0, worse: dominated;
     * 9 (6, 0.5) front (most accurate) */
    const double x[] = {1, 2, 3, 4, 5, 2, 3, 0.5, 1, 6};
    const double y[] = {5, 3, 4, 1, 1, 3, NAN, 9, 6, 0.5};
    size_t idx[10], work[10];
    size_t n = plot_pareto_front(x, y, 10, idx, work);
    const size_t want[] = {7, 0, 1, 3, 9};
    CHECK(n == 5);
    for (size_t i = 0; i < 5 && i < n; ++i) CHECK(idx[i] == want[i]);
    /* y strictly decreasing along the front, x increasing */
    for (size_t i = 1; i < n; ++i) {
        CHECK(x[idx[i]] > x[idx[i - 1]]);
        CHECK(y[idx[i]] < y[idx[i - 1]]);
    }
    /* single point, empty, all NaN */
    const double x1[] = {3}, y1[] = {2};
    CHECK(plot_pareto_front(x1, y1, 1, idx, work) == 1 && idx[0] == 0);
    CHECK(plot_pareto_front(x1, y1, 0, idx, work) == 0);
    const double xn[] = {NAN, 1}, yn[] = {1, INFINITY};
    CHECK(plot_pareto_front(xn, yn, 2, idx, work) == 0);
    /* the fastest point with the same time as another but a lower error wins */
    const double x2[] = {2, 2, 1}, y2[] = {3, 1, 4};
    n = plot_pareto_front(x2, y2, 3, idx, work);
    CHECK(n == 2 && idx[0] == 2 && idx[1] == 1);
}

/* ---- rasteriser --------------------------------------------------------------------- */

static void test_lines(void)
{
    plot_image im = small_image();
    plot_line(&im, 0, 0, 4, 2, k_red);
    /* Bresenham from (0,0) to (4,2) */
    const int want[5][2] = {{0, 0}, {1, 1}, {2, 1}, {3, 2}, {4, 2}};
    for (int i = 0; i < 5; ++i) CHECK(is_red(&im, want[i][0], want[i][1]));
    CHECK(count_red(&im) == 5);

    /* horizontal, vertical, steep: max(|dx|, |dy|) + 1 pixels, both ends */
    im = small_image();
    plot_line(&im, 10, 5, 20, 5, k_red);
    CHECK(count_red(&im) == 11);
    for (int x = 10; x <= 20; ++x) CHECK(is_red(&im, x, 5));
    im = small_image();
    plot_line(&im, 7, 30, 7, 3, k_red);
    CHECK(count_red(&im) == 28);
    im = small_image();
    plot_line(&im, 30, 40, 33, 10, k_red);
    CHECK(count_red(&im) == 31);
    CHECK(is_red(&im, 30, 40) && is_red(&im, 33, 10));
    /* one pixel per row of a steep line */
    for (int y = 10; y <= 40; ++y) {
        int n = 0;
        for (int x = 0; x < (int)IMG_W; ++x) n += is_red(&im, x, y);
        CHECK(n == 1);
    }
    /* a diagonal */
    im = small_image();
    plot_line(&im, 0, 0, 9, 9, k_red);
    CHECK(count_red(&im) == 10);
    for (int i = 0; i <= 9; ++i) CHECK(is_red(&im, i, i));

    /* clipping: only the inside part is drawn, nothing crashes */
    im = small_image();
    plot_line(&im, -100, 20, 200, 20, k_red);
    CHECK(count_red(&im) == (int)IMG_W);
    im = small_image();
    plot_line(&im, -50, -50, -10, -60, k_red);
    CHECK(count_red(&im) == 0);

    /* wide: 3 rows for a flat line */
    im = small_image();
    plot_line_wide(&im, 5, 10, 15, 10, 3, k_red);
    CHECK(count_red(&im) == 33);
    CHECK(is_red(&im, 5, 9) && is_red(&im, 5, 11) && !is_red(&im, 5, 12));

    /* dashed: 3 on, 2 off along 20 steps -> steps 0-2, 5-7, 10-12, 15-17 */
    im = small_image();
    plot_line_dashed(&im, 0, 0, 19, 0, 3, 2, k_red);
    CHECK(count_red(&im) == 12);
    CHECK(is_red(&im, 0, 0) && is_red(&im, 2, 0) && !is_red(&im, 3, 0) && !is_red(&im, 4, 0) &&
          is_red(&im, 5, 0));

    /* blend: 50% red over white */
    im = small_image();
    plot_pixel_blend(&im, 1, 1, (plot_rgba){255, 0, 0, 128});
    const uint8_t *p = im.rgba + (1 * IMG_W + 1) * 4u;
    CHECK(p[0] == 255 && p[1] == 127 && p[2] == 127 && p[3] == 255);
}

static void test_markers(void)
{
    plot_image im = small_image();
    plot_marker(&im, 20, 20, 2, PLOT_MARKER_SQUARE, k_red);
    CHECK(count_red(&im) == 25);
    CHECK(is_red(&im, 18, 18) && is_red(&im, 22, 22) && !is_red(&im, 23, 20));

    im = small_image();
    plot_marker(&im, 20, 20, 2, PLOT_MARKER_DIAMOND, k_red);
    CHECK(count_red(&im) == 13);
    CHECK(is_red(&im, 20, 18) && !is_red(&im, 19, 18));

    /* disc r = 3: dx^2 + dy^2 <= 12 -> 37 pixels */
    im = small_image();
    plot_marker(&im, 20, 20, 3, PLOT_MARKER_DISC, k_red);
    CHECK(count_red(&im) == 37);
    CHECK(is_red(&im, 23, 20) && is_red(&im, 22, 22) && !is_red(&im, 23, 22));

    /* ring r = 4: the disc minus the r = 2 disc (13 pixels of 61) */
    im = small_image();
    plot_marker(&im, 20, 20, 4, PLOT_MARKER_RING, k_red);
    CHECK(count_red(&im) == 61 - 13);
    CHECK(!is_red(&im, 20, 20) && is_red(&im, 24, 20));

    /* triangle r = 2, apex up: rows of 1, 1, 3, 3, 5 pixels */
    im = small_image();
    plot_marker(&im, 20, 20, 2, PLOT_MARKER_TRIANGLE, k_red);
    CHECK(count_red(&im) == 13);
    CHECK(is_red(&im, 20, 18) && !is_red(&im, 19, 18) && is_red(&im, 18, 22));

    /* clipped at the corner: only the inside quarter */
    im = small_image();
    plot_marker(&im, 0, 0, 2, PLOT_MARKER_SQUARE, k_red);
    CHECK(count_red(&im) == 9);
}

static void test_text(void)
{
    plot_image im = small_image();
    int w = plot_text(&im, 3, 4, "H1", 1, k_red);
    CHECK(w == 12);
    CHECK(plot_text_width("H1", 2) == 24);
    /* every pixel of the two glyphs, nothing else */
    int expect = 0;
    for (int g = 0; g < 2; ++g) {
        const uint8_t *rows = ft_font5x7_glyph("H1"[g]);
        for (int r = 0; r < 7; ++r) {
            for (int c = 0; c < 5; ++c) {
                int on = (rows[r] >> (4 - c)) & 1;
                expect += on;
                CHECK(is_red(&im, 3 + g * 6 + c, 4 + r) == on);
            }
        }
    }
    CHECK(count_red(&im) == expect);

    /* scale 2: each font pixel is a 2x2 block */
    im = small_image();
    (void)plot_text(&im, 0, 0, "1", 2, k_red);
    int ones = 0;
    const uint8_t *one = ft_font5x7_glyph('1');
    for (int r = 0; r < 7; ++r) {
        for (int c = 0; c < 5; ++c) ones += (one[r] >> (4 - c)) & 1;
    }
    CHECK(count_red(&im) == 4 * ones);

    /* rotated: font pixel (c, r) of the first glyph lands at (x + r, y - c) */
    im = small_image();
    (void)plot_text_up(&im, 10, 40, "H", 1, k_red);
    const uint8_t *h = ft_font5x7_glyph('H');
    int hn = 0;
    for (int r = 0; r < 7; ++r) {
        for (int c = 0; c < 5; ++c) {
            int on = (h[r] >> (4 - c)) & 1;
            hn += on;
            CHECK(is_red(&im, 10 + r, 40 - c) == on);
        }
    }
    CHECK(count_red(&im) == hn);
    /* a space draws nothing but advances */
    im = small_image();
    CHECK(plot_text(&im, 0, 0, "  ", 1, k_red) == 12 && count_red(&im) == 0);
}

static void test_axes(void)
{
    plot_axis a;
    plot_axis_fit(&a, 0.03, 2.5, 1);
    CHECK_NEAR(a.lo, 0.01, 1e-12);
    CHECK_NEAR(a.hi, 10.0, 1e-9);
    a.p0 = 500;
    a.p1 = 100;
    CHECK_NEAR(plot_axis_map(&a, 0.01), 500.0, 1e-9);
    CHECK_NEAR(plot_axis_map(&a, 10.0), 100.0, 1e-9);
    CHECK_NEAR(plot_axis_map(&a, 1.0), 500.0 - 400.0 * 2.0 / 3.0, 1e-9);
    double t[40];
    int n = plot_axis_ticks(&a, t, 40); /* 3 decades: 1, 2, 5 per decade, then 10 */
    CHECK(n == 10);
    CHECK_NEAR(t[0], 0.01, 1e-12);
    CHECK_NEAR(t[1], 0.02, 1e-12);
    CHECK_NEAR(t[n - 1], 10.0, 1e-9);

    plot_axis_fit(&a, 3.0, 87.0, 0); /* from 0, step 20 -> 0..100 */
    CHECK_NEAR(a.lo, 0.0, 0.0);
    CHECK_NEAR(a.hi, 100.0, 1e-9);
    a.p0 = 0;
    a.p1 = 200;
    CHECK_NEAR(plot_axis_map(&a, 25.0), 50.0, 1e-9);
    n = plot_axis_ticks(&a, t, 40);
    CHECK(n >= 4 && n <= 11);
    CHECK_NEAR(t[0], 0.0, 0.0);
    CHECK_NEAR(t[n - 1], 100.0, 1e-9);
    for (int i = 1; i < n; ++i) CHECK_NEAR(t[i] - t[i - 1], t[1] - t[0], 1e-9);

    char buf[16];
    plot_format_tick(0.5, buf, sizeof buf);
    CHECK(strcmp(buf, "0.5") == 0);
    plot_format_tick(0.1 + 0.2, buf, sizeof buf);
    CHECK(strcmp(buf, "0.3") == 0);
    plot_format_tick(1000.0, buf, sizeof buf);
    CHECK(strcmp(buf, "1000") == 0);
    plot_format_tick(0.0, buf, sizeof buf);
    CHECK(strcmp(buf, "0") == 0);
    plot_format_tick(1e-4, buf, sizeof buf);
    CHECK(strcmp(buf, "1e-04") == 0);
}

/* ---- PNG reader (just enough for our own files) ------------------------------------- */

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Reads an 8-bit RGBA, filter-0 PNG (what plot_write_png writes) into *rgba
 * (malloc'd). Checks the signature and every chunk CRC. 0 on success. */
static int read_png(const char *path, uint8_t **rgba, uint32_t *w, uint32_t *h)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) return -1;
    static uint8_t file[8u << 20];
    size_t len = fread(file, 1, sizeof file, f);
    fclose(f);
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (len < 8 || memcmp(file, sig, 8) != 0) return -2;
    static uint8_t idat[8u << 20];
    size_t idat_len = 0, pos = 8;
    int have_ihdr = 0, have_iend = 0;
    while (pos + 12 <= len) {
        uint32_t n = be32(file + pos);
        const uint8_t *type = file + pos + 4, *data = file + pos + 8;
        if (pos + 12 + n > len) return -3;
        uLong crc = crc32(crc32(0L, Z_NULL, 0), type, 4 + n);
        if (crc != be32(data + n)) return -4;
        if (memcmp(type, "IHDR", 4) == 0) {
            if (n != 13 || data[8] != 8 || data[9] != 6 || data[12] != 0) return -5;
            *w = be32(data);
            *h = be32(data + 4);
            have_ihdr = 1;
        } else if (memcmp(type, "IDAT", 4) == 0) {
            if (idat_len + n > sizeof idat) return -6;
            memcpy(idat + idat_len, data, n);
            idat_len += n;
        } else if (memcmp(type, "IEND", 4) == 0) {
            have_iend = 1;
            break;
        }
        pos += 12 + n;
    }
    if (!have_ihdr || !have_iend) return -7;
    size_t row = (size_t)*w * 4u + 1u;
    uLongf raw_len = (uLongf)(row * *h);
    uint8_t *raw = malloc(raw_len);
    *rgba = malloc((size_t)*w * *h * 4u);
    if (raw == NULL || *rgba == NULL || uncompress(raw, &raw_len, idat, idat_len) != Z_OK ||
        raw_len != row * *h) {
        free(raw);
        return -8;
    }
    for (uint32_t y = 0; y < *h; ++y) {
        if (raw[y * row] != 0) {
            free(raw);
            return -9;
        }
        memcpy(*rgba + (size_t)y * *w * 4u, raw + y * row + 1, (size_t)*w * 4u);
    }
    free(raw);
    return 0;
}

static void test_png(void)
{
    plot_image im = small_image();
    plot_line(&im, 0, 0, 63, 47, k_red);
    (void)plot_text(&im, 2, 30, "PNG", 1, (plot_rgba){0, 0, 255, 255});
    const char *path = FT_TEST_OUT_DIR "/test_plot.png";
    char err[200];
    REQUIRE(plot_write_png(path, &im, err, sizeof err) == 0);
    uint8_t *back = NULL;
    uint32_t w = 0, h = 0;
    int rc = read_png(path, &back, &w, &h);
    CHECK(rc == 0);
    if (rc == 0) {
        CHECK(w == IMG_W && h == IMG_H);
        CHECK(memcmp(back, im.rgba, (size_t)IMG_W * IMG_H * 4u) == 0);
    }
    free(back);
    CHECK(plot_write_png(FT_TEST_OUT_DIR "/no/such/dir/x.png", &im, err, sizeof err) == -1);
    CHECK(strstr(err, "cannot open") != NULL);
}

/* A chart: each series' points are drawn in its colour where the axes put
 * them, the fronts join them, the reference line is dashed grey. */
static void test_chart(void)
{
    static uint8_t buf[800u * 600u * 4u];
    plot_image im = {buf, 800, 600};
    const double x1[] = {10, 20, 40}, y1[] = {3, 0.5, 0.4};
    const double x2[] = {5, 15}, y2[] = {8, 0.9};
    const char *l1[] = {"a", "b", "c"};
    plot_chart ch;
    memset(&ch, 0, sizeof ch);
    ch.title = "test";
    ch.x_label = "ms";
    ch.y_label = "px";
    ch.y_log = 1;
    ch.y_floor = 1e-3;
    ch.series[0] = (plot_series){"one", {214, 39, 40, 255}, PLOT_MARKER_DISC, x1, y1, l1, 3};
    ch.series[1] = (plot_series){"two", {44, 160, 44, 255}, PLOT_MARKER_SQUARE, x2, y2, NULL, 2};
    ch.series_count = 2;
    ch.hline[0] = 1.0;
    ch.hline_count = 1;
    plot_axis xa, ya;
    REQUIRE(plot_chart_draw(&im, &ch, &xa, &ya) == 1);
    CHECK(xa.lo == 0.0 && xa.hi >= 40.0);
    CHECK(ya.lo <= 0.4 && ya.hi >= 8.0);
    for (int s = 0; s < 2; ++s) {
        const plot_series *se = &ch.series[s];
        for (size_t i = 0; i < se->n; ++i) {
            int px = (int)lround(plot_axis_map(&xa, se->x[i]));
            int py = (int)lround(plot_axis_map(&ya, se->y[i]));
            const uint8_t *p = buf + ((size_t)py * 800u + (size_t)px) * 4u;
            CHECK(p[0] == se->colour.r && p[1] == se->colour.g && p[2] == se->colour.b);
        }
    }
    /* all three points of series one are on its front (each is slower and more
     * accurate than the one before): the middle of the segment 0-1 is in its colour */
    int mx = (int)lround((plot_axis_map(&xa, 10) + plot_axis_map(&xa, 20)) / 2.0);
    int my = (int)lround((plot_axis_map(&ya, 3) + plot_axis_map(&ya, 0.5)) / 2.0);
    int found = 0;
    for (int dy = -2; dy <= 2; ++dy) {
        const uint8_t *p = buf + ((size_t)(my + dy) * 800u + (size_t)mx) * 4u;
        found |= p[0] == 214 && p[1] == 39 && p[2] == 40;
    }
    CHECK(found);
    /* no data: a blank chart and 0 */
    plot_chart empty;
    memset(&empty, 0, sizeof empty);
    CHECK(plot_chart_draw(&im, &empty, NULL, NULL) == 0);
}

/* ---- bench output checker ------------------------------------------------------------ */

#define CSV_COLS_MAX 40
#define CSV_ROWS_MAX 64

static int col(char *const head[], int n, const char *name)
{
    for (int i = 0; i < n; ++i) {
        if (strcmp(head[i], name) == 0) return i;
    }
    fprintf(stderr, "CSV: no column %s\n", name);
    ++g_ft_test_failures;
    return 0;
}

static double num(const char *s)
{
    char *end = NULL;
    double v = strtod(s, &end);
    return (end == s || *end != '\0') ? NAN : v;
}

static int check_bench(const char *csv, const char *png, int frames, int measured, int nrows,
                       char **rows)
{
    FILE *f = fopen(csv, "rb");
    REQUIRE(f != NULL);
    static char text[CSV_ROWS_MAX * 1024];
    const size_t len = fread(text, 1, sizeof text - 1u, f);
    fclose(f);
    REQUIRE(len < sizeof text - 1u);
    text[len] = '\0';
    /* RFC 4180 records: a quoted field may hold commas, quotes and line ends */
    static char lines[CSV_ROWS_MAX][1024];
    static char *cells[CSV_ROWS_MAX][CSV_COLS_MAX];
    int ncols[CSV_ROWS_MAX];
    int nl = 0;
    const char *at = text;
    while (nl < CSV_ROWS_MAX) {
        ncols[nl] = plot_csv_record(&at, lines[nl], sizeof lines[nl], cells[nl], CSV_COLS_MAX);
        CHECK(ncols[nl] >= 0);
        if (ncols[nl] <= 0) break;
        ++nl;
    }
    CHECK(*at == '\0');
    REQUIRE(nl >= 1);
    static const char *const want_head[] = {
        "method", "setting", "paths", "frames", "time_median_ms", "time_p99_ms", "time_max_ms",
        "ratio_to_brute", "select_median_ms", "err_max_px", "err_p999_px", "err_mean_px",
        "coverage_mismatch_px", "coverage_mismatch_mean_px", "nonfinite_px", "measured_frames",
        "triangles_mean", "budget_hits", "init_ms", "occlusion_mismatch_px",
        "occlusion_mismatch_mean_px", "occlusion_err_max_px", "raycast_fraction_mean",
        "raycast_fraction_max", "oracle_median_ms", "x_oracle", "tau_achieved_max_px",
        "bound_short_frames", "raycast_fraction_max_measured",
        "raycast_fraction_max_measured_view", "raycast_small_terrain_frames",
        "cache_coarser_frames", "cache_behind_frames", "err_max_fine_px", "bound_over_frames",
        "bound_none_frames", "err_max_vertical_px", "bound_over_vertical_frames"};
    const int nh = (int)(sizeof want_head / sizeof want_head[0]);
    CHECK(ncols[0] == nh);
    for (int i = 0; i < nh && i < ncols[0]; ++i) CHECK(strcmp(cells[0][i], want_head[i]) == 0);
    char *const *H = cells[0];
    const int c_method = col(H, nh, "method"), c_set = col(H, nh, "setting"),
              c_frames = col(H, nh, "frames"), c_med = col(H, nh, "time_median_ms"),
              c_p99 = col(H, nh, "time_p99_ms"), c_max = col(H, nh, "time_max_ms"),
              c_ratio = col(H, nh, "ratio_to_brute"), c_emax = col(H, nh, "err_max_px"),
              c_e999 = col(H, nh, "err_p999_px"), c_emean = col(H, nh, "err_mean_px"),
              c_cov = col(H, nh, "coverage_mismatch_px"), c_nf = col(H, nh, "nonfinite_px"),
              c_meas = col(H, nh, "measured_frames"), c_tri = col(H, nh, "triangles_mean"),
              c_occ = col(H, nh, "occlusion_mismatch_px"),
              c_occ_e = col(H, nh, "occlusion_err_max_px"),
              c_rc_mean = col(H, nh, "raycast_fraction_mean"),
              c_rc_max = col(H, nh, "raycast_fraction_max"),
              c_or = col(H, nh, "oracle_median_ms"), c_xo = col(H, nh, "x_oracle"),
              c_coarse = col(H, nh, "cache_coarser_frames"),
              c_fine = col(H, nh, "err_max_fine_px"),
              c_bover = col(H, nh, "bound_over_frames"),
              c_bnone = col(H, nh, "bound_none_frames"),
              c_vmax = col(H, nh, "err_max_vertical_px"),
              c_vover = col(H, nh, "bound_over_vertical_frames");
    CHECK(nl - 1 == nrows);
    for (int r = 0; r < nrows; ++r) {
        char want_method[64];
        const char *colon = strchr(rows[r], ':');
        REQUIRE(colon != NULL && (size_t)(colon - rows[r]) < sizeof want_method);
        memcpy(want_method, rows[r], (size_t)(colon - rows[r]));
        want_method[colon - rows[r]] = '\0';
        int found = -1;
        for (int l = 1; l < nl; ++l) {
            if (ncols[l] == nh && strcmp(cells[l][c_method], want_method) == 0 &&
                strcmp(cells[l][c_set], colon + 1) == 0) {
                found = l;
            }
        }
        if (found < 0) {
            fprintf(stderr, "CSV: no row %s\n", rows[r]);
            ++g_ft_test_failures;
            continue;
        }
        char *const *c = cells[found];
        const double med = num(c[c_med]), p99 = num(c[c_p99]), mx = num(c[c_max]);
        const double emax = num(c[c_emax]), e999 = num(c[c_e999]), emean = num(c[c_emean]);
        printf("%s: median %.2f ms, max error %.3f px, p99.9 %.3f px, mean %.4f px, %s "
               "triangles\n",
               rows[r], med, emax, e999, emean, c[c_tri]);
        CHECK(num(c[c_frames]) == frames);
        CHECK(num(c[c_meas]) == measured);
        CHECK(med > 0.0 && med <= p99 && p99 <= mx && mx < 60000.0);
        CHECK(emax >= 0.0 && emax < 100.0 && e999 >= 0.0 && e999 <= emax);
        CHECK(emean >= 0.0 && emean <= emax);
        CHECK(num(c[c_cov]) >= 0.0 && num(c[c_nf]) == 0.0);
        /* occlusion errors are inside the max */
        CHECK(num(c[c_occ]) >= 0.0 && num(c[c_occ_e]) >= 0.0 && num(c[c_occ_e]) <= emax);
        CHECK(num(c[c_tri]) >= 1.0);
        /* ray-cast pixels over terrain pixels (above 1 when the silhouette's
         * one-pixel widening adds sky pixels); only pgrid ray casts */
        CHECK(num(c[c_rc_mean]) >= 0.0 && num(c[c_rc_mean]) <= num(c[c_rc_max]));
        if (strcmp(want_method, "pgrid") != 0) CHECK(num(c[c_rc_max]) == 0.0);
        /* only a method reading the clipmap cache draws from coarser data;
         * the max without such frames is inside the max */
        CHECK(num(c[c_coarse]) >= 0.0 && num(c[c_coarse]) <= frames);
        if (strcmp(want_method, "clipmap") != 0) CHECK(num(c[c_coarse]) == 0.0);
        CHECK(num(c[c_fine]) >= 0.0 && num(c[c_fine]) <= emax);
        if (num(c[c_coarse]) == 0.0) CHECK(num(c[c_fine]) == emax);
        /* measured frames over a reported bound, or without one: brute
         * force reports none; a bintree row keeps its bound */
        CHECK(num(c[c_bover]) >= 0.0 && num(c[c_bover]) <= measured);
        CHECK(num(c[c_bnone]) >= 0.0 && num(c[c_bnone]) <= measured);
        if (strcmp(want_method, "brute") == 0) {
            CHECK(num(c[c_bover]) == 0.0 && num(c[c_bnone]) == 0.0);
        }
        if (strcmp(want_method, "bintree") == 0) CHECK(num(c[c_bover]) == 0.0);
        /* the vertical error alone is inside the max, and a frame over the
         * bound by it is over the bound */
        CHECK(num(c[c_vmax]) >= 0.0 && num(c[c_vmax]) <= emax);
        CHECK(num(c[c_vover]) >= 0.0 && num(c[c_vover]) <= num(c[c_bover]));
        if (strcmp(want_method, "brute") == 0) CHECK_NEAR(num(c[c_ratio]), 1.0, 1e-9);
        else CHECK(num(c[c_ratio]) > 0.0);
        /* the oracle (bintree rows only): its median frame time and the row's
         * median over it; other methods leave both empty */
        if (strcmp(want_method, "bintree") == 0) {
            const double om = num(c[c_or]), xo = num(c[c_xo]);
            printf("  oracle %.2f ms, x_oracle %.3f\n", om, xo);
            CHECK(om > 0.0 && om < 60000.0);
            CHECK(xo > 0.0);
            CHECK_NEAR(xo, med / om, 0.01 * xo); /* both printed rounded */
        } else {
            CHECK(c[c_or][0] == '\0' && c[c_xo][0] == '\0');
        }
    }

    uint8_t *rgba = NULL;
    uint32_t w = 0, h = 0;
    int rc = read_png(png, &rgba, &w, &h);
    CHECK(rc == 0);
    if (rc == 0) {
        CHECK(w == 800 && h == 600);
        size_t ink = 0, coloured = 0;
        for (size_t i = 0; i < (size_t)w * h; ++i) {
            const uint8_t *p = rgba + i * 4u;
            ink += !(p[0] == 255 && p[1] == 255 && p[2] == 255);
            coloured += (p[0] == 214 && p[1] == 39 && p[2] == 40) ||
                        (p[0] == 31 && p[1] == 119 && p[2] == 180);
        }
        printf("plot: %zu non-white pixels, %zu in the first two series' colours\n", ink,
               coloured);
        CHECK(ink > 5000);     /* axes, ticks, labels, legend */
        CHECK(coloured > 100); /* markers and fronts */
    }
    free(rgba);
    return ft_test_result("test_plot --check-bench");
}

/* CSV fields: written quoted when they must be, read back unchanged */
static void test_csv(void)
{
    static const char *const field[] = {"pgrid", "grid=200x800 gamma_px=1", "a,b", "say \"hi\"",
                                        "two\nlines", "cr\r", "", "valley+q\"x.wp"};
    const int n = (int)(sizeof field / sizeof field[0]);
    char line[512] = "", one[128];
    for (int i = 0; i < n; ++i) {
        REQUIRE(plot_csv_field(one, sizeof one, field[i]));
        if (i) strcat(line, ",");
        strcat(line, one);
    }
    strcat(line, "\r\nnext,row\n");
    CHECK(plot_csv_field(one, sizeof one, "a,b") && strcmp(one, "\"a,b\"") == 0);
    CHECK(plot_csv_field(one, sizeof one, "say \"hi\"") && strcmp(one, "\"say \"\"hi\"\"\"") == 0);
    CHECK(plot_csv_field(one, sizeof one, "plain") && strcmp(one, "plain") == 0);
    CHECK(!plot_csv_field(one, 4, "a,b")); /* "a,b" needs 6 bytes */
    char buf[512];
    char *cells[16];
    const char *at = line;
    CHECK(plot_csv_record(&at, buf, sizeof buf, cells, 16) == n);
    for (int i = 0; i < n; ++i) CHECK(strcmp(cells[i], field[i]) == 0);
    CHECK(plot_csv_record(&at, buf, sizeof buf, cells, 16) == 2);
    CHECK(strcmp(cells[0], "next") == 0 && strcmp(cells[1], "row") == 0);
    CHECK(plot_csv_record(&at, buf, sizeof buf, cells, 16) == 0);
    static const char *const bad[] = {"\"open,1\n", "\"a\"b,1\n", "a\"b,1\n"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        at = bad[i];
        CHECK(plot_csv_record(&at, buf, sizeof buf, cells, 16) == -1);
    }
    at = "a,b,c\n";
    CHECK(plot_csv_record(&at, buf, sizeof buf, cells, 2) == -1); /* more fields than room */
}

int main(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "--check-bench") == 0) {
        if (argc < 7) {
            fprintf(stderr, "usage: %s --check-bench CSV PNG FRAMES MEASURED ROW...\n", argv[0]);
            return 2;
        }
        return check_bench(argv[2], argv[3], atoi(argv[4]), atoi(argv[5]), argc - 6, argv + 6);
    }
    test_pareto();
    test_lines();
    test_markers();
    test_text();
    test_axes();
    test_png();
    test_chart();
    test_csv();
    return ft_test_result("test_plot");
}
