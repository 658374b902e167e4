/* import_dev.c - the deviation pass of the database importer (import_dev.h).
 *
 * "Resolves at level m": the runtime's rule takes a point's truth from
 * level m (its data, or m's bilinear value between samples that have data).
 * For a level-k cell c, the reference ref is B_k when c's 4 corners have
 * data, else the constant r (terrain_db.h). Over each level-(k-1) sub-cell
 * c' of c, the points that matter (all of c' when ref is B_k, those
 * resolving finer than k when it is r) obey:
 *   - points resolving at level k-1 (a bilinear mix of c''s corners that
 *     have data, weights summing to 1): |T - ref| <= the largest
 *     |v(s) - ref(s)| over those corners s ("near");
 *   - points resolving finer than k-1: when c' has 4 data corners, its dev
 *     bounds |T - B_(k-1)|, and B_(k-1) - ref is bilinear on c': dev + near;
 *     when c' is at a data edge, its dev bounds |T - r'|: dev + the largest
 *     |r' - ref| over c' (ref is bilinear or constant there, extreme at a
 *     corner); COARSER: there are none;
 *   - points resolving at level k or coarser: 0 against B_k (B_k is their
 *     truth when c's corners have data), not counted against r.
 * dev(c) is the largest term over its 4 sub-cells. A corner of c' without
 * data resolves at level k (when c's corners have data) or coarser: it adds
 * nothing. A cell at a data edge with no finer data (no level-(k-1) data off
 * the level-k points, every sub-cell COARSER) is COARSER. A level-(k-1) tile
 * without data has COARSER cells when nothing under it has data, else NONE,
 * which makes the cells above it NONE. */
#define _POSIX_C_SOURCE 200809L
#include "import_dev.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#include "core/byte_codec.h"
#include "terrain/terrain.h"

int ft_dev_pass_init(ft_dev_pass *P, FILE *f, const char *path, const ft_tdb_header *hdr,
                     ft_tdb_entry *entries, const uint8_t *subtree_data)
{
    memset(P, 0, sizeof *P);
    P->f = f;
    P->path = path;
    P->hdr = hdr;
    P->entries = entries;
    P->subtree_data = subtree_data;
    const size_t T = hdr->tile_samples;
    P->T = (uint32_t)T;
    P->hk = malloc((T + 1u) * (T + 1u) * sizeof(float));
    P->hc = malloc((2u * T + 1u) * (2u * T + 1u) * sizeof(float));
    P->dc = malloc(4u * T * T * sizeof(float));
    P->tile_h = malloc(T * T * sizeof(float));
    P->tile_dev = malloc(T * T * sizeof(float));
    P->dev_out = malloc(T * T * sizeof(float));
    P->bits = malloc(T * T / 8u);
    P->measured = malloc(T * T * sizeof(double));
    P->seen = malloc(T * T * sizeof(uint64_t));
    P->exact = malloc(T * T * sizeof(double));
    P->bytes_cap = ft_tdb_tile_bytes((uint32_t)T, 1u, 1u);
    P->bytes = malloc(P->bytes_cap);
    return P->hk != NULL && P->hc != NULL && P->dc != NULL && P->tile_h != NULL &&
           P->tile_dev != NULL && P->dev_out != NULL && P->bits != NULL && P->bytes != NULL &&
           P->measured != NULL && P->seen != NULL && P->exact != NULL;
}

void ft_dev_pass_free(ft_dev_pass *P)
{
    free(P->hk);
    free(P->hc);
    free(P->dc);
    free(P->tile_h);
    free(P->tile_dev);
    free(P->dev_out);
    free(P->bits);
    free(P->bytes);
    free(P->measured);
    free(P->seen);
    free(P->exact);
    memset(P, 0, sizeof *P);
}

/* Index of tile (k, tx, ty) in the entries, or -1 when the index does not
 * list it (past the lattice as well: wrap_columns reads across 180 deg). */
static int64_t entry_index(const ft_dev_pass *P, uint32_t k, uint64_t tx, uint64_t ty)
{
    const ft_tdb_level *lv = &P->hdr->levels[k];
    if (tx < lv->tx0 || ty < lv->ty0 || tx - lv->tx0 >= lv->cols || ty - lv->ty0 >= lv->rows) {
        return -1;
    }
    return (int64_t)lv->first_entry + (int64_t)((ty - lv->ty0) * lv->cols + (tx - lv->tx0));
}

/* Reads data tile n (level k) and decodes its heights (and, on k >= 1, dev;
 * with bits != NULL, its void bits). */
static int read_tile(ft_dev_pass *P, int64_t n, uint32_t k, int want_dev, uint8_t *bits)
{
    const ft_tdb_entry *e = &P->entries[n];
    const size_t cells = (size_t)P->T * P->T;
    if (e->byte_size > P->bytes_cap || fseeko(P->f, (off_t)e->offset, SEEK_SET) != 0 ||
        fread(P->bytes, 1, e->byte_size, P->f) != e->byte_size) {
        fprintf(stderr, "fixterrain import: %s: reading back tile (level %u, entry %lld) "
                        "failed\n",
                P->path, k, (long long)n);
        return 0;
    }
    for (size_t i = 0u; i < cells; ++i) {
        P->tile_h[i] = ft_le_get_f32(P->bytes + i * 4u);
    }
    const size_t bits_bytes = e->void_count > 0u ? cells / 8u : 0u;
    if (bits != NULL) {
        if (bits_bytes > 0u) {
            memcpy(bits, P->bytes + cells * 4u, bits_bytes);
        } else {
            memset(bits, 0, cells / 8u);
        }
    }
    if (want_dev && k > 0u) {
        const uint8_t *d = P->bytes + cells * 4u + bits_bytes;
        for (size_t i = 0u; i < cells; ++i) {
            P->tile_dev[i] = ft_le_get_f32(d + i * 4u);
        }
    }
    return 1;
}

/* Copies the decoded tile's samples x in [x0, x1), y in [y0, y1) into the
 * grid g (row stride gw) at (gx, gy). */
static void place(const ft_dev_pass *P, const float *src, float *g, size_t gw, uint32_t x0,
                  uint32_t x1, uint32_t y0, uint32_t y1, size_t gx, size_t gy)
{
    for (uint32_t y = y0; y < y1; ++y) {
        for (uint32_t x = x0; x < x1; ++x) {
            g[(gy + (y - y0)) * gw + gx + (x - x0)] = src[(size_t)y * P->T + x];
        }
    }
}

/* Tile (k, tx, ty)'s samples [x0, x1) x [y0, y1) into grid g at (gx, gy)
 * when it has data (left as they are otherwise). */
static int take(ft_dev_pass *P, uint32_t k, uint64_t tx, uint64_t ty, float *g, size_t gw,
                uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1, size_t gx, size_t gy)
{
    const int64_t n = entry_index(P, k, tx, ty);
    if (n < 0 || P->entries[n].state != FT_TDB_DATA) {
        return 1;
    }
    if (!read_tile(P, n, k, 0, NULL)) {
        return 0;
    }
    place(P, P->tile_h, g, gw, x0, x1, y0, y1, gx, gy);
    return 1;
}

static int has(float v)
{
    return v != FT_TDB_NODATA_M;
}

/* On a level that closes around the globe the runtime reads sample i >= nx
 * (at or east of 180 deg) as sample i - nx: the columns of grid g (cols x
 * rows from level-k sample (i0, j0), row stride gw) that lie there get
 * those samples (the tiles store their own, which it does not read). */
static int wrap_columns(ft_dev_pass *P, uint32_t k, float *g, size_t gw, uint64_t i0,
                        uint64_t j0, uint32_t cols, uint32_t rows)
{
    const uint32_t T = P->T;
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(P->hdr->samples_per_deg, k, &nx, &ny);
    if (!ft_tdb_lattice_closes(P->hdr->samples_per_deg, k) || i0 + cols <= nx) {
        return 1;
    }
    const uint64_t first = i0 > nx ? i0 : nx;
    for (uint32_t y = 0u; y < rows; ++y) {
        for (uint64_t i = first; i < i0 + cols; ++i) {
            g[(size_t)y * gw + (size_t)(i - i0)] = FT_TDB_NODATA_M;
        }
    }
    /* bounded: the columns span at most 3 tile columns, the rows 3 tile rows */
    for (uint64_t w = first - nx; w < i0 + cols - nx;) {
        const uint32_t x0 = (uint32_t)(w % T);
        const uint64_t wleft = i0 + cols - nx - w;
        const uint32_t x1 = wleft < (uint64_t)(T - x0) ? x0 + (uint32_t)wleft : T;
        for (uint64_t j = j0; j < j0 + rows;) {
            const uint32_t y0 = (uint32_t)(j % T);
            const uint64_t left = j0 + rows - j;
            const uint32_t y1 = left < (uint64_t)(T - y0) ? y0 + (uint32_t)left : T;
            if (!take(P, k, w / T, j / T, g, gw, x0, x1, y0, y1, (size_t)(w + nx - i0),
                      (size_t)(j - j0))) {
                return 0;
            }
            j += y1 - y0;
        }
        w += x1 - x0;
    }
    return 1;
}

/* Samples of grid g (cols x rows from level-k sample (i0, j0)) past the
 * lattice lack data, as the runtime reads them: north of the pole row, and
 * at or east of 180 deg on a level that does not close (one that closes
 * has them from wrap_columns). */
static void mask_past_lattice(const ft_dev_pass *P, uint32_t k, float *g, uint32_t cols,
                              uint32_t rows, uint64_t i0, uint64_t j0)
{
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(P->hdr->samples_per_deg, k, &nx, &ny);
    const int closes = ft_tdb_lattice_closes(P->hdr->samples_per_deg, k);
    for (uint32_t y = 0u; y < rows; ++y) {
        for (uint32_t x = 0u; x < cols; ++x) {
            const uint64_t i = i0 + x, j = j0 + y;
            if (j >= ny || (i >= nx && !closes)) {
                g[(size_t)y * cols + x] = FT_TDB_NODATA_M;
            }
        }
    }
}

/* Level k's heights under tile (tx, ty) with the east and north apron. */
static int load_level(ft_dev_pass *P, uint32_t k, uint32_t tx, uint32_t ty)
{
    const uint32_t T = P->T;
    const size_t w = T + 1u;
    for (size_t i = 0u; i < w * w; ++i) {
        P->hk[i] = FT_TDB_NODATA_M;
    }
    return take(P, k, tx, ty, P->hk, w, 0u, T, 0u, T, 0u, 0u) &&
           take(P, k, (uint64_t)tx + 1u, ty, P->hk, w, 0u, 1u, 0u, T, T, 0u) &&
           take(P, k, tx, (uint64_t)ty + 1u, P->hk, w, 0u, T, 0u, 1u, 0u, T) &&
           take(P, k, (uint64_t)tx + 1u, (uint64_t)ty + 1u, P->hk, w, 0u, 1u, 0u, 1u, T, T) &&
           wrap_columns(P, k, P->hk, w, (uint64_t)tx * T, (uint64_t)ty * T, T + 1u, T + 1u) &&
           (mask_past_lattice(P, k, P->hk, T + 1u, T + 1u, (uint64_t)tx * T, (uint64_t)ty * T),
            1);
}

/* Level k-1 under tile (k, tx, ty): heights of the 2x2 children and their
 * apron into hc, the children's cell devs into dc. */
static int load_children(ft_dev_pass *P, uint32_t k, uint32_t tx, uint32_t ty)
{
    const uint32_t T = P->T, c = k - 1u;
    const size_t w = 2u * T + 1u, dw = 2u * T;
    for (size_t i = 0u; i < w * w; ++i) {
        P->hc[i] = FT_TDB_NODATA_M;
    }
    const uint64_t cx = 2u * (uint64_t)tx, cy = 2u * (uint64_t)ty;
    for (uint32_t b = 0u; b < 2u; ++b) {
        for (uint32_t a = 0u; a < 2u; ++a) {
            const int64_t n = entry_index(P, c, cx + a, cy + b);
            const int data = n >= 0 && P->entries[n].state == FT_TDB_DATA;
            P->child_avg_m[b][a] = data ? (double)P->entries[n].avg_m : 0.0;
            if (data && !read_tile(P, n, c, 1, NULL)) {
                return 0;
            }
            if (data) {
                place(P, P->tile_h, P->hc, w, 0u, T, 0u, T, (size_t)a * T, (size_t)b * T);
            }
            if (c == 0u) {
                continue; /* level 0's cells: from hc below */
            }
            if (data) {
                place(P, P->tile_dev, P->dc, dw, 0u, T, 0u, T, (size_t)a * T, (size_t)b * T);
                continue;
            }
            const float fill = (n >= 0 && P->subtree_data[n]) ? FT_TDB_DEV_NONE
                                                               : FT_TDB_DEV_COARSER;
            for (uint32_t y = 0u; y < T; ++y) {
                for (uint32_t x = 0u; x < T; ++x) {
                    P->dc[((size_t)b * T + y) * dw + (size_t)a * T + x] = fill;
                }
            }
        }
    }
    for (uint32_t a = 0u; a < 2u; ++a) {
        if (!take(P, c, cx + 2u, cy + a, P->hc, w, 0u, 1u, 0u, T, 2u * T, (size_t)a * T) ||
            !take(P, c, cx + a, cy + 2u, P->hc, w, 0u, T, 0u, 1u, (size_t)a * T, 2u * T)) {
            return 0;
        }
    }
    if (!take(P, c, cx + 2u, cy + 2u, P->hc, w, 0u, 1u, 0u, 1u, 2u * T, 2u * T)) {
        return 0;
    }
    if (!wrap_columns(P, c, P->hc, w, cx * T, cy * T, 2u * T + 1u, 2u * T + 1u)) {
        return 0;
    }
    mask_past_lattice(P, c, P->hc, 2u * T + 1u, 2u * T + 1u, cx * T, cy * T);
    if (c == 0u) {
        for (size_t y = 0u; y < dw; ++y) {
            for (size_t x = 0u; x < dw; ++x) {
                const float *r0 = P->hc + y * w + x, *r1 = r0 + w;
                const int all = has(r0[0]) && has(r0[1]) && has(r1[0]) && has(r1[1]);
                P->dc[y * dw + x] = all ? 0.0f : FT_TDB_DEV_COARSER;
            }
        }
    }
    return 1;
}

/* Round a bound up to float, capped at the height range (no two heights
 * differ more: still a bound). */
static float bound_up(double v)
{
    if (v >= (double)FT_TDB_DEV_MAX_M) {
        return FT_TDB_DEV_MAX_M;
    }
    float f = (float)v;
    if ((double)f < v) {
        f = nextafterf(f, INFINITY);
    }
    return f;
}

/* The 2x2 samples of grid g (row stride gw) at (x, y) that have data: their
 * mean in *mean (when any), their count returned. */
static int data_corners(const float *g, size_t gw, size_t x, size_t y, double *mean)
{
    const float c[4] = {g[y * gw + x], g[y * gw + x + 1u], g[(y + 1u) * gw + x],
                        g[(y + 1u) * gw + x + 1u]};
    double sum = 0.0;
    int n = 0;
    for (int q = 0; q < 4; ++q) {
        if (has(c[q])) {
            sum += (double)c[q];
            ++n;
        }
    }
    *mean = n > 0 ? sum / (double)n : 0.0;
    return n;
}

/* The dev of level-k cell (i, j) of the loaded tile (terrain_db.h): against
 * B_k when its corners have data, else against its reference r (the mean of
 * its corners with data, or tile_avg_m). */
static float cell_dev(const ft_dev_pass *P, uint32_t i, uint32_t j, double tile_avg_m,
                      int *partial)
{
    const size_t kw = P->T + 1u, cw = 2u * P->T + 1u, dw = 2u * P->T;
    double r = 0.0;
    const int corners = data_corners(P->hk, kw, i, j, &r);
    *partial = corners < 4;
    if (corners == 0) {
        r = tile_avg_m;
    }
    const float *k0 = P->hk + (size_t)j * kw + i, *k1 = k0 + kw;
    const double h00 = k0[0], h10 = k0[1], h01 = k1[0], h11 = k1[1];
    const size_t ci = 2u * (size_t)i, cj = 2u * (size_t)j;
    int finer = 0;
    double worst = 0.0;
    for (size_t b = 0u; b < 2u; ++b) {
        for (size_t a = 0u; a < 2u; ++a) {
            const float d = P->dc[(cj + b) * dw + ci + a];
            if (d == FT_TDB_DEV_NONE) {
                return FT_TDB_DEV_NONE;
            }
            double sub_r = 0.0;
            const int sub_corners = data_corners(P->hc, cw, ci + a, cj + b, &sub_r);
            if (sub_corners == 0) {
                sub_r = P->child_avg_m[b][a];
            }
            /* reference at each sub-cell corner: B_k there, or r */
            double near = 0.0;      /* largest |v - ref| over the data corners */
            double ref_lo = INFINITY, ref_hi = -INFINITY;
            for (size_t v = 0u; v < 2u; ++v) {
                for (size_t u = 0u; u < 2u; ++u) {
                    double ref = r;
                    if (corners == 4) {
                        const double fx = 0.5 * (double)(a + u), fy = 0.5 * (double)(b + v);
                        ref = (1.0 - fy) * ((1.0 - fx) * h00 + fx * h10) +
                              fy * ((1.0 - fx) * h01 + fx * h11);
                    }
                    ref_lo = ref < ref_lo ? ref : ref_lo;
                    ref_hi = ref > ref_hi ? ref : ref_hi;
                    const float sv = P->hc[(cj + b + v) * cw + ci + a + u];
                    const int odd = ((a + u) | (b + v)) & 1u;
                    finer |= odd && has(sv);
                    if (has(sv)) {
                        const double diff = fabs((double)sv - ref);
                        near = diff > near ? diff : near;
                    }
                    /* a corner without data: its truth is a coarser level's
                     * (B_k itself when the cell's corners have data) */
                }
            }
            double term = near;
            if (d != FT_TDB_DEV_COARSER) {
                finer = 1;
                if (sub_corners == 4) {
                    term = (double)d + near; /* |T - B_(k-1)| + |B_(k-1) - ref| */
                } else {
                    /* |T - sub_r| over its finer points, + |sub_r - ref| */
                    const double shift =
                        fabs(sub_r - ref_lo) > fabs(sub_r - ref_hi) ? fabs(sub_r - ref_lo)
                                                                    : fabs(sub_r - ref_hi);
                    term = (double)d + shift > near ? (double)d + shift : near;
                }
            }
            worst = term > worst ? term : worst;
        }
    }
    if (corners < 4 && !finer) {
        return FT_TDB_DEV_COARSER;
    }
    return bound_up(worst);
}

/* The finest level m with data under tile (k, tx, ty)'s closed footprint:
 * no tile of level m-1 there (nor under it) has data. 0 when level 0 has. */
static uint32_t finest_under(const ft_dev_pass *P, uint32_t k, uint32_t tx, uint32_t ty)
{
    for (uint32_t m = 1u; m < k; ++m) {
        const uint64_t span = (uint64_t)1u << (k - m + 1u); /* level m-1 tiles per side */
        int any = 0;
        /* bounded: at most (2^(k-m+1) + 1)^2 index lookups */
        for (uint64_t y = (uint64_t)ty * span; y <= (uint64_t)ty * span + span && !any; ++y) {
            for (uint64_t x = (uint64_t)tx * span; x <= (uint64_t)tx * span + span && !any;
                 ++x) {
                const int64_t n = entry_index(P, m - 1u, x, y);
                any = n >= 0 && P->subtree_data[n];
            }
        }
        if (any) {
            return m - 1u;
        }
    }
    return k;
}

/* Level m (nothing finer under the tile: finest_under) under tile (k, tx,
 * ty), measured: for each cell with 4 data corners, the largest
 * |v_m - B_k| over its level-m points that have data (measured) and their
 * number (seen; (2^(k-m) + 1)^2 when level m covers the closed cell). T is
 * level m's bilinear surface there, and T - B_k is bilinear on each level-m
 * cell, so over a covered cell this maximum is exact. Streams the level-m
 * tiles one at a time. Returns 1 when measured, 0 when skipped (the
 * footprint crosses 180 deg, where level m's columns wrap), -1 on a read
 * error. */
static int measure_from(ft_dev_pass *P, uint32_t k, uint32_t m, uint32_t tx, uint32_t ty)
{
    const uint32_t T = P->T;
    const uint64_t step = (uint64_t)1u << (k - m);
    const uint64_t i_lo = (uint64_t)tx * T * step, j_lo = (uint64_t)ty * T * step;
    const uint64_t i_hi = i_lo + (uint64_t)T * step, j_hi = j_lo + (uint64_t)T * step;
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(P->hdr->samples_per_deg, m, &nx, &ny);
    if (i_hi >= nx) {
        return 0;
    }
    memset(P->measured, 0, (size_t)T * T * sizeof *P->measured);
    memset(P->seen, 0, (size_t)T * T * sizeof *P->seen);
    const ft_tdb_level *l0 = &P->hdr->levels[m];
    const size_t kw = T + 1u;
    /* bounded: the level-0 box, clipped to the footprint */
    const uint64_t bx0 = l0->tx0, bx1 = (uint64_t)l0->tx0 + l0->cols - 1u;
    const uint64_t by0 = l0->ty0, by1 = (uint64_t)l0->ty0 + l0->rows - 1u;
    const uint64_t ax0 = i_lo / T > bx0 ? i_lo / T : bx0, ax1 = i_hi / T < bx1 ? i_hi / T : bx1;
    const uint64_t ay0 = j_lo / T > by0 ? j_lo / T : by0, ay1 = j_hi / T < by1 ? j_hi / T : by1;
    for (uint64_t y0t = ay0; y0t <= ay1 && ax0 <= ax1; ++y0t) {
        for (uint64_t x0t = ax0; x0t <= ax1; ++x0t) {
            const int64_t n = entry_index(P, m, x0t, y0t);
            if (n < 0 || P->entries[n].state != FT_TDB_DATA) {
                continue;
            }
            if (!read_tile(P, n, m, 0, NULL)) {
                return -1;
            }
            for (uint32_t y = 0u; y < T; ++y) {
                const uint64_t J = y0t * T + y;
                if (J < j_lo || J > j_hi) {
                    continue;
                }
                const uint64_t rj = J - j_lo;
                const uint64_t cj_a = rj / step < T ? rj / step : T - 1u;
                const uint64_t cj_b = (rj % step == 0u && rj > 0u) ? rj / step - 1u : cj_a;
                for (uint32_t x = 0u; x < T; ++x) {
                    const uint64_t I = x0t * T + x;
                    const float v = P->tile_h[(size_t)y * T + x];
                    if (I < i_lo || I > i_hi || !has(v)) {
                        continue;
                    }
                    const uint64_t ri = I - i_lo;
                    const uint64_t ci_a = ri / step < T ? ri / step : T - 1u;
                    const uint64_t ci_b = (ri % step == 0u && ri > 0u) ? ri / step - 1u : ci_a;
                    /* the 1, 2 or 4 closed cells this point lies in */
                    for (uint64_t cj = cj_b; cj <= cj_a; ++cj) {
                        for (uint64_t ci = ci_b; ci <= ci_a; ++ci) {
                            const float *k0 = P->hk + cj * kw + ci, *k1 = k0 + kw;
                            if (!has(k0[0]) || !has(k0[1]) || !has(k1[0]) || !has(k1[1])) {
                                continue;
                            }
                            const double fx = (double)(ri - ci * step) / (double)step;
                            const double fy = (double)(rj - cj * step) / (double)step;
                            const double b = (1.0 - fy) * ((1.0 - fx) * k0[0] + fx * k0[1]) +
                                             fy * ((1.0 - fx) * k1[0] + fx * k1[1]);
                            const double e = fabs((double)v - b);
                            const size_t c = (size_t)(cj * T + ci);
                            P->measured[c] = e > P->measured[c] ? e : P->measured[c];
                            P->seen[c]++;
                        }
                    }
                }
            }
        }
    }
    return 1;
}

/* P->exact: per cell of tile (k, tx, ty), the exact largest |T - B_k|
 * where it can be measured, else -1. A cell's truth is the finest level j
 * with data in the closed cell when j covers all of it (no finer data, so
 * every point resolves at j); its measured maximum is then exact. Levels
 * from k-2 down to the finest under the tile, each overwriting the cells
 * it has data in; levels k-1 and k are as exact by the recursion. Skipped
 * (all -1) where a level's footprint crosses 180 deg. 0 on a read error. */
static int measure_exact(ft_dev_pass *P, uint32_t k, uint32_t tx, uint32_t ty)
{
    const size_t cells = (size_t)P->T * P->T;
    for (size_t c = 0u; c < cells; ++c) {
        P->exact[c] = -1.0;
    }
    const uint32_t finest = finest_under(P, k, tx, ty);
    for (uint32_t j = k - 1u; j-- > finest && k >= 2u;) {
        const int r = measure_from(P, k, j, tx, ty);
        if (r < 0) {
            return 0;
        }
        if (r == 0) {
            for (size_t c = 0u; c < cells; ++c) {
                P->exact[c] = -1.0;
            }
            return 1;
        }
        const uint64_t full = ((uint64_t)1u << (k - j)) + 1u;
        for (size_t c = 0u; c < cells; ++c) {
            if (P->seen[c] > 0u) {
                P->exact[c] = P->seen[c] == full * full ? P->measured[c] : -1.0;
            }
        }
    }
    return 1;
}

static void note(ft_dev_stats *s, float d, int partial)
{
    if (d == FT_TDB_DEV_NONE) {
        s->none_cells++;
        return;
    }
    if (d == FT_TDB_DEV_COARSER) {
        s->coarser_cells++;
        return;
    }
    if (partial) {
        s->partial_cells++;
        return;
    }
    s->bound_cells++;
    s->sum_m += (double)d;
    s->max_m = d > s->max_m ? d : s->max_m;
    const double bin = ceil((double)d / FT_DEV_HIST_STEP_M);
    s->hist[bin >= (double)FT_DEV_HIST_BINS ? FT_DEV_HIST_BINS : (size_t)bin]++;
}

double ft_dev_stats_quantile(const ft_dev_stats *s, double q)
{
    if (s->bound_cells == 0u) {
        return 0.0;
    }
    const double want = q * (double)s->bound_cells;
    uint64_t seen = 0u;
    for (uint32_t b = 0u; b < FT_DEV_HIST_BINS; ++b) {
        seen += s->hist[b];
        if ((double)seen >= want) {
            return (double)b * FT_DEV_HIST_STEP_M;
        }
    }
    return (double)s->max_m;
}

int ft_dev_pass_level(ft_dev_pass *P, uint32_t k, ft_dev_stats *s)
{
    const ft_tdb_level *lv = &P->hdr->levels[k];
    const uint32_t T = P->T;
    for (uint32_t r = 0u; r < lv->rows; ++r) {
        for (uint32_t c = 0u; c < lv->cols; ++c) {
            const uint32_t tx = lv->tx0 + c, ty = lv->ty0 + r;
            const int64_t n = (int64_t)lv->first_entry + (int64_t)r * lv->cols + c;
            ft_tdb_entry *e = &P->entries[n];
            if (e->state != FT_TDB_DATA) {
                continue;
            }
            if (!load_level(P, k, tx, ty) || !load_children(P, k, tx, ty)) {
                return 0;
            }
            /* levels k-1 and k measure as exactly by the recursion */
            if (!measure_exact(P, k, tx, ty)) {
                return 0;
            }
            for (uint32_t j = 0u; j < T; ++j) {
                for (uint32_t i = 0u; i < T; ++i) {
                    int partial = 0;
                    const size_t cell = (size_t)j * T + i;
                    float d = cell_dev(P, i, j, (double)e->avg_m, &partial);
                    if (!partial && d >= 0.0f && P->exact[cell] >= 0.0) {
                        const float exact_m = bound_up(P->exact[cell]);
                        d = exact_m < d ? exact_m : d;
                    }
                    P->dev_out[cell] = d;
                    note(s, d, partial);
                }
            }
            /* the tile again with its dev: same size, new crc; the
             * footprint bounds and offset stay */
            if (!read_tile(P, n, k, 0, P->bits)) {
                return 0;
            }
            const ft_tdb_entry kept = *e;
            char what[512];
            (void)snprintf(what, sizeof what, "%s: tile (level %u, %u, %u)", P->path, k, tx, ty);
            ft_error err;
            if (ft_tdb_encode_tile(P->tile_h, P->bits, P->dev_out, T, k, P->bytes, P->bytes_cap,
                                   e, what, &err) != FT_OK) {
                fprintf(stderr, "fixterrain import: %s\n", err.text);
                return 0;
            }
            if (e->byte_size != kept.byte_size) {
                fprintf(stderr, "fixterrain import: %s: re-encoded in %u bytes, not %u\n", what,
                        e->byte_size, kept.byte_size);
                return 0;
            }
            e->offset = kept.offset;
            e->min_m = kept.min_m;
            e->max_m = kept.max_m;
            if (fseeko(P->f, (off_t)e->offset, SEEK_SET) != 0 ||
                fwrite(P->bytes, 1, e->byte_size, P->f) != e->byte_size) {
                fprintf(stderr, "fixterrain import: %s: writing its dev failed\n", what);
                return 0;
            }
        }
    }
    return 1;
}
