/* pyramid.h - avg/min/max pyramids of a terrain (layout in terrain.h). */
#ifndef FT_PYRAMID_H
#define FT_PYRAMID_H

#include <stddef.h>
#include <stdint.h>

#include "terrain/terrain.h"

/* Level counts and the total float32 storage (bytes) the pyramids of a
 * width x height grid need (avg levels >= 1 plus min and max levels).
 * Pure arithmetic: used to plan the FT_POOL_PYRAMIDS budget. */
uint32_t ft_pyramid_avg_levels(uint32_t width, uint32_t height);
uint32_t ft_pyramid_minmax_levels(uint32_t width, uint32_t height);
size_t ft_pyramid_bytes(uint32_t width, uint32_t height);

/* Points the level arrays of t->pyr into `storage` (ft_pyramid_bytes long,
 * 64-byte aligned), in this fixed order: avg levels 1.., then for each
 * min/max level L: min_L, max_L. Same order as in the terrain file. */
ft_status ft_pyramid_layout(ft_terrain *t, void *storage, size_t storage_bytes, ft_error *err);

/* Computes all levels from t->heights_m (after ft_pyramid_layout); also sets
 * t->min_height_m / max_height_m. O(width*height), no recursion. */
void ft_pyramid_build(ft_terrain *t);

/* Checks laid-out, filled pyramids against t->heights_m before anything
 * trusts them (a file's crc guards transport, not meaning):
 *  - min/max level 0 texel (i,j) equals the min/max of its cell's 4 samples;
 *  - min/max level L+1 equals the min/max of its 2x2 (clamped) children, so
 *    every node bounds its children and min <= max everywhere;
 *  - avg level L+1 lies within the range of its 2x2 (clamped) children (a
 *    mean cannot leave it; the exact float rounding is not compared).
 * Fails with FT_ERR_FORMAT naming `name`, the first inconsistent node
 * (pyramid, level, x, y) and the values. O(width*height), no recursion. */
ft_status ft_pyramid_check(const ft_terrain *t, const char *name, ft_error *err);

#endif
