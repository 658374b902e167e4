#include "core/camera.h"

#include <math.h>
#include <string.h>

#include "terrain/terrain.h"

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

#if FT_WITH_HORIZON
int ft_camera_horizon_px(const ft_camera *c, double p0[2], double p1[2])
{
    /* d(sx, sy) = forward + sx right + sy up (sx, sy: image-plane tangents)
     * is horizontal where f_z + sx r_z + sy u_z = 0, a line in the image */
    const double t = tan(c->fovy_rad * 0.5);
    const double aspect = (double)c->width_px / (double)c->height_px;
    const double fz = c->forward[2], rz = c->right[2], uz = c->up[2];
    const double w = (double)c->width_px, h = (double)c->height_px;
    if (fabs(uz) >= fabs(rz)) {
        if (fabs(uz) < 1e-9) {
            return 0;
        }
        for (int i = 0; i < 2; ++i) {
            const double sx = (i == 0 ? -1.0 : 1.0) * t * aspect;
            const double sy = -(fz + sx * rz) / uz;
            double *p = i == 0 ? p0 : p1;
            p[0] = i == 0 ? 0.0 : w;
            p[1] = (1.0 - sy / t) * 0.5 * h;
        }
    } else {
        for (int i = 0; i < 2; ++i) {
            const double sy = (i == 0 ? 1.0 : -1.0) * t;
            const double sx = -(fz + sy * uz) / rz;
            double *p = i == 0 ? p0 : p1;
            p[0] = (sx / (t * aspect) + 1.0) * 0.5 * w;
            p[1] = i == 0 ? 0.0 : h;
        }
    }
    return isfinite(p0[0]) && isfinite(p0[1]) && isfinite(p1[0]) && isfinite(p1[1]);
}
#endif

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

/* Distance from the eye to the 3D box [x0, x1] x [y0, y1] x [zmin, zmax],
 * the z range first widened by the earth-curvature drop: a point at
 * horizontal distance d from the eye is drawn k d^2 lower, and over the
 * rectangle d runs from its nearest to its farthest point, so the drawn
 * heights lie in [zmin - drop_max, zmax - drop_min]. */
double ft_camera_box_distance_m(const double eye_m[3], double x0, double x1, double y0,
                                double y1, double zmin, double zmax, double curv_k_per_m)
{
    double dx = 0.0, dy = 0.0;
    if (eye_m[0] < x0) dx = x0 - eye_m[0];
    if (eye_m[0] > x1) dx = eye_m[0] - x1;
    if (eye_m[1] < y0) dy = y0 - eye_m[1];
    if (eye_m[1] > y1) dy = eye_m[1] - y1;
    const double fx = fmax(fabs(eye_m[0] - x0), fabs(eye_m[0] - x1));
    const double fy = fmax(fabs(eye_m[1] - y0), fabs(eye_m[1] - y1));
    const double d2_min = dx * dx + dy * dy;
    const double d2_max = fx * fx + fy * fy;
    /* k >= 0 lowers (a sphere); a negative k would raise: order the two. */
    double drop_lo = curv_k_per_m * d2_min, drop_hi = curv_k_per_m * d2_max;
    if (drop_lo > drop_hi) {
        const double tmp = drop_lo;
        drop_lo = drop_hi;
        drop_hi = tmp;
    }
    const double lo = zmin - drop_hi, hi = zmax - drop_lo;
    double dz = 0.0;
    if (eye_m[2] < lo) dz = lo - eye_m[2];
    if (eye_m[2] > hi) dz = eye_m[2] - hi;
    return sqrt(d2_min + dz * dz);
}

/* Near from a lower bound of the distance to the terrain, far from the
 * farthest terrain corner, both with the curvature drop.
 *
 * The near plane cuts at a DEPTH along the view axis, and a point at that
 * distance in the frustum's corner lies only distance * corner_cos deep
 * (0.16 at FOV 150): scale by it, and keep a factor of 2 margin, which also
 * covers meshes whose triangles cut chords a little nearer than the
 * surface they sample (a chord between two points at distance D comes
 * nearer than D / 2 only when it spans more than 120 degrees of the view).
 * Clamped to 0.25 m .. 5000 m as before: the floor keeps the range valid
 * with the eye on or in the ground; the cap only binds more than 10 km
 * from all terrain, where 5000 m already makes a 24-bit step at 100 km
 * 0.12 m. */
static void pick_range(const double eye_m[3], double closest_m, double terrain_min_z_m,
                       double terrain_max_z_m, const double box_min_m[2],
                       const double box_max_m[2], double corner_cos, double curv_k_per_m,
                       double *near_m, double *far_m)
{
    if (!(corner_cos > 0.0) || corner_cos > 1.0) corner_cos = 1.0;
    double n = 0.5 * closest_m * corner_cos;
    if (!(n >= 0.25)) n = 0.25; /* also catches NaN */
    if (n > 5000.0) n = 5000.0;

    /* The farthest point is no farther than the farthest corner
     * horizontally, with the largest height difference the drop allows. */
    double far2 = 0.0;
    for (int i = 0; i < 4; ++i) {
        double cx = (i & 1) ? box_max_m[0] : box_min_m[0];
        double cy = (i & 2) ? box_max_m[1] : box_min_m[1];
        double h2 = (cx - eye_m[0]) * (cx - eye_m[0]) + (cy - eye_m[1]) * (cy - eye_m[1]);
        if (h2 > far2) far2 = h2;
    }
    const double drop = fabs(curv_k_per_m) * far2;
    double zl = fabs(eye_m[2] - (terrain_min_z_m - drop));
    double zh = fabs(eye_m[2] - (terrain_max_z_m + (curv_k_per_m < 0.0 ? drop : 0.0)));
    double z = zl > zh ? zl : zh;
    double f = sqrt(far2 + z * z) * 1.05 + 1.0;
    if (f < n * 4.0) f = n * 4.0;
    *near_m = n;
    *far_m = f;
}

void ft_camera_depth_range_from(const double eye_m[3], double closest_m, double zmin_m,
                                double zmax_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos,
                                double curv_k_per_m, double *near_m, double *far_m)
{
    pick_range(eye_m, closest_m, zmin_m, zmax_m, box_min_m, box_max_m, corner_cos,
               curv_k_per_m, near_m, far_m);
}

ft_status ft_camera_set_depth_range(ft_camera *c, double near_m, double far_m, ft_error *err)
{
    if (!(near_m > 0.0) || !(far_m > near_m) || !isfinite(far_m)) {
        return ft_fail(err, FT_ERR_ARG, "camera: bad depth range %g..%g", near_m, far_m);
    }
    c->near_m = near_m;
    c->far_m = far_m;
    c->proj[10] = (float)((far_m + near_m) / (near_m - far_m));
    c->proj[14] = (float)(2.0 * far_m * near_m / (near_m - far_m));
    mat4_mul(c->view_proj, c->proj, c->view_rot);
    return FT_OK;
}

void ft_camera_pick_depth_range(const double eye_m[3], double terrain_min_z_m,
                                double terrain_max_z_m, const double box_min_m[2],
                                const double box_max_m[2], double corner_cos, double *near_m,
                                double *far_m)
{
    /* Nothing of the terrain can be closer than the clearance above its
     * highest point (or its horizontal distance to the box). */
    const double closest = ft_camera_box_distance_m(eye_m, box_min_m[0], box_max_m[0], box_min_m[1],
                                        box_max_m[1], terrain_min_z_m, terrain_max_z_m, 0.0);
    pick_range(eye_m, closest, terrain_min_z_m, terrain_max_z_m, box_min_m, box_max_m,
               corner_cos, 0.0, near_m, far_m);
}

/* World rectangle of min/max texel (i, j) of level l (footprint rule in
 * terrain.h: grid x in [i 2^l, min((i + 1) 2^l, width - 1)], same in y). */
static void texel_rect(const ft_terrain *t, uint32_t l, uint32_t i, uint32_t j, double *x0,
                       double *x1, double *y0, double *y1)
{
    const uint64_t s = (uint64_t)1u << l;
    uint64_t gx0 = (uint64_t)i * s, gx1 = ((uint64_t)i + 1u) * s;
    uint64_t gy0 = (uint64_t)j * s, gy1 = ((uint64_t)j + 1u) * s;
    if (gx1 > t->width - 1u) gx1 = t->width - 1u;
    if (gy1 > t->height - 1u) gy1 = t->height - 1u;
    *x0 = t->origin_world_x_m + (double)gx0 * t->cell_x_m;
    *x1 = t->origin_world_x_m + (double)gx1 * t->cell_x_m;
    *y0 = t->origin_world_y_m + (double)gy0 * t->cell_y_m;
    *y1 = t->origin_world_y_m + (double)gy1 * t->cell_y_m;
}

/* Texels per side of each level's window, along the axis with the larger
 * cells; along the other axis as many more as make the window about square
 * in metres, at most FT_DEPTH_WINDOW_MAX (so at most 8 x 64 texels a
 * level). Even, so a window is a union of whole next-level texels and the
 * windows nest. */
#define FT_DEPTH_WINDOW 8
#define FT_DEPTH_WINDOW_MAX 64

/* [lo, hi) of the window of n texels (even) around texel c, even-aligned,
 * inside [0, size). */
static void window_span(int64_t c, uint32_t n, uint32_t size, uint32_t *lo, uint32_t *hi)
{
    int64_t a = c - ((int64_t)n / 2 - 1);
    a = (a >= 0) ? (a & ~(int64_t)1) : -((-a + 1) & ~(int64_t)1); /* floor to even */
    if (a + (int64_t)n > (int64_t)size) a = (int64_t)size - (int64_t)n;
    if (a < 0) a = 0;
    int64_t b = a + (int64_t)n;
    if (b > (int64_t)size) b = (int64_t)size;
    *lo = (uint32_t)a;
    *hi = (uint32_t)b;
}

/* Window side along an axis whose cells are `ratio` times smaller than the
 * other axis's (ratio <= 1: the larger cells). */
static uint32_t window_side(double ratio)
{
    double n = 2.0 * floor(0.5 * FT_DEPTH_WINDOW * ratio + 0.5);
    if (!(n >= FT_DEPTH_WINDOW)) n = FT_DEPTH_WINDOW; /* also catches NaN */
    if (n > FT_DEPTH_WINDOW_MAX) n = FT_DEPTH_WINDOW_MAX;
    return (uint32_t)n;
}

double ft_camera_terrain_clearance_m(const ft_terrain *t, const double eye_m[3],
                                     double curv_k_per_m)
{
    const ft_pyramid *p = &t->pyr;
    if (!isfinite(curv_k_per_m)) curv_k_per_m = 0.0;
    const uint32_t levels =
        p->minmax_levels < FT_PYRAMID_LEVELS_MAX ? p->minmax_levels : FT_PYRAMID_LEVELS_MAX;
    if (levels == 0u) {
        /* no pyramid: the whole grid as one box (the global rule) */
        return ft_camera_box_distance_m(eye_m, t->origin_world_x_m,
                            t->origin_world_x_m + t->cell_x_m * (double)(t->width - 1u),
                            t->origin_world_y_m,
                            t->origin_world_y_m + t->cell_y_m * (double)(t->height - 1u),
                            (double)t->min_height_m, (double)t->max_height_m, curv_k_per_m);
    }
    /* The eye in grid coordinates, clamped into the grid (NaN-safe): the
     * windows only choose which texels are looked at finely; every texel
     * of the grid is covered at some level whatever they are. */
    double gx = (eye_m[0] - t->origin_world_x_m) / t->cell_x_m;
    double gy = (eye_m[1] - t->origin_world_y_m) / t->cell_y_m;
    if (!(gx > 0.0)) gx = 0.0;
    if (!(gy > 0.0)) gy = 0.0;
    if (gx > (double)(t->width - 1u)) gx = (double)(t->width - 1u);
    if (gy > (double)(t->height - 1u)) gy = (double)(t->height - 1u);

    /* Level by level from fine to coarse: the texels of this level's window
     * that the finer window does not cover (all 2x2 children inside it),
     * and at the coarsest level every texel. Each texel bounds the surface
     * over its footprint, so the least box distance over this set bounds
     * the distance to the whole terrain from below. At most 8 x 64
     * texels per level (the coarsest level is 1x1). */
    const uint32_t nx = window_side(t->cell_y_m / t->cell_x_m);
    const uint32_t ny = window_side(t->cell_x_m / t->cell_y_m);
    double best = INFINITY;
    uint32_t px0 = 0, px1 = 0, py0 = 0, py1 = 0; /* finer level's window */
    for (uint32_t l = 0; l < levels; ++l) {
        const ft_pyramid_level *lv = &p->minmax[l];
        const int top = (l + 1u == levels);
        uint32_t x0 = 0, x1 = lv->width, y0 = 0, y1 = lv->height;
        if (!top) {
            const double s = (double)((uint64_t)1u << l);
            window_span((int64_t)floor(gx / s), nx, lv->width, &x0, &x1);
            window_span((int64_t)floor(gy / s), ny, lv->height, &y0, &y1);
        }
        const uint32_t fw = (l > 0u) ? p->minmax[l - 1u].width : 0u;
        const uint32_t fh = (l > 0u) ? p->minmax[l - 1u].height : 0u;
        for (uint32_t j = y0; j < y1; ++j) {
            const uint32_t cy1 = (2u * j + 1u < fh) ? 2u * j + 1u : fh - 1u;
            const int in_y = (l > 0u) && 2u * j >= py0 && cy1 < py1;
            for (uint32_t i = x0; i < x1; ++i) {
                const uint32_t cx1 = (2u * i + 1u < fw) ? 2u * i + 1u : fw - 1u;
                if (in_y && 2u * i >= px0 && cx1 < px1) {
                    continue; /* the finer level looked at all of it */
                }
                double rx0, rx1, ry0, ry1;
                texel_rect(t, l, i, j, &rx0, &rx1, &ry0, &ry1);
                const size_t k = (size_t)j * lv->width + i;
                const double d = ft_camera_box_distance_m(eye_m, rx0, rx1, ry0, ry1, (double)lv->min_m[k],
                                              (double)lv->max_m[k], curv_k_per_m);
                if (d < best) best = d;
            }
        }
        px0 = x0;
        px1 = x1;
        py0 = y0;
        py1 = y1;
    }
    return best;
}

void ft_camera_depth_range_for_terrain(const ft_terrain *t, const double eye_m[3],
                                       double corner_cos, double curv_k_per_m, double *near_m,
                                       double *far_m)
{
    if (!isfinite(curv_k_per_m)) curv_k_per_m = 0.0;
    const double box_min[2] = {t->origin_world_x_m, t->origin_world_y_m};
    const double box_max[2] = {t->origin_world_x_m + t->cell_x_m * (double)(t->width - 1u),
                               t->origin_world_y_m + t->cell_y_m * (double)(t->height - 1u)};
    const double closest = ft_camera_terrain_clearance_m(t, eye_m, curv_k_per_m);
    pick_range(eye_m, closest, (double)t->min_height_m, (double)t->max_height_m, box_min,
               box_max, corner_cos, curv_k_per_m, near_m, far_m);
}

double ft_camera_depth_step_m(double near_m, double far_m, uint32_t depth_bits, int depth_float,
                              double eye_depth_m)
{
    const double n = near_m, f = far_m, z = eye_depth_m;
    if (!(n > 0.0) || !(f > n) || !(z > 0.0)) {
        return INFINITY;
    }
    /* Window depth d(z) = f / (f - n) (1 - n / z) (glDepthRange 0..1), so
     * dd/dz = f n / ((f - n) z^2), and one step of the stored value spans
     * step_d / (dd/dz) of eye depth. */
    double step_d;
    if (depth_float) {
        /* Spacing of float32 just below d: 2^(e - 24) for d in [2^(e-1),
         * 2^e), the lower binade's spacing at a power of two. For d near 1
         * (all far terrain) that is 2^-24: the same as 24-bit fixed point.
         * The standard mapping crowds far depths against 1, where float
         * has no more bits than fixed point; reversed Z would put them
         * near 0, but GLES has no clip control, and without it the
         * [-1, 1] -> [0, 1] mapping adds 0.5 and rounds the gain away. */
        double d = (f / (f - n)) * (1.0 - n / z);
        if (d > 1.0) d = 1.0;
        if (!(d > 0.0)) {
            return 0.0;
        }
        int e = 0;
        const double m = frexp(d, &e); /* d = m 2^e, m in [0.5, 1) */
        step_d = ldexp(1.0, (m == 0.5) ? e - 25 : e - 24);
    } else {
        if (depth_bits == 0u || depth_bits > 32u) {
            return INFINITY;
        }
        step_d = ldexp(1.0, -(int)depth_bits);
    }
    return step_d * (f - n) * z * z / (f * n);
}

void ft_view_key_take(ft_view_key *k, const ft_camera *cam)
{
    memcpy(k->eye_m, cam->eye_m, sizeof k->eye_m);
    memcpy(k->forward, cam->forward, sizeof k->forward);
    memcpy(k->up, cam->up, sizeof k->up);
    k->fovy_rad = cam->fovy_rad;
    k->width_px = cam->width_px;
    k->height_px = cam->height_px;
    k->valid = 1;
}

int ft_view_key_matches(const ft_view_key *k, const ft_camera *cam)
{
    return k->valid && memcmp(k->eye_m, cam->eye_m, sizeof k->eye_m) == 0 &&
           memcmp(k->forward, cam->forward, sizeof k->forward) == 0 &&
           memcmp(k->up, cam->up, sizeof k->up) == 0 && k->fovy_rad == cam->fovy_rad &&
           k->width_px == cam->width_px && k->height_px == cam->height_px;
}
