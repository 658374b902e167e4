/* pgm.h - persistent grid mapping (method 'pgm'): the mapping math, in C.
 *
 * shaders/pgm.vert.glsl does the per-vertex part on the GPU; this file is
 * the same arithmetic in double, for the per-frame set-up on the CPU (the
 * sampling camera, the viewport extension) and as the mirror the tests hold
 * the shader to. Any change here must be made in the shader too.
 *
 * The grid: cols x rows vertices (pgm.grid_cols x pgm.grid_rows), vertex
 * (i, j) at the image point
 *     x = mix(rect.x0, rect.x1, i / (cols - 1)),  y = mix(rect.y0, rect.y1, j / (rows - 1))
 * of the SAMPLING camera's image plane at distance 1 (tan units; row 0 is
 * the bottom, the nearest ground). Its ray d = fwd + x right + y up from
 * the sampling eye S meets the base plane z = base_z at
 *     P = S + h / (-d_z) d        (h = S_z - base_z)
 * which is the P = V + v_z / (v_z - g_z) (G - V) with V = S, G = S + d
 * and heights measured from the base plane. The vertex is put on the
 * terrain at P.xy (clamped into the grid) and drawn with the VIEWING camera.
 *
 * Base plane: z = terrain minimum (t->min_height_m), not z = 0, so every
 * terrain point is on or above it and rays meet it as close to the surface
 * as a plane can (z = 0 under a high plateau would move every sample far
 * beyond the surface point the ray sees). The sampling eye is the viewing
 * eye, at least FT_PGM_MIN_HEIGHT_M above the base plane (h > 0 always). A
 * camera under the terrain but above the plane needs nothing special (the
 * mesh is the same surface, seen from below; no face culling). A camera
 * below the plane (below z = 0, or under the terrain's lowest point) can
 * only see terrain along rising rays, and a ray rising at elevation e meets
 * the plane where its mirror image falling at depression e does: the eye and
 * the view are mirrored through the plane (`mirrored`), and everything below
 * works on the mirrored view; there is no viewport extension then (terrain
 * nearer than the steepest ray's plane point is above that ray).
 *
 * Sampling camera (no roll): heading = the view's heading (at nadir/zenith
 * from the view's up vector), depression (pitch down)
 *     dep_s = min(90 deg, max(dep_v, a + eps))
 * the "A_sam = A_view if |A_view| > FOV/2 else FOV/2 + epsilon",
 * with FOV/2 -> a = atan(ty_b): the half angle of the view's frustum
 * bounded in the roll-free frame (ty_b = |sin roll| tx + |cos roll| ty), and
 * eps = max(FT_PGM_EPS_MIN_RAD, atan(h / far)), far = the largest horizontal
 * distance from the eye to a grid corner: rays flatter than that meet the
 * plane outside the terrain. Every ray of the rectangle has d_z <= -sin(eps)
 * / cos(dep_s - eps) < 0 (the top edge is at depression >= eps), so every
 * ray hits the base plane; looking at or above the horizon only pitches the
 * sampling camera down, it never produces a ray that misses. The shader
 * still floors -d_z at min_neg_dz (half the smallest -d_z of the rectangle)
 * so even a neighbour outside the rectangle (LOD) stays finite.
 * Rectangle: x in [-tx_s, tx_s] with tx_s = tx_b, widened to tx_b cos(dep_v)
 * / cos(dep_s) when the sampling camera is pitched below the view (that
 * covers every view ray below the horizon), widened further where a view
 * ray's reachable terrain needs it (a view pitched up: pgm.c,
 * columns_for_view, up to FT_PGM_COLUMNS_WIDEN_MAX tx_b), and cut where
 * rays get flatter than eps (the cap taken over rows down to -tan a at
 * least, so the columns do not narrow when the bottom edge rises: a level
 * ray's terrain can lie under the eps line at the sides, below that edge);
 * y from the bottom edge y_b, extended by gamma, to tan(min(a, dep_s - eps))
 * (top). y_b is the VIEW's bottom edge, tan(dep_s - dep_v - a): both
 * cameras share the right vector, so the view's roll-free bottom edge is a
 * row of the sampling image, and the rows below it (down to the sampling
 * camera's own edge -tan a, where it is pitched down) hold ground the view
 * cannot show except through the peaks the extension looks for. A view
 * pitched up at altitude gave most of the grid to them: a climb frame at
 * 7 km pitched 14.8 degrees up drew its ridge tops with a third of the rows.
 * A level view gave them half. Where the view's bottom edge is not below
 * the top edge (it shows only peaks above the eye) or its top edge rises
 * past the zenith (it sees terrain above the eye behind it, whose base
 * points lie past the nadir, where the extension does not look), y_b is
 * the sampling camera's own edge -tan a.
 *
 * Viewport extension below the sampling camera: a peak of height m (above
 * the base plane) nearer than the bottom rows' ground points can reach into
 * the view without being sampled. The rule: with r the base-plane
 * distance of the nearest view ray (depression beta, tan beta = h / r), lower
 * the bottom edge by gamma,
 *     tan(gamma) = r h m / (h^3 + r^2 (h - m))
 * (gamma = 90 deg - beta when m >= h makes the denominator <= 0): the ray at
 * beta + gamma meets the plane at x = (h - m) r / h, and a peak of height m
 * nearer than x stays under the view's bottom edge. Applied here:
 *  - per bottom column (left corner, centre, right corner of the sampling
 *    rectangle's bottom edge, whose ground points span the wedge in front of
 *    the eye): a corner's ray is flatter than the centre's and needs more;
 *  - r and beta are those of the VIEW's bottom edge in that column's azimuth
 *    (the same ray unless the sampling camera is pitched below the view,
 *    whose lower bottom edge would ask for peaks the view never shows);
 *  - m per distance piece: FT_PGM_GAMMA_BANDS + 1 bands [x1 / 2, x1] (x1 =
 *    rc, rc / 2, ...; the last [0, x1]) of FT_PGM_GAMMA_PIECES pieces each, m
 *    = the highest terrain in the piece's box (ft_pgm_max_height: exact near
 *    the eye, else the max pyramid's bound); the piece asks for x, but never
 *    nearer than its own near edge (nearer ground holds none of its peaks);
 *  - the bottom edge is lowered until every column's ground point is as near
 *    as its nearest such x (bisection along the column), and gamma is what
 *    that adds to the half angle.
 * For the centre column, an unpitched sampling camera and one piece [0, r]
 * this is the formula exactly; the pieces keep a high peak far away (or a
 * slope beside a thin, diagonal wedge) from dragging the edge to the nadir.
 * The bottom edge stops at FT_PGM_HALF_ANGLE_MAX_RAD below the axis, or at
 * the nadir if that is lower (a nearly level sampling camera close to a
 * hillside needs the ground right under the eye).
 *
 * Level of detail per vertex: r = the ground distance (in grid cells) to the
 * farthest of its 4 grid neighbours' ground points; level L = max(0,
 * floor(log2 r)) of the AVERAGE pyramid, parent weight w = r / 2^L - 1
 * (rising linearly from 0 to 1 across the level); height = mix(h_L, h_L+1, w),
 * so L + w is continuous in r and samples never pop. Level L is sampled
 * bilinearly at texel coordinate u = (g + 0.5) / 2^L - 0.5 (a level-L texel
 * is the mean of 2^L x 2^L samples centred at that coordinate; level 0 is the
 * exact bilinear surface), indices clamped into the level. The coarsest
 * level (1 x 1) has no parent (w = 0). */
#ifndef FT_PGM_H
#define FT_PGM_H

#include <stdint.h>

#include "core/camera.h"
#include "core/units.h"
#include "terrain/terrain.h"

#define FT_PGM_GRID_SIDE_MIN 2u
#define FT_PGM_GRID_SIDE_MAX 8192u
/* 16-bit indices: a band of rows holds at most this many vertices. */
#define FT_PGM_BAND_VERTICES_MAX 65536u
/* Smallest depression of the sampling camera's top edge (0.01 deg: the ray
 * meets a plane 1 km below at 5700 km). */
#define FT_PGM_EPS_MIN_RAD (0.01 * FT_PI / 180.0)
/* Largest half angle of the sampling rectangle (tan 88 deg = 28.6). */
#define FT_PGM_HALF_ANGLE_MAX_RAD (88.0 * FT_PI / 180.0)
/* The columns are widened for the view's rays up to this factor of the
 * view's own half width (pgm.c, columns_for_view). */
#define FT_PGM_COLUMNS_WIDEN_MAX 1.5
/* Boxes up to this many cells a side get the exact maximum (pgm.c). */
#define FT_PGM_EXACT_MAX_CELLS 8u
/* Distance bands (halving toward the eye) the viewport extension checks,
 * and pieces per band (each its own box). */
#define FT_PGM_GAMMA_BANDS 12u
#define FT_PGM_GAMMA_PIECES 8u
/* The sampling eye is at least this high above the base plane. */
#define FT_PGM_MIN_HEIGHT_M 1.0

typedef struct ft_pgm_sampling {
    double eye_m[3];          /* viewing eye (world) */
    double base_z_m;          /* base plane: terrain minimum less the largest curvature drop */
    double lift_m;            /* sampling eye = viewing eye + (0, 0, lift_m) */
    int mirrored;             /* eye below the base plane: view mirrored through it */
    double height_m;          /* h: sampling eye above the base plane, >= FT_PGM_MIN_HEIGHT_M */
    double forward[3], right[3], up[3]; /* sampling frame (world, unit, right horizontal) */
    double view_depression_rad; /* dep_v: the view's forward below the horizon */
    double roll_rad;            /* the view's roll in that frame */
    double half_x_tan, half_y_tan; /* tx_b, ty_b: view frustum bounded in the roll-free frame */
    double far_m;               /* farthest grid corner, horizontally */
    double eps_rad;             /* top edge depression bound */
    double depression_rad;      /* dep_s */
    int pitched_down;           /* dep_s > dep_v (the view reaches up to or past the horizon) */
    double near_ground_m;  /* sampling bottom centre ray's ground distance (0: past nadir) */
    double missed_max_m;   /* highest m (above base) of a piece that asked for more */
    double gamma_rad;           /* viewport extension */
    double rect[4];             /* x0, y0, x1, y1 (tan units, sampling image plane) */
    double min_neg_dz;          /* floor for -d_z (unit: the ray of a rect point) */
} ft_pgm_sampling;

/* One grid vertex as the shader computes it. */
typedef struct ft_pgm_vertex {
    double ground_rel_m[2]; /* P.xy - viewing eye.xy (unclamped) */
    double grid[2];         /* P in grid coordinates, clamped into the grid */
    double r_cells;         /* ground distance to the farthest neighbour, cells */
    uint32_t level;         /* avg pyramid level L */
    double parent_w;        /* weight of level L + 1 */
    double height_m;        /* mix(h_L, h_L+1, w) */
    double pos_rel_eye_m[3]; /* as drawn: lowered by the curvature drop (terrain.h) */
} ft_pgm_vertex;

/* pgm.heights = clipmap: what the vertex shader is given per frame
 * (shaders/pgm_grid.glsl, FT_PGM_CLIP), in double. Per level L: base, the
 * level-L sample at or below the eye; off, the eye less base 2^L (level-0
 * samples); box, the resident level-L samples relative to base, inclusive
 * (x0, y0, x1, y1; x1 < x0: none). clamp_m: what is drawn, metres from the
 * eye. texel(ctx, L, a, b): the cached height of level-L sample (a, b). */
#define FT_PGM_CLIP_LEVELS_MAX 16u
typedef double (*ft_pgm_texel_fn)(const void *ctx, uint32_t level, int64_t a, int64_t b);
typedef struct ft_pgm_clip_view {
    uint32_t levels;
    double transition_samples;
    int64_t base[FT_PGM_CLIP_LEVELS_MAX][2];
    double off[FT_PGM_CLIP_LEVELS_MAX][2];
    double box[FT_PGM_CLIP_LEVELS_MAX][4];
    double clamp_m[4];
    ft_pgm_texel_fn texel;
    const void *ctx;
} ft_pgm_clip_view;

/* The finest level whose resident box holds g0 (level-0 samples from the
 * eye) one sample in from its edge, plus how far into the last
 * transition_samples before that edge g0 is (0..1); the top level when none. */
double ft_pgm_clip_resident(const ft_pgm_clip_view *v, double g0x, double g0y);

/* 1 when the eye's own ground is drawn from a level past 0: level 0's
 * resident samples do not hold the eye one sample in from their edge. */
int ft_pgm_clip_eye_coarser(const ft_pgm_clip_view *v);

/* Grid vertex (i, j) over the clip cache: the shader's arithmetic (level =
 * max(log2 r, resident) split into L + w, bilinear in L and L + 1 inside
 * their resident boxes), cell_* and curv_drop_per_m2 the terrain's. grid[]
 * holds g0; level and parent_w as drawn. */
void ft_pgm_clip_vertex_at(const ft_pgm_sampling *s, const ft_pgm_clip_view *v,
                           double cell_x_m, double cell_y_m, double curv_drop_per_m2,
                           uint32_t cols, uint32_t rows, uint32_t i, uint32_t j,
                           ft_pgm_vertex *out);

/* dep_s from dep_v, the half angle a and eps (closed form, see the top). */
double ft_pgm_sampling_depression(double view_depression_rad, double half_angle_rad,
                                  double eps_rad);

/* gamma from h, m (both above the base plane), r; never more than room_rad
 * (the angle left to the nadir), 0 when m <= 0. */
double ft_pgm_gamma(double h_m, double m_m, double r_m, double room_rad);

/* L = max(0, floor(log2 r)) and w = r / 2^L - 1 in [0, 1), for a pyramid of
 * `levels` avg levels (L <= levels - 1; at the coarsest level w = 0). */
void ft_pgm_lod(double r_cells, uint32_t levels, uint32_t *level, double *parent_w);

/* Avg level `level` sampled bilinearly at grid coordinate (gx, gy) (see the
 * top); level 0 is the bilinear height field. grad (may be NULL): dh/dg per
 * grid cell (x, y). */
double ft_pgm_level_height(const ft_terrain *t, uint32_t level, double gx, double gy,
                           double grad[2]);

/* Highest terrain over world box [x0, x1] x [y0, y1]: exact (the bilinear
 * surface's maximum) for a box of at most FT_PGM_EXACT_MAX_CELLS cells a
 * side, else the max pyramid's bound (at most 4 x 4 texels of one level are
 * read); -INFINITY if the box misses the grid. */
double ft_pgm_max_height(const ft_terrain *t, double x0_m, double y0_m, double x1_m,
                         double y1_m);

/* What the grid is laid over: the world box its points are clamped into,
 * the height range of everything drawn, and the highest drawn height in a
 * world box (-INFINITY: none there). Over the terrain: its grid, its range
 * and ft_pgm_max_height; over the clipmap cache: the coarsest level's box
 * and the resident blocks' bounds. */
typedef double (*ft_pgm_max_fn)(const void *ctx, double x0_m, double y0_m, double x1_m,
                                double y1_m);
typedef struct ft_pgm_surface {
    double x0_m, y0_m, x1_m, y1_m;
    double zmin_m, zmax_m;
    ft_pgm_max_fn max_in;
    const void *ctx;
    double curv_drop_per_m2; /* the terrain's (terrain.h) */
} ft_pgm_surface;

/* The terrain t as ground (ctx = t). */
ft_pgm_surface ft_pgm_surface_of_terrain(const ft_terrain *t);

/* The sampling camera for viewing camera c over t (per frame; O(levels)). */
void ft_pgm_setup(ft_pgm_sampling *s, const ft_camera *c, const ft_terrain *t);
/* The same over any ground. */
void ft_pgm_setup_over(ft_pgm_sampling *s, const ft_camera *c, const ft_pgm_surface *g);

/* Ray of grid point (i, j) (real numbers: neighbours may lie outside). */
void ft_pgm_ray(const ft_pgm_sampling *s, uint32_t cols, uint32_t rows, double i, double j,
                double dir[3]);
/* Its base-plane point, relative to the viewing eye (xy). */
void ft_pgm_ground(const ft_pgm_sampling *s, uint32_t cols, uint32_t rows, double i, double j,
                   double rel_xy_m[2]);

/* Vertex (i, j) exactly as shaders/pgm.vert.glsl places it. */
void ft_pgm_vertex_at(const ft_pgm_sampling *s, const ft_terrain *t, uint32_t cols,
                      uint32_t rows, uint32_t i, uint32_t j, ft_pgm_vertex *out);

/* Avg levels 1.. side by side in one texture (level L at origin_px[L],
 * size of t->pyr.avg[L]): level 1 at (0, 0), levels 2.. stacked in a column
 * right of it. Level 0 (the heights) is not in the atlas. Returns 0 when
 * the pyramid has a single level (nothing to lay out). */
int ft_pgm_atlas_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                        uint32_t *height_px);

#endif
