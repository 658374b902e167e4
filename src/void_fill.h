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
 * Cost: O(voids * side) worst case, no recursion, no allocation. */
#ifndef FT_VOID_FILL_H
#define FT_VOID_FILL_H

#include <stdint.h>

#define FT_VOID_FILL_RULE_IDW8 1u

/* heights: w*h; void_mask: w*h bytes, 1 = void (read only).
 * Returns the number of voids filled. */
uint32_t ft_void_fill(float *heights, const uint8_t *void_mask, uint32_t w, uint32_t h,
                      int *all_void);

#endif
