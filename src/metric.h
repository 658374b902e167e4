/* metric.h - the screen-space error every method is judged by.
 *
 * For each pixel with terrain: P = rendered surface point (camera-relative,
 * from the method's float position target), H = bilinear height of the full-
 * resolution grid at P.xy, e = |P.z - H| * K / |P - eye| in pixels, with
 * K = height_px / (2 tan(fovy/2)). Per frame: max, 99.9th percentile, mean of
 * e over terrain pixels, and the coverage mismatches against the reference
 * (terrain here but sky in the reference, and the reverse).
 *
 * Details (tested in tests/test_metric.c):
 *  - terrain pixel: pos_rgba w > 0.5 (a NaN w is sky).
 *  - a terrain pixel whose xyz is not finite is counted in nonfinite_px and
 *    makes max_px = INFINITY; it is left out of mean_px and p999_px (which
 *    are over the finite terrain pixels only) and out of outside_grid_px.
 *  - P.xy outside the grid: counted in outside_grid_px; its error still
 *    counts, against the edge-clamped height (ft_terrain_height_at).
 *  - |P - eye| is floored at the camera's near_m (no division by zero).
 *  - p999_px: with n finite terrain pixels, the value of rank
 *    k = ceil(0.999 n) - 1 (0-based) in ascending order (integer arithmetic,
 *    ft_metric_p999_rank), found by an iterative quickselect in scratch.
 *  - no terrain pixels: max, p999 and mean are 0 (never NaN).
 * Cost O(width * height) expected (quickselect), no allocation. */
#ifndef FT_METRIC_H
#define FT_METRIC_H

#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "reference.h"
#include "terrain.h"

typedef struct ft_error_stats {
    double max_px, p999_px, mean_px;
    uint32_t terrain_px;      /* pixels the method covered */
    uint32_t only_method_px;  /* terrain in the frame, sky in the reference */
    uint32_t only_ref_px;     /* sky in the frame, terrain in the reference */
    uint32_t outside_grid_px; /* method pixels whose P.xy fell outside the grid */
    uint32_t nonfinite_px;    /* terrain pixels with a non-finite P (max_px = inf) */
} ft_error_stats;

/* 0-based rank of the 99.9th percentile among n >= 1 sorted values:
 * ceil(0.999 n) - 1, computed exactly in integers. 0 for n == 0. */
size_t ft_metric_p999_rank(size_t n);

/* pos_rgba: width*height*4 floats, row 0 = top; xyz = P - eye (world axes,
 * metres), w > 0.5 means terrain. ref may be NULL (no coverage comparison).
 * scratch: width*height floats for the percentile (scratch_cap >= that,
 * else FT_ERR_ARG). ft_terrain_height_at needs t->heights_m. */
ft_status ft_metric_compute(const ft_terrain *t, const ft_camera *c, const float *pos_rgba,
                            const ft_ref_pixel *ref, float *scratch, size_t scratch_cap,
                            ft_error_stats *out, ft_error *err);

#endif
