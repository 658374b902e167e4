/* reference.h - ground truth: an exact CPU ray caster of the full-resolution
 * bilinear height field.
 *
 * For each pixel the ray from the eye is intersected with the bilinear patch
 * surface (per cell: the height along the ray is quadratic in t, solved in
 * closed form), visiting cells front to back with a max-mip traversal of the
 * min/max cell pyramids (terrain.h) so empty space is skipped. Iterative,
 * bounded loops, no recursion, no allocation: output goes to caller storage.
 * The surface exists only over the grid's extent [0, w-1] x [0, h-1]. */
#ifndef FT_REFERENCE_H
#define FT_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "terrain.h"

typedef struct ft_ref_pixel {
    float pos_rel_eye_m[3]; /* hit point minus eye (world axes) */
    float dist_m;           /* |hit - eye|, 0 if no hit */
    uint8_t hit;            /* 1 terrain, 0 sky */
    uint8_t rgba[4];        /* ft_shade_rgba8 of the hit, sky colour otherwise */
} ft_ref_pixel;

/* Intersects one ray (origin, unit dir, world metres) with the terrain.
 * Returns 1 and the distance along the ray of the first hit, else 0. */
int ft_reference_ray(const ft_terrain *t, const double origin_m[3], const double dir[3],
                     double *t_hit_m);

/* Renders all width_px*height_px pixels of camera c into out (row 0 = top).
 * out_cap is the number of ft_ref_pixel entries available. */
ft_status ft_reference_render(const ft_terrain *t, const ft_camera *c, ft_ref_pixel *out,
                              size_t out_cap, ft_error *err);

#endif
