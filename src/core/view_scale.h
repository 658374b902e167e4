/* view_scale.h - how many pixels a vertical metre covers, bounded over a box.
 *
 * Every error the methods bound is vertical: the drawn surface lies within
 * e metres of the truth straight above or below it. A point q (relative to
 * the eye; camera axes f forward, r right, u up, all in world coordinates)
 * is drawn at K (q.r, q.u) / Z pixels from the image centre, Z = q.f. Moving
 * it up by dz moves its image by
 *
 *   K dz / Z * |(r_z - x f_z, u_z - y f_z)|,   (x, y) = (q.r, q.u) / Z,
 *
 * (the derivative of the projection along world z). With Z = d cos theta
 * (d = |q|, theta off the view axis) that is K dz G / d, G = A B:
 *   A = |(r_z - x f_z, u_z - y f_z)|: how much of the vertical is seen
 *       across the ray (0 looking straight down it);
 *   B = sqrt(1 + x^2 + y^2) = 1 / cos theta: the image plane's stretch.
 * Since (p x e)_z summed in squares over the orthonormal axes e is |q_h|^2
 * (q_h the horizontal part of q), A Z = sqrt(|q_h|^2 - (q_x f_y - q_y f_x)^2):
 * no cancellation near the nadir, and only the view axis is needed.
 * A <= B (Cauchy-Schwarz, (r_z, u_z, f_z) is a unit vector), so G is at
 * most 1 / cos^2 theta, the radial stretch an arbitrary displacement would
 * get, and about 1 / cos theta for a level view: 1.39 instead of 1.92 at
 * the corners of a 60 deg 4:3 view. The error metric measures the same
 * displacement exactly (metric.h), so a bound built on G bounds the metric.
 *
 * Over a box in front of the eye, the image of the box is the convex hull
 * of its corners' images, and A and B are convex in (x, y), so each peaks at
 * a corner: G over the box <= max A x max B over the 8 corners, and a
 * sub-box never gets more (nested boxes keep nested errors). Points outside
 * the frustum are not drawn, so each factor is also capped at its largest
 * over the image rectangle (a convex function: at a corner of the image);
 * a box with a corner at or behind the eye gets the caps.
 *
 * The bintree and the clipmap bound their boxes with G (ft_view_bound below).
 * pgrid's per-fragment rho keeps
 * 1 / cos^2 theta (>= G): its mesh also misplaces the terrain's edge
 * sideways, which no vertical bound covers, and its sweep test at 100 km
 * straight down relies on the larger factor marking those pixels. */
#ifndef FT_VIEW_SCALE_H
#define FT_VIEW_SCALE_H

#include "core/camera.h"

/* What the gain needs of a camera. */
typedef struct ft_view_gain_frame {
    double fwd[3]; /* the view axis (world, unit) */
    double a_cap; /* largest A over the image rectangle */
    double b_cap; /* largest B over it: 1 / ft_view_corner_cos */
} ft_view_gain_frame;

/* Cosine of the angle between the view axis and a frustum corner ray:
 * 1 / sqrt(1 + tan^2(fovx/2) + tan^2(fovy/2)). */
double ft_view_corner_cos(const ft_camera *c);

void ft_view_gain_frame_from_camera(const ft_camera *c, ft_view_gain_frame *g);

/* Upper bound of G = A B over the points of the axis-aligned box [lo, hi]
 * (relative to the eye, metres) that lie inside the frustum (see the top).
 * Always in [0, a_cap b_cap]. */
double ft_view_vertical_gain(const ft_view_gain_frame *g, const double lo_rel_m[3],
                             const double hi_rel_m[3]);

/* ---- a vertical error over a box, in pixels ----------------------------------

 * What a method's per-box bound needs of a view, in the method's own frame
 * (world metres less an origin the caller chose; heights as stored): the
 * eye, K (pixels per radian), the gain frame, the curvature drop k (a point
 * at horizontal distance r from the eye is drawn k r^2 lower) and the
 * frustum's four side planes through the eye (a point p is inside iff
 * dot(n, p - eye) >= 0 for each). */
typedef struct ft_view_bound {
    double eye_m[3];
    double k_px;
    ft_view_gain_frame gain;
    double curv_drop_per_m2;
    double plane_n[4][3];
} ft_view_bound;

/* origin_m: the world x, y of the frame's origin. */
void ft_view_bound_from_camera(const ft_camera *c, const double origin_m[2],
                               double curv_drop_per_m2, ft_view_bound *v);

/* The box as drawn: its z range lowered by the curvature drop, k r^2 with
 * r at least the box's nearest and at most its farthest xy point. */
void ft_view_bound_drawn_box(const ft_view_bound *v, double lo_m[3], double hi_m[3]);

/* The terms of an error err_m over a drawn box: the distance from the eye
 * to it, the vertical gain over it (0 when the error or the distance is 0:
 * not needed), and the error plus the chord k L^2 / 4 by which a straight
 * edge of length L (at most the box's xy diagonal) lies under the curved
 * surface. */
typedef struct ft_view_box_terms {
    double dist_m;
    double gain;
    double err_m;
} ft_view_box_terms;

void ft_view_bound_terms(const ft_view_bound *v, double err_m, const double lo_m[3],
                         const double hi_m[3], ft_view_box_terms *out);

/* Pixels an error err_m over the drawn box can move a point of it on the
 * image: K (err + chord) G / distance; 0 for no error, +INF with the eye in
 * the box (and for an infinite or NaN error). */
double ft_view_bound_error_px(const ft_view_bound *v, double err_m, const double lo_m[3],
                              const double hi_m[3]);

/* 1 if the box lies wholly outside one frustum side plane or behind the
 * eye (nothing of it is drawn). */
int ft_view_bound_outside(const ft_view_bound *v, const double lo_m[3], const double hi_m[3]);

#endif
