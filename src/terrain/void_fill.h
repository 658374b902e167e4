/* void_fill.h - fill DEM voids from valid neighbours (documented rule).
 *
 * Rule (FT_VOID_FILL_RULE_IDW8 = 1): each void sample takes the
 * inverse-distance-weighted mean (weight 1/d) of the nearest valid sample
 * found along each of the 8 grid directions (N, NE, E, ... ; diagonal steps
 * count sqrt(2)), looking at ORIGINAL valid samples only, so the result does
 * not depend on scan order. Directions that leave the grid without a valid
 * sample are ignored. A void none of whose 8 rays meets a valid sample (while
 * valid samples exist elsewhere) takes the mean of all valid samples. If the
 * grid has no valid sample at all, every sample
 * becomes 0 m and the caller is told (all_void = 1).
 * So a filled sample is a convex combination of valid samples (it lies within
 * the range of the valid samples its rays meet), and valid samples are never
 * written.
 *
 * Cost: O(width * height) whatever the void pattern: one sweep over the rows
 * keeps, per column, per diagonal and per anti-diagonal, the last valid
 * sample below and a forward pointer to the next valid sample above; each
 * pointer only moves north, so all the look-ahead of a sweep is bounded by
 * the grid size. No recursion, no allocation: the per-line state lives in
 * caller scratch of ft_void_fill_scratch_bytes() (40 bytes per grid side of
 * a square grid, 48 KB for a 1201 x 1201 tile). */
#ifndef FT_VOID_FILL_H
#define FT_VOID_FILL_H

#include <stddef.h>
#include <stdint.h>

#define FT_VOID_FILL_RULE_IDW8 1u

/* Scratch bytes ft_void_fill needs for a w x h grid (0 for an empty grid or
 * one whose per-line state would not fit size_t). */
size_t ft_void_fill_scratch_bytes(uint32_t w, uint32_t h);

/* heights: w*h; void_mask: w*h bytes, 1 = void (read only); scratch: at
 * least ft_void_fill_scratch_bytes(w, h) bytes, 4-byte aligned.
 * Returns the number of voids filled; 0 (nothing written) on a NULL argument
 * or a scratch that is too small, so a caller that counted its voids sees
 * the shortfall. */
uint32_t ft_void_fill(float *heights, const uint8_t *void_mask, uint32_t w, uint32_t h,
                      void *scratch, size_t scratch_bytes, int *all_void);

#endif
