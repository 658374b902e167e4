/* clip_cache.h - nested clipmap levels around the eye, filled from a height
 * source a strip at a time (no GL here: the caller uploads).
 *
 * Lattice: the cache works on the source's level-0 lattice of integer
 * sample indices (i east, j north). Level l sample (a, b) is level-0 sample
 * (a * 2^l, b * 2^l); its world position is
 *   x = origin_world_x_m + (a * 2^l - src.lattice_i0) * cell_x_m
 * (y alike), so a source over the runtime's terrain (lattice_i0 = 0) or over
 * a database window (lattice_i0 = the window's first sample) puts level-0
 * sample (lattice_i0, lattice_j0) at the terrain's sample (0, 0).
 *
 * Levels: `levels` levels of side x side samples each (side a power of two),
 * level l spacing 2^l samples of level 0. Each level has a WANTED box, the
 * side x side samples around the eye (origin even in level-l samples, so its
 * edges fall on level l+1 samples, and inside level l+1's wanted box with at
 * least side / 4 - 1 level-l+1 samples to spare on each side), and a VALID
 * box, the rectangle of level-l samples whose heights are resident. Sample
 * (a, b) of level l lives at texel (a mod side, b mod side) of the level's
 * side x side texture (toroidal: a box that moves by dx columns rewrites only
 * the dx columns it enters, in the texel columns the leaving ones held).
 *
 * Updates: ft_clip_recentre moves the wanted boxes and shrinks each valid
 * box to its part inside the new wanted box (those texels are untouched);
 * ft_clip_next_update produces the next piece of work (coarsest level first,
 * so a finer level's valid box stays inside the coarser one's): a strip next
 * to the valid box, an even number of samples wide, at most
 * update_samples_max samples read from the source into the cache's staging,
 * as one texel rectangle that does not wrap. The caller uploads it (a
 * sub-image upload) and calls ft_clip_commit. A strip is filled in chunks
 * (rows of its columns, split where the texels wrap) and joins the valid box
 * when its last chunk is committed: first the east and west strips over the
 * valid box's rows, then the north and south strips over the whole width (an
 * empty valid box starts as the wanted box's southern edge, zero rows high,
 * and the whole box is one north strip). So a valid box is always a
 * rectangle with even edges that only grows until the eye moves again; a
 * level that jumps by side or more is drawn again only when refilled whole.
 * Nothing here waits or allocates after init; the caller runs updates as
 * jobs in the frame's spare time and draws each level over its valid box.
 *
 * Stats say how far behind the cache is: levels whose valid box is not their
 * wanted box, and the samples still to read. */
#ifndef FT_CLIP_CACHE_H
#define FT_CLIP_CACHE_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "core/mem_budget.h"

#define FT_CLIP_LEVELS_MAX 16u
#define FT_CLIP_SIDE_MIN 16u
#define FT_CLIP_SIDE_MAX 4096u

/* Reads level `level` samples [i0, i0 + w) x [j0, j0 + h) (level-l indices)
 * into heights_m (row-major, w per row, row 0 = south); when marks is not
 * NULL, one byte per sample: 0 measured, 1 not measured (void-filled, from a
 * coarser level, or no data anywhere); when dev_m is not NULL, per sample a
 * bound of how far the source's finest data depart from this level's
 * bilinear surface over the cell whose south-west corner it is, valid when
 * none of the cell's 4 corners is negative (negative: not known, or the
 * sample lacks this level's own data). A source gives a height for every
 * sample it is asked for (outside its data: the rule it documents, marked). */
typedef ft_status (*ft_clip_read_fn)(void *ctx, uint32_t level, int64_t i0, int64_t j0,
                                     uint32_t w, uint32_t h, float *heights_m, uint8_t *marks,
                                     float *dev_m, ft_error *err);

typedef struct ft_clip_source {
    ft_clip_read_fn read;
    void *ctx;
    uint32_t levels;            /* levels it can give: 0 .. levels - 1 */
    int64_t lattice_i0, lattice_j0; /* level-0 sample at the terrain's sample (0, 0) */
    /* level-0 samples that hold data, inclusive (the methods draw no
     * further): [data_i_lo, data_i_hi] x [data_j_lo, data_j_hi] */
    int64_t data_i_lo, data_i_hi, data_j_lo, data_j_hi;
} ft_clip_source;

typedef struct ft_clip_desc {
    uint32_t side;               /* samples per level side: power of two, MIN..MAX */
    uint32_t levels;             /* 1 .. min(FT_CLIP_LEVELS_MAX, source levels) */
    uint32_t update_samples_max; /* samples one update reads (>= 2 * side) */
    int keep_bounds;             /* keep bounds of what is resident: heights
                                    (ft_clip_clearance_m) and the error against
                                    the source's finest data
                                    (ft_clip_blocks_visit): a CPU copy of every
                                    level's heights and cell deviations,
                                    levels x 2 side^2 floats more */
} ft_clip_desc;

/* Height bounds: per level, blocks of FT_CLIP_BOUND_BLOCK^2 texels, each
 * with the range of its texels and of FT_CLIP_BOUND_APRON texels around it
 * (toroidally), so a block's range also holds every triangle that reaches
 * one sample past it and every transition vertex's blend with the coarser
 * level (whose samples are this level's, point-sampled, within 2). */
#define FT_CLIP_BOUND_BLOCK 16u
#define FT_CLIP_BOUND_APRON 2u

/* Where the level-0 lattice sits in the world: sample (lattice_i0 + i,
 * lattice_j0 + j) at (origin_x_m + i cell_x_m, origin_y_m + j cell_y_m). */
typedef struct ft_clip_world {
    double origin_x_m, origin_y_m, cell_x_m, cell_y_m;
} ft_clip_world;

/* A rectangle of level-l samples, half-open: [i0, i1) x [j0, j1); empty when
 * i1 <= i0 or j1 <= j0. */
typedef struct ft_clip_box {
    int64_t i0, j0, i1, j1;
} ft_clip_box;

typedef struct ft_clip_level {
    ft_clip_box want;  /* side x side around the eye */
    ft_clip_box valid; /* resident samples (a sub-box of want while it moves) */
    uint64_t samples_outstanding; /* samples of want not yet resident */
} ft_clip_level;

/* One piece of work, read and ready to upload: level `level`'s samples box
 * (no wrap inside it) go to texels [tex_x, tex_x + w) x [tex_y, tex_y + h). */
typedef struct ft_clip_update {
    uint32_t level;
    ft_clip_box box;
    uint32_t tex_x, tex_y, w, h;
    const float *heights_m; /* w * h, the cache's staging, valid until the next call */
    const uint8_t *marks;   /* w * h */
    const float *dev_m;     /* w * h cell deviations (keep_bounds), else NULL */
} ft_clip_update;

typedef struct ft_clip_stats {
    uint64_t updates;              /* committed */
    uint64_t samples_uploaded;
    uint64_t recentres_moved;      /* recentres that moved some wanted box */
    uint32_t levels_behind;        /* now: levels whose valid box != wanted box */
    uint64_t samples_outstanding;  /* now: over all levels */
    uint32_t levels_behind_max;    /* high-water marks since init */
    uint64_t samples_outstanding_max;
} ft_clip_stats;

typedef struct ft_clip_cache {
    ft_clip_desc desc;
    ft_clip_source src;
    ft_clip_level level[FT_CLIP_LEVELS_MAX];
    float *staging_m;   /* update_samples_max, in FT_POOL_CLIP */
    uint8_t *marks;     /* update_samples_max, in FT_POOL_CLIP */
    ft_clip_stats stats;
    /* per level: the strip being filled (empty: none) and the next chunk's
     * first sample */
    ft_clip_box strip[FT_CLIP_LEVELS_MAX];
    int64_t cursor_i[FT_CLIP_LEVELS_MAX], cursor_j[FT_CLIP_LEVELS_MAX];
    int pending;        /* an update was produced and not committed */
    ft_clip_update last; /* the update produced last */
    /* keep_bounds: each level's texels as uploaded and their cells'
     * deviations (+INF where the source gave none), and per block its
     * range and errors (ft_clip_block_bound) */
    float *dev_staging_m;                    /* update_samples_max */
    float *mirror_m[FT_CLIP_LEVELS_MAX];     /* side^2 */
    float *dev_mirror_m[FT_CLIP_LEVELS_MAX]; /* side^2 */
    float *block_lo_m[FT_CLIP_LEVELS_MAX];   /* (side / BLOCK)^2 */
    float *block_hi_m[FT_CLIP_LEVELS_MAX];
    float *block_err_m[FT_CLIP_LEVELS_MAX];
    float *block_morph_m[FT_CLIP_LEVELS_MAX];
    float *block_dev_m[FT_CLIP_LEVELS_MAX];
} ft_clip_cache;

/* Checks the description (the message names the scene key: clipmap.side,
 * clipmap.levels, clipmap.update_samples_max) and plans the staging in FT_POOL_CLIP. */
ft_status ft_clip_plan(const ft_clip_desc *d, const ft_clip_source *src, ft_arena *a,
                       ft_error *err);
/* Takes the staging; every level starts empty (valid boxes empty). */
ft_status ft_clip_init(ft_clip_cache *c, const ft_clip_desc *d, const ft_clip_source *src,
                       ft_arena *a, ft_error *err);

/* The eye in level-0 lattice samples (fractional: i, j as world x, y over the
 * cell size plus lattice_i0, lattice_j0). Moves the wanted boxes; returns 1
 * when one moved. No source reads. */
int ft_clip_recentre(ft_clip_cache *c, double eye_i, double eye_j);

/* Reads the next update into the staging: *have = 0 when every level is
 * current. An error is the source's (the cache is unchanged by it). */
ft_status ft_clip_next_update(ft_clip_cache *c, ft_clip_update *u, int *have, ft_error *err);

/* The caller has uploaded u: its samples are resident. */
void ft_clip_commit(ft_clip_cache *c, const ft_clip_update *u);

/* Texel of level-l sample index a: a mod side, in [0, side). */
uint32_t ft_clip_texel(const ft_clip_cache *c, int64_t a);

/* The finest level whose valid box equals its wanted box (levels when none). */
uint32_t ft_clip_finest_current(const ft_clip_cache *c);

/* keep_bounds: a lower bound of the distance from eye_m (world) to any
 * surface drawn from the resident samples (every level's valid box, block
 * by block: ft_camera_box_distance_m with the curvature drop curv_k_per_m),
 * and the horizontal box and height range of all of it (for a far plane).
 * Returns 0 when nothing is resident (or bounds are not kept). At most
 * levels x (side / BLOCK)^2 x 4 boxes; no memory. */
int ft_clip_clearance_m(const ft_clip_cache *c, const ft_clip_world *w, const double eye_m[3],
                        double curv_k_per_m, double *clearance_m, double box_min_m[2],
                        double box_max_m[2], double *zmin_m, double *zmax_m);

/* keep_bounds: the highest height of any resident block piece that meets
 * the world box [x0, x1] x [y0, y1] (every level's: a surface drawn there
 * from any of them stays under it); -INFINITY when none does. */
double ft_clip_max_height_in(const ft_clip_cache *c, const ft_clip_world *w, double x0_m,
                             double y0_m, double x1_m, double y1_m);

/* keep_bounds: what a resident block of level l bounds, over the piece
 * of its samples that is resident (the toroidal texels of one block hold at
 * most 2 x 2 pieces of the lattice).
 *  - err_m: over every cell with a corner in the piece, how far the
 *    surface drawn from level l's samples (2 triangles a cell, or the
 *    stitch rule's 3: any triangle of points on the cell's bilinear
 *    surface) departs from the source's finest data: dev + |h00 + h11 -
 *    h10 - h01| / 4 (the bilinear surface departs from a triangle of its
 *    points by at most a quarter of the twist), the largest over the cells
 *    of the block and its apron; +INF when a cell's deviation is unknown.
 *  - morph_m: the largest |h - H(l + 1)| at the level's samples of the
 *    block and apron, H(l + 1) the next level's bilinear surface as its
 *    texels hold it; a vertex blended between the two moves by at most that
 *    (0 on the coarsest level).
 * Rounding: err_m and morph_m are rounded up to float and include 4 float
 * steps of the block's largest height (the shader's bilinear and blend). */
typedef struct ft_clip_block_bound {
    ft_clip_box box; /* level-l samples, resident */
    float lo_m, hi_m; /* the block's height range, apron included */
    float err_m, morph_m;
    /* how far the finest data depart from level l's bilinear surface
     * itself (no triangles: the deviation without the twist), the largest
     * over the cells of the block and its apron, rounded as err_m; +INF
     * when a cell's deviation is unknown */
    float dev_m;
} ft_clip_block_bound;

typedef void (*ft_clip_block_fn)(void *ctx, uint32_t level, const ft_clip_block_bound *b);

/* Calls fn for every resident piece of level l's blocks; returns how many
 * (0 without keep_bounds). At most (side / BLOCK)^2 x 4 calls. */
uint64_t ft_clip_blocks_visit(const ft_clip_cache *c, uint32_t level, ft_clip_block_fn fn,
                              void *ctx);

/* keep_bounds: the same for the one cell of level l whose south-west
 * corner is sample (a, b) (box [a, a + 1) x [b, b + 1)): lo/hi its four
 * corners' range (a blended vertex moves by at most morph_m from it),
 * err_m = its deviation + a quarter of its twist, morph_m over its four
 * corners; both rounded as above. 0 (out untouched) when a corner is not
 * resident. */
int ft_clip_cell_bound(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b,
                       ft_clip_block_bound *out);

/* keep_bounds: the heights the source's finest data (their bilinear
 * surface) take over cell (a, b) of level l (south-west corner sample (a, b),
 * texels as the mirror holds them, resident or not: the caller asks for
 * cells whose four corners are resident): the range of its 4 corners
 * widened by the deviation of the finest data from the level's bilinear
 * surface there (clip_source), and by 4 float steps of its largest height (a
 * shader's subtraction), rounded outward to float. -INF / +INF when a
 * corner's deviation is unknown. No residency check, no memory. */
void ft_clip_cell_range(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b, float *lo_m,
                        float *hi_m);

/* 1 when level l's valid box equals its wanted box (and it has one). */
int ft_clip_level_current(const ft_clip_cache *c, uint32_t l);

#endif
