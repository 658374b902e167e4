/* metric.h - the screen-space error every method is judged by: what a person
 * at the display sees, per pixel, in pixels.
 *
 * Truth: the bilinear surface of the full-resolution grid, lowered by the
 * earth's curvature as every method draws it (terrain.h, curv_drop_per_m2:
 * z = H(x, y) - k ((x - eye_x)^2 + (y - eye_y)^2), k = 1 / (2 R) or 0).
 *
 * Per pixel with terrain, P = the drawn surface point (camera-relative, from
 * the method's float position target):
 *  - vertical error, exact projection: P' = (P.xy, truth z at P.xy); both P
 *    and P' go through the frame's own view and perspective (camera.h: K =
 *    height_px / (2 tan(fovy/2)) pixels per unit of tangent, the same scale as
 *    the GPU's view_proj), in double, and the error is the distance between
 *    the two image points in pixels (sub-pixel). A P' at or behind the eye's
 *    image plane (the true surface is not in front of the eye there) scores
 *    the image diagonal and is counted in behind_eye_px. The old formula
 *    |P.z - z'| K / |P - eye| equals this to first order on the view axis
 *    only (off axis it under-reports by up to 1 / cos^2 theta);
 *    tests/test_metric.c checks both.
 *  - occlusion (hidden-surface) error: where the frame and the reference
 *    (reference.h: first hit of the same pixel's ray) both show terrain but
 *    on different surfaces, the pixel is an occlusion mismatch. "Different"
 *    means their distances along the ray differ by more than the vertical
 *    error at the pixel explains: |t_P - t_ref| > 2 dz n_z / |dir . n| +
 *    1e-4 t_ref + 0.05 m, with dz = |P.z - z'(P.xy)| and n the true
 *    surface's unit normal at the reference hit (a vertical offset dz moves a
 *    ray's hit on a plane by dz n_z / |dir . n|; the factor 2 and the
 *    additive terms absorb the drawn surface's own slope and float32
 *    positions). A missed ridge, exposing terrain behind it, is such a pixel.
 *    Its error: the distance from its centre to the nearest pixel centre
 *    where the frame and the reference agree (both sky, or both terrain and
 *    not an occlusion mismatch), minus half a pixel (the boundary lies
 *    between the last mismatched and the first agreeing centre; a single
 *    flipped pixel at a silhouette scores 0.5 px). The search is exact over
 *    the whole image (a Euclidean distance transform, O(pixels)); with no
 *    agreeing pixel anywhere the error is the image diagonal. The pixel's
 *    error is the larger of its vertical and occlusion errors.
 *  - coverage mismatches (terrain here, sky in the reference, and the
 *    reverse) are counted, as before, and not given an error.
 * Per frame: max, 99.9th percentile, mean over terrain pixels, and the
 * largest vertical error alone (vertical_max_px).
 *
 * Details (tested in tests/test_metric.c):
 *  - terrain pixel: pos_rgba w > 0.5 (a NaN w is sky).
 *  - a terrain pixel whose xyz is not finite is counted in nonfinite_px and
 *    makes max_px = INFINITY; it is left out of mean_px and p999_px (which
 *    are over the finite terrain pixels only) and out of outside_grid_px.
 *  - P.xy outside the grid: counted in outside_grid_px; its error still
 *    counts, against the edge-clamped height (ft_terrain_height_at).
 *  - p999_px: with n finite terrain pixels, the value of rank
 *    k = ceil(0.999 n) - 1 (0-based) in ascending order (integer arithmetic,
 *    ft_metric_p999_rank), found by an iterative quickselect in scratch.
 *  - no terrain pixels: max, p999 and mean are 0 (never NaN).
 * Cost O(width * height) expected, no allocation: scratch is the caller's
 * (ft_metric_scratch_bytes). */
#ifndef FT_METRIC_H
#define FT_METRIC_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "measure/reference.h"
#include "terrain/terrain.h"

/* The metric's resolution at an edge: a pixel that any sub-pixel shift of
 * a silhouette or occlusion boundary flips scores this much (above), so a
 * bound under it is checked against it. */
#define FT_METRIC_FLIP_PX 0.5

typedef struct ft_error_stats {
    double max_px, p999_px, mean_px;
    double occlusion_max_px;  /* worst occlusion error (0 without any) */
    double vertical_max_px;   /* worst vertical error alone: the screen displacement of
                                 a drawn point, which a method's bound is about
                                 (occlusion errors are not in it; max_px has both) */
    uint32_t terrain_px;      /* pixels the method covered */
    uint32_t only_method_px;  /* terrain in the frame, sky in the reference */
    uint32_t only_ref_px;     /* sky in the frame, terrain in the reference */
    uint32_t occlusion_px;    /* terrain in both, on different surfaces */
    uint32_t outside_grid_px; /* method pixels whose P.xy fell outside the grid */
    uint32_t nonfinite_px;    /* terrain pixels with a non-finite P (max_px = inf) */
    uint32_t behind_eye_px;   /* pixels whose true point is not in front of the eye */
} ft_error_stats;

/* 0-based rank of the 99.9th percentile among n >= 1 sorted values:
 * ceil(0.999 n) - 1, computed exactly in integers. 0 for n == 0. */
size_t ft_metric_p999_rank(size_t n);

/* Bytes of scratch ft_metric_compute needs for a width x height frame
 * (per pixel: an error, a squared distance and a class byte; per line of the
 * distance transform: 3 (max side + 1) values). 0 if the size overflows. */
size_t ft_metric_scratch_bytes(uint32_t width_px, uint32_t height_px);

/* Image-plane distance in pixels between the projections of two
 * camera-relative points a and b (exact, double). Returns the image
 * diagonal when either is not in front of the eye (depth <= 1e-9 m). */
double ft_metric_projected_px(const ft_camera *c, const double a_rel_m[3], const double b_rel_m[3]);

/* pos_rgba: width*height*4 floats, row 0 = top; xyz = P - eye (world axes,
 * metres), w > 0.5 means terrain. ref may be NULL (no coverage or occlusion
 * comparison). scratch: scratch_bytes >= ft_metric_scratch_bytes(...), any
 * alignment suitable for float (else FT_ERR_ARG). ft_terrain_height_at needs
 * t->heights_m. */
ft_status ft_metric_compute(const ft_terrain *t, const ft_camera *c, const float *pos_rgba,
                            const ft_ref_pixel *ref, void *scratch, size_t scratch_bytes,
                            ft_error_stats *out, ft_error *err);

#endif
