/* view_scale.c - the pixels a vertical metre covers (view_scale.h). */
#include "core/view_scale.h"

#include <math.h>

double ft_view_corner_cos(const ft_camera *c)
{
    const double ty = tan(0.5 * c->fovy_rad);
    const double tx = ty * (double)c->width_px / (double)(c->height_px > 0u ? c->height_px : 1u);
    return 1.0 / sqrt(1.0 + tx * tx + ty * ty);
}

/* (A Z)^2 of q: |q_h|^2 - (q_x f_y - q_y f_x)^2, never negative. */
static double a_z_sq(const double f[3], const double q[3])
{
    const double c = q[0] * f[1] - q[1] * f[0];
    const double v = q[0] * q[0] + q[1] * q[1] - c * c;
    return (v > 0.0) ? v : 0.0;
}

/* A of the point q (relative to the eye, in front of it: q.f > 0). */
static double vertical_a(const double fwd[3], const double q[3])
{
    const double z = q[0] * fwd[0] + q[1] * fwd[1] + q[2] * fwd[2];
    return sqrt(a_z_sq(fwd, q)) / z;
}

void ft_view_gain_frame_from_camera(const ft_camera *c, ft_view_gain_frame *g)
{
    const double ty = tan(0.5 * c->fovy_rad);
    const double tx = ty * (double)c->width_px / (double)(c->height_px > 0u ? c->height_px : 1u);
    double cc = ft_view_corner_cos(c);
    if (!(cc > 0.0) || cc > 1.0) {
        cc = 1e-3; /* a degenerate frustum: the largest gain pgrid allows too */
    }
    g->b_cap = 1.0 / cc;
    g->a_cap = 0.0;
    for (int i = 0; i < 3; ++i) {
        g->fwd[i] = c->forward[i];
    }
    for (int corner = 0; corner < 4; ++corner) {
        const double x = (corner & 1) ? tx : -tx, y = (corner & 2) ? ty : -ty;
        const double q[3] = {c->forward[0] + x * c->right[0] + y * c->up[0],
                             c->forward[1] + x * c->right[1] + y * c->up[1],
                             c->forward[2] + x * c->right[2] + y * c->up[2]};
        const double a = vertical_a(g->fwd, q);
        g->a_cap = (a > g->a_cap) ? a : g->a_cap;
    }
    if (!(g->a_cap <= g->b_cap)) {
        g->a_cap = g->b_cap; /* A <= B everywhere; also catches a NaN */
    }
}

double ft_view_vertical_gain(const ft_view_gain_frame *g, const double lo[3], const double hi[3])
{
    const double *f = g->fwd;
    double a2_max = 0.0, b2_max = 1.0;
    for (int corner = 0; corner < 8; ++corner) {
        const double q[3] = {(corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1],
                             (corner & 4) ? hi[2] : lo[2]};
        const double z = q[0] * f[0] + q[1] * f[1] + q[2] * f[2];
        if (!(z > 0.0)) {
            return g->a_cap * g->b_cap; /* a corner at or behind the eye: any angle */
        }
        const double z2 = z * z;
        const double a2 = a_z_sq(f, q) / z2;
        const double b2 = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) / z2;
        a2_max = (a2 > a2_max) ? a2 : a2_max;
        b2_max = (b2 > b2_max) ? b2 : b2_max;
    }
    const double a = fmin(sqrt(a2_max), g->a_cap);
    const double b = fmin(sqrt(b2_max), g->b_cap);
    return a * b;
}

/* ---- a vertical error over a box ----------------------------------------------- */

void ft_view_bound_from_camera(const ft_camera *c, const double origin_m[2],
                               double curv_drop_per_m2, ft_view_bound *v)
{
    v->eye_m[0] = c->eye_m[0] - origin_m[0];
    v->eye_m[1] = c->eye_m[1] - origin_m[1];
    v->eye_m[2] = c->eye_m[2];
    v->k_px = c->px_per_rad_k;
    ft_view_gain_frame_from_camera(c, &v->gain);
    v->curv_drop_per_m2 = curv_drop_per_m2;
    const double tv = tan(0.5 * c->fovy_rad);
    const double th = tv * (double)c->width_px / (double)(c->height_px > 0u ? c->height_px : 1u);
    for (int i = 0; i < 3; ++i) {
        v->plane_n[0][i] = c->forward[i] * tv - c->up[i];    /* top */
        v->plane_n[1][i] = c->forward[i] * tv + c->up[i];    /* bottom */
        v->plane_n[2][i] = c->forward[i] * th - c->right[i]; /* right */
        v->plane_n[3][i] = c->forward[i] * th + c->right[i]; /* left */
    }
}

/* Distance from e to the interval [lo, hi] (0 inside). */
static double gap_1d(double e, double lo, double hi)
{
    return (e < lo) ? lo - e : ((e > hi) ? e - hi : 0.0);
}

void ft_view_bound_drawn_box(const ft_view_bound *v, double lo[3], double hi[3])
{
    if (!(v->curv_drop_per_m2 > 0.0)) {
        return;
    }
    double near2 = 0.0, far2 = 0.0;
    for (int i = 0; i < 2; ++i) {
        const double g = gap_1d(v->eye_m[i], lo[i], hi[i]);
        const double f = fmax(fabs(v->eye_m[i] - lo[i]), fabs(v->eye_m[i] - hi[i]));
        near2 += g * g;
        far2 += f * f;
    }
    lo[2] -= v->curv_drop_per_m2 * far2;
    hi[2] -= v->curv_drop_per_m2 * near2;
}

void ft_view_bound_terms(const ft_view_bound *v, double err_m, const double lo[3],
                         const double hi[3], ft_view_box_terms *out)
{
    double rlo[3], rhi[3], d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double g = gap_1d(v->eye_m[i], lo[i], hi[i]);
        d2 += g * g;
        rlo[i] = lo[i] - v->eye_m[i];
        rhi[i] = hi[i] - v->eye_m[i];
    }
    const double l2 = (rhi[0] - rlo[0]) * (rhi[0] - rlo[0]) + (rhi[1] - rlo[1]) * (rhi[1] - rlo[1]);
    out->err_m = err_m + 0.25 * v->curv_drop_per_m2 * l2;
    out->dist_m = sqrt(d2);
    out->gain = (out->err_m > 0.0 && d2 > 0.0) ? ft_view_vertical_gain(&v->gain, rlo, rhi) : 0.0;
}

double ft_view_bound_error_px(const ft_view_bound *v, double err_m, const double lo[3],
                              const double hi[3])
{
    if (!(err_m < INFINITY)) {
        return INFINITY; /* unknown (or NaN): no bound */
    }
    ft_view_box_terms t;
    ft_view_bound_terms(v, err_m, lo, hi, &t);
    if (!(t.err_m > 0.0)) {
        return 0.0;
    }
    if (!(t.dist_m > 0.0)) {
        return INFINITY;
    }
    return v->k_px * t.err_m * t.gain / t.dist_m;
}

int ft_view_bound_outside(const ft_view_bound *v, const double lo[3], const double hi[3])
{
    for (int p = 0; p < 5; ++p) {
        const double *nrm = (p < 4) ? v->plane_n[p] : v->gain.fwd;
        double best = 0.0;
        for (int i = 0; i < 3; ++i) {
            const double c = (nrm[i] >= 0.0) ? hi[i] : lo[i];
            best += nrm[i] * (c - v->eye_m[i]);
        }
        if (best < 0.0) {
            return 1;
        }
    }
    return 0;
}
