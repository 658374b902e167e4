/* bintree.c - error tables and per-frame selection (see bintree.h). */
#include "lod/bintree.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/invariant.h"
#include "core/view_scale.h"
#include "lod/bintree_template.h"

/* The lattice has 2^N + 1 samples a side: the largest grid a terrain has. */
_Static_assert((1u << FT_BT_N_MAX) + 1u == FT_GRID_SIDE_MAX, "bintree levels vs the grid side");

/* ---- sizes ---------------------------------------------------------------- */

uint32_t ft_bt_domain_n(uint32_t w, uint32_t h)
{
    uint32_t cells = ((w > h) ? w : h) - 1u;
    uint32_t n = 0;
    while (n < 31u && (1u << n) < cells) {
        ++n;
    }
    return n;
}

static uint32_t lattice_side(uint32_t n, uint32_t k)
{
    return (k <= n) ? ((1u << (n - k)) + 1u) : 2u;
}

static uint32_t ceil_shift(uint32_t v, uint32_t m)
{
    return (v + (1u << m) - 1u) >> m;
}

void ft_bt_twist_layout_for(uint32_t w, uint32_t h, uint32_t k, ft_bt_twist_layout *l)
{
    memset(l, 0, sizeof *l);
    const uint32_t cells = ((w > h) ? w : h) - 1u;
    l->levels = 1u;
    while (l->levels < k + 3u && l->levels < FT_BT_TWIST_LEVELS_MAX &&
           (1u << (l->levels - 1u)) < cells) {
        ++l->levels;
    }
    uint32_t y = 0;
    for (uint32_t m = 0; m < l->levels; ++m) {
        l->w[m] = ceil_shift(w - 1u, m);
        l->h[m] = ceil_shift(h - 1u, m);
        l->ox[m] = (m == 0u) ? 0u : l->w[0];
        l->oy[m] = (m == 0u) ? 0u : y;
        y += (m == 0u) ? 0u : l->h[m];
    }
    l->atlas_w = l->w[0] + ((l->levels > 1u) ? l->w[1] : 0u);
    l->atlas_h = (y > l->h[0]) ? y : l->h[0];
}

void ft_bt_zblock_size(uint32_t w, uint32_t h, uint32_t k, uint32_t *bw, uint32_t *bh)
{
    *bw = ceil_shift(w - 1u, k + 2u);
    *bh = ceil_shift(h - 1u, k + 2u);
}

void ft_bintree_plan(ft_arena *a, uint32_t w, uint32_t h, uint32_t k, uint32_t sub,
                     uint32_t tiles_max)
{
    uint32_t n = ft_bt_domain_n(w, h);
    size_t m = lattice_side(n, k);
    ft_arena_plan(a, FT_POOL_METHOD, m * m * sizeof(float));
    ft_arena_plan(a, FT_POOL_METHOD, m * m * 4u * sizeof(float));
    if (sub == 0u) {
        const size_t leaves = (k <= n) ? ((size_t)1 << (n - k)) * ((size_t)1 << (n - k)) : 1u;
        ft_arena_plan(a, FT_POOL_METHOD, leaves * sizeof(float));
        ft_arena_plan(a, FT_POOL_METHOD, leaves * 2u * sizeof(float));
    } else {
        ft_bt_twist_layout l;
        ft_bt_twist_layout_for(w, h, k, &l);
        ft_arena_plan(a, FT_POOL_METHOD, (size_t)l.atlas_w * l.atlas_h * sizeof(float));
        uint32_t bw, bh;
        ft_bt_zblock_size(w, h, k, &bw, &bh);
        ft_arena_plan(a, FT_POOL_METHOD, (size_t)bw * bh * 4u * sizeof(float));
    }
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)tiles_max * sizeof(ft_bt_tile));
    if (k >= FT_BT_TEMPLATE_K_MIN && k <= FT_BT_TEMPLATE_K_MAX) {
        ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_scratch(k) * sizeof(int16_t));
    }
}

/* ---- table building (init only) -------------------------------------------- */

typedef struct tri_acc {
    double err_m;
    float z0, z1;
    int32_t x0, x1, y0, y1; /* clamped bbox of non-degenerate parts */
    int any;                /* some sample inside */
} tri_acc;

typedef struct build_ctx {
    ft_bintree *bt;
    const int16_t *tmpl; /* template triangles, 6 ints each, units of 2^-k */
    uint32_t tmpl_count;
} build_ctx;

static int32_t clamp_i(int32_t v, int32_t hi)
{
    return (v < 0) ? 0 : ((v > hi) ? hi : v);
}

static float height_at(const ft_bintree *bt, int32_t x, int32_t y)
{
    return bt->heights_m[(size_t)y * bt->width + (size_t)x];
}

static int64_t edge_fn(const int32_t a[2], const int32_t b[2], int32_t px, int32_t py)
{
    return (int64_t)(b[0] - a[0]) * (int64_t)(py - a[1]) -
           (int64_t)(b[1] - a[1]) * (int64_t)(px - a[0]);
}

/* The bilinear surface over the cell whose corner is (cx, cy), at grid
 * point (x, y) (the truth every error here is measured against). */
static double bilinear_in_cell(const ft_bintree *bt, int32_t cx, int32_t cy, double x, double y)
{
    const double h00 = height_at(bt, cx, cy), h10 = height_at(bt, cx + 1, cy);
    const double h01 = height_at(bt, cx, cy + 1), h11 = height_at(bt, cx + 1, cy + 1);
    const double u = x - (double)cx, v = y - (double)cy;
    return h00 + (h10 - h00) * u + (h01 - h00) * v + (h00 + h11 - h10 - h01) * u * v;
}

/* Max |H - L| along the edge a -> b of a template triangle, H the bilinear
 * surface and L linear from ha (at a) to hb (at b). The edge is cut where it
 * crosses cell lines; on each piece H - L is a quadratic in the edge
 * parameter (the bilinear twist D u v along a line), so its extremes are
 * the piece's ends and its one stationary point. Together with the samples
 * inside the triangle this is the exact max over the triangle: inside a
 * cell H - L is linear plus a saddle, with no extremum in the interior, and
 * along cell lines H is linear. Bounded: |dx| + |dy| + 1 pieces. */
static double edge_max(const ft_bintree *bt, const int32_t a[2], const int32_t b[2], double ha,
                       double hb)
{
    const int32_t dx = b[0] - a[0], dy = b[1] - a[1];
    const int32_t cx_max = (int32_t)bt->width - 2, cy_max = (int32_t)bt->height - 2;
    const int32_t nx = (dx < 0) ? -dx : dx, ny = (dy < 0) ? -dy : dy;
    int32_t ix = 1, iy = 1; /* next x / y crossing (1..n-1) */
    double t0 = 0.0, worst = 0.0;
    for (int32_t piece = 0; piece <= nx + ny; ++piece) {
        const double tx = (ix < nx) ? (double)ix / (double)nx : 2.0;
        const double ty = (iy < ny) ? (double)iy / (double)ny : 2.0;
        double t1 = (tx < ty) ? tx : ty;
        if (t1 > 1.0) {
            t1 = 1.0;
        }
        if (t1 > t0) {
            const double tm = 0.5 * (t0 + t1);
            const double xm = (double)a[0] + (double)dx * tm, ym = (double)a[1] + (double)dy * tm;
            int32_t cx = (int32_t)floor(xm), cy = (int32_t)floor(ym);
            cx = (cx < 0) ? 0 : ((cx > cx_max) ? cx_max : cx);
            cy = (cy < 0) ? 0 : ((cy > cy_max) ? cy_max : cy);
            double ts[3] = {t0, t1, -1.0};
            const double d = height_at(bt, cx, cy) + height_at(bt, cx + 1, cy + 1) -
                             height_at(bt, cx + 1, cy) - height_at(bt, cx, cy + 1);
            const double c2 = d * (double)dx * (double)dy; /* e(t) = c2 t^2 + ... */
            if (c2 != 0.0) {
                const double u0 = (double)(a[0] - cx), v0 = (double)(a[1] - cy);
                const double bx = height_at(bt, cx + 1, cy) - height_at(bt, cx, cy);
                const double by = height_at(bt, cx, cy + 1) - height_at(bt, cx, cy);
                const double c1 = bx * dx + by * dy + d * (dx * v0 + dy * u0) - (hb - ha);
                const double ts_star = -c1 / (2.0 * c2);
                if (ts_star > t0 && ts_star < t1) {
                    ts[2] = ts_star;
                }
            }
            for (int i = 0; i < 3; ++i) {
                if (ts[i] < 0.0) {
                    continue;
                }
                const double x = (double)a[0] + (double)dx * ts[i];
                const double y = (double)a[1] + (double)dy * ts[i];
                const double e = fabs(bilinear_in_cell(bt, cx, cy, x, y) - (ha + (hb - ha) * ts[i]));
                worst = (e > worst) ? e : worst;
            }
        }
        if (t1 >= 1.0) {
            break;
        }
        if (tx <= ty) {
            ++ix;
        }
        if (ty <= tx) {
            ++iy;
        }
        t0 = t1;
    }
    return worst;
}

/* Exact max |bilinear surface - plane| over one clamped template triangle
 * (the samples inside it and the quadratic along its edges, see edge_max);
 * also the sample height range and bbox. */
static void scan_triangle(ft_bintree *bt, int32_t v[3][2], tri_acc *acc)
{
    const int32_t wx = (int32_t)bt->width - 1, hy = (int32_t)bt->height - 1;
    for (int i = 0; i < 3; ++i) {
        v[i][0] = clamp_i(v[i][0], wx);
        v[i][1] = clamp_i(v[i][1], hy);
    }
    int64_t area2 = edge_fn(v[0], v[1], v[2][0], v[2][1]);
    if (area2 == 0) {
        return; /* collapsed onto the grid edge: draws nothing */
    }
    if (area2 < 0) {
        bt->flipped_triangles += 1u;
        return;
    }
    int32_t x0 = v[0][0], x1 = v[0][0], y0 = v[0][1], y1 = v[0][1];
    for (int i = 1; i < 3; ++i) {
        x0 = (v[i][0] < x0) ? v[i][0] : x0;
        x1 = (v[i][0] > x1) ? v[i][0] : x1;
        y0 = (v[i][1] < y0) ? v[i][1] : y0;
        y1 = (v[i][1] > y1) ? v[i][1] : y1;
    }
    const double h0 = height_at(bt, v[0][0], v[0][1]);
    const double h1 = height_at(bt, v[1][0], v[1][1]);
    const double h2 = height_at(bt, v[2][0], v[2][1]);
    const double inv = 1.0 / (double)area2;
    for (int32_t y = y0; y <= y1; ++y) {
        for (int32_t x = x0; x <= x1; ++x) {
            int64_t w0 = edge_fn(v[1], v[2], x, y);
            int64_t w1 = edge_fn(v[2], v[0], x, y);
            int64_t w2 = edge_fn(v[0], v[1], x, y);
            if (w0 < 0 || w1 < 0 || w2 < 0) {
                continue;
            }
            double plane = ((double)w0 * h0 + (double)w1 * h1 + (double)w2 * h2) * inv;
            float hs = height_at(bt, x, y);
            double d = fabs((double)hs - plane);
            acc->err_m = (d > acc->err_m) ? d : acc->err_m;
            if (!acc->any) {
                acc->z0 = acc->z1 = hs;
                acc->x0 = x0; acc->x1 = x1; acc->y0 = y0; acc->y1 = y1;
                acc->any = 1;
            }
            acc->z0 = (hs < acc->z0) ? hs : acc->z0;
            acc->z1 = (hs > acc->z1) ? hs : acc->z1;
        }
    }
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        const double hi = (i == 0) ? h0 : ((i == 1) ? h1 : h2);
        const double hj = (j == 0) ? h0 : ((j == 1) ? h1 : h2);
        const double d = edge_max(bt, v[i], v[j], hi, hj);
        acc->err_m = (d > acc->err_m) ? d : acc->err_m;
    }
    if (acc->any) {
        acc->x0 = (x0 < acc->x0) ? x0 : acc->x0;
        acc->x1 = (x1 > acc->x1) ? x1 : acc->x1;
        acc->y0 = (y0 < acc->y0) ? y0 : acc->y0;
        acc->y1 = (y1 > acc->y1) ? y1 : acc->y1;
    }
}

/* Exact template error and bounds of tile (apex, left, right). */
static void measure_tile(build_ctx *bc, const int32_t apex[2], const int32_t left[2],
                         const int32_t right[2], tri_acc *acc)
{
    const uint32_t k = bc->bt->k;
    const int32_t ux[2] = {left[0] - apex[0], left[1] - apex[1]};
    const int32_t uy[2] = {right[0] - apex[0], right[1] - apex[1]};
    for (uint32_t t = 0; t < bc->tmpl_count; ++t) {
        const int16_t *p = bc->tmpl + 6u * t;
        int32_t v[3][2];
        for (int i = 0; i < 3; ++i) {
            int32_t a = p[2 * i], b = p[2 * i + 1];
            /* exact: legs are multiples of 2^k for tile levels <= L */
            v[i][0] = apex[0] + ((a * ux[0] + b * uy[0]) >> k);
            v[i][1] = apex[1] + ((a * ux[1] + b * uy[1]) >> k);
        }
        scan_triangle(bc->bt, v, acc);
    }
}

static size_t lat_index(const ft_bintree *bt, int32_t x, int32_t y)
{
    return (size_t)((uint32_t)y >> bt->k) * bt->lattice_side + ((uint32_t)x >> bt->k);
}

static void box_set_empty(float *b)
{
    b[0] = b[2] = b[4] = FLT_MAX;
    b[1] = b[3] = b[5] = -FLT_MAX;
}

/* Square side (fine units) of the diamonds of `level`. */
static double square_side(const ft_bintree *bt, uint32_t level)
{
    return (double)(bt->fine_side >> (level / 2u));
}

/* The morph width W of a diamond of `level`, metres (see bintree.h). */
static double morph_width_m(const ft_bintree *bt, uint32_t level)
{
    return bt->morph_width * square_side(bt, level) * bt->fine_m;
}

/* The box margin M of a diamond of `level`, fine units. */
static double box_margin(const ft_bintree *bt, uint32_t level)
{
    return (((level & 1u) != 0u) ? 2.0 : 3.0) * bt->morph_width * square_side(bt, level);
}

/* Widens box b's z range by m metres, rounded outward (empty stays empty). */
static void widen_z(float *b, double m)
{
    if (!(b[4] <= b[5])) {
        return;
    }
    const double lo = (double)b[4] - m, hi = (double)b[5] + m;
    b[4] = (float)lo;
    b[5] = (float)hi;
    if ((double)b[4] > lo) {
        b[4] = nextafterf(b[4], -FLT_MAX);
    }
    if ((double)b[5] < hi) {
        b[5] = nextafterf(b[5], FLT_MAX);
    }
}

/* The closed-form xy of the box of diamond c (fine units) at `level`: its
 * closure widened by the margin, in grid units, not clamped (clamping would
 * close the gap at the grid's edge). */
static void closure_xy(const ft_bintree *bt, uint32_t level, const int32_t c[2], float b[4])
{
    const double f = (double)(1u << bt->sub);
    const double s = square_side(bt, level);
    const double r = (((level & 1u) != 0u) ? s : 1.5 * s) + box_margin(bt, level);
    const double v[4] = {((double)c[0] - r) / f, ((double)c[0] + r) / f, ((double)c[1] - r) / f,
                         ((double)c[1] + r) / f};
    for (int i = 0; i < 4; ++i) {
        b[i] = (float)v[i];
        /* outward: lower bounds down, upper bounds up */
        if ((i & 1) == 0 && (double)b[i] > v[i]) {
            b[i] = nextafterf(b[i], -FLT_MAX);
        } else if ((i & 1) == 1 && (double)b[i] < v[i]) {
            b[i] = nextafterf(b[i], FLT_MAX);
        }
    }
}

/* The (at most two) triangles of the diamond with split vertex c at level
 * `level`. Returns how many; tris[i] = apex, left, right. */
static uint32_t diamond_triangles(const ft_bintree *bt, uint32_t level, int32_t cx, int32_t cy,
                                  int32_t tris[2][3][2])
{
    const int32_t n_cells = (int32_t)bt->side_cells;
    uint32_t count = 0;
#define FT_SET_TRI(ax, ay, lx, ly, rx, ry)                                          \
    do {                                                                           \
        tris[count][0][0] = (ax); tris[count][0][1] = (ay);                        \
        tris[count][1][0] = (lx); tris[count][1][1] = (ly);                        \
        tris[count][2][0] = (rx); tris[count][2][1] = (ry);                        \
        ++count;                                                                   \
    } while (0)
    if ((level & 1u) == 0u) {
        const int32_t h = (int32_t)(bt->side_cells >> (level / 2u)) / 2; /* half side */
        const int32_t x0 = cx - h, x1 = cx + h, y0 = cy - h, y1 = cy + h;
        const int32_t qx = x0 / (2 * h), qy = y0 / (2 * h);
        if (((qx + qy) & 1) == 0) { /* "/" diagonal (x0,y0)-(x1,y1) */
            FT_SET_TRI(x1, y0, x1, y1, x0, y0);
            FT_SET_TRI(x0, y1, x0, y0, x1, y1);
        } else { /* "\" diagonal (x0,y1)-(x1,y0) */
            FT_SET_TRI(x0, y0, x1, y0, x0, y1);
            FT_SET_TRI(x1, y1, x0, y1, x1, y0);
        }
    } else {
        const int32_t s = (int32_t)(bt->side_cells >> (level / 2u));
        const int32_t h = s / 2;
        if ((cx % s) != 0) { /* midpoint of a horizontal edge */
            if (cy < n_cells) FT_SET_TRI(cx, cy + h, cx - h, cy, cx + h, cy);
            if (cy > 0) FT_SET_TRI(cx, cy - h, cx + h, cy, cx - h, cy);
        } else { /* midpoint of a vertical edge */
            if (cx < n_cells) FT_SET_TRI(cx + h, cy, cx, cy + h, cx, cy - h);
            if (cx > 0) FT_SET_TRI(cx - h, cy, cx, cy - h, cx, cy + h);
        }
    }
#undef FT_SET_TRI
    return count;
}

/* Calls fn for every diamond split vertex of `level` (row by row). */
typedef void (*diamond_fn)(build_ctx *bc, uint32_t level, int32_t cx, int32_t cy);

static void for_each_diamond(build_ctx *bc, uint32_t level, diamond_fn fn)
{
    const ft_bintree *bt = bc->bt;
    const int32_t s = (int32_t)(bt->side_cells >> (level / 2u)); /* square side */
    const int32_t cnt = (int32_t)bt->side_cells / s;
    if ((level & 1u) == 0u) {
        for (int32_t qy = 0; qy < cnt; ++qy) {
            for (int32_t qx = 0; qx < cnt; ++qx) {
                fn(bc, level, qx * s + s / 2, qy * s + s / 2);
            }
        }
    } else {
        for (int32_t qy = 0; qy <= cnt; ++qy) {
            for (int32_t qx = 0; qx < cnt; ++qx) {
                fn(bc, level, qx * s + s / 2, qy * s); /* horizontal edges */
            }
        }
        for (int32_t qy = 0; qy < cnt; ++qy) {
            for (int32_t qx = 0; qx <= cnt; ++qx) {
                fn(bc, level, qx * s, qy * s + s / 2); /* vertical edges */
            }
        }
    }
}

/* The leaf table's index of a level-L diamond (a square of side 2^k,
 * centred on an odd multiple of 2^(k-1)). */
static size_t leaf_index(const ft_bintree *bt, int32_t x, int32_t y)
{
    return (size_t)((uint32_t)y >> bt->k) * bt->leaf_side + ((uint32_t)x >> bt->k);
}

/* Error and box of diamond c into (err, box). */
static void measure_diamond(build_ctx *bc, uint32_t level, int32_t cx, int32_t cy, float *err,
                            float *b)
{
    ft_bintree *bt = bc->bt;
    int32_t tris[2][3][2];
    uint32_t count = diamond_triangles(bt, level, cx, cy, tris);
    tri_acc acc;
    memset(&acc, 0, sizeof acc);
    for (uint32_t i = 0; i < count; ++i) {
        measure_tile(bc, tris[i][0], tris[i][1], tris[i][2], &acc);
    }
    *err = (float)acc.err_m;
    if (acc.err_m > (double)*err) {
        /* round up: the stored bound must not be below the exact error */
        *err = nextafterf(*err, FLT_MAX);
    }
    if (acc.any) {
        b[0] = (float)acc.x0; b[1] = (float)acc.x1;
        b[2] = (float)acc.y0; b[3] = (float)acc.y1;
        b[4] = acc.z0; b[5] = acc.z1;
    } else {
        box_set_empty(b);
    }
}

static void own_error(build_ctx *bc, uint32_t level, int32_t cx, int32_t cy)
{
    ft_bintree *bt = bc->bt;
    size_t li = lat_index(bt, cx, cy);
    float b[FT_BT_BOX_FLOATS];
    measure_diamond(bc, level, cx, cy, &bt->err_m[li], b);
    bt->dia[4u * li + 1u] = b[4];
    bt->dia[4u * li + 2u] = b[5];
}

static void leaf_error(build_ctx *bc, uint32_t level, int32_t cx, int32_t cy)
{
    ft_bintree *bt = bc->bt;
    size_t li = leaf_index(bt, cx, cy);
    float b[FT_BT_BOX_FLOATS];
    measure_diamond(bc, level, cx, cy, &bt->leaf_err_m[li], b);
    bt->leaf_z[2u * li] = b[4];
    bt->leaf_z[2u * li + 1u] = b[5];
}

/* The box of the leaf diamond c: its square (side 2^k) clamped to the grid,
 * and its stored height range (empty when all of it lies in the padding). */
static void leaf_box(const ft_bintree *bt, int32_t cx, int32_t cy, float b[FT_BT_BOX_FLOATS])
{
    const int32_t h = (int32_t)bt->step / 2;
    const int32_t wx = (int32_t)bt->width - 1, hy = (int32_t)bt->height - 1;
    const size_t li = leaf_index(bt, cx, cy);
    b[0] = (float)clamp_i(cx - h, wx);
    b[1] = (float)clamp_i(cx + h, wx);
    b[2] = (float)clamp_i(cy - h, hy);
    b[3] = (float)clamp_i(cy + h, hy);
    b[4] = bt->leaf_z[2u * li];
    b[5] = bt->leaf_z[2u * li + 1u];
    if (b[4] > b[5]) {
        box_set_empty(b);
    }
}

/* A diamond's error and box take in its children's (the midpoints of its
 * triangles' legs), so a child is active only if both its parents are. */
static void saturate(build_ctx *bc, uint32_t level, int32_t cx, int32_t cy)
{
    ft_bintree *bt = bc->bt;
    int32_t tris[2][3][2];
    uint32_t count = diamond_triangles(bt, level, cx, cy, tris);
    size_t li = lat_index(bt, cx, cy);
    const int leaf_children = (bt->sub == 0u && level + 1u == bt->leaf_level);
    const int sub_children = (bt->sub > 0u && level + 1u == bt->sub_level);
    for (uint32_t i = 0; i < count; ++i) {
        for (int leg = 1; leg <= 2; ++leg) {
            int32_t mx = (tris[i][0][0] + tris[i][leg][0]) / 2;
            int32_t my = (tris[i][0][1] + tris[i][leg][1]) / 2;
            float cb[FT_BT_BOX_FLOATS];
            float ce;
            if (leaf_children) {
                ce = bt->leaf_err_m[leaf_index(bt, mx, my)];
                leaf_box(bt, mx, my, cb);
            } else if (sub_children) {
                const int32_t cf[2] = {mx << bt->sub, my << bt->sub};
                const double e = ft_bt_sub_error(bt, level + 1u, cf, cb);
                ce = (float)e;
                if (e > (double)ce) {
                    ce = nextafterf(ce, FLT_MAX);
                }
            } else {
                const size_t ci = lat_index(bt, mx, my);
                ce = bt->err_m[ci];
                box_set_empty(cb);
                cb[4] = bt->dia[4u * ci + 1u];
                cb[5] = bt->dia[4u * ci + 2u];
            }
            bt->err_m[li] = (ce > bt->err_m[li]) ? ce : bt->err_m[li];
            if (cb[4] <= cb[5]) {
                /* the child's range widened by its morph width: the gap the
                 * geomorph's rule needs (see bintree.h) */
                widen_z(cb, morph_width_m(bt, level + 1u));
                float *z = &bt->dia[4u * li + 1u];
                z[0] = (cb[4] < z[0]) ? cb[4] : z[0];
                z[1] = (cb[5] > z[1]) ? cb[5] : z[1];
            }
        }
    }
}

/* ---- sub-sample levels (S > 0) ----------------------------------------------------
 *
 * From sub_level on, a tile's template vertices lie on or between samples
 * and take the bilinear height, so inside one cell its triangles' surface
 * differs from the truth only by the cell's twist: a triangle of level
 * >= 2n (inside one cell) with axis legs of a cells, or with diagonal legs
 * and hypotenuse a, is off by at most |D| a^2 / 4, or |D| (a/2)^2 / 4
 * (sub_q; a = 1: the classic |D| / 4 of a cell split along a diagonal).
 * A diamond's error is sub_q times the largest |D| over its closure: the square of half-side 1.5 s (even level, square side
 * s) or s (odd level) around its split vertex, which holds the closures of
 * all its descendants (a child lies s/2 or s/4 from its parent), so errors
 * and boxes nest and the selection stays conforming. The largest |D| and
 * the height range over the closure come from <= 4 aligned blocks of the
 * twist and min/max pyramids. */

static double sub_q(const ft_bintree *bt, uint32_t level)
{
    const uint32_t tl = level + 2u * bt->k; /* the template triangles' level */
    const double a = (double)(bt->fine_side >> (tl / 2u)) / (double)(1u << bt->sub);
    const double leg = ((tl & 1u) != 0u) ? 0.5 * a : a;
    return 0.25 * leg * leg;
}

static int32_t clamp_range(int32_t v, int32_t lo, int32_t hi)
{
    return (v < lo) ? lo : ((v > hi) ? hi : v);
}

/* The largest twist and the height range over the cells under the grid
 * rectangle [gx0, gx1] x [gy0, gy1] (already inside the grid), from <= 4
 * aligned blocks of the twist and min/max pyramids; the rectangle and range
 * into box. Sub-rectangles get sub-blocks: nested in, nested out. */
static double cover_twist(const ft_bintree *bt, double gx0, double gx1, double gy0, double gy1,
                          float box[FT_BT_BOX_FLOATS])
{
    const int32_t cmx = (int32_t)bt->width - 2, cmy = (int32_t)bt->height - 2;
    const int32_t cx0 = clamp_range((int32_t)floor(gx0), 0, cmx);
    const int32_t cy0 = clamp_range((int32_t)floor(gy0), 0, cmy);
    const int32_t cx1 = clamp_range((int32_t)ceil(gx1) - 1, cx0, cmx);
    const int32_t cy1 = clamp_range((int32_t)ceil(gy1) - 1, cy0, cmy);
    const int32_t span = ((cx1 - cx0) > (cy1 - cy0) ? (cx1 - cx0) : (cy1 - cy0)) + 1;
    uint32_t m = 0;
    while (m + 1u < FT_PYRAMID_LEVELS_MAX && (1 << m) < span) {
        ++m;
    }
    const uint32_t mt = (m < bt->twist.levels) ? m : bt->twist.levels - 1u;
    const ft_pyramid *pyr = &bt->terrain->pyr;
    const uint32_t mz = (m < pyr->minmax_levels) ? m : pyr->minmax_levels - 1u;
    double dmax = 0.0;
    float z0 = FLT_MAX, z1 = -FLT_MAX;
    for (int32_t by = cy0 >> mt; by <= (cy1 >> mt); ++by) {
        for (int32_t bx = cx0 >> mt; bx <= (cx1 >> mt); ++bx) {
            const float d = bt->twist_atlas[(size_t)(bt->twist.oy[mt] + (uint32_t)by) *
                                                bt->twist.atlas_w +
                                            bt->twist.ox[mt] + (uint32_t)bx];
            dmax = ((double)d > dmax) ? (double)d : dmax;
        }
    }
    const ft_pyramid_level *pz = &pyr->minmax[mz];
    for (int32_t by = cy0 >> mz; by <= (cy1 >> mz); ++by) {
        for (int32_t bx = cx0 >> mz; bx <= (cx1 >> mz); ++bx) {
            const size_t i = (size_t)by * pz->width + (size_t)bx;
            z0 = (pz->min_m[i] < z0) ? pz->min_m[i] : z0;
            z1 = (pz->max_m[i] > z1) ? pz->max_m[i] : z1;
        }
    }
    box[0] = (float)gx0;
    box[1] = (float)gx1;
    box[2] = (float)gy0;
    box[3] = (float)gy1;
    box[4] = z0;
    box[5] = z1;
    return dmax;
}

/* The height range of the aligned 2^(k+2)-cell blocks under the cells of
 * grid rectangle [gx0, gx1] x [gy0, gy1] (inside the grid) into z. A
 * sub-rectangle gets a subset of the blocks: nested in, nested out. */
static void zblock_range(const ft_bintree *bt, double gx0, double gx1, double gy0, double gy1,
                         float z[2])
{
    const int32_t cmx = (int32_t)bt->width - 2, cmy = (int32_t)bt->height - 2;
    const int32_t cx0 = clamp_range((int32_t)floor(gx0), 0, cmx);
    const int32_t cy0 = clamp_range((int32_t)floor(gy0), 0, cmy);
    const int32_t cx1 = clamp_range((int32_t)ceil(gx1) - 1, cx0, cmx);
    const int32_t cy1 = clamp_range((int32_t)ceil(gy1) - 1, cy0, cmy);
    const uint32_t sh = bt->zblock_shift;
    z[0] = FLT_MAX;
    z[1] = -FLT_MAX;
    for (int32_t by = cy0 >> sh; by <= (cy1 >> sh); ++by) {
        for (int32_t bx = cx0 >> sh; bx <= (cx1 >> sh); ++bx) {
            const float *b = &bt->zblock[4u * ((size_t)by * bt->zblock_w + (size_t)bx)];
            z[0] = (b[0] < z[0]) ? b[0] : z[0];
            z[1] = (b[1] > z[1]) ? b[1] : z[1];
        }
    }
}

double ft_bt_sub_error(const ft_bintree *bt, uint32_t level, const int32_t c[2],
                       float box[FT_BT_BOX_FLOATS])
{
    const double f = (double)(1u << bt->sub);
    const double s = square_side(bt, level);
    const double r = ((level & 1u) != 0u) ? s : 1.5 * s;
    const double wx = (double)bt->width - 1.0, hy = (double)bt->height - 1.0;
    const double gx0 = fmin(fmax(((double)c[0] - r) / f, 0.0), wx);
    const double gx1 = fmin(fmax(((double)c[0] + r) / f, 0.0), wx);
    const double gy0 = fmin(fmax(((double)c[1] - r) / f, 0.0), hy);
    const double gy1 = fmin(fmax(((double)c[1] + r) / f, 0.0), hy);
    const double e = sub_q(bt, level) * cover_twist(bt, gx0, gx1, gy0, gy1, box);
    float z[2];
    zblock_range(bt, gx0, gx1, gy0, gy1, z);
    closure_xy(bt, level, c, box);
    box[4] = z[0];
    box[5] = z[1];
    widen_z(box, box_margin(bt, level) * bt->fine_m);
    return e;
}

/* A leaf tile's own error and box (S > 0): its template triangles lie in
 * the cells under its bounding rectangle, so sub_q x the largest twist
 * there, and that rectangle's height range. Tighter than the diamond's
 * closure, which only the split decision needs (for nesting). */
static double leaf_tile_error(const ft_bintree *bt, const int32_t x[3], const int32_t y[3],
                              float box[FT_BT_BOX_FLOATS])
{
    const double f = (double)(1u << bt->sub);
    const double wx = (double)bt->width - 1.0, hy = (double)bt->height - 1.0;
    double gx0 = wx, gx1 = 0.0, gy0 = hy, gy1 = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double gx = fmin((double)x[i] / f, wx), gy = fmin((double)y[i] / f, hy);
        gx0 = fmin(gx0, gx);
        gx1 = fmax(gx1, gx);
        gy0 = fmin(gy0, gy);
        gy1 = fmax(gy1, gy);
    }
    return sub_q(bt, bt->leaf_level) * cover_twist(bt, gx0, gx1, gy0, gy1, box);
}

float ft_bt_height_fine(const ft_bintree *bt, int32_t x, int32_t y)
{
    const uint32_t sh = bt->sub;
    const int32_t f = 1 << sh;
    if (((x | y) & (f - 1)) == 0) {
        return height_at(bt, clamp_i(x >> sh, (int32_t)bt->width - 1),
                         clamp_i(y >> sh, (int32_t)bt->height - 1));
    }
    const int32_t cx = clamp_i(x >> sh, (int32_t)bt->width - 2);
    const int32_t cy = clamp_i(y >> sh, (int32_t)bt->height - 2);
    const float u = (float)(x - cx * f) / (float)f, v = (float)(y - cy * f) / (float)f;
    const float h00 = height_at(bt, cx, cy), h10 = height_at(bt, cx + 1, cy);
    const float h01 = height_at(bt, cx, cy + 1), h11 = height_at(bt, cx + 1, cy + 1);
    return h00 + (h10 - h00) * u + (h01 - h00) * v + ((h00 + h11) - (h10 + h01)) * u * v;
}

/* Level 0: |D| per cell; level m + 1: max over 2 x 2 blocks (clamped). */
static float *twist_at(ft_bintree *bt, uint32_t m, uint32_t x, uint32_t y)
{
    return &bt->twist_atlas[(size_t)(bt->twist.oy[m] + y) * bt->twist.atlas_w + bt->twist.ox[m] + x];
}

static void build_twist(ft_bintree *bt)
{
    const ft_bt_twist_layout *l = &bt->twist;
    memset(bt->twist_atlas, 0, (size_t)l->atlas_w * l->atlas_h * sizeof(float));
    for (uint32_t y = 0; y < l->h[0]; ++y) {
        for (uint32_t x = 0; x < l->w[0]; ++x) {
            const double d = (double)height_at(bt, (int32_t)x, (int32_t)y) +
                             height_at(bt, (int32_t)x + 1, (int32_t)y + 1) -
                             height_at(bt, (int32_t)x + 1, (int32_t)y) -
                             height_at(bt, (int32_t)x, (int32_t)y + 1);
            float fd = (float)fabs(d);
            if ((double)fd < fabs(d)) {
                fd = nextafterf(fd, FLT_MAX);
            }
            *twist_at(bt, 0u, x, y) = fd;
        }
    }
    for (uint32_t m = 1; m < l->levels; ++m) {
        for (uint32_t y = 0; y < l->h[m]; ++y) {
            for (uint32_t x = 0; x < l->w[m]; ++x) {
                float v = 0.0f;
                for (uint32_t j = 2u * y; j <= 2u * y + 1u && j < l->h[m - 1u]; ++j) {
                    for (uint32_t i = 2u * x; i <= 2u * x + 1u && i < l->w[m - 1u]; ++i) {
                        const float d = *twist_at(bt, m - 1u, i, j);
                        v = (d > v) ? d : v;
                    }
                }
                *twist_at(bt, m, x, y) = v;
            }
        }
    }
}

/* Height range of every aligned 2^(k+2)-cell block (its cells' corners). */
static void build_zblocks(ft_bintree *bt)
{
    const uint32_t sh = bt->zblock_shift;
    for (uint32_t by = 0; by < bt->zblock_h; ++by) {
        for (uint32_t bx = 0; bx < bt->zblock_w; ++bx) {
            float z0 = FLT_MAX, z1 = -FLT_MAX;
            const uint32_t x1 = ((bx + 1u) << sh) < bt->width ? ((bx + 1u) << sh) : bt->width - 1u;
            const uint32_t y1 = ((by + 1u) << sh) < bt->height ? ((by + 1u) << sh) : bt->height - 1u;
            for (uint32_t y = by << sh; y <= y1; ++y) {
                for (uint32_t x = bx << sh; x <= x1; ++x) {
                    const float h = bt->heights_m[(size_t)y * bt->width + x];
                    z0 = (h < z0) ? h : z0;
                    z1 = (h > z1) ? h : z1;
                }
            }
            float *o = &bt->zblock[4u * ((size_t)by * bt->zblock_w + bx)];
            o[0] = z0;
            o[1] = z1;
            o[2] = 0.0f;
            o[3] = 0.0f;
        }
    }
}

ft_status ft_bintree_init(ft_bintree *bt, const ft_terrain *t, uint32_t k, uint32_t sub,
                          double morph_width, uint32_t tiles_max, ft_arena *a, ft_error *err)
{
    memset(bt, 0, sizeof *bt);
    if (t->heights_m == NULL || t->width < FT_GRID_SIDE_MIN || t->height < FT_GRID_SIDE_MIN) {
        return ft_fail(err, FT_ERR_ARG, "bintree: terrain has no heights");
    }
    if (k < FT_BT_TEMPLATE_K_MIN || k > FT_BT_TEMPLATE_K_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.template_k = %u outside %u..%u", k,
                       FT_BT_TEMPLATE_K_MIN, FT_BT_TEMPLATE_K_MAX);
    }
    if (tiles_max < FT_BT_TILES_MIN || tiles_max > FT_BT_TILES_MAX_LIMIT) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.tiles_max = %u outside %u..%u", tiles_max,
                       FT_BT_TILES_MIN, FT_BT_TILES_MAX_LIMIT);
    }
    bt->n = ft_bt_domain_n(t->width, t->height);
    if (bt->n > FT_BT_N_MAX) {
        return ft_fail(err, FT_ERR_ARG, "bintree: grid %ux%u larger than 2^%u + 1", t->width,
                       t->height, FT_BT_N_MAX);
    }
    if (sub > FT_BT_SUB_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.subsample_levels = %u outside 0..%u", sub,
                       FT_BT_SUB_MAX);
    }
    if (!(morph_width >= FT_BT_MORPH_WIDTH_MIN && morph_width <= FT_BT_MORPH_WIDTH_MAX)) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.morph_width = %g outside %g..%g", morph_width,
                       FT_BT_MORPH_WIDTH_MIN, FT_BT_MORPH_WIDTH_MAX);
    }
    if (sub > 0u && t->pyr.minmax_levels == 0u) {
        return ft_fail(err, FT_ERR_ARG, "bintree: sub-sample levels need the terrain's pyramids");
    }
    if (k > bt->n) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "bintree.template_k = %u is too large for a %ux%u grid (at most %u: "
                       "one tile template would cover more than the padded %u-cell domain)",
                       k, t->width, t->height, bt->n, 1u << bt->n);
    }
    bt->k = k;
    bt->side_cells = 1u << bt->n;
    bt->step = 1u << k;
    bt->lattice_side = lattice_side(bt->n, k);
    bt->sub = sub;
    bt->fine_side = bt->side_cells << sub;
    bt->sub_level = 2u * (bt->n - k);
    bt->leaf_level = 2u * (bt->n + sub - k);
    bt->terrain = t;
    bt->width = t->width;
    bt->height = t->height;
    bt->heights_m = t->heights_m;
    bt->domain_z[0] = t->min_height_m;
    bt->domain_z[1] = t->max_height_m;
    bt->tiles_max = tiles_max;
    bt->morph_width = morph_width;
    bt->fine_m = fmin(t->cell_x_m, t->cell_y_m) / (double)(1u << sub);

    bt->leaf_side = bt->side_cells >> k;
    const size_t m2 = (size_t)bt->lattice_side * bt->lattice_side;
    const size_t leaves = (size_t)bt->leaf_side * bt->leaf_side;
    int16_t *tmpl = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, m2 * sizeof(float), (void **)&bt->err_m, err);
    if (st == FT_OK) {
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, m2 * 4u * sizeof(float), (void **)&bt->dia, err);
    }
    if (st == FT_OK && sub == 0u) {
        st = ft_arena_take(a, FT_POOL_METHOD, leaves * sizeof(float), (void **)&bt->leaf_err_m,
                           err);
        if (st == FT_OK) {
            st = ft_arena_take(a, FT_POOL_METHOD, leaves * 2u * sizeof(float),
                               (void **)&bt->leaf_z, err);
        }
    }
    if (st == FT_OK && sub > 0u) {
        ft_bt_twist_layout_for(t->width, t->height, k, &bt->twist);
        st = ft_arena_take(a, FT_POOL_METHOD,
                           (size_t)bt->twist.atlas_w * bt->twist.atlas_h * sizeof(float),
                           (void **)&bt->twist_atlas, err);
        bt->zblock_shift = k + 2u;
        ft_bt_zblock_size(t->width, t->height, k, &bt->zblock_w, &bt->zblock_h);
        if (st == FT_OK) {
            st = ft_arena_take(a, FT_POOL_METHOD,
                               (size_t)bt->zblock_w * bt->zblock_h * 4u * sizeof(float),
                               (void **)&bt->zblock, err);
        }
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)tiles_max * sizeof(ft_bt_tile),
                           (void **)&bt->tiles, err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)ft_bt_template_scratch(k) * sizeof(int16_t),
                           (void **)&tmpl, err);
    }
    if (st != FT_OK) {
        return st;
    }
    ft_bt_template_corners(k, tmpl);
    for (size_t i = 0; i < m2; ++i) {
        bt->dia[4u * i + 1u] = FLT_MAX; /* empty height range */
        bt->dia[4u * i + 2u] = -FLT_MAX;
    }
    build_ctx bc = {bt, tmpl, ft_bt_template_triangles(k)};
    if (sub > 0u) {
        build_twist(bt);
        build_zblocks(bt);
    }
    for (uint32_t level = 0; level < bt->sub_level; ++level) {
        for_each_diamond(&bc, level, own_error);
    }
    if (sub == 0u) {
        for_each_diamond(&bc, bt->leaf_level, leaf_error);
    }
    for (uint32_t level = bt->sub_level; level-- > 0u;) {
        for_each_diamond(&bc, level, saturate);
    }
    for (size_t i = 0; i < m2; ++i) {
        bt->dia[4u * i] = bt->err_m[i];
        bt->dia[4u * i + 3u] = 0.0f;
    }
    if (bt->flipped_triangles != 0u) {
        return ft_fail(err, FT_ERR_ARG,
                       "bintree: %u template triangles flip under the padding clamp (grid %ux%u)",
                       bt->flipped_triangles, t->width, t->height);
    }
    const int32_t mid = (int32_t)bt->side_cells / 2;
    if (bt->sub_level > 0u) {
        bt->max_err_m = bt->err_m[lat_index(bt, mid, mid)];
    } else if (sub == 0u) {
        bt->max_err_m = bt->leaf_err_m[leaf_index(bt, mid, mid)];
    } else {
        float b[FT_BT_BOX_FLOATS];
        const int32_t cf[2] = {mid << sub, mid << sub};
        bt->max_err_m = ft_bt_sub_error(bt, 0u, cf, b);
    }
    return FT_OK;
}

/* ---- view ------------------------------------------------------------------------ */

void ft_bt_view_from_camera(const ft_camera *cam, const ft_terrain *t, int cull, int morph,
                            ft_bt_view *v)
{
    memset(v, 0, sizeof *v);
    const double origin_m[2] = {t->origin_world_x_m, t->origin_world_y_m};
    ft_view_bound_from_camera(cam, origin_m, t->curv_drop_per_m2, &v->b);
    v->cell_m[0] = t->cell_x_m;
    v->cell_m[1] = t->cell_y_m;
    v->cull = cull;
    v->morph = morph;
}

/* ---- selection (per frame) ------------------------------------------------------------ */

typedef struct bt_node {
    int32_t apex[2], left[2], right[2];
    uint32_t level;
} bt_node;

/* World-metre box (relative to sample (0,0)) of grid box b, as drawn (its
 * z range lowered by the curvature drop: ft_view_bound_drawn_box). */
static void box_to_m(const ft_bt_view *v, const float *b, double lo[3], double hi[3])
{
    lo[0] = (double)b[0] * v->cell_m[0];
    hi[0] = (double)b[1] * v->cell_m[0];
    lo[1] = (double)b[2] * v->cell_m[1];
    hi[1] = (double)b[3] * v->cell_m[1];
    lo[2] = b[4];
    hi[2] = b[5];
    ft_view_bound_drawn_box(&v->b, lo, hi);
}

/* Screen-space size in pixels of a diamond error err_m over grid box b
 * (ft_view_bound_error_px: K (err + chord) G / distance to the drawn box). */
static double box_error_px(const ft_bt_view *v, double err_m, const float *b)
{
    double lo[3], hi[3];
    box_to_m(v, b, lo, hi);
    return ft_view_bound_error_px(&v->b, err_m, lo, hi);
}

/* Q of an error err_m over grid box b at target tau (see bintree.h). */
static double box_q_m(const ft_bt_view *v, double err_m, const float *b, double tau_px)
{
    if (!(tau_px >= 0.0) || !isfinite(tau_px)) {
        return -INFINITY;
    }
    double lo[3], hi[3];
    box_to_m(v, b, lo, hi);
    ft_view_box_terms t;
    ft_view_bound_terms(&v->b, err_m, lo, hi, &t);
    if (!(t.err_m > 0.0)) {
        return -INFINITY;
    }
    if (!(t.dist_m > 0.0) || tau_px == 0.0) {
        return INFINITY; /* the eye in its box, or a target of 0: split */
    }
    return v->b.k_px * t.err_m * t.gain / tau_px - t.dist_m;
}

/* 1 if the box is wholly outside one frustum side plane or behind the eye. */
static int box_outside(const ft_bt_view *v, const double lo[3], const double hi[3])
{
    return ft_view_bound_outside(&v->b, lo, hi);
}

static int32_t min3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = (a < b) ? a : b;
    return (m < c) ? m : c;
}

static int32_t max3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = (a > b) ? a : b;
    return (m > c) ? m : c;
}

double ft_bt_diamond_error(const ft_bintree *bt, uint32_t level, const int32_t c[2],
                           float box[FT_BT_BOX_FLOATS])
{
    if (level < bt->sub_level) {
        const size_t li = lat_index(bt, c[0] >> bt->sub, c[1] >> bt->sub);
        closure_xy(bt, level, c, box);
        box[4] = bt->dia[4u * li + 1u];
        box[5] = bt->dia[4u * li + 2u];
        return (double)bt->err_m[li];
    }
    if (bt->sub == 0u) {
        leaf_box(bt, c[0], c[1], box);
        return (double)bt->leaf_err_m[leaf_index(bt, c[0], c[1])];
    }
    return ft_bt_sub_error(bt, level, c, box);
}

uint32_t ft_bt_level_of(const ft_bintree *bt, int32_t sd, int odd)
{
    uint32_t l = 0;
    while (l < FT_BT_LEVELS_MAX && (int32_t)(bt->fine_side >> (l / 2u)) > sd) {
        l += 2u;
    }
    return l + (odd ? 1u : 0u);
}

double ft_bt_diamond_q(const ft_bintree *bt, const ft_bt_view *v, uint32_t level,
                       const int32_t c[2], double tau_px, double *w_m)
{
    float box[FT_BT_BOX_FLOATS];
    const double e = ft_bt_diamond_error(bt, level, c, box);
    *w_m = morph_width_m(bt, level);
    if (!(box[4] <= box[5])) {
        return -INFINITY;
    }
    return box_q_m(v, e, box, tau_px);
}

double ft_bt_morph_weight(double q_m, double w_m)
{
    const double w = 2.0 * q_m / w_m + 1.0;
    return (w > 1.0) ? 1.0 : ((w > 0.0) ? w : 0.0);
}

/* One selection at target tau_px. Returns 0 when the tiles
 * would exceed tiles_max (bt->tiles then holds a partial list). Tile
 * coordinates are fine units (2^-S cells). */
static int select_once(ft_bintree *bt, const ft_bt_view *v, double tau_px, ft_bt_select_stats *st)
{
    bt_node stack[FT_BT_STACK_MAX];
    uint32_t sp = 0;
    const int32_t n = (int32_t)bt->fine_side;
    const int32_t wx = ((int32_t)bt->width - 1) << bt->sub;
    const int32_t hy = ((int32_t)bt->height - 1) << bt->sub;
    const float inv_f = 1.0f / (float)(1u << bt->sub); /* exact: a power of two */
    st->tiles = 0;
    st->tiles_coarse = 0;
    uint32_t tiles_fine = 0; /* emitted from the end of the list, moved after the coarse */
    st->leaf_px_max = 0.0;
    st->nodes_visited = 0;
    st->culled = 0;
    st->level_min = UINT32_MAX;
    st->level_max = 0;
    /* roots: T1 then T0 on the stack */
    stack[sp++] = (bt_node){{0, n}, {0, 0}, {n, n}, 0u};
    stack[sp++] = (bt_node){{n, 0}, {n, n}, {0, 0}, 0u};
    /* Bounded: every pop either emits, drops or replaces a node by its two
     * children one level down; depth <= leaf_level so sp <= leaf_level + 2,
     * and the number of pops is bounded by the tree size. */
    while (sp > 0u) {
        bt_node t = stack[--sp];
        st->nodes_visited += 1u;
        int32_t gx0 = min3(t.apex[0], t.left[0], t.right[0]);
        int32_t gy0 = min3(t.apex[1], t.left[1], t.right[1]);
        if (gx0 >= wx || gy0 >= hy) {
            continue; /* wholly in the padding: zero area after the clamp */
        }
        int32_t c[2] = {(t.left[0] + t.right[0]) / 2, (t.left[1] + t.right[1]) / 2};
        const int leaf = (t.level >= bt->leaf_level);
        float dbox[FT_BT_BOX_FLOATS];
        const double e = ft_bt_diamond_error(bt, t.level, c, dbox);
        if (dbox[4] > dbox[5]) {
            continue; /* no sample under it or its descendants: zero area after the clamp */
        }
        if (v->cull) {
            float tb[6];
            tb[0] = (float)gx0 * inv_f;
            tb[1] = (float)clamp_i(max3(t.apex[0], t.left[0], t.right[0]), wx) * inv_f;
            tb[2] = (float)gy0 * inv_f;
            tb[3] = (float)clamp_i(max3(t.apex[1], t.left[1], t.right[1]), hy) * inv_f;
            tb[4] = dbox[4];
            tb[5] = dbox[5];
            double lo[3], hi[3];
            box_to_m(v, tb, lo, hi);
            if (box_outside(v, lo, hi)) {
                st->culled += 1u;
                continue;
            }
        }
        if (!leaf) {
            const double q = box_q_m(v, e, dbox, tau_px);
            const double w_m = morph_width_m(bt, t.level);
            if (v->morph ? (q > -w_m) : (q > 0.0)) {
                stack[sp++] = (bt_node){{c[0], c[1]},
                                        {t.right[0], t.right[1]},
                                        {t.apex[0], t.apex[1]},
                                        t.level + 1u};
                stack[sp++] = (bt_node){{c[0], c[1]},
                                        {t.apex[0], t.apex[1]},
                                        {t.left[0], t.left[1]},
                                        t.level + 1u};
                continue;
            }
        } else {
            /* nothing refines a leaf: its own error is what the frame achieves there */
            double px;
            if (bt->sub > 0u) {
                const int32_t xs[3] = {t.apex[0], t.left[0], t.right[0]};
                const int32_t ys[3] = {t.apex[1], t.left[1], t.right[1]};
                float lb[FT_BT_BOX_FLOATS];
                const double le = leaf_tile_error(bt, xs, ys, lb);
                px = box_error_px(v, le, lb);
            } else {
                px = box_error_px(v, e, dbox);
            }
            st->leaf_px_max = (px > st->leaf_px_max) ? px : st->leaf_px_max;
        }
        if (st->tiles >= bt->tiles_max) {
            return 0;
        }
        const int fine = (bt->sub > 0u && t.level >= bt->sub_level);
        ft_bt_tile *out = fine ? &bt->tiles[bt->tiles_max - 1u - tiles_fine++]
                               : &bt->tiles[st->tiles_coarse++];
        st->tiles += 1u;
        memcpy(out->apex, t.apex, sizeof out->apex);
        memcpy(out->left, t.left, sizeof out->left);
        memcpy(out->right, t.right, sizeof out->right);
        out->level = t.level;
        st->level_min = (t.level < st->level_min) ? t.level : st->level_min;
        st->level_max = (t.level > st->level_max) ? t.level : st->level_max;
    }
    /* the fine tiles (in reverse order at the end) follow the coarse ones */
    ft_bt_tile *fine0 = &bt->tiles[bt->tiles_max - tiles_fine];
    for (uint32_t a = 0, b = tiles_fine; a + 1u < b; ++a, --b) {
        const ft_bt_tile tmp = fine0[a];
        fine0[a] = fine0[b - 1u];
        fine0[b - 1u] = tmp;
    }
    memmove(&bt->tiles[st->tiles_coarse], fine0, (size_t)tiles_fine * sizeof(ft_bt_tile));
    return 1;
}

/* 2x the signed area of (a, b, p), p in fine units (exact for the
 * integer corners; p's rounding moves it by far less than a millimetre). */
static double orient(const int32_t a[2], const int32_t b[2], const double p[2])
{
    return ((double)b[0] - a[0]) * (p[1] - a[1]) - ((double)b[1] - a[1]) * (p[0] - a[0]);
}

static int in_triangle(const bt_node *t, const double p[2])
{
    const double a = orient(t->apex, t->left, p), b = orient(t->left, t->right, p),
                 c = orient(t->right, t->apex, p);
    return (a >= 0.0 && b >= 0.0 && c >= 0.0) || (a <= 0.0 && b <= 0.0 && c <= 0.0);
}

/* Whether back faces are hidden: the eye over the real grid and above the
 * drawn surface under it. A height field seen from above it is met first
 * on its upper side along every ray: a ray that reaches a back face comes
 * from below the surface there, so it crossed the surface downwards
 * nearer the eye, at a point of a tile frustum culling keeps. Culling
 * never changes which diamonds split, so the surface under the eye is
 * the unculled selection's: walk from the root down the diamonds holding
 * the eye's xy, splitting as the selection does at tau; the first unsplit
 * one (or a leaf) is drawn there, and its box top bounds every height it
 * draws (sample heights, morph midpoints, sub-sample bilinear heights;
 * the curvature only lowers them). */
static int back_faces_hidden(const ft_bintree *bt, const ft_bt_view *v, double tau_px)
{
    const double f = (double)(1u << bt->sub);
    const double ex = v->b.eye_m[0] / v->cell_m[0], ey = v->b.eye_m[1] / v->cell_m[1];
    if (!(ex >= 0.0 && ey >= 0.0 && ex <= (double)bt->width - 1.0 &&
          ey <= (double)bt->height - 1.0)) {
        return 0; /* off the grid: a ray may enter under the surface through its edge */
    }
    const double p[2] = {ex * f, ey * f};
    const int32_t n = (int32_t)bt->fine_side;
    bt_node t = {{0, n}, {0, 0}, {n, n}, 0u};
    const bt_node t0 = {{n, 0}, {n, n}, {0, 0}, 0u};
    if (!in_triangle(&t, p)) {
        t = t0;
    }
    /* bounded: one level a step, at most leaf_level + 1 steps */
    for (uint32_t step = 0; step <= bt->leaf_level; ++step) {
        const int32_t c[2] = {(t.left[0] + t.right[0]) / 2, (t.left[1] + t.right[1]) / 2};
        float dbox[FT_BT_BOX_FLOATS];
        const double e = ft_bt_diamond_error(bt, t.level, c, dbox);
        int split = 0;
        if (t.level < bt->leaf_level) {
            const double q = box_q_m(v, e, dbox, tau_px);
            split = v->morph ? (q > -morph_width_m(bt, t.level)) : (q > 0.0);
        }
        if (!split) {
            /* a centimetre over the float box top */
            return v->b.eye_m[2] > (double)dbox[5] + 0.01;
        }
        const bt_node a = {{c[0], c[1]}, {t.right[0], t.right[1]}, {t.apex[0], t.apex[1]},
                           t.level + 1u};
        const bt_node b = {{c[0], c[1]}, {t.apex[0], t.apex[1]}, {t.left[0], t.left[1]},
                           t.level + 1u};
        t = in_triangle(&a, p) ? a : b;
    }
    return 0;
}

void ft_bintree_select(ft_bintree *bt, const ft_bt_view *v, double tau_px,
                       ft_bt_select_stats *st)
{
    double tau = (tau_px > 0.0) ? tau_px : 0.0;
    memset(st, 0, sizeof *st);
    st->tau_target_px = tau;
    for (uint32_t i = 0; i < FT_BT_COARSEN_STEPS_MAX; ++i) {
        st->attempts = i + 1u;
        if (select_once(bt, v, tau, st)) {
            st->budget_hit = (i > 0u);
            st->tau_used_px = tau;
            st->tau_achieved_px = (st->leaf_px_max > tau) ? st->leaf_px_max : tau;
            st->back_faces_hidden = back_faces_hidden(bt, v, tau);
            return;
        }
        tau = (tau > 0.0) ? tau * FT_BT_COARSEN_FACTOR : 1e-3;
    }
    /* Last resort (tiles_max >= 2): the two roots, bound = their projected error. */
    st->attempts += 1u;
    const int roots_fit = select_once(bt, v, INFINITY, st);
    FT_INVARIANT(roots_fit, "bintree: the two root tiles over bintree.tiles_max");
    st->budget_hit = 1;
    const int32_t root_c[2] = {(int32_t)bt->fine_side / 2, (int32_t)bt->fine_side / 2};
    float b[FT_BT_BOX_FLOATS];
    const double e = ft_bt_diamond_error(bt, 0u, root_c, b);
    st->tau_used_px = box_error_px(v, e, b);
    st->tau_achieved_px = st->tau_used_px;
    st->back_faces_hidden = back_faces_hidden(bt, v, INFINITY);
}

/* ---- geomorph rule (mirrors shaders/bintree.vert.glsl) --------------------------------- */

int ft_bt_vertex_morph(const ft_bintree *bt, int32_t x, int32_t y, int32_t e0[2], int32_t e1[2],
                       int32_t c[2], uint32_t *level)
{
    const int32_t n = (int32_t)bt->fine_side;
    if ((x | y) == 0) {
        return 0;
    }
    int32_t s = (x | y) & -(x | y); /* lowest set bit */
    int odd_x = ((x / s) & 1) != 0, odd_y = ((y / s) & 1) != 0;
    int32_t sd = 2 * s * (int32_t)bt->step; /* square side of the insertion diamond */
    if (sd > n) {
        return 0; /* present in the coarsest tiles: never morphs */
    }
    if (odd_x && odd_y) {
        int32_t qx = (x - s) / (2 * s), qy = (y - s) / (2 * s);
        int slash = ((qx + qy) & 1) == 0;
        e0[0] = x - s; e0[1] = slash ? y - s : y + s;
        e1[0] = x + s; e1[1] = slash ? y + s : y - s;
        c[0] = (x / sd) * sd + sd / 2;
        c[1] = (y / sd) * sd + sd / 2;
    } else {
        if (odd_x) {
            e0[0] = x - s; e0[1] = y; e1[0] = x + s; e1[1] = y;
        } else {
            e0[0] = x; e0[1] = y - s; e1[0] = x; e1[1] = y + s;
        }
        int32_t bx = (x / sd) * sd, by = (y / sd) * sd;
        int32_t rx = x - bx, ry = y - by;
        if (ry <= rx && ry <= sd - rx) {
            c[0] = bx + sd / 2; c[1] = by;
        } else if (ry >= rx && ry >= sd - rx) {
            c[0] = bx + sd / 2; c[1] = by + sd;
        } else if (rx <= ry && rx <= sd - ry) {
            c[0] = bx; c[1] = by + sd / 2;
        } else {
            c[0] = bx + sd; c[1] = by + sd / 2;
        }
    }
    /* Vertices the padding clamp moves do not morph (no coarse edge to slide on). */
    const int32_t wx = ((int32_t)bt->width - 1) << bt->sub;
    const int32_t hy = ((int32_t)bt->height - 1) << bt->sub;
    if (x > wx || y > hy || e0[0] > wx || e0[1] > hy || e1[0] > wx || e1[1] > hy) {
        return 0;
    }
    *level = ft_bt_level_of(bt, sd, !(odd_x && odd_y));
    return 1;
}

/* ---- the one-fetch vertex table --------------------------------------------- */

float ft_bt_pack_normal(const double n[3])
{
    /* hemi-octahedral: project on |x| + |y| + z = 1, turn the diamond 45 deg
     * into the square [-1, 1]^2 (even precision over the hemisphere) */
    const double l1 = fabs(n[0]) + fabs(n[1]) + n[2];
    const double px = n[0] / l1, py = n[1] / l1;
    const double uv[2] = {px + py, px - py};
    uint32_t q[2];
    for (int i = 0; i < 2; ++i) {
        double v = floor((uv[i] + 1.0) * 0.5 * FT_BT_NORMAL_Q + 0.5);
        v = (v < 0.0) ? 0.0 : ((v > FT_BT_NORMAL_Q) ? FT_BT_NORMAL_Q : v);
        q[i] = (uint32_t)v;
    }
    return (float)(q[0] * 4096u + q[1]);
}

void ft_bt_unpack_normal(float packed, double n[3])
{
    /* the shader's arithmetic: p / 4096 is exact, floor and subtraction too */
    const double p = (double)packed;
    const double qx = floor(p / 4096.0), qy = p - qx * 4096.0;
    const double u = qx / FT_BT_NORMAL_Q * 2.0 - 1.0, v = qy / FT_BT_NORMAL_Q * 2.0 - 1.0;
    n[0] = 0.5 * (u + v);
    n[1] = 0.5 * (u - v);
    n[2] = 1.0 - fabs(n[0]) - fabs(n[1]);
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int i = 0; i < 3; ++i) {
        n[i] /= len;
    }
}

static float sample_at(const ft_bintree *bt, uint32_t x, uint32_t y)
{
    return bt->heights_m[(size_t)y * bt->width + x];
}

void ft_bt_sample_texel(const ft_bintree *bt, uint32_t gx, uint32_t gy, float out[4])
{
    const float h = sample_at(bt, gx, gy);
    /* normal: central differences, one-sided at the grid edge */
    const uint32_t x0 = (gx > 0u) ? gx - 1u : 0u, x1 = (gx + 1u < bt->width) ? gx + 1u : gx;
    const uint32_t y0 = (gy > 0u) ? gy - 1u : 0u, y1 = (gy + 1u < bt->height) ? gy + 1u : gy;
    const double dhx = ((double)sample_at(bt, x1, gy) - (double)sample_at(bt, x0, gy)) /
                       ((double)(x1 - x0) * bt->terrain->cell_x_m);
    const double dhy = ((double)sample_at(bt, gx, y1) - (double)sample_at(bt, gx, y0)) /
                       ((double)(y1 - y0) * bt->terrain->cell_y_m);
    const double len = sqrt(dhx * dhx + dhy * dhy + 1.0);
    out[0] = h;
    out[1] = h;
    out[2] = -1.0f;
    const double n[3] = {-dhx / len, -dhy / len, 1.0 / len};
    out[3] = ft_bt_pack_normal(n);
    int32_t e0[2], e1[2], c[2];
    uint32_t level;
    const int32_t x = (int32_t)(gx << bt->sub), y = (int32_t)(gy << bt->sub);
    if (!ft_bt_vertex_morph(bt, x, y, e0, e1, c, &level)) {
        return;
    }
    /* a sample's inserting diamond lies on the table lattice (its square side
     * is at least 2^(k+S+1) fine units) */
    const uint32_t sh = bt->k + bt->sub;
    const size_t li = (size_t)((uint32_t)c[1] >> sh) * bt->lattice_side + ((uint32_t)c[0] >> sh);
    if (li >= (size_t)bt->lattice_side * bt->lattice_side) {
        return;
    }
    const float h0 = sample_at(bt, (uint32_t)e0[0] >> bt->sub, (uint32_t)e0[1] >> bt->sub);
    const float h1 = sample_at(bt, (uint32_t)e1[0] >> bt->sub, (uint32_t)e1[1] >> bt->sub);
    const float sum = h0 + h1;
    out[1] = 0.5f * sum;
    out[2] = bt->err_m[li];
}
