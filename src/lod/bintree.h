/* bintree.h - the crack-free bintree of triangular tiles: error tables built
 * at init, per-frame selection with an explicit stack.
 *
 * Domain: the grid padded (conceptually) to (2^n + 1)^2 samples, N = 2^n
 * cells a side, sample (0,0) at the corner. Padding rule: a grid of W x H
 * samples uses the smallest N = 2^n >= max(W, H) - 1; every grid coordinate
 * is clamped to [0, W-1] x [0, H-1] before a height is read, in the error
 * tables and in the vertex shader alike. Triangles wholly in the padding
 * collapse onto the grid edge (zero area, never drawn, never selected);
 * triangles across the edge are measured with the clamped geometry they are
 * drawn with. No padded heights are stored.
 *
 * Tree: the square split along its (0,0)-(N,N) diagonal into two root
 * triangles (level 0); a triangle (apex, left, right) with hypotenuse
 * left-right splits at m = (left+right)/2 into (m, apex, left) and
 * (m, right, apex). Every tile is drawn with the 2k-level template
 * (bintree_template.h), so tile levels run 0..L with L = 2(n - k): a level-L
 * tile's template is the full-resolution grid.
 *
 * Diamonds: the two triangles sharing a hypotenuse split together. A diamond
 * is named by its split vertex c (the hypotenuse midpoint); for tile levels
 * < L every c lies on the lattice of step 2^k, so the tables are
 * (N/2^k + 1)^2 entries:
 *   err_m[c]  saturated object-space error: max of the exact template error
 *             of the diamond's triangles and err_m of its child diamonds
 *             (the midpoints of its triangles' legs).
 *   dia[c]    (err_m[c], z0, z1, 0): its height range (see Boxes below;
 *             the box's xy is a closed form), the geomorph's texel.
 * Level-L (leaf) diamonds have their own table (leaf_err_m, leaf_z,
 * (N/2^k)^2 entries): nothing refines them, so their error is not a split
 * criterion but what the frame achieves where one is drawn.
 * Exact template error of a triangle: max over the triangle of
 * |bilinear surface - template surface|, the bilinear surface of the
 * samples being the truth. The template surface is linear on each template
 * triangle; on the part of a template triangle inside one cell the
 * difference is linear plus the cell's twist D u v (a saddle), so its
 * extremes lie on the part's boundary: at the samples inside the triangle,
 * or along the triangle's edges, where between two cell lines the
 * difference is a quadratic (ends and one stationary point). Along a cell
 * diagonal this is the classic |D| / 4 of a cell split into two triangles.
 * Boxes (the selection's and the geomorph's): a diamond of level l has
 * square side s = N 2^S >> (l / 2) (fine units); its descendants lie in
 * its closure, the square of half-side 1.5 s (even l, c a square's centre)
 * or s (odd l) around c. Its box is that square widened by the margin
 * M = 3 w s (even) or 2 w s (odd), w = bintree.morph_width, unclamped, in
 * xy, and in z the height range under the closure widened by M in metres
 * (M fine units x the smaller cell side / 2^S). The margins are what the
 * geomorph's rule needs: a child's box widened by its morph width
 * W = w s_child lies inside its parent's box (tight: 1.5 + 3w >= 0.5 + 1 +
 * 2w + w and 1 + 2w >= 0.25 + (1.5 + 3w) / 2 + w / 2), so a parent is at
 * least W nearer the eye than its child. Lattice diamonds keep their height
 * range in dia[c] (the samples of their triangles united with their
 * children's ranges widened by the child's W); diamonds below the samples
 * take the range of the aligned 2^(k+2)-cell blocks (zblock) under their
 * closure widened by M.
 * Selection and geomorph: with Q = K (err + chord) gain / tau - d (metres;
 * d the distance from the eye to the drawn box, gain the pixels a vertical
 * metre covers at distance 1 bounded over it, view_scale.h), diamond c is
 * split iff err > 0 and Q > -W (Q > 0 without geomorphing), and a vertex it inserts has morph weight
 * clamp(2 Q / W + 1, 0, 1): it starts to move at Q = -W / 2 and is at its
 * own height from Q = 0, where the box's projected error reaches tau. A
 * parent's Q is at least its child's + W (errors saturate, boxes nest with
 * the gap), so while a vertex moves, the endpoints of the edge it bisects
 * (inserted by ancestors) are at their own heights: a split never pops,
 * and every unsplit or moving diamond projects under tau. The same Q
 * nests the selection, so splitting every triangle of a split diamond gives
 * a conforming bintree by construction (no forced splits). Frustum culling
 * drops whole subtrees (their edges are outside the view).
 *
 * Budget: at most tiles_max tiles. If tau needs more, tau is multiplied by
 * FT_BT_COARSEN_FACTOR and the selection redone (at most
 * FT_BT_COARSEN_STEPS_MAX times, then the two roots).
 *
 * Achieved bound: the tau used, or the largest projected error of a leaf
 * tile drawn if that is larger (near the eye the sample spacing itself can
 * be coarser than tau). */
#ifndef FT_BINTREE_H
#define FT_BINTREE_H

#include <stdint.h>

#include "core/camera.h"
#include "core/ft_status.h"
#include "core/mem_budget.h"
#include "core/scene.h"
#include "core/view_scale.h"
#include "terrain/terrain.h"

#define FT_BT_N_MAX 14u /* N = 2^14: FT_GRID_SIDE_MAX = 16385 */
/* bintree.subsample_levels: tiles refine to 2^-S of a cell (S <= 4) */
#define FT_BT_SUB_MAX 4u
#define FT_BT_LEVELS_MAX (2u * (FT_BT_N_MAX + FT_BT_SUB_MAX))
#define FT_BT_STACK_MAX (FT_BT_LEVELS_MAX + 4u)
#define FT_BT_TILES_MIN 2u
#define FT_BT_TILES_MAX_LIMIT 1048576u
#define FT_BT_COARSEN_FACTOR 1.5
#define FT_BT_COARSEN_STEPS_MAX 40u
#define FT_BT_BOX_FLOATS 6u /* x0, x1, y0, y1 (grid), z0, z1 (m) */
/* Twist pyramid levels: a sub-sample diamond's closure is at most 3 * 2^k
 * cells wide, so blocks up to 2^(k+2) cells (k <= 6) are enough. */
#define FT_BT_TWIST_LEVELS_MAX 9u

typedef struct ft_bt_tile {
    int32_t apex[2], left[2], right[2]; /* grid coordinates */
    uint32_t level;
} ft_bt_tile;

typedef struct ft_bt_select_stats {
    uint32_t tiles;
    /* tiles [0, tiles_coarse) have every template vertex on a sample; the
     * rest (S > 0 only) are finer than the samples; DFS order within each */
    uint32_t tiles_coarse;
    uint32_t nodes_visited;
    uint32_t culled;
    uint32_t attempts;       /* selections run (1 unless the budget was hit) */
    int budget_hit;          /* tau was raised to fit tiles_max */
    double tau_target_px;
    double tau_used_px;      /* the selection's target after any budget coarsening */
    double leaf_px_max;      /* largest projected error of a leaf tile drawn (0: none) */
    double tau_achieved_px;  /* the bound the drawn tiles meet: max(tau_used, leaf_px_max) */
    uint32_t level_min, level_max;
    /* 1: the eye is over the grid and above the drawn surface there (the
     * box top of the unsplit diamond under it), so every back face is
     * hidden by a front face nearer on its ray and may be culled */
    int back_faces_hidden;
} ft_bt_select_stats;

typedef struct ft_bt_twist_layout {
    uint32_t levels;
    uint32_t w[FT_BT_TWIST_LEVELS_MAX], h[FT_BT_TWIST_LEVELS_MAX];
    uint32_t ox[FT_BT_TWIST_LEVELS_MAX], oy[FT_BT_TWIST_LEVELS_MAX];
    uint32_t atlas_w, atlas_h;
} ft_bt_twist_layout;

typedef struct ft_bintree {
    uint32_t n, k;
    uint32_t side_cells;   /* N = 2^n */
    uint32_t step;         /* 2^k: lattice step of split vertices */
    uint32_t lattice_side; /* N / 2^k + 1 */
    uint32_t sub;          /* S = bintree.subsample_levels */
    uint32_t fine_side;    /* N 2^S: the domain in fine units (tile coordinates) */
    uint32_t sub_level;    /* L_s = 2(n - k): tiles of this level and finer have
                              templates finer than the samples (S > 0) */
    uint32_t leaf_level;   /* L = 2(n + S - k) */
    uint32_t width, height;
    float domain_z[2];     /* min / max height of the grid */
    const float *heights_m;
    float *err_m; /* lattice_side^2 */
    float *dia;   /* lattice_side^2 * 4: (err_m, z0, z1, 0), the geomorph's texture */
    double morph_width;  /* w = bintree.morph_width: W = w s fine units (see the top) */
    double fine_m;       /* the smaller cell side / 2^S: metres per fine unit of W and M */
    uint32_t leaf_side;  /* N / 2^k: level-L diamonds a side */
    float *leaf_err_m;   /* leaf_side^2: error of the level-L diamonds (not refinable) */
    float *leaf_z;       /* leaf_side^2 * 2: their height range (the box's xy is their square) */
    /* S > 0: twist pyramid, level m texel = max |D| over the cells of an
     * aligned 2^m x 2^m block (D = h00 + h11 - h10 - h01 of a cell), all
     * levels in one atlas (the GPU's texture too): level 0 at (0, 0), level
     * m >= 1 at (w0, sum of the heights of levels 1..m-1). */
    ft_bt_twist_layout twist;
    float *twist_atlas; /* twist.atlas_w * twist.atlas_h */
    const ft_terrain *terrain;
    /* S > 0: height range of aligned blocks of 2^zblock_shift cells
     * (zblock_shift = k + 2: a closure below the samples spans <= 2 a side),
     * zblock_w x zblock_h blocks, (min, max, 0, 0) each: the GPU's texture */
    uint32_t zblock_shift, zblock_w, zblock_h;
    float *zblock;
    uint32_t tiles_max;
    ft_bt_tile *tiles; /* tiles_max */
    uint32_t flipped_triangles; /* template triangles the padding clamp flipped (must be 0) */
    double max_err_m;           /* err_m of the root diamond */
} ft_bintree;

/* The view the selection works with (see ft_bt_view_from_camera). */
typedef struct ft_bt_view {
    ft_view_bound b;       /* view_scale.h, relative to grid sample (0,0) at height 0:
                              the eye, K, the gain (b.gain.fwd the view axis), the
                              curvature drop (terrain.h) and the frustum's planes */
    double cell_m[2];
    int cull;
    int morph;
} ft_bt_view;

/* Smallest n with 2^n >= max(w, h) - 1. */
uint32_t ft_bt_domain_n(uint32_t w, uint32_t h);

/* Adds the tables and tile list to FT_POOL_METHOD. */
void ft_bintree_plan(ft_arena *a, uint32_t w, uint32_t h, uint32_t k, uint32_t sub,
                     uint32_t tiles_max);

/* Height blocks below the samples (S > 0) for a w x h grid and template k. */
void ft_bt_zblock_size(uint32_t w, uint32_t h, uint32_t k, uint32_t *bw, uint32_t *bh);

/* Twist pyramid geometry for a w x h grid and template k. */
void ft_bt_twist_layout_for(uint32_t w, uint32_t h, uint32_t k, ft_bt_twist_layout *l);

/* Builds the error and bound tables (O(L * N^2)). Fails on k > n, tiles_max
 * outside FT_BT_TILES_MIN..FT_BT_TILES_MAX_LIMIT, morph_width outside
 * FT_BT_MORPH_WIDTH_MIN..MAX, or arena exhaustion. */
ft_status ft_bintree_init(ft_bintree *bt, const ft_terrain *t, uint32_t k, uint32_t sub,
                          double morph_width, uint32_t tiles_max, ft_arena *a, ft_error *err);

/* Level of the diamond whose square side is sd fine units; odd: a square
 * side's midpoint (else the square's centre). */
uint32_t ft_bt_level_of(const ft_bintree *bt, int32_t sd, int odd);

/* The geomorph and split quantity of diamond c (fine units) at `level` for
 * target tau (see the top): Q in metres (+inf when the eye is in its box,
 * -inf when its error is 0 or tau is not finite); *w_m its morph width W. */
double ft_bt_diamond_q(const ft_bintree *bt, const ft_bt_view *v, uint32_t level,
                       const int32_t c[2], double tau_px, double *w_m);

/* Morph weight from Q and W: clamp(2 Q / W + 1, 0, 1). */
double ft_bt_morph_weight(double q_m, double w_m);

/* The selection's error (m) and box (grid units) of the diamond with split
 * vertex c (fine units) at `level`: the tables below sub_level, the leaf
 * table at the leaf level without sub-sample levels, else the closed form. */
double ft_bt_diamond_error(const ft_bintree *bt, uint32_t level, const int32_t c[2],
                           float box[FT_BT_BOX_FLOATS]);

/* Error (m) and box (grid units) of the diamond with split vertex c (fine
 * units) at a level >= sub_level (S > 0): closed form from the twist
 * pyramid (see the top). */
double ft_bt_sub_error(const ft_bintree *bt, uint32_t level, const int32_t c[2],
                       float box[FT_BT_BOX_FLOATS]);

/* The bilinear surface at fine point (x, y): the height every vertex of a
 * tile takes (a sample when both are multiples of 2^S). Cell = floor of the
 * point, clamped into the grid; float arithmetic in the shader's order. */
float ft_bt_height_fine(const ft_bintree *bt, int32_t x, int32_t y);

void ft_bt_view_from_camera(const ft_camera *cam, const ft_terrain *t, int cull, int morph,
                            ft_bt_view *v);

/* Selects tiles into bt->tiles (bounded: explicit stack, no recursion). */
void ft_bintree_select(ft_bintree *bt, const ft_bt_view *v, double tau_px,
                       ft_bt_select_stats *st);

/* Morph endpoints and insertion diamond of grid vertex (x, y), the same rule
 * the vertex shader uses: the vertex is the midpoint of e0-e1; it appears when
 * diamond c (fine units, level *level) splits. Returns 0 when the vertex
 * never morphs. */
int ft_bt_vertex_morph(const ft_bintree *bt, int32_t x, int32_t y, int32_t e0[2], int32_t e1[2],
                       int32_t c[2], uint32_t *level);

/* The one-fetch vertex table (GLES 3): per sample one RGBA32F texel with
 * what a vertex on that sample needs, so it does one texel fetch and no
 * search for its diamond:
 *   x  its height (m),
 *   y  the morph's coarse height (h(e0) + h(e1)) / 2 in float arithmetic, the
 *      shader's own expression (its height when it never morphs),
 *   z  the error (m) of the diamond that inserts it, or -1 when it never
 *      morphs (ft_bt_vertex_morph),
 *   w  its unit normal (central differences, one-sided at the grid edge)
 *      in hemi-octahedral coordinates (u, v) = (x + y, x - y) / (|x| + |y| + z),
 *      12 bits each: qu * 4096 + qv, an integer below 2^24 (exact in float).
 * A vertex between samples reads its cell's four heights instead. */
#define FT_BT_NORMAL_Q 4095.0
void ft_bt_sample_texel(const ft_bintree *bt, uint32_t gx, uint32_t gy, float out[4]);
float ft_bt_pack_normal(const double n[3]); /* n unit, n[2] >= 0 */
void ft_bt_unpack_normal(float packed, double n[3]);

#endif
