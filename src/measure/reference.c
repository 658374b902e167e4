/* reference.c - exact CPU ray caster of the bilinear height field.
 *
 * Frame: everything is done in GRID coordinates relative to sample (0,0):
 *   gx = (x_world - origin_world_x_m) / cell_x_m   (same for y), z in metres.
 * The ray parameter t stays the world ray parameter (metres along a unit
 * direction), so a grid-space direction is (dx / cell_x, dy / cell_y, dz).
 * The subtraction eye - origin happens once, in double, so 1e7 m origins
 * keep sub-millimetre precision.
 *
 * Traversal (max-mip, iterative):
 *   1. clip the ray to the box [0, w-1] x [0, h-1] x [zmin - pad, zmax + pad]
 *      (zmin/zmax from the 1x1 top level; the pad only makes a ray that enters
 *      a flat field's zero-thickness slab see a non-empty interval);
 *   2. start at the top level's only texel; per iteration, over the texel's
 *      t-interval [t_cur, t_exit]:
 *        - the ray's z range is above the texel max or below its min: skip the
 *          texel (step to its neighbour across the exit face; ascend while the
 *          step left the parent);
 *        - else at level 0 solve the cell exactly (below), else descend to the
 *          child that contains the ray point at t_cur.
 *   Without a usable min/max pyramid the same loop runs on level 0 only, with
 *   cell bounds taken from the 4 samples (a plain 2D DDA).
 *
 * Cell solve: inside cell (i, j) with u = gx - i, v = gy - j,
 *   H(u, v) = a + b u + c v + e u v,
 * and along the ray (u = ua + du s, v = va + dv s, z = za + dz s, s = t - t_a):
 *   f(s) = z - H = C + B s + A s^2,
 *   A = -e du dv, B = dz - (b + e va) du - (c + e ua) dv, C = za - H(ua, va).
 * Roots by the stable formula q = -(B + sign(B) sqrt(B^2 - 4AC)) / 2,
 * r1 = q / A (skipped when A == 0), r2 = C / q (= -C/B when A == 0); a
 * bisection on a sign change catches what rounding might lose. The smallest
 * root in [0, s_b] (tolerance 1e-9 (1 + s_b), clamped) is the hit. */
#include "measure/reference.h"

#include <float.h>
#include <math.h>

#include "gpu/shade.h"

/* Ray in grid space. With earth curvature the terrain at horizontal
 * distance r from the eye is drawn k r^2 lower; equivalently the ray rises
 * by k r^2 over the unlowered terrain: z(t) = o.z + d.z t + bend t^2, with
 * bend = k |dir_xy|^2 (world direction, r = t |dir_xy|). The bend keeps the
 * cell solve a quadratic and the ray's z range over a t-interval convex. */
typedef struct ref_ray {
    double o[3]; /* origin: grid x, grid y, z metres */
    double d[3]; /* direction per unit t: 1/cell_x, 1/cell_y, metres */
    double bend; /* metres per t^2 (0 on a flat earth) */
} ref_ray;

/* Height of the (bent) ray at t, over the unlowered terrain. */
static double ray_z(const ref_ray *r, double t)
{
    return r->o[2] + t * (r->d[2] + r->bend * t);
}

typedef struct ref_hit {
    double t;
    uint32_t ci, cj; /* cell of the hit */
    double u, v;     /* local coordinates in the cell, clamped to [0,1] */
} ref_hit;

/* 1 if t->pyr holds a complete min/max pyramid of this grid (terrain.h). */
static int pyramid_usable(const ft_terrain *t)
{
    const ft_pyramid *p = &t->pyr;
    if (p->minmax_levels == 0u || p->minmax_levels > FT_PYRAMID_LEVELS_MAX) {
        return 0;
    }
    uint32_t w = t->width - 1u, h = t->height - 1u;
    for (uint32_t l = 0; l < p->minmax_levels; ++l) { /* bound: <= 16 levels */
        const ft_pyramid_level *lv = &p->minmax[l];
        if (lv->width != w || lv->height != h || lv->min_m == NULL || lv->max_m == NULL) {
            return 0;
        }
        if (l + 1u == p->minmax_levels) {
            return w == 1u && h == 1u;
        }
        w = (w + 1u) / 2u;
        h = (h + 1u) / 2u;
    }
    return 0;
}

static int terrain_usable(const ft_terrain *t)
{
    return t != NULL && t->heights_m != NULL && t->width >= FT_GRID_SIDE_MIN &&
           t->height >= FT_GRID_SIDE_MIN && t->width <= FT_GRID_SIDE_MAX &&
           t->height <= FT_GRID_SIDE_MAX && t->cell_x_m > 0.0 && t->cell_y_m > 0.0 &&
           isfinite(t->cell_x_m) && isfinite(t->cell_y_m) && isfinite(t->origin_world_x_m) &&
           isfinite(t->origin_world_y_m);
}

/* Clips [*t0, *t1] to lo <= o + d t <= hi. Returns 0 if empty. */
static int clip_slab(double o, double d, double lo, double hi, double *t0, double *t1)
{
    if (d == 0.0) {
        return o >= lo && o <= hi;
    }
    double ta = (lo - o) / d;
    double tb = (hi - o) / d;
    if (ta > tb) {
        double s = ta;
        ta = tb;
        tb = s;
    }
    if (ta > *t0) *t0 = ta;
    if (tb < *t1) *t1 = tb;
    return *t0 <= *t1;
}

static void cell_heights(const ft_terrain *t, uint32_t i, uint32_t j, double h[4])
{
    const float *r0 = t->heights_m + (size_t)j * t->width + i;
    const float *r1 = r0 + t->width;
    h[0] = r0[0]; /* h00 */
    h[1] = r0[1]; /* h10 */
    h[2] = r1[0]; /* h01 */
    h[3] = r1[1]; /* h11 */
}

/* Smallest s in [0, sb] with f(s) = C + B s + A s^2 = 0; -1 if none. */
static double smallest_root(double A, double B, double C, double sb)
{
    if (C == 0.0) {
        return 0.0;
    }
    double tol = 1e-9 * (1.0 + sb);
    double best = INFINITY;
    double disc = B * B - 4.0 * A * C;
    if (disc < 0.0 && disc > -1e-12 * (B * B + fabs(4.0 * A * C))) {
        disc = 0.0; /* grazing: rounding must not lose a touching ray */
    }
    if (disc >= 0.0) {
        double sq = sqrt(disc);
        double q = -0.5 * (B + (B >= 0.0 ? sq : -sq));
        double r[2] = {INFINITY, INFINITY};
        if (A != 0.0) r[0] = q / A;
        if (q != 0.0) r[1] = C / q;
        for (int k = 0; k < 2; ++k) {
            if (r[k] >= -tol && r[k] <= sb + tol && r[k] < best) {
                best = r[k];
            }
        }
    }
    if (best == INFINITY) {
        /* A sign change guarantees a root; find it by bisection (<= 200
         * halvings, each strictly shrinks [lo, hi] until it stops). */
        double fb = C + sb * (B + A * sb);
        if (!((C > 0.0 && fb <= 0.0) || (C < 0.0 && fb >= 0.0))) {
            return -1.0;
        }
        double lo = 0.0, hi = sb;
        for (int it = 0; it < 200; ++it) {
            double mid = 0.5 * (lo + hi);
            if (!(mid > lo && mid < hi)) break;
            double fm = C + mid * (B + A * mid);
            if ((fm > 0.0) == (C > 0.0) && fm != 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        best = hi;
    }
    if (best < 0.0) best = 0.0;
    if (best > sb) best = sb;
    return best;
}

/* Exact intersection with cell (i, j) for t in [ta, tb]. */
static int solve_cell(const ft_terrain *t, const ref_ray *r, uint32_t i, uint32_t j, double ta,
                      double tb, ref_hit *hit)
{
    double h[4];
    cell_heights(t, i, j, h);
    double a = h[0], b = h[1] - h[0], c = h[2] - h[0], e = h[3] - h[1] - h[2] + h[0];
    double ua = r->o[0] + r->d[0] * ta - (double)i;
    double va = r->o[1] + r->d[1] * ta - (double)j;
    double za = ray_z(r, ta);
    double du = r->d[0], dv = r->d[1];
    double A = r->bend - e * du * dv;
    double B = (r->d[2] + 2.0 * r->bend * ta) - (b + e * va) * du - (c + e * ua) * dv;
    double C = za - (a + b * ua + c * va + e * ua * va);
    double sb = tb - ta;
    if (!(sb >= 0.0)) sb = 0.0;
    double s = smallest_root(A, B, C, sb);
    if (s < 0.0) {
        return 0;
    }
    double u = ua + du * s, v = va + dv * s;
    hit->t = ta + s;
    hit->ci = i;
    hit->cj = j;
    hit->u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    hit->v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
    return 1;
}

/* Index of the child (2p or 2p+1, clamped to n_child-1) holding coordinate x,
 * children of size sc; ties on the boundary go the way the ray travels. */
static uint32_t child_index(uint32_t p, double x, double d, double sc, uint32_t n_child)
{
    uint32_t lo = 2u * p;
    double mid = (double)(lo + 1u) * sc;
    uint32_t k = (x > mid || (x == mid && d > 0.0)) ? lo + 1u : lo;
    return k < n_child ? k : n_child - 1u;
}

/* The traversal. Returns 1 with *hit filled on a hit. */
static int cast(const ft_terrain *t, const ref_ray *r, ref_hit *hit)
{
    const int use_pyr = pyramid_usable(t);
    const double gw = (double)(t->width - 1u), gh = (double)(t->height - 1u);
    double t0 = 0.0, t1 = INFINITY;
    if (!clip_slab(r->o[0], r->d[0], 0.0, gw, &t0, &t1) ||
        !clip_slab(r->o[1], r->d[1], 0.0, gh, &t0, &t1)) {
        return 0;
    }
    uint32_t top = 0;
    if (use_pyr) {
        top = t->pyr.minmax_levels - 1u;
        double zmin = t->pyr.minmax[top].min_m[0], zmax = t->pyr.minmax[top].max_m[0];
        double pad = 1e-3 + 1e-6 * fmax(fabs(zmin), fabs(zmax));
        /* a bent ray is not a line: the texel tests below bound it instead */
        if (r->bend == 0.0 && !clip_slab(r->o[2], r->d[2], zmin - pad, zmax + pad, &t0, &t1)) {
            return 0;
        }
    }

    uint32_t level = top;
    uint32_t ti = 0, tj = 0;
    if (!use_pyr) {
        double px = r->o[0] + r->d[0] * t0, py = r->o[1] + r->d[1] * t0;
        double fx = floor(px), fy = floor(py);
        if (px == fx && r->d[0] < 0.0) fx -= 1.0;
        if (py == fy && r->d[1] < 0.0) fy -= 1.0;
        fx = fx < 0.0 ? 0.0 : (fx > gw - 1.0 ? gw - 1.0 : fx);
        fy = fy < 0.0 ? 0.0 : (fy > gh - 1.0 ? gh - 1.0 : fy);
        ti = (uint32_t)fx;
        tj = (uint32_t)fy;
        if (!isfinite(t1)) {
            /* a vertical ray stays in its cell: bound t by the cell's heights */
            double h[4];
            cell_heights(t, ti, tj, h);
            double zmin = fmin(fmin(h[0], h[1]), fmin(h[2], h[3]));
            double zmax = fmax(fmax(h[0], h[1]), fmax(h[2], h[3]));
            double pad = 1e-3 + 1e-6 * fmax(fabs(zmin), fabs(zmax));
            if (!clip_slab(r->o[2], r->d[2], zmin - pad, zmax + pad, &t0, &t1)) {
                return 0;
            }
        }
    }
    if (!isfinite(t1) || !isfinite(t0)) {
        return 0; /* cannot happen for a non-zero direction: the box is bounded */
    }
    double t_cur = t0;
    const int sx = r->d[0] > 0.0 ? 1 : (r->d[0] < 0.0 ? -1 : 0);
    const int sy = r->d[1] > 0.0 ? 1 : (r->d[1] < 0.0 ? -1 : 0);

    /* Bound: every iteration either descends one level or steps one texel
     * forward at its level. A line crosses at most w_L + h_L texels of level
     * L, each step ascends at most `top` levels and descends are paid by
     * ascends, so 2 (w + h) (top + 2) iterations suffice; the cap below is
     * four times that (unreachable; a miss is returned if it ever is). */
    const uint64_t cap = 8u * ((uint64_t)t->width + t->height) * (uint64_t)(top + 2u) + 64u;
    for (uint64_t it = 0; it < cap; ++it) {
        const double s = ldexp(1.0, (int)level);
        const double x0 = (double)ti * s, y0 = (double)tj * s;
        const double x1 = fmin(x0 + s, gw), y1 = fmin(y0 + s, gh);
        double tx = INFINITY, ty = INFINITY;
        if (sx > 0) tx = (x1 - r->o[0]) / r->d[0];
        if (sx < 0) tx = (x0 - r->o[0]) / r->d[0];
        if (sy > 0) ty = (y1 - r->o[1]) / r->d[1];
        if (sy < 0) ty = (y0 - r->o[1]) / r->d[1];
        double t_face = fmin(tx, ty);
        double tb = fmin(t_face, t1);
        if (tb < t_cur) tb = t_cur;

        double lo_h, hi_h;
        if (use_pyr) {
            const ft_pyramid_level *lv = &t->pyr.minmax[level];
            size_t k = (size_t)tj * lv->width + ti;
            lo_h = lv->min_m[k];
            hi_h = lv->max_m[k];
        } else {
            double h[4];
            cell_heights(t, ti, tj, h);
            lo_h = fmin(fmin(h[0], h[1]), fmin(h[2], h[3]));
            hi_h = fmax(fmax(h[0], h[1]), fmax(h[2], h[3]));
        }
        double za = ray_z(r, t_cur), zb = ray_z(r, tb);
        double zlo = fmin(za, zb), zhi = fmax(za, zb);
        if (r->bend > 0.0) { /* convex: its minimum may lie inside */
            double t_min = -r->d[2] / (2.0 * r->bend);
            if (t_min > t_cur && t_min < tb) zlo = fmin(zlo, ray_z(r, t_min));
        }
        double ztol = 1e-7 + 1e-12 * (fabs(zlo) + fabs(zhi));
        int skip = zlo > hi_h + ztol || zhi < lo_h - ztol;

        if (!skip && level > 0u) {
            /* descend to the child holding the ray point at t_cur */
            const ft_pyramid_level *ch = &t->pyr.minmax[level - 1u];
            double sc = 0.5 * s;
            double px = r->o[0] + r->d[0] * t_cur, py = r->o[1] + r->d[1] * t_cur;
            ti = child_index(ti, px, r->d[0], sc, ch->width);
            tj = child_index(tj, py, r->d[1], sc, ch->height);
            --level;
            continue;
        }
        if (!skip && solve_cell(t, r, ti, tj, t_cur, tb, hit)) {
            return 1;
        }
        /* step across the exit face */
        if (!(t_face < t1)) {
            return 0; /* the ray leaves the box inside this texel */
        }
        t_cur = tb;
        const ft_pyramid_level *lv = use_pyr ? &t->pyr.minmax[level] : NULL;
        uint32_t nw = use_pyr ? lv->width : t->width - 1u;
        uint32_t nh = use_pyr ? lv->height : t->height - 1u;
        uint32_t ni = ti, nj = tj;
        if (tx <= ty) {
            if ((sx < 0 && ti == 0u) || (sx > 0 && ti + 1u >= nw)) return 0;
            ni = (uint32_t)((int64_t)ti + sx);
        }
        if (ty <= tx) {
            if ((sy < 0 && tj == 0u) || (sy > 0 && tj + 1u >= nh)) return 0;
            nj = (uint32_t)((int64_t)tj + sy);
        }
        /* ascend while the step left the parent (bound: top levels) */
        while (use_pyr && level < top && ((ni >> 1) != (ti >> 1) || (nj >> 1) != (tj >> 1))) {
            ni >>= 1;
            nj >>= 1;
            ti >>= 1;
            tj >>= 1;
            ++level;
        }
        ti = ni;
        tj = nj;
    }
    return 0;
}

static int make_ray(const ft_terrain *t, const double origin_m[3], const double dir[3],
                    ref_ray *r)
{
    if (!terrain_usable(t) || origin_m == NULL || dir == NULL) {
        return 0;
    }
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(origin_m[k]) || !isfinite(dir[k])) return 0;
    }
    if (dir[0] == 0.0 && dir[1] == 0.0 && dir[2] == 0.0) {
        return 0;
    }
    r->o[0] = (origin_m[0] - t->origin_world_x_m) / t->cell_x_m;
    r->o[1] = (origin_m[1] - t->origin_world_y_m) / t->cell_y_m;
    r->o[2] = origin_m[2];
    r->d[0] = dir[0] / t->cell_x_m;
    r->d[1] = dir[1] / t->cell_y_m;
    r->d[2] = dir[2];
    r->bend = t->curv_drop_per_m2 * (dir[0] * dir[0] + dir[1] * dir[1]);
    return isfinite(r->o[0]) && isfinite(r->o[1]) && isfinite(r->bend) && r->bend >= 0.0;
}

int ft_reference_ray(const ft_terrain *t, const double origin_m[3], const double dir[3],
                     double *t_hit_m)
{
    ref_ray r;
    ref_hit h;
    if (!make_ray(t, origin_m, dir, &r) || !cast(t, &r, &h)) {
        return 0;
    }
    if (t_hit_m != NULL) *t_hit_m = h.t;
    return 1;
}

static uint8_t unit_to_u8(float x)
{
    return (uint8_t)(x <= 0.0f ? 0.0f : (x >= 1.0f ? 255.0f : x * 255.0f + 0.5f));
}

ft_status ft_reference_render(const ft_terrain *t, const ft_camera *c, ft_ref_pixel *out,
                              size_t out_cap, ft_error *err)
{
    if (t == NULL || c == NULL || out == NULL) {
        return ft_fail(err, FT_ERR_ARG, "reference: NULL terrain, camera or output");
    }
    if (!terrain_usable(t)) {
        return ft_fail(err, FT_ERR_ARG,
                       "reference: terrain %ux%u without heights or with a bad frame",
                       t->width, t->height);
    }
    if (t->pyr.minmax_levels != 0u && !pyramid_usable(t)) {
        return ft_fail(err, FT_ERR_ARG,
                       "reference: min/max pyramid (%u levels) does not match the %ux%u grid",
                       t->pyr.minmax_levels, t->width, t->height);
    }
    size_t n = (size_t)c->width_px * c->height_px;
    if (c->width_px == 0u || c->height_px == 0u || out_cap < n) {
        return ft_fail(err, FT_ERR_ARG, "reference: %ux%u pixels need %zu entries, %zu given",
                       c->width_px, c->height_px, n, out_cap);
    }
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(c->eye_m[k])) {
            return ft_fail(err, FT_ERR_NUMERIC, "reference: eye coordinate %d not finite", k);
        }
    }
    const uint8_t sky[4] = {unit_to_u8(FT_SKY_R), unit_to_u8(FT_SKY_G), unit_to_u8(FT_SKY_B), 255};
    for (uint32_t py = 0; py < c->height_px; ++py) {
        for (uint32_t px = 0; px < c->width_px; ++px) {
            ft_ref_pixel *o = &out[(size_t)py * c->width_px + px];
            double dir[3];
            ft_camera_pixel_ray(c, (double)px + 0.5, (double)py + 0.5, dir);
            ref_ray r;
            ref_hit h;
            if (!make_ray(t, c->eye_m, dir, &r) || !cast(t, &r, &h)) {
                o->pos_rel_eye_m[0] = o->pos_rel_eye_m[1] = o->pos_rel_eye_m[2] = 0.0f;
                o->dist_m = 0.0f;
                o->hit = 0;
                for (int k = 0; k < 4; ++k) o->rgba[k] = sky[k];
                continue;
            }
            double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int k = 0; k < 3; ++k) {
                o->pos_rel_eye_m[k] = (float)(dir[k] * h.t);
            }
            o->dist_m = (float)(h.t * len);
            o->hit = 1;
            /* analytic normal of the patch: (-dH/dx, -dH/dy, 1) normalised */
            double hh[4];
            cell_heights(t, h.ci, h.cj, hh);
            double e = hh[3] - hh[1] - hh[2] + hh[0];
            double hx = ((hh[1] - hh[0]) + e * h.v) / t->cell_x_m;
            double hy = ((hh[2] - hh[0]) + e * h.u) / t->cell_y_m;
            double nl = sqrt(hx * hx + hy * hy + 1.0);
            float nrm[3] = {(float)(-hx / nl), (float)(-hy / nl), (float)(1.0 / nl)};
            double z = ray_z(&r, h.t); /* the terrain's own height at the hit */
            ft_shade_rgba8((float)z, nrm, o->rgba);
        }
    }
    return FT_OK;
}
