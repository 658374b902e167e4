/* void_fill.c - 8-direction inverse-distance void fill (rule in void_fill.h).
 *
 * Only samples whose mask byte is 0 are ever read as sources and only void
 * samples are written, so the result does not depend on the scan order.
 *
 * Not covered by the header's rule: a void whose 8 rays all leave the grid
 * without meeting a valid sample while the grid does have valid samples (e.g.
 * the only valid sample is a knight's move away). Such a void takes the mean
 * of all valid samples, which is still order independent and deterministic. */
#include "void_fill.h"

#include <stddef.h>

/* Direction steps: N, NE, E, SE, S, SW, W, NW (y runs north). */
static const int k_dx[8] = {0, 1, 1, 1, 0, -1, -1, -1};
static const int k_dy[8] = {1, 1, 0, -1, -1, -1, 0, 1};

/* Distance of one step in each direction: diagonals count sqrt(2). */
#define FT_SQRT2 1.41421356237309504880

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

/* IDW over the 8 rays from void (x, y); returns 0 if no ray found a sample. */
static int idw8(const float *heights, const uint8_t *void_mask, uint32_t w, uint32_t h, uint32_t x,
                uint32_t y, double *out)
{
    double wsum = 0.0, hsum = 0.0;
    for (int d = 0; d < 8; ++d) {
        int64_t cx = (int64_t)x, cy = (int64_t)y;
        double step = (k_dx[d] != 0 && k_dy[d] != 0) ? FT_SQRT2 : 1.0;
        /* A ray is at most max(w, h) steps long before it leaves the grid. */
        uint32_t limit = (w > h ? w : h);
        for (uint32_t k = 1u; k <= limit; ++k) {
            cx += k_dx[d];
            cy += k_dy[d];
            if (cx < 0 || cy < 0 || cx >= (int64_t)w || cy >= (int64_t)h) {
                break;
            }
            size_t idx = (size_t)cy * w + (size_t)cx;
            if (void_mask[idx] == 0u) {
                double wt = 1.0 / ((double)k * step);
                wsum += wt;
                hsum += wt * (double)heights[idx];
                break;
            }
        }
    }
    if (wsum > 0.0) {
        *out = hsum / wsum;
        return 1;
    }
    return 0;
}

uint32_t ft_void_fill(float *heights, const uint8_t *void_mask, uint32_t w, uint32_t h,
                      int *all_void)
{
    if (all_void != NULL) {
        *all_void = 0;
    }
    if (heights == NULL || void_mask == NULL || w == 0u || h == 0u) {
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
    int have_mean = 0;
    double mean = 0.0;
    for (uint32_t y = 0u; y < h; ++y) {
        for (uint32_t x = 0u; x < w; ++x) {
            size_t idx = (size_t)y * w + x;
            if (void_mask[idx] == 0u) {
                continue;
            }
            double v = 0.0;
            if (!idw8(heights, void_mask, w, h, x, y, &v)) {
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
