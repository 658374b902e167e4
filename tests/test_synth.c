/* test_synth.c - the embedded synthetic terrain.
 *
 * Determinism (two runs bit-identical, golden crc32 of a 129x129 seed-1 run),
 * range 0..relief with the peak at relief, a lake of exactly 0 m, not flat
 * (real slopes and several distinct ridges), different seeds differ, probe
 * validation, and the time of the default 1025x1025 run (printed). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <zlib.h>

#include "terrain/synth_terrain.h"
#include "test_util.h"

/* crc32 of the 129x129 seed-1 heights as little-endian float32. Changing the
 * generator on purpose means updating this number (the test prints it). */
#define GOLDEN_CRC_129 0x6792c3dcu

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static ft_synth_desc default_desc(uint32_t side)
{
    ft_synth_desc d;
    memset(&d, 0, sizeof d);
    d.side = side;
    d.spacing_m = 30.0;
    d.relief_m = 2400.0;
    d.seed = 1;
    d.octaves = 9;
    d.anchor_lat_deg = 46.5;
    d.anchor_lon_deg = 8.0;
    return d;
}

static float *run(const ft_synth_desc *d, ft_terrain *t)
{
    ft_error err;
    memset(t, 0, sizeof *t);
    ft_status st = ft_synth_probe(d, t, &err);
    if (st != FT_OK) fprintf(stderr, "%s\n", err.text);
    REQUIRE(st == FT_OK);
    t->heights_m = (float *)malloc((size_t)t->width * t->height * sizeof(float));
    REQUIRE(t->heights_m != NULL);
    ft_synth_generate(d, t);
    return t->heights_m;
}

static uint32_t crc_heights(const float *h, size_t n)
{
    uLong c = crc32(0L, Z_NULL, 0);
    for (size_t k = 0; k < n; ++k) {
        uint32_t u;
        memcpy(&u, &h[k], 4);
        uint8_t b[4] = {(uint8_t)u, (uint8_t)(u >> 8), (uint8_t)(u >> 16), (uint8_t)(u >> 24)};
        c = crc32(c, b, 4);
    }
    return (uint32_t)c;
}

static void check_shape(const ft_terrain *t, double relief)
{
    uint32_t n = t->width;
    size_t count = (size_t)n * n, zeros = 0;
    float lo = INFINITY, hi = -INFINITY;
    double slope_sum = 0.0;
    for (size_t k = 0; k < count; ++k) {
        float v = t->heights_m[k];
        CHECK(v >= 0.0f && v <= (float)relief);
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
        zeros += (v == 0.0f);
    }
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x + 1u < n; ++x)
            slope_sum += fabs(t->heights_m[y * n + x + 1u] - t->heights_m[y * n + x]);
    double mean_step = slope_sum / ((double)n * (n - 1u));
    CHECK(lo == 0.0f);
    CHECK(t->min_height_m == lo && t->max_height_m == hi);
    CHECK(hi > 0.95f * (float)relief); /* peaks near the relief */
    /* a lake: a connected-looking area of exact zeros, not a single pixel */
    double lake_frac = (double)zeros / (double)count;
    CHECK(lake_frac > 0.002 && lake_frac < 0.15);
    /* mean of the map in the middle: mountains AND valleys */
    double mean = 0.0;
    for (size_t k = 0; k < count; ++k) mean += t->heights_m[k];
    mean /= (double)count;
    CHECK(mean > 0.15 * relief && mean < 0.7 * relief);
    printf("  %ux%u: %.1f..%.1f m, mean %.0f m, lake %.2f%% of samples, mean |dh| per sample %.2f m\n",
           n, n, (double)lo, (double)hi, mean, 100.0 * lake_frac, mean_step);
    CHECK(mean_step > 1.0); /* not flat */
}

int main(void)
{
    ft_synth_desc d = default_desc(129);
    ft_terrain a, b;
    run(&d, &a);
    run(&d, &b);
    CHECK(memcmp(a.heights_m, b.heights_m, 129u * 129u * sizeof(float)) == 0);
    uint32_t crc = crc_heights(a.heights_m, 129u * 129u);
    printf("  golden crc32 129x129 seed 1: 0x%08x\n", crc);
    CHECK(crc == GOLDEN_CRC_129);
    check_shape(&a, d.relief_m);
    CHECK(a.unit == FT_UNIT_METRE && a.cell_x_m == 30.0 && strcmp(a.crs, "local") == 0);
    CHECK(a.anchor_lat_deg == 46.5 && a.anchor_lon_deg == 8.0);

    /* another seed gives another terrain (run() allocates anew: free the first b) */
    free(b.heights_m);
    d.seed = 2;
    run(&d, &b);
    CHECK(memcmp(a.heights_m, b.heights_m, 129u * 129u * sizeof(float)) != 0);
    check_shape(&b, d.relief_m);
    free(a.heights_m);
    free(b.heights_m);

    /* probe rejects bad descs */
    {
        ft_terrain t;
        ft_error err;
        ft_synth_desc bad = default_desc(1);
        CHECK(ft_synth_probe(&bad, &t, &err) == FT_ERR_CONFIG && strstr(err.text, "side 1"));
        bad = default_desc(129);
        bad.octaves = 0;
        CHECK(ft_synth_probe(&bad, &t, &err) == FT_ERR_CONFIG && strstr(err.text, "octaves 0"));
        bad = default_desc(129);
        bad.relief_m = NAN;
        CHECK(ft_synth_probe(&bad, &t, &err) == FT_ERR_CONFIG && strstr(err.text, "relief"));
        bad = default_desc(129);
        bad.spacing_m = -30.0;
        CHECK(ft_synth_probe(&bad, &t, &err) == FT_ERR_CONFIG && strstr(err.text, "spacing"));
        bad = default_desc(129);
        bad.anchor_lat_deg = 95.0;
        CHECK(ft_synth_probe(&bad, &t, &err) == FT_ERR_CONFIG && strstr(err.text, "anchor"));
    }

    /* the default scene terrain: 1025x1025, timed */
    {
        ft_synth_desc big = default_desc(1025);
        ft_terrain t;
        double t0 = now_s();
        run(&big, &t);
        double t1 = now_s();
        printf("  1025x1025 generate: %.1f ms\n", (t1 - t0) * 1e3);
        check_shape(&t, big.relief_m);
        free(t.heights_m);
    }
    return ft_test_result("test_synth");
}
