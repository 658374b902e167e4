/* clipmap.h - geometry clipmaps (method 'clipmap'): which parts of each
 * cached level are drawn, how they are cut into template draws, and the
 * per-vertex rule the vertex shader applies (shaders/clipmap.vert.glsl),
 * mirrored here on the CPU for tests. No GL and no allocation here.
 *
 * Coordinates. Level l's vertex (a, b) is its sample (a, b) of the cache
 * (src/terrain/clip_cache.h): level-0 lattice sample (a * 2^l, b * 2^l).
 * A rectangle here (ft_cm_rect) is inclusive in vertex coordinates: the
 * cells between x0..x1 and y0..y1.
 *
 * Drawn boxes, coarsest level first. Level l may be drawn over
 *   R_l = [valid.i0, valid.i1 - 2] x [valid.j0, valid.j1 - 2]
 * (its resident samples, edges on the level-l+1 lattice: the cache keeps
 * valid edges even, and the last odd column is left to the coarser level)
 * and over the data, rounded outward to the level-l+1 lattice
 *   O_l = [floor(lo / 2^(l+1)) * 2, ceil(hi / 2^(l+1)) * 2].
 * Its drawn box D_l, side by side: the tightest of R_l, O_l and the coarser
 * box D_(l+1) (in level-l units); on a side where D_(l+1) is not at the data
 * D_l stays one coarse cell inside it, so the coarse level always has a ring
 * cell between the two there. A side of D_l that is neither O_l's nor
 * D_(l+1)'s is a TRANSITION side (a coarser level's ring cell lies beyond
 * it, inside the data); beyond the other sides is no terrain (the data
 * edge, or the coarsest drawn box's outer edge). A level whose box is less than
 * one coarse cell wide is not drawn, nor is any finer level.
 *
 * What each level draws. The finest drawn level draws D_l whole; every
 * other drawn level draws its RING, D_l minus the finer box H = D_(l-1) / 2:
 *  - regular cells (2 triangles each), in blocks of FT_CM_BLOCK_CELLS^2 cells
 *    of one template, clamped to the piece of ring they cover;
 *  - the STITCH rule: each ring cell that shares an edge with H is cut into
 *    3 triangles with the midpoint of that edge, which is the finer level's
 *    boundary vertex between two coarse samples (strip draws, one template);
 *    the corner cells diagonal to H's corners stay 2 triangles. So the two
 *    levels share every boundary vertex and no T-junction is left; no
 *    triangle is zero-area (clamped cells past a piece's end are, and draw
 *    nothing, as brute's do).
 *
 * The vertex rule (clipmap.vert.glsl and ft_cm_vertex):
 *  1. c = clamp(origin + u * t.x + v * t.y, draw clamp) (level-l units; t is
 *     the template vertex, in half cells for strips), then c is clamped to
 *     the data [lo, hi] / 2^l: no geometry beyond the terrain.
 *  2. H(l, c) = bilinear over the four level-l samples around c (one texel
 *     each at (a mod side, b mod side)); at an integer c that is the sample,
 *     at a half-integer on one axis the mean of the two along the edge.
 *  3. Morph weight w = clamp((T_l - d) / T_l, 0, 1), d = the distance from
 *     c to the nearest TRANSITION side of D_l (level-l samples); 0 when
 *     there is none. So w is exactly 1 on a transition side.
 *  4. h = H(l, c) when w = 0, H(l+1, c / 2) when w = 1 (selected, not
 *     mixed, so it is that value to the bit), else mix of the two.
 *  5. position = origin_rel_eye + (c * 2^l - lattice0) * cell, h.
 * A fine vertex on a transition side thus takes H(l+1, c / 2); the coarse
 * stitch vertex at the same place computes H(l+1, c') with c' = c / 2 (the
 * same floats: the scale is a power of two) and must have w = 0 there:
 * T_l is capped by the ring's narrowest transition side (the distance from
 * H to any transition side of D_l is at least that width), so the coarse
 * level never morphs on its inner edge. Same inputs, same shader code:
 * the same bits.
 *
 * The view decides nothing: a level's samples are the cache's (the source's
 * level-l heights). So the method targets no error; it REPORTS the bound
 * of what it drew (ft_cm_frame_bound below), from the error the cache
 * keeps per block against the source's finest data. */
#ifndef FT_CLIPMAP_H
#define FT_CLIPMAP_H

#include <stdint.h>

#include "core/view_scale.h"
#include "terrain/clip_cache.h"

/* Template block side in cells; strips are that many cells long. */
#define FT_CM_BLOCK_CELLS 32u
/* Template vertices: block (B+1)^2, then the strip's inner row (2B+1, at
 * half cells) and outer row (B+1). */
#define FT_CM_BLOCK_VERTICES ((FT_CM_BLOCK_CELLS + 1u) * (FT_CM_BLOCK_CELLS + 1u))
#define FT_CM_STRIP_VERTICES (3u * FT_CM_BLOCK_CELLS + 2u)
#define FT_CM_BLOCK_INDICES (FT_CM_BLOCK_CELLS * FT_CM_BLOCK_CELLS * 6u)
#define FT_CM_STRIP_INDICES (FT_CM_BLOCK_CELLS * 9u)

/* Inclusive vertex rectangle; drawn when x1 > x0 and y1 > y0. */
typedef struct ft_cm_rect {
    int64_t x0, y0, x1, y1;
} ft_cm_rect;

enum { FT_CM_W = 0, FT_CM_S = 1, FT_CM_E = 2, FT_CM_N = 3 };

typedef struct ft_cm_level {
    int drawn;
    ft_cm_rect box;      /* D_l */
    int transition[4];   /* per side (FT_CM_W..N): a coarser ring lies beyond */
    ft_cm_rect hole;     /* H = D_(l-1) / 2 when has_hole */
    int has_hole;
    double transition_samples; /* T_l (> 0) */
} ft_cm_level;

typedef struct ft_cm_layout {
    uint32_t levels;
    uint32_t finest, coarsest; /* drawn levels, finest <= coarsest (drawn_count > 0) */
    uint32_t drawn_count;
    ft_cm_level level[FT_CLIP_LEVELS_MAX];
    int64_t data_lo[2], data_hi[2]; /* level-0 samples with data, inclusive (x, y) */
} ft_cm_layout;

/* Drawn boxes for the cache's valid boxes (valid[l] in level-l samples),
 * the data extent (level-0, inclusive) and the transition width (level
 * samples, >= 1). */
void ft_cm_layout_make(ft_cm_layout *out, uint32_t levels, const ft_clip_box *valid,
                       const int64_t data_lo[2], const int64_t data_hi[2],
                       double transition_samples);

typedef enum ft_cm_kind { FT_CM_BLOCK, FT_CM_STRIP, FT_CM_CORNER } ft_cm_kind;

/* One template draw: template vertex t goes to
 * clamp(origin + axis_u * t.x + axis_v * t.y, clamp) in level units. */
typedef struct ft_cm_draw {
    uint32_t level;
    ft_cm_kind kind;
    int64_t origin[2];
    int32_t axis_u[2], axis_v[2];
    ft_cm_rect clamp;
    uint32_t triangles; /* non-degenerate triangles it draws */
} ft_cm_draw;

typedef void (*ft_cm_draw_fn)(void *ctx, const ft_cm_draw *d);

/* Calls fn for every draw of level l (nothing when it is not drawn).
 * Returns the triangles drawn. */
uint64_t ft_cm_level_draws(const ft_cm_layout *lay, uint32_t l, ft_cm_draw_fn fn, void *ctx);

/* Template vertex k of a kind (block: (x, y) cells; strip: (x in half
 * cells, y 0 inner / 1 outer)); the index list of a kind's template. */
void ft_cm_template_vertex(ft_cm_kind kind, uint32_t k, float out[2]);
uint32_t ft_cm_template_vertex_count(ft_cm_kind kind);
/* Writes the kind's indices (into the kind's own vertex numbering). */
uint32_t ft_cm_template_indices(ft_cm_kind kind, uint16_t *out);

/* ---- the CPU mirror of clipmap.vert.glsl ---------------------------------- */

/* The height texel of level l's sample (a, b), as the texture holds it. */
typedef float (*ft_cm_texel_fn)(void *ctx, uint32_t level, int64_t a, int64_t b);

/* What the shader gets for one draw, in floats as the uniforms carry them. */
typedef struct ft_cm_uniforms {
    float place[4];   /* origin x, y; unused */
    float axes[4];    /* u.x, u.y, v.x, v.y */
    float clamp[4];   /* x0, y0, x1, y1 */
    float data[4];    /* data lo x, y, hi x, y in level units */
    float mbox[4];    /* transition sides of D_l (+-FT_CM_FAR on the others) */
    float level[4];   /* 2^l, T_l, 1 when a coarser level exists, unused */
} ft_cm_uniforms;
#define FT_CM_FAR 1.0e9f

void ft_cm_uniforms_of(const ft_cm_layout *lay, const ft_cm_draw *d, ft_cm_uniforms *u);

typedef struct ft_cm_vertex_out {
    float c[2];   /* level units, after the clamps */
    float g[2];   /* level-0 lattice units: c * 2^l */
    float h_m;
    float w;      /* morph weight */
} ft_cm_vertex_out;

void ft_cm_vertex(const ft_cm_uniforms *u, uint32_t level, const float t[2],
                  ft_cm_texel_fn texel, void *ctx, ft_cm_vertex_out *out);

/* ---- the bound of what a frame draws ----------------------------------------

 * A drawn triangle of level l has its vertices on level l's bilinear
 * surface (a sample, an edge's midpoint, a point clamped to the data) or,
 * within T_l of a transition side, blended towards level l + 1's: so over
 * a cell it lies within err + morph of the finest data (err, morph: the
 * cache's block bound, clip_cache.h; morph only where a blend can reach),
 * plus the packed texels' quantum where heights are packed. Each resident
 * block piece of a drawn level that holds drawn cells (in D_l, not all in
 * the finer box H) and meets the frustum is bounded as a box: K e G / d
 * (ft_view_bound_error_px: the eye's distance d to the box as drawn, its
 * vertical gain G, the curvature chord over it). The frame's bound is the
 * largest; +INF when a drawn piece's error is not known (a level finer
 * than the data there, e.g. SRTM levels over ETOPO5-only terrain) or its
 * box holds the eye, and when data the coarsest drawn box does not reach
 * may be in view (over the data's height range data_z*: terrain there is
 * drawn as sky, which no vertical bound covers). Pieces whose box bound is over 1 px and whose box
 * lies near the eye are bounded again cell by cell (ft_clip_cell_bound),
 * which a 16-sample block's wide height range otherwise spoils: at most
 * FT_CM_REFINE_PIECES_MAX of them a frame, the largest first. */
#define FT_CM_REFINE_PIECES_MAX 16u

typedef struct ft_cm_bound {
    double bound_px;      /* over every visible drawn piece */
    uint64_t pieces;      /* visible drawn pieces */
    uint64_t unbounded;   /* of those, with no known error (or holding the eye) */
    uint32_t refined;     /* pieces bounded again cell by cell */
    uint32_t worst_level; /* the level of the piece that set bound_px */
    int undrawn_visible;  /* data past the coarsest drawn box may be in view: no bound */
} ft_cm_bound;

/* view: in the cache's world frame less (w->origin_x_m, w->origin_y_m);
 * quantum_m: the height texels' step (0 for float texels); data_z*: the
 * source's height range. No memory; at most levels x (side / 16)^2 x 4
 * pieces and FT_CM_REFINE_PIECES_MAX x 18^2 cells. */
void ft_cm_frame_bound(const ft_cm_layout *lay, const ft_clip_cache *c, const ft_clip_world *w,
                       const ft_view_bound *view, double quantum_m, double data_zmin_m,
                       double data_zmax_m, ft_cm_bound *out);

#endif
