/* synth_terrain.c - deterministic synthetic mountains (see synth_terrain.h).
 *
 * Recipe (all double, fixed evaluation order, integer-hash gradient noise):
 *   1. domain warp: the sample position is pushed by a 3-octave fBm so ridges
 *      bend instead of following the lattice axes;
 *   2. per octave one gradient-noise sample n in [-1,1] feeds both a ridged
 *      multifractal (1-|n|)^2 weighted by the previous octave (sharp crests,
 *      smooth low ground) and a plain fBm (rolling foothills); each octave is
 *      rotated against the last;
 *   3. blend, then h^1.5 flattens the valley floors;
 *   4. a warped, noisy disc blends the relief down to a floor; after
 *      normalising to 0..1 everything below a waterline becomes exactly 0 m:
 *      a flat lake with an irregular shore.
 * Coordinates are normalised to the grid, so any side shows the same range.
 * Two passes over t->heights_m (raw field, then normalise): no scratch. */
#include "terrain/synth_terrain.h"

#include <math.h>
#include <string.h>

/* Bit-identical results need every a*b+c rounded twice, never fused: GCC in
 * ISO C mode already does this, clang needs telling. */
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

#define FT_SYNTH_OCTAVES_MAX 16u
/* Lattice cells across the map at the first octave. */
#define FT_SYNTH_BASE_FREQ 3.0
#define FT_SYNTH_LACUNARITY 2.0
/* Share of the normalised range below which the basin is water (0 m). */
#define FT_SYNTH_WATERLINE 0.05
/* Basin centre (fraction of the map) and radius. */
#define FT_SYNTH_BASIN_X 0.30
#define FT_SYNTH_BASIN_Y 0.36
#define FT_SYNTH_BASIN_R 0.13
#define FT_SYNTH_BASIN_FLOOR (-0.02)
/* Domain warp amplitude (fraction of the map). */
#define FT_SYNTH_WARP 0.08

/* 32-bit integer hash of a lattice point (lowbias32-style mixing). */
static uint32_t hash3(int32_t x, int32_t y, uint32_t salt)
{
    uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ salt * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

static double fade(double t)
{
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); /* C2 quintic: no creases */
}

/* 16 unit gradients (k * 22.5 deg), written out so no libm call is involved. */
static const double k_grad[16][2] = {
    {1.0, 0.0},
    {0.9238795325112867, 0.3826834323650898},
    {0.7071067811865476, 0.7071067811865476},
    {0.3826834323650898, 0.9238795325112867},
    {0.0, 1.0},
    {-0.3826834323650898, 0.9238795325112867},
    {-0.7071067811865476, 0.7071067811865476},
    {-0.9238795325112867, 0.3826834323650898},
    {-1.0, 0.0},
    {-0.9238795325112867, -0.3826834323650898},
    {-0.7071067811865476, -0.7071067811865476},
    {-0.3826834323650898, -0.9238795325112867},
    {0.0, -1.0},
    {0.3826834323650898, -0.9238795325112867},
    {0.7071067811865476, -0.7071067811865476},
    {0.9238795325112867, -0.3826834323650898},
};

static double grad_dot(int32_t ix, int32_t iy, uint32_t salt, double dx, double dy)
{
    const double *g = k_grad[hash3(ix, iy, salt) >> 28];
    return g[0] * dx + g[1] * dy;
}

/* Gradient (Perlin-style) noise, scaled to roughly [-1, 1]: smoother and far
 * less blocky than value noise, so ridges do not follow the lattice. */
static double gnoise(double x, double y, uint32_t salt)
{
    /* floor without a libm call (|x| < 2^31 here: octaves <= 16) */
    int32_t ix = (int32_t)x, iy = (int32_t)y;
    ix -= ((double)ix > x);
    iy -= ((double)iy > y);
    double fx = (double)ix, fy = (double)iy;
    double rx = x - fx, ry = y - fy;
    double u = fade(rx), v = fade(ry);
    double a = grad_dot(ix, iy, salt, rx, ry);
    double b = grad_dot(ix + 1, iy, salt, rx - 1.0, ry);
    double c = grad_dot(ix, iy + 1, salt, rx, ry - 1.0);
    double d = grad_dot(ix + 1, iy + 1, salt, rx - 1.0, ry - 1.0);
    double ab = a + (b - a) * u;
    double cd = c + (d - c) * u;
    return 1.4142135623730951 * (ab + (cd - ab) * v);
}

static double fbm3(double x, double y, uint32_t salt)
{
    double sum = 0.0, amp = 0.5, f = 1.0;
    for (uint32_t o = 0u; o < 3u; ++o) {
        sum += amp * gnoise(x * f, y * f, salt + o * 0x9e37u);
        amp *= 0.5;
        f *= 2.0;
    }
    return sum;
}

/* Raw height at normalised position (u, v) in [0,1]^2 (any range; the
 * caller normalises). */
static double raw_height(double u, double v, uint32_t seed, uint32_t octaves)
{
    uint32_t salt = seed * 0x632be5abu + 0x5bd1e995u;
    double wu = u + FT_SYNTH_WARP * fbm3(u * 2.0 + 11.3, v * 2.0 + 7.1, salt ^ 0xa5a5u);
    double wv = v + FT_SYNTH_WARP * fbm3(u * 2.0 + 3.7, v * 2.0 + 19.9, salt ^ 0x5a5au);

    double ridge = 0.0, fbm = 0.0, amp = 1.0, weight = 1.0, norm = 0.0;
    double x = wu * FT_SYNTH_BASE_FREQ, y = wv * FT_SYNTH_BASE_FREQ;
    for (uint32_t o = 0u; o < octaves; ++o) {
        double n = gnoise(x, y, salt + o * 0x27d4eb2fu);
        double r = 1.0 - fabs(n);
        r = r * r * weight; /* crests where n crosses 0, damped in low ground */
        weight = r * 1.8;
        weight = weight > 1.0 ? 1.0 : (weight < 0.0 ? 0.0 : weight);
        ridge += r * amp;
        fbm += n * amp;
        norm += amp;
        amp *= 0.5;
        /* next octave: double the frequency and rotate by 36.87 deg (a 3-4-5
         * triangle) so octaves never share lattice axes */
        double nx = (0.8 * x - 0.6 * y) * FT_SYNTH_LACUNARITY + 17.0;
        double ny = (0.6 * x + 0.8 * y) * FT_SYNTH_LACUNARITY + 31.0;
        x = nx;
        y = ny;
    }
    ridge /= norm;                /* about 0..1 */
    fbm = 0.5 + 0.5 * fbm / norm; /* about 0..1 */
    double h = 0.7 * ridge + 0.3 * fbm;
    h = h > 0.0 ? h : 0.0;
    h = h * sqrt(h); /* h^1.5: broad valley floors; sqrt is exactly rounded, pow is not */

    /* Basin: inside a warped disc the relief is blended down to a floor
     * below every other height, so the lake (what ends up under the
     * waterline) has a flat bed and an irregular shore. */
    double dx = wu - FT_SYNTH_BASIN_X, dy = wv - FT_SYNTH_BASIN_Y;
    double q = (dx * dx + dy * dy) / (FT_SYNTH_BASIN_R * FT_SYNTH_BASIN_R);
    if (q < 2.0) {
        /* bays and headlands: a finer noise bends the shore */
        q *= 1.0 + 0.9 * fbm3(u * 9.0 + 5.5, v * 9.0 + 1.25, salt ^ 0x3c3cu);
    }
    if (q < 1.0) {
        double t = (1.0 - q) / 0.6;
        t = t > 1.0 ? 1.0 : t;
        double s = t * t * (3.0 - 2.0 * t);
        h = h * (1.0 - s) + FT_SYNTH_BASIN_FLOOR * s;
    }
    return h;
}

ft_status ft_synth_probe(const ft_synth_desc *d, ft_terrain *t, ft_error *err)
{
    if (d == NULL || t == NULL) {
        return ft_fail(err, FT_ERR_ARG, "synth terrain: desc or terrain is NULL");
    }
    if (d->side < FT_GRID_SIDE_MIN || d->side > FT_GRID_SIDE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "synth terrain: side %u outside %u..%u", d->side,
                       FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    if (!isfinite(d->spacing_m) || !(d->spacing_m > 0.0) || d->spacing_m > 1.0e5) {
        return ft_fail(err, FT_ERR_CONFIG, "synth terrain: spacing %g m outside (0, 1e5]",
                       d->spacing_m);
    }
    if (!isfinite(d->relief_m) || !(d->relief_m > 0.0) || d->relief_m > 1.0e4) {
        return ft_fail(err, FT_ERR_CONFIG, "synth terrain: relief %g m outside (0, 1e4]",
                       d->relief_m);
    }
    if (d->octaves < 1u || d->octaves > FT_SYNTH_OCTAVES_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "synth terrain: octaves %u outside 1..%u", d->octaves,
                       FT_SYNTH_OCTAVES_MAX);
    }
    if (!isfinite(d->anchor_lat_deg) || !isfinite(d->anchor_lon_deg) ||
        fabs(d->anchor_lat_deg) > 89.0 || fabs(d->anchor_lon_deg) > 360.0) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "synth terrain: anchor %g, %g deg outside |lat| <= 89, |lon| <= 360",
                       d->anchor_lat_deg, d->anchor_lon_deg);
    }
    t->width = d->side;
    t->height = d->side;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = d->spacing_m;
    t->spacing_y = d->spacing_m;
    t->origin_x = 0.0;
    t->origin_y = 0.0;
    t->anchor_lat_deg = d->anchor_lat_deg;
    t->anchor_lon_deg = d->anchor_lon_deg;
    memset(t->crs, 0, sizeof t->crs);
    memcpy(t->crs, "local", sizeof "local");
    t->void_count = 0u;
    t->min_height_m = 0.0f;
    t->max_height_m = (float)d->relief_m;
    return ft_terrain_derive_frame(t, err);
}

void ft_synth_generate(const ft_synth_desc *d, ft_terrain *t)
{
    if (d == NULL || t == NULL || t->heights_m == NULL || d->side < FT_GRID_SIDE_MIN ||
        d->side > FT_GRID_SIDE_MAX || t->width != d->side || t->height != d->side) {
        return;
    }
    uint32_t n = d->side;
    uint32_t octaves = d->octaves < 1u ? 1u : d->octaves;
    octaves = octaves > FT_SYNTH_OCTAVES_MAX ? FT_SYNTH_OCTAVES_MAX : octaves;
    double inv = 1.0 / (double)(n - 1u);
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t y = 0u; y < n; ++y) {
        float *row = t->heights_m + (size_t)y * n;
        for (uint32_t x = 0u; x < n; ++x) {
            double h = raw_height((double)x * inv, (double)y * inv, d->seed, octaves);
            row[x] = (float)h;
            lo = h < lo ? h : lo;
            hi = h > hi ? h : hi;
        }
    }
    /* Normalise from the float values actually stored, so the extremes map
     * exactly to 0 and relief. */
    lo = (double)(float)lo;
    hi = (double)(float)hi;
    double span = hi - lo;
    if (!(span > 0.0)) {
        span = 1.0;
    }
    double scale = d->relief_m / (1.0 - FT_SYNTH_WATERLINE);
    size_t count = (size_t)n * n;
    float mn = INFINITY, mx = -INFINITY;
    for (size_t k = 0u; k < count; ++k) {
        double s = ((double)t->heights_m[k] - lo) / span - FT_SYNTH_WATERLINE;
        double h = s > 0.0 ? s * scale : 0.0; /* below the waterline: the lake, exactly 0 m */
        float f = (float)h;
        f = f > (float)d->relief_m ? (float)d->relief_m : f;
        t->heights_m[k] = f;
        mn = f < mn ? f : mn;
        mx = f > mx ? f : mx;
    }
    t->min_height_m = mn;
    t->max_height_m = mx;
}
