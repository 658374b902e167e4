/* clip_source.h - height sources for the clipmap cache (clip_cache.h).
 *
 * Over the runtime's terrain (ft_terrain in memory): the lattice is the
 * terrain's samples (lattice_i0 = lattice_j0 = 0); level l sample (a, b) is
 * the terrain's sample (a * 2^l, b * 2^l), point-sampled as the terrain
 * database's coarser levels are (so a lattice point has one height on every
 * level). A sample off the terrain takes the height of the nearest edge
 * sample and is marked, as is every sample the DEM void-filled; the methods
 * draw nothing off the terrain (data_* is the terrain's extent), so the
 * clamped heights only serve the coarse samples a level's box reaches past
 * the edge. */
#ifndef FT_CLIP_SOURCE_H
#define FT_CLIP_SOURCE_H

#include "terrain/clip_cache.h"
#include "terrain/terrain.h"

/* t must stay valid (and its heights unchanged) while the source is used. */
void ft_clip_source_terrain(ft_clip_source *out, const ft_terrain *t);

#endif
