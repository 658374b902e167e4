/* metric.h - the screen-space error every method is judged by.
 *
 * For each pixel with terrain: P = rendered surface point (camera-relative,
 * from the method's float position target), H = bilinear height of the full-
 * resolution grid at P.xy, e = |P.z - H| * K / |P - eye| in pixels, with
 * K = height_px / (2 tan(fovy/2)). Per frame: max, 99.9th percentile, mean of
 * e over terrain pixels, and the coverage mismatches against the reference
 * (terrain here but sky in the reference, and the reverse). */
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
} ft_error_stats;

/* pos_rgba: width*height*4 floats, row 0 = top; xyz = P - eye (world axes,
 * metres), w > 0.5 means terrain. ref may be NULL (no coverage comparison).
 * scratch: width*height floats for the percentile. */
ft_status ft_metric_compute(const ft_terrain *t, const ft_camera *c, const float *pos_rgba,
                            const ft_ref_pixel *ref, float *scratch, size_t scratch_cap,
                            ft_error_stats *out, ft_error *err);

#endif
