#include "terrain/db_window.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A level's step 2^level (level < FT_TDB_LEVELS_MAX) is taken in 64 bits. */
_Static_assert(FT_TDB_LEVELS_MAX <= 32u, "a level's step 2^level fits 32 bits");

static const char *file_name(const ft_reader_at *r)
{
    return (r->name != NULL) ? r->name : "(unnamed)";
}

static double spacing_deg(const ft_dbw *w)
{
    return (double)((uint64_t)1u << w->level) / (double)w->hdr.samples_per_deg;
}

/* Lattice index of the middle of the data tiles [t0, t1] of one axis, the
 * last tile clipped to the lattice's n samples. */
static double data_middle(uint32_t t0, uint32_t t1, uint32_t tile, uint64_t n)
{
    uint64_t end = ((uint64_t)t1 + 1u) * tile;
    end = end < n ? end : n;
    return 0.5 * ((double)t0 * tile + (double)(end - 1u));
}

ft_status ft_dbw_probe(const ft_reader_at *r, const ft_dbw_desc *d, ft_dbw *w, ft_terrain *t,
                       ft_error *err)
{
    memset(w, 0, sizeof *w);
    ft_status st = ft_tdb_read_header(r, &w->hdr, err);
    if (st != FT_OK) {
        return st;
    }
    const char *name = file_name(r);
    if (d->level >= w->hdr.level_count) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "terrain.db_level %u: %s has levels 0..%u (level 0 every 1/%u deg)",
                       d->level, name, w->hdr.level_count - 1u, w->hdr.samples_per_deg);
    }
    if (d->side_samples < FT_GRID_SIDE_MIN || d->side_samples > FT_GRID_SIDE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "terrain.db_side_samples %u is outside %u..%u",
                       d->side_samples, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    w->level = d->level;
    w->side = d->side_samples;
    ft_tdb_lattice_samples(w->hdr.samples_per_deg, w->level, &w->nx, &w->ny);
    const double sp = spacing_deg(w);
    double ic = 0.0, jc = 0.0;
    if (isnan(d->centre_lat_deg) || isnan(d->centre_lon_deg)) {
        uint32_t box[4], tiles = 0u;
        st = ft_tdb_data_box(r, &w->hdr, w->level, box, &tiles, err);
        if (st != FT_OK) {
            return st;
        }
        if (tiles == 0u) {
            return ft_fail(err, FT_ERR_CONFIG, "terrain.db_level %u: %s has no data at that level",
                           w->level, name);
        }
        ic = data_middle(box[0], box[2], w->hdr.tile_samples, w->nx);
        jc = data_middle(box[1], box[3], w->hdr.tile_samples, w->ny);
    }
    if (!isnan(d->centre_lon_deg)) {
        ic = (d->centre_lon_deg + 180.0) / sp;
    }
    if (!isnan(d->centre_lat_deg)) {
        jc = (d->centre_lat_deg + 90.0) / sp;
    }
    const int64_t half = (int64_t)(w->side - 1u) / 2;
    w->i0 = (int64_t)floor(ic + 0.5) - half;
    w->j0 = (int64_t)floor(jc + 0.5) - half;
    const double south = -90.0 + (double)w->j0 * sp;
    const double north = south + (double)(w->side - 1u) * sp;
    if (south < -90.0 || north > 90.0) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "terrain.db_centre_lat_deg / db_side_samples: the window of %u samples "
                       "at level %u spans latitude %.6f..%.6f deg, past a pole",
                       w->side, w->level, south, north);
    }
    const int64_t side = (int64_t)w->side;
    if (w->i0 + side <= 0 || w->i0 >= (int64_t)w->nx) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "terrain.db_centre_lon_deg: the window of %u samples at level %u spans "
                       "longitude %.6f..%.6f deg, outside the database's -180..180 deg",
                       w->side, w->level, -180.0 + (double)w->i0 * sp,
                       -180.0 + (double)(w->i0 + side - 1) * sp);
    }
    memset(t, 0, sizeof *t);
    t->width = w->side;
    t->height = w->side;
    t->unit = FT_UNIT_DEGREE;
    t->spacing_x = sp;
    t->spacing_y = sp;
    t->origin_x = -180.0 + (double)w->i0 * sp;
    t->origin_y = south;
    t->anchor_lat_deg = t->origin_y;
    t->anchor_lon_deg = t->origin_x;
    (void)snprintf(t->crs, sizeof t->crs, "EPSG:4326");
    t->min_height_m = w->hdr.min_height_m;
    t->max_height_m = w->hdr.max_height_m;
    return ft_terrain_derive_frame(t, err);
}

size_t ft_dbw_index_bytes(const ft_dbw *w)
{
    return (size_t)w->hdr.entry_count * sizeof(ft_tdb_entry);
}

/* Samples of a coarser level's grid around a rect of len samples on one
 * axis: at most (len - 1) / 2 + 1 of the next level (fewer further up),
 * plus one on each side for the bilinear cell. */
static uint32_t coarse_len(uint32_t len)
{
    return (len - 1u) / 2u + 3u;
}

size_t ft_dbw_rect_coarse_bytes(const ft_tdb_header *h, uint32_t level, uint32_t w,
                                uint32_t hgt)
{
    return (level + 1u < h->level_count) ? (size_t)coarse_len(w) * coarse_len(hgt) * sizeof(float)
                                         : 0u;
}

static size_t slot_bytes(const ft_tdb_header *h, int with_dev)
{
    const size_t n = (size_t)h->tile_samples * h->tile_samples;
    /* a multiple of 4: T >= 16 */
    return n * sizeof(float) + n / 8u + (with_dev ? n * sizeof(float) : 0u);
}

size_t ft_tdb_tile_cache_bytes(const ft_tdb_header *h, uint32_t slots, int with_dev)
{
    return slot_bytes(h, with_dev) * slots;
}

void ft_tdb_tile_cache_init(ft_tdb_tile_cache *tc, const ft_tdb_header *h, uint32_t slots,
                            int with_dev, void *mem)
{
    memset(tc, 0, sizeof *tc);
    tc->slots = slots < FT_TDB_TILE_CACHE_MAX ? slots : FT_TDB_TILE_CACHE_MAX;
    tc->with_dev = with_dev != 0;
    tc->tile_n = (size_t)h->tile_samples * h->tile_samples;
    for (uint32_t k = 0u; k < tc->slots; ++k) {
        uint8_t *base = (uint8_t *)mem + slot_bytes(h, tc->with_dev) * k;
        tc->slot[k].heights_m = (float *)(void *)base;
        tc->slot[k].void_bits = base + tc->tile_n * sizeof(float);
        tc->slot[k].dev_m =
            tc->with_dev ? (float *)(void *)(base + tc->tile_n * sizeof(float) + tc->tile_n / 8u)
                         : NULL;
    }
}

/* Tile (level, tx, ty) from the cache or, on a miss, read into the least
 * recently used slot (with every check of ft_tdb_read_tile). NULL in *out
 * when the database has no data there (nothing read). */
static ft_status cached_tile(const ft_tdb *db, ft_tdb_tile_cache *tc, uint32_t level,
                             uint32_t tx, uint32_t ty, const ft_tdb_tile **out, ft_error *err)
{
    *out = NULL;
    const ft_tdb_entry *e = ft_tdb_find(db, level, tx, ty);
    if (e == NULL || e->state != FT_TDB_DATA) {
        return FT_OK;
    }
    ft_tdb_tile_slot *victim = &tc->slot[0];
    for (uint32_t k = 0u; k < tc->slots; ++k) {
        ft_tdb_tile_slot *sl = &tc->slot[k];
        if (sl->filled && sl->level == level && sl->tx == tx && sl->ty == ty) {
            sl->stamp = ++tc->clock;
            ++tc->hits;
            *out = &sl->tile;
            return FT_OK;
        }
        if (!sl->filled || (victim->filled && sl->stamp < victim->stamp)) {
            victim = sl;
        }
    }
    victim->filled = 0;
    const ft_status st =
        ft_tdb_read_tile_dev(db, level, tx, ty, victim->heights_m, tc->tile_n, victim->void_bits,
                             tc->tile_n / 8u, victim->dev_m, tc->with_dev ? tc->tile_n : 0u,
                             &victim->tile, err);
    if (st != FT_OK) {
        return st;
    }
    ++tc->reads;
    victim->filled = 1;
    victim->level = level;
    victim->tx = tx;
    victim->ty = ty;
    victim->stamp = ++tc->clock;
    *out = &victim->tile;
    return FT_OK;
}

size_t ft_dbw_staging_bytes(const ft_dbw *w)
{
    return ft_tdb_tile_cache_bytes(&w->hdr, 1u, 0) +
           ft_dbw_rect_coarse_bytes(&w->hdr, w->level, w->side, w->side);
}

static void mark(uint8_t *bits, size_t i)
{
    bits[i >> 3] = (uint8_t)(bits[i >> 3] | (1u << (i & 7u)));
}

uint64_t ft_dbw_floor_missing(float *heights_m, size_t n, float fill_m, uint8_t *void_bits)
{
    uint64_t missing = 0u;
    for (size_t k = 0u; k < n; ++k) {
        if (heights_m[k] == FT_TDB_NODATA_M) {
            heights_m[k] = fill_m;
            mark(void_bits, k);
            ++missing;
        }
    }
    return missing;
}

/* floor(a / b) for b > 0 (a may be negative: west of -180 deg). */
static int64_t floor_div(int64_t a, int64_t b)
{
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

/* A w x h block of one level's lattice samples from (i0, j0), row 0 = south;
 * bits (NULL: none) marks the samples the database void-filled. */
typedef struct lattice_grid {
    uint32_t level;
    int64_t i0, j0;
    uint32_t w, h;
    float *m;
    uint8_t *bits;
    float *dev; /* NULL, or w * h cell devs (ft_dbw_rect) */
} lattice_grid;

/* The grid's samples [lo, hi) on one axis that the lattice (n samples)
 * holds; 0 when none. */
static int clip_axis(int64_t g0, uint32_t len, uint64_t n, uint64_t *lo, uint64_t *hi)
{
    const int64_t a = g0 < 0 ? 0 : g0;
    const int64_t b = g0 + (int64_t)len;
    const int64_t bn = b < (int64_t)n ? b : (int64_t)n;
    if (bn <= a) {
        return 0;
    }
    *lo = (uint64_t)a;
    *hi = (uint64_t)bn;
    return 1;
}

/* Copies the part of tile (tx, ty) inside [ilo, ihi) x [jlo, jhi) into g. */
static void copy_tile(const ft_tdb_tile *tile, uint64_t T, uint64_t tx, uint64_t ty, uint64_t ilo,
                      uint64_t ihi, uint64_t jlo, uint64_t jhi, lattice_grid *g,
                      ft_dbw_counts *c)
{
    const uint64_t i_a = tx * T > ilo ? tx * T : ilo;
    const uint64_t i_b = (tx + 1u) * T < ihi ? (tx + 1u) * T : ihi;
    const uint64_t j_a = ty * T > jlo ? ty * T : jlo;
    const uint64_t j_b = (ty + 1u) * T < jhi ? (ty + 1u) * T : jhi;
    for (uint64_t j = j_a; j < j_b; ++j) {
        const size_t src_row = (size_t)((j - ty * T) * T);
        const size_t dst_row = (size_t)((int64_t)j - g->j0) * g->w;
        for (uint64_t i = i_a; i < i_b; ++i) {
            const size_t s = src_row + (size_t)(i - tx * T);
            const size_t o = dst_row + (size_t)((int64_t)i - g->i0);
            g->m[o] = tile->heights_m[s];
            if (g->dev != NULL) {
                /* a sample without data here takes a coarser level's value:
                 * no cell it is a corner of has this level's bound */
                g->dev[o] = (tile->heights_m[s] == FT_TDB_NODATA_M) ? FT_TDB_DEV_NONE
                            : (g->level == 0u)                    ? 0.0f
                            : (tile->dev_m != NULL)               ? tile->dev_m[s]
                                                                  : FT_TDB_DEV_NONE;
            }
            if (g->bits != NULL && ((tile->void_bits[s >> 3] >> (s & 7u)) & 1u) != 0u) {
                mark(g->bits, o);
                ++c->filled_samples;
            }
        }
    }
}

/* Reads g from the database tile by tile through the staging buffer;
 * samples no tile covers (no data, outside the lattice) hold
 * FT_TDB_NODATA_M. A level whose lattice closes around the globe wraps in
 * longitude: g's columns are read a turn (nx samples) at a time, each turn's
 * part from lattice columns 0..nx-1. */
static ft_status read_grid(const ft_tdb *db, lattice_grid *g, ft_tdb_tile_cache *tc,
                           ft_dbw_counts *c, ft_error *err)
{
    const size_t n = (size_t)g->w * g->h;
    for (size_t k = 0u; k < n; ++k) {
        g->m[k] = FT_TDB_NODATA_M; /* until a tile says otherwise */
    }
    for (size_t k = 0u; g->dev != NULL && k < n; ++k) {
        g->dev[k] = FT_TDB_DEV_NONE;
    }
    uint64_t nx = 0u, ny = 0u, jlo = 0u, jhi = 0u;
    ft_tdb_lattice_samples(db->hdr.samples_per_deg, g->level, &nx, &ny);
    if (nx == 0u || !clip_axis(g->j0, g->h, ny, &jlo, &jhi)) {
        return FT_OK;
    }
    int64_t turn_lo = 0, turn_hi = 0; /* no wrap: the lattice's own columns only */
    if (ft_tdb_lattice_closes(db->hdr.samples_per_deg, g->level)) {
        turn_lo = floor_div(g->i0, (int64_t)nx);
        turn_hi = floor_div(g->i0 + (int64_t)g->w - 1, (int64_t)nx);
    }
    const uint64_t T = db->hdr.tile_samples;
    /* bounded: at most w / nx + 2 turns */
    for (int64_t turn = turn_lo; turn <= turn_hi; ++turn) {
        lattice_grid gt = *g; /* g as seen from this turn's lattice columns */
        gt.i0 = g->i0 - turn * (int64_t)nx;
        uint64_t ilo = 0u, ihi = 0u;
        if (!clip_axis(gt.i0, gt.w, nx, &ilo, &ihi)) {
            continue;
        }
        for (uint64_t ty = jlo / T; ty <= (jhi - 1u) / T; ++ty) {
            for (uint64_t tx = ilo / T; tx <= (ihi - 1u) / T; ++tx) {
                const ft_tdb_tile *tile = NULL;
                const ft_status st =
                    cached_tile(db, tc, g->level, (uint32_t)tx, (uint32_t)ty, &tile, err);
                if (st != FT_OK) {
                    return st;
                }
                if (tile == NULL) {
                    ++c->tiles_no_data;
                    continue;
                }
                ++c->tiles_read;
                copy_tile(tile, T, tx, ty, ilo, ihi, jlo, jhi, &gt, c);
            }
        }
    }
    return FT_OK;
}

/* Draws the rect's samples still without data from coarser level `level`
 * (grid cg, read here): the bilinear interpolant of the coarser samples
 * around each, when every one with a weight has data. Marks them (coarser
 * data is real but not the level's). Returns how many remain. */
static ft_status fill_from_coarser(const ft_tdb *db, uint32_t level, lattice_grid *win,
                                   lattice_grid *cg, ft_tdb_tile_cache *tc, ft_dbw_counts *c,
                                   uint64_t *remaining, ft_error *err)
{
    const int64_t s = (int64_t)1 << (level - win->level);
    /* Only the coarser tiles under the samples still without data are read:
     * their box in the rect, x0..x1, y0..y1. */
    uint32_t x0 = win->w, y0 = win->h, x1 = 0u, y1 = 0u;
    for (uint32_t y = 0u; y < win->h; ++y) {
        for (uint32_t x = 0u; x < win->w; ++x) {
            if (win->m[(size_t)y * win->w + x] == FT_TDB_NODATA_M) {
                x0 = x < x0 ? x : x0;
                x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
            }
        }
    }
    if (x0 > x1) {
        *remaining = 0u;
        return FT_OK;
    }
    cg->level = level;
    cg->i0 = floor_div(win->i0 + x0, s);
    cg->j0 = floor_div(win->j0 + y0, s);
    cg->w = (uint32_t)(floor_div(win->i0 + x1, s) + 2 - cg->i0);
    cg->h = (uint32_t)(floor_div(win->j0 + y1, s) + 2 - cg->j0);
    cg->bits = NULL;
    if (cg->w > coarse_len(win->w) || cg->h > coarse_len(win->h)) {
        return ft_fail(err, FT_ERR_BUDGET,
                       "%u x %u samples at level %u: a level-%u grid of %u x %u samples, "
                       "planned %u x %u",
                       win->w, win->h, win->level, level, cg->w, cg->h, coarse_len(win->w),
                       coarse_len(win->h));
    }
    ft_status st = read_grid(db, cg, tc, c, err);
    if (st != FT_OK) {
        return st;
    }
    uint64_t left = 0u;
    for (uint32_t y = 0u; y < win->h; ++y) {
        for (uint32_t x = 0u; x < win->w; ++x) {
            const size_t o = (size_t)y * win->w + x;
            if (win->m[o] != FT_TDB_NODATA_M) {
                continue;
            }
            const int64_t i = win->i0 + x, j = win->j0 + y;
            const size_t ci = (size_t)(floor_div(i, s) - cg->i0);
            const size_t cj = (size_t)(floor_div(j, s) - cg->j0);
            const double fx = (double)(i - floor_div(i, s) * s) / (double)s;
            const double fy = (double)(j - floor_div(j, s) * s) / (double)s;
            const float *r0 = cg->m + cj * cg->w + ci, *r1 = r0 + cg->w;
            const double wt[4] = {(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy,
                                  fx * fy};
            const float v[4] = {r0[0], r0[1], r1[0], r1[1]};
            double sum = 0.0;
            int ok = 1;
            for (int q = 0; q < 4; ++q) {
                ok = ok && (wt[q] == 0.0 || v[q] != FT_TDB_NODATA_M);
                sum += wt[q] > 0.0 ? wt[q] * (double)v[q] : 0.0;
            }
            if (!ok) {
                ++left;
                continue;
            }
            win->m[o] = (float)sum;
            mark(win->bits, o);
            ++c->coarser_samples;
        }
    }
    *remaining = left;
    return FT_OK;
}

ft_status ft_dbw_read_rect(const ft_tdb *db, const ft_dbw_rect *r, ft_tdb_tile_cache *tc,
                           float *coarse_m, size_t coarse_bytes, ft_dbw_counts *c,
                           uint64_t *remaining, ft_error *err)
{
    const ft_tdb_header *h = &db->hdr;
    if (r->w == 0u || r->h == 0u || r->level >= h->level_count || tc->slots == 0u ||
        tc->tile_n != (size_t)h->tile_samples * h->tile_samples ||
        coarse_bytes < ft_dbw_rect_coarse_bytes(h, r->level, r->w, r->h) ||
        (r->dev_m != NULL && !tc->with_dev)) {
        return ft_fail(err, FT_ERR_ARG, "database rect %u x %u at level %u without its staging",
                       r->w, r->h, r->level);
    }
    lattice_grid g = {r->level, r->i0, r->j0, r->w, r->h, r->heights_m, r->void_bits, r->dev_m};
    ft_status st = read_grid(db, &g, tc, c, err);
    const size_t n = (size_t)r->w * r->h;
    uint64_t left = 0u;
    for (size_t k = 0u; k < n; ++k) {
        left += r->heights_m[k] == FT_TDB_NODATA_M;
    }
    /* Coarser levels, nearest first, while samples lack data. Bounded by
     * the level count (at most FT_TDB_LEVELS_MAX). */
    for (uint32_t k = r->level + 1u; st == FT_OK && left > 0u && k < h->level_count; ++k) {
        lattice_grid cg = {0u, 0, 0, 0u, 0u, coarse_m, NULL, NULL};
        st = fill_from_coarser(db, k, &g, &cg, tc, c, &left, err);
    }
    *remaining = left;
    return st;
}

ft_status ft_dbw_load(const ft_reader_at *r, const ft_dbw *w, ft_terrain *t, void *io,
                      size_t io_bytes, ft_dbw_counts *counts, ft_error *err)
{
    const char *name = file_name(r);
    const size_t index_bytes = ft_dbw_index_bytes(w), staging_bytes = ft_dbw_staging_bytes(w);
    memset(counts, 0, sizeof *counts);
    /* index_bytes is a multiple of sizeof(ft_tdb_entry), itself of 8: the
     * staging after it is aligned for floats */
    _Static_assert(sizeof(ft_tdb_entry) % sizeof(float) == 0u, "staging aligned after the index");
    if (io == NULL || io_bytes < index_bytes + staging_bytes || t->heights_m == NULL ||
        t->void_bits == NULL || t->width != w->side || t->height != w->side) {
        return ft_fail(err, FT_ERR_ARG, "%s: window load without its buffers", name);
    }
    ft_tdb db;
    ft_status st = ft_tdb_open(&db, r, (ft_tdb_entry *)io, w->hdr.entry_count, err);
    if (st != FT_OK) {
        return st;
    }
    /* the probe placed the window and planned the buffers from its header */
    const ft_tdb_header *h0 = &w->hdr, *h1 = &db.hdr;
    if (h1->index_crc32 != h0->index_crc32 || h1->entry_count != h0->entry_count ||
        h1->file_bytes != h0->file_bytes || h1->tile_samples != h0->tile_samples ||
        h1->samples_per_deg != h0->samples_per_deg || h1->level_count != h0->level_count) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: the header changed between probe and load", name);
    }
    const ft_dbw_rect rect = {w->level, w->i0, w->j0, w->side, w->side, t->heights_m,
                              t->void_bits, NULL};
    uint64_t remaining = 0u;
    ft_tdb_tile_cache tc;
    uint8_t *staging = (uint8_t *)io + index_bytes;
    const size_t tile_bytes = ft_tdb_tile_cache_bytes(&w->hdr, 1u, 0);
    ft_tdb_tile_cache_init(&tc, &w->hdr, 1u, 0, staging);
    st = ft_dbw_read_rect(&db, &rect, &tc, (float *)(void *)(staging + tile_bytes),
                          staging_bytes - tile_bytes, counts, &remaining, err);
    if (st != FT_OK) {
        return st;
    }
    const size_t n = (size_t)w->side * w->side;
    /* The floor: the lowest height the window has. */
    float lo_m = INFINITY, hi_m = -INFINITY;
    for (size_t k = 0u; k < n; ++k) {
        const float v = t->heights_m[k];
        if (v != FT_TDB_NODATA_M) {
            lo_m = v < lo_m ? v : lo_m;
            hi_m = v > hi_m ? v : hi_m;
        }
    }
    if (!(lo_m <= hi_m)) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "terrain.db_centre_lat_deg / db_centre_lon_deg: the window of %u samples "
                       "at level %u (latitude %.6f, longitude %.6f deg at its south-west "
                       "corner) holds no data of %s at any level",
                       w->side, w->level, t->origin_y, t->origin_x, name);
    }
    counts->missing_samples += ft_dbw_floor_missing(t->heights_m, n, lo_m, t->void_bits);
    counts->fill_m = lo_m;
    t->min_height_m = lo_m;
    t->max_height_m = hi_m;
    t->void_count =
        (uint32_t)(counts->missing_samples + counts->filled_samples + counts->coarser_samples);
    return ft_terrain_check_void_bits(t->void_bits, t->width, t->height, t->void_count, name,
                                      err);
}
