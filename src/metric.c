/* metric.c - screen-space error of a rendered position buffer (metric.h). */
#include "metric.h"

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

ft_status ft_metric_compute(const ft_terrain *t, const ft_camera *c, const float *pos_rgba,
                            const ft_ref_pixel *ref, float *scratch, size_t scratch_cap,
                            ft_error_stats *out, ft_error *err)
{
    if (t == NULL || c == NULL || pos_rgba == NULL || out == NULL || scratch == NULL) {
        return ft_fail(err, FT_ERR_ARG, "metric: NULL terrain, camera, positions, scratch or out");
    }
    if (t->heights_m == NULL || t->width < FT_GRID_SIDE_MIN || t->height < FT_GRID_SIDE_MIN ||
        !(t->cell_x_m > 0.0) || !(t->cell_y_m > 0.0)) {
        return ft_fail(err, FT_ERR_ARG, "metric: terrain %ux%u has no heights or bad spacing",
                       t->width, t->height);
    }
    size_t n = (size_t)c->width_px * c->height_px;
    if (n == 0u || scratch_cap < n) {
        return ft_fail(err, FT_ERR_ARG, "metric: %ux%u pixels need %zu scratch floats, %zu given",
                       c->width_px, c->height_px, n, scratch_cap);
    }
    double k_px = c->px_per_rad_k;
    double near_m = c->near_m;
    if (!isfinite(k_px) || !(k_px > 0.0) || !isfinite(near_m) || !(near_m > 0.0)) {
        return ft_fail(err, FT_ERR_NUMERIC, "metric: camera K %g or near %g not positive finite",
                       k_px, near_m);
    }
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(c->eye_m[i])) {
            return ft_fail(err, FT_ERR_NUMERIC, "metric: eye coordinate %d not finite", i);
        }
    }

    ft_error_stats s = {0};
    size_t m = 0; /* finite terrain pixels, errors in scratch[0..m) */
    double sum = 0.0, mx = 0.0;
    for (size_t p = 0; p < n; ++p) {
        const float *q = pos_rgba + 4u * p;
        int terrain = q[3] > 0.5f;
        if (ref != NULL) {
            if (terrain && !ref[p].hit) ++s.only_method_px;
            if (!terrain && ref[p].hit) ++s.only_ref_px;
        }
        if (!terrain) {
            continue;
        }
        ++s.terrain_px;
        if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) {
            ++s.nonfinite_px;
            continue;
        }
        double rx = q[0], ry = q[1], rz = q[2];
        double wx = c->eye_m[0] + rx, wy = c->eye_m[1] + ry, wz = c->eye_m[2] + rz;
        if (!ft_terrain_contains(t, wx, wy)) {
            ++s.outside_grid_px;
        }
        double h = ft_terrain_height_at(t, wx, wy);
        double dist = sqrt(rx * rx + ry * ry + rz * rz);
        if (dist < near_m) dist = near_m;
        double e = fabs(wz - h) * k_px / dist;
        if (!(e <= (double)FLT_MAX)) e = (double)FLT_MAX; /* also a NaN height */
        scratch[m++] = (float)e;
        sum += e;
        if (e > mx) mx = e;
    }
    if (m > 0u) {
        s.mean_px = sum / (double)m;
        s.p999_px = select_kth(scratch, m, ft_metric_p999_rank(m));
    }
    s.max_px = s.nonfinite_px > 0u ? INFINITY : mx;
    *out = s;
    return FT_OK;
}
