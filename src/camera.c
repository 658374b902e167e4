#include "camera.h"

#include <math.h>
#include <string.h>

static void mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    for (int c = 0; c < 4; ++c) {
        for (int row = 0; row < 4; ++row) {
            float s = 0.0f;
            for (int k = 0; k < 4; ++k) {
                s += a[k * 4 + row] * b[c * 4 + k];
            }
            r[c * 4 + row] = s;
        }
    }
    memcpy(out, r, sizeof r);
}

ft_status ft_camera_init(ft_camera *c, const double eye_m[3], double heading_rad,
                         double pitch_rad, double roll_rad, double fovy_rad, uint32_t width_px,
                         uint32_t height_px, double near_m, double far_m, ft_error *err)
{
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(eye_m[i])) {
            return ft_fail(err, FT_ERR_NUMERIC, "camera: eye coordinate %d is not finite", i);
        }
    }
    if (!isfinite(heading_rad) || !isfinite(pitch_rad) || !isfinite(roll_rad)) {
        return ft_fail(err, FT_ERR_NUMERIC, "camera: attitude is not finite");
    }
    if (!(fovy_rad > 1e-4 && fovy_rad < 3.1)) {
        return ft_fail(err, FT_ERR_ARG, "camera: fovy %.6f rad outside (0.0001, 3.1)", fovy_rad);
    }
    if (width_px == 0 || height_px == 0 || !(near_m > 0.0) || !(far_m > near_m)) {
        return ft_fail(err, FT_ERR_ARG, "camera: bad viewport %ux%u or depth range %g..%g",
                       width_px, height_px, near_m, far_m);
    }
    memset(c, 0, sizeof *c);
    memcpy(c->eye_m, eye_m, sizeof c->eye_m);
    c->fovy_rad = fovy_rad;
    c->width_px = width_px;
    c->height_px = height_px;
    c->near_m = near_m;
    c->far_m = far_m;
    c->px_per_rad_k = (double)height_px / (2.0 * tan(fovy_rad * 0.5));

    /* Heading/pitch give the forward direction; roll turns right/up about it. */
    double ch = cos(heading_rad), sh = sin(heading_rad);
    double cp = cos(pitch_rad), sp = sin(pitch_rad);
    double cr = cos(roll_rad), sr = sin(roll_rad);
    double fwd[3] = {sh * cp, ch * cp, sp};
    double right0[3] = {ch, -sh, 0.0};          /* level right wing */
    double up0[3] = {-sh * sp, -ch * sp, cp};   /* right0 x fwd... = up with pitch */
    for (int i = 0; i < 3; ++i) {
        c->forward[i] = fwd[i];
        c->right[i] = cr * right0[i] - sr * up0[i];
        c->up[i] = sr * right0[i] + cr * up0[i];
    }

    /* View rotation: rows are right, up, -forward (column-major storage). */
    float *v = c->view_rot;
    for (int i = 0; i < 3; ++i) {
        v[i * 4 + 0] = (float)c->right[i];
        v[i * 4 + 1] = (float)c->up[i];
        v[i * 4 + 2] = (float)-c->forward[i];
        v[i * 4 + 3] = 0.0f;
    }
    v[12] = v[13] = v[14] = 0.0f;
    v[15] = 1.0f;

    double f = 1.0 / tan(fovy_rad * 0.5);
    double aspect = (double)width_px / (double)height_px;
    float *p = c->proj;
    memset(p, 0, 16 * sizeof(float));
    p[0] = (float)(f / aspect);
    p[5] = (float)f;
    p[10] = (float)((far_m + near_m) / (near_m - far_m));
    p[11] = -1.0f;
    p[14] = (float)(2.0 * far_m * near_m / (near_m - far_m));
    mat4_mul(c->view_proj, c->proj, c->view_rot);
    return FT_OK;
}

void ft_camera_pixel_ray(const ft_camera *c, double px, double py, double dir[3])
{
    double t = tan(c->fovy_rad * 0.5);
    double aspect = (double)c->width_px / (double)c->height_px;
    double sx = ((px / (double)c->width_px) * 2.0 - 1.0) * t * aspect;
    double sy = (1.0 - (py / (double)c->height_px) * 2.0) * t;
    double len = 0.0;
    for (int i = 0; i < 3; ++i) {
        dir[i] = c->forward[i] + sx * c->right[i] + sy * c->up[i];
        len += dir[i] * dir[i];
    }
    len = sqrt(len);
    for (int i = 0; i < 3; ++i) {
        dir[i] /= len;
    }
}

void ft_camera_pick_depth_range(const double eye_m[3], double terrain_min_z_m,
                                double terrain_max_z_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos, double *near_m,
                                double *far_m)
{
    /* Nothing of the terrain can be closer than the clearance above its
     * highest point (or its horizontal distance to the box). The near plane
     * cuts at a DEPTH along the view axis, and a point at that distance in
     * the frustum's corner lies only distance * corner_cos deep (0.16 at
     * FOV 150): scale by it, and keep a factor of 2 margin; a 24-bit depth
     * buffer holds far/near ratios of 1e5 well. */
    double dx = 0.0, dy = 0.0;
    if (eye_m[0] < box_min_m[0]) dx = box_min_m[0] - eye_m[0];
    if (eye_m[0] > box_max_m[0]) dx = eye_m[0] - box_max_m[0];
    if (eye_m[1] < box_min_m[1]) dy = box_min_m[1] - eye_m[1];
    if (eye_m[1] > box_max_m[1]) dy = eye_m[1] - box_max_m[1];
    double dz = 0.0;
    if (eye_m[2] > terrain_max_z_m) dz = eye_m[2] - terrain_max_z_m;
    if (eye_m[2] < terrain_min_z_m) dz = terrain_min_z_m - eye_m[2];
    double closest = sqrt(dx * dx + dy * dy + dz * dz);
    if (!(corner_cos > 0.0) || corner_cos > 1.0) corner_cos = 1.0;
    double n = 0.5 * closest * corner_cos;
    if (n < 0.25) n = 0.25;
    if (n > 5000.0) n = 5000.0;

    double far2 = 0.0;
    for (int i = 0; i < 4; ++i) {
        double cx = (i & 1) ? box_max_m[0] : box_min_m[0];
        double cy = (i & 2) ? box_max_m[1] : box_min_m[1];
        double zl = fabs(eye_m[2] - terrain_min_z_m);
        double zh = fabs(eye_m[2] - terrain_max_z_m);
        double z = zl > zh ? zl : zh;
        double d2 = (cx - eye_m[0]) * (cx - eye_m[0]) + (cy - eye_m[1]) * (cy - eye_m[1]) + z * z;
        if (d2 > far2) far2 = d2;
    }
    double f = sqrt(far2) * 1.05 + 1.0;
    if (f < n * 4.0) f = n * 4.0;
    *near_m = n;
    *far_m = f;
}
