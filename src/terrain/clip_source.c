/* clip_source.c - the clipmap cache's height source over the terrain in
 * memory (clip_source.h). */
#include <math.h>
#include <string.h>

#include "terrain/clip_source.h"

static int64_t clamp_i64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static int void_bit(const ft_terrain *t, uint64_t k)
{
    return t->void_bits != NULL && ((t->void_bits[k >> 3] >> (k & 7u)) & 1u) != 0u;
}

/* How far the terrain departs from level l's bilinear surface over the
 * cell whose south-west corner is level-l sample (a, b), where the cell
 * meets the terrain (the methods draw nothing past it): exactly, since on
 * every terrain cell inside it the difference of the two surfaces is
 * bilinear and peaks at that cell's corners, so the largest |h - H_l| at
 * the terrain samples of the closed cell is the maximum. The level's
 * corner heights are the clamped reads a cache sample holds. 0 where the
 * cell misses the terrain. At most (2^l + 1)^2 samples a call, and a level
 * that covers the terrain visits each sample about once. */
static float coarse_cell_dev_m(const ft_terrain *t, uint32_t level, int64_t a, int64_t b)
{
    const int64_t s = (int64_t)1 << level;
    const int64_t wmax = (int64_t)t->width - 1, hmax = (int64_t)t->height - 1;
    const int64_t x0 = a * s, y0 = b * s;
    const int64_t xa = clamp_i64(x0, 0, wmax), xb = clamp_i64(x0 + s, 0, wmax);
    const int64_t ya = clamp_i64(y0, 0, hmax), yb = clamp_i64(y0 + s, 0, hmax);
    if (x0 > wmax || y0 > hmax || x0 + s < 0 || y0 + s < 0) {
        return 0.0f;
    }
    /* the corners as the cache holds them: clamped reads (a corner past the
     * edge holds the edge's height) */
    const float *hm = t->heights_m;
    const double c00 = hm[(uint64_t)ya * t->width + (uint64_t)xa];
    const double c10 = hm[(uint64_t)ya * t->width + (uint64_t)xb];
    const double c01 = hm[(uint64_t)yb * t->width + (uint64_t)xa];
    const double c11 = hm[(uint64_t)yb * t->width + (uint64_t)xb];
    const double inv = 1.0 / (double)s;
    double dev = 0.0;
    for (int64_t y = ya; y <= yb; ++y) {
        const double v = (double)(y - y0) * inv;
        const double w0 = c00 + (c01 - c00) * v, w1 = c10 + (c11 - c10) * v;
        const float *row = hm + (uint64_t)y * t->width;
        for (int64_t x = xa; x <= xb; ++x) {
            const double u = (double)(x - x0) * inv;
            const double d = fabs((double)row[x] - (w0 + (w1 - w0) * u));
            dev = (d > dev) ? d : dev;
        }
    }
    /* rounded up to float */
    float f = (float)dev;
    if ((double)f < dev) {
        f = nextafterf(f, INFINITY);
    }
    return f;
}

static ft_status read_terrain(void *ctx, uint32_t level, int64_t i0, int64_t j0, uint32_t w,
                              uint32_t h, float *heights_m, uint8_t *marks, float *dev_m,
                              ft_error *err)
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
            /* level 0 is the terrain itself (void fills included: the
             * reference draws them too) */
            if (dev_m != NULL) {
                dev_m[o] = (level == 0u)
                               ? 0.0f
                               : coarse_cell_dev_m(t, level, i0 + (int64_t)q, j0 + (int64_t)r);
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

/* The largest coarser-level grid a rect of at most u samples and side
 * samples a row needs is under (w / 2 + 3) (h / 2 + 3) <= u / 4 + 3 side + 9
 * samples. */
static size_t coarse_bytes_of(const ft_clip_desc *d)
{
    return ((size_t)d->update_samples_max / 4u + 3u * (size_t)d->side + 9u) * sizeof(float);
}

size_t ft_clip_db_source_bytes(const ft_tdb_header *h, uint32_t tile_slots,
                               const ft_clip_desc *d)
{
    return ft_arena_round(ft_tdb_tile_cache_bytes(h, tile_slots, 1)) +
           ft_arena_round(coarse_bytes_of(d)) +
           ft_arena_round(((size_t)d->update_samples_max + 7u) / 8u);
}

void ft_clip_db_source_plan(const ft_tdb_header *h, uint32_t tile_slots, const ft_clip_desc *d,
                            ft_arena *a)
{
    ft_arena_plan(a, FT_POOL_CLIP, ft_tdb_tile_cache_bytes(h, tile_slots, 1));
    ft_arena_plan(a, FT_POOL_CLIP, coarse_bytes_of(d));
    ft_arena_plan(a, FT_POOL_CLIP, ((size_t)d->update_samples_max + 7u) / 8u);
}

static ft_status read_db(void *ctx, uint32_t level, int64_t i0, int64_t j0, uint32_t w,
                         uint32_t h, float *heights_m, uint8_t *marks, float *dev_m,
                         ft_error *err)
{
    ft_clip_db_source *s = ctx;
    const size_t n = (size_t)w * h;
    if (n > s->update_samples_max) {
        return ft_fail(err, FT_ERR_ARG, "database source: %u x %u samples, staging holds %u", w,
                       h, s->update_samples_max);
    }
    memset(s->bits, 0, (n + 7u) / 8u);
    const ft_dbw_rect r = {s->base_level + level, i0, j0, w, h, heights_m, s->bits, dev_m};
    uint64_t remaining = 0u;
    const ft_status st = ft_dbw_read_rect(s->db, &r, &s->tiles, s->coarse_m, s->coarse_bytes,
                                          &s->counts, &remaining, err);
    if (st != FT_OK) {
        return st;
    }
    s->counts.missing_samples += ft_dbw_floor_missing(heights_m, n, s->fill_m, s->bits);
    for (size_t k = 0u; k < n && marks != NULL; ++k) {
        marks[k] = (uint8_t)((s->bits[k >> 3] >> (k & 7u)) & 1u);
    }
    return FT_OK;
}

ft_status ft_clip_source_db(ft_clip_source *out, ft_clip_db_source *s, const ft_tdb *db,
                            uint32_t base_level, int64_t lattice_i0, int64_t lattice_j0,
                            float fill_m, uint32_t tile_slots, const ft_clip_desc *d,
                            ft_arena *a, ft_error *err)
{
    memset(s, 0, sizeof(*s));
    if (base_level >= db->hdr.level_count) {
        return ft_fail(err, FT_ERR_CONFIG, "database source: level %u, the database has 0..%u",
                       base_level, db->hdr.level_count - 1u);
    }
    if (tile_slots < 1u || tile_slots > FT_TDB_TILE_CACHE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "clipmap.tile_slots = %u: must be 1..%u", tile_slots,
                       FT_TDB_TILE_CACHE_MAX);
    }
    s->db = db;
    s->base_level = base_level;
    s->fill_m = fill_m;
    s->update_samples_max = d->update_samples_max;
    s->coarse_bytes = coarse_bytes_of(d);
    void *tiles = NULL, *coarse = NULL, *bits = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_CLIP, ft_tdb_tile_cache_bytes(&db->hdr, tile_slots, 1),
                                 &tiles, err);
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_CLIP, s->coarse_bytes, &coarse, err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_CLIP, ((size_t)d->update_samples_max + 7u) / 8u, &bits,
                           err);
    }
    if (st != FT_OK) {
        return st;
    }
    ft_tdb_tile_cache_init(&s->tiles, &db->hdr, tile_slots, 1, tiles);
    s->coarse_m = coarse;
    s->bits = bits;
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(db->hdr.samples_per_deg, base_level, &nx, &ny);
    out->read = read_db;
    out->ctx = s;
    out->levels = db->hdr.level_count - base_level;
    out->lattice_i0 = lattice_i0;
    out->lattice_j0 = lattice_j0;
    out->data_i_lo = 0;
    out->data_j_lo = 0;
    out->data_i_hi = (int64_t)nx - 1;
    out->data_j_hi = (int64_t)ny - 1;
    /* every level the cache reads wraps in longitude: the terrain goes on
     * east and west without end (bounded far past any box the cache holds) */
    int wraps = 1;
    for (uint32_t l = 0u; l < d->levels && l < out->levels; ++l) {
        wraps = wraps && ft_tdb_lattice_closes(db->hdr.samples_per_deg, base_level + l);
    }
    if (wraps) {
        out->data_i_lo = -FT_CLIP_DATA_UNBOUNDED;
        out->data_i_hi = FT_CLIP_DATA_UNBOUNDED;
    }
    s->wraps = wraps;
    return FT_OK;
}
