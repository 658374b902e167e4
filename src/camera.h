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

#include "ft_status.h"

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

/* Builds a camera at world position eye_m with the given attitude (radians).
 * near/far are picked by the caller (see ft_camera_pick_depth_range). */
ft_status ft_camera_init(ft_camera *c, const double eye_m[3], double heading_rad,
                         double pitch_rad, double roll_rad, double fovy_rad, uint32_t width_px,
                         uint32_t height_px, double near_m, double far_m, ft_error *err);

/* Unit ray direction (world) through image point (px, py) in pixel units:
 * pass (x + 0.5, y + 0.5) for the centre of pixel (x, y). */
void ft_camera_pixel_ray(const ft_camera *c, double px, double py, double dir[3]);

/* Near plane from the eye's clearance above the highest terrain (times
 * corner_cos, the cosine of the angle between the view axis and a frustum
 * corner ray: 1 / sqrt(1 + tan^2(fovx/2) + tan^2(fovy/2))), far plane from
 * the farthest terrain corner; both clamped to sane bounds. */
void ft_camera_pick_depth_range(const double eye_m[3], double terrain_min_z_m,
                                double terrain_max_z_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos, double *near_m,
                                double *far_m);

#endif
