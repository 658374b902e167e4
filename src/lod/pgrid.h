/* pgrid.h - the error-bounded projective grid (method 'pgrid'): the CPU half
 * of the arithmetic, the mirror the tests hold shaders/pgrid*.glsl to.
 *
 * pgrid is pgm (src/lod/pgm.h: sampling camera, viewport extension, per-vertex
 * avg-pyramid LOD; its C functions are reused here) plus:
 *
 * 1. Row distribution. Row j of rows (t = j / (rows - 1)) sits at image-plane
 *    height y_j of the sampling camera (depression dep_s, eye h above the
 *    base plane). uniform: y_j = mix(y0, y1, t) (pgm). view: the centre ray at
 *    image height y has depression beta = dep_s - atan(y) and meets the base
 *    plane at the signed ground distance d = h cot(beta). Rows are evenly
 *    spaced in
 *        s = asinh(d / h)
 *    so s_j = mix(s(y0), s(y1), t), beta_j = atan2(1, sinh(s_j)),
 *    y_j = tan(dep_s - beta_j) (closed form, monotone in j). For d >> h,
 *    s ~ ln(2 d / h): rows are spaced uniformly in log ground distance, so
 *    a cell's depth on the ground (d ds) grows like its width (prop. to d) and
 *    cells stay close to square; near the nadir (d ~ 0) asinh is linear and
 *    the rows are ~h apart, and a bottom edge past the nadir (d < 0) is fine.
 *    Columns: uniform in x by default (pgrid.columns = uniform): a grid row
 *    lies on a line of constant depth in the view, so uniform columns are
 *    uniform in the view's pixels along it. pgrid.columns = error (with ray
 *    casting) moves them to where the error was: x is cut in
 *    FT_PGRID_COL_BANDS equal bands, band b gets the columns with t = i /
 *    (cols - 1) in [T_b, T_b+1] (a piecewise linear map, the shader's
 *    ft_col_x and ft_pgrid_col_u), and each frame the knots T come from the
 *    previous frame's error buffer, which carries each pixel's column t:
 *    per band the histogram of codes, and the share s_b = 16 (T_b+1 - T_b)
 *    in [1/2, 4] that puts fewest pixels over code(gamma) if a pixel's error
 *    scales as 1 / s_b (ft_pgrid_col_warp), blended with the last share by a
 *    geometric mean. The bound does not depend on where the columns are:
 *    every quad is bounded as drawn (6).
 *
 * 2. Per-vertex object-space error. Region of influence of vertex (i, j):
 *    the axis-aligned box of the ground points of grid points (i +- 1, j +- 1)
 *    (clamped into the grid): every triangle touching the vertex lies in it.
 *    hmin, hmax: min/max pyramid over the box, read at the level L_b where the
 *    box spans at most 2 x 2 texels, L_b = max(0, ceil(log2(box side in
 *    cells))). With h_v the vertex's (avg-pyramid, morphed) height,
 *        delta = max(hmax - h_v, h_v - hmin)   (>= 0 always; h_v may lie outside)
 *    and |h_v - H(x)| <= delta for every x of the box. A mesh point P is a
 *    convex combination of its triangle's vertices, so |P.z - H(P.xy)| <=
 *    the same combination of the deltas: the interpolated delta. Per fragment
 *        rho = K * delta / (|P - eye| cos^2 theta),  K = height_px / (2 tan(fovy / 2))
 *    with theta the angle between P - eye and the view axis, bounds the
 *    metric's e (src/measure/metric.h, which is rho's numerator over |P - eye|: the
 *    angle in centre pixels) and the displacement in true pixels: a
 *    perspective image stretches angles by up to 1 / cos^2 theta (radially),
 *    15x at 75 degrees off axis, so wide views (FOV 150) need the factor.
 *    Over the clipmap cache (pgrid.heights = clipmap; GLES 3; ray casting:
 *    7; the tight bound: 6): the grid reads its heights as pgm does over the cache
 *    (pgm.h), and hmin, hmax are the finest data's range over the box
 *    (clamped into what is drawn): from the cache's cell ranges of the
 *    finest level whose resident cells hold the box within 2 x 2 of them,
 *    else its block ranges of the finest level whose blocks do, else the
 *    coarsest level's range (lod/clip_levels.h FT_CLIP_BOUNDS_RANGES; a
 *    level-L cell's range is its corners' widened by how far the finest
 *    data depart from level L's bilinear surface there, so it bounds the
 *    finest data whatever level the vertex's height came from). The same
 *    delta then bounds the drawn mesh against the finest data; the frame
 *    reports the largest rho it drew (tau_achieved_px; +INF where a
 *    deviation is unknown, e.g. SRTM levels over ETOPO5-only terrain, or
 *    where rho passes 256 px).
 *
 * 3. Error buffer (RGBA8, drawn with the grid; on GLES 3 the picture pass
 *    writes it as a second colour attachment): R = 1 - gamma / rho where
 *    rho > gamma, else 0 (the normalised error), G = code(rho), an 8-bit
 *    log code rounded UP: code(rho) = ceil((log2(rho) + 8) * 255 / 16) clamped
 *    to [1, 255] for terrain, 0 for sky (clear). rho > g implies code(rho) >=
 *    code(g), so thresholding codes is conservative. B = the pixel's grid
 *    column t = i / (cols - 1), for the column warp (1).
 *    With ray casting, the grid is drawn twice more into it, as envelopes:
 *    every vertex at the max (then the min) of its region, with GLES 3 MAX
 *    blending and depth writes off (the mesh's depth decides what is in
 *    front). A vertex's region holds every cell around it, so the upper
 *    envelope lies on or above the surface over each triangle's footprint,
 *    and a ray from an eye above it that reaches the surface crosses it
 *    first: every pixel the true surface can cover is covered by the mesh or
 *    an envelope in front of it, and takes the largest code there. Without
 *    them a ridge whose mesh skyline is lower than the true one shows sky
 *    (or farther terrain) with a small code: 28 pixels of missed ridge on
 *    Rainier at 800 x 600, 0 with them. The lower envelope does the same for
 *    an eye under the ground, looking at the surface from below, and it
 *    is the net for the mesh's own misses near the eye (an eye 1 m above
 *    the ground can be under the mesh, whose interpolated heights rise
 *    over it: the picture shows sky under it and the lower envelope marks
 *    it). So it is left out only where neither can happen: the eye over
 *    the grid and above the terrain's highest sample (then every sample,
 *    every mesh vertex, an average or bilinear value of samples, and the
 *    truth lie under it, and every ray meets both surfaces first from
 *    above). A rule that asked only for the eye above the cell under it
 *    failed two tests: 1 m above the ground (26,079 pixels of terrain left
 *    as sky) and FOV 170 at 30 m (14,000-24,000), where the sampling
 *    rectangle is cut at its half-angle cap and rays miss the grid. Where
 *    the rule leaves it out, drawing it changes no pixel's ray-cast decision
 *    (test_pgrid_gl "lower"); the sweep's FOV 170 views from 3 km and 100 km
 *    hold without it.
 *
 * 4. Ray-cast set: pixel p is ray cast iff max(code over p's 3 x 3
 *    neighbourhood) >= code_thr. The one-pixel dilation is the silhouette
 *    rule: a sky pixel next to a terrain pixel over gamma is ray cast too
 *    (the mesh edge there may be off by up to rho px); sky next to terrain
 *    under gamma is within gamma (<= 1 px for gamma <= 1). code_thr =
 *    code(gamma_px) unless the budget says otherwise (5).
 *    The ray caster runs per screen tile of raycast_tile_px^2: a tile pass
 *    writes each tile's largest code over the tile and a one-pixel border
 *    around it (every code a pixel of the tile dilates from), and the ray
 *    caster draws only the tiles whose largest code reaches code_thr, so a
 *    tile it leaves out holds no pixel of the set. The reason is the
 *    rasteriser: a SIMD shader core such as llvmpipe's runs the whole
 *    fragment shader, every branch and one visit of every loop, for a
 *    block of pixels even when all of them are discarded at its first line
 *    (measured: a full-screen pass that discarded every pixel took 13-20
 *    ms a frame at 640x480).
 *
 * 5. Budget: the histogram of dilated codes of an error buffer gives the
 *    count for every threshold. The smallest threshold >= code(gamma) whose
 *    count fits raycast_max_px is used; if it is above code(gamma) the
 *    budget was hit, and the error reported is rho_hi(thr - 1) (the largest
 *    rho a code below the threshold stands for). With ray casting (GLES 3)
 *    the decision is one frame late and never stalls: the frame's error
 *    buffer is read into a pixel-pack buffer without waiting, and the next
 *    frame maps it (complete by then) to choose its own threshold. The
 *    threshold is applied per pixel on the GPU to the frame's own buffer,
 *    so the bound holds on every frame; what is late is the count: after an
 *    abrupt change of view one frame can ray cast more than raycast_max_px
 *    (a time overrun, not an error one), and the counts reported are the
 *    previous frame's. Without ray casting (GLES 2) the buffer is read at
 *    once and the reported error is rho_hi(largest code present). */
#ifndef FT_PGRID_H
#define FT_PGRID_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "lod/pgm.h"
#include "terrain/clip_cache.h"
#include "terrain/terrain.h"

#define FT_PGRID_COL_BANDS 16u
#define FT_PGRID_DIST_UNIFORM 0
#define FT_PGRID_DIST_VIEW 1
#define FT_PGRID_CODE_LOG2_MIN (-8.0)
#define FT_PGRID_CODE_LOG2_SPAN 16.0
#define FT_PGRID_CODES 256u

/* delta = max(hmax - h, h - hmin) (>= 0 for h in or out of [hmin, hmax]). */
double ft_pgrid_delta(double hmin_m, double hmax_m, double h_m);
/* rho = K * delta / dist (dist floored at 1e-6 m). */
double ft_pgrid_rho(double k_px, double delta_m, double dist_m);
/* 0 where rho <= gamma, else 1 - gamma / rho (in [0, 1)). */
double ft_pgrid_norm_error(double rho_px, double gamma_px);

/* 1 when the lower envelope must be drawn (3) for the frame's sampling
 * set-up s: the eye off the grid or not above the terrain's highest sample. */
int ft_pgrid_lower_envelope_needed(const ft_terrain *t, const ft_pgm_sampling *s);

/* The column warp's knots t (FT_PGRID_COL_BANDS + 1, t[0] = 0, t[last] =
 * 1, increasing): band b of the sampling rectangle's width holds the
 * columns with i / (cols - 1) in [t[b], t[b + 1]]. The rectangle's u in
 * [0, 1] (x = mix(x0, x1, u)) of column parameter t; past either end the end
 * band's slope (the shader's ft_col_x). */
double ft_pgrid_col_u(const float t_knots[], double t);
/* Next knots from the band histograms of a frame's codes (hist[b][c]:
 * pixels of band b with code c; drawn with knots prev): each band takes
 * s_b = 16 (t[b+1] - t[b]) times the uniform columns, s_b in [1/2, 4], to
 * minimise the pixels over code(gamma) if each pixel's error scales as 1 /
 * s_b, at a fixed column count; geometric mean with prev (no jumps). */
void ft_pgrid_col_warp(const uint32_t (*hist)[256], const float prev[], double gamma_px,
                       float next[]);

/* 8-bit error code (rounded up; >= 1 for any rho, 0 is reserved for sky). */
uint32_t ft_pgrid_code(double rho_px);
/* The largest rho code c stands for: 2^((c * 16 / 255) - 8). */
double ft_pgrid_code_rho_hi(uint32_t code);

/* s(y) = asinh(cot(dep - atan(y))) for the sampling depression dep. */
double ft_pgrid_row_s(double depression_rad, double y);
/* Image-plane height of row j (0 bottom) of rows, for rect y in [y0, y1]. */
double ft_pgrid_row_y(int distribution, double depression_rad, double y0, double y1,
                      uint32_t rows, double j);

/* Min and max of the surface over the world box [x0,x1] x [y0,y1] (metres),
 * clamped into the grid, read from the min/max pyramid at the level where
 * the box spans at most 2 x 2 texels (the shader's rule). */
void ft_pgrid_region_minmax(const ft_terrain *t, double x0_m, double y0_m, double x1_m,
                            double y1_m, double *hmin_m, double *hmax_m);

/* The ray-cast threshold for a histogram of dilated codes (hist[c] pixels
 * with dilated code c; hist[0] is sky away from terrain over gamma): the
 * smallest code >= code(gamma) with count(code >= thr) <= max_px (256 =
 * nothing ray cast). *count: pixels ray cast at the threshold;
 * *budget_hit: thr > code(gamma). */
uint32_t ft_pgrid_budget_threshold(const uint32_t hist[FT_PGRID_CODES], double gamma_px,
                                   uint64_t max_px, uint64_t *count, int *budget_hit);

/* Dilated-code histogram from an RGBA8 error-buffer readback (G = code),
 * w x h; work: w * h bytes scratch (may alias rgba's last 3/4: see .c). */
void ft_pgrid_histogram(const uint8_t *rgba, uint32_t w, uint32_t h, uint8_t *work,
                        uint32_t hist[FT_PGRID_CODES]);

/* Atlas of the min and max pyramids' levels FT_PGRID_ATLAS_L0.. (levels 0
 * and 1 are computed from the heights texture in the shaders: 2 x 2 and
 * 3 x 3 samples; that keeps the atlas at 1/16 of the grid): level L at
 * origin_px[L] for min and origin_px[L] + (half_w, 0) for max. 1 x 1 when
 * there are no such levels. */
#define FT_PGRID_ATLAS_L0 2u
void ft_pgrid_minmax_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *half_w,
                            uint32_t *height_px);
/* The ray caster's max atlas (4): the max pyramid's levels 1.. (level 0 is
 * the cell's 4 samples, which its traversal fetches on every visit anyway),
 * in the residual atlas's layout (6): level 1 at (0, 0), levels 2.. in a
 * column right of it; 1 x 1 when there are none. */
void ft_pgrid_rc_max_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                            uint32_t *height_px);

/* 6. The tight bound (GLES 3 with ray casting): what the error buffer needs
 *    is |L(x) - H(x)|, L the drawn surface (the grid's linear interpolation
 *    of its vertex heights), H the bilinear truth, not the relief of H
 *    around a vertex (2), which on real terrain exceeds gamma's worth of
 *    metres at almost every vertex.
 *    Plane-residual pyramid: node (i, j) of level L covers the same samples
 *    as min/max texel (i, j) of level L, [x0, x1] x [y0, y1] with x0 = i 2^L,
 *    x1 = min(x0 + 2^L, width - 1). Its plane p is the least-squares plane of
 *    its four corner samples: centre value m = mean of the corners, slopes
 *    bx = (h10 + h11 - h00 - h01) / 2 across x1 - x0, by likewise. Its
 *    residual r = max |H - p| over the node, exact from the samples alone
 *    (H - p is bilinear on every cell, so its extremes are at samples). At
 *    level 0 (one cell) r = |h00 - h10 - h01 + h11| / 4, computed from the
 *    heights; levels FT_PGRID_RES_L0.. are an R32F atlas.
 *    Quad bound: a grid quad with corners (g_k, h_k) (grid coordinates of
 *    the drawn vertices and their drawn heights) is covered by <= 2 x 2 nodes
 *    of the level where its box spans at most 2 nodes (2's rule). Over the
 *    part of the quad in node N,
 *        H - L = (H - p_N) + (p_N - L),  |H - p_N| <= r_N,
 *    and p_N - L is linear on each of the quad's two triangles, so its extreme
 *    is at a corner: |H - L| <= r_N + max_k |p_N(g_k) - h_k|. The quad's
 *    bound e_Q is the largest over its nodes, plus the curvature chord (2)
 *    and a margin for the shader's float arithmetic.
 *    One bound a quad: both triangles of quad (i, j) end at vertex
 *    (i + 1, j + 1) (src/lod/method_pgm.c's index order), and GLES 3 takes
 *    a flat output from a triangle's last vertex, so that vertex hands its
 *    quad's e_Q to every mesh pixel of the quad, flat: the point a mesh
 *    pixel shows lies on that quad, within e_Q of the truth above or below
 *    it, so the pixel is coded with the bound of its own quad. A vertex's
 *    delta, the largest e_Q of the <= 4 quads around it (every triangle
 *    touching the vertex lies in one of them), is computed once a frame
 *    (the vertex-bound pass); it moves the envelopes (the mesh moved up and
 *    down by it at every vertex encloses H over every triangle) and,
 *    interpolated, codes their pixels. An envelope pixel stands for a point
 *    of the truth the mesh hides or misses, further along the ray than the
 *    envelope's fragment and not always over the same quad; coded with the
 *    fragment's own quad's e_Q, the 1 m above ground case of extreme_cases
 *    measured 1.5 px at gamma 1 (0.002 px with the interpolated delta).
 *    Over the cache (pgrid.heights = clipmap) there is no residual atlas:
 *    a quad is bounded on the finest level L whose resident samples hold a
 *    window of FT_PGRID_EXACT_CELLS^2 level-L cells around its box (the
 *    level where it is small enough, or the next one that holds it), by
 *    |L - T| <= |L - H_L| + |H_L - T|, T the finest data: the exact rule on
 *    H_L, level L's bilinear surface, plus the largest deviation of T from
 *    H_L over the cells the quad touches, read from the cell ranges (2: a
 *    cell's range is its corners' widened by that deviation, so range hi -
 *    the corners' max and the corners' min - range lo are at least it).
 *    Level 0 is the finest data itself. A quad no level holds so takes the
 *    relief rule over its box from the cache's ranges (every point of the
 *    quad lies between its corners' heights, every point of T in the box
 *    within the range). Unknown deviations give unbounded ranges, so an
 *    unbounded e_Q: its pixels take the top code, as with the relief bound. */
#define FT_PGRID_RES_L0 1u
/* Atlas of the residual levels FT_PGRID_RES_L0.. (level L at origin_px[L]),
 * width_px x height_px (1 x 1 when the terrain has no such level). */
void ft_pgrid_residual_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                              uint32_t *height_px);
/* Residual r of node (i, j) at level (any level, 0 included), from the
 * heights: max |H - p| over the node's samples. */
double ft_pgrid_node_residual(const ft_terrain *t, uint32_t level, uint32_t i, uint32_t j);
/* Plane of node (i, j) at level evaluated at grid point (gx, gy). */
double ft_pgrid_node_plane(const ft_terrain *t, uint32_t level, uint32_t i, uint32_t j,
                           double gx, double gy);
/* Fills the residual atlas (row-major, width_px x height_px floats; texels
 * outside every level are 0). Init time: each level visits every sample once. */
void ft_pgrid_residual_fill(const ft_terrain *t, float *atlas, uint32_t width_px,
                            uint32_t height_px);
/* A grid quad as drawn: corners (i, j), (i+1, j), (i, j+1), (i+1, j+1) at
 * grid coordinates g[k] (clamped into the grid) with drawn heights h_m[k]. */
typedef struct ft_pgrid_quad {
    double g[4][2];
    double h_m[4];
} ft_pgrid_quad;
/* Exact quads: a quad whose box lies in a window of FT_PGRID_EXACT_CELLS^2
 * cells gets the exact max of |L - H|. On a piece (a triangle inside one
 * cell) H - L = linear + D u v (D the cell's twist): a saddle, so its
 * extremes over the piece are on the piece's boundary; along a cell line H
 * is linear, so on the cell-line parts of the boundary they are at the
 * ends, which are samples inside the triangle or points on its edges; along
 * a triangle edge inside a cell H - L is a quadratic in the edge parameter
 * (curvature D dx dy): its ends and its one stationary point. So the max is
 * over (a) the 5 edges of the quad's two triangles, cut at the cell lines,
 * each piece's ends and stationary point, and (b) the samples inside a
 * triangle. Bigger quads take the residual rule. */
#define FT_PGRID_EXACT_CELLS 4u
/* The exact max for a quad that fits the window (*fits = 1), else 0 with
 * *fits = 0. */
double ft_pgrid_quad_exact(const ft_terrain *t, const ft_pgrid_quad *q, int *fits);
/* The residual rule's bound (any quad). */
double ft_pgrid_quad_residual(const ft_terrain *t, const ft_pgrid_quad *q);
/* The quad bound e_Q (metres, without the chord): exact when the quad fits
 * the window, else the residual rule; the shader's rule in double. */
double ft_pgrid_quad_bound(const ft_terrain *t, const ft_pgrid_quad *q);

/* 7. Ray casting over the clipmap cache (pgrid.heights = clipmap, GLES 3):
 *    the traversal's max-mip is the cache's levels (shaders/pgrid_rc.frag.glsl):
 *    a node is a resident level-L cell, its max the hi of the cell's range of
 *    the finest data (2), its children the level L - 1 cells under it. A
 *    node whose point the finer level does not hold is a leaf: the ray meets
 *    level L's bilinear surface H_L there, and the finest data lie within the
 *    cell's deviation e of H_L (ft_clip_block_bound dev_m: the database's
 *    per-cell deviation, no twist term, since no triangle is drawn). So the
 *    point a ray-cast pixel shows, and any surface of the finest data the
 *    ray passed over in a leaf, is within e of it vertically, and the
 *    pixel's error is at most K e G / |P - eye|, G the vertical gain of
 *    core/view_scale.h (<= 1 / cos^2 theta, the mesh's factor (2): a ray
 *    goes through its pixel's centre, so nothing is misplaced sideways).
 *    Level 0's leaves are the finest data: exact. Level L >= 1 holds leaves
 *    only where level L - 1's box does not hold its cells, so the frame's
 *    bound is the largest ft_view_bound_error_px(dev_m) over the cache's
 *    blocks of levels >= 1 with such cells that meet the view (heights lo -
 *    e .. hi + e); the FT_PGRID_LEAF_REFINE_MAX largest over refine_over_px
 *    are bounded again cell by cell (ft_clip_cell_bound), over the cells
 *    that can be leaves and meet the data (the ray is clipped to them: past
 *    the data's edge a deviation is unknown). A cell whose deviation is
 *    unknown counts over the column a ray can cross it in: from truth_top_m
 *    (the finest data's highest point) down to the ray floor, the lowest
 *    drawn height nearer than the cell's farthest point: a ray from an eye
 *    over the drawn surface under it that is under every drawn height on
 *    its way has crossed the surface (continuous along the path; a ray that
 *    enters a leaf under it stops at the entry) and ended. The frame reports
 *    max(its threshold's bound, this) whenever it ray casts; +INF where such
 *    a column meets the view. No GPU read-back: the CPU keeps every block's
 *    bounds (clip_cache.h). */
#define FT_PGRID_LEAF_REFINE_MAX 64u
/* The bound (px) for a frame that ray casts over the cache as the shader
 * sees it (v: the boxes it got), camera cam; 0 when no block with leaves
 * meets the view. At most levels x (side / 16)^2 x 4 blocks and
 * FT_PGRID_LEAF_REFINE_MAX x 16^2 cells; no memory. */
double ft_pgrid_cache_leaf_bound_px(const ft_clip_cache *c, const ft_pgm_clip_view *v,
                                    const ft_clip_world *w, const ft_camera *cam,
                                    double curv_k_per_m, double truth_top_m,
                                    double refine_over_px);

#endif
