/* terrain_file.h - the project's own terrain file (".ftt").
 *
 * Layout (all little-endian, no padding surprises: written field by field):
 *   header, FT_TFILE_HEADER_BYTES (256) long:
 *     0   char[8]  magic "FXTERR\r\n" (catches text-mode mangling)
 *     8   u32      version (FT_TFILE_VERSION)
 *     12  u32      header_bytes (256)
 *     16  u32      width, 20 u32 height (samples)
 *     24  u32      spacing_unit (0 metre, 1 degree)
 *     28  u32      avg_levels, 32 u32 minmax_levels (must equal the computed counts)
 *     36  u32      void_count (voids filled at import)
 *     40  f64      spacing_x, 48 f64 spacing_y
 *     56  f64      origin_x, 64 f64 origin_y (sample (0,0) = SW corner sample)
 *     72  f64      anchor_lat_deg, 80 f64 anchor_lon_deg
 *     88  f32      vertical_scale, 92 f32 vertical_offset: h_m = stored*scale + offset
 *     96  f32      nodata_value (what the source used for voids; info only)
 *     100 u32      void_fill_rule (1 = 8-direction inverse-distance, see void_fill.h)
 *     104 f32      min_height_m, 108 f32 max_height_m (after fill)
 *     112 u64      payload_bytes
 *     120 u32      payload_crc32 (zlib crc32 of the payload)
 *     124 u32      header_crc32 (crc32 of bytes 0..255 with this field zeroed)
 *     128 char[64] crs (NUL-terminated)
 *     192 ..255    zero
 *   payload: float32 heights (width*height, row 0 = south), then the pyramid
 *   arrays in the exact order of ft_pyramid_layout(): avg levels 1.., then per
 *   min/max level: min, max. So init reads it straight into the pools.
 *   Version 2, when void_count > 0: then the void bits (ft_terrain.void_bits:
 *   one bit per sample, set = void in the source and filled), so the
 *   renderer can show invented terrain as such; exactly void_count bits set,
 *   none past the last sample. Version 1 files are read when they filled no
 *   sample; one that did is refused (it cannot say which).
 *
 * Loading checks: magic, version (1 or 2), header size, header crc, dimensions within
 * FT_GRID_SIDE_MIN..MAX, level counts, finite spacing/origin, file size ==
 * header + payload (truncated -> FT_ERR_TRUNCATED, longer -> FT_ERR_OVERSIZED),
 * payload crc, every height finite. Never trusts a size before checking it.
 * The crcs guard transport, not meaning, so the content is checked too:
 * probe range-checks every derived quantity (cell size, extent, world
 * origin, anchor; ft_terrain_derive_frame) and the crs text
 * (ft_terrain_check_crs); the payload load checks every height against
 * FT_HEIGHT_MIN_M..MAX_M (ft_terrain_check_heights) and the pyramids against
 * the heights (ft_pyramid_check) before any method trusts them. The writer
 * runs the same checks, so it never writes a file the reader refuses. */
#ifndef FT_TERRAIN_FILE_H
#define FT_TERRAIN_FILE_H

#include "core/io.h"
#include "terrain/terrain.h"

#define FT_TFILE_MAGIC "FXTERR\r\n"
#define FT_TFILE_VERSION 2u
/* Version 1 had no void bits: read only when it filled no sample. */
#define FT_TFILE_VERSION_NO_VOID_BITS 1u
#define FT_TFILE_HEADER_BYTES 256u

/* What the probe read that the payload load needs and ft_terrain does not
 * hold. The caller keeps it between the two calls: no hidden state. */
typedef struct ft_tfile_header {
    uint32_t payload_crc32;
    float vertical_scale, vertical_offset;
    float header_min_m, header_max_m;
    size_t void_bits_bytes; /* 0: the payload has no void bits */
    int valid; /* set by a successful probe, cleared by the load (one load per probe) */
} ft_tfile_header;

/* Reads and validates the header; fills every ft_terrain field except the
 * data pointers (heights_m, pyr arrays stay NULL) and derives the frame.
 * Also checks r->size_bytes against the declared payload size. */
ft_status ft_tfile_probe(const ft_reader *r, ft_terrain *t, ft_tfile_header *hdr, ft_error *err);

/* Continues after ft_tfile_probe on the same reader: reads heights into
 * t->heights_m and pyramids into the arrays set by ft_pyramid_layout, checks
 * the crc and that heights are finite. */
ft_status ft_tfile_load_payload(const ft_reader *r, ft_terrain *t, ft_tfile_header *hdr,
                                ft_error *err);

/* Writes t (heights and built pyramids) as a terrain file. */
ft_status ft_tfile_write(const ft_terrain *t, float nodata_value, const ft_writer *w,
                         ft_error *err);

#endif
