/* pgrid.c - the error-bounded projective grid's CPU arithmetic (pgrid.h). */
#include "lod/pgrid.h"

#include <math.h>
#include <string.h>

#include "core/view_scale.h"
#include "lod/worst_pieces.h"

int ft_pgrid_lower_envelope_needed(const ft_terrain *t, const ft_pgm_sampling *s)
{
    /* every sample, so every mesh vertex (an average or bilinear value of
     * samples) and the bilinear truth, lies at or under the terrain's highest
     * sample, and the curvature drop only lowers them */
    return !(ft_terrain_contains(t, s->eye_m[0], s->eye_m[1]) &&
             s->eye_m[2] > (double)t->max_height_m);
}

double ft_pgrid_delta(double hmin_m, double hmax_m, double h_m)
{
    const double a = hmax_m - h_m, b = h_m - hmin_m;
    return (a > b) ? a : b;
}

double ft_pgrid_rho(double k_px, double delta_m, double dist_m)
{
    return k_px * delta_m / ((dist_m > 1e-6) ? dist_m : 1e-6);
}

double ft_pgrid_norm_error(double rho_px, double gamma_px)
{
    return (rho_px > gamma_px) ? 1.0 - gamma_px / rho_px : 0.0;
}

uint32_t ft_pgrid_code(double rho_px)
{
    if (!(rho_px > 0.0)) {
        return 1u;
    }
    const double c =
        ceil((log2(rho_px) - FT_PGRID_CODE_LOG2_MIN) * 255.0 / FT_PGRID_CODE_LOG2_SPAN);
    if (!(c >= 1.0)) {
        return 1u;
    }
    return (c >= 255.0) ? 255u : (uint32_t)c;
}

double ft_pgrid_code_rho_hi(uint32_t code)
{
    if (code >= 255u) {
        return INFINITY; /* saturated: anything above 2^8 px */
    }
    return exp2((double)code * FT_PGRID_CODE_LOG2_SPAN / 255.0 + FT_PGRID_CODE_LOG2_MIN);
}

double ft_pgrid_col_u(const float t_knots[], double t)
{
    uint32_t k = 0u;
    for (uint32_t n = 1u; n < FT_PGRID_COL_BANDS; ++n) {
        if (t >= (double)t_knots[n]) k = n;
    }
    const double t0 = t_knots[k], t1 = t_knots[k + 1u];
    return ((double)k + (t - t0) / (t1 - t0)) / (double)FT_PGRID_COL_BANDS;
}

#define COL_STEPS 13 /* s = 2^(j / 4 - 1), j = 0..12: 1/2 .. 4 */

void ft_pgrid_col_warp(const uint32_t (*hist)[256], const float prev[], double gamma_px,
                       float next[])
{
    const uint32_t nb = FT_PGRID_COL_BANDS;
    const double cg = (double)ft_pgrid_code(gamma_px);
    /* over[b][j]: band b's pixels over code(gamma) at share s_j */
    double over[FT_PGRID_COL_BANDS][COL_STEPS];
    double share[COL_STEPS];
    for (int j = 0; j < COL_STEPS; ++j) share[j] = exp2((double)j / 4.0 - 1.0);
    double s_prev[FT_PGRID_COL_BANDS];
    double any = 0.0;
    for (uint32_t b = 0; b < nb; ++b) {
        s_prev[b] = (double)nb * ((double)prev[b + 1u] - (double)prev[b]);
        uint32_t above[257];
        above[256] = 0u;
        for (int c = 255; c >= 0; --c) above[c] = above[c + 1] + hist[b][c];
        for (int j = 0; j < COL_STEPS; ++j) {
            const double s = share[j];
            /* a pixel of code c drawn at s_prev is over at s iff
             * c >= code(gamma) + log2(s / s_prev) * 255 / 16 */
            double c = ceil(cg + log2(s / s_prev[b]) * 255.0 / FT_PGRID_CODE_LOG2_SPAN);
            c = c < 1.0 ? 1.0 : (c > 256.0 ? 256.0 : c);
            over[b][j] = (double)above[(int)c];
        }
        any += over[b][4]; /* s = 1 */
    }
    double s_new[FT_PGRID_COL_BANDS];
    if (any <= 0.0) {
        for (uint32_t b = 0; b < nb; ++b) s_new[b] = 1.0;
    } else {
        /* each band's best share at a price lambda a unit of share; the
         * price that spends the columns there are (sum s_b = 16), bisected
         * (the sum falls as the price rises) */
        double lo = 0.0, hi = 1e12;
        for (int it = 0; it < 80; ++it) {
            const double lam = 0.5 * (lo + hi);
            double sum = 0.0;
            for (uint32_t b = 0; b < nb; ++b) {
                int best = 0;
                for (int j = 1; j < COL_STEPS; ++j) {
                    if (over[b][j] + lam * share[j] < over[b][best] + lam * share[best]) best = j;
                }
                s_new[b] = share[best];
                sum += s_new[b];
            }
            if (sum > (double)nb) lo = lam; else hi = lam;
        }
    }
    double sum = 0.0;
    for (uint32_t b = 0; b < nb; ++b) {
        s_new[b] = sqrt(s_new[b] * s_prev[b]);
        sum += s_new[b];
    }
    next[0] = 0.0f;
    double acc = 0.0;
    for (uint32_t b = 0; b < nb; ++b) {
        acc += s_new[b] / sum;
        next[b + 1u] = (float)acc;
    }
    next[nb] = 1.0f;
}

double ft_pgrid_row_s(double depression_rad, double y)
{
    const double beta = depression_rad - atan(y);
    /* cot(beta) = cos / sin; beta in (0, pi) for every ray that meets the plane */
    return asinh(cos(beta) / sin(beta));
}

double ft_pgrid_row_y(int distribution, double depression_rad, double y0, double y1,
                      uint32_t rows, double j)
{
    const double t = j / (double)(rows - 1u);
    if (distribution != FT_PGRID_DIST_VIEW) {
        return y0 + (y1 - y0) * t;
    }
    const double s0 = ft_pgrid_row_s(depression_rad, y0);
    const double s1 = ft_pgrid_row_s(depression_rad, y1);
    const double s = s0 + (s1 - s0) * t;
    const double beta = atan2(1.0, sinh(s));
    return tan(depression_rad - beta);
}

static double clampd(double v, double lo, double hi)
{
    return (v < lo) ? lo : ((v > hi) ? hi : v);
}

void ft_pgrid_region_minmax(const ft_terrain *t, double x0_m, double y0_m, double x1_m,
                            double y1_m, double *hmin_m, double *hmax_m)
{
    const double wx = (double)(t->width - 1u), wy = (double)(t->height - 1u);
    double gx0 = clampd((x0_m - t->origin_world_x_m) / t->cell_x_m, 0.0, wx);
    double gx1 = clampd((x1_m - t->origin_world_x_m) / t->cell_x_m, 0.0, wx);
    double gy0 = clampd((y0_m - t->origin_world_y_m) / t->cell_y_m, 0.0, wy);
    double gy1 = clampd((y1_m - t->origin_world_y_m) / t->cell_y_m, 0.0, wy);
    if (gx1 < gx0) { double s = gx0; gx0 = gx1; gx1 = s; }
    if (gy1 < gy0) { double s = gy0; gy0 = gy1; gy1 = s; }
    const double side = fmax(fmax(gx1 - gx0, gy1 - gy0), 1.0);
    uint32_t level = (uint32_t)fmax(0.0, ceil(log2(side)));
    const ft_pyramid *p = &t->pyr;
    if (level >= p->minmax_levels) {
        level = p->minmax_levels - 1u;
    }
    const ft_pyramid_level *lv = &p->minmax[level];
    const double scale = exp2((double)level);
    /* texel i covers grid x in [i 2^L, (i + 1) 2^L]; x = 2^L k touches two */
    uint32_t i0 = (uint32_t)fmin(floor(gx0 / scale), (double)(lv->width - 1u));
    uint32_t i1 = (uint32_t)fmin(floor(gx1 / scale), (double)(lv->width - 1u));
    uint32_t j0 = (uint32_t)fmin(floor(gy0 / scale), (double)(lv->height - 1u));
    uint32_t j1 = (uint32_t)fmin(floor(gy1 / scale), (double)(lv->height - 1u));
    if (i0 > 0u && gx0 == (double)i0 * scale) i0 -= 1u;
    if (j0 > 0u && gy0 == (double)j0 * scale) j0 -= 1u;
    if (i1 > i0 + 1u) i1 = i0 + 1u; /* side <= 2^L: never more than 2 texels */
    if (j1 > j0 + 1u) j1 = j0 + 1u;
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t j = j0; j <= j1; ++j) {
        for (uint32_t i = i0; i <= i1; ++i) {
            const size_t k = (size_t)j * lv->width + i;
            lo = fmin(lo, (double)lv->min_m[k]);
            hi = fmax(hi, (double)lv->max_m[k]);
        }
    }
    *hmin_m = lo;
    *hmax_m = hi;
}

uint32_t ft_pgrid_budget_threshold(const uint32_t hist[FT_PGRID_CODES], double gamma_px,
                                   uint64_t max_px, uint64_t *count, int *budget_hit)
{
    const uint32_t c0 = ft_pgrid_code(gamma_px);
    uint64_t above[FT_PGRID_CODES + 1u];
    above[FT_PGRID_CODES] = 0u;
    for (uint32_t c = FT_PGRID_CODES; c-- > 0u;) {
        above[c] = above[c + 1u] + hist[c];
    }
    uint32_t thr = c0;
    while (thr < FT_PGRID_CODES && above[thr] > max_px) {
        ++thr;
    }
    *count = above[thr];
    *budget_hit = (thr > c0);
    return thr;
}

void ft_pgrid_histogram(const uint8_t *rgba, uint32_t w, uint32_t h, uint8_t *work,
                        uint32_t hist[FT_PGRID_CODES])
{
    for (uint32_t c = 0; c < FT_PGRID_CODES; ++c) {
        hist[c] = 0u;
    }
    for (uint32_t y = 0; y < h; ++y) {
        const uint8_t *row = rgba + (size_t)y * w * 4u + 1u;
        uint8_t *out = work + (size_t)y * w;
        for (uint32_t x = 0; x < w; ++x) {
            uint8_t m = row[(size_t)x * 4u];
            if (x > 0u && row[(size_t)(x - 1u) * 4u] > m) m = row[(size_t)(x - 1u) * 4u];
            if (x + 1u < w && row[(size_t)(x + 1u) * 4u] > m) m = row[(size_t)(x + 1u) * 4u];
            out[x] = m;
        }
    }
    for (uint32_t y = 0; y < h; ++y) {
        const uint8_t *a = work + (size_t)(y > 0u ? y - 1u : y) * w;
        const uint8_t *b = work + (size_t)y * w;
        const uint8_t *c = work + (size_t)(y + 1u < h ? y + 1u : y) * w;
        for (uint32_t x = 0; x < w; ++x) {
            uint8_t m = b[x];
            if (a[x] > m) m = a[x];
            if (c[x] > m) m = c[x];
            hist[m] += 1u;
        }
    }
}

/* Atlas of the min/max-shaped levels l0..: level l0 at (0, 0), levels
 * l0 + 1.. stacked in a column right of it; 1 x 1 when there are none. */
static void atlas_layout(const ft_terrain *t, uint32_t l0, uint32_t origin_px[][2],
                         uint32_t *width_px, uint32_t *height_px)
{
    const ft_pyramid *p = &t->pyr;
    *width_px = *height_px = 1u;
    if (p->minmax_levels <= l0) {
        return; /* the lower levels come from the heights: nothing to lay out */
    }
    const uint32_t w0 = p->minmax[l0].width, h0 = p->minmax[l0].height;
    uint32_t col_w = 0u, y = 0u;
    origin_px[l0][0] = 0u;
    origin_px[l0][1] = 0u;
    for (uint32_t l = l0 + 1u; l < p->minmax_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        origin_px[l][0] = w0;
        origin_px[l][1] = y;
        y += p->minmax[l].height;
        col_w = (p->minmax[l].width > col_w) ? p->minmax[l].width : col_w;
    }
    *width_px = w0 + col_w;
    *height_px = (y > h0) ? y : h0;
}

void ft_pgrid_minmax_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *half_w,
                            uint32_t *height_px)
{
    atlas_layout(t, FT_PGRID_ATLAS_L0, origin_px, half_w, height_px);
}

void ft_pgrid_rc_max_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                            uint32_t *height_px)
{
    atlas_layout(t, 1u, origin_px, width_px, height_px);
}

/* ---- 6. the tight bound ---------------------------------------------------- */

void ft_pgrid_residual_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                              uint32_t *height_px)
{
    atlas_layout(t, FT_PGRID_RES_L0, origin_px, width_px, height_px);
}

typedef struct node_box {
    uint32_t x0, x1, y0, y1;
    double m, bx, by; /* plane: centre value, rise across the node in x and y */
} node_box;

static node_box node_of(const ft_terrain *t, uint32_t level, uint32_t i, uint32_t j)
{
    node_box n;
    const uint32_t s = 1u << level;
    n.x0 = i * s;
    n.y0 = j * s;
    n.x1 = (n.x0 + s < t->width - 1u) ? n.x0 + s : t->width - 1u;
    n.y1 = (n.y0 + s < t->height - 1u) ? n.y0 + s : t->height - 1u;
    const float *h = t->heights_m;
    const double h00 = h[(size_t)n.y0 * t->width + n.x0], h10 = h[(size_t)n.y0 * t->width + n.x1];
    const double h01 = h[(size_t)n.y1 * t->width + n.x0], h11 = h[(size_t)n.y1 * t->width + n.x1];
    n.m = 0.25 * (h00 + h10 + h01 + h11);
    n.bx = 0.5 * (h10 + h11 - h00 - h01);
    n.by = 0.5 * (h01 + h11 - h00 - h10);
    return n;
}

static double plane_at(const node_box *n, double gx, double gy)
{
    const double u = (gx - (double)n->x0) / (double)(n->x1 - n->x0) - 0.5;
    const double v = (gy - (double)n->y0) / (double)(n->y1 - n->y0) - 0.5;
    return n->m + n->bx * u + n->by * v;
}

double ft_pgrid_node_plane(const ft_terrain *t, uint32_t level, uint32_t i, uint32_t j,
                           double gx, double gy)
{
    const node_box n = node_of(t, level, i, j);
    return plane_at(&n, gx, gy);
}

double ft_pgrid_node_residual(const ft_terrain *t, uint32_t level, uint32_t i, uint32_t j)
{
    const node_box n = node_of(t, level, i, j);
    double r = 0.0;
    for (uint32_t y = n.y0; y <= n.y1; ++y) {
        const float *row = t->heights_m + (size_t)y * t->width;
        for (uint32_t x = n.x0; x <= n.x1; ++x) {
            const double d = fabs((double)row[x] - plane_at(&n, (double)x, (double)y));
            r = (d > r) ? d : r;
        }
    }
    return r;
}

void ft_pgrid_residual_fill(const ft_terrain *t, float *atlas, uint32_t width_px,
                            uint32_t height_px)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2], w = 1u, h = 1u;
    ft_pgrid_residual_layout(t, origin, &w, &h);
    for (size_t k = 0; k < (size_t)width_px * height_px; ++k) {
        atlas[k] = 0.0f;
    }
    const ft_pyramid *p = &t->pyr;
    for (uint32_t l = FT_PGRID_RES_L0; l < p->minmax_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        const ft_pyramid_level *lv = &p->minmax[l];
        for (uint32_t j = 0; j < lv->height; ++j) {
            float *row = atlas + (size_t)(origin[l][1] + j) * width_px + origin[l][0];
            for (uint32_t i = 0; i < lv->width; ++i) {
                /* float rounds to nearest: one ulp up keeps it a bound */
                const double r = ft_pgrid_node_residual(t, l, i, j);
                row[i] = nextafterf((float)r, INFINITY);
            }
        }
    }
}

/* The quad with its corners clamped into the grid (the shader's rule: the
 * grid's vertices are clamped into it, a rounding must not leave it). */
static ft_pgrid_quad clamped(const ft_terrain *t, const ft_pgrid_quad *q)
{
    ft_pgrid_quad c = *q;
    for (int k = 0; k < 4; ++k) {
        c.g[k][0] = clampd(c.g[k][0], 0.0, (double)(t->width - 1u));
        c.g[k][1] = clampd(c.g[k][1], 0.0, (double)(t->height - 1u));
    }
    return c;
}

/* The grid-coordinate box of a quad's corners. */
static void quad_box(const ft_pgrid_quad *q, double *lo_x, double *hi_x, double *lo_y,
                     double *hi_y)
{
    *lo_x = *hi_x = q->g[0][0];
    *lo_y = *hi_y = q->g[0][1];
    for (int k = 1; k < 4; ++k) {
        *lo_x = fmin(*lo_x, q->g[k][0]);
        *hi_x = fmax(*hi_x, q->g[k][0]);
        *lo_y = fmin(*lo_y, q->g[k][1]);
        *hi_y = fmax(*hi_y, q->g[k][1]);
    }
}

/* |f| at the ends of a quadratic piece f(t) on [ta, tb] with end values fa,
 * fb and curvature gamma (f'' = 2 gamma), and at its stationary point */
static double piece_max(double ta, double tb, double fa, double fb, double gamma)
{
    double m = fmax(fabs(fa), fabs(fb));
    const double w = tb - ta;
    if (w > 0.0 && gamma != 0.0) {
        const double sl = (fb - fa) / w;
        const double ts = 0.5 * (ta + tb) - sl / (2.0 * gamma);
        if (ts > ta && ts < tb) {
            m = fmax(m, fabs(fa + (ts - ta) * sl + gamma * (ts - ta) * (ts - tb)));
        }
    }
    return m;
}

/* Barycentric weights of (x, y) in triangle a b c; 0 if degenerate. */
static int barycentric(const double a[2], const double b[2], const double c[2], double x,
                       double y, double w[3])
{
    const double det = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
    if (fabs(det) < 1e-12) {
        return 0;
    }
    w[0] = ((b[1] - c[1]) * (x - c[0]) + (c[0] - b[0]) * (y - c[1])) / det;
    w[1] = ((c[1] - a[1]) * (x - c[0]) + (a[0] - c[0]) * (y - c[1])) / det;
    w[2] = 1.0 - w[0] - w[1];
    return 1;
}

static double sample_at(const ft_terrain *t, uint32_t x, uint32_t y)
{
    return (double)t->heights_m[(size_t)y * t->width + x];
}

double ft_pgrid_quad_exact(const ft_terrain *t, const ft_pgrid_quad *q_in, int *fits)
{
    const ft_pgrid_quad qc = clamped(t, q_in);
    const double(*g)[2] = qc.g;
    const double *h = qc.h_m;
    double lo_x, hi_x, lo_y, hi_y;
    quad_box(&qc, &lo_x, &hi_x, &lo_y, &hi_y);
    /* the window: FT_PGRID_EXACT_CELLS cells from floor(lo), moved inside */
    const double n = (double)FT_PGRID_EXACT_CELLS;
    const double wx = (double)(t->width - 1u), wy = (double)(t->height - 1u);
    const double ox = fmax(0.0, fmin(floor(lo_x), wx - n)), oy = fmax(0.0, fmin(floor(lo_y), wy - n));
    *fits = (lo_x >= ox && lo_y >= oy && hi_x <= ox + n && hi_y <= oy + n);
    if (!*fits) {
        return 0.0;
    }
    /* the quad's 5 edges (triangles 0-1-3 and 0-3-2: the grid's index order) */
    static const int edge[5][2] = {{0, 1}, {1, 3}, {3, 2}, {2, 0}, {0, 3}};
    double e = 0.0;
    for (uint32_t cy = 0; cy < FT_PGRID_EXACT_CELLS; ++cy) {
        for (uint32_t cx = 0; cx < FT_PGRID_EXACT_CELLS; ++cx) {
            const double x0 = ox + cx, y0 = oy + cy;
            if (x0 + 1.0 > wx + 1e-9 || y0 + 1.0 > wy + 1e-9) continue; /* grid smaller than the window */
            if (x0 > hi_x || x0 + 1.0 < lo_x || y0 > hi_y || y0 + 1.0 < lo_y) continue;
            const uint32_t ix = (uint32_t)x0, iy = (uint32_t)y0;
            const double h00 = sample_at(t, ix, iy), h10 = sample_at(t, ix + 1u, iy);
            const double h01 = sample_at(t, ix, iy + 1u), h11 = sample_at(t, ix + 1u, iy + 1u);
            const double d = h00 - h10 - h01 + h11;
            for (int k = 0; k < 5; ++k) {
                const double *p = g[edge[k][0]], *r = g[edge[k][1]];
                const double hp = h[edge[k][0]], hr = h[edge[k][1]];
                const double dx = r[0] - p[0], dy = r[1] - p[1];
                /* the edge's parameter range inside the cell (slabs) */
                double ta = 0.0, tb = 1.0;
                if (dx != 0.0) {
                    const double t0 = (x0 - p[0]) / dx, t1 = (x0 + 1.0 - p[0]) / dx;
                    ta = fmax(ta, fmin(t0, t1));
                    tb = fmin(tb, fmax(t0, t1));
                } else if (p[0] < x0 || p[0] > x0 + 1.0) {
                    continue;
                }
                if (dy != 0.0) {
                    const double t0 = (y0 - p[1]) / dy, t1 = (y0 + 1.0 - p[1]) / dy;
                    ta = fmax(ta, fmin(t0, t1));
                    tb = fmin(tb, fmax(t0, t1));
                } else if (p[1] < y0 || p[1] > y0 + 1.0) {
                    continue;
                }
                if (ta > tb) continue;
                double f[2];
                for (int end = 0; end < 2; ++end) {
                    const double tt = end ? tb : ta;
                    const double u = p[0] + tt * dx - x0, v = p[1] + tt * dy - y0;
                    const double hb = h00 + (h10 - h00) * u + (h01 - h00) * v + d * u * v;
                    f[end] = hb - (hp + tt * (hr - hp));
                }
                e = fmax(e, piece_max(ta, tb, f[0], f[1], d * dx * dy));
            }
        }
    }
    /* samples inside a triangle: H has a kink there */
    static const int tri[2][3] = {{0, 1, 3}, {0, 3, 2}};
    for (uint32_t sy = 0; sy <= FT_PGRID_EXACT_CELLS; ++sy) {
        for (uint32_t sx = 0; sx <= FT_PGRID_EXACT_CELLS; ++sx) {
            const double x = ox + sx, y = oy + sy;
            if (x > wx || y > wy || x < lo_x || x > hi_x || y < lo_y || y > hi_y) continue;
            for (int k = 0; k < 2; ++k) {
                double w[3];
                const int *v = tri[k];
                if (!barycentric(g[v[0]], g[v[1]], g[v[2]], x, y, w)) continue;
                if (w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0) continue;
                const double l = w[0] * h[v[0]] + w[1] * h[v[1]] + w[2] * h[v[2]];
                e = fmax(e, fabs(sample_at(t, (uint32_t)x, (uint32_t)y) - l));
            }
        }
    }
    return e;
}

double ft_pgrid_quad_bound(const ft_terrain *t, const ft_pgrid_quad *q)
{
    int fits = 0;
    const double exact = ft_pgrid_quad_exact(t, q, &fits);
    if (fits) {
        return exact;
    }
    return ft_pgrid_quad_residual(t, q);
}

double ft_pgrid_quad_residual(const ft_terrain *t, const ft_pgrid_quad *q_in)
{
    const ft_pgrid_quad qc = clamped(t, q_in);
    const double(*g)[2] = qc.g;
    const double *h = qc.h_m;
    double lo_x, hi_x, lo_y, hi_y;
    quad_box(&qc, &lo_x, &hi_x, &lo_y, &hi_y);
    const double wx = (double)(t->width - 1u), wy = (double)(t->height - 1u);
    lo_x = clampd(lo_x, 0.0, wx);
    hi_x = clampd(hi_x, 0.0, wx);
    lo_y = clampd(lo_y, 0.0, wy);
    hi_y = clampd(hi_y, 0.0, wy);
    const double side = fmax(fmax(hi_x - lo_x, hi_y - lo_y), 1.0);
    uint32_t level = (uint32_t)fmax(0.0, ceil(log2(side)));
    const ft_pyramid *p = &t->pyr;
    if (level >= p->minmax_levels) {
        level = p->minmax_levels - 1u;
    }
    const ft_pyramid_level *lv = &p->minmax[level];
    const double scale = exp2((double)level);
    const uint32_t i0 = (uint32_t)fmin(floor(lo_x / scale), (double)(lv->width - 1u));
    const uint32_t j0 = (uint32_t)fmin(floor(lo_y / scale), (double)(lv->height - 1u));
    uint32_t i1 = (uint32_t)fmin(floor(hi_x / scale), (double)(lv->width - 1u));
    uint32_t j1 = (uint32_t)fmin(floor(hi_y / scale), (double)(lv->height - 1u));
    if (i1 > i0 + 1u) i1 = i0 + 1u; /* side <= 2^L: never more than 2 nodes */
    if (j1 > j0 + 1u) j1 = j0 + 1u;
    double e = 0.0;
    for (uint32_t j = j0; j <= j1; ++j) {
        for (uint32_t i = i0; i <= i1; ++i) {
            const node_box n = node_of(t, level, i, j);
            double off = 0.0;
            for (int k = 0; k < 4; ++k) {
                off = fmax(off, fabs(plane_at(&n, g[k][0], g[k][1]) - h[k]));
            }
            e = fmax(e, ft_pgrid_node_residual(t, level, i, j) + off);
        }
    }
    return e;
}

/* ---- 7. ray casting over the clipmap cache: the leaves' bound ------------------ */

/* Distance bins of the ray floor: bin 0 up to 100 m, bin b up to
 * 100 m 2^(b / 3). */
#define FT_PGRID_FLOOR_BINS 64

static int floor_bin(double r_m)
{
    if (!(r_m > 100.0)) {
        return 0;
    }
    const double b = ceil(3.0 * log2(r_m / 100.0));
    return b >= FT_PGRID_FLOOR_BINS - 1 ? FT_PGRID_FLOOR_BINS - 1 : (int)b;
}

typedef struct leaf_bound_ctx {
    const ft_clip_cache *c;
    const ft_pgm_clip_view *v;
    const ft_clip_world *w;
    ft_view_bound vb;
    double refine_over_px;
    /* the ray floor (see leaf_px): per distance bin, the lowest drawn
     * height of the blocks whose nearest point is in that bin or nearer */
    double floor_m[FT_PGRID_FLOOR_BINS];
    double eye_over_m;   /* the drawn surface under the eye is under it */
    double truth_top_m;  /* no height of the finest data is over it */
    ft_worst_pieces worst; /* the FT_PGRID_LEAF_REFINE_MAX largest, and the rest */
} leaf_bound_ctx;

/* 1 when level l - 1's resident box (as the shader got it) holds every
 * point of the level-l cells with south-west corners [i0, i1) x [j0, j1):
 * the traversal descends there, so no leaf of level l. */
static int finer_holds(const ft_pgm_clip_view *v, uint32_t l, const ft_clip_box *b)
{
    const uint32_t f = l - 1u;
    const double *bx = v->box[f];
    if (bx[2] <= bx[0] || bx[3] <= bx[1]) {
        return 0;
    }
    const double x0 = (double)v->base[f][0] + bx[0], x1 = (double)v->base[f][0] + bx[2];
    const double y0 = (double)v->base[f][1] + bx[1], y1 = (double)v->base[f][1] + bx[3];
    return 2.0 * (double)b->i0 >= x0 && 2.0 * (double)b->i1 <= x1 &&
           2.0 * (double)b->j0 >= y0 && 2.0 * (double)b->j1 <= y1;
}

/* 1 when a level-l cell with south-west corner (a, b) meets the data (the
 * ray is clipped to them: a cell past their edge is never met). */
static int meets_data(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b)
{
    const int64_t s = (int64_t)1 << l;
    const ft_clip_source *src = &c->src;
    return (a + 1) * s > src->data_i_lo && a * s < src->data_i_hi &&
           (b + 1) * s > src->data_j_lo && b * s < src->data_j_hi;
}

/* The horizontal distances from the eye to the xy box [lo, hi] (frame
 * coordinates): its nearest and farthest points. */
static void box_reach(const ft_view_bound *v, const double lo[2], const double hi[2],
                      double *near_m, double *far_m)
{
    double n2 = 0.0, f2 = 0.0;
    for (int i = 0; i < 2; ++i) {
        const double a = lo[i] - v->eye_m[i], b = hi[i] - v->eye_m[i];
        const double n = (a > 0.0) ? a : ((b < 0.0) ? -b : 0.0);
        const double f = fmax(fabs(a), fabs(b));
        n2 += n * n;
        f2 += f * f;
    }
    *near_m = sqrt(n2);
    *far_m = sqrt(f2);
}

/* The lowest height a ray can cross the column over the xy box [lo, hi]
 * at. A ray starts at an eye over the drawn surface under it; over the box
 * its path has crossed only points nearer than the box's farthest. Were it
 * there under every drawn height of those points (each block whose nearest
 * point is that near), it would be under the drawn surface where it is:
 * it has crossed the surface on the way (continuous along the path, and a
 * ray that enters a leaf under it stops at the entry) and ended, at a
 * height the same rule bounds. An eye under the surface: no floor. */
static double ray_floor(const leaf_bound_ctx *k, const double lo[3], const double hi[3])
{
    if (k->vb.eye_m[2] < k->eye_over_m) {
        return -INFINITY;
    }
    double near_m = 0.0, far_m = 0.0;
    box_reach(&k->vb, lo, hi, &near_m, &far_m);
    return k->floor_m[floor_bin(far_m)];
}

/* Error e_m over the level-l cells with south-west corners in r, heights
 * [lo, hi] widened by e_m: its pixels (0 outside the view). */
static double leaf_px(const leaf_bound_ctx *k, uint32_t l, const ft_clip_box *r, double lo_m,
                      double hi_m, double e_m)
{
    const ft_clip_world *w = k->w;
    const double s = ldexp(1.0, (int)l);
    const double li = (double)k->c->src.lattice_i0, lj = (double)k->c->src.lattice_j0;
    /* An unknown deviation leaves the cell's range unbounded too: a ray
     * over its column can end in it or miss the finest data there, from the
     * top of the finest data down to the ray floor. */
    const int known = isfinite(e_m);
    double lo[3] = {((double)r->i0 * s - li) * w->cell_x_m, ((double)r->j0 * s - lj) * w->cell_y_m,
                    lo_m - e_m};
    double hi[3] = {((double)r->i1 * s - li) * w->cell_x_m, ((double)r->j1 * s - lj) * w->cell_y_m,
                    hi_m + e_m};
    if (!known) {
        lo[2] = ray_floor(k, lo, hi);
        hi[2] = fmax(hi_m, k->truth_top_m);
    }
    ft_view_bound_drawn_box(&k->vb, lo, hi);
    if (ft_view_bound_outside(&k->vb, lo, hi)) {
        return 0.0;
    }
    return ft_view_bound_error_px(&k->vb, e_m, lo, hi);
}

static void lowest_block(void *ctx, uint32_t level, const ft_clip_block_bound *b)
{
    leaf_bound_ctx *k = ctx;
    const double s = ldexp(1.0, (int)level);
    const double li = (double)k->c->src.lattice_i0, lj = (double)k->c->src.lattice_j0;
    const double lo[2] = {((double)b->box.i0 * s - li) * k->w->cell_x_m,
                          ((double)b->box.j0 * s - lj) * k->w->cell_y_m};
    /* the cells reach one sample past the box */
    const double hi[2] = {((double)b->box.i1 * s - li) * k->w->cell_x_m,
                          ((double)b->box.j1 * s - lj) * k->w->cell_y_m};
    double near_m = 0.0, far_m = 0.0;
    box_reach(&k->vb, lo, hi, &near_m, &far_m);
    const int bin = floor_bin(near_m);
    k->floor_m[bin] = fmin(k->floor_m[bin], (double)b->lo_m);
}

/* The highest point of the drawn surface under the eye: the corners of
 * the cell holding it on the finest level whose box (as the shader got
 * it) holds it, the level the ray caster starts on; +INF when none. */
static double surface_top_under_eye(const leaf_bound_ctx *k)
{
    const ft_pgm_clip_view *v = k->v;
    for (uint32_t l = 0u; l < v->levels && l < FT_PGM_CLIP_LEVELS_MAX; ++l) {
        const double *bx = v->box[l];
        const double sc = ldexp(1.0, (int)l);
        const double ux = v->off[l][0] / sc, uy = v->off[l][1] / sc;
        if (bx[2] <= bx[0] || bx[3] <= bx[1] || ux < bx[0] || ux > bx[2] || uy < bx[1] ||
            uy > bx[3]) {
            continue;
        }
        const double cx = fmin(fmax(floor(ux), bx[0]), bx[2] - 1.0);
        const double cy = fmin(fmax(floor(uy), bx[1]), bx[3] - 1.0);
        ft_clip_block_bound cb;
        if (ft_clip_cell_bound(k->c, l, v->base[l][0] + (int64_t)cx, v->base[l][1] + (int64_t)cy,
                               &cb)) {
            return (double)cb.hi_m;
        }
        return INFINITY;
    }
    return INFINITY;
}

static void leaf_block(void *ctx, uint32_t level, const ft_clip_block_bound *b)
{
    leaf_bound_ctx *k = ctx;
    if (level == 0u || finer_holds(k->v, level, &b->box)) {
        return;
    }
    /* dev_m, not err_m: the twist term is for triangles, and the ray meets
     * the bilinear surface itself */
    const double px = leaf_px(k, level, &b->box, (double)b->lo_m, (double)b->hi_m,
                              (double)b->dev_m);
    if (px > 0.0) {
        ft_worst_pieces_note(&k->worst, level, &b->box, px);
    }
}

/* A piece again, cell by cell: only the cells that can be leaves and that
 * meet the data. */
static double refine_leaf_piece(const leaf_bound_ctx *k, const ft_worst_piece *p)
{
    double best = 0.0;
    for (int64_t b = p->box.j0; b < p->box.j1; ++b) {
        for (int64_t a = p->box.i0; a < p->box.i1; ++a) {
            const ft_clip_box cell = {a, b, a + 1, b + 1};
            ft_clip_block_bound cb;
            if (finer_holds(k->v, p->level, &cell) || !meets_data(k->c, p->level, a, b) ||
                !ft_clip_cell_bound(k->c, p->level, a, b, &cb)) {
                continue;
            }
            best = fmax(best, leaf_px(k, p->level, &cell, (double)cb.lo_m, (double)cb.hi_m,
                                      (double)cb.dev_m));
        }
    }
    return best;
}

double ft_pgrid_cache_leaf_bound_px(const ft_clip_cache *c, const ft_pgm_clip_view *v,
                                    const ft_clip_world *w, const ft_camera *cam,
                                    double curv_k_per_m, double truth_top_m,
                                    double refine_over_px)
{
    leaf_bound_ctx k;
    memset(&k, 0, sizeof k);
    k.c = c;
    k.v = v;
    k.w = w;
    k.refine_over_px = refine_over_px;
    ft_worst_pieces_init(&k.worst, FT_PGRID_LEAF_REFINE_MAX);
    const double origin_m[2] = {w->origin_x_m, w->origin_y_m};
    ft_view_bound_from_camera(cam, origin_m, curv_k_per_m, &k.vb);
    const uint32_t levels = (v->levels < c->desc.levels) ? v->levels : c->desc.levels;
    /* the ray floor: the lowest drawn height by distance, then prefix
     * minima (a bin's floor holds every nearer block too) */
    for (int b = 0; b < FT_PGRID_FLOOR_BINS; ++b) {
        k.floor_m[b] = INFINITY;
    }
    k.eye_over_m = surface_top_under_eye(&k);
    for (uint32_t l = 0u; l < levels && l < FT_PGM_CLIP_LEVELS_MAX; ++l) {
        (void)ft_clip_blocks_visit(c, l, lowest_block, &k);
    }
    for (int b = 1; b < FT_PGRID_FLOOR_BINS; ++b) {
        k.floor_m[b] = fmin(k.floor_m[b], k.floor_m[b - 1]);
    }
    k.truth_top_m = truth_top_m;
    for (uint32_t l = 1u; l < levels && l < FT_PGM_CLIP_LEVELS_MAX; ++l) {
        (void)ft_clip_blocks_visit(c, l, leaf_block, &k);
    }
    double bound = k.worst.rest_px;
    for (uint32_t i = 0u; i < k.worst.n; ++i) {
        const ft_worst_piece *p = &k.worst.piece[i];
        double px = p->px;
        if (px > refine_over_px) { /* both bound the piece: the smaller */
            px = fmin(px, refine_leaf_piece(&k, p));
        }
        bound = fmax(bound, px);
    }
    return bound;
}
