/* terrain_db.h - the tiled, multi-resolution terrain database (".ftd").
 *
 * A region (many SRTM tiles, or the planet at coarse resolution) in fixed-size
 * tiles a runtime reads one at a time by position; nothing is loaded whole.
 *
 * Lattice (geographic, lon/lat degrees on WGS 84):
 *   level 0 spacing is 1/N degree, N = samples_per_deg (the finest input's
 *   spacing, e.g. N = 1200 for SRTM3, 3600 for SRTM1); level k has spacing
 *   2^k / N degree. Sample (i, j) of level k lies at
 *     lon = -180 + i * 2^k / N,   lat = -90 + j * 2^k / N
 *   (i runs east, j runs north: row 0 = south, as in terrain.h), so level k+1
 *   sample (i, j) is level k sample (2i, 2j) and whole-degree SRTM tiles fall
 *   on the lattice. Tile (k, tx, ty) holds samples i in [tx*T, tx*T + T),
 *   j in [ty*T, ty*T + T) of level k, T = tile_samples: tiles share no rows;
 *   the sample east of a tile's last column is column 0 of tile (k, tx+1, ty).
 *   A tile's lon/lat is fixed by (k, tx, ty) alone.
 *
 * Layout (all little-endian, written field by field):
 *   header, FT_TDB_HEADER_BYTES (512) long:
 *     0   char[8]  magic "FXTRDB\r\n"
 *     8   u32      version (FT_TDB_VERSION)
 *     12  u32      header_bytes (512)
 *     16  u32      tile_samples T (power of two, FT_TDB_TILE_MIN..MAX)
 *     20  u32      level_count L (1..FT_TDB_LEVELS_MAX)
 *     24  u32      samples_per_deg N (1..FT_TDB_SAMPLES_PER_DEG_MAX)
 *     28  u32      entry_count (sum over levels of cols * rows)
 *     32  u32      data_tiles (entries with state data)
 *     36  u32      index_crc32 (zlib crc32 of the index bytes)
 *     40  u32      void_fill_rule (FT_VOID_FILL_RULE_IDW8, void_fill.h)
 *     44  f32      min_height_m, 48 f32 max_height_m (over every data tile)
 *     52  u32      reserved (0)
 *     56  u64      file_bytes (the whole file)
 *     64  ..123    reserved (0)
 *     124 u32      header_crc32 (crc32 of bytes 0..511 with this field zeroed)
 *     128 level table, FT_TDB_LEVELS_MAX records of 16 bytes; record k:
 *         u32 tx0, u32 ty0, u32 cols, u32 rows: the tiles of level k the
 *         index lists (every level's box lies inside the global lattice);
 *         records at and past L are zero.
 *   index at 512: entry_count records of FT_TDB_ENTRY_BYTES (40), level by
 *   level, in each level row by row from (tx0, ty0) eastwards then north:
 *     0  u32 state (0 no data, 1 data)
 *     4  u32 byte_size (T*T*4, plus T*T/8 when void_count > 0, plus T*T*4
 *        on levels k >= 1)
 *     8  u64 offset
 *     16 u32 crc32 of the tile's bytes
 *     20 f32 min_m, 24 f32 max_m: exact bounds of every level-0-and-coarser
 *        sample under the tile's half-open footprint (the finest data there,
 *        not only the tile's own samples), for error bounds;
 *     28 f32 avg_m: mean of the tile's own covered samples
 *     32 u32 void_count: samples void in the source and filled (void_fill.h)
 *     36 u32 nodata_count: samples no input covers (FT_TDB_NODATA_M)
 *   A "no data" entry (no input covers any of its samples) is all zero: missing
 *   coverage is recorded, never invented.
 *   tiles, from 512 + entry_count * 40, in index order, packed (each data
 *   tile starts where the previous one ends, the last ends at file_bytes):
 *     T*T f32 heights, row 0 = south; a sample no input covers holds exactly
 *     FT_TDB_NODATA_M (outside the height range, so never mistaken for one);
 *     then, when void_count > 0, the void bits (one per sample, as
 *     ft_terrain.void_bits: set = void in the source and filled);
 *     then, on levels k >= 1, T*T f32 dev_m: dev_m[j*T + i] bounds, over
 *     the closed level-k cell whose south-west corner is the tile's sample
 *     (i, j), how far the finest data depart from this level's bilinear
 *     surface (below). Level 0 is the finest data: it has no dev.
 *
 * Deviation from the finest data (for error bounds drawn from coarse levels).
 *   The truth T is level 0 read by the runtime's rule (db_window.h): a
 *   sample's data, else the nearest coarser level's bilinear value where
 *   every sample with a weight has data; a point "resolves" at the level
 *   the rule takes it from. B_k is level k's bilinear surface. dev_m of a
 *   level-k cell c (closed: its edges and corners included) is:
 *   - c's 4 corners have data at level k: a bound of |T - B_k| at every
 *     point of c (every point resolves at level k or finer);
 *   - a corner lacks data ("at a data edge") and finer data lie in c: a
 *     bound of |T - r| at the points of c that resolve finer than k, where
 *     r is the mean of c's corners that have data, or the tile's avg_m when
 *     none has (its other points take a coarser level's truth);
 *   - FT_TDB_DEV_COARSER (-2): a corner lacks data and no finer data lie in
 *     c: every point of it takes a coarser level's truth;
 *   - FT_TDB_DEV_NONE (-1): not known (finer data under a level-k tile that
 *     has none: data only between its samples).
 *   It is built level by level: over each of c's 4 level-(k-1) sub-cells
 *   c', |T - B_k| <= |T - B_(k-1)| + |B_(k-1) - B_k|, and two surfaces
 *   bilinear on c' differ most at a corner of c' (likewise against r); so
 *   dev_1 is exact and each level above may add slack. Computed in double,
 *   rounded up to float, capped at FT_TDB_DEV_MAX_M (no two heights differ
 *   more). Cells past the lattice (north of the pole row; east of 180 deg
 *   on a level that does not close) lack data; on a level that closes, the
 *   sample at 180 deg is sample 0, as the runtime reads it.
 *
 * Opening checks: magic, version, sizes, header crc, T, L, N, each level's box
 * (inside the lattice; ntiles and entries within FT_TDB_ENTRIES_MAX and the
 * caller's capacity), file size == file_bytes, index crc, every entry (state,
 * exact byte size, offsets packed from the data start to the file end: no
 * overlap, no gap, none past the end; min <= avg <= max within the height
 * range; counts within T*T; a no-data entry all zero). Reading a tile checks
 * its crc, then every height (finite, in range or the no-data value), the
 * counts and min/max/avg against the index, the void bits and every dev
 * (a bound within 0..FT_TDB_DEV_MAX_M, or one of the two markers). Never
 * trusts a size before checking it. Version 1 (no dev) is refused: import
 * the inputs again. */
#ifndef FT_TERRAIN_DB_H
#define FT_TERRAIN_DB_H

#include <stddef.h>
#include <stdint.h>

#include "core/io.h"

#define FT_TDB_MAGIC "FXTRDB\r\n"
#define FT_TDB_VERSION 2u
#define FT_TDB_HEADER_BYTES 512u
#define FT_TDB_ENTRY_BYTES 40u
/* Level table records in the header: at most this many levels. */
#define FT_TDB_LEVELS_MAX 24u
#define FT_TDB_TILE_MIN 16u
#define FT_TDB_TILE_MAX 1024u
/* 36000 per degree = 0.1 arc-second: finer than any DEM this is for. */
#define FT_TDB_SAMPLES_PER_DEG_MAX 36000u
/* Index entries a database may list (40 MB of index on disk). */
#define FT_TDB_ENTRIES_MAX (1u << 20)
/* The stored value of a sample no input covers. */
#define FT_TDB_NODATA_M (-32768.0f)
/* dev_m markers (terrain_db.h top) and the largest bound: the height range. */
#define FT_TDB_DEV_NONE (-1.0f)
#define FT_TDB_DEV_COARSER (-2.0f)
#define FT_TDB_DEV_MAX_M 21000.0f

typedef enum ft_tdb_state { FT_TDB_NO_DATA = 0, FT_TDB_DATA = 1 } ft_tdb_state;

typedef struct ft_tdb_entry {
    uint32_t state; /* ft_tdb_state */
    uint32_t byte_size;
    uint64_t offset;
    uint32_t crc32;
    float min_m, max_m, avg_m;
    uint32_t void_count;
    uint32_t nodata_count;
} ft_tdb_entry;

typedef struct ft_tdb_level {
    uint32_t tx0, ty0, cols, rows; /* tiles the index lists */
    uint32_t first_entry;          /* index of (tx0, ty0) in the entry array */
} ft_tdb_level;

typedef struct ft_tdb_header {
    uint32_t tile_samples;
    uint32_t level_count;
    uint32_t samples_per_deg;
    uint32_t entry_count;
    uint32_t data_tiles;
    uint32_t index_crc32;
    uint32_t void_fill_rule;
    float min_height_m, max_height_m;
    uint64_t file_bytes;
    ft_tdb_level levels[FT_TDB_LEVELS_MAX];
} ft_tdb_header;

/* An open database: the header, and the index in the caller's array. */
typedef struct ft_tdb {
    const ft_reader_at *r;
    ft_tdb_header hdr;
    ft_tdb_entry *entries; /* caller storage, hdr.entry_count used */
} ft_tdb;

/* A tile read into caller storage. */
typedef struct ft_tdb_tile {
    float *heights_m;   /* T*T, row 0 = south; FT_TDB_NODATA_M where not covered */
    uint8_t *void_bits; /* T*T/8 bytes; all zero when the tile filled no sample */
    float *dev_m;       /* T*T on levels >= 1 when asked for; else NULL */
    ft_tdb_state state; /* FT_TDB_NO_DATA: nothing was read, heights untouched */
    ft_tdb_entry entry; /* the index entry (zero for no data) */
} ft_tdb_tile;

/* Samples of level `level` across the lattice: i < nx (lon < 180), j < ny
 * (lat <= 90). */
void ft_tdb_lattice_samples(uint32_t samples_per_deg, uint32_t level, uint64_t *nx,
                            uint64_t *ny);
/* 1 when level `level`'s lattice closes around the globe: 360 N is a whole
 * number of its spacings, so sample nx lies on sample 0 (lon 180 = -180) and
 * the level wraps in longitude, sample i being sample i mod nx. Else its
 * samples past 180 deg would fall between samples across the seam: such a
 * level does not wrap. (SRTM3 N = 1200: levels 0..7; ETOPO5 N = 12:
 * levels 0..5.) */
int ft_tdb_lattice_closes(uint32_t samples_per_deg, uint32_t level);
/* Number of tiles of level `level` across the lattice (columns, rows). */
void ft_tdb_lattice_tiles(uint32_t samples_per_deg, uint32_t tile_samples, uint32_t level,
                          uint32_t *cols, uint32_t *rows);

/* Reads and validates the header alone (the first checks of ft_tdb_open):
 * enough to plan the index and tile buffers before any memory is bound. */
ft_status ft_tdb_read_header(const ft_reader_at *r, ft_tdb_header *h, ft_error *err);

/* The tiles of `level` that hold data: box = {tx_min, ty_min, tx_max, ty_max}
 * (inclusive) and their number (0: none, box unset). Reads that level's index
 * entries in small chunks on the stack, with no memory bound; their crc is
 * checked by ft_tdb_open, which a later load runs. */
ft_status ft_tdb_data_box(const ft_reader_at *r, const ft_tdb_header *h, uint32_t level,
                          uint32_t box[4], uint32_t *data_tiles, ft_error *err);

/* Reads and validates header and index into `entries` (capacity
 * entries_cap). The reader must stay valid while db is used. */
ft_status ft_tdb_open(ft_tdb *db, const ft_reader_at *r, ft_tdb_entry *entries,
                      uint32_t entries_cap, ft_error *err);

/* The index entry of tile (level, tx, ty), or NULL when the index does not
 * list it (outside the level's box: no data as well). */
const ft_tdb_entry *ft_tdb_find(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty);

/* Reads tile (level, tx, ty) into heights_m (heights_cap floats) and
 * void_bits (bits_cap bytes). FT_OK with out->state FT_TDB_NO_DATA when the
 * database has no data there; an error (with the file, tile and reason)
 * when the tile is damaged or the arguments are outside the lattice. */
ft_status ft_tdb_read_tile(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty,
                           float *heights_m, size_t heights_cap, uint8_t *void_bits,
                           size_t bits_cap, ft_tdb_tile *out, ft_error *err);
/* The same, and the tile's dev into dev_m (dev_cap floats, T*T on levels
 * >= 1; untouched on level 0). dev_m NULL: the dev is read through a small
 * stack block and checked all the same, but not kept. */
ft_status ft_tdb_read_tile_dev(const ft_tdb *db, uint32_t level, uint32_t tx, uint32_t ty,
                               float *heights_m, size_t heights_cap, uint8_t *void_bits,
                               size_t bits_cap, float *dev_m, size_t dev_cap, ft_tdb_tile *out,
                               ft_error *err);

/* 1 when d is a stored dev: a bound within 0..FT_TDB_DEV_MAX_M or a marker. */
int ft_tdb_dev_ok(float d);

/* ---- writing (the importer; the same checks as the reader) -------------- */

/* Bytes of one data tile of `level` (T*T floats, plus the void bits when
 * voids > 0, plus T*T dev floats on levels >= 1). */
uint32_t ft_tdb_tile_bytes(uint32_t tile_samples, uint32_t void_count, uint32_t level);

/* Serialises the header (crc included) into out[FT_TDB_HEADER_BYTES]; fails
 * on a header the reader would refuse (except the index crc and file size,
 * which it cannot see). */
ft_status ft_tdb_encode_header(const ft_tdb_header *h, uint8_t *out, const char *name,
                               ft_error *err);
/* Serialises one entry into out[FT_TDB_ENTRY_BYTES]. */
void ft_tdb_encode_entry(const ft_tdb_entry *e, uint8_t *out);

/* Serialises a tile of `level` into out (ft_tdb_tile_bytes bytes) and
 * fills the entry's byte_size, crc32, counts, avg and own min/max (the
 * caller widens min/max to the footprint). dev_m (T*T, levels >= 1): NULL
 * writes FT_TDB_DEV_NONE throughout (not yet known). Checks each height and
 * dev as the reader will. */
ft_status ft_tdb_encode_tile(const float *heights_m, const uint8_t *void_bits,
                             const float *dev_m, uint32_t tile_samples, uint32_t level,
                             uint8_t *out, size_t out_cap, ft_tdb_entry *e, const char *what,
                             ft_error *err);

#endif
