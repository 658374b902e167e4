/* metric.c - screen-space error of a rendered position buffer (metric.h). */
#include "measure/metric.h"

#include <float.h>
#include <math.h>

size_t ft_metric_p999_rank(size_t n)
{
    if (n == 0u) {
        return 0u;
    }
    /* ceil(999 n / 1000) - 1; n <= 2^54 keeps 999 n in range */
    uint64_t nn = (uint64_t)n;
    return (size_t)((nn * 999u + 999u) / 1000u - 1u);
}

static void swap_f(float *a, float *b)
{
    float t = *a;
    *a = *b;
    *b = t;
}

/* k-th smallest of a[0..n) (n >= 1, k < n, no NaN), partially reorders a.
 * Iterative Hoare quickselect with a median-of-three pivot. Bound: every
 * pass shrinks [lo, hi] by at least one element (the first swap always
 * happens because a[lo] <= pivot <= a[hi] after the median sort), so at most
 * n passes of at most n steps; expected O(n). */
static float select_kth(float *a, size_t n, size_t k)
{
    int64_t lo = 0, hi = (int64_t)n - 1, kk = (int64_t)k;
    for (size_t pass = 0; pass < n && hi > lo; ++pass) {
        int64_t mid = lo + (hi - lo) / 2;
        if (a[mid] < a[lo]) swap_f(&a[mid], &a[lo]);
        if (a[hi] < a[lo]) swap_f(&a[hi], &a[lo]);
        if (a[hi] < a[mid]) swap_f(&a[hi], &a[mid]);
        float pivot = a[mid];
        int64_t i = lo, j = hi;
        /* inner scans are bounded by the sentinels a[lo] <= pivot <= a[hi]
         * and by the swapped elements; i <= hi + 1, j >= lo - 1 */
        while (i <= j) {
            while (a[i] < pivot) ++i;
            while (a[j] > pivot) --j;
            if (i <= j) {
                swap_f(&a[i], &a[j]);
                ++i;
                --j;
            }
        }
        /* now a[lo..j] <= pivot <= a[i..hi], and a[j+1..i-1] == pivot */
        if (kk <= j) {
            hi = j;
        } else if (kk >= i) {
            lo = i;
        } else {
            return a[kk];
        }
    }
    return a[kk];
}

/* Pixel classes for the distance transform. */
enum { PX_SKY_BOTH = 0, PX_AGREE, PX_OCCLUDED, PX_COVERAGE, PX_SKY_ONLY_REF };

/* "No agreeing pixel" in the squared-distance image: larger than any
 * squared distance inside the largest image (65536^2 pixels: 8.6e9). */
#define NO_SEED_PX2 1e18f

typedef struct metric_scratch {
    float *err_px;   /* per pixel; compacted to the finite terrain errors */
    float *dist2;    /* squared distance to the nearest agreeing pixel */
    uint8_t *cls;    /* PX_* */
    double *line_f;  /* one line of dist2 (max side) */
    double *line_z;  /* parabola boundaries (max side + 1) */
    int32_t *line_v; /* parabola apexes (max side) */
} metric_scratch;

size_t ft_metric_scratch_bytes(uint32_t width_px, uint32_t height_px)
{
    uint64_t n = (uint64_t)width_px * height_px;
    uint64_t side = (uint64_t)(width_px > height_px ? width_px : height_px) + 1u;
    uint64_t bytes = side * (2u * sizeof(double) + sizeof(int32_t)) + n * (2u * sizeof(float) + 1u);
    if (width_px > 65536u || height_px > 65536u || bytes > (uint64_t)SIZE_MAX) {
        return 0u;
    }
    return (size_t)bytes;
}

/* Layout: the line arrays (doubles first, for alignment), then the per-pixel
 * floats, then the class bytes. */
static int split_scratch(void *scratch, size_t bytes, uint32_t w, uint32_t h, metric_scratch *m)
{
    size_t need = ft_metric_scratch_bytes(w, h);
    if (scratch == NULL || need == 0u || bytes < need ||
        ((uintptr_t)scratch % sizeof(double)) != 0u) {
        return 0;
    }
    size_t n = (size_t)w * h, side = (size_t)(w > h ? w : h) + 1u;
    m->line_f = scratch;
    m->line_z = m->line_f + side;
    m->line_v = (int32_t *)(void *)(m->line_z + side);
    m->err_px = (float *)(void *)(m->line_v + side);
    m->dist2 = m->err_px + n;
    m->cls = (uint8_t *)(void *)(m->dist2 + n);
    return 1;
}

/* Exact 1-D squared distance transform (lower envelope of parabolas,
 * Felzenszwalb & Huttenlocher) of the strided line base[0..n), in place.
 * Bounded: each index enters the envelope once and leaves it at most once. */
static void edt_line(const metric_scratch *m, float *base, size_t n, size_t stride)
{
    double *f = m->line_f;
    double *z = m->line_z;
    int32_t *v = m->line_v;
    for (size_t q = 0; q < n; ++q) {
        f[q] = base[q * stride];
    }
    size_t k = 0;
    int have = 0;
    for (size_t q = 0; q < n; ++q) {
        if (!(f[q] < (double)NO_SEED_PX2)) {
            continue;
        }
        if (!have) {
            v[0] = (int32_t)q;
            z[0] = -INFINITY;
            z[1] = INFINITY;
            have = 1;
            continue;
        }
        const double dq = (double)q;
        double s;
        for (;;) { /* z[0] = -inf stops it at k = 0: at most k + 1 pops */
            const double dv = (double)v[k];
            s = ((f[q] + dq * dq) - (f[v[k]] + dv * dv)) / (2.0 * (dq - dv));
            if (s > z[k]) {
                break;
            }
            --k;
        }
        ++k;
        v[k] = (int32_t)q;
        z[k] = s;
        z[k + 1u] = INFINITY;
    }
    if (!have) {
        return; /* no seed on this line: it stays NO_SEED_PX2 */
    }
    k = 0;
    for (size_t q = 0; q < n; ++q) {
        while (z[k + 1u] < (double)q) {
            ++k;
        }
        const double d = (double)q - (double)v[k];
        base[q * stride] = (float)(d * d + f[v[k]]);
    }
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double ft_metric_projected_px(const ft_camera *c, const double a[3], const double b[3])
{
    double diag = sqrt((double)c->width_px * c->width_px + (double)c->height_px * c->height_px);
    double za = dot3(a, c->forward), zb = dot3(b, c->forward);
    if (!(za > 1e-9) || !(zb > 1e-9)) {
        return diag;
    }
    double dx = dot3(a, c->right) / za - dot3(b, c->right) / zb;
    double dy = dot3(a, c->up) / za - dot3(b, c->up) / zb;
    double e = c->px_per_rad_k * sqrt(dx * dx + dy * dy);
    return (e < diag || !(e == e)) ? e : diag;
}

/* 1 if the drawn point p (camera-relative, at vertical error dz_m from the
 * truth) and the reference hit r lie on different surfaces (metric.h). */
static int on_other_surface(const ft_terrain *t, const ft_camera *c, const double p[3],
                            const ft_ref_pixel *r, double dz_m)
{
    double t_p = sqrt(dot3(p, p));
    double t_r = r->dist_m;
    double rel[3] = {r->pos_rel_eye_m[0], r->pos_rel_eye_m[1], r->pos_rel_eye_m[2]};
    double gx, gy;
    ft_terrain_gradient_at(t, c->eye_m[0] + rel[0], c->eye_m[1] + rel[1], &gx, &gy);
    gx += 2.0 * t->curv_drop_per_m2 * rel[0]; /* the curved truth's slope */
    gy += 2.0 * t->curv_drop_per_m2 * rel[1];
    double nl = sqrt(gx * gx + gy * gy + 1.0);
    double n[3] = {-gx / nl, -gy / nl, 1.0 / nl};
    double len = sqrt(dot3(rel, rel));
    double cos_in = (len > 0.0) ? fabs(dot3(rel, n)) / len : 1.0;
    double slack = 1e-4 * t_r + 0.05;
    double gap = fabs(t_p - t_r);
    if (gap <= slack) {
        return 0;
    }
    /* gap > slack + 2 dz n_z / cos_in, without dividing by a grazing cos */
    return (gap - slack) * cos_in > 2.0 * dz_m * n[2];
}

ft_status ft_metric_compute(const ft_terrain *t, const ft_camera *c, const float *pos_rgba,
                            const ft_ref_pixel *ref, void *scratch, size_t scratch_bytes,
                            ft_error_stats *out, ft_error *err)
{
    if (t == NULL || c == NULL || pos_rgba == NULL || out == NULL || scratch == NULL) {
        return ft_fail(err, FT_ERR_ARG, "metric: NULL terrain, camera, positions, scratch or out");
    }
    if (t->heights_m == NULL || t->width < FT_GRID_SIDE_MIN || t->height < FT_GRID_SIDE_MIN ||
        !(t->cell_x_m > 0.0) || !(t->cell_y_m > 0.0) || !isfinite(t->curv_drop_per_m2) ||
        t->curv_drop_per_m2 < 0.0) {
        return ft_fail(err, FT_ERR_ARG, "metric: terrain %ux%u has no heights, bad spacing or curvature",
                       t->width, t->height);
    }
    const uint32_t w = c->width_px, h = c->height_px;
    const size_t n = (size_t)w * h;
    metric_scratch ms;
    if (n == 0u || !split_scratch(scratch, scratch_bytes, w, h, &ms)) {
        return ft_fail(err, FT_ERR_ARG, "metric: %ux%u pixels need %zu scratch bytes, %zu given",
                       w, h, ft_metric_scratch_bytes(w, h), scratch_bytes);
    }
    const double k_px = c->px_per_rad_k;
    if (!isfinite(k_px) || !(k_px > 0.0)) {
        return ft_fail(err, FT_ERR_NUMERIC, "metric: camera K %g not positive finite", k_px);
    }
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(c->eye_m[i])) {
            return ft_fail(err, FT_ERR_NUMERIC, "metric: eye coordinate %d not finite", i);
        }
    }
    const double diag_px = sqrt((double)w * w + (double)h * h);
    const double curv = t->curv_drop_per_m2;

    /* Pass 1: per pixel its class and vertical error (-1: not terrain, or
     * not finite); agreeing pixels seed the distance transform. */
    ft_error_stats s = {0};
    uint32_t occluded = 0;
    for (size_t p = 0; p < n; ++p) {
        const float *q = pos_rgba + 4u * p;
        const int terrain = q[3] > 0.5f;
        const int ref_hit = (ref != NULL) && ref[p].hit;
        uint8_t cls = PX_SKY_BOTH;
        ms.err_px[p] = -1.0f;
        if (!terrain) {
            cls = ref_hit ? PX_SKY_ONLY_REF : PX_SKY_BOTH;
            s.only_ref_px += ref_hit ? 1u : 0u;
        } else {
            ++s.terrain_px;
            cls = (ref != NULL && !ref_hit) ? PX_COVERAGE : PX_AGREE;
            s.only_method_px += (ref != NULL && !ref_hit) ? 1u : 0u;
            if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) {
                ++s.nonfinite_px;
            } else {
                double pr[3] = {q[0], q[1], q[2]};
                double wx = c->eye_m[0] + pr[0], wy = c->eye_m[1] + pr[1];
                if (!ft_terrain_contains(t, wx, wy)) {
                    ++s.outside_grid_px;
                }
                double z_true = ft_terrain_height_at(t, wx, wy) - c->eye_m[2] -
                                curv * (pr[0] * pr[0] + pr[1] * pr[1]);
                double pt[3] = {pr[0], pr[1], z_true};
                double e = ft_metric_projected_px(c, pr, pt);
                if (!(dot3(pt, c->forward) > 1e-9)) {
                    ++s.behind_eye_px;
                }
                if (!(e <= diag_px)) e = diag_px; /* also a NaN height */
                ms.err_px[p] = (float)e;
                if (ms.err_px[p] > s.vertical_max_px) s.vertical_max_px = ms.err_px[p];
                if (ref_hit && on_other_surface(t, c, pr, &ref[p], fabs(pr[2] - z_true))) {
                    cls = PX_OCCLUDED;
                    ++occluded;
                }
            }
        }
        ms.cls[p] = cls;
        ms.dist2[p] = (cls == PX_SKY_BOTH || cls == PX_AGREE) ? 0.0f : NO_SEED_PX2;
    }
    s.occlusion_px = occluded;

    /* Pass 2 (only with occlusion mismatches): distance to the nearest
     * agreeing pixel, columns then rows. */
    if (occluded > 0u) {
        for (uint32_t x = 0; x < w; ++x) {
            edt_line(&ms, ms.dist2 + x, h, w);
        }
        for (uint32_t y = 0; y < h; ++y) {
            edt_line(&ms, ms.dist2 + (size_t)y * w, w, 1u);
        }
    }

    /* Pass 3: each finite terrain pixel's error, compacted in place for the
     * percentile (m <= p always). */
    size_t m = 0;
    double sum = 0.0, mx = 0.0;
    for (size_t p = 0; p < n; ++p) {
        double e = ms.err_px[p];
        if (e < 0.0) {
            continue;
        }
        if (ms.cls[p] == PX_OCCLUDED) {
            double d2 = ms.dist2[p];
            double eo = (d2 < (double)NO_SEED_PX2) ? sqrt(d2) - 0.5 : diag_px;
            if (eo > diag_px) eo = diag_px;
            if (eo > s.occlusion_max_px) s.occlusion_max_px = eo;
            if (eo > e) e = eo;
        }
        ms.err_px[m++] = (float)e;
        sum += e;
        if (e > mx) mx = e;
    }
    if (m > 0u) {
        s.mean_px = sum / (double)m;
        s.p999_px = select_kth(ms.err_px, m, ft_metric_p999_rank(m));
    }
    s.max_px = s.nonfinite_px > 0u ? INFINITY : mx;
    *out = s;
    return FT_OK;
}
