/* void_fill.c - 8-direction inverse-distance void fill (rule in void_fill.h).
 *
 * Only samples whose mask byte is 0 are ever read as sources and only void
 * samples are written, so the result does not depend on the scan order.
 *
 * The nearest valid sample along each direction is found without walking the
 * ray: rows are swept south to north; every line through the grid (row,
 * column, diagonal x - y = c, anti-diagonal x + y = c) carries "the hit
 * behind" of the last void swept on it (a void's hit behind is its neighbour
 * if that is valid, else the hit of that neighbour, a void swept just
 * before) and "the next valid sample ahead" (a pointer moved forward only
 * when the sweep has reached it, so over the whole sweep each pointer visits
 * each sample of its line at most once). Valid samples cost one mask test. The per-void sum is taken in the same direction order
 * (N, NE, E, SE, S, SW, W, NW) with the same weights as the plain ray walk,
 * so the result is bit-identical to it.
 *
 * Not covered by the header's rule: a void whose 8 rays all leave the grid
 * without meeting a valid sample while the grid does have valid samples (e.g.
 * the only valid sample is a knight's move away). Such a void takes the mean
 * of all valid samples, which is still order independent and deterministic. */
#include "terrain/void_fill.h"

#include <stddef.h>

/* Distance of one step in each direction: diagonals count sqrt(2). */
#define FT_SQRT2 1.41421356237309504880

/* "no valid sample on this side" for the behind / ahead markers. */
#define NONE_BEHIND (-1)
#define NONE_AHEAD INT32_MAX
/* Not looked up yet: forces the first look-ahead of a line. */
#define AHEAD_UNKNOWN (-2)

size_t ft_void_fill_scratch_bytes(uint32_t w, uint32_t h)
{
    if (w == 0u || h == 0u) {
        return 0u;
    }
    /* Sides are at most 2^32 - 1 each: this stays far below SIZE_MAX on any
     * host with a 64-bit size_t; on 32-bit hosts refuse absurd sizes. */
    uint64_t lines = (uint64_t)w + (uint64_t)h - 1u;
    uint64_t words = 2u * (uint64_t)w + 4u * lines;
    uint64_t bytes = words * sizeof(int32_t);
    if (bytes > (uint64_t)((size_t)-1)) {
        return 0u;
    }
    return (size_t)bytes;
}

static double mean_of_valid(const float *heights, const uint8_t *void_mask, size_t n)
{
    double sum = 0.0;
    size_t count = 0u;
    for (size_t k = 0u; k < n; ++k) {
        if (void_mask[k] == 0u) {
            sum += (double)heights[k];
            ++count;
        }
    }
    return count > 0u ? sum / (double)count : 0.0;
}

/* Per-line sweep state, all in caller scratch. Rows are indexed by y, so a
 * position on a column, diagonal or anti-diagonal is its y. */
typedef struct fill_lines {
    int32_t *col_below; /* [w]   S hit (y) of the last void swept in column x */
    int32_t *col_above; /* [w]   smallest valid y > current row, or NONE_AHEAD */
    int32_t *dia_below; /* [w+h-1] diagonal x - y + h - 1: SW hit of its last void */
    int32_t *dia_above; /* [w+h-1] next valid y above (NE) */
    int32_t *ant_below; /* [w+h-1] anti-diagonal x + y: SE hit of its last void */
    int32_t *ant_above; /* [w+h-1] next valid y above (NW) */
} fill_lines;

/* Moves *ahead to the smallest valid y' > y on the line through (x, y) with
 * x' = x + dxdy * (y' - y); NONE_AHEAD if the line leaves the grid first.
 * Only scans when the pointer is not already ahead of y, and then from y + 1:
 * the pointer never moves back, so a line is scanned at most once per sweep. */
static void advance_ahead(int32_t *ahead, const uint8_t *mask, uint32_t w, uint32_t h,
                          uint32_t x, uint32_t y, int dxdy)
{
    if (*ahead > (int32_t)y) {
        return;
    }
    int64_t cx = (int64_t)x, cy = (int64_t)y;
    for (uint32_t guard = 0u; guard < h; ++guard) {
        cx += dxdy;
        cy += 1;
        if (cy >= (int64_t)h || cx < 0 || cx >= (int64_t)w) {
            *ahead = NONE_AHEAD;
            return;
        }
        if (mask[(size_t)cy * w + (size_t)cx] == 0u) {
            *ahead = (int32_t)cy;
            return;
        }
    }
    *ahead = NONE_AHEAD;
}

/* Adds one ray's hit (k steps away) the way the plain ray walk does. */
static void add_hit(double *wsum, double *hsum, const float *heights, size_t idx, int64_t k,
                    double step)
{
    double wt = 1.0 / ((double)k * step);
    *wsum += wt;
    *hsum += wt * (double)heights[idx];
}

uint32_t ft_void_fill(float *heights, const uint8_t *void_mask, uint32_t w, uint32_t h,
                      void *scratch, size_t scratch_bytes, int *all_void)
{
    if (all_void != NULL) {
        *all_void = 0;
    }
    if (heights == NULL || void_mask == NULL || w == 0u || h == 0u ||
        w > (uint32_t)(INT32_MAX / 2) || h > (uint32_t)(INT32_MAX / 2)) {
        return 0u;
    }
    size_t n = (size_t)w * h;
    size_t voids = 0u;
    for (size_t k = 0u; k < n; ++k) {
        voids += (void_mask[k] != 0u);
    }
    if (voids == 0u) {
        return 0u;
    }
    if (voids == n) {
        for (size_t k = 0u; k < n; ++k) {
            heights[k] = 0.0f;
        }
        if (all_void != NULL) {
            *all_void = 1;
        }
        return (uint32_t)n;
    }
    size_t need = ft_void_fill_scratch_bytes(w, h);
    if (scratch == NULL || need == 0u || scratch_bytes < need ||
        ((uintptr_t)scratch % sizeof(int32_t)) != 0u) {
        return 0u;
    }
    const size_t lines = (size_t)w + h - 1u;
    fill_lines L;
    L.col_below = (int32_t *)scratch;
    L.col_above = L.col_below + w;
    L.dia_below = L.col_above + w;
    L.dia_above = L.dia_below + lines;
    L.ant_below = L.dia_above + lines;
    L.ant_above = L.ant_below + lines;
    for (size_t k = 0u; k < w; ++k) {
        L.col_below[k] = NONE_BEHIND;
        L.col_above[k] = AHEAD_UNKNOWN;
    }
    for (size_t k = 0u; k < lines; ++k) {
        L.dia_below[k] = NONE_BEHIND;
        L.dia_above[k] = AHEAD_UNKNOWN;
        L.ant_below[k] = NONE_BEHIND;
        L.ant_above[k] = AHEAD_UNKNOWN;
    }
    int have_mean = 0;
    double mean = 0.0;
    for (uint32_t y = 0u; y < h; ++y) {
        const uint8_t *mrow = void_mask + (size_t)y * w;
        int64_t west = NONE_BEHIND; /* W hit of the last void swept in this row */
        int64_t east = AHEAD_UNKNOWN;
        for (uint32_t x = 0u; x < w; ++x) {
            if (mrow[x] == 0u) {
                continue; /* valid samples cost one mask test: nothing to update */
            }
            const size_t idx = (size_t)y * w + x;
            const size_t dia = (size_t)x + (size_t)(h - 1u - y);
            const size_t ant = (size_t)x + (size_t)y;
            /* Behind (W, S, SW, SE): the neighbour one step back if it is
             * valid, else that neighbour is a void on the same line, swept
             * just before, whose hit is the same sample. */
            const uint8_t *mbelow = (y > 0u) ? mrow - w : NULL;
            if (x == 0u) {
                west = NONE_BEHIND;
            } else if (mrow[x - 1u] == 0u) {
                west = (int64_t)x - 1;
            } /* else: west still holds the hit of void x - 1 */
            if (mbelow == NULL) {
                L.col_below[x] = NONE_BEHIND;
                L.dia_below[dia] = NONE_BEHIND;
                L.ant_below[ant] = NONE_BEHIND;
            } else {
                if (mbelow[x] == 0u) {
                    L.col_below[x] = (int32_t)y - 1;
                }
                if (x == 0u) {
                    L.dia_below[dia] = NONE_BEHIND;
                } else if (mbelow[x - 1u] == 0u) {
                    L.dia_below[dia] = (int32_t)y - 1;
                }
                if (x + 1u >= w) {
                    L.ant_below[ant] = NONE_BEHIND;
                } else if (mbelow[x + 1u] == 0u) {
                    L.ant_below[ant] = (int32_t)y - 1;
                }
            }
            /* East pointer of this row: smallest valid x' > x. */
            if (east <= (int64_t)x) {
                int64_t cx = (int64_t)x + 1;
                while (cx < (int64_t)w && mrow[cx] != 0u) {
                    ++cx;
                }
                east = (cx < (int64_t)w) ? cx : (int64_t)NONE_AHEAD;
            }
            advance_ahead(&L.col_above[x], void_mask, w, h, x, y, 0);
            advance_ahead(&L.dia_above[dia], void_mask, w, h, x, y, 1);
            advance_ahead(&L.ant_above[ant], void_mask, w, h, x, y, -1);
            const int64_t yy = (int64_t)y, xx = (int64_t)x;
            double wsum = 0.0, hsum = 0.0;
            int64_t yn = L.col_above[x], yne = L.dia_above[dia], ynw = L.ant_above[ant];
            int64_t ys = L.col_below[x], ysw = L.dia_below[dia], yse = L.ant_below[ant];
            /* Same order as the ray walk: N, NE, E, SE, S, SW, W, NW. */
            if (yn != NONE_AHEAD) {
                add_hit(&wsum, &hsum, heights, (size_t)yn * w + x, yn - yy, 1.0);
            }
            if (yne != NONE_AHEAD) {
                add_hit(&wsum, &hsum, heights, (size_t)yne * w + (size_t)(xx + (yne - yy)),
                        yne - yy, FT_SQRT2);
            }
            if (east != NONE_AHEAD) {
                add_hit(&wsum, &hsum, heights, (size_t)y * w + (size_t)east, east - xx, 1.0);
            }
            if (yse != NONE_BEHIND) {
                add_hit(&wsum, &hsum, heights, (size_t)yse * w + (size_t)(xx + (yy - yse)),
                        yy - yse, FT_SQRT2);
            }
            if (ys != NONE_BEHIND) {
                add_hit(&wsum, &hsum, heights, (size_t)ys * w + x, yy - ys, 1.0);
            }
            if (ysw != NONE_BEHIND) {
                add_hit(&wsum, &hsum, heights, (size_t)ysw * w + (size_t)(xx - (yy - ysw)),
                        yy - ysw, FT_SQRT2);
            }
            if (west != NONE_BEHIND) {
                add_hit(&wsum, &hsum, heights, (size_t)y * w + (size_t)west, xx - west, 1.0);
            }
            if (ynw != NONE_AHEAD) {
                add_hit(&wsum, &hsum, heights, (size_t)ynw * w + (size_t)(xx - (ynw - yy)),
                        ynw - yy, FT_SQRT2);
            }
            double v;
            if (wsum > 0.0) {
                v = hsum / wsum;
            } else {
                if (!have_mean) {
                    mean = mean_of_valid(heights, void_mask, n);
                    have_mean = 1;
                }
                v = mean;
            }
            heights[idx] = (float)v;
        }
    }
    return (uint32_t)voids;
}
