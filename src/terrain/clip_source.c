/* clip_source.c - the clipmap cache's height source over the terrain in
 * memory (clip_source.h). */
#include "terrain/clip_source.h"

static int64_t clamp_i64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static int void_bit(const ft_terrain *t, uint64_t k)
{
    return t->void_bits != NULL && ((t->void_bits[k >> 3] >> (k & 7u)) & 1u) != 0u;
}

static ft_status read_terrain(void *ctx, uint32_t level, int64_t i0, int64_t j0, uint32_t w,
                              uint32_t h, float *heights_m, uint8_t *marks, ft_error *err)
{
    (void)err;
    const ft_terrain *t = ctx;
    const int64_t wmax = (int64_t)t->width - 1, hmax = (int64_t)t->height - 1;
    for (uint32_t r = 0u; r < h; ++r) {
        const int64_t y = (j0 + (int64_t)r) * ((int64_t)1 << level);
        const int64_t yc = clamp_i64(y, 0, hmax);
        for (uint32_t q = 0u; q < w; ++q) {
            const int64_t x = (i0 + (int64_t)q) * ((int64_t)1 << level);
            const int64_t xc = clamp_i64(x, 0, wmax);
            const uint64_t k = (uint64_t)yc * t->width + (uint64_t)xc;
            const size_t o = (size_t)r * w + q;
            heights_m[o] = t->heights_m[k];
            if (marks != NULL) {
                marks[o] = (uint8_t)((x != xc || y != yc || void_bit(t, k)) ? 1u : 0u);
            }
        }
    }
    return FT_OK;
}

void ft_clip_source_terrain(ft_clip_source *out, const ft_terrain *t)
{
    out->read = read_terrain;
    out->ctx = (void *)(uintptr_t)t; /* the reader only reads through it */
    out->levels = FT_CLIP_LEVELS_MAX;
    out->lattice_i0 = 0;
    out->lattice_j0 = 0;
    out->data_i_lo = 0;
    out->data_j_lo = 0;
    out->data_i_hi = (int64_t)t->width - 1;
    out->data_j_hi = (int64_t)t->height - 1;
}
