/* dem_hgt.h - raw SRTM .hgt reader (big-endian int16, no header, -32768 void).
 *
 * Size from the file length: 1201x1201 (3") or 3601x3601 (1"), any other
 * square N*N*2 with 2 <= N <= FT_GRID_SIDE_MAX is accepted too; the SW corner
 * from the file name (N46W122.hgt; any directory prefix; case-insensitive).
 * Rows in the file run north to south; they are flipped (row 0 = south).
 * Voids are filled by ft_void_fill (void_fill.h) and counted. */
#ifndef FT_DEM_HGT_H
#define FT_DEM_HGT_H

#include <stddef.h>

#include "core/io.h"
#include "terrain/terrain.h"

#define FT_HGT_VOID (-32768)

/* Valid SRTM heights lie well inside this (Dead Sea shore -430 m, Everest
 * 8849 m); anything else that is not the void marker is a corrupt file. The
 * importer applies the same range to .hgt sources (GDAL driver SRTMHGT). */
#define FT_HGT_MIN_VALID_M (-1000)
#define FT_HGT_MAX_VALID_M 9000

/* 1 if v_m is a height an SRTM .hgt may hold: the shared terrain range
 * (ft_terrain_height_ok) narrowed to FT_HGT_MIN/MAX_VALID_M. The reader and
 * the importer (for GDAL's SRTMHGT driver) both use it. */
int ft_hgt_height_ok(double v_m);

/* Validates size and name; fills t's header fields (unit degree, spacing
 * 1/(N-1) deg, origin from the name, crs "EPSG:4326") and derives the frame. */
ft_status ft_hgt_probe(const ft_reader *r, const char *path, ft_terrain *t, ft_error *err);

/* Scratch the load needs in FT_POOL_DEM_IO: one file row + one void mark byte
 * per sample + the void fill's per-line state (ft_void_fill_scratch_bytes). */
size_t ft_hgt_scratch_bytes(uint32_t width, uint32_t height);

/* Reads the samples into t->heights_m, fills voids, sets t->void_count and
 * t->min/max_height_m. Does not build pyramids. */
ft_status ft_hgt_load(const ft_reader *r, ft_terrain *t, void *scratch, size_t scratch_bytes,
                      ft_error *err);

#endif
