/* ftd_synth.h - a small .ftd made with the encoders (no shared data needed),
 * shared by tests/test_terrain_db.c and the fuzz seeds (tests/fuzz/make_seeds.c).
 *
 * 16-sample tiles at 1 sample per degree: level 0 lists tiles (10, 5) with
 * data (samples 40, 41 and 43 void-filled, the 3 x 2 south-west corner not
 * covered) and (11, 5) without; level 1 lists (5, 2) with the same heights
 * and no voids, its max raised by widen_m (a footprint wider than the tile's
 * own samples). */
#ifndef FT_FTD_SYNTH_H
#define FT_FTD_SYNTH_H

#include <string.h>

#include "core/byte_codec.h"
#include "terrain/terrain_db.h"

#define FT_SYNTH_FTD_T 16u

/* The heights both data tiles hold. */
static inline void ft_synth_ftd_heights(float hv[FT_SYNTH_FTD_T * FT_SYNTH_FTD_T])
{
    for (uint32_t i = 0u; i < FT_SYNTH_FTD_T * FT_SYNTH_FTD_T; ++i) {
        const uint32_t x = i % FT_SYNTH_FTD_T, y = i / FT_SYNTH_FTD_T;
        hv[i] = (x < 3u && y < 2u) ? FT_TDB_NODATA_M : (float)(i % 97u) - 20.0f;
    }
}

/* Writes the database into out (cap bytes); *hdr_out gets its header.
 * Returns its size, or 0 with err set when an encoder refuses. */
static inline size_t ft_synth_ftd(uint8_t *out, size_t cap, float widen_m,
                                  ft_tdb_header *hdr_out, ft_error *err)
{
    const uint32_t T = FT_SYNTH_FTD_T;
    ft_tdb_header h;
    memset(&h, 0, sizeof h);
    h.tile_samples = T;
    h.level_count = 2u;
    h.samples_per_deg = 1u;
    h.entry_count = 3u;
    h.void_fill_rule = 1u;
    h.levels[0] = (ft_tdb_level){10u, 5u, 2u, 1u, 0u};
    h.levels[1] = (ft_tdb_level){5u, 2u, 1u, 1u, 2u};
    ft_tdb_entry e[3];
    memset(e, 0, sizeof e);
    float hv[FT_SYNTH_FTD_T * FT_SYNTH_FTD_T];
    uint8_t bits[FT_SYNTH_FTD_T * FT_SYNTH_FTD_T / 8u];
    const size_t index_end = FT_TDB_HEADER_BYTES + 3u * FT_TDB_ENTRY_BYTES;
    if (cap < index_end) {
        (void)ft_fail(err, FT_ERR_OVERSIZED, "ft_synth_ftd: %zu bytes do not hold the index",
                      cap);
        return 0u;
    }
    size_t pos = index_end;
    ft_synth_ftd_heights(hv);
    for (uint32_t t = 0u; t < 3u; t += 2u) {
        memset(bits, 0, sizeof bits);
        if (t == 0u) {
            bits[5] = 0x0bu; /* samples 40, 41, 43 */
        }
        if (ft_tdb_encode_tile(hv, bits, NULL, T, t == 2u ? 1u : 0u, out + pos, cap - pos, &e[t],
                               "synth", err) != FT_OK) {
            return 0u;
        }
        e[t].offset = pos;
        pos += e[t].byte_size;
    }
    e[2].max_m += widen_m;
    uint32_t crc = 0u;
    for (uint32_t t = 0u; t < 3u; ++t) {
        uint8_t *rec = out + FT_TDB_HEADER_BYTES + t * FT_TDB_ENTRY_BYTES;
        ft_tdb_encode_entry(&e[t], rec);
        crc = ft_crc32(crc, rec, FT_TDB_ENTRY_BYTES);
    }
    h.index_crc32 = crc;
    h.data_tiles = 2u;
    h.min_height_m = e[0].min_m;
    h.max_height_m = e[2].max_m > e[0].max_m ? e[2].max_m : e[0].max_m;
    h.file_bytes = pos;
    if (ft_tdb_encode_header(&h, out, "synth", err) != FT_OK) {
        return 0u;
    }
    *hdr_out = h;
    return pos;
}

#endif
