#include "terrain/db_window.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The scene's db_level rows allow levels up to this; the database says how
 * many it has. */
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

size_t ft_dbw_staging_bytes(const ft_dbw *w)
{
    const size_t n = (size_t)w->hdr.tile_samples * w->hdr.tile_samples;
    return n * sizeof(float) + n / 8u;
}

static void mark(uint8_t *bits, size_t i)
{
    bits[i >> 3] = (uint8_t)(bits[i >> 3] | (1u << (i & 7u)));
}

/* The window's lattice samples [lo, hi) on one axis that the lattice holds;
 * 0 when none. */
static int clip_axis(int64_t w0, uint32_t side, uint64_t n, uint64_t *lo, uint64_t *hi)
{
    const int64_t a = w0 < 0 ? 0 : w0;
    const int64_t b = w0 + (int64_t)side;
    const int64_t bn = b < (int64_t)n ? b : (int64_t)n;
    if (bn <= a) {
        return 0;
    }
    *lo = (uint64_t)a;
    *hi = (uint64_t)bn;
    return 1;
}

/* Copies the part of tile (tx, ty) inside [ilo, ihi) x [jlo, jhi) into the
 * window; marks the samples the database void-filled. */
static void copy_tile(const ft_dbw *w, const ft_tdb_tile *tile, uint64_t tx, uint64_t ty,
                      uint64_t ilo, uint64_t ihi, uint64_t jlo, uint64_t jhi, ft_terrain *t,
                      ft_dbw_counts *c)
{
    const uint64_t T = w->hdr.tile_samples;
    const uint64_t i_a = tx * T > ilo ? tx * T : ilo, i_b = (tx + 1u) * T < ihi ? (tx + 1u) * T : ihi;
    const uint64_t j_a = ty * T > jlo ? ty * T : jlo, j_b = (ty + 1u) * T < jhi ? (ty + 1u) * T : jhi;
    for (uint64_t j = j_a; j < j_b; ++j) {
        const size_t src_row = (size_t)((j - ty * T) * T);
        const size_t dst_row = (size_t)((int64_t)j - w->j0) * w->side;
        for (uint64_t i = i_a; i < i_b; ++i) {
            const size_t s = src_row + (size_t)(i - tx * T);
            const size_t o = dst_row + (size_t)((int64_t)i - w->i0);
            t->heights_m[o] = tile->heights_m[s];
            if (((tile->void_bits[s >> 3] >> (s & 7u)) & 1u) != 0u) {
                mark(t->void_bits, o);
                ++c->filled_samples;
            }
        }
    }
}

ft_status ft_dbw_load(const ft_reader_at *r, const ft_dbw *w, ft_terrain *t, void *io,
                      size_t io_bytes, ft_dbw_counts *counts, ft_error *err)
{
    const char *name = file_name(r);
    const size_t index_bytes = ft_dbw_index_bytes(w), staging_bytes = ft_dbw_staging_bytes(w);
    memset(counts, 0, sizeof *counts);
    if (io == NULL || io_bytes < index_bytes + staging_bytes || t->heights_m == NULL ||
        t->void_bits == NULL || t->width != w->side || t->height != w->side) {
        return ft_fail(err, FT_ERR_ARG, "%s: window load without its buffers", name);
    }
    ft_tdb db;
    ft_tdb_entry *entries = (ft_tdb_entry *)io;
    ft_status st = ft_tdb_open(&db, r, entries, w->hdr.entry_count, err);
    if (st != FT_OK) {
        return st;
    }
    if (memcmp(&db.hdr, &w->hdr, sizeof db.hdr) != 0) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: the header changed between probe and load", name);
    }
    const size_t tile_n = (size_t)w->hdr.tile_samples * w->hdr.tile_samples;
    /* staging after the index, aligned for floats */
    const size_t stage_at = (index_bytes + sizeof(float) - 1u) / sizeof(float) * sizeof(float);
    if (io_bytes < stage_at + staging_bytes) {
        return ft_fail(err, FT_ERR_ARG, "%s: window load without room for its staging", name);
    }
    float *stage_m = (float *)(void *)((uint8_t *)io + stage_at);
    uint8_t *stage_bits = (uint8_t *)(stage_m + tile_n);

    const size_t n = (size_t)w->side * w->side;
    for (size_t k = 0u; k < n; ++k) {
        t->heights_m[k] = FT_TDB_NODATA_M; /* until a tile says otherwise */
    }
    uint64_t ilo = 0u, ihi = 0u, jlo = 0u, jhi = 0u;
    if (clip_axis(w->i0, w->side, w->nx, &ilo, &ihi) &&
        clip_axis(w->j0, w->side, w->ny, &jlo, &jhi)) {
        const uint64_t T = w->hdr.tile_samples;
        for (uint64_t ty = jlo / T; ty <= (jhi - 1u) / T; ++ty) {
            for (uint64_t tx = ilo / T; tx <= (ihi - 1u) / T; ++tx) {
                ft_tdb_tile tile;
                st = ft_tdb_read_tile(&db, w->level, (uint32_t)tx, (uint32_t)ty, stage_m, tile_n,
                                      stage_bits, tile_n / 8u, &tile, err);
                if (st != FT_OK) {
                    return st;
                }
                if (tile.state != FT_TDB_DATA) {
                    ++counts->tiles_no_data;
                    continue;
                }
                ++counts->tiles_read;
                copy_tile(w, &tile, tx, ty, ilo, ihi, jlo, jhi, t, counts);
            }
        }
    }
    /* The floor: the lowest height the window's data has. */
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
                       "corner) holds no data of %s",
                       w->side, w->level, t->origin_y, t->origin_x, name);
    }
    for (size_t k = 0u; k < n; ++k) {
        if (t->heights_m[k] == FT_TDB_NODATA_M) {
            t->heights_m[k] = lo_m;
            mark(t->void_bits, k);
            ++counts->missing_samples;
        }
    }
    counts->fill_m = lo_m;
    t->min_height_m = lo_m;
    t->max_height_m = hi_m;
    t->void_count = (uint32_t)(counts->missing_samples + counts->filled_samples);
    return ft_terrain_check_void_bits(t->void_bits, t->width, t->height, t->void_count, name,
                                      err);
}
