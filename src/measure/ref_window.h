/* ref_window.h - the error metric's truth over a terrain database: a window
 * of the database that follows the eye.
 *
 * A scene over a .ftd window draws its terrain from that window (fixed at
 * init), and a method with a cache (clipmap) goes on past it. The truth is
 * the finest data the database has wherever the eye goes, so the reference
 * ray caster reads its own window of the database: the scene window's level,
 * metric.truth_side_samples per side, in the scene's world frame (the database lattice laid out
 * linearly, as the cache lays it out), recentred when the eye moves on.
 *
 * Where it sits is a function of the eye alone (the same eye always gets
 * the same window, whatever the flight before): its middle sample is the
 * eye's lattice position rounded to a multiple of FT_REF_WINDOW_STEP_DIV-th
 * of the side, so the eye is always at least 3/8 of the side inside it.
 * Samples are read by the window's rule (db_window.h: the level's data,
 * else the nearest coarser level's bilinear value, else the scene window's
 * floor), and the max-mip pyramid is rebuilt after each move.
 *
 * Memory: the heights, their pyramid, a tile cache of FT_REF_WINDOW_TILE_SLOTS
 * slots and the coarse-level grid of one read, all in the caller's block
 * (ft_ref_window_bytes), taken once; a move reads with pread and allocates
 * nothing. A move costs a window's load (a 1201^2 window: about 0.1 s). */
#ifndef FT_REF_WINDOW_H
#define FT_REF_WINDOW_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "terrain/db_window.h"
#include "terrain/terrain.h"

#define FT_REF_WINDOW_STEP_DIV 4u
#define FT_REF_WINDOW_TILE_SLOTS 4u

typedef struct ft_ref_window {
    ft_terrain t;            /* the truth's terrain (heights, pyramid, frame) */
    const ft_terrain *scene; /* the scene's window: its database, level, frame */
    ft_tdb_tile_cache tiles;
    float *coarse_m;
    size_t coarse_bytes;
    int64_t i0, j0; /* lattice index of sample (0, 0); loaded = 1 once read */
    int loaded;
    uint64_t loads;  /* reads of a whole window, the first included */
    ft_dbw_counts counts; /* of the last load */
} ft_ref_window;

/* Bytes of the block for a scene window of side samples at level of the
 * database with header h. */
size_t ft_ref_window_bytes(const ft_tdb_header *h, uint32_t level, uint32_t side);

/* Lays a window of side samples out in mem (bytes from ft_ref_window_bytes);
 * nothing read. */
ft_status ft_ref_window_init(ft_ref_window *w, const ft_terrain *scene, uint32_t side, void *mem,
                             size_t bytes, ft_error *err);

/* Moves the window to where eye_m (world, the scene's frame) puts it and
 * reads it when that changed (*moved = 1). */
ft_status ft_ref_window_follow(ft_ref_window *w, const double eye_m[3], int *moved,
                               ft_error *err);

#endif
