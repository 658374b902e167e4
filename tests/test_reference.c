/* test_reference.c - the CPU reference ray caster against closed forms,
 * a dense march, and a brute-force scan of every cell.
 *
 * The min/max pyramids are built here, directly from the footprint rule in
 * terrain.h (independent of src/terrain/pyramid.c). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/camera.h"
#include "core/units.h"
#include "gpu/shade.h"
#include "measure/reference.h"
#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "test_util.h"


/* ---------------------------------------------------------------- helpers */

static uint64_t g_rng = 0x9E3779B97F4A7C15ull;

static double rnd(void) /* [0, 1) */
{
    g_rng ^= g_rng << 13;
    g_rng ^= g_rng >> 7;
    g_rng ^= g_rng << 17;
    return (double)(g_rng >> 11) * (1.0 / 9007199254740992.0);
}

static double rnd_in(double a, double b)
{
    return a + (b - a) * rnd();
}

typedef double (*height_fn)(double x, double y, const double *p);

/* Grid w x h, spacing sx, sy (metres), origin (ox, oy); heights from fn at
 * grid-relative metres. Builds the min/max pyramid per terrain.h. */
static void grid_make(ft_terrain *t, uint32_t w, uint32_t h, double sx, double sy, double ox,
                      double oy, height_fn fn, const double *p)
{
    memset(t, 0, sizeof *t);
    t->width = w;
    t->height = h;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = sx;
    t->spacing_y = sy;
    t->origin_x = ox;
    t->origin_y = oy;
    REQUIRE(ft_terrain_derive_frame(t, NULL) == FT_OK);
    t->heights_m = malloc(sizeof(float) * w * h);
    REQUIRE(t->heights_m != NULL);
    float mn = INFINITY, mx = -INFINITY;
    for (uint32_t j = 0; j < h; ++j) {
        for (uint32_t i = 0; i < w; ++i) {
            float v = (float)fn(i * sx, j * sy, p);
            t->heights_m[(size_t)j * w + i] = v;
            mn = v < mn ? v : mn;
            mx = v > mx ? v : mx;
        }
    }
    t->min_height_m = mn;
    t->max_height_m = mx;

    uint32_t lw = w - 1u, lh = h - 1u, L = 0;
    for (;;) {
        ft_pyramid_level *lv = &t->pyr.minmax[L];
        lv->width = lw;
        lv->height = lh;
        lv->min_m = malloc(sizeof(float) * lw * lh);
        lv->max_m = malloc(sizeof(float) * lw * lh);
        REQUIRE(lv->min_m != NULL && lv->max_m != NULL);
        for (uint32_t j = 0; j < lh; ++j) {
            for (uint32_t i = 0; i < lw; ++i) {
                float a = INFINITY, b = -INFINITY;
                for (uint32_t dj = 0; dj < 2; ++dj) {
                    for (uint32_t di = 0; di < 2; ++di) {
                        float lo, hi;
                        if (L == 0) {
                            lo = hi = t->heights_m[(size_t)(j + dj) * w + i + di];
                        } else {
                            const ft_pyramid_level *pv = &t->pyr.minmax[L - 1];
                            uint32_t ci = 2 * i + di, cj = 2 * j + dj;
                            if (ci >= pv->width) ci = pv->width - 1;
                            if (cj >= pv->height) cj = pv->height - 1;
                            lo = pv->min_m[(size_t)cj * pv->width + ci];
                            hi = pv->max_m[(size_t)cj * pv->width + ci];
                        }
                        a = lo < a ? lo : a;
                        b = hi > b ? hi : b;
                    }
                }
                lv->min_m[(size_t)j * lw + i] = a;
                lv->max_m[(size_t)j * lw + i] = b;
            }
        }
        ++L;
        if (lw == 1 && lh == 1) break;
        lw = (lw + 1) / 2;
        lh = (lh + 1) / 2;
        REQUIRE(L < FT_PYRAMID_LEVELS_MAX);
    }
    t->pyr.minmax_levels = L;
}

static void grid_free(ft_terrain *t)
{
    for (uint32_t l = 0; l < t->pyr.minmax_levels; ++l) {
        free(t->pyr.minmax[l].min_m);
        free(t->pyr.minmax[l].max_m);
    }
    free(t->heights_m);
    memset(t, 0, sizeof *t);
}

static double ext_x(const ft_terrain *t)
{
    return (t->width - 1) * t->cell_x_m;
}

static double ext_y(const ft_terrain *t)
{
    return (t->height - 1) * t->cell_y_m;
}

/* world ray from grid-relative origin */
static void to_world(const ft_terrain *t, const double rel[3], double w[3])
{
    w[0] = t->origin_world_x_m + rel[0];
    w[1] = t->origin_world_y_m + rel[1];
    w[2] = rel[2];
}

static void normalize(double d[3])
{
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    d[0] /= l;
    d[1] /= l;
    d[2] /= l;
}

static void rand_dir(double d[3])
{
    double z = rnd_in(-1.0, 1.0), a = rnd_in(0.0, 2.0 * FT_PI), r = sqrt(1.0 - z * z);
    d[0] = r * cos(a);
    d[1] = r * sin(a);
    d[2] = z;
}

/* 1 if (x, y) (relative metres) is inside the extent by more than m */
static int inside_by(const ft_terrain *t, double x, double y, double m)
{
    return x > m && y > m && x < ext_x(t) - m && y < ext_y(t) - m;
}

/* ------------------------------------------------------- analytic surfaces */

/* p = {a, b, c}: z = a x + b y + c */
static double f_plane(double x, double y, const double *p)
{
    return p[0] * x + p[1] * y + p[2];
}

/* p = {k, xc, yc, c}: z = k (x - xc)(y - yc) + c */
static double f_hyp(double x, double y, const double *p)
{
    return p[0] * (x - p[1]) * (y - p[2]) + p[3];
}

/* p = {A, kx, ky, c}: z = A sin(kx x) sin(ky y) + c */
static double f_sine(double x, double y, const double *p)
{
    return p[0] * sin(p[1] * x) * sin(p[2] * y) + p[3];
}

/* p = {peak, ic, jc, spacing}: tent with its single top at sample (ic, jc) */
static double f_tent(double x, double y, const double *p)
{
    return p[0] - fabs(x / p[3] - p[1]) - fabs(y / p[3] - p[2]);
}

static double f_rough(double x, double y, const double *p)
{
    (void)x;
    (void)y;
    return p[0] * rnd();
}

/* Closed-form first hit with the plane (relative coordinates); -1 if none,
 * -2 if ambiguous (edge/grazing; the caller skips the ray). */
static double cf_plane(const ft_terrain *t, const double *p, const double o[3],
                       const double d[3])
{
    double den = d[2] - p[0] * d[0] - p[1] * d[1];
    double num = p[0] * o[0] + p[1] * o[1] + p[2] - o[2];
    if (fabs(den) < 1e-9) return -2.0;
    double tt = num / den;
    if (tt < 0.0) return fabs(tt) < 1e-6 ? -2.0 : -1.0;
    double x = o[0] + d[0] * tt, y = o[1] + d[1] * tt;
    if (inside_by(t, x, y, 1e-6)) return tt;
    if (inside_by(t, x, y, -1e-6)) return -2.0;
    return -1.0;
}

/* Closed form for z = k (x - xc)(y - yc) + c: smallest root t >= 0 inside. */
static double cf_hyp(const ft_terrain *t, const double *p, const double o[3], const double d[3])
{
    long double k = p[0];
    long double px = o[0] - p[1], py = o[1] - p[2];
    long double qa = k * d[0] * d[1];
    long double qb = k * (px * d[1] + py * d[0]) - d[2];
    long double qc = k * px * py + p[3] - o[2];
    long double r[2];
    int nr = 0;
    if (fabsl(qa) < 1e-15L) {
        if (fabsl(qb) < 1e-12L) return -2.0;
        r[nr++] = -qc / qb;
    } else {
        long double disc = qb * qb - 4.0L * qa * qc;
        if (disc < 0.0L) return -1.0;
        if (disc < 1e-8L * qb * qb) return -2.0; /* grazing */
        long double sq = sqrtl(disc);
        long double q = -0.5L * (qb + (qb >= 0 ? sq : -sq));
        r[nr++] = q / qa;
        r[nr++] = qc / q;
        if (r[1] < r[0]) {
            long double s = r[0];
            r[0] = r[1];
            r[1] = s;
        }
    }
    for (int i = 0; i < nr; ++i) {
        double tt = (double)r[i];
        if (tt < 0.0) {
            if (tt > -1e-6) return -2.0;
            continue;
        }
        double x = o[0] + d[0] * tt, y = o[1] + d[1] * tt;
        if (inside_by(t, x, y, 1e-6)) return tt;
        if (inside_by(t, x, y, -1e-6)) return -2.0;
    }
    return -1.0;
}

static double cast_rel(const ft_terrain *t, const double o_rel[3], const double d[3], int *hit)
{
    double w[3], th = -1.0;
    to_world(t, o_rel, w);
    *hit = ft_reference_ray(t, w, d, &th);
    return th;
}

/* f(t) = ray z - bilinear H along the ray (relative coordinates). */
static double f_along(const ft_terrain *t, const double o[3], const double d[3], double tt)
{
    double x = o[0] + d[0] * tt, y = o[1] + d[1] * tt;
    return o[2] + d[2] * tt - ft_terrain_height_at(t, t->origin_world_x_m + x,
                                                    t->origin_world_y_m + y);
}

/* Ray/extent interval (relative), t >= 0; 0 if empty. */
static int extent_interval(const ft_terrain *t, const double o[3], const double d[3], double *t0,
                           double *t1)
{
    double lo = 0.0, hi = 1e30;
    double ex[2] = {ext_x(t), ext_y(t)};
    for (int a = 0; a < 2; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < 0.0 || o[a] > ex[a]) return 0;
            continue;
        }
        double ta = (0.0 - o[a]) / d[a], tb = (ex[a] - o[a]) / d[a];
        if (ta > tb) {
            double s = ta;
            ta = tb;
            tb = s;
        }
        lo = ta > lo ? ta : lo;
        hi = tb < hi ? tb : hi;
    }
    *t0 = lo;
    *t1 = hi;
    return lo <= hi;
}

/* Dense march (step = 0.05 of the smaller cell) over the extent up to t_end:
 * returns 1 if f changes sign (|f| > 1e-9 on both sides), i.e. a crossing. */
static int march_finds_crossing(const ft_terrain *t, const double o[3], const double d[3],
                                double t_end)
{
    double t0, t1;
    if (!extent_interval(t, o, d, &t0, &t1)) return 0;
    if (t_end < t1) t1 = t_end;
    double step = 0.05 * fmin(t->cell_x_m, t->cell_y_m);
    int sign = 0;
    long n = (long)((t1 - t0) / step);
    for (long k = 0; k <= n; ++k) {
        double f = f_along(t, o, d, t0 + k * step);
        int s = f > 1e-9 ? 1 : (f < -1e-9 ? -1 : 0);
        if (s == 0) continue;
        if (sign == 0) sign = s;
        if (s != sign) return 1;
    }
    return 0;
}

/* ------------------------------------------------------------ brute force */

/* Independent brute force: every cell, ray clipped to the cell's rectangle,
 * quadratic in t solved in long double; smallest root. -1 if none. */
static double brute_force(const ft_terrain *t, const double o[3], const double d[3])
{
    long double best = -1.0L;
    long double gx = o[0] / t->cell_x_m, gy = o[1] / t->cell_y_m, gz = o[2];
    long double dx = d[0] / t->cell_x_m, dy = d[1] / t->cell_y_m, dz = d[2];
    for (uint32_t j = 0; j + 1 < t->height; ++j) {
        for (uint32_t i = 0; i + 1 < t->width; ++i) {
            long double ta = 0.0L, tb = 1e30L;
            long double lo[2] = {i, j}, pp[2] = {gx, gy}, dd[2] = {dx, dy};
            int ok = 1;
            for (int a = 0; a < 2 && ok; ++a) {
                if (dd[a] == 0.0L) {
                    ok = pp[a] >= lo[a] && pp[a] <= lo[a] + 1.0L;
                    continue;
                }
                long double t0 = (lo[a] - pp[a]) / dd[a], t1 = (lo[a] + 1.0L - pp[a]) / dd[a];
                if (t0 > t1) {
                    long double s = t0;
                    t0 = t1;
                    t1 = s;
                }
                ta = t0 > ta ? t0 : ta;
                tb = t1 < tb ? t1 : tb;
                ok = ta <= tb;
            }
            if (!ok) continue;
            if (best >= 0.0L && ta > best) continue;
            const float *r0 = t->heights_m + (size_t)j * t->width + i;
            long double h00 = r0[0], h10 = r0[1], h01 = r0[t->width], h11 = r0[t->width + 1];
            /* u = gx + dx t - i, v = gy + dy t - j */
            long double u0 = gx - i, v0 = gy - j;
            long double b = h10 - h00, c = h01 - h00, e = h11 - h10 - h01 + h00;
            /* H = h00 + b u + c v + e u v; f = gz + dz t - H */
            long double A = -e * dx * dy;
            long double B = dz - b * dx - c * dy - e * (u0 * dy + v0 * dx);
            long double C = gz - (h00 + b * u0 + c * v0 + e * u0 * v0);
            long double roots[2];
            int nr = 0;
            if (fabsl(A) < 1e-18L * (fabsl(B) + 1.0L)) {
                if (B != 0.0L) roots[nr++] = -C / B;
            } else {
                long double disc = B * B - 4 * A * C;
                if (disc >= 0.0L) {
                    roots[nr++] = (-B - sqrtl(disc)) / (2 * A);
                    roots[nr++] = (-B + sqrtl(disc)) / (2 * A);
                }
            }
            for (int k = 0; k < nr; ++k) {
                long double r = roots[k];
                long double tol = 1e-9L * (1.0L + fabsl(r));
                if (r >= ta - tol && r <= tb + tol) {
                    if (r < ta) r = ta;
                    if (best < 0.0L || r < best) best = r;
                }
            }
        }
    }
    return (double)best;
}

/* ------------------------------------------------------------------ tests */

/* (a)/(b): a plane (flat or tilted) vs closed form, random rays. */
static void test_plane_rays(double ox, double oy, double a, double b, const char *name)
{
    ft_terrain t;
    double p[3] = {a, b, 123.25};
    grid_make(&t, 65, 65, 10.0, 10.0, ox, oy, f_plane, p);
    int checked = 0, hits = 0, bad = 0;
    double worst = 0.0;
    for (int n = 0; n < 20000; ++n) {
        double o[3], d[3];
        o[0] = rnd_in(-320.0, 960.0);
        o[1] = rnd_in(-320.0, 960.0);
        o[2] = rnd_in(-100.0, 500.0);
        if (n % 2 == 0) {
            rand_dir(d);
        } else { /* aim at a point of the extent near the surface */
            double tx = rnd_in(0.0, 640.0), ty = rnd_in(0.0, 640.0);
            d[0] = tx - o[0];
            d[1] = ty - o[1];
            d[2] = f_plane(tx, ty, p) + rnd_in(-20.0, 20.0) - o[2];
            normalize(d);
        }
        double cf = cf_plane(&t, p, o, d);
        if (cf == -2.0) continue;
        int hit;
        double th = cast_rel(&t, o, d, &hit);
        ++checked;
        if (hit != (cf >= 0.0)) {
            if (bad++ < 5) {
                fprintf(stderr, "%s: ray %d hit %d vs closed form %.9g\n", name, n, hit, cf);
            }
            continue;
        }
        if (hit) {
            ++hits;
            double rel = fabs(th - cf) / fmax(1.0, cf);
            worst = fmax(worst, rel);
        }
    }
    CHECK(bad == 0);
    CHECK(worst < 1e-6);
    CHECK(hits > 3000);
    printf("%s: %d rays checked, %d hits, worst relative distance error %.3g\n", name, checked,
           hits, worst);
    grid_free(&t);
}

/* (a)/(b): a full camera render vs the closed form per pixel. */
static void test_plane_render(double ox, double oy, double a, double b, const char *name)
{
    ft_terrain t;
    double p[3] = {a, b, 123.25};
    grid_make(&t, 65, 65, 10.0, 10.0, ox, oy, f_plane, p);
    const uint32_t W = 160, H = 120;
    static ft_ref_pixel px[160 * 120];
    ft_camera cam;
    double eye_rel[3] = {320.0, -100.0, 123.25 + 200.0}, eye[3];
    to_world(&t, eye_rel, eye);
    REQUIRE(ft_camera_init(&cam, eye, 0.1, -25.0 * FT_PI / 180.0, 0.05, 60.0 * FT_PI / 180.0, W, H, 1.0,
                           5000.0, NULL) == FT_OK);
    ft_error err;
    CHECK(ft_reference_render(&t, &cam, px, (size_t)W * H - 1, &err) == FT_ERR_ARG);
    REQUIRE(ft_reference_render(&t, &cam, px, (size_t)W * H, &err) == FT_OK);
    int hits = 0, skipped = 0, bad = 0;
    double worst = 0.0;
    double nl = sqrt(a * a + b * b + 1.0);
    float nrm[3] = {(float)(-a / nl), (float)(-b / nl), (float)(1.0 / nl)};
    uint8_t sky[4] = {(uint8_t)(FT_SKY_R * 255.0f + 0.5f), (uint8_t)(FT_SKY_G * 255.0f + 0.5f),
                      (uint8_t)(FT_SKY_B * 255.0f + 0.5f), 255};
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            const ft_ref_pixel *q = &px[y * W + x];
            double d[3];
            ft_camera_pixel_ray(&cam, x + 0.5, y + 0.5, d);
            double cf = cf_plane(&t, p, eye_rel, d);
            if (cf == -2.0) {
                ++skipped;
                continue;
            }
            if ((q->hit != 0) != (cf >= 0.0)) {
                ++bad;
                continue;
            }
            if (!q->hit) {
                CHECK(q->dist_m == 0.0f);
                CHECK(memcmp(q->rgba, sky, 4) == 0);
                continue;
            }
            ++hits;
            worst = fmax(worst, fabs(q->dist_m - cf) / cf);
            for (int k = 0; k < 3; ++k) {
                CHECK_NEAR(q->pos_rel_eye_m[k], d[k] * cf, 1e-6 * cf + 1e-4);
            }
            uint8_t want[4];
            double z = eye_rel[2] + d[2] * cf;
            ft_shade_rgba8((float)z, nrm, want);
            for (int k = 0; k < 4; ++k) {
                CHECK(abs((int)q->rgba[k] - (int)want[k]) <= 1);
            }
        }
    }
    /* the top rows look above the horizon at this pitch: sky */
    CHECK(px[0].hit == 0);
    CHECK(bad == 0);
    CHECK(hits > (int)(W * H / 3));
    CHECK(worst < 1e-6);
    printf("%s: %ux%u render, %d hits, %d skipped (edge), worst rel dist error %.3g\n", name, W,
           H, hits, skipped, worst);
    grid_free(&t);
}

/* (c) hyperbolic paraboloid, exactly bilinear. */
static void test_hyperbolic(void)
{
    ft_terrain t;
    double p[4] = {1.0 / 1024.0, 320.0, 320.0, 200.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_hyp, p);
    /* the samples are exact in float, so the bilinear surface IS the saddle */
    CHECK(t.heights_m[0] == (float)f_hyp(0, 0, p));
    int checked = 0, hits = 0, bad = 0;
    double worst = 0.0;
    for (int n = 0; n < 20000; ++n) {
        double o[3], d[3];
        o[0] = rnd_in(-320.0, 960.0);
        o[1] = rnd_in(-320.0, 960.0);
        o[2] = rnd_in(0.0, 500.0);
        if (n % 2 == 0) {
            rand_dir(d);
        } else {
            double tx = rnd_in(0.0, 640.0), ty = rnd_in(0.0, 640.0);
            d[0] = tx - o[0];
            d[1] = ty - o[1];
            d[2] = f_hyp(tx, ty, p) + rnd_in(-20.0, 20.0) - o[2];
            normalize(d);
        }
        double cf = cf_hyp(&t, p, o, d);
        if (cf == -2.0) continue;
        int hit;
        double th = cast_rel(&t, o, d, &hit);
        ++checked;
        if (hit != (cf >= 0.0)) {
            if (bad++ < 5) fprintf(stderr, "hyperbolic: ray %d hit %d vs %.9g\n", n, hit, cf);
            continue;
        }
        if (hit) {
            ++hits;
            worst = fmax(worst, fabs(th - cf) / fmax(1.0, cf));
        }
    }
    CHECK(bad == 0);
    CHECK(worst < 1e-6);
    CHECK(hits > 3000);
    printf("hyperbolic paraboloid: %d rays, %d hits, worst rel distance error %.3g\n", checked,
           hits, worst);
    grid_free(&t);
}

/* (d) sampled sine field: residual, no earlier crossing, interpolation bound */
static void test_sine(void)
{
    ft_terrain t;
    double p[4] = {40.0, 2.0 * FT_PI / 200.0, 2.0 * FT_PI / 150.0, 60.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_sine, p);
    double bound = p[0] * (p[1] * p[1] * 100.0 + p[2] * p[2] * 100.0) / 8.0 + 1e-4;
    int hits = 0, misses = 0, bad_res = 0, bad_march = 0, bad_bound = 0;
    double worst_res = 0.0;
    for (int n = 0; n < 3000; ++n) {
        double o[3], d[3];
        o[0] = rnd_in(-200.0, 840.0);
        o[1] = rnd_in(-200.0, 840.0);
        o[2] = rnd_in(0.0, 300.0);
        if (n % 3 == 0) {
            rand_dir(d);
        } else {
            double tx = rnd_in(0.0, 640.0), ty = rnd_in(0.0, 640.0);
            d[0] = tx - o[0];
            d[1] = ty - o[1];
            d[2] = f_sine(tx, ty, p) + rnd_in(-30.0, 30.0) - o[2];
            normalize(d);
        }
        int hit;
        double th = cast_rel(&t, o, d, &hit);
        if (!hit) {
            ++misses;
            if (march_finds_crossing(&t, o, d, 1e30)) ++bad_march;
            continue;
        }
        ++hits;
        double x = o[0] + d[0] * th, y = o[1] + d[1] * th, z = o[2] + d[2] * th;
        double res = fabs(z - ft_terrain_height_at(&t, x, y));
        worst_res = fmax(worst_res, res);
        if (!(res < 1e-6)) ++bad_res;
        if (march_finds_crossing(&t, o, d, th - 1e-6)) ++bad_march;
        if (!(fabs(z - f_sine(x, y, p)) <= bound)) ++bad_bound;
    }
    CHECK(bad_res == 0);
    CHECK(bad_march == 0);
    CHECK(bad_bound == 0);
    CHECK(hits > 1000);
    printf("sine field: %d hits (worst residual %.3g m), %d misses; march/bound failures %d/%d\n",
           hits, worst_res, misses, bad_march, bad_bound);
    grid_free(&t);
}

/* (e) edge cases */
static void test_edges(void)
{
    ft_terrain t;
    double ps[4] = {40.0, 2.0 * FT_PI / 200.0, 2.0 * FT_PI / 150.0, 60.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_sine, ps);
    int hit;
    double th;
    double hx = 123.4, hy = 234.5, hz = ft_terrain_height_at(&t, hx, hy);

    /* nadir */
    double o1[3] = {hx, hy, 500.0}, down[3] = {0, 0, -1}, up[3] = {0, 0, 1};
    th = cast_rel(&t, o1, down, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 500.0 - hz, 1e-9);
    /* straight up from above: nothing */
    th = cast_rel(&t, o1, up, &hit);
    CHECK(hit == 0);
    /* straight up from below the surface: first crossing from below */
    double o2[3] = {hx, hy, hz - 30.0};
    th = cast_rel(&t, o2, up, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 30.0, 1e-9);
    /* straight down from below: nothing */
    th = cast_rel(&t, o2, down, &hit);
    CHECK(hit == 0);
    /* nadir exactly on a sample */
    double o3[3] = {320.0, 320.0, 1000.0};
    th = cast_rel(&t, o3, down, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 1000.0 - t.heights_m[32 * 65 + 32], 1e-9);
    /* nadir outside the grid */
    double o4[3] = {-1.0, 320.0, 1000.0};
    th = cast_rel(&t, o4, down, &hit);
    CHECK(hit == 0);

    /* slanted ray from below the surface */
    double hb = ft_terrain_height_at(&t, 300.0, 300.0);
    double o5[3] = {300.0, 300.0, hb - 5.0}, d5[3] = {0.3, 0.2, 0.5};
    normalize(d5);
    th = cast_rel(&t, o5, d5, &hit);
    CHECK(hit == 1);
    if (hit) {
        CHECK(fabs(f_along(&t, o5, d5, th)) < 1e-6);
        CHECK(!march_finds_crossing(&t, o5, d5, th - 1e-6));
        CHECK(f_along(&t, o5, d5, th * 0.5) < 0.0); /* still below before the hit */
    }
    /* from outside, entering from the west side above the edge (z 89 m over
     * an edge at 60 m) */
    double o6[3] = {-500.0, 321.0, 200.0}, d6[3] = {900.0, -21.0, -200.0};
    normalize(d6);
    th = cast_rel(&t, o6, d6, &hit);
    CHECK(hit == 1);
    if (hit) {
        CHECK(o6[0] + d6[0] * th >= 0.0);
        CHECK(fabs(f_along(&t, o6, d6, th)) < 1e-6);
        CHECK(!march_finds_crossing(&t, o6, d6, th - 1e-6));
    }
    /* entering through the side BELOW the edge (44 m under a 60 m edge):
     * the sheet has no side wall, so the hit is the first crossing from
     * below, if any; the dense march agrees either way */
    double o6b[3] = {-500.0, 321.0, 50.0}, d6b[3] = {900.0, -21.0, -10.0};
    normalize(d6b);
    th = cast_rel(&t, o6b, d6b, &hit);
    CHECK(f_along(&t, o6b, d6b, (500.0 + 1e-9) / d6b[0]) < 0.0);
    CHECK(hit == march_finds_crossing(&t, o6b, d6b, 1e30));
    if (hit) {
        CHECK(fabs(f_along(&t, o6b, d6b, th)) < 1e-6);
        CHECK(!march_finds_crossing(&t, o6b, d6b, th - 1e-6));
    }
    /* axis-parallel rays (dy = 0 / dx = 0), on and off grid lines */
    double offs[2] = {321.7, 320.0};
    for (int k = 0; k < 2; ++k) {
        for (int axis = 0; axis < 2; ++axis) {
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double o[3], d[3] = {0, 0, -0.2};
                o[axis] = sgn > 0 ? -100.0 : 740.0;
                o[1 - axis] = offs[k];
                o[2] = 130.0;
                d[axis] = sgn;
                normalize(d);
                th = cast_rel(&t, o, d, &hit);
                CHECK(hit == 1);
                if (hit) {
                    CHECK(fabs(f_along(&t, o, d, th)) < 1e-6);
                    CHECK(!march_finds_crossing(&t, o, d, th - 1e-6));
                }
                d[2] = 0.0; /* horizontal at 130 m: above everything */
                th = cast_rel(&t, o, d, &hit);
                CHECK(hit == 0);
            }
        }
    }
    /* non-finite input and zero direction are misses, not NaN */
    double zero[3] = {0, 0, 0}, nan_o[3] = {NAN, 0, 0};
    CHECK(ft_reference_ray(&t, o1, zero, &th) == 0);
    CHECK(ft_reference_ray(&t, nan_o, down, &th) == 0);
    grid_free(&t);

    /* horizontal rays at exactly the max height: a tent with its top at
     * sample (32, 32) is touched only on the grid lines through the top */
    double pt[4] = {100.0, 32.0, 32.0, 10.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_tent, pt);
    CHECK(t.max_height_m == 100.0f);
    double ox7[3] = {-50.0, 320.0, 100.0}, east[3] = {1, 0, 0}, north[3] = {0, 1, 0};
    th = cast_rel(&t, ox7, east, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 370.0, 1e-6);
    double oy7[3] = {320.0, 700.0, 100.0}, south[3] = {0, -1, 0};
    th = cast_rel(&t, oy7, south, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 380.0, 1e-6);
    double ox8[3] = {-50.0, 325.0, 100.0};
    th = cast_rel(&t, ox8, east, &hit);
    CHECK(hit == 0);
    double ox9[3] = {-50.0, 320.0, 100.001};
    th = cast_rel(&t, ox9, east, &hit);
    CHECK(hit == 0);
    double oy9[3] = {320.0, -50.0, 100.0};
    th = cast_rel(&t, oy9, north, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 370.0, 1e-6);
    grid_free(&t);

    /* flat plane, horizontal ray in the surface: hit where it enters */
    double pp[3] = {0.0, 0.0, 50.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_plane, pp);
    double o10[3] = {-50.0, 123.0, 50.0};
    th = cast_rel(&t, o10, east, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 50.0, 1e-9);
    double o11[3] = {100.0, 123.0, 50.0};
    th = cast_rel(&t, o11, east, &hit);
    CHECK(hit == 1);
    CHECK_NEAR(th, 0.0, 1e-9);
    /* ray exactly at grazing incidence just above: miss */
    double o12[3] = {-50.0, 123.0, 50.01};
    th = cast_rel(&t, o12, east, &hit);
    CHECK(hit == 0);
    grid_free(&t);

    /* huge origin: eye 1e7 m east/north, ray vs flat plane */
    grid_make(&t, 65, 65, 10.0, 10.0, 1e7, 1e7, f_plane, pp);
    double eye[3] = {1e7 + 100.25, 1e7 + 200.5, 1050.0};
    double dd[3] = {0.3, 0.1, -1.0};
    normalize(dd);
    th = -1;
    hit = ft_reference_ray(&t, eye, dd, &th);
    CHECK(hit == 1);
    CHECK(fabs(th - 1000.0 / -dd[2]) < 1e-9 * 1000.0);
    /* and from 1e7 m away from the grid (grid at the origin, eye far off) */
    grid_free(&t);
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_plane, pp);
    double far_eye[3] = {-1e7, 320.0, 51.0};
    double fd[3] = {1e7 + 320.0, 0.0, -1.0};
    normalize(fd);
    hit = ft_reference_ray(&t, far_eye, fd, &th);
    CHECK(hit == 1);
    CHECK(fabs((far_eye[0] + fd[0] * th) - 320.0) < 1e-3);
    grid_free(&t);

    /* fuzz: extreme magnitudes, denormal and zero direction components; every
     * call returns (bounded loops), a hit has a finite t >= 0 on the surface */
    grid_make(&t, 33, 17, 10.0, 30.0, 0.0, 0.0, f_sine, ps);
    int fuzz_bad = 0, fuzz_hits = 0;
    for (int n = 0; n < 20000; ++n) {
        double o[3], d[3];
        for (int k = 0; k < 3; ++k) {
            double mag = pow(10.0, rnd_in(-3.0, 12.0));
            o[k] = (rnd() < 0.5 ? -mag : mag) + (k < 2 ? 160.0 : 60.0);
            if (rnd() < 0.3) o[k] = rnd_in(0.0, k == 0 ? 320.0 : (k == 1 ? 480.0 : 120.0));
        }
        rand_dir(d);
        for (int k = 0; k < 3; ++k) {
            double r = rnd();
            if (r < 0.1) d[k] = 0.0;
            else if (r < 0.15) d[k] = 4.9e-324 * (rnd() < 0.5 ? -1 : 1);
            else if (r < 0.2) d[k] *= 1e-12;
        }
        th = cast_rel(&t, o, d, &hit);
        if (!hit) continue;
        ++fuzz_hits;
        double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(isfinite(th) && th >= 0.0)) {
            ++fuzz_bad;
            continue;
        }
        double x = o[0] + d[0] * th, y = o[1] + d[1] * th, z = o[2] + d[2] * th;
        double tol = 1e-6 + 1e-12 * (fabs(o[0]) + fabs(o[1]) + fabs(o[2])) / fmax(l, 1e-300) +
                     1e-9 * th;
        if (!(fabs(z - ft_terrain_height_at(&t, x, y)) <= tol) || !inside_by(&t, x, y, -1e-3)) {
            if (fuzz_bad++ < 5) {
                fprintf(stderr, "fuzz: o %.17g %.17g %.17g d %.17g %.17g %.17g t %.17g\n", o[0],
                        o[1], o[2], d[0], d[1], d[2], th);
            }
        }
    }
    CHECK(fuzz_bad == 0);
    printf("fuzz: %d hits, %d bad\n", fuzz_hits, fuzz_bad);
    grid_free(&t);
    printf("edge cases done\n");
}

/* max-mip traversal == brute-force scan of every cell. Rays: random
 * directions, rays aimed at the surface, axis-parallel rays, rays along grid
 * lines, vertical rays. Also: the no-pyramid level-0 walk gives the same. */
static void brute_case(uint32_t gw, uint32_t gh, double sx, double sy, int N, uint64_t seed)
{
    ft_terrain t;
    double pr[1] = {200.0};
    g_rng = seed;
    grid_make(&t, gw, gh, sx, sy, 0.0, 0.0, f_rough, pr);
    int agree = 0, flag_mismatch = 0, dist_mismatch = 0, hits = 0, nopyr_mismatch = 0;
    double worst = 0.0;
    ft_terrain flat = t; /* same heights, no pyramid: level-0 walk */
    flat.pyr.minmax_levels = 0;
    double ex = ext_x(&t), ey = ext_y(&t);
    for (int n = 0; n < N; ++n) {
        double o[3], d[3];
        o[0] = rnd_in(-0.3 * ex, 1.3 * ex);
        o[1] = rnd_in(-0.3 * ey, 1.3 * ey);
        o[2] = rnd_in(-50.0, 500.0);
        if (n % 2 == 0) {
            rand_dir(d);
        } else {
            double tx = rnd_in(0.0, ex), ty = rnd_in(0.0, ey);
            d[0] = tx - o[0];
            d[1] = ty - o[1];
            d[2] = rnd_in(0.0, 200.0) - o[2];
        }
        switch (n % 11) {
        case 3: d[0] = 0.0; break;                         /* parallel to y */
        case 5: d[1] = 0.0; break;                         /* parallel to x */
        case 7: o[1] = sy * (double)(uint32_t)rnd_in(0, gh); d[1] = 0.0; break; /* on a row */
        case 9: o[0] = sx * (double)(uint32_t)rnd_in(0, gw); d[0] = 0.0; break; /* on a column */
        case 10: d[0] = d[1] = 0.0; d[2] = n % 2 ? -1.0 : 1.0; break; /* vertical */
        default: break;
        }
        if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) d[2] = -1.0;
        normalize(d);
        int hit;
        double th = cast_rel(&t, o, d, &hit);
        double bf = brute_force(&t, o, d);
        int bhit = bf >= 0.0;
        int hit2;
        double th2 = cast_rel(&flat, o, d, &hit2);
        if (hit2 != hit || (hit && fabs(th2 - th) > 1e-9 * (1.0 + th))) {
            if (nopyr_mismatch++ < 5) {
                fprintf(stderr, "no-pyramid: ray %d hit %d (%.12g) vs %d (%.12g) o %.17g %.17g %.17g d %.17g %.17g %.17g\n", n, hit, th, hit2, th2, o[0],o[1],o[2],d[0],d[1],d[2]);
            }
        }
        if (hit != bhit) {
            if (flag_mismatch++ < 5) {
                fprintf(stderr, "brute: ray %d hit %d (%.9g) vs brute %.9g nopyr %d o %.17g %.17g %.17g d %.17g %.17g %.17g\n", n, hit, th, bf, hit2, o[0],o[1],o[2],d[0],d[1],d[2]);
            }
            continue;
        }
        if (hit) {
            ++hits;
            double e = fabs(th - bf) / fmax(1.0, bf);
            worst = fmax(worst, e);
            if (e > 1e-6) {
                if (dist_mismatch++ < 5) {
                    fprintf(stderr, "brute: ray %d t %.12g vs %.12g\n", n, th, bf);
                }
                continue;
            }
        }
        ++agree;
    }
    CHECK(flag_mismatch == 0);
    CHECK(dist_mismatch == 0);
    CHECK(nopyr_mismatch == 0);
    CHECK(hits > N / 5);
    printf("max-mip vs brute force, %ux%u grid (%u levels): %d/%d rays agree (%d hits), worst rel "
           "dist diff %.3g; no-pyramid walk mismatches %d\n",
           gw, gh, t.pyr.minmax_levels, agree, N, hits, worst, nopyr_mismatch);
    grid_free(&t);
}

static void test_vs_brute(void)
{
    brute_case(97, 77, 10.0, 7.0, 10000, 12345);
    brute_case(65, 65, 10.0, 10.0, 3000, 777);
    brute_case(2, 2, 10.0, 10.0, 2000, 99);
    brute_case(3, 6, 5.0, 10.0, 2000, 4242);
    brute_case(130, 18, 10.0, 10.0, 3000, 31337);
}

/* renders from awkward poses: every pixel finite, hits on the surface */
static void test_render_poses(void)
{
    ft_terrain t;
    double ps[4] = {40.0, 2.0 * FT_PI / 200.0, 2.0 * FT_PI / 150.0, 60.0};
    grid_make(&t, 65, 65, 10.0, 10.0, 0.0, 0.0, f_sine, ps);
    static ft_ref_pixel px[64 * 48];
    struct pose {
        double x, y, z, head, pitch, roll;
        const char *what;
    } poses[] = {
        {320.0, 320.0, 300.0, 0.0, -90.0, 0.0, "nadir"},
        {320.0, 320.0, 300.0, 30.0, 90.0, 0.0, "zenith (all sky)"},
        {123.4, 234.5, -100.0, 10.0, 89.0, 5.0, "below the grid looking up"},
        {300.0, 300.0, 40.0, 45.0, 45.0, 0.0, "under the surface, looking up"},
        {-2e3, 320.0, 300.0, 90.0, -6.0, 0.0, "2 km west, oblique"},
        {-1e7, 320.0, 2000.0, 90.0, -0.0001, 0.0, "1e7 m west, level"},
        {320.0, -5e6, 1e5, 0.0, -1.1, 0.0, "5e6 m south, high"},
        {0.0, 0.0, 100.0, 45.0, 0.0, 180.0, "grid corner, upside down"},
    };
    for (size_t k = 0; k < sizeof poses / sizeof poses[0]; ++k) {
        ft_camera cam;
        double eye[3] = {poses[k].x, poses[k].y, poses[k].z};
        if (k == 3) eye[2] = ft_terrain_height_at(&t, eye[0], eye[1]) - 3.0;
        REQUIRE(ft_camera_init(&cam, eye, poses[k].head * FT_PI / 180.0,
                               poses[k].pitch * FT_PI / 180.0, poses[k].roll * FT_PI / 180.0, 1.0, 64,
                               48, 0.5, 1e8, NULL) == FT_OK);
        REQUIRE(ft_reference_render(&t, &cam, px, 64 * 48, NULL) == FT_OK);
        int hits = 0, bad = 0;
        for (int i = 0; i < 64 * 48; ++i) {
            const ft_ref_pixel *q = &px[i];
            int fin = isfinite(q->dist_m) && isfinite(q->pos_rel_eye_m[0]) &&
                      isfinite(q->pos_rel_eye_m[1]) && isfinite(q->pos_rel_eye_m[2]);
            if (!fin || q->dist_m < 0.0f) {
                ++bad;
                continue;
            }
            if (!q->hit) continue;
            ++hits;
            double x = eye[0] + q->pos_rel_eye_m[0], y = eye[1] + q->pos_rel_eye_m[1];
            double z = eye[2] + q->pos_rel_eye_m[2];
            double tol = 1e-6 * q->dist_m + 1e-4 + 1e-7 * (fabs(eye[0]) + fabs(eye[1]));
            if (!(fabs(z - ft_terrain_height_at(&t, x, y)) < 2.0 * tol + 0.05 * (k >= 5))) ++bad;
        }
        CHECK(bad == 0);
        if (k == 1) CHECK(hits == 0);
        if (k == 0 || k == 2 || k == 3) CHECK(hits == 64 * 48);
        if (k == 4) CHECK(hits > 0);
        printf("render pose '%s': %d hits, %d bad\n", poses[k].what, hits, bad);
    }
    grid_free(&t);
}

/* src/terrain/pyramid.c builds the same min/max pyramid as the rule coded above,
 * and the caster renders identically with it */
static void test_with_pyramid_build(void)
{
    static const uint32_t dims[3][2] = {{97, 77}, {2, 2}, {130, 18}};
    for (int c = 0; c < 3; ++c) {
        ft_terrain t;
        double pr[1] = {300.0};
        g_rng = 555u + (uint64_t)c;
        grid_make(&t, dims[c][0], dims[c][1], 10.0, 10.0, 0.0, 0.0, f_rough, pr);
        ft_terrain u = t;
        memset(&u.pyr, 0, sizeof u.pyr);
        size_t bytes = ft_pyramid_bytes(u.width, u.height);
        void *store = malloc(bytes);
        REQUIRE(store != NULL);
        REQUIRE(ft_pyramid_layout(&u, store, bytes, NULL) == FT_OK);
        ft_pyramid_build(&u);
        CHECK(u.pyr.minmax_levels == t.pyr.minmax_levels);
        int same = u.pyr.minmax_levels == t.pyr.minmax_levels;
        for (uint32_t l = 0; same && l < t.pyr.minmax_levels; ++l) {
            const ft_pyramid_level *a = &t.pyr.minmax[l], *b = &u.pyr.minmax[l];
            size_t n = (size_t)a->width * a->height;
            same = a->width == b->width && a->height == b->height &&
                   memcmp(a->min_m, b->min_m, n * sizeof(float)) == 0 &&
                   memcmp(a->max_m, b->max_m, n * sizeof(float)) == 0;
        }
        CHECK(same);
        CHECK(u.min_height_m == t.min_height_m && u.max_height_m == t.max_height_m);
        static ft_ref_pixel pa[96 * 64], pb[96 * 64];
        ft_camera cam;
        double eye[3] = {-50.0, -80.0, 400.0};
        REQUIRE(ft_camera_init(&cam, eye, 0.7, -0.5, 0.0, 1.0, 96, 64, 1.0, 1e4, NULL) == FT_OK);
        REQUIRE(ft_reference_render(&t, &cam, pa, 96 * 64, NULL) == FT_OK);
        REQUIRE(ft_reference_render(&u, &cam, pb, 96 * 64, NULL) == FT_OK);
        int diff = 0;
        for (int i = 0; i < 96 * 64; ++i) {
            diff += pa[i].hit != pb[i].hit || pa[i].dist_m != pb[i].dist_m ||
                    memcmp(pa[i].pos_rel_eye_m, pb[i].pos_rel_eye_m, sizeof pa[i].pos_rel_eye_m) ||
                    memcmp(pa[i].rgba, pb[i].rgba, 4);
        }
        CHECK(diff == 0);
        free(store);
        grid_free(&t);
    }
    printf("ft_pyramid_build pyramid == test pyramid, identical renders\n");
}

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* p = {seed phases...}: smooth octaves plus per-sample noise */
static double f_fractal(double x, double y, const double *p)
{
    double z = 800.0, amp = 600.0, k = 2.0 * FT_PI / 20000.0;
    for (int o = 0; o < 8; ++o) {
        z += amp * sin(k * x + p[2 * o]) * sin(k * 1.3 * y + p[2 * o + 1]);
        amp *= 0.5;
        k *= 2.1;
    }
    return z + 3.0 * rnd();
}

/* timing: 640x480 over a 1025x1025 rough grid, oblique low view */
static void test_timing(void)
{
    ft_terrain t;
    double ph[16];
    for (int i = 0; i < 16; ++i) ph[i] = rnd_in(0.0, 2.0 * FT_PI);
    grid_make(&t, 1025, 1025, 30.0, 30.0, 5e5, 4e6, f_fractal, ph);
    const uint32_t W = 640, H = 480;
    ft_ref_pixel *px = malloc(sizeof(ft_ref_pixel) * W * H);
    REQUIRE(px != NULL);
    double eye_rel[3] = {2000.0, 2000.0, 0.0}, eye[3];
    eye_rel[2] = t.max_height_m + 150.0;
    to_world(&t, eye_rel, eye);
    ft_camera cam;
    REQUIRE(ft_camera_init(&cam, eye, 45.0 * FT_PI / 180.0, -6.0 * FT_PI / 180.0, 0.0,
                           45.0 * FT_PI / 180.0, W, H, 1.0, 60000.0, NULL) == FT_OK);
    double t0 = now_s();
    REQUIRE(ft_reference_render(&t, &cam, px, (size_t)W * H, NULL) == FT_OK);
    double t1 = now_s();
    size_t hits = 0;
    int bad = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) {
        if (!px[i].hit) continue;
        ++hits;
        /* every 97th hit: on the surface */
        if (i % 97 == 0) {
            double x = eye[0] + px[i].pos_rel_eye_m[0], y = eye[1] + px[i].pos_rel_eye_m[1];
            double z = eye[2] + px[i].pos_rel_eye_m[2];
            if (!(fabs(z - ft_terrain_height_at(&t, x, y)) < 0.05)) ++bad; /* float pos */
        }
    }
    CHECK(bad == 0);
    CHECK(hits > (size_t)W * H / 4);
    printf("timing: ft_reference_render 640x480 over 1025x1025 (oblique, low): %.1f ms, "
           "%.1f%% terrain pixels\n",
           (t1 - t0) * 1e3, 100.0 * (double)hits / (double)(W * H));
    free(px);
    grid_free(&t);
}

/* Depth range: no terrain point may fall in front of the near plane. Nothing
 * is nearer than the clearance over the highest point, and along a frustum
 * corner ray a point at that distance is only distance * cos(corner angle)
 * deep: at FOV 150 (4:3) that is 0.16 of it, so the old near = clearance / 2
 * cut the view's corners off (seen as ~5,000 missing pixels at FOV 150). */
static void test_depth_range(void)
{
    static const double fovs_deg[] = {1.0, 30.0, 60.0, 150.0, 170.0};
    const double eye[3] = {500.0, 700.0, 3000.0};
    const double bmin[2] = {0.0, 0.0}, bmax[2] = {40000.0, 30000.0};
    const double zmin = 200.0, zmax = 1000.0, clearance = 2000.0;
    for (size_t k = 0; k < sizeof fovs_deg / sizeof fovs_deg[0]; ++k) {
        const uint32_t w = 160u, h = 120u;
        const double ty = tan(0.5 * fovs_deg[k] * FT_PI / 180.0), tx = ty * w / h;
        double n = 0.0, f = 0.0;
        ft_camera_pick_depth_range(eye, zmin, zmax, bmin, bmax, 1.0 / sqrt(1.0 + tx * tx + ty * ty),
                                   &n, &f);
        ft_camera cam;
        REQUIRE(ft_camera_init(&cam, eye, 0.3, -0.4, 0.2, fovs_deg[k] * FT_PI / 180.0, w, h, n, f,
                               NULL) == FT_OK);
        double least_depth = INFINITY;
        for (uint32_t y = 0; y <= h; y += h / 4u) {
            for (uint32_t x = 0; x <= w; x += w / 4u) {
                double d[3];
                ft_camera_pixel_ray(&cam, (double)x, (double)y, d);
                const double depth = clearance * (d[0] * cam.forward[0] + d[1] * cam.forward[1] +
                                                  d[2] * cam.forward[2]);
                if (depth < least_depth) least_depth = depth;
            }
        }
        printf("depth range fov %.0f: near %.2f m, far %.0f m, least depth of a point %.0f m "
               "away %.1f m\n", fovs_deg[k], n, f, clearance, least_depth);
        CHECK(n >= 0.25 && n < f);
        CHECK(least_depth >= n);
        /* the farthest terrain corner, at any angle, is inside the far plane */
        CHECK(f >= sqrt(39500.0 * 39500.0 + 29300.0 * 29300.0 + 2800.0 * 2800.0));
    }
}

int main(void)
{
    test_plane_rays(0.0, 0.0, 0.0, 0.0, "flat plane");
    test_plane_rays(1e7, 1e7, 0.0, 0.0, "flat plane, origin 1e7 m");
    test_plane_rays(0.0, 0.0, 0.25, -0.125, "tilted plane");
    test_plane_rays(1e7, -1e7, 0.25, -0.125, "tilted plane, origin (1e7, -1e7) m");
    test_plane_render(0.0, 0.0, 0.0, 0.0, "flat plane render");
    test_plane_render(1e7, 1e7, 0.0, 0.0, "flat plane render, origin 1e7 m");
    test_plane_render(0.0, 0.0, 0.25, -0.125, "tilted plane render");
    test_plane_render(1e7, 1e7, 0.25, -0.125, "tilted plane render, origin 1e7 m");
    test_hyperbolic();
    test_sine();
    test_edges();
    test_vs_brute();
    test_render_poses();
    test_with_pyramid_build();
    test_depth_range();
    test_timing();
    return ft_test_result("test_reference");
}
