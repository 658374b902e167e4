/* fuzz_ftd.c - libFuzzer harness: the .ftd tiled terrain database reader
 * (src/terrain/terrain_db.c: ft_tdb_open, then ft_tdb_read_tile on every
 * tile the index lists and a few it does not), over a positional memory
 * reader of exactly the input's size, so any read past the data is an
 * AddressSanitizer finding.
 *
 * Built twice: as given (FUZZ_FTD_FIX_CRC 0: most mutations stop at a crc),
 * and with FUZZ_FTD_FIX_CRC 1, which first rewrites each listed tile's crc,
 * then the index crc, then the header crc to match the bytes, so the checks
 * behind them (level boxes, offsets, packing, bounds, heights) see the
 * mutations. Tile buffers are allocated at exactly one tile, so an overrun
 * is caught too. Invariants of an accepted tile: every sample a height in
 * range within the index bounds or the no-data value, as many filled
 * samples as the index says. */
#include <math.h>
#include <string.h>
#include <zlib.h>

#include "fuzz_util.h"
#include "core/io.h"
#include "terrain/terrain.h"
#include "terrain/terrain_db.h"

#ifndef FUZZ_FTD_FIX_CRC
#define FUZZ_FTD_FIX_CRC 0
#endif

/* Index capacity of the harness: larger indexes are refused (FT_ERR_BUDGET). */
#define FUZZ_FTD_ENTRIES 4096u

static ft_tdb_entry g_entries[FUZZ_FTD_ENTRIES];

static void put_u32le(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint64_t u64le(const uint8_t *p)
{
    return (uint64_t)fuzz_u32(p) | ((uint64_t)fuzz_u32(p + 4) << 32);
}

static void fix_crcs(uint8_t *b, size_t size)
{
    if (size < FT_TDB_HEADER_BYTES) {
        return;
    }
    uint64_t entries = fuzz_u32(b + 28);
    const uint64_t fit = (size - FT_TDB_HEADER_BYTES) / FT_TDB_ENTRY_BYTES;
    entries = entries < fit ? entries : fit;
    for (uint64_t n = 0u; n < entries; ++n) {
        uint8_t *rec = b + FT_TDB_HEADER_BYTES + n * FT_TDB_ENTRY_BYTES;
        const uint64_t off = u64le(rec + 8);
        const uint32_t bytes = fuzz_u32(rec + 4);
        if (fuzz_u32(rec) == 1u && off <= size && bytes <= size - off) {
            put_u32le(rec + 16, (uint32_t)crc32(0L, b + off, bytes));
        }
    }
    put_u32le(b + 36, (uint32_t)crc32(0L, b + FT_TDB_HEADER_BYTES,
                                      (uInt)(entries * FT_TDB_ENTRY_BYTES)));
    put_u32le(b + 124, 0u);
    put_u32le(b + 124, (uint32_t)crc32(0L, b, FT_TDB_HEADER_BYTES));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    uint8_t *copy = (uint8_t *)malloc(size > 0u ? size : 1u);
    FUZZ_CHECK(copy != NULL);
    memcpy(copy, data, size);
    if (FUZZ_FTD_FIX_CRC) {
        fix_crcs(copy, size);
    }
    ft_reader_at r;
    ft_mem_reader m;
    ft_mem_reader_at_init(&r, &m, copy, size, "fuzz.ftd");
    ft_tdb db;
    ft_error err;
    memset(&err, 0, sizeof err);
    ft_status st = ft_tdb_open(&db, &r, g_entries, FUZZ_FTD_ENTRIES, &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st != FT_OK) {
        FUZZ_CHECK(err.text[0] != '\0');
        free(copy);
        return 0;
    }
    const uint32_t T = db.hdr.tile_samples, n = T * T;
    FUZZ_CHECK(T >= FT_TDB_TILE_MIN && T <= FT_TDB_TILE_MAX);
    FUZZ_CHECK(db.hdr.file_bytes == size);
    float *h = (float *)malloc((size_t)n * sizeof(float));
    uint8_t *bits = (uint8_t *)malloc(n / 8u);
    FUZZ_CHECK(h != NULL && bits != NULL);
    for (uint32_t k = 0u; k < db.hdr.level_count; ++k) {
        const ft_tdb_level *lv = &db.hdr.levels[k];
        /* every listed tile, and the ones just outside the box */
        for (uint32_t y = 0u; y < lv->rows + 2u; ++y) {
            for (uint32_t x = 0u; x < lv->cols + 2u; ++x) {
                if (lv->tx0 + x == 0u || lv->ty0 + y == 0u) {
                    continue;
                }
                ft_tdb_tile t;
                st = ft_tdb_read_tile(&db, k, lv->tx0 + x - 1u, lv->ty0 + y - 1u, h, n, bits,
                                      n / 8u, &t, &err);
                FUZZ_CHECK_TEXT(err.text);
                if (st != FT_OK || t.state != FT_TDB_DATA) {
                    continue;
                }
                uint32_t filled = 0u;
                for (uint32_t i = 0u; i < n; ++i) {
                    const float v = h[i];
                    FUZZ_CHECK(v == FT_TDB_NODATA_M ||
                               (isfinite(v) && v >= t.entry.min_m && v <= t.entry.max_m));
                    filled += (uint32_t)((bits[i >> 3] >> (i & 7u)) & 1u);
                }
                FUZZ_CHECK(filled == t.entry.void_count);
            }
        }
    }
    free(bits);
    free(h);
    free(copy);
    return 0;
}
