/* bintree_cache.h - the bintree over the clipmap cache (bintree.heights =
 * clipmap): the same tiles and template as over the window (bintree.h), on
 * the cache's level-0 lattice instead of one grid, with each tile's heights
 * read from the cache level whose spacing is its template's.
 *
 * Domain: a square of D = 2^p level-0 samples a side, D = side / 2 samples
 * of the coarsest cache level Lc, its origin o a multiple of D / 2 nearest
 * the eye among those that keep it inside the coarsest level's usable box
 * (below), kept while it stays there: it moves about every D / 2 of travel
 * (the roots change then). Tile coordinates are level-0 samples relative
 * to o (integers below 2^24, exact in a shader's float).
 *
 * Tree and tables: as bintree.h, a diamond of tree level t has square side
 * s = D >> (t / 2). The template (2k bisections) puts an even diamond's
 * tile vertices on the lattice of spacing s / 2^k and an odd one's on
 * s / 2^(k+1): that spacing is 2^m level-0 samples, m the diamond's table
 * level, and its tiles read their heights from cache level min(m, Lc)
 * (levels are point samples of each other, so a vertex shared by tiles of
 * different levels has one height: no cracks). Tables m > Lc are virtual:
 * their vertices are every 2^(m - Lc)-th sample of level Lc. The finest
 * tiles are even with m = 0 (the leaves).
 *
 * Error (against the finest data, the database's bilinear surface):
 *  - a tile on level m <= Lc: its template triangles are half-cells of level
 *    m (even) or triangles over two half-cells with their hypotenuse's
 *    midpoint a sample off the plane (odd), so it departs from level m's
 *    bilinear surface by at most |D| / 4 of a cell (D its twist) plus the
 *    second difference |h(-1) + h(+1) - 2 h(0)| / 2 at a sample, and the
 *    finest data depart from that surface by the cell's deviation
 *    (clip_cache.h): own(cell) = |D| / 4 + dev, own(sample) = that second
 *    difference, both maxed over blocks of 2^k x 2^k cells of the level;
 *  - a virtual tile: the relief of the finest data under it (its surface
 *    and the truth both lie in that range).
 * Each level's blocks are kept by absolute block index (slots of
 * (side / 2^k + 1)^2, tagged), folded in from the cache's CPU mirror for the
 * cells that became resident since the last update. Each frame a pyramid
 * takes per block the max over its own and every finer level's resident
 * blocks under it (cum), and the min/max of the finest data.
 *
 * Saturation without tables of diamonds: a diamond's error is the max of
 * cum over the blocks of table lambda under its closure R (half-side 1.5 s
 * around its split vertex when even, s when odd; cut to the domain), where
 * lambda is its table when even and the next one up (its parents') when
 * odd: cum_e there plus the second differences of the finer levels (an odd
 * tile of table m reads those of level m, which lie below lambda = m + 1),
 * and above Lc at least the blocks' relief. A child's R lies in both its
 * parents' and its lambda is not larger, and block grids nest, so errors
 * (and the boxes of R x the height range of the same blocks) nest: Q
 * (bintree.h, without geomorphing) of a child is at most its parents'.
 *
 * Splitting into a level: a diamond may split only when its region S lies
 * in U, the usable box of its children's level: U of the coarsest level is
 * its valid box shrunk by 2 samples (a vertex's normal reads its
 * neighbours), and U of a finer level l is its own valid box so shrunk, cut
 * to U of level l + 1 shrunk by 3 * 2^(l + k + 1) level-0 samples. S is an
 * even diamond's closure, an odd one's the box of its two parents'
 * closures, cut to the domain. A parent's S holds its child's except for an
 * odd diamond's even children, whose level is one finer and whose S lies
 * within 1.5 s of theirs: the margin between the U's covers that step. So
 * a child may split only if both its parents may, with the levels resident
 * or lagging (while a level is refilled its U is what is resident). A
 * diamond that may not split is drawn as it is and its tile's own error
 * (over its own blocks) joins the achieved bound (as a leaf's does over the
 * window).
 *
 * The data's edge (a single grid: the source's data box; a database's
 * lattice has none in practice): the shader clamps a vertex's position
 * into the box and keeps the height the cache holds for its lattice point,
 * which the terrain source clamps the same way (clip_source.h). Where the
 * box's edges lie on a tile's lattice (2^m divides them) every template
 * triangle lies on one side of an edge, or is clamped onto exactly its
 * part inside, so what is drawn inside is the tile's own surface; a tile
 * across the edge on a coarser lattice must split (or reports an unbounded
 * bound where it may not).
 *
 * Culling: a tile's box is its bounding box and the range of the samples
 * its level and the finer ones hold under it (what can be drawn there; the
 * finest data's range is unbounded where their deviation is unknown).
 *
 * No geomorphing (bintree.morph = 0 over the cache): a split is immediate. */
#ifndef FT_BINTREE_CACHE_H
#define FT_BINTREE_CACHE_H

#include <stdint.h>

#include "core/ft_status.h"
#include "core/mem_budget.h"
#include "core/view_scale.h"
#include "lod/bintree.h"
#include "terrain/clip_cache.h"

/* tables above the coarsest cache level: D / 2^(Lc + k) = side / 2^(k+1) */
#define FT_BTC_TABLES_MAX (FT_CLIP_LEVELS_MAX + 12u)

/* One table's blocks of 2^k x 2^k cells of its data level (virtual tables:
 * 2^(m - Lc + k) cells of Lc), by absolute block index: n^2 slots, a slot
 * holding block (bx, by) when its tag says so. */
typedef struct ft_btc_blocks {
    uint32_t n;            /* slots a side: the blocks a wanted box can touch */
    int64_t *tag;          /* n^2 x 2: the block whose own values a slot holds */
    int64_t *ctag;         /* n^2 x 2: the block whose cum values a slot holds */
    float *own_e_m;        /* max |D| / 4 + dev over its folded cells */
    float *own_s_m;        /* max second difference / 2 over its folded samples */
    float *lo_m, *hi_m;    /* the finest data's range over its folded cells */
    float *cum_e_m;        /* own_e maxed with the usable finer levels' (per frame) */
    float *cum_s_m;        /* the usable finer levels' own_s only: a tile of this
                              level whose vertices are this level's needs no second
                              difference of its own samples unless it is odd, and
                              an odd diamond looks up its parents' table */
    float *cum_lo_m, *cum_hi_m;
    float *tlo_m, *thi_m;  /* its samples' own range (what is drawn: never unbounded) */
    float *cum_tlo_m, *cum_thi_m; /* with the finer levels' */
} ft_btc_blocks;

typedef struct ft_bt_cache {
    uint32_t k, side, levels; /* template k, the cache's side and levels */
    uint32_t top;             /* Lc = levels - 1 */
    uint32_t root_m;          /* the roots' table: D = 2^(root_m + k) */
    uint32_t domain_log2;     /* p: D = 2^p level-0 samples */
    int64_t origin[2];        /* o, level-0 lattice samples */
    int origin_set;
    int64_t lattice0[2];      /* the terrain's sample (0, 0) on the lattice */
    int64_t data[4];          /* the source's data box: i_lo, j_lo, i_hi, j_hi (inclusive) */
    uint32_t data_exact_m;    /* the largest table whose lattice holds the box's edges */
    double cell_m[2];
    ft_btc_blocks blk[FT_BTC_TABLES_MAX];
    /* per cache level: the cells folded so far (the valid box at the last update) */
    ft_clip_box folded[FT_CLIP_LEVELS_MAX];
    /* per cache level: where a diamond whose children read it may split
     * (closed boxes, level-0 samples: x0, y0, x1, y1; empty when x1 < x0),
     * and the finest level with a non-empty one */
    int64_t usable[FT_CLIP_LEVELS_MAX][4];
    uint32_t finest_usable;
    ft_bt_tile *tiles;        /* tiles_max; coordinates relative to origin */
    uint32_t tiles_max;
    uint64_t cells_folded;    /* since init */
} ft_bt_cache;

/* FT_POOL_METHOD bytes for the tables and the tile list. */
void ft_btc_plan(ft_arena *a, uint32_t side, uint32_t levels, uint32_t k, uint32_t tiles_max);

/* Checks side >= 12 * 2^k + 8 (message names clipmap.side and
 * bintree.template_k) and tiles_max, and takes the memory. The cache must
 * keep its bounds (clip_cache.h keep_bounds). */
ft_status ft_btc_init(ft_bt_cache *bc, const ft_clip_cache *c, const ft_terrain *t, uint32_t k,
                      uint32_t tiles_max, ft_arena *a, ft_error *err);

/* After the cache's updates of a frame: folds in the newly resident cells,
 * rebuilds the pyramid and places the domain around the eye (level-0
 * lattice, fractional). Bounded: the cells of the boxes' growth and the
 * slots of every level. */
void ft_btc_update(ft_bt_cache *bc, const ft_clip_cache *c, double eye_i, double eye_j);

/* The table level m of a tile (or diamond) of tree level t: the spacing of
 * its template's vertices is 2^m level-0 samples. */
uint32_t ft_btc_table_of(const ft_bt_cache *bc, uint32_t tree_level);

/* Error (m) and box of the diamond with split vertex c (relative to the
 * origin) at tree level t: lo/hi in metres relative to the terrain's sample
 * (0, 0) (x, y, z). +INF when a block under it is not known. */
double ft_btc_diamond(const ft_bt_cache *bc, uint32_t tree_level, const int32_t c[2],
                      double lo[3], double hi[3]);

/* Whether that diamond may split (above). */
int ft_btc_may_split(const ft_bt_cache *bc, uint32_t tree_level, const int32_t cv[2]);

/* 1 when the eye's surroundings cannot be drawn from level 0: the eye
 * (level-0 lattice, fractional) is not inside level 0's usable box shrunk
 * by the largest region of a diamond whose children read level 0
 * (2^(k+2) samples: an odd diamond's parents' closures). */
int ft_btc_eye_coarser(const ft_bt_cache *bc, double eye_i, double eye_j);

/* Selects tiles into bc->tiles for target tau (view from
 * ft_bt_view_from_camera: its origin is the terrain's sample (0, 0)); the
 * stats as over the window (leaf_px_max: the largest projected error of a
 * drawn diamond that may not split). Budget as bintree.h. */
void ft_btc_select(ft_bt_cache *bc, const ft_bt_view *v, double tau_px, ft_bt_select_stats *st);

#endif
