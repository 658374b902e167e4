/* terrain_db.c - the ".ftd" tiled terrain database (layout in terrain_db.h).
 *
 * Field by field little-endian, like terrain_file.c. The reader holds no
 * state between calls besides the header and the caller's index array, reads
 * each tile straight into the caller's buffer by position, and checks it
 * before it is handed out. */
#include "terrain/terrain_db.h"

#include <math.h>
#include <string.h>

#include "core/byte_codec.h"
#include "terrain/terrain.h"
#include "terrain/void_fill.h"

enum {
    OFF_MAGIC = 0,
    OFF_VERSION = 8,
    OFF_HEADER_BYTES = 12,
    OFF_TILE = 16,
    OFF_LEVELS = 20,
    OFF_PER_DEG = 24,
    OFF_ENTRIES = 28,
    OFF_DATA_TILES = 32,
    OFF_INDEX_CRC = 36,
    OFF_FILL_RULE = 40,
    OFF_MIN_H = 44,
    OFF_MAX_H = 48,
    OFF_RESERVED0 = 52,
    OFF_FILE_BYTES = 56,
    OFF_RESERVED1 = 64,
    OFF_HEADER_CRC = 124,
    OFF_LEVEL_TABLE = 128,
    LEVEL_RECORD_BYTES = 16
};

/* Entries parsed per read while opening (a 2.5 KB stack block). */
#define FT_TDB_INDEX_CHUNK 64u
static uint32_t header_crc(const uint8_t *hdr)
{
    uint8_t copy[FT_TDB_HEADER_BYTES];
    memcpy(copy, hdr, sizeof copy);
    ft_le_put_u32(copy + OFF_HEADER_CRC, 0u);
    return ft_crc32(0u, copy, sizeof copy);
}

void ft_tdb_lattice_samples(uint32_t samples_per_deg, uint32_t level, uint64_t *nx,
                            uint64_t *ny)
{
    *nx = 0u;
    *ny = 0u;
    if (samples_per_deg == 0u || level >= FT_TDB_LEVELS_MAX) {
        return;
    }
    const uint64_t step = (uint64_t)1u << level;
    /* samples with lon < 180 (sample nx is lon 180, the lattice's sample 0
     * again when the level closes: ft_tdb_lattice_closes) and lat <= 90 */
    *nx = ((uint64_t)360u * samples_per_deg + step - 1u) / step;
    *ny = (uint64_t)180u * samples_per_deg / step + 1u;
}

int ft_tdb_lattice_closes(uint32_t samples_per_deg, uint32_t level)
{
    if (samples_per_deg == 0u || level >= FT_TDB_LEVELS_MAX) {
        return 0;
    }
    return ((uint64_t)360u * samples_per_deg) % ((uint64_t)1u << level) == 0u;
}

void ft_tdb_lattice_tiles(uint32_t samples_per_deg, uint32_t tile_samples, uint32_t level,
                          uint32_t *cols, uint32_t *rows)
{
    *cols = 0u;
    *rows = 0u;
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(samples_per_deg, level, &nx, &ny);
    if (nx == 0u || tile_samples == 0u) {
        return;
    }
    *cols = (uint32_t)((nx + tile_samples - 1u) / tile_samples);
    *rows = (uint32_t)((ny + tile_samples - 1u) / tile_samples);
}

uint32_t ft_tdb_tile_bytes(uint32_t tile_samples, uint32_t void_count, uint32_t level)
{
    const uint32_t n = tile_samples * tile_samples;
    return n * 4u + (void_count > 0u ? n / 8u : 0u) + (level > 0u ? n * 4u : 0u);
}

int ft_tdb_dev_ok(float d)
{
    return (d >= 0.0f && d <= FT_TDB_DEV_MAX_M) || d == FT_TDB_DEV_NONE ||
           d == FT_TDB_DEV_COARSER;
}

static int is_pow2(uint32_t v)
{
    return v != 0u && (v & (v - 1u)) == 0u;
}

/* The header fields every writer and reader agree on (not crcs, not size). */
static ft_status check_header(const ft_tdb_header *h, const char *name, ft_error *err)
{
    if (!is_pow2(h->tile_samples) || h->tile_samples < FT_TDB_TILE_MIN ||
        h->tile_samples > FT_TDB_TILE_MAX) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile_samples %u is not a power of two within %u..%u", name,
                       h->tile_samples, FT_TDB_TILE_MIN, FT_TDB_TILE_MAX);
    }
    if (h->level_count < 1u || h->level_count > FT_TDB_LEVELS_MAX) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: level_count %u is outside 1..%u", name,
                       h->level_count, FT_TDB_LEVELS_MAX);
    }
    if (h->samples_per_deg < 1u || h->samples_per_deg > FT_TDB_SAMPLES_PER_DEG_MAX) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: samples_per_deg %u is outside 1..%u", name,
                       h->samples_per_deg, FT_TDB_SAMPLES_PER_DEG_MAX);
    }
    if (h->void_fill_rule != FT_VOID_FILL_RULE_IDW8) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: void_fill_rule %u unknown (this build: %u)",
                       name, h->void_fill_rule, FT_VOID_FILL_RULE_IDW8);
    }
    uint64_t entries = 0u;
    for (uint32_t k = 0u; k < h->level_count; ++k) {
        const ft_tdb_level *lv = &h->levels[k];
        uint32_t cols = 0u, rows = 0u;
        ft_tdb_lattice_tiles(h->samples_per_deg, h->tile_samples, k, &cols, &rows);
        if (lv->cols == 0u || lv->rows == 0u || lv->tx0 >= cols || lv->ty0 >= rows ||
            lv->cols > cols - lv->tx0 || lv->rows > rows - lv->ty0) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: level %u lists tiles x %u+%u, y %u+%u; the lattice has %u x %u "
                           "tiles (none may be empty)",
                           name, k, lv->tx0, lv->cols, lv->ty0, lv->rows, cols, rows);
        }
        if (lv->first_entry != (uint32_t)entries) {
            return ft_fail(err, FT_ERR_FORMAT, "%s: level %u starts at entry %u, not %llu", name,
                           k, lv->first_entry, (unsigned long long)entries);
        }
        entries += (uint64_t)lv->cols * lv->rows;
        if (entries > FT_TDB_ENTRIES_MAX) {
            return ft_fail(err, FT_ERR_OVERSIZED,
                           "%s: levels 0..%u list more than %u index entries", name, k,
                           FT_TDB_ENTRIES_MAX);
        }
    }
    if (entries != h->entry_count) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: entry_count %u, the level table lists %llu tiles", name,
                       h->entry_count, (unsigned long long)entries);
    }
    if (h->data_tiles > h->entry_count) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: data_tiles %u exceeds the %u entries", name,
                       h->data_tiles, h->entry_count);
    }
    if (h->data_tiles > 0u &&
        (!ft_terrain_height_ok((double)h->min_height_m) ||
         !ft_terrain_height_ok((double)h->max_height_m) || h->min_height_m > h->max_height_m)) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: header height range %g..%g m is not ordered within %g..%g m", name,
                       (double)h->min_height_m, (double)h->max_height_m, FT_HEIGHT_MIN_M,
                       FT_HEIGHT_MAX_M);
    }
    return FT_OK;
}

ft_status ft_tdb_encode_header(const ft_tdb_header *h, uint8_t *out, const char *name,
                               ft_error *err)
{
    ft_status st = check_header(h, name, err);
    if (st != FT_OK) {
        return st;
    }
    memset(out, 0, FT_TDB_HEADER_BYTES);
    memcpy(out + OFF_MAGIC, FT_TDB_MAGIC, 8u);
    ft_le_put_u32(out + OFF_VERSION, FT_TDB_VERSION);
    ft_le_put_u32(out + OFF_HEADER_BYTES, FT_TDB_HEADER_BYTES);
    ft_le_put_u32(out + OFF_TILE, h->tile_samples);
    ft_le_put_u32(out + OFF_LEVELS, h->level_count);
    ft_le_put_u32(out + OFF_PER_DEG, h->samples_per_deg);
    ft_le_put_u32(out + OFF_ENTRIES, h->entry_count);
    ft_le_put_u32(out + OFF_DATA_TILES, h->data_tiles);
    ft_le_put_u32(out + OFF_INDEX_CRC, h->index_crc32);
    ft_le_put_u32(out + OFF_FILL_RULE, h->void_fill_rule);
    ft_le_put_f32(out + OFF_MIN_H, h->data_tiles > 0u ? h->min_height_m : 0.0f);
    ft_le_put_f32(out + OFF_MAX_H, h->data_tiles > 0u ? h->max_height_m : 0.0f);
    ft_le_put_u64(out + OFF_FILE_BYTES, h->file_bytes);
    for (uint32_t k = 0u; k < h->level_count; ++k) {
        uint8_t *p = out + OFF_LEVEL_TABLE + k * LEVEL_RECORD_BYTES;
        ft_le_put_u32(p, h->levels[k].tx0);
        ft_le_put_u32(p + 4, h->levels[k].ty0);
        ft_le_put_u32(p + 8, h->levels[k].cols);
        ft_le_put_u32(p + 12, h->levels[k].rows);
    }
    ft_le_put_u32(out + OFF_HEADER_CRC, header_crc(out));
    return FT_OK;
}

void ft_tdb_encode_entry(const ft_tdb_entry *e, uint8_t *out)
{
    ft_le_put_u32(out, e->state);
    ft_le_put_u32(out + 4, e->byte_size);
    ft_le_put_u64(out + 8, e->offset);
    ft_le_put_u32(out + 16, e->crc32);
    ft_le_put_f32(out + 20, e->min_m);
    ft_le_put_f32(out + 24, e->max_m);
    ft_le_put_f32(out + 28, e->avg_m);
    ft_le_put_u32(out + 32, e->void_count);
    ft_le_put_u32(out + 36, e->nodata_count);
}

static void decode_entry(const uint8_t *p, ft_tdb_entry *e)
{
    e->state = ft_le_get_u32(p);
    e->byte_size = ft_le_get_u32(p + 4);
    e->offset = ft_le_get_u64(p + 8);
    e->crc32 = ft_le_get_u32(p + 16);
    e->min_m = ft_le_get_f32(p + 20);
    e->max_m = ft_le_get_f32(p + 24);
    e->avg_m = ft_le_get_f32(p + 28);
    e->void_count = ft_le_get_u32(p + 32);
    e->nodata_count = ft_le_get_u32(p + 36);
}

/* Level and tile of entry number n (for messages). */
static void entry_tile(const ft_tdb_header *h, uint32_t n, uint32_t *level, uint32_t *tx,
                       uint32_t *ty)
{
    *level = 0u;
    for (uint32_t k = 0u; k < h->level_count; ++k) {
        if (n >= h->levels[k].first_entry) {
            *level = k;
        }
    }
    const ft_tdb_level *lv = &h->levels[*level];
    uint32_t local = n - lv->first_entry;
    *tx = lv->tx0 + local % lv->cols;
    *ty = lv->ty0 + local / lv->cols;
}

/* One entry's own consistency (the packing is checked by the caller). */
static ft_status check_entry(const ft_tdb_header *h, const ft_tdb_entry *e, uint32_t n,
                             const char *name, ft_error *err)
{
    uint32_t k = 0u, tx = 0u, ty = 0u;
    entry_tile(h, n, &k, &tx, &ty);
    const uint32_t samples = h->tile_samples * h->tile_samples;
    if (e->state == (uint32_t)FT_TDB_NO_DATA) {
        if (e->byte_size != 0u || e->offset != 0u || e->crc32 != 0u || e->min_m != 0.0f ||
            e->max_m != 0.0f || e->avg_m != 0.0f || e->void_count != 0u ||
            e->nodata_count != 0u) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: tile (level %u, %u, %u) has no data but its index fields are "
                           "not all zero",
                           name, k, tx, ty);
        }
        return FT_OK;
    }
    if (e->state != (uint32_t)FT_TDB_DATA) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: tile (level %u, %u, %u) has state %u (0 or 1)",
                       name, k, tx, ty, e->state);
    }
    if (e->void_count > samples || e->nodata_count >= samples ||
        (uint64_t)e->void_count + e->nodata_count > samples) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile (level %u, %u, %u): %u filled + %u uncovered samples do not "
                       "fit %u samples with one covered",
                       name, k, tx, ty, e->void_count, e->nodata_count, samples);
    }
    if (e->byte_size != ft_tdb_tile_bytes(h->tile_samples, e->void_count, k)) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile (level %u, %u, %u) is %u bytes, a %ux%u tile with %u voids is "
                       "%u",
                       name, k, tx, ty, e->byte_size, h->tile_samples, h->tile_samples,
                       e->void_count, ft_tdb_tile_bytes(h->tile_samples, e->void_count, k));
    }
    if (!ft_terrain_height_ok((double)e->min_m) || !ft_terrain_height_ok((double)e->max_m) ||
        !ft_terrain_height_ok((double)e->avg_m) || !(e->min_m <= e->avg_m) ||
        !(e->avg_m <= e->max_m)) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: tile (level %u, %u, %u): min %g <= avg %g <= max %g m does not hold "
                       "within %g..%g m",
                       name, k, tx, ty, (double)e->min_m, (double)e->avg_m, (double)e->max_m,
                       FT_HEIGHT_MIN_M, FT_HEIGHT_MAX_M);
    }
    if (e->min_m < h->min_height_m || e->max_m > h->max_height_m) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile (level %u, %u, %u) spans %g..%g m, outside the header's %g..%g m",
                       name, k, tx, ty, (double)e->min_m, (double)e->max_m,
                       (double)h->min_height_m, (double)h->max_height_m);
    }
    return FT_OK;
}

ft_status ft_tdb_read_header(const ft_reader_at *r, ft_tdb_header *h, ft_error *err)
{
    if (r == NULL || r->read_at == NULL || h == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain database header: a NULL argument");
    }
    memset(h, 0, sizeof *h);
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    uint8_t hb[FT_TDB_HEADER_BYTES];
    if (r->size_bytes >= 8u) {
        ft_status st = ft_read_at_exact(r, 0u, hb, 8u, err);
        if (st != FT_OK) {
            return st;
        }
        if (memcmp(hb, FT_TDB_MAGIC, 8u) != 0) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: bad magic (not a fixterrain .ftd database, or mangled by a "
                           "text-mode copy)",
                           name);
        }
    }
    if (r->size_bytes < FT_TDB_HEADER_BYTES) {
        return ft_fail(err, FT_ERR_TRUNCATED,
                       "%s: truncated inside the header (%llu of %u bytes)", name,
                       (unsigned long long)r->size_bytes, FT_TDB_HEADER_BYTES);
    }
    ft_status st = ft_read_at_exact(r, 0u, hb, sizeof hb, err);
    if (st != FT_OK) {
        return st;
    }
    const uint32_t version = ft_le_get_u32(hb + OFF_VERSION);
    if (version != FT_TDB_VERSION) {
        return ft_fail(err, FT_ERR_VERSION,
                       "%s: database version %u, this build reads %u%s", name, version,
                       FT_TDB_VERSION,
                       version < FT_TDB_VERSION
                           ? " (older files have no deviation bounds: import the inputs again)"
                           : "");
    }
    if (ft_le_get_u32(hb + OFF_HEADER_BYTES) != FT_TDB_HEADER_BYTES) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: header_bytes is %u, expected %u", name,
                       ft_le_get_u32(hb + OFF_HEADER_BYTES), FT_TDB_HEADER_BYTES);
    }
    const uint32_t crc_stored = ft_le_get_u32(hb + OFF_HEADER_CRC), crc_calc = header_crc(hb);
    if (crc_stored != crc_calc) {
        return ft_fail(err, FT_ERR_CHECKSUM,
                       "%s: header crc32 is 0x%08x, the header bytes give 0x%08x", name,
                       crc_stored, crc_calc);
    }
    h->tile_samples = ft_le_get_u32(hb + OFF_TILE);
    h->level_count = ft_le_get_u32(hb + OFF_LEVELS);
    h->samples_per_deg = ft_le_get_u32(hb + OFF_PER_DEG);
    h->entry_count = ft_le_get_u32(hb + OFF_ENTRIES);
    h->data_tiles = ft_le_get_u32(hb + OFF_DATA_TILES);
    h->index_crc32 = ft_le_get_u32(hb + OFF_INDEX_CRC);
    h->void_fill_rule = ft_le_get_u32(hb + OFF_FILL_RULE);
    h->min_height_m = ft_le_get_f32(hb + OFF_MIN_H);
    h->max_height_m = ft_le_get_f32(hb + OFF_MAX_H);
    h->file_bytes = ft_le_get_u64(hb + OFF_FILE_BYTES);
    if (ft_le_get_u32(hb + OFF_RESERVED0) != 0u) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: reserved header bytes %u..%u are not 0", name,
                       (unsigned)OFF_RESERVED0, (unsigned)OFF_RESERVED0 + 3u);
    }
    for (uint32_t b = OFF_RESERVED1; b < OFF_HEADER_CRC; ++b) {
        if (hb[b] != 0u) {
            return ft_fail(err, FT_ERR_FORMAT, "%s: reserved header byte %u is 0x%02x, not 0",
                           name, b, hb[b]);
        }
    }
    if (h->level_count < 1u || h->level_count > FT_TDB_LEVELS_MAX) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: level_count %u is outside 1..%u", name,
                       h->level_count, FT_TDB_LEVELS_MAX);
    }
    uint32_t first = 0u;
    for (uint32_t k = 0u; k < FT_TDB_LEVELS_MAX; ++k) {
        const uint8_t *p = hb + OFF_LEVEL_TABLE + k * LEVEL_RECORD_BYTES;
        if (k >= h->level_count) {
            for (uint32_t b = 0u; b < LEVEL_RECORD_BYTES; ++b) {
                if (p[b] != 0u) {
                    return ft_fail(err, FT_ERR_FORMAT,
                                   "%s: level table record %u is past the %u levels but not 0",
                                   name, k, h->level_count);
                }
            }
            continue;
        }
        ft_tdb_level *lv = &h->levels[k];
        lv->tx0 = ft_le_get_u32(p);
        lv->ty0 = ft_le_get_u32(p + 4);
        lv->cols = ft_le_get_u32(p + 8);
        lv->rows = ft_le_get_u32(p + 12);
        lv->first_entry = first;
        /* bounded: cols, rows checked against the lattice by check_header */
        uint64_t next = (uint64_t)first + (uint64_t)lv->cols * lv->rows;
        first = next > FT_TDB_ENTRIES_MAX ? FT_TDB_ENTRIES_MAX + 1u : (uint32_t)next;
    }
    return check_header(h, name, err);
}

ft_status ft_tdb_open(ft_tdb *db, const ft_reader_at *r, ft_tdb_entry *entries,
                      uint32_t entries_cap, ft_error *err)
{
    if (db == NULL || r == NULL || r->read_at == NULL || entries == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain database open: a NULL argument");
    }
    memset(db, 0, sizeof *db);
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    ft_tdb_header *h = &db->hdr;
    ft_status st = ft_tdb_read_header(r, h, err);
    if (st != FT_OK) {
        return st;
    }
    if (h->entry_count > entries_cap) {
        return ft_fail(err, FT_ERR_BUDGET,
                       "%s: the index lists %u tiles, the caller has room for %u entries", name,
                       h->entry_count, entries_cap);
    }
    const uint64_t data_start =
        (uint64_t)FT_TDB_HEADER_BYTES + (uint64_t)h->entry_count * FT_TDB_ENTRY_BYTES;
    if (r->size_bytes < h->file_bytes || r->size_bytes < data_start) {
        return ft_fail(err, FT_ERR_TRUNCATED,
                       "%s: file is %llu bytes, the header says %llu (index ends at %llu)", name,
                       (unsigned long long)r->size_bytes, (unsigned long long)h->file_bytes,
                       (unsigned long long)data_start);
    }
    if (r->size_bytes > h->file_bytes) {
        return ft_fail(err, FT_ERR_OVERSIZED,
                       "%s: file is %llu bytes, %llu more than the header's %llu", name,
                       (unsigned long long)r->size_bytes,
                       (unsigned long long)(r->size_bytes - h->file_bytes),
                       (unsigned long long)h->file_bytes);
    }
    /* The index: crc over its bytes, each entry checked, and the tiles packed
     * in index order from data_start to the end: no overlap, gap or overrun. */
    uint8_t chunk[FT_TDB_INDEX_CHUNK * FT_TDB_ENTRY_BYTES];
    uint32_t crc = 0u;
    uint64_t next_offset = data_start;
    uint32_t prev_data = UINT32_MAX;
    uint32_t data_tiles = 0u;
    for (uint32_t n0 = 0u; n0 < h->entry_count; n0 += FT_TDB_INDEX_CHUNK) {
        uint32_t cnt = h->entry_count - n0;
        cnt = cnt < FT_TDB_INDEX_CHUNK ? cnt : FT_TDB_INDEX_CHUNK;
        st = ft_read_at_exact(r, FT_TDB_HEADER_BYTES + (uint64_t)n0 * FT_TDB_ENTRY_BYTES, chunk,
                              (size_t)cnt * FT_TDB_ENTRY_BYTES, err);
        if (st != FT_OK) {
            return st;
        }
        crc = ft_crc32(crc, chunk, (size_t)cnt * FT_TDB_ENTRY_BYTES);
        for (uint32_t i = 0u; i < cnt; ++i) {
            decode_entry(chunk + (size_t)i * FT_TDB_ENTRY_BYTES, &entries[n0 + i]);
        }
    }
    if (crc != h->index_crc32) {
        return ft_fail(err, FT_ERR_CHECKSUM, "%s: index crc32 is 0x%08x, the header says 0x%08x",
                       name, crc, h->index_crc32);
    }
    for (uint32_t n = 0u; n < h->entry_count; ++n) {
        const ft_tdb_entry *e = &entries[n];
        st = check_entry(h, e, n, name, err);
        if (st != FT_OK) {
            return st;
        }
        if (e->state != (uint32_t)FT_TDB_DATA) {
            continue;
        }
        uint32_t k = 0u, tx = 0u, ty = 0u;
        entry_tile(h, n, &k, &tx, &ty);
        if (e->offset > h->file_bytes || e->byte_size > h->file_bytes - e->offset) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: tile (level %u, %u, %u) at offset %llu + %u bytes runs past the "
                           "end of the %llu-byte file",
                           name, k, tx, ty, (unsigned long long)e->offset, e->byte_size,
                           (unsigned long long)h->file_bytes);
        }
        if (e->offset < next_offset) {
            uint32_t pk = 0u, ptx = 0u, pty = 0u;
            if (prev_data != UINT32_MAX) {
                entry_tile(h, prev_data, &pk, &ptx, &pty);
                return ft_fail(err, FT_ERR_FORMAT,
                               "%s: tile (level %u, %u, %u) at offset %llu overlaps tile "
                               "(level %u, %u, %u), which ends at %llu",
                               name, k, tx, ty, (unsigned long long)e->offset, pk, ptx, pty,
                               (unsigned long long)next_offset);
            }
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: tile (level %u, %u, %u) at offset %llu overlaps the header and "
                           "index, which end at %llu",
                           name, k, tx, ty, (unsigned long long)e->offset,
                           (unsigned long long)next_offset);
        }
        if (e->offset > next_offset) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: tile (level %u, %u, %u) at offset %llu leaves a gap after %llu "
                           "(tiles are packed in index order)",
                           name, k, tx, ty, (unsigned long long)e->offset,
                           (unsigned long long)next_offset);
        }
        next_offset = e->offset + e->byte_size;
        prev_data = n;
        ++data_tiles;
    }
    if (data_tiles != h->data_tiles) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: the index has %u data tiles, the header says %u",
                       name, data_tiles, h->data_tiles);
    }
    if (next_offset != h->file_bytes) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: the tiles end at byte %llu, the file at %llu (unlisted bytes)", name,
                       (unsigned long long)next_offset, (unsigned long long)h->file_bytes);
    }
    db->r = r;
    db->entries = entries;
    return FT_OK;
}

const ft_tdb_entry *ft_tdb_find(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty)
{
    if (db == NULL || db->entries == NULL || level >= db->hdr.level_count) {
        return NULL;
    }
    const ft_tdb_level *lv = &db->hdr.levels[level];
    if (tx < lv->tx0 || ty < lv->ty0 || tx - lv->tx0 >= lv->cols || ty - lv->ty0 >= lv->rows) {
        return NULL;
    }
    return &db->entries[lv->first_entry + (ty - lv->ty0) * lv->cols + (tx - lv->tx0)];
}

ft_status ft_tdb_data_box(const ft_reader_at *r, const ft_tdb_header *h, uint32_t level,
                          uint32_t box[4], uint32_t *data_tiles, ft_error *err)
{
    *data_tiles = 0u;
    box[0] = box[1] = UINT32_MAX;
    box[2] = box[3] = 0u;
    if (level >= h->level_count) {
        return ft_fail(err, FT_ERR_ARG, "%s: level %u: the database has %u levels",
                       r->name != NULL ? r->name : "(unnamed)", level, h->level_count);
    }
    const ft_tdb_level *lv = &h->levels[level];
    const uint32_t count = lv->cols * lv->rows; /* within FT_TDB_ENTRIES_MAX (checked) */
    uint8_t chunk[FT_TDB_INDEX_CHUNK * FT_TDB_ENTRY_BYTES];
    for (uint32_t n0 = 0u; n0 < count; n0 += FT_TDB_INDEX_CHUNK) {
        const uint32_t cnt = count - n0 < FT_TDB_INDEX_CHUNK ? count - n0 : FT_TDB_INDEX_CHUNK;
        const uint64_t at =
            FT_TDB_HEADER_BYTES + ((uint64_t)lv->first_entry + n0) * FT_TDB_ENTRY_BYTES;
        ft_status st = ft_read_at_exact(r, at, chunk, (size_t)cnt * FT_TDB_ENTRY_BYTES, err);
        if (st != FT_OK) {
            return st;
        }
        for (uint32_t i = 0u; i < cnt; ++i) {
            ft_tdb_entry e;
            decode_entry(chunk + (size_t)i * FT_TDB_ENTRY_BYTES, &e);
            if (e.state != (uint32_t)FT_TDB_DATA) {
                continue;
            }
            const uint32_t tx = lv->tx0 + (n0 + i) % lv->cols, ty = lv->ty0 + (n0 + i) / lv->cols;
            box[0] = tx < box[0] ? tx : box[0];
            box[1] = ty < box[1] ? ty : box[1];
            box[2] = tx > box[2] ? tx : box[2];
            box[3] = ty > box[3] ? ty : box[3];
            ++*data_tiles;
        }
    }
    return FT_OK;
}

static int host_is_little_endian(void)
{
    const uint16_t probe = 1u;
    uint8_t b = 0u;
    memcpy(&b, &probe, 1u);
    return b == 1u;
}

static float le_float(const float *p)
{
    uint8_t b[4];
    memcpy(b, p, 4u);
    return ft_le_get_f32(b);
}

/* Own statistics of a tile's samples, the same arithmetic on both sides. */
typedef struct tile_stats {
    uint32_t nodata, voids;
    float min_m, max_m;
    double sum_m;
    uint32_t bad_index; /* first sample neither a height nor no-data; UINT32_MAX none */
    float bad_value;
    uint32_t void_on_nodata; /* first void bit on an uncovered sample; UINT32_MAX none */
} tile_stats;

static void tile_scan(const float *h, const uint8_t *bits, uint32_t n, tile_stats *s)
{
    s->nodata = 0u;
    s->voids = 0u;
    s->min_m = INFINITY;
    s->max_m = -INFINITY;
    s->sum_m = 0.0;
    s->bad_index = UINT32_MAX;
    s->bad_value = 0.0f;
    s->void_on_nodata = UINT32_MAX;
    for (uint32_t i = 0u; i < n; ++i) {
        const float v = h[i];
        const int filled = bits != NULL && ((bits[i >> 3] >> (i & 7u)) & 1u) != 0u;
        s->voids += (uint32_t)filled;
        if (v == FT_TDB_NODATA_M) {
            s->nodata++;
            if (filled && s->void_on_nodata == UINT32_MAX) {
                s->void_on_nodata = i;
            }
            continue;
        }
        if (!ft_terrain_height_ok((double)v)) {
            if (s->bad_index == UINT32_MAX) {
                s->bad_index = i;
                s->bad_value = v;
            }
            continue;
        }
        s->min_m = v < s->min_m ? v : s->min_m;
        s->max_m = v > s->max_m ? v : s->max_m;
        s->sum_m += (double)v;
    }
}

static float stats_avg(const tile_stats *s, uint32_t n)
{
    uint32_t covered = n - s->nodata;
    float avg = covered > 0u ? (float)(s->sum_m / (double)covered) : 0.0f;
    /* float rounding of the mean must not step outside the exact bounds */
    avg = avg < s->min_m ? s->min_m : avg;
    avg = avg > s->max_m ? s->max_m : avg;
    return avg;
}

ft_status ft_tdb_encode_tile(const float *heights_m, const uint8_t *void_bits,
                             const float *dev_m, uint32_t tile_samples, uint32_t level,
                             uint8_t *out, size_t out_cap, ft_tdb_entry *e, const char *what,
                             ft_error *err)
{
    const uint32_t n = tile_samples * tile_samples;
    tile_stats s;
    tile_scan(heights_m, void_bits, n, &s);
    if (s.bad_index != UINT32_MAX) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: height %g m at row %u col %u is outside %g..%g m", what,
                       (double)s.bad_value, s.bad_index / tile_samples,
                       s.bad_index % tile_samples, FT_HEIGHT_MIN_M, FT_HEIGHT_MAX_M);
    }
    if (s.void_on_nodata != UINT32_MAX || s.nodata >= n) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s: no covered sample, or a void bit on an uncovered one", what);
    }
    const uint32_t bytes = ft_tdb_tile_bytes(tile_samples, s.voids, level);
    for (uint32_t i = 0u; level > 0u && dev_m != NULL && i < n; ++i) {
        if (!ft_tdb_dev_ok(dev_m[i])) {
            return ft_fail(err, FT_ERR_NUMERIC,
                           "%s: dev %g m at row %u col %u is neither within 0..%g m nor a marker",
                           what, (double)dev_m[i], i / tile_samples, i % tile_samples,
                           (double)FT_TDB_DEV_MAX_M);
        }
    }
    if (out_cap < bytes) {
        return ft_fail(err, FT_ERR_ARG, "%s: %zu bytes of room for a %u-byte tile", what,
                       out_cap, bytes);
    }
    for (uint32_t i = 0u; i < n; ++i) {
        ft_le_put_f32(out + (size_t)i * 4u, heights_m[i]);
    }
    if (s.voids > 0u) {
        memcpy(out + (size_t)n * 4u, void_bits, n / 8u);
    }
    if (level > 0u) {
        uint8_t *dev_out = out + (size_t)n * 4u + (s.voids > 0u ? n / 8u : 0u);
        for (uint32_t i = 0u; i < n; ++i) {
            ft_le_put_f32(dev_out + (size_t)i * 4u, dev_m != NULL ? dev_m[i] : FT_TDB_DEV_NONE);
        }
    }
    e->state = FT_TDB_DATA;
    e->byte_size = bytes;
    e->crc32 = ft_crc32(0u, out, bytes);
    e->min_m = s.min_m;
    e->max_m = s.max_m;
    e->avg_m = stats_avg(&s, n);
    e->void_count = s.voids;
    e->nodata_count = s.nodata;
    return FT_OK;
}

/* Dev floats checked per read when the caller keeps none (1 KB of stack). */
#define FT_TDB_DEV_CHUNK 256u

/* Reads the dev block at `at` (n floats) into dev_m, or through a stack
 * block when dev_m is NULL; folds it into *crc and returns the first value
 * that is not a stored dev (index in *bad, UINT32_MAX none). */
static ft_status read_dev(const ft_reader_at *r, uint64_t at, uint32_t n, float *dev_m,
                          uint32_t *crc, uint32_t *bad, float *bad_value, ft_error *err)
{
    float chunk[FT_TDB_DEV_CHUNK];
    *bad = UINT32_MAX;
    for (uint32_t i0 = 0u; i0 < n; i0 += FT_TDB_DEV_CHUNK) {
        const uint32_t cnt = n - i0 < FT_TDB_DEV_CHUNK ? n - i0 : FT_TDB_DEV_CHUNK;
        float *dst = dev_m != NULL ? dev_m + i0 : chunk;
        ft_status st = ft_read_at_exact(r, at + (uint64_t)i0 * 4u, dst, (size_t)cnt * 4u, err);
        if (st != FT_OK) {
            return st;
        }
        *crc = ft_crc32(*crc, dst, (size_t)cnt * 4u);
        for (uint32_t i = 0u; i < cnt; ++i) {
            dst[i] = le_float(&dst[i]);
            if (*bad == UINT32_MAX && !ft_tdb_dev_ok(dst[i])) {
                *bad = i0 + i;
                *bad_value = dst[i];
            }
        }
    }
    return FT_OK;
}

ft_status ft_tdb_read_tile(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty,
                           float *heights_m, size_t heights_cap, uint8_t *void_bits,
                           size_t bits_cap, ft_tdb_tile *out, ft_error *err)
{
    return ft_tdb_read_tile_dev(db, level, tx, ty, heights_m, heights_cap, void_bits, bits_cap,
                                NULL, 0u, out, err);
}

ft_status ft_tdb_read_tile_dev(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty,
                               float *heights_m, size_t heights_cap, uint8_t *void_bits,
                               size_t bits_cap, float *dev_m, size_t dev_cap, ft_tdb_tile *out,
                               ft_error *err)
{
    if (db == NULL || db->r == NULL || out == NULL || heights_m == NULL || void_bits == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain database read: a NULL argument (or not open)");
    }
    const ft_tdb_header *h = &db->hdr;
    const char *name = (db->r->name != NULL) ? db->r->name : "(unnamed)";
    memset(out, 0, sizeof *out);
    out->state = FT_TDB_NO_DATA;
    if (level >= h->level_count) {
        return ft_fail(err, FT_ERR_ARG, "%s: tile (level %u, %u, %u): the database has %u levels",
                       name, level, tx, ty, h->level_count);
    }
    uint32_t cols = 0u, rows = 0u;
    ft_tdb_lattice_tiles(h->samples_per_deg, h->tile_samples, level, &cols, &rows);
    if (tx >= cols || ty >= rows) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s: tile (level %u, %u, %u) is outside the lattice's %u x %u tiles", name,
                       level, tx, ty, cols, rows);
    }
    const uint32_t n = h->tile_samples * h->tile_samples;
    if (heights_cap < n || bits_cap < n / 8u || (dev_m != NULL && level > 0u && dev_cap < n)) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s: tile buffers hold %zu heights, %zu void-bit bytes and %zu devs, a "
                       "tile needs %u, %u and %u",
                       name, heights_cap, bits_cap, dev_m != NULL ? dev_cap : 0u, n, n / 8u,
                       level > 0u && dev_m != NULL ? n : 0u);
    }
    const ft_tdb_entry *e = ft_tdb_find(db, level, tx, ty);
    if (e == NULL || e->state != (uint32_t)FT_TDB_DATA) {
        return FT_OK; /* no data there: recorded, not an error */
    }
    /* Sizes and offsets were checked at open; read them again for the bytes. */
    ft_status st = ft_read_at_exact(db->r, e->offset, heights_m, (size_t)n * 4u, err);
    if (st != FT_OK) {
        return st;
    }
    uint32_t crc = ft_crc32(0u, heights_m, (size_t)n * 4u);
    if (e->void_count > 0u) {
        st = ft_read_at_exact(db->r, e->offset + (uint64_t)n * 4u, void_bits, n / 8u, err);
        if (st != FT_OK) {
            return st;
        }
        crc = ft_crc32(crc, void_bits, n / 8u);
    } else {
        memset(void_bits, 0, n / 8u);
    }
    uint32_t bad_dev = UINT32_MAX;
    float bad_dev_value = 0.0f;
    if (level > 0u) {
        const uint64_t at = e->offset + (uint64_t)n * 4u + (e->void_count > 0u ? n / 8u : 0u);
        st = read_dev(db->r, at, n, dev_m, &crc, &bad_dev, &bad_dev_value, err);
        if (st != FT_OK) {
            return st;
        }
    }
    if (crc != e->crc32) {
        return ft_fail(err, FT_ERR_CHECKSUM,
                       "%s: tile (level %u, %u, %u) crc32 is 0x%08x, the index says 0x%08x", name,
                       level, tx, ty, crc, e->crc32);
    }
    if (!host_is_little_endian()) {
        for (uint32_t i = 0u; i < n; ++i) {
            heights_m[i] = le_float(&heights_m[i]);
        }
    }
    tile_stats s;
    tile_scan(heights_m, void_bits, n, &s);
    if (s.bad_index != UINT32_MAX) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: tile (level %u, %u, %u): height at row %u col %u is %g, neither "
                       "within %g..%g m nor the no-data value %g",
                       name, level, tx, ty, s.bad_index / h->tile_samples,
                       s.bad_index % h->tile_samples, (double)s.bad_value, FT_HEIGHT_MIN_M,
                       FT_HEIGHT_MAX_M, (double)FT_TDB_NODATA_M);
    }
    if (s.nodata != e->nodata_count || s.voids != e->void_count ||
        s.void_on_nodata != UINT32_MAX) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile (level %u, %u, %u) has %u uncovered and %u filled samples, the "
                       "index says %u and %u (or a void bit on an uncovered sample)",
                       name, level, tx, ty, s.nodata, s.voids, e->nodata_count, e->void_count);
    }
    /* The index bounds the whole footprint (finer levels, resampled input
     * samples): the tile's own samples lie within them. */
    const float avg = stats_avg(&s, n);
    if (s.min_m < e->min_m || s.max_m > e->max_m ||
        fabsf(avg - e->avg_m) > 1e-3f * (1.0f + fabsf(avg))) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: tile (level %u, %u, %u) heights span %g..%g m (mean %g), the index "
                       "says %g..%g m (mean %g)",
                       name, level, tx, ty, (double)s.min_m, (double)s.max_m, (double)avg,
                       (double)e->min_m, (double)e->max_m, (double)e->avg_m);
    }
    if (bad_dev != UINT32_MAX) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: tile (level %u, %u, %u): dev at row %u col %u is %g, neither within "
                       "0..%g m nor a marker (%g, %g)",
                       name, level, tx, ty, bad_dev / h->tile_samples,
                       bad_dev % h->tile_samples, (double)bad_dev_value,
                       (double)FT_TDB_DEV_MAX_M, (double)FT_TDB_DEV_NONE,
                       (double)FT_TDB_DEV_COARSER);
    }
    out->heights_m = heights_m;
    out->void_bits = void_bits;
    out->dev_m = level > 0u ? dev_m : NULL;
    out->state = FT_TDB_DATA;
    out->entry = *e;
    return FT_OK;
}
