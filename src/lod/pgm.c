/* pgm.c - persistent grid mapping, CPU side (the math is explained in pgm.h).
 * Loops are bounded by the pyramid depth or a small constant; no allocation. */
#include "lod/pgm.h"

#include <math.h>
#include <string.h>

static double clampd(double v, double lo, double hi)
{
    return (v > lo) ? ((v < hi) ? v : hi) : lo; /* NaN -> lo */
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double ft_pgm_sampling_depression(double view_depression_rad, double half_angle_rad,
                                  double eps_rad)
{
    /* "A_sam = A_view if |A_view| > FOV/2 else FOV/2 + eps", written as a max so
     * the band between FOV/2 and FOV/2 + eps also keeps eps below the horizon. */
    double dep = view_depression_rad;
    if (!(dep >= half_angle_rad + eps_rad)) {
        dep = half_angle_rad + eps_rad;
    }
    return (dep < 0.5 * FT_PI) ? dep : 0.5 * FT_PI;
}

double ft_pgm_gamma(double h_m, double m_m, double r_m, double room_rad)
{
    if (!(m_m > 0.0) || !(h_m > 0.0) || !(room_rad > 0.0)) {
        return 0.0;
    }
    const double den = h_m * h_m * h_m + r_m * r_m * (h_m - m_m);
    if (!(den > 0.0)) {
        return room_rad; /* a peak at or above the eye: extend down to the nadir */
    }
    const double g = atan(r_m * h_m * m_m / den);
    return (g < room_rad) ? g : room_rad;
}

void ft_pgm_lod(double r_cells, uint32_t levels, uint32_t *level, double *parent_w)
{
    uint32_t l = 0;
    double w = 0.0;
    if (r_cells > 1.0) {
        /* floor(log2 r) by doubling: bounded by the 32 levels a uint can name */
        double span = 1.0;
        for (uint32_t guard = 0; guard < 32u && r_cells >= 2.0 * span; ++guard) {
            span *= 2.0;
            ++l;
        }
        w = clampd(r_cells / span - 1.0, 0.0, 1.0);
    }
    const uint32_t top = (levels > 0u) ? levels - 1u : 0u;
    if (l >= top) {
        l = top;
        w = 0.0;
    }
    *level = l;
    *parent_w = w;
}

double ft_pgm_level_height(const ft_terrain *t, uint32_t level, double gx, double gy,
                           double grad[2])
{
    const ft_pyramid_level *lv = &t->pyr.avg[level];
    const float *a = (level == 0u) ? t->heights_m : lv->avg_m;
    const uint32_t w = (level == 0u) ? t->width : lv->width;
    const uint32_t h = (level == 0u) ? t->height : lv->height;
    const double scale = ldexp(1.0, (int)level);
    const double ux = (gx + 0.5) / scale - 0.5, uy = (gy + 0.5) / scale - 0.5;
    const double ix = floor(ux), iy = floor(uy);
    const double fx = ux - ix, fy = uy - iy;
    const double hx = (double)w - 1.0, hy = (double)h - 1.0;
    const size_t x0 = (size_t)clampd(ix, 0.0, hx), x1 = (size_t)clampd(ix + 1.0, 0.0, hx);
    const size_t y0 = (size_t)clampd(iy, 0.0, hy), y1 = (size_t)clampd(iy + 1.0, 0.0, hy);
    const double h00 = a[y0 * w + x0], h10 = a[y0 * w + x1];
    const double h01 = a[y1 * w + x0], h11 = a[y1 * w + x1];
    if (grad != NULL) {
        grad[0] = ((h10 - h00) * (1.0 - fy) + (h11 - h01) * fy) / scale;
        grad[1] = ((h01 - h00) * (1.0 - fx) + (h11 - h10) * fx) / scale;
    }
    const double lo = h00 + (h10 - h00) * fx, hi = h01 + (h11 - h01) * fx;
    return lo + (hi - lo) * fy;
}

double ft_pgm_max_height(const ft_terrain *t, double x0_m, double y0_m, double x1_m, double y1_m)
{
    const ft_pyramid *p = &t->pyr;
    if (p->minmax_levels == 0u || t->width < 2u || t->height < 2u) {
        return (double)t->max_height_m; /* no bound pyramid: the global bound */
    }
    /* world box -> cell index box of level 0, clamped; NaN-safe */
    const double cx0 = floor((x0_m - t->origin_world_x_m) / t->cell_x_m);
    const double cx1 = floor((x1_m - t->origin_world_x_m) / t->cell_x_m);
    const double cy0 = floor((y0_m - t->origin_world_y_m) / t->cell_y_m);
    const double cy1 = floor((y1_m - t->origin_world_y_m) / t->cell_y_m);
    const double mx = (double)t->width - 2.0, my = (double)t->height - 2.0;
    if (!(cx1 >= 0.0 && cy1 >= 0.0 && cx0 <= mx && cy0 <= my)) {
        return -INFINITY;
    }
    /* A small box: the exact maximum of the bilinear surface. On each cell's
     * part of the box the surface is bilinear, so its maximum is at a corner
     * of that part: the corners are every (X, Y) with X in {x0, x1, the grid
     * columns between} and Y likewise. */
    const double gx0 = clampd((x0_m - t->origin_world_x_m) / t->cell_x_m, 0.0, mx + 1.0);
    const double gx1 = clampd((x1_m - t->origin_world_x_m) / t->cell_x_m, 0.0, mx + 1.0);
    const double gy0 = clampd((y0_m - t->origin_world_y_m) / t->cell_y_m, 0.0, my + 1.0);
    const double gy1 = clampd((y1_m - t->origin_world_y_m) / t->cell_y_m, 0.0, my + 1.0);
    if (gx1 - gx0 <= FT_PGM_EXACT_MAX_CELLS && gy1 - gy0 <= FT_PGM_EXACT_MAX_CELLS) {
        double best = -INFINITY;
        const double fx0 = floor(gx0), fy0 = floor(gy0);
        for (uint32_t a = 0; a <= FT_PGM_EXACT_MAX_CELLS + 2u; ++a) {
            double gx = (a == 0u) ? gx0 : fx0 + (double)a;
            if (gx >= gx1) gx = gx1;
            for (uint32_t b = 0; b <= FT_PGM_EXACT_MAX_CELLS + 2u; ++b) {
                double gy = (b == 0u) ? gy0 : fy0 + (double)b;
                if (gy >= gy1) gy = gy1;
                const double v = ft_pgm_level_height(t, 0u, gx, gy, NULL);
                best = (v > best) ? v : best;
                if (gy >= gy1) break;
            }
            if (gx >= gx1) break;
        }
        return best;
    }
    uint32_t ix0 = (uint32_t)clampd(cx0, 0.0, mx), ix1 = (uint32_t)clampd(cx1, 0.0, mx);
    uint32_t iy0 = (uint32_t)clampd(cy0, 0.0, my), iy1 = (uint32_t)clampd(cy1, 0.0, my);
    /* the finest level where the box spans at most 4 x 4 texels */
    uint32_t l = 0;
    while (l + 1u < p->minmax_levels && ((ix1 >> l) - (ix0 >> l) > 3u || (iy1 >> l) - (iy0 >> l) > 3u)) {
        ++l;
    }
    const ft_pyramid_level *lv = &p->minmax[l];
    double m = -INFINITY;
    for (uint32_t y = iy0 >> l; y <= (iy1 >> l) && y < lv->height; ++y) {
        for (uint32_t x = ix0 >> l; x <= (ix1 >> l) && x < lv->width; ++x) {
            const double v = lv->max_m[(size_t)y * lv->width + x];
            m = (v > m) ? v : m;
        }
    }
    return m;
}

/* Largest |x| at which a ray of the rectangle's rows [y0, y1] still has a
 * depression >= eps (beyond it every ray meets the plane past `far`). */
static double x_cap(double dep, double eps, double y0, double y1)
{
    const double s = sin(eps), sd = sin(dep), cd = cos(dep);
    const double qa = cd * cd / (s * s) - 1.0, qb = -2.0 * sd * cd / (s * s);
    const double qc = sd * sd / (s * s) - 1.0;
    double best = qa * y0 * y0 + qb * y0 + qc;
    const double at1 = qa * y1 * y1 + qb * y1 + qc;
    best = (at1 > best) ? at1 : best;
    if (qa < 0.0) {
        const double ys = -qb / (2.0 * qa);
        if (ys > y0 && ys < y1) {
            const double v = qa * ys * ys + qb * ys + qc;
            best = (v > best) ? v : best;
        }
    }
    return (best > 0.0) ? sqrt(best) : 0.0;
}

static void ground_of(const ft_pgm_sampling *s, double x, double y, double out[2])
{
    double d[3];
    for (int k = 0; k < 3; ++k) {
        d[k] = s->forward[k] + x * s->right[k] + y * s->up[k];
    }
    const double ndz = (-d[2] > s->min_neg_dz) ? -d[2] : s->min_neg_dz;
    const double tr = s->height_m / ndz;
    out[0] = tr * d[0];
    out[1] = tr * d[1];
}

/* Columns wide enough for every view ray that can meet terrain (sampled
 * along the side edges x = +-tx_b of the roll-free bounding rectangle). A
 * ray at azimuth az off the heading and depression dv can meet terrain only
 * where its base-plane point lies at a depression d >= d_min from the eye:
 *  - falling (dv > 0): d_min = max(dv, eps) (it meets the plane at dv, and
 *    the grid ends at the far corner, depression eps);
 *  - level or rising: only terrain higher than the eye, m above the plane
 *    (h: the eye), within D_max = (m - h) / tan(-dv) of it (or the far
 *    corner): d_min = atan2(h, min(D_max, far)); none at all when m <= h.
 * That ground direction has the sampling image abscissa
 *     x_s = cos d sin az / (cos d cos az cos dep_s + sin d sin dep_s)
 * (when the denominator, its depth along the sampling axis, is > 0), which
 * falls as d grows: the need is at d_min. A view pitched up (dep_v < 0)
 * needs it: its lower side rays spread wider than tx_b, and at FOV 1
 * pitched up 10 deg the image's edge column (1.7% of the width) went
 * missing. Widened, it gets a 1% margin for the need between the samples
 * (where the view's own columns suffice, as when the sampling camera is the
 * view, they stay exact). The columns stop at FT_PGM_COLUMNS_WIDEN_MAX x
 * tx_b: near the zenith a view's sideways rays run at right angles to the
 * sampling camera's heading (no finite width holds them, as no rectangle
 * holds rays past the 88 deg cap), and widening the columns toward the cap
 * for them would thin out the whole grid (on N42E001, pitch 90, FOV 120,
 * 1 m above a slope: 1983 pixels of missed terrain instead of 86). */
static double columns_for_view(double tx_cov, double dep_v, double dep_s, double eps,
                               double tx_b, double ty_b, double h, double m, double far)
{
    const double e = -dep_v; /* the view axis's elevation */
    for (int k = 0; k <= 32; ++k) {
        const double y = -ty_b + 2.0 * ty_b * (double)k / 32.0;
        const double fwd = cos(e) - y * sin(e); /* horizontal, along the heading */
        const double up = sin(e) + y * cos(e);
        const double hz = hypot(fwd, tx_b);
        if (hz <= 1e-12) {
            continue;
        }
        const double dv = atan2(-up, hz);
        double d = (dv > eps) ? dv : eps;
        if (dv <= 0.0) {
            if (m <= h) {
                continue; /* rising from above every peak: no terrain */
            }
            const double reach = (up > 1e-12) ? (m - h) * hz / up : far;
            d = atan2(h, (reach < far) ? reach : far);
            d = (d > eps) ? d : eps;
        }
        const double depth = cos(d) * (fwd / hz) * cos(dep_s) + sin(d) * sin(dep_s);
        if (depth <= 1e-9) {
            continue;
        }
        double need = cos(d) * (tx_b / hz) / depth;
        if (need > tx_cov * (1.0 + 1e-9)) {
            need *= 1.01; /* the margin: the need between the samples */
            need = (need < FT_PGM_COLUMNS_WIDEN_MAX * tx_b) ? need : FT_PGM_COLUMNS_WIDEN_MAX * tx_b;
            tx_cov = (need > tx_cov) ? need : tx_cov;
        }
    }
    return tx_cov;
}

static double terrain_max_in(const void *ctx, double x0_m, double y0_m, double x1_m,
                             double y1_m)
{
    return ft_pgm_max_height(ctx, x0_m, y0_m, x1_m, y1_m);
}

ft_pgm_surface ft_pgm_surface_of_terrain(const ft_terrain *t)
{
    const ft_pgm_surface g = {
        t->origin_world_x_m,
        t->origin_world_y_m,
        t->origin_world_x_m + (double)(t->width - 1u) * t->cell_x_m,
        t->origin_world_y_m + (double)(t->height - 1u) * t->cell_y_m,
        (double)t->min_height_m,
        (double)t->max_height_m,
        terrain_max_in,
        t,
        t->curv_drop_per_m2,
    };
    return g;
}

void ft_pgm_setup(ft_pgm_sampling *s, const ft_camera *c, const ft_terrain *t)
{
    const ft_pgm_surface g = ft_pgm_surface_of_terrain(t);
    ft_pgm_setup_over(s, c, &g);
}

void ft_pgm_setup_over(ft_pgm_sampling *s, const ft_camera *c, const ft_pgm_surface *t)
{
    memset(s, 0, sizeof *s);
    memcpy(s->eye_m, c->eye_m, sizeof s->eye_m);
    /* the farthest grid corner bounds how far any sampled ground lies */
    double far2 = 1.0;
    for (int k = 0; k < 4; ++k) {
        const double dx = ((k & 1) ? t->x1_m : t->x0_m) - c->eye_m[0];
        const double dy = ((k & 2) ? t->y1_m : t->y0_m) - c->eye_m[1];
        far2 = (dx * dx + dy * dy > far2) ? dx * dx + dy * dy : far2;
    }
    s->far_m = sqrt(far2);
    /* Every drawn point lies on or above the base plane: the terrain minimum,
     * less the largest earth-curvature drop over the grid (terrain.h). A
     * plane through the undropped minimum would leave dropped terrain at the
     * view's edges (a nadir view from 100 km, FOV 150 from 3 km) outside the
     * grid. */
    s->base_z_m = t->zmin_m - t->curv_drop_per_m2 * far2;
    /* Under the base plane only rising rays can meet the terrain (it is all
     * above the plane), and a ray rising at elevation e meets the plane where
     * the mirrored ray falling at depression e does: mirror the eye and the
     * view through the plane. */
    const double above = c->eye_m[2] - s->base_z_m;
    s->mirrored = above < 0.0;
    double h = s->mirrored ? -above : above;
    h = (h > FT_PGM_MIN_HEIGHT_M) ? h : FT_PGM_MIN_HEIGHT_M;
    s->height_m = h;
    s->lift_m = s->base_z_m + h - c->eye_m[2];
    const double zs = s->mirrored ? -1.0 : 1.0;
    const double f[3] = {c->forward[0], c->forward[1], zs * c->forward[2]};
    const double view_up[3] = {c->up[0], c->up[1], zs * c->up[2]};
    const double view_right[3] = {c->right[0], c->right[1], zs * c->right[2]};

    /* Heading: the forward's horizontal direction; looking straight down
     * (or up) the image's up vector says where the heading is. */
    double hd[2];
    const double fxy = hypot(f[0], f[1]);
    if (fxy > 1e-9) {
        hd[0] = f[0] / fxy;
        hd[1] = f[1] / fxy;
    } else {
        const double sg = (f[2] < 0.0) ? 1.0 : -1.0;
        const double uxy = hypot(view_up[0], view_up[1]);
        hd[0] = sg * view_up[0] / uxy;
        hd[1] = sg * view_up[1] / uxy;
    }
    const double r0[3] = {hd[1], -hd[0], 0.0};
    const double dep_v = asin(clampd(-f[2], -1.0, 1.0));
    s->view_depression_rad = dep_v;
    /* roll: the view's right against the roll-free right, about the forward */
    const double up_nr[3] = {r0[1] * f[2] - r0[2] * f[1], r0[2] * f[0] - r0[0] * f[2],
                             r0[0] * f[1] - r0[1] * f[0]};
    const double cr = dot3(view_right, r0), sr = -dot3(view_right, up_nr);
    s->roll_rad = atan2(sr, cr);
    const double ty = tan(0.5 * c->fovy_rad);
    const double tx = ty * (double)c->width_px / (double)c->height_px;
    double a = atan(fabs(sr) * tx + fabs(cr) * ty);
    a = (a < FT_PGM_HALF_ANGLE_MAX_RAD) ? a : FT_PGM_HALF_ANGLE_MAX_RAD;
    const double tmax = tan(FT_PGM_HALF_ANGLE_MAX_RAD);
    s->half_x_tan = fabs(cr) * tx + fabs(sr) * ty;
    s->half_x_tan = (s->half_x_tan < tmax) ? s->half_x_tan : tmax;
    s->half_y_tan = tan(a);

    /* eps: the top edge never looks farther than the farthest grid corner */
    const double eps_far = atan2(h, s->far_m);
    s->eps_rad = (eps_far > FT_PGM_EPS_MIN_RAD) ? eps_far : FT_PGM_EPS_MIN_RAD;

    const double dep = ft_pgm_sampling_depression(dep_v, a, s->eps_rad);
    s->depression_rad = dep;
    s->pitched_down = dep > dep_v;
    const double cd = cos(dep), sd = sin(dep);
    for (int k = 0; k < 3; ++k) {
        const double hz = (k < 2) ? hd[k] : 0.0, z = (k == 2) ? 1.0 : 0.0;
        s->forward[k] = cd * hz - sd * z;
        s->up[k] = sd * hz + cd * z;
        s->right[k] = r0[k];
    }
    const double top_a = (a < dep - s->eps_rad) ? a : dep - s->eps_rad;
    const double y1 = tan(top_a);
    double tx_cov = s->half_x_tan;
    if (s->pitched_down) {
        /* every view ray below the horizon: x_s < tx_b cos(dep_v) / cos(dep_s) */
        const double wide = (cd > 1e-12) ? s->half_x_tan * cos(dep_v) / cd : tmax;
        tx_cov = (wide > tx_cov) ? wide : tx_cov;
    }
    tx_cov = columns_for_view(tx_cov, dep_v, dep, s->eps_rad, s->half_x_tan, s->half_y_tan,
                              s->height_m, t->zmax_m - s->base_z_m, s->far_m);
    tx_cov = (tx_cov < tmax) ? tx_cov : tmax;
    /* -d_z is smallest on the top edge: -d_z = sin(dep) - y1 cos(dep) > 0 */
    s->min_neg_dz = 0.5 * (sd - y1 * cd);

    /* The bottom edge starts at the VIEW's bottom edge, a row of the
     * sampling image (pgm.h, Rectangle), unless the view shows no ground
     * under the eps line or its top edge rises past the zenith; the clamp
     * is for round-off only (dep_s >= dep_v puts the row at or above -tan a). */
    double y_start = tan(dep - dep_v - a);
    if (!(y_start < y1 - 0.01 * (y1 + s->half_y_tan)) || !(a - dep_v < 0.5 * FT_PI)) {
        y_start = -s->half_y_tan;
    }
    y_start = (y_start > -s->half_y_tan) ? y_start : -s->half_y_tan;
    /* viewport extension from the rectangle before it (none when mirrored:
     * seen from below, terrain nearer than the steepest ray's plane point is
     * above that ray, so out of the view) */
    const double beta = dep - atan(y_start);
    double gamma = 0.0;
    double y_bot = y_start;
    if (0.5 * FT_PI - beta > 1e-9 && !s->mirrored) {
        const double xc0 = x_cap(dep, s->eps_rad, -s->half_y_tan, y1);
        const double txp = (tx_cov < xc0) ? tx_cov : xc0;
        s->near_ground_m = h / tan(beta);
        /* the bottom edge's left corner, right corner and centre columns */
        const double col_x[3] = {-txp, txp, 0.0};
        double col_r[3], dir[3][2];
        for (int k = 0; k < 3; ++k) {
            double g[2];
            ground_of(s, col_x[k], y_start, g);
            col_r[k] = hypot(g[0], g[1]);
            dir[k][0] = (col_r[k] > 0.0) ? g[0] / col_r[k] : 0.0;
            dir[k][1] = (col_r[k] > 0.0) ? g[1] / col_r[k] : 0.0;
        }
        const double rc = (col_r[0] > col_r[1]) ? col_r[0] : col_r[1];
        double x_req[3] = {col_r[0], col_r[1], col_r[2]};
        /* What can enter the VIEW decides, so the formula's r is the ground
         * distance of the view's bottom-edge ray in the column's azimuth (the
         * same ray as the sampling camera's unless that one is pitched down):
         * in the view's roll-free frame that ray is f_v + X r0 - ty_b u_v
         * with X chosen for the azimuth. tan_bv <= 0: the view's bottom edge
         * is at or above the horizon there. */
        double tan_bv[3];
        int past_nadir[3] = {0, 0, 0};
        const double cv = cos(dep_v), sv = sin(dep_v);
        const double c0 = cv - s->half_y_tan * sv; /* horizontal forward part */
        for (int k = 0; k < 3; ++k) {
            const double af = dir[k][0] * hd[0] + dir[k][1] * hd[1];
            const double ar = dir[k][0] * r0[0] + dir[k][1] * r0[1];
            if (!(c0 > 0.0) || !(af > 0.0)) {
                past_nadir[k] = 1; /* the view looks down past the nadir */
                tan_bv[k] = 0.0;
                continue;
            }
            const double x = c0 * ar / af, dz = -sv - s->half_y_tan * cv;
            tan_bv[k] = -dz / hypot(c0, x);
        }
        for (uint32_t q = 0; q < (FT_PGM_GAMMA_BANDS + 1u) * FT_PGM_GAMMA_PIECES; ++q) {
            /* band b spans ground distances [x1 / 2, x1] of the bottom edge's
             * wedge ([0, x1] for the last); piece q of it 1 / PIECES of that,
             * so a thin wedge's box stays thin even when it runs diagonally */
            const uint32_t b = q / FT_PGM_GAMMA_PIECES, pc = q % FT_PGM_GAMMA_PIECES;
            const double bx = ldexp(rc, -(int)(FT_PGM_GAMMA_BANDS - b));
            const double bw = (b == 0u) ? bx : 0.5 * bx;
            const double x0 = bx - bw + bw * (double)pc / FT_PGM_GAMMA_PIECES;
            const double x1 = bx - bw + bw * (double)(pc + 1u) / FT_PGM_GAMMA_PIECES;
            double bx0 = INFINITY, by0 = INFINITY, bx1 = -INFINITY, by1 = -INFINITY;
            for (int k = 0; k < 6; ++k) {
                const double d = (k < 3) ? x0 : x1;
                const double px = d * dir[k % 3][0], py = d * dir[k % 3][1];
                bx0 = (px < bx0) ? px : bx0;
                bx1 = (px > bx1) ? px : bx1;
                by0 = (py < by0) ? py : by0;
                by1 = (py > by1) ? py : by1;
            }
            const double mx = t->max_in(t->ctx, c->eye_m[0] + bx0, c->eye_m[1] + by0,
                                        c->eye_m[0] + bx1, c->eye_m[1] + by1);
            const double m = isfinite(mx) ? mx - s->base_z_m : 0.0;
            /* per column: the formula with this piece's peak m and the
             * view's bottom ray at depression beta_v (r = h / tan beta_v): the
             * ray at beta_v + gamma meets the plane at x = h / tan(beta_v +
             * gamma) = (h - m) r / h, and a peak of height m nearer than x
             * stays under the view. Never nearer than the piece's near edge. */
            if (!(m > 0.0)) {
                continue;
            }
            for (int k = 0; k < 3; ++k) {
                double x;
                if (past_nadir[k]) {
                    x = x0; /* the view sees down to the nadir */
                } else if (!(tan_bv[k] > 0.0)) {
                    /* bottom edge at or above the horizon: only a peak above
                     * the eye can show, and then at any distance */
                    x = (m >= h) ? x0 : INFINITY;
                } else {
                    const double beta_v = atan(tan_bv[k]);
                    const double room_v = 0.5 * FT_PI - beta_v;
                    const double g = ft_pgm_gamma(h, m, h / tan_bv[k], room_v);
                    x = (g >= room_v) ? 0.0 : h / tan(beta_v + g);
                }
                if (!(x < x1)) {
                    continue; /* the whole piece is under the view's bottom edge */
                }
                x = (x > x0) ? x : x0;
                if (x < x_req[k]) {
                    x_req[k] = x;
                    s->missed_max_m = (m > s->missed_max_m) ? m : s->missed_max_m;
                }
            }
        }
        /* lower the bottom edge until every column's ground point is within
         * its x_req: along a column the distance falls monotonically from the
         * edge (y = -ty) down to the nadir line y = -cot(dep) (bisection) */
        const double y_nadir = -cd / sd;
        for (int k = 0; k < 3; ++k) {
            double hi = y_start, lo = y_nadir;
            double g[2];
            ground_of(s, col_x[k], lo, g);
            if (hypot(g[0], g[1]) >= x_req[k]) {
                hi = lo; /* not even the nadir line gets that near: go there */
            }
            for (int it = 0; it < 60 && hi - lo > 1e-12 * (1.0 - lo); ++it) {
                const double mid = 0.5 * (lo + hi);
                ground_of(s, col_x[k], mid, g);
                if (hypot(g[0], g[1]) > x_req[k]) hi = mid; else lo = mid;
            }
            y_bot = (hi < y_bot) ? hi : y_bot;
        }
        gamma = atan(-y_bot) - atan(-y_start);
        gamma = (gamma > 0.0) ? gamma : 0.0;
    }
    s->gamma_rad = gamma;
    /* bottom: extended, but not past the half-angle cap (unless that is
     * needed to reach the nadir, where the sampling camera is nearly level)
     * nor so far past the nadir that it looks flatter than eps behind */
    double bot_a = atan(-y_start) + gamma;
    const double cap = (0.5 * FT_PI - dep > FT_PGM_HALF_ANGLE_MAX_RAD)
                           ? 0.5 * FT_PI - dep
                           : FT_PGM_HALF_ANGLE_MAX_RAD;
    bot_a = (bot_a < cap) ? bot_a : cap;
    const double behind = FT_PI - s->eps_rad - dep;
    bot_a = (bot_a < behind) ? bot_a : behind;
    const double y0 = -tan(bot_a);
    /* the columns as wide as the sampling camera's own rows would make
     * them: a level or rising view ray can meet terrain whose base point
     * lies out to the eps line in its azimuth, which bends below the view's
     * bottom edge at the sides (the extra columns' rays in the upper rows
     * meet the plane past the far corner: wasted, never a miss) */
    const double xc = x_cap(dep, s->eps_rad, (y0 < -s->half_y_tan) ? y0 : -s->half_y_tan, y1);
    double tx_s = (tx_cov < xc) ? tx_cov : xc;
    tx_s = (tx_s > 1e-6) ? tx_s : 1e-6;
    s->rect[0] = -tx_s;
    s->rect[1] = y0;
    s->rect[2] = tx_s;
    s->rect[3] = y1;
}

void ft_pgm_ray(const ft_pgm_sampling *s, uint32_t cols, uint32_t rows, double i, double j,
                double dir[3])
{
    const double u = i / (double)(cols - 1u), v = j / (double)(rows - 1u);
    const double x = s->rect[0] + (s->rect[2] - s->rect[0]) * u;
    const double y = s->rect[1] + (s->rect[3] - s->rect[1]) * v;
    for (int k = 0; k < 3; ++k) {
        dir[k] = s->forward[k] + x * s->right[k] + y * s->up[k];
    }
}

void ft_pgm_ground(const ft_pgm_sampling *s, uint32_t cols, uint32_t rows, double i, double j,
                   double rel_xy_m[2])
{
    const double u = i / (double)(cols - 1u), v = j / (double)(rows - 1u);
    ground_of(s, s->rect[0] + (s->rect[2] - s->rect[0]) * u,
              s->rect[1] + (s->rect[3] - s->rect[1]) * v, rel_xy_m);
}

/* Vertex (i, j)'s ground point p and footprint: the ground distance in
 * cells to the farthest of its 4 grid neighbours' points. */
static void footprint(const ft_pgm_sampling *s, uint32_t cols, uint32_t rows, uint32_t i,
                      uint32_t j, double cell_x_m, double cell_y_m, ft_pgm_vertex *out)
{
    static const double nb[4][2] = {{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}};
    memset(out, 0, sizeof *out);
    double p[2];
    ft_pgm_ground(s, cols, rows, (double)i, (double)j, p);
    double r2 = 0.0;
    for (int k = 0; k < 4; ++k) {
        double q[2];
        ft_pgm_ground(s, cols, rows, (double)i + nb[k][0], (double)j + nb[k][1], q);
        const double dx = (q[0] - p[0]) / cell_x_m, dy = (q[1] - p[1]) / cell_y_m;
        r2 = (dx * dx + dy * dy > r2) ? dx * dx + dy * dy : r2;
    }
    out->ground_rel_m[0] = p[0];
    out->ground_rel_m[1] = p[1];
    out->r_cells = sqrt(r2);
}

void ft_pgm_vertex_at(const ft_pgm_sampling *s, const ft_terrain *t, uint32_t cols,
                      uint32_t rows, uint32_t i, uint32_t j, ft_pgm_vertex *out)
{
    footprint(s, cols, rows, i, j, t->cell_x_m, t->cell_y_m, out);
    const double p[2] = {out->ground_rel_m[0], out->ground_rel_m[1]};
    ft_pgm_lod(out->r_cells, t->pyr.avg_levels, &out->level, &out->parent_w);
    const double ox = t->origin_world_x_m - s->eye_m[0], oy = t->origin_world_y_m - s->eye_m[1];
    /* clamped into the grid, xy relative to the eye: near the eye this never
     * goes through the (large) grid origin, so float keeps millimetres */
    const double px = clampd(p[0], ox, ox + ((double)t->width - 1.0) * t->cell_x_m);
    const double py = clampd(p[1], oy, oy + ((double)t->height - 1.0) * t->cell_y_m);
    out->grid[0] = (px - ox) / t->cell_x_m;
    out->grid[1] = (py - oy) / t->cell_y_m;
    double hgt = ft_pgm_level_height(t, out->level, out->grid[0], out->grid[1], NULL);
    if (out->parent_w > 0.0) {
        const double hp =
            ft_pgm_level_height(t, out->level + 1u, out->grid[0], out->grid[1], NULL);
        hgt += (hp - hgt) * out->parent_w;
    }
    out->height_m = hgt;
    out->pos_rel_eye_m[0] = px;
    out->pos_rel_eye_m[1] = py;
    /* drawn lowered by the earth's curvature, as shaders/curvature.glsl */
    out->pos_rel_eye_m[2] = hgt - s->eye_m[2] - t->curv_drop_per_m2 * (px * px + py * py);
}

/* ---- heights from the clip cache (the shader's FT_PGM_CLIP part) ---------------- */

/* Level L bilinear at g0 inside its resident box: height, and its gradient
 * per level-0 sample when grad is not NULL. */
static double clip_sample(const ft_pgm_clip_view *v, uint32_t level, double g0x, double g0y,
                          double grad[2])
{
    const double scale = ldexp(1.0, (int)level);
    const double *b = v->box[level];
    const double ux = clampd((g0x + v->off[level][0]) / scale, b[0], b[2]);
    const double uy = clampd((g0y + v->off[level][1]) / scale, b[1], b[3]);
    const double ix = fmin(floor(ux), b[2] - 1.0), iy = fmin(floor(uy), b[3] - 1.0);
    const double fx = ux - ix, fy = uy - iy;
    const int64_t a = v->base[level][0] + (int64_t)ix, c = v->base[level][1] + (int64_t)iy;
    const double h00 = v->texel(v->ctx, level, a, c), h10 = v->texel(v->ctx, level, a + 1, c);
    const double h01 = v->texel(v->ctx, level, a, c + 1);
    const double h11 = v->texel(v->ctx, level, a + 1, c + 1);
    if (grad != NULL) {
        grad[0] = ((h10 - h00) * (1.0 - fy) + (h11 - h01) * fy) / scale;
        grad[1] = ((h01 - h00) * (1.0 - fx) + (h11 - h10) * fx) / scale;
    }
    const double lo = h00 + (h10 - h00) * fx, hi = h01 + (h11 - h01) * fx;
    return lo + (hi - lo) * fy;
}

double ft_pgm_clip_resident(const ft_pgm_clip_view *v, double g0x, double g0y)
{
    const uint32_t top = v->levels - 1u;
    for (uint32_t l = 0; l < top && l < FT_PGM_CLIP_LEVELS_MAX; ++l) {
        const double *b = v->box[l];
        const double scale = ldexp(1.0, (int)l);
        const double ux = (g0x + v->off[l][0]) / scale, uy = (g0y + v->off[l][1]) / scale;
        const double d = fmin(fmin(ux - b[0], b[2] - ux), fmin(uy - b[1], b[3] - uy)) - 1.0;
        if (b[2] >= b[0] && b[3] >= b[1] && d >= 0.0) {
            return (double)l + clampd(1.0 - d / v->transition_samples, 0.0, 1.0);
        }
    }
    return (double)top;
}

int ft_pgm_clip_eye_coarser(const ft_pgm_clip_view *v)
{
    const double *b = v->box[0], *o = v->off[0];
    return !(b[2] >= b[0] && o[0] - b[0] >= 1.0 && b[2] - o[0] >= 1.0 && o[1] - b[1] >= 1.0 &&
             b[3] - o[1] >= 1.0);
}

void ft_pgm_clip_vertex_at(const ft_pgm_sampling *s, const ft_pgm_clip_view *v,
                           double cell_x_m, double cell_y_m, double curv_drop_per_m2,
                           uint32_t cols, uint32_t rows, uint32_t i, uint32_t j,
                           ft_pgm_vertex *out)
{
    footprint(s, cols, rows, i, j, cell_x_m, cell_y_m, out);
    const double px = clampd(out->ground_rel_m[0], v->clamp_m[0], v->clamp_m[2]);
    const double py = clampd(out->ground_rel_m[1], v->clamp_m[1], v->clamp_m[3]);
    const double g0x = px / cell_x_m, g0y = py / cell_y_m;
    double lc = (out->r_cells > 1.0) ? log2(out->r_cells) : 0.0;
    lc = fmax(lc, ft_pgm_clip_resident(v, g0x, g0y));
    const double top = (double)(v->levels - 1u);
    const double level = fmin(floor(lc), top);
    const double w = (level >= top) ? 0.0 : clampd(lc - level, 0.0, 1.0);
    out->level = (uint32_t)level;
    out->parent_w = w;
    out->grid[0] = g0x;
    out->grid[1] = g0y;
    double hgt = clip_sample(v, out->level, g0x, g0y, NULL);
    if (w > 0.0) {
        hgt += (clip_sample(v, out->level + 1u, g0x, g0y, NULL) - hgt) * w;
    }
    out->height_m = hgt;
    out->pos_rel_eye_m[0] = px;
    out->pos_rel_eye_m[1] = py;
    out->pos_rel_eye_m[2] = hgt - s->eye_m[2] - curv_drop_per_m2 * (px * px + py * py);
}

int ft_pgm_atlas_layout(const ft_terrain *t, uint32_t origin_px[][2], uint32_t *width_px,
                        uint32_t *height_px)
{
    const ft_pyramid *p = &t->pyr;
    *width_px = *height_px = 0u;
    if (p->avg_levels < 2u) {
        return 0;
    }
    origin_px[0][0] = origin_px[0][1] = 0u; /* level 0 lives in the heights texture */
    origin_px[1][0] = origin_px[1][1] = 0u;
    uint32_t w = p->avg[1].width, hcol = 0u, wcol = 0u;
    for (uint32_t l = 2u; l < p->avg_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        origin_px[l][0] = p->avg[1].width;
        origin_px[l][1] = hcol;
        hcol += p->avg[l].height;
        wcol = (p->avg[l].width > wcol) ? p->avg[l].width : wcol;
    }
    *width_px = w + wcol;
    *height_px = (p->avg[1].height > hcol) ? p->avg[1].height : hcol;
    return 1;
}
