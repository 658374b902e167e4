/* import_dev.h - the importer's deviation pass: each coarse tile's dev_m,
 * how far the finest data depart from that level's bilinear surface
 * (the rule and its proof in src/terrain/terrain_db.h).
 *
 * Runs after a level k >= 1 is written, level by level upwards, so a
 * level's pass reads its own tiles and neighbours and the finished level
 * k-1 (heights and dev) from the file being written, and rewrites each data
 * tile's dev and crc in place. Offline: buffers come from malloc. */
#ifndef FT_IMPORT_DEV_H
#define FT_IMPORT_DEV_H

#include <stdint.h>
#include <stdio.h>

#include "terrain/terrain_db.h"

/* Histogram of the bounds, for quantiles: FT_DEV_HIST_BINS bins of
 * FT_DEV_HIST_STEP_M and one past them. */
#define FT_DEV_HIST_BINS 16384u
#define FT_DEV_HIST_STEP_M 0.1

typedef struct ft_dev_stats {
    uint64_t bound_cells;   /* cells with data at 4 corners: a bound of |T - B_k| */
    uint64_t partial_cells; /* a corner without data: a bound of |T - r| (finer points) */
    uint64_t none_cells;    /* FT_TDB_DEV_NONE: finer data, no bound */
    uint64_t coarser_cells; /* FT_TDB_DEV_COARSER: a coarser level's truth */
    double sum_m;
    float max_m;
    uint64_t hist[FT_DEV_HIST_BINS + 1u];
} ft_dev_stats;

typedef struct ft_dev_pass {
    FILE *f;
    const char *path;
    const ft_tdb_header *hdr; /* tile size, lattice, level boxes */
    ft_tdb_entry *entries;    /* the index being written; dev tiles' crcs updated */
    const uint8_t *subtree_data; /* per entry: it or a tile under it has data */
    uint32_t T;
    float *hk;       /* (T+1)^2: the level's heights with the east and north apron */
    float *hc;       /* (2T+1)^2: level k-1 under the tile, with its apron */
    float *dc;       /* (2T)^2: level k-1 cells' dev (level 0: 0 or COARSER) */
    double child_avg_m[2][2]; /* the 2x2 level k-1 tiles' avg_m (partial cells' reference) */
    float *tile_h;   /* T*T: one decoded tile */
    float *tile_dev; /* T*T */
    float *dev_out;  /* T*T: the tile's new dev */
    uint8_t *bits;   /* T*T/8 */
    double *measured; /* T*T: largest |v_m - B_k| over a cell's level-m points */
    uint64_t *seen;   /* T*T: level-m points with data in each closed cell */
    double *exact;    /* T*T: the exact largest |T - B_k| where measured, else -1 */
    uint8_t *bytes;  /* one encoded tile */
    size_t bytes_cap;
} ft_dev_pass;

/* 1 on success (0: out of memory). */
int ft_dev_pass_init(ft_dev_pass *P, FILE *f, const char *path, const ft_tdb_header *hdr,
                     ft_tdb_entry *entries, const uint8_t *subtree_data);
void ft_dev_pass_free(ft_dev_pass *P);

/* Computes and rewrites the dev of every data tile of level k (>= 1);
 * accumulates into *s. 1 on success; 0 with a message on stderr. */
int ft_dev_pass_level(ft_dev_pass *P, uint32_t k, ft_dev_stats *s);

/* The q-quantile (0..1) of the bounds in s, to the histogram's step (the
 * bin's upper edge: never under). */
double ft_dev_stats_quantile(const ft_dev_stats *s, double q);

#endif
