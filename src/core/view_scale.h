/* view_scale.h - how many pixels a length subtends off the view axis.
 *
 * A perspective image maps a direction at angle theta off the view axis to
 * K tan(theta) pixels from the centre (K = camera.h's px_per_rad_k), so a
 * small angle there spans K / cos^2 theta pixels radially (K / cos theta
 * across): 1.9x at the corners of a 60 deg 4:3 view, 15x at FOV 150. A
 * displacement of L metres at distance d therefore moves a point by at most
 * K L / (d cos^2 theta) pixels (to first order). The error metric measures
 * this exactly (metric.h); the methods' bounds use the same gain, bounded
 * over a box (bintree) or per fragment (pgrid), so the bounds they claim
 * are bounds of the metric. Points outside the frustum are not drawn, so
 * theta is capped at the frustum corner's angle. */
#ifndef FT_VIEW_SCALE_H
#define FT_VIEW_SCALE_H

#include "core/camera.h"

/* Cosine of the angle between the view axis and a frustum corner ray:
 * 1 / sqrt(1 + tan^2(fovx/2) + tan^2(fovy/2)). */
double ft_view_corner_cos(const ft_camera *c);

/* Upper bound of 1 / cos^2 theta over the points of the axis-aligned box
 * [lo, hi] (relative to the eye, metres) that lie inside the frustum; fwd
 * is the unit view axis. The largest angle over the box is at one of its
 * corners (exact, and monotone: a sub-box never gets more); a box with a
 * corner at or behind the eye gets the frustum corner's gain
 * 1 / corner_cos^2. Always in [1, 1 / corner_cos^2]. */
double ft_view_offaxis_gain(const double fwd[3], double corner_cos, const double lo_rel_m[3],
                            const double hi_rel_m[3]);

#endif
