/* clip_source.h - height sources for the clipmap cache (clip_cache.h).
 *
 * Over the runtime's terrain (ft_terrain in memory): the lattice is the
 * terrain's samples (lattice_i0 = lattice_j0 = 0); level l sample (a, b) is
 * the terrain's sample (a * 2^l, b * 2^l), point-sampled as the terrain
 * database's coarser levels are (so a lattice point has one height on every
 * level). A sample off the terrain takes the height of the nearest edge
 * sample and is marked, as is every sample the DEM void-filled; the methods
 * draw nothing off the terrain (data_* is the terrain's extent), so the
 * clamped heights only serve the coarse samples a level's box reaches past
 * the edge. */
#ifndef FT_CLIP_SOURCE_H
#define FT_CLIP_SOURCE_H

#include "terrain/clip_cache.h"
#include "terrain/db_window.h"
#include "terrain/terrain.h"
#include "terrain/terrain_db.h"

/* t must stay valid (and its heights unchanged) while the source is used. */
void ft_clip_source_terrain(ft_clip_source *out, const ft_terrain *t);

/* Over a terrain database (.ftd, open): cache level l is database level
 * base_level + l, and the cache's level-0 lattice is base_level's, so
 * lattice_i0/j0 (the window's first sample at base_level) put the cache in
 * the runtime terrain's frame. A sample is read by the window's rule
 * (db_window.h: the level's data, else the nearest coarser level's bilinear
 * value, else the floor fill_m; all but the first marked), tile by tile
 * through the staging with every tile's checks; the data box is the whole
 * lattice of base_level (missing data is drawn, marked, never a hole), and
 * when every level the cache reads closes around the globe
 * (ft_tdb_lattice_closes) it has no east or west edge: the levels wrap at
 * the antimeridian (data_i_* = -+FT_CLIP_DATA_UNBOUNDED). */
#define FT_CLIP_DATA_UNBOUNDED ((int64_t)1 << 40)
typedef struct ft_clip_db_source {
    const ft_tdb *db;
    uint32_t base_level;
    float fill_m;
    ft_tdb_tile_cache tiles; /* tile_slots decoded tiles */
    float *coarse_m;         /* the coarser-level grid of one update */
    size_t coarse_bytes;
    uint8_t *bits; /* (update_samples_max + 7) / 8 */
    uint32_t update_samples_max;
    int wraps;            /* every level read wraps in longitude */
    ft_dbw_counts counts; /* summed over every read */
} ft_clip_db_source;

/* FT_POOL_CLIP bytes of the source for the cache's description: tile_slots
 * decoded tiles (1..FT_TDB_TILE_CACHE_MAX), one update's coarser grid and
 * marks. */
size_t ft_clip_db_source_bytes(const ft_tdb_header *h, uint32_t tile_slots,
                               const ft_clip_desc *d);
void ft_clip_db_source_plan(const ft_tdb_header *h, uint32_t tile_slots, const ft_clip_desc *d,
                            ft_arena *a);
/* Takes its memory from FT_POOL_CLIP; src->ctx is s, which must outlive it. */
ft_status ft_clip_source_db(ft_clip_source *out, ft_clip_db_source *s, const ft_tdb *db,
                            uint32_t base_level, int64_t lattice_i0, int64_t lattice_j0,
                            float fill_m, uint32_t tile_slots, const ft_clip_desc *d,
                            ft_arena *a, ft_error *err);

#endif
