/* synth_terrain.h - the embedded default terrain: deterministic fBm.
 *
 * Same desc -> bit-identical heights on every machine (integer hash value
 * noise, no libc rand, double arithmetic in a fixed order). A ridged mix gives
 * valleys, ridges and a lake at 0 m so every method has something to show. */
#ifndef FT_SYNTH_TERRAIN_H
#define FT_SYNTH_TERRAIN_H

#include <stdint.h>

#include "terrain/terrain.h"

typedef struct ft_synth_desc {
    uint32_t side;      /* samples per side (e.g. 1025) */
    double spacing_m;   /* e.g. 30 */
    double relief_m;    /* highest peak, e.g. 2400 */
    uint32_t seed;
    uint32_t octaves;   /* e.g. 9 */
    double anchor_lat_deg, anchor_lon_deg; /* where --pose LAT,LON lands */
} ft_synth_desc;

/* Fills t's header fields (unit metre, origin 0,0, crs "local") and derives
 * the frame; no data. */
ft_status ft_synth_probe(const ft_synth_desc *d, ft_terrain *t, ft_error *err);

/* Writes the heights into t->heights_m (laid out by the caller), sets
 * min/max. Does not build pyramids. */
void ft_synth_generate(const ft_synth_desc *d, ft_terrain *t);

#endif
