/* pyramid.c - avg/min/max pyramids (footprint rules in terrain.h).
 *
 * Every level is computed from the level below with a 2x2 clamped gather,
 * so the whole build is O(width*height) with no recursion and no scratch. */
#include "terrain/pyramid.h"

#include <stdint.h>

/* Next level's side: ceil(n / 2), and a side of 1 stays 1. */
static uint32_t half_up(uint32_t n)
{
    return (n + 1u) / 2u;
}

static int dims_ok(uint32_t width, uint32_t height)
{
    return width >= FT_GRID_SIDE_MIN && height >= FT_GRID_SIDE_MIN && width <= FT_GRID_SIDE_MAX &&
           height <= FT_GRID_SIDE_MAX;
}

/* Number of levels from w x h down to 1x1 inclusive (both dims must reach 1).
 * Bounded: a side <= 2^15 halves to 1 in at most 16 steps. */
static uint32_t level_count(uint32_t w, uint32_t h)
{
    uint32_t n = 1u;
    for (uint32_t guard = 0; guard < 40u && (w > 1u || h > 1u); ++guard) {
        w = half_up(w);
        h = half_up(h);
        ++n;
    }
    return n;
}

uint32_t ft_pyramid_avg_levels(uint32_t width, uint32_t height)
{
    if (!dims_ok(width, height)) {
        return 0u;
    }
    return level_count(width, height);
}

uint32_t ft_pyramid_minmax_levels(uint32_t width, uint32_t height)
{
    if (!dims_ok(width, height)) {
        return 0u;
    }
    return level_count(width - 1u, height - 1u);
}

/* Float count of all pyramid arrays (avg levels >= 1, min and max levels).
 * In uint64 so it cannot wrap even on a 32-bit size_t. */
static uint64_t pyramid_floats(uint32_t width, uint32_t height)
{
    uint64_t n = 0u;
    uint32_t w = width, h = height;
    uint32_t levels = ft_pyramid_avg_levels(width, height);
    for (uint32_t l = 1u; l < levels; ++l) {
        w = half_up(w);
        h = half_up(h);
        n += (uint64_t)w * h;
    }
    w = width - 1u;
    h = height - 1u;
    levels = ft_pyramid_minmax_levels(width, height);
    for (uint32_t l = 0u; l < levels; ++l) {
        n += 2u * (uint64_t)w * h;
        w = half_up(w);
        h = half_up(h);
    }
    return n;
}

size_t ft_pyramid_bytes(uint32_t width, uint32_t height)
{
    if (!dims_ok(width, height)) {
        return 0u;
    }
    uint64_t bytes = pyramid_floats(width, height) * (uint64_t)sizeof(float);
    if (bytes > (uint64_t)SIZE_MAX) {
        return 0u; /* cannot be addressed on this target; layout will refuse */
    }
    return (size_t)bytes;
}

ft_status ft_pyramid_layout(ft_terrain *t, void *storage, size_t storage_bytes, ft_error *err)
{
    if (t == NULL) {
        return ft_fail(err, FT_ERR_ARG, "pyramid layout: terrain is NULL");
    }
    if (!dims_ok(t->width, t->height)) {
        return ft_fail(err, FT_ERR_ARG, "pyramid layout: grid %ux%u outside %u..%u per side",
                       t->width, t->height, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    size_t need = ft_pyramid_bytes(t->width, t->height);
    if (need == 0u) {
        return ft_fail(err, FT_ERR_BUDGET, "pyramid layout: %ux%u pyramids exceed the address space",
                       t->width, t->height);
    }
    if (storage == NULL || storage_bytes < need) {
        return ft_fail(err, FT_ERR_BUDGET,
                       "pyramid layout: %ux%u grid needs %zu bytes of pyramid storage, got %zu",
                       t->width, t->height, need, storage == NULL ? (size_t)0 : storage_bytes);
    }
    if (((uintptr_t)storage % sizeof(float)) != 0u) {
        return ft_fail(err, FT_ERR_ARG, "pyramid layout: storage is not float-aligned");
    }
    ft_pyramid *p = &t->pyr;
    float *cur = (float *)storage;
    uint32_t w = t->width, h = t->height;

    p->avg_levels = ft_pyramid_avg_levels(t->width, t->height);
    p->minmax_levels = ft_pyramid_minmax_levels(t->width, t->height);
    for (uint32_t l = 0u; l < FT_PYRAMID_LEVELS_MAX; ++l) {
        p->avg[l] = (ft_pyramid_level){0u, 0u, NULL, NULL, NULL};
        p->minmax[l] = (ft_pyramid_level){0u, 0u, NULL, NULL, NULL};
    }
    /* Level 0 of avg is the heights themselves (no copy). */
    p->avg[0].width = w;
    p->avg[0].height = h;
    p->avg[0].avg_m = t->heights_m;
    for (uint32_t l = 1u; l < p->avg_levels; ++l) {
        w = half_up(w);
        h = half_up(h);
        p->avg[l].width = w;
        p->avg[l].height = h;
        p->avg[l].avg_m = cur;
        cur += (size_t)w * h;
    }
    w = t->width - 1u;
    h = t->height - 1u;
    for (uint32_t l = 0u; l < p->minmax_levels; ++l) {
        size_t n = (size_t)w * h;
        p->minmax[l].width = w;
        p->minmax[l].height = h;
        p->minmax[l].min_m = cur;
        p->minmax[l].max_m = cur + n;
        cur += 2u * n;
        w = half_up(w);
        h = half_up(h);
    }
    return FT_OK;
}

static float min4(float a, float b, float c, float d)
{
    float m = a < b ? a : b;
    float n = c < d ? c : d;
    return m < n ? m : n;
}

static float max4(float a, float b, float c, float d)
{
    float m = a > b ? a : b;
    float n = c > d ? c : d;
    return m > n ? m : n;
}

/* dst (dw x dh) = 2x2 clamped mean of src (sw x sh). Summed in double in a
 * fixed order so the result is reproducible on every machine. */
static void avg_down(const float *src, uint32_t sw, uint32_t sh, float *dst, uint32_t dw,
                     uint32_t dh)
{
    for (uint32_t j = 0u; j < dh; ++j) {
        uint32_t y0 = 2u * j;
        uint32_t y1 = (y0 + 1u < sh) ? y0 + 1u : sh - 1u;
        const float *r0 = src + (size_t)y0 * sw;
        const float *r1 = src + (size_t)y1 * sw;
        float *out = dst + (size_t)j * dw;
        for (uint32_t i = 0u; i < dw; ++i) {
            uint32_t x0 = 2u * i;
            uint32_t x1 = (x0 + 1u < sw) ? x0 + 1u : sw - 1u;
            double s = ((double)r0[x0] + (double)r0[x1]) + ((double)r1[x0] + (double)r1[x1]);
            out[i] = (float)(s * 0.25);
        }
    }
}

/* dst = 2x2 clamped min and max of (smin, smax), both sw x sh. */
static void minmax_down(const float *smin, const float *smax, uint32_t sw, uint32_t sh,
                        float *dmin, float *dmax, uint32_t dw, uint32_t dh)
{
    for (uint32_t j = 0u; j < dh; ++j) {
        uint32_t y0 = 2u * j;
        uint32_t y1 = (y0 + 1u < sh) ? y0 + 1u : sh - 1u;
        size_t o0 = (size_t)y0 * sw, o1 = (size_t)y1 * sw;
        size_t od = (size_t)j * dw;
        for (uint32_t i = 0u; i < dw; ++i) {
            uint32_t x0 = 2u * i;
            uint32_t x1 = (x0 + 1u < sw) ? x0 + 1u : sw - 1u;
            dmin[od + i] = min4(smin[o0 + x0], smin[o0 + x1], smin[o1 + x0], smin[o1 + x1]);
            dmax[od + i] = max4(smax[o0 + x0], smax[o0 + x1], smax[o1 + x0], smax[o1 + x1]);
        }
    }
}

void ft_pyramid_build(ft_terrain *t)
{
    if (t == NULL || t->heights_m == NULL || !dims_ok(t->width, t->height)) {
        return;
    }
    ft_pyramid *p = &t->pyr;
    if (p->avg_levels != ft_pyramid_avg_levels(t->width, t->height) ||
        p->minmax_levels != ft_pyramid_minmax_levels(t->width, t->height)) {
        return; /* not laid out: nothing to write into */
    }
    p->avg[0].avg_m = t->heights_m; /* heights may have been bound after layout */
    for (uint32_t l = 1u; l < p->avg_levels; ++l) {
        const ft_pyramid_level *s = &p->avg[l - 1u];
        ft_pyramid_level *d = &p->avg[l];
        avg_down(s->avg_m, s->width, s->height, d->avg_m, d->width, d->height);
    }
    /* Level 0 of min/max: the 4 samples of each cell. */
    {
        const float *hm = t->heights_m;
        uint32_t gw = t->width;
        ft_pyramid_level *d = &p->minmax[0];
        for (uint32_t j = 0u; j < d->height; ++j) {
            const float *r0 = hm + (size_t)j * gw;
            const float *r1 = r0 + gw;
            float *omin = d->min_m + (size_t)j * d->width;
            float *omax = d->max_m + (size_t)j * d->width;
            for (uint32_t i = 0u; i < d->width; ++i) {
                omin[i] = min4(r0[i], r0[i + 1u], r1[i], r1[i + 1u]);
                omax[i] = max4(r0[i], r0[i + 1u], r1[i], r1[i + 1u]);
            }
        }
    }
    for (uint32_t l = 1u; l < p->minmax_levels; ++l) {
        const ft_pyramid_level *s = &p->minmax[l - 1u];
        ft_pyramid_level *d = &p->minmax[l];
        minmax_down(s->min_m, s->max_m, s->width, s->height, d->min_m, d->max_m, d->width,
                    d->height);
    }
    /* The 1x1 top level bounds every cell, i.e. every sample. */
    const ft_pyramid_level *top = &p->minmax[p->minmax_levels - 1u];
    t->min_height_m = top->min_m[0];
    t->max_height_m = top->max_m[0];
}

/* Range of the 2x2 clamped children of texel (i, j) in a sw x sh array. */
static void children_range(const float *lo_src, const float *hi_src, uint32_t sw, uint32_t sh,
                           uint32_t i, uint32_t j, float *lo, float *hi)
{
    uint32_t x0 = 2u * i, y0 = 2u * j;
    uint32_t x1 = (x0 + 1u < sw) ? x0 + 1u : sw - 1u;
    uint32_t y1 = (y0 + 1u < sh) ? y0 + 1u : sh - 1u;
    size_t o0 = (size_t)y0 * sw, o1 = (size_t)y1 * sw;
    *lo = min4(lo_src[o0 + x0], lo_src[o0 + x1], lo_src[o1 + x0], lo_src[o1 + x1]);
    *hi = max4(hi_src[o0 + x0], hi_src[o0 + x1], hi_src[o1 + x0], hi_src[o1 + x1]);
}

ft_status ft_pyramid_check(const ft_terrain *t, const char *name, ft_error *err)
{
    if (name == NULL) {
        name = "terrain";
    }
    if (t == NULL || t->heights_m == NULL || !dims_ok(t->width, t->height)) {
        return ft_fail(err, FT_ERR_ARG, "%s: pyramid check: terrain is not loaded", name);
    }
    const ft_pyramid *p = &t->pyr;
    if (p->avg_levels != ft_pyramid_avg_levels(t->width, t->height) ||
        p->minmax_levels != ft_pyramid_minmax_levels(t->width, t->height)) {
        return ft_fail(err, FT_ERR_ARG, "%s: pyramid check: pyramids are not laid out", name);
    }
    for (uint32_t l = 0u; l < p->minmax_levels; ++l) {
        const ft_pyramid_level *d = &p->minmax[l];
        const ft_pyramid_level *s = (l == 0u) ? NULL : &p->minmax[l - 1u];
        for (uint32_t j = 0u; j < d->height; ++j) {
            for (uint32_t i = 0u; i < d->width; ++i) {
                size_t k = (size_t)j * d->width + i;
                float mn = d->min_m[k], mx = d->max_m[k], lo, hi;
                if (s == NULL) {
                    const float *r0 = t->heights_m + (size_t)j * t->width;
                    const float *r1 = r0 + t->width;
                    lo = min4(r0[i], r0[i + 1u], r1[i], r1[i + 1u]);
                    hi = max4(r0[i], r0[i + 1u], r1[i], r1[i + 1u]);
                } else {
                    float lo_min, hi_min, lo_max, hi_max;
                    children_range(s->min_m, s->min_m, s->width, s->height, i, j, &lo_min,
                                   &hi_min);
                    children_range(s->max_m, s->max_m, s->width, s->height, i, j, &lo_max,
                                   &hi_max);
                    (void)hi_min;
                    (void)lo_max;
                    lo = lo_min;
                    hi = hi_max;
                }
                if (!(mn <= mx)) {
                    return ft_fail(err, FT_ERR_FORMAT,
                                   "%s: min/max pyramid level %u node (x %u, y %u): min %g m > "
                                   "max %g m",
                                   name, l, i, j, (double)mn, (double)mx);
                }
                if (mn != lo || mx != hi) {
                    return ft_fail(err, FT_ERR_FORMAT,
                                   "%s: min/max pyramid level %u node (x %u, y %u) holds "
                                   "%g..%g m, but its %s span %g..%g m",
                                   name, l, i, j, (double)mn, (double)mx,
                                   l == 0u ? "cell's 4 samples" : "children", (double)lo,
                                   (double)hi);
                }
            }
        }
    }
    for (uint32_t l = 1u; l < p->avg_levels; ++l) {
        const ft_pyramid_level *d = &p->avg[l];
        const ft_pyramid_level *s = &p->avg[l - 1u];
        const float *src = (l == 1u) ? t->heights_m : s->avg_m;
        for (uint32_t j = 0u; j < d->height; ++j) {
            for (uint32_t i = 0u; i < d->width; ++i) {
                float v = d->avg_m[(size_t)j * d->width + i], lo, hi;
                children_range(src, src, s->width, s->height, i, j, &lo, &hi);
                if (!(v >= lo && v <= hi)) {
                    return ft_fail(err, FT_ERR_FORMAT,
                                   "%s: avg pyramid level %u node (x %u, y %u) is %g m, outside "
                                   "its children's %g..%g m",
                                   name, l, i, j, (double)v, (double)lo, (double)hi);
                }
            }
        }
    }
    return FT_OK;
}
