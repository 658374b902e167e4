/* reference.h - ground truth: an exact CPU ray caster of the full-resolution
 * bilinear height field.
 *
 * For each pixel the ray from the eye is intersected with the bilinear patch
 * surface (per cell: the height along the ray is quadratic in t, solved in
 * closed form), visiting cells front to back with a max-mip traversal of the
 * min/max cell pyramids (terrain.h) so empty space is skipped. Iterative,
 * bounded loops, no recursion, no allocation: output goes to caller storage.
 * The surface exists only over the grid's extent [0, w-1] x [0, h-1].
 * Earth curvature (t->curv_drop_per_m2 = k > 0): the surface is drawn
 * lowered by k r^2 at horizontal distance r from the ray's origin (the
 * eye), as every method draws it; the caster bends the ray up by the same
 * amount instead (reference.c), which keeps the cell solve a quadratic.
 * Hit positions and distances stay along the straight ray (what the display
 * shows); the shading uses the terrain's own height.
 *
 * Hit rule: the first point along the ray (t >= 0) where the ray meets the
 * surface, from either side. An eye above the surface gets the usual hit; an
 * eye BELOW the surface at its xy gets the point where the ray first crosses
 * the surface from below (not distance 0); an eye exactly on the surface hits
 * at distance 0. A ray lying in a flat surface hits where it enters the grid.
 * Any finite eye works (also 1e7 m away: the eye is made relative to the grid
 * origin once, in double), as do axis-parallel, vertical and upward rays.
 * Without a min/max pyramid (t->pyr.minmax_levels == 0) the same traversal
 * runs on level 0 only (a plain cell walk, same results, slower).
 *
 * Cost: per ray O(L + k) texel visits, L = number of pyramid levels
 * (log2 of the grid side), k = texels whose z range the ray overlaps; a ray
 * over empty space costs O(log N), a grazing ray at worst O((w + h) * L).
 * Each visit is O(1) (one quadratic solve at level 0). ft_reference_render is
 * O(width_px * height_px) rays; no allocation, stack use O(1). */
#ifndef FT_REFERENCE_H
#define FT_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "terrain/terrain.h"

typedef struct ft_ref_pixel {
    float pos_rel_eye_m[3]; /* hit point minus eye (world axes) */
    float dist_m;           /* |hit - eye|, 0 if no hit */
    uint8_t hit;            /* 1 terrain, 0 sky */
    uint8_t rgba[4];        /* ft_shade_rgba8 of the hit, sky colour otherwise */
} ft_ref_pixel;

/* Intersects one ray (origin, unit dir, world metres) with the terrain.
 * Returns 1 and the distance along the ray of the first hit, else 0 (also
 * for non-finite input, a zero direction or a terrain without heights).
 * For a non-unit dir, *t_hit_m is the ray parameter (hit = origin + t dir). */
int ft_reference_ray(const ft_terrain *t, const double origin_m[3], const double dir[3],
                     double *t_hit_m);

/* Renders all width_px*height_px pixels of camera c into out (row 0 = top),
 * one ray through each pixel centre, ft_camera_pixel_ray(c, px + 0.5,
 * py + 0.5). Hits: shaded with the patch's analytic normal at the hit; sky:
 * rgba = round(255 * FT_SKY_*), alpha 255, position and dist 0.
 * out_cap is the number of ft_ref_pixel entries available. FT_ERR_ARG if
 * it is too small, the terrain has no heights or its pyramid is present
 * (minmax_levels > 0) but does not match the grid. */
ft_status ft_reference_render(const ft_terrain *t, const ft_camera *c, ft_ref_pixel *out,
                              size_t out_cap, ft_error *err);

#endif
