/* test_pyramid.c - src/terrain/pyramid.c against the footprint rules in terrain.h.
 *
 * min/max: every texel of every level is recomputed by brute force from the
 * samples of its documented footprint, grid x in [i*2^L, min((i+1)*2^L,
 * w-1)] (same in y), and must match exactly. avg: each level is recomputed
 * from the level below with explicitly clamped indices (the rule is defined
 * level by level) and must match exactly; for power-of-two sides, where
 * clamping never duplicates a texel, the top texel must be the plain mean.
 * Also checks level counts, layout order and contiguity, and error paths. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "terrain/pyramid.h"
#include "test_util.h"

static uint32_t g_rng = 12345u;
static float rnd(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (float)((g_rng >> 8) % 100000u) * 0.05f - 1000.0f;
}

static uint32_t expect_levels(uint32_t w, uint32_t h)
{
    uint32_t n = 1u;
    while (w > 1u || h > 1u) {
        w = (w + 1u) / 2u;
        h = (h + 1u) / 2u;
        ++n;
    }
    return n;
}

static uint32_t umin(uint32_t a, uint32_t b)
{
    return a < b ? a : b;
}

/* ft_pyramid_check: a fresh build passes; one node changed at each level
 * (min raised, max lowered, min above max, an avg outside its children) is
 * caught, and the message names that level and node. */
static void check_consistency(ft_terrain *t)
{
    ft_error err;
    CHECK(ft_pyramid_check(t, "p", &err) == FT_OK);
    char want[96];
    for (uint32_t l = 0; l < t->pyr.minmax_levels; ++l) {
        ft_pyramid_level *lv = &t->pyr.minmax[l];
        uint32_t i = lv->width / 2u, j = lv->height - 1u;
        size_t k = (size_t)j * lv->width + i;
        (void)snprintf(want, sizeof want, "min/max pyramid level %u node (x %u, y %u)", l, i, j);
        for (int mode = 0; mode < 3; ++mode) {
            float keep_min = lv->min_m[k], keep_max = lv->max_m[k];
            if (mode == 0) lv->min_m[k] = keep_min + 0.5f;
            if (mode == 1) lv->max_m[k] = keep_max - 0.5f;
            if (mode == 2) {
                lv->min_m[k] = keep_max;
                lv->max_m[k] = keep_min;
            }
            int hit = ft_pyramid_check(t, "p", &err) == FT_ERR_FORMAT &&
                      strstr(err.text, want) != NULL;
            /* a level 0 node whose cell is flat has min == max: swapping is a no-op */
            if (!(mode == 2 && keep_min == keep_max)) {
                if (!hit) fprintf(stderr, "mode %d: wanted \"%s\", got \"%s\"\n", mode, want, err.text);
                CHECK(hit);
            }
            lv->min_m[k] = keep_min;
            lv->max_m[k] = keep_max;
        }
    }
    for (uint32_t l = 1; l < t->pyr.avg_levels; ++l) {
        ft_pyramid_level *lv = &t->pyr.avg[l];
        size_t k = (size_t)(lv->height - 1u) * lv->width;
        float keep = lv->avg_m[k];
        lv->avg_m[k] = 1.0e6f;
        (void)snprintf(want, sizeof want, "avg pyramid level %u node (x 0, y %u)", l,
                       lv->height - 1u);
        CHECK(ft_pyramid_check(t, "p", &err) == FT_ERR_FORMAT && strstr(err.text, want) != NULL);
        lv->avg_m[k] = keep;
    }
    CHECK(ft_pyramid_check(t, "p", &err) == FT_OK);
}

static void check_grid(uint32_t w, uint32_t h, int pattern)
{
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = w;
    t.height = h;
    t.heights_m = (float *)malloc((size_t)w * h * sizeof(float));
    REQUIRE(t.heights_m != NULL);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            float v;
            switch (pattern) {
            case 0: v = rnd(); break;
            case 1: v = (float)(x * 7u + y * 13u); break;            /* ramp */
            case 2: v = ((x ^ y) & 1u) ? 100.0f : -50.0f; break;      /* checker */
            default: v = (x == w / 2u && y == h / 3u) ? 999.0f : 1.0f; /* spike */
            }
            t.heights_m[(size_t)y * w + x] = v;
        }
    }
    uint32_t al = ft_pyramid_avg_levels(w, h);
    uint32_t ml = ft_pyramid_minmax_levels(w, h);
    CHECK(al == expect_levels(w, h));
    CHECK(ml == expect_levels(w - 1u, h - 1u));
    size_t bytes = ft_pyramid_bytes(w, h);
    /* expected byte count from the documented sizes */
    size_t floats = 0;
    {
        uint32_t aw = w, ah = h;
        for (uint32_t l = 1; l < al; ++l) {
            aw = (aw + 1u) / 2u;
            ah = (ah + 1u) / 2u;
            floats += (size_t)aw * ah;
        }
        aw = w - 1u;
        ah = h - 1u;
        for (uint32_t l = 0; l < ml; ++l) {
            floats += 2u * (size_t)aw * ah;
            aw = (aw + 1u) / 2u;
            ah = (ah + 1u) / 2u;
        }
    }
    CHECK(bytes == floats * sizeof(float));
    /* Poisoned storage with a guard float past the end. */
    float *store = (float *)malloc(bytes + 64u);
    REQUIRE(store != NULL);
    for (size_t k = 0; k < bytes / sizeof(float) + 16u; ++k) {
        store[k] = -12345.0f;
    }
    ft_error err;
    memset(&err, 0, sizeof err);
    CHECK(ft_pyramid_layout(&t, store, bytes - 4u, &err) == FT_ERR_BUDGET);
    REQUIRE(ft_pyramid_layout(&t, store, bytes, &err) == FT_OK);
    CHECK(t.pyr.avg_levels == al);
    CHECK(t.pyr.minmax_levels == ml);
    /* Documented order, contiguous, no padding. */
    {
        const float *cur = store;
        for (uint32_t l = 1; l < al; ++l) {
            CHECK(t.pyr.avg[l].avg_m == cur);
            cur += (size_t)t.pyr.avg[l].width * t.pyr.avg[l].height;
        }
        for (uint32_t l = 0; l < ml; ++l) {
            size_t n = (size_t)t.pyr.minmax[l].width * t.pyr.minmax[l].height;
            CHECK(t.pyr.minmax[l].min_m == cur);
            CHECK(t.pyr.minmax[l].max_m == cur + n);
            cur += 2u * n;
        }
        CHECK(cur == store + bytes / sizeof(float));
    }
    ft_pyramid_build(&t);
    CHECK(store[bytes / sizeof(float)] == -12345.0f); /* nothing written past the end */

    /* avg level 0 and sizes */
    CHECK(t.pyr.avg[0].width == w && t.pyr.avg[0].height == h);
    CHECK(t.pyr.avg[al - 1u].width == 1u && t.pyr.avg[al - 1u].height == 1u);
    CHECK(t.pyr.minmax[ml - 1u].width == 1u && t.pyr.minmax[ml - 1u].height == 1u);
    for (uint32_t l = 1; l < al; ++l) {
        const ft_pyramid_level *s = &t.pyr.avg[l - 1u];
        const float *src = (l == 1u) ? t.heights_m : s->avg_m;
        const ft_pyramid_level *d = &t.pyr.avg[l];
        CHECK(d->width == (s->width + 1u) / 2u && d->height == (s->height + 1u) / 2u);
        int bad = 0;
        for (uint32_t j = 0; j < d->height; ++j) {
            for (uint32_t i = 0; i < d->width; ++i) {
                double sum = 0.0;
                /* sum in the same order as the rule reads: (x0,y0)+(x1,y0), (x0,y1)+(x1,y1) */
                uint32_t xa = umin(2u * i, s->width - 1u), xb = umin(2u * i + 1u, s->width - 1u);
                uint32_t ya = umin(2u * j, s->height - 1u), yb = umin(2u * j + 1u, s->height - 1u);
                sum = ((double)src[(size_t)ya * s->width + xa] + (double)src[(size_t)ya * s->width + xb]) +
                      ((double)src[(size_t)yb * s->width + xa] + (double)src[(size_t)yb * s->width + xb]);
                float want = (float)(sum * 0.25);
                if (d->avg_m[(size_t)j * d->width + i] != want) {
                    ++bad;
                }
            }
        }
        if (bad) {
            fprintf(stderr, "%ux%u avg level %u: %d texels differ\n", w, h, l, bad);
        }
        CHECK(bad == 0);
    }
    /* Power-of-two sides: clamping never duplicates, top = mean of all. */
    if ((w & (w - 1u)) == 0u && (h & (h - 1u)) == 0u) {
        double sum = 0.0;
        for (size_t k = 0; k < (size_t)w * h; ++k) sum += t.heights_m[k];
        CHECK_NEAR(t.pyr.avg[al - 1u].avg_m[0], sum / ((double)w * h), 1e-3);
    }
    /* min/max: brute force over the footprint of every texel. */
    float gmin = t.heights_m[0], gmax = t.heights_m[0];
    for (size_t k = 0; k < (size_t)w * h; ++k) {
        gmin = t.heights_m[k] < gmin ? t.heights_m[k] : gmin;
        gmax = t.heights_m[k] > gmax ? t.heights_m[k] : gmax;
    }
    for (uint32_t l = 0; l < ml; ++l) {
        const ft_pyramid_level *lv = &t.pyr.minmax[l];
        uint32_t step = 1u << l;
        int bad = 0;
        for (uint32_t j = 0; j < lv->height; ++j) {
            for (uint32_t i = 0; i < lv->width; ++i) {
                uint32_t x0 = i * step, x1 = umin((i + 1u) * step, w - 1u);
                uint32_t y0 = j * step, y1 = umin((j + 1u) * step, h - 1u);
                float mn = INFINITY, mx = -INFINITY;
                for (uint32_t y = y0; y <= y1; ++y) {
                    for (uint32_t x = x0; x <= x1; ++x) {
                        float v = t.heights_m[(size_t)y * w + x];
                        mn = v < mn ? v : mn;
                        mx = v > mx ? v : mx;
                    }
                }
                if (lv->min_m[(size_t)j * lv->width + i] != mn ||
                    lv->max_m[(size_t)j * lv->width + i] != mx) {
                    ++bad;
                }
            }
        }
        if (bad) {
            fprintf(stderr, "%ux%u minmax level %u: %d texels differ\n", w, h, l, bad);
        }
        CHECK(bad == 0);
    }
    CHECK(t.min_height_m == gmin);
    CHECK(t.max_height_m == gmax);
    check_consistency(&t);
    free(store);
    free(t.heights_m);
}

int main(void)
{
    /* odd, even, power-of-two, 2^k+1, non-square, 2xN, Nx2, 2x2 */
    static const uint32_t sizes[][2] = {
        {2, 2},  {3, 3},   {4, 4},  {5, 5},   {8, 8},  {9, 9},  {17, 17}, {16, 16},
        {33, 7}, {7, 33},  {2, 9},  {9, 2},   {2, 64}, {65, 2}, {3, 2},   {100, 37},
        {64, 32}, {129, 129}, {31, 60}, {2, 3},
    };
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
        for (int pattern = 0; pattern < 4; ++pattern) {
            check_grid(sizes[s][0], sizes[s][1], pattern);
        }
    }
    /* random sizes */
    for (int k = 0; k < 20; ++k) {
        g_rng = g_rng * 1664525u + 1013904223u;
        uint32_t w = 2u + (g_rng >> 10) % 90u;
        g_rng = g_rng * 1664525u + 1013904223u;
        uint32_t h = 2u + (g_rng >> 10) % 90u;
        check_grid(w, h, 0);
    }
    /* level counts at the limits */
    CHECK(ft_pyramid_avg_levels(16385, 16385) == 16u);
    CHECK(ft_pyramid_minmax_levels(16385, 16385) == 15u);
    CHECK(ft_pyramid_avg_levels(1025, 1025) == 12u);
    CHECK(ft_pyramid_minmax_levels(1025, 1025) == 11u);
    CHECK(ft_pyramid_minmax_levels(2, 2) == 1u);
    CHECK(ft_pyramid_avg_levels(16385, 2) == 16u);
    CHECK(ft_pyramid_bytes(16385, 16385) > 0u);
    CHECK(ft_pyramid_bytes(1, 5) == 0u);
    CHECK(ft_pyramid_bytes(16386, 5) == 0u);
    CHECK(ft_pyramid_avg_levels(0, 0) == 0u);
    {
        ft_terrain t;
        ft_error err;
        float store[16];
        memset(&t, 0, sizeof t);
        t.width = 1;
        t.height = 4;
        CHECK(ft_pyramid_layout(&t, store, sizeof store, &err) == FT_ERR_ARG);
        CHECK(strstr(err.text, "1x4") != NULL);
        t.width = 3;
        t.height = 3;
        CHECK(ft_pyramid_layout(&t, NULL, 0, &err) == FT_ERR_BUDGET);
    }
    return ft_test_result("test_pyramid");
}
