/* db_window.h - a square window of a terrain database (.ftd, terrain_db.h)
 * as the runtime's terrain: `[terrain] dem = region.ftd` with the scene keys
 * terrain.db_level, db_centre_lat_deg, db_centre_lon_deg, db_side_samples.
 *
 * The window is side x side samples of one level's lattice, its middle
 * sample the lattice point nearest the centre (for an even side, the one
 * south-west of the middle); the terrain's frame is that of a .hgt (degrees,
 * origin = sample (0,0), anchor there), so every method, the metric, the
 * reference and the pose checks work unchanged.
 *
 * Probe: the header only (and, when the centre is not given, that level's
 * index entries in small chunks on the stack, for the data's extent): no
 * memory is bound yet. Load: the index into FT_POOL_DEM_IO, then one tile at
 * a time through a staging buffer there (ft_tdb_read_tile: crc, heights and
 * counts checked); the whole file is never read.
 *
 * Longitude wraps where the lattice closes: a level whose 360 N / 2^level is
 * whole (ft_tdb_lattice_closes) reads column i as column i mod nx, so a
 * window (or a clipmap level) runs on across the antimeridian; a position
 * given at -179.9 deg lands east of such a window's 180 deg
 * (ft_terrain_geo_to_world). A level that does not close has no column at
 * 180 deg (it would fall between its samples) and does not wrap.
 *
 * Missing data is never invented silently. A window sample "lacks data"
 * when its tile is "no data", when it holds FT_TDB_NODATA_M, or when it lies
 * outside the lattice (north of 90 deg, south of -90 deg; at or east of 180
 * deg or west of -180 deg on a level that does not wrap). Such a sample is drawn
 *  1. from the nearest coarser level that has data around it: the bilinear
 *     interpolant of that level's samples around it (real data, coarser),
 *     when every one of them with a weight has data; else
 *  2. at the lowest height the window has (a flat floor, so the methods
 *     have a height everywhere).
 * Both are marked in ft_terrain.void_bits, as are the samples the database
 * itself void-filled: the renderer hatches every cell with a marked corner
 * and counts its pixels (unmeasured_px). The three are counted apart
 * (ft_dbw_counts) but drawn with the one marking.
 * A window with no data at all is refused. */
#ifndef FT_DB_WINDOW_H
#define FT_DB_WINDOW_H

#include <stddef.h>
#include <stdint.h>

#include "core/io.h"
#include "terrain/terrain.h"
#include "terrain/terrain_db.h"

/* What the scene asks for. A NaN centre coordinate: the middle of the data
 * tiles of that level (tile-aligned: their bounding box of whole tiles). */
typedef struct ft_dbw_desc {
    uint32_t level;
    uint32_t side_samples;
    double centre_lat_deg, centre_lon_deg;
} ft_dbw_desc;

/* The window the probe placed; the caller keeps it until the load. */
typedef struct ft_dbw {
    ft_tdb_header hdr;
    uint32_t level;
    uint32_t side;     /* samples per side */
    int64_t i0, j0;    /* level lattice index of window sample (0,0) */
    uint64_t nx, ny;   /* lattice samples of the level (i < nx, j < ny) */
} ft_dbw;

/* What the load found, for the report and the tests. */
typedef struct ft_dbw_counts {
    uint32_t tiles_read;       /* data tiles read (the window's level and coarser ones) */
    uint32_t tiles_no_data;    /* tiles (any level read) listed as no data or not at all */
    uint64_t coarser_samples;  /* drawn from a coarser level and marked */
    uint64_t missing_samples;  /* no level has data: drawn at fill_m and marked */
    uint64_t filled_samples;   /* void-filled by the database, marked */
    float fill_m;              /* the floor missing samples are drawn at */
} ft_dbw_counts;

/* Reads the header, checks the level against it and places the window;
 * fills t's header fields (no heights) and derives its frame. */
ft_status ft_dbw_probe(const ft_reader_at *r, const ft_dbw_desc *d, ft_dbw *w, ft_terrain *t,
                       ft_error *err);

/* FT_POOL_DEM_IO bytes of the load: the index; and the staging: one tile's
 * heights and void bits, and (when the database has a coarser level) a grid
 * of ((side - 1) / 2 + 3)^2 heights of a coarser level around the window. */
size_t ft_dbw_index_bytes(const ft_dbw *w);
size_t ft_dbw_staging_bytes(const ft_dbw *w);

/* A rect of one level's lattice samples (level-l indices, row 0 = south)
 * and where its heights and void bits (rect-local, bit k of sample k, zeroed
 * by the caller) go; and, when dev_m is not NULL, each sample's cell dev
 * (terrain_db.h: of the level-l cell whose south-west corner it is): the
 * level's own tile's value, 0 on level 0 (the finest data itself), and
 * FT_TDB_DEV_NONE where the sample lacks this level's data (no tile, no
 * data in it, outside the lattice: its height is a coarser level's), so a
 * cell bounds |truth - this level's bilinear surface| by its south-west
 * corner's value only when none of its 4 corners is NONE (dev_m needs a
 * tile cache made with its dev). */
typedef struct ft_dbw_rect {
    uint32_t level;
    int64_t i0, j0;
    uint32_t w, h;
    float *heights_m; /* w * h */
    uint8_t *void_bits; /* (w * h + 7) / 8 */
    float *dev_m;       /* w * h, or NULL */
} ft_dbw_rect;

/* Decoded tiles kept between reads, least recently used replaced: one
 * slot is enough for a window read once; a cache that reads strips next to
 * each other keeps more. Slots are T*T heights and their void bits, and
 * with_dev T*T dev bounds more (read on levels >= 1), in caller memory
 * (ft_tdb_tile_cache_bytes). */
#define FT_TDB_TILE_CACHE_MAX 64u
typedef struct ft_tdb_tile_slot {
    uint32_t level, tx, ty;
    int filled;
    uint64_t stamp;
    float *heights_m;
    uint8_t *void_bits;
    float *dev_m; /* with_dev: T*T (level 0: untouched), else NULL */
    ft_tdb_tile tile;
} ft_tdb_tile_slot;

typedef struct ft_tdb_tile_cache {
    ft_tdb_tile_slot slot[FT_TDB_TILE_CACHE_MAX];
    uint32_t slots;
    int with_dev;
    size_t tile_n;
    uint64_t clock, hits, reads;
} ft_tdb_tile_cache;

size_t ft_tdb_tile_cache_bytes(const ft_tdb_header *h, uint32_t slots, int with_dev);
/* slots is capped at FT_TDB_TILE_CACHE_MAX; mem holds the bytes above. */
void ft_tdb_tile_cache_init(ft_tdb_tile_cache *tc, const ft_tdb_header *h, uint32_t slots,
                            int with_dev, void *mem);

/* Bytes of the grid of a coarser level ft_dbw_read_rect needs for a rect
 * of w x hgt samples at `level` (0 at the last level). */
size_t ft_dbw_rect_coarse_bytes(const ft_tdb_header *h, uint32_t level, uint32_t w,
                                uint32_t hgt);

/* Reads the rect by the window's rule: the level's data, else the nearest
 * coarser level's bilinear value, marked; samples no level has stay
 * FT_TDB_NODATA_M (*remaining counts them: the caller floors them). Tiles
 * come through the tile cache (each read with its checks), "no data" tiles
 * from the index alone. */
ft_status ft_dbw_read_rect(const ft_tdb *db, const ft_dbw_rect *r, ft_tdb_tile_cache *tc,
                           float *coarse_m, size_t coarse_bytes, ft_dbw_counts *c,
                           uint64_t *remaining, ft_error *err);

/* Samples no level has (FT_TDB_NODATA_M after ft_dbw_read_rect) drawn at
 * fill_m and marked in void_bits (bit k of sample k); returns how many. */
uint64_t ft_dbw_floor_missing(float *heights_m, size_t n, float fill_m, uint8_t *void_bits);

/* Opens the database (index into io, checked), reads the window's tiles one
 * by one into t->heights_m (bound, side*side) and marks t->void_bits (bound,
 * zeroed); sets void_count and the height range. io holds
 * ft_dbw_index_bytes + ft_dbw_staging_bytes. Does not build pyramids. */
ft_status ft_dbw_load(const ft_reader_at *r, const ft_dbw *w, ft_terrain *t, void *io,
                      size_t io_bytes, ft_dbw_counts *counts, ft_error *err);

#endif
