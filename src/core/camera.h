/* camera.h - a camera pose in double precision, and what the GPU gets.
 *
 * Attitude convention (aircraft): heading clockwise from north, pitch up
 * positive, roll right-wing-down positive, applied in that order (Z-X'-Y'').
 * Camera axes in world: right, up, forward (OpenGL view looks along -back).
 *
 * Relative to eye: the eye position stays double; the GPU receives float
 * offsets (terrain origin minus eye) and a rotation-only view matrix, so
 * 1e7 m coordinates do not jitter.
 *
 * Pixels: (px, py) with py = 0 the TOP row; pixel centres at +0.5. */
#ifndef FT_CAMERA_H
#define FT_CAMERA_H

#include <stdint.h>

#include "core/ft_status.h"

typedef struct ft_pose {
    double lat_deg, lon_deg, alt_m;
    double heading_deg, pitch_deg, roll_deg;
} ft_pose;

typedef struct ft_camera {
    double eye_m[3];       /* world */
    double right[3];       /* unit vectors in world */
    double up[3];
    double forward[3];
    double fovy_rad;
    uint32_t width_px, height_px;
    double near_m, far_m;
    /* K = height_px / (2 tan(fovy/2)): metres at distance d to pixels. */
    double px_per_rad_k;
    float view_rot[16]; /* column-major, rotation only (eye at origin) */
    float proj[16];     /* column-major perspective */
    float view_proj[16];
} ft_camera;

/* The view a selection was made for. Frames whose camera matches the key
 * bit for bit (any change of pose or viewport does not) may keep the last
 * selection; valid = 0 makes the next frame select again. */
typedef struct ft_view_key {
    int valid;
    double eye_m[3], forward[3], up[3], fovy_rad;
    uint32_t width_px, height_px;
} ft_view_key;

void ft_view_key_take(ft_view_key *k, const ft_camera *cam);
int ft_view_key_matches(const ft_view_key *k, const ft_camera *cam);

/* Builds a camera at world position eye_m with the given attitude (radians).
 * near/far are picked by the caller (see ft_camera_pick_depth_range). */
ft_status ft_camera_init(ft_camera *c, const double eye_m[3], double heading_rad,
                         double pitch_rad, double roll_rad, double fovy_rad, uint32_t width_px,
                         uint32_t height_px, double near_m, double far_m, ft_error *err);

#if FT_WITH_HORIZON
/* The zero-pitch line (the horizon of the eye's horizontal plane: every
 * view direction with no vertical component) in pixel coordinates (origin
 * top-left, y down): two points on it at the view's left and right edges
 * (or top and bottom edges when it is steeper than 45 degrees). Returns 0
 * when the view looks straight up or down (the line is not in the image
 * plane's finite part). On a flat sea the visible sea edge lies below it by
 * the dip sqrt(2 h / R) (h the eye's height, R the earth's radius). */
int ft_camera_horizon_px(const ft_camera *c, double p0[2], double p1[2]);
#endif

/* Unit ray direction (world) through image point (px, py) in pixel units:
 * pass (x + 0.5, y + 0.5) for the centre of pixel (x, y). */
void ft_camera_pixel_ray(const ft_camera *c, double px, double py, double dir[3]);

/* Distance from eye_m to the 3D box [x0, x1] x [y0, y1] x [zmin, zmax], the
 * z range first widened by the curvature drop over the rectangle (a point at
 * horizontal distance d is drawn curv_k_per_m d^2 lower); 0 inside. */
double ft_camera_box_distance_m(const double eye_m[3], double x0, double x1, double y0,
                                double y1, double zmin, double zmax, double curv_k_per_m);

/* The depth range rule below from a lower bound of the distance to the
 * drawn terrain (closest_m), its height range and its horizontal box. */
void ft_camera_depth_range_from(const double eye_m[3], double closest_m, double zmin_m,
                                double zmax_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos,
                                double curv_k_per_m, double *near_m, double *far_m);

/* Replaces c's depth range (projection and view_proj follow); the view is
 * unchanged. For a method whose drawn terrain is not the scene's grid. */
ft_status ft_camera_set_depth_range(ft_camera *c, double near_m, double far_m, ft_error *err);

/* The global rule (the fallback when a terrain has no min/max pyramid):
 * near plane from the eye's clearance above the highest terrain (or its
 * horizontal distance to the box), times corner_cos, the cosine of the
 * angle between the view axis and a frustum corner ray:
 * 1 / sqrt(1 + tan^2(fovx/2) + tan^2(fovy/2)), with a factor 2 margin; far
 * plane from the farthest terrain corner; both clamped to sane bounds. */
void ft_camera_pick_depth_range(const double eye_m[3], double terrain_min_z_m,
                                double terrain_max_z_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos, double *near_m,
                                double *far_m);

struct ft_terrain;

/* Lower bound of the distance from eye_m to the terrain as drawn: the
 * surface over every grid cell lowered by curv_k_per_m d^2 (d: horizontal
 * distance from the eye; 1 / (2 R) on a sphere, 0 on a flat earth). From
 * the min/max cell pyramid: per level from fine to coarse, a window of 8
 * texels around the eye (more along the axis with the smaller cells, up to
 * 64, so it is about square in metres; even-aligned, so the windows nest);
 * the bound is the least distance from the eye to the 3D box [x0, x1] x
 * [y0, y1] x [zmin - k dmax^2, zmax - k dmin^2] of each texel of a window
 * that the finer window does not cover, and of every texel of the coarsest
 * level. No recursion, no memory, at most 8 x 64 texels a level. Without
 * a pyramid (t->pyr.minmax_levels == 0) the whole grid is one box (the
 * global rule). 0 when the eye is inside a box. */
double ft_camera_terrain_clearance_m(const struct ft_terrain *t, const double eye_m[3],
                                     double curv_k_per_m);

/* The depth range every frame uses: near = clamp(0.5 * clearance *
 * corner_cos, 0.25 m, 5000 m) with the clearance above, far = the farthest
 * grid corner with the height range widened by the curvature drop (times
 * 1.05, plus 1 m). The caller passes the drop coefficient curv_k_per_m
 * (metres of drop per square metre of horizontal distance) it draws the
 * terrain with. */
void ft_camera_depth_range_for_terrain(const struct ft_terrain *t, const double eye_m[3],
                                       double corner_cos, double curv_k_per_m, double *near_m,
                                       double *far_m);

/* Eye-depth span of one step of the depth buffer at eye depth z (metres),
 * for the standard GL projection with near/far and glDepthRange(0, 1):
 * 2^-bits (f - n) z^2 / (f n) for a fixed-point buffer; for a float buffer
 * (depth_float) the float32 spacing of the window depth at z, which near
 * the far plane is 2^-24: the same as 24-bit fixed point. INFINITY for a
 * bad range. */
double ft_camera_depth_step_m(double near_m, double far_m, uint32_t depth_bits, int depth_float,
                              double eye_depth_m);

#endif
