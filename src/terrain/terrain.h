/* terrain.h - a height field in static memory, and its pyramids.
 *
 * Grid convention (every module uses it):
 *   sample (ix, iy), ix in [0, width), iy in [0, height); ix runs east, iy runs
 *   NORTH: row 0 is the southern edge (readers of north-up files flip rows).
 *   heights_m[iy * width + ix] is the height in metres (float32).
 *
 * World frame: metres, x east, y north, z up. Sample (ix, iy) sits at
 *   world = (origin_world_x_m + ix * cell_x_m, origin_world_y_m + iy * cell_y_m).
 * For grids in metres (a projected CRS) origin_world_* is the CRS easting /
 * northing of sample (0,0), so huge coordinates (1e7 m) stay huge in double
 * and only camera-relative offsets go to the GPU as float. For grids in
 * degrees (SRTM) the world frame is a local equirectangular plane anchored at
 * sample (0,0): origin_world = (0,0), cell_x_m = dlon * m_per_deg * cos(lat_mid).
 * The true surface is the bilinear interpolant of the samples.
 *
 * Pyramids (see pyramid.h) live in the same struct. */
#ifndef FT_TERRAIN_H
#define FT_TERRAIN_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"

/* Largest grid side the runtime accepts (also bounded by GL_MAX_TEXTURE_SIZE
 * at GPU init). 16385 = 2^14 + 1. */
#define FT_GRID_SIDE_MAX 16385u
#define FT_GRID_SIDE_MIN 2u
/* Levels: side 16385 -> 15 levels of cells (16384 .. 1). */
#define FT_PYRAMID_LEVELS_MAX 16u
#define FT_CRS_TEXT_MAX 64u

/* Mean Earth radius (IUGG), for the local equirectangular plane. */
#define FT_EARTH_RADIUS_M 6371008.8

typedef enum ft_spacing_unit { FT_UNIT_METRE = 0, FT_UNIT_DEGREE = 1 } ft_spacing_unit;

/* Earth curvature (scene terrain.curvature). Every method, ray caster and
 * the metric's truth draw a point at horizontal distance d from the eye
 * lowered by k d^2, k = 1 / (2 R), R = FT_EARTH_RADIUS_M: the parabola of the
 * sphere's drop R - sqrt(R^2 - d^2), which it under-states by d^4 / (8 R^3)
 * (0.8 m at 200 km, 7.8 m at the 357 km horizon of a 10 km eye: below
 * 0.001 deg). Heights stay above the sphere along each vertical; the
 * horizontal plane is the terrain's own (equirectangular for SRTM). */
typedef enum ft_curvature {
    FT_CURVATURE_AUTO = 0,
    FT_CURVATURE_SPHERE = 1,
    FT_CURVATURE_FLAT = 2
} ft_curvature;

typedef struct ft_pyramid_level {
    uint32_t width, height; /* texels at this level */
    float *avg_m;           /* width*height; avg[0].avg_m points at the heights */
    float *min_m;           /* width*height */
    float *max_m;           /* width*height */
} ft_pyramid_level;

/* Footprints (documented rule, both tested against brute force):
 *  - avg: level 0 is the heights themselves (width x height samples).
 *    Level l+1 texel (i,j) = mean of level-l texels (2i..2i+1, 2j..2j+1),
 *    indices clamped to the level's size. Size: ceil(w/2) x ceil(h/2).
 *  - min/max are CELL bounds: level 0 has (width-1) x (height-1) texels, texel
 *    (i,j) = min/max of the 4 samples of cell (i,j), which bounds the bilinear
 *    patch exactly. Level l+1 = min/max of level-l texels (2i..2i+1, 2j..2j+1),
 *    clamped. So texel (i,j) of level L bounds the surface over grid x in
 *    [i*2^L, min((i+1)*2^L, width-1)] (same in y): a max-mip for ray casting
 *    and a conservative bound for LOD. The last min/max level is 1x1. */
typedef struct ft_pyramid {
    uint32_t avg_levels;    /* levels in avg incl. level 0; last is 1x1 */
    uint32_t minmax_levels; /* levels in min/max; last is 1x1 */
    ft_pyramid_level avg[FT_PYRAMID_LEVELS_MAX];    /* avg[0].avg_m == heights */
    ft_pyramid_level minmax[FT_PYRAMID_LEVELS_MAX]; /* .min_m/.max_m used */
} ft_pyramid;

typedef struct ft_terrain {
    uint32_t width, height;      /* samples */
    ft_spacing_unit unit;        /* unit of spacing_* and origin_* */
    double spacing_x, spacing_y; /* distance between samples (m or deg) */
    double origin_x, origin_y;   /* sample (0,0): easting/northing m or lon/lat deg */
    double anchor_lat_deg;       /* geodetic position of sample (0,0), for */
    double anchor_lon_deg;       /* --pose LAT,LON (equirectangular about it) */
    char crs[FT_CRS_TEXT_MAX];   /* "EPSG:4326", "local", ... */
    uint32_t void_count;         /* voids found in the source and filled */
    float min_height_m, max_height_m;

    /* derived by ft_terrain_derive_frame() */
    double cell_x_m, cell_y_m;
    double origin_world_x_m, origin_world_y_m;

    /* drop per square metre of horizontal distance from the eye: 1 / (2 R)
     * on a sphere, 0 on a flat earth (ft_terrain_curvature_drop) */
    double curv_drop_per_m2;

    float *heights_m; /* width*height, in FT_POOL_HEIGHTS */
    ft_pyramid pyr;   /* levels in FT_POOL_PYRAMIDS */
    /* Which samples were void in the source and filled (invented by
     * src/terrain/void_fill.h, never measured): one bit per sample, row-major from
     * row 0, bit (i & 7) of byte i >> 3, set = filled; the bits past the
     * last sample are 0 and exactly void_count bits are set. NULL when the
     * terrain has no filled sample (in FT_POOL_HEIGHTS otherwise). */
    uint8_t *void_bits;
    /* When the terrain is a window of a terrain database (.ftd), the open
     * database and where the window sits in it, so a cache can read past
     * the window (clip_source.h); db is NULL otherwise. */
    const struct ft_tdb *db;
    uint32_t db_level;       /* the window's level */
    int64_t db_i0, db_j0;    /* the window's sample (0,0) in that level's lattice */
    float db_fill_m;         /* the window's floor for samples no level has */
} ft_terrain;

/* Ranges every terrain must keep, whatever its source (.ftt, .hgt, synth,
 * import). ft_terrain_derive_frame checks the frame, the .ftt reader and
 * writer and the importer check heights and crs with the functions below, so
 * the importer refuses exactly what the runtime would refuse.
 *  - heights: -12000..9000 m (below the deepest trench, above Everest; SRTM
 *    .hgt is narrower still, dem_hgt.h);
 *  - cell size (cell_x_m, cell_y_m): 0.001..200000 m (1 degree of latitude
 *    is 111 km);
 *  - extent ((side - 1) * cell) per axis: at most 4.1e7 m (the equator);
 *  - metre grids: |origin| and |origin + extent| at most 1e8 m;
 *  - degree grids: origin_x (lon) -360..360 deg, lon extent at most 360 deg,
 *    origin_y (lat) and the northern edge -90..90 deg, middle latitude
 *    within +-89 deg (the equirectangular plane degenerates at a pole);
 *  - anchor: |lat| <= 89, |lon| <= 360 deg;
 *  - crs: printable ASCII (0x20..0x7e), shorter than FT_CRS_TEXT_MAX. */
#define FT_HEIGHT_MIN_M (-12000.0)
#define FT_HEIGHT_MAX_M 9000.0
#define FT_CELL_MIN_M 1.0e-3
#define FT_CELL_MAX_M 2.0e5
#define FT_EXTENT_MAX_M 4.1e7
#define FT_COORD_MAX_M 1.0e8

/* Fills cell_*_m and origin_world_* from unit/spacing/origin/anchor, after
 * checking spacing, origin and anchor, and then the derived cell size,
 * extent and world origin against the ranges above; the message names the
 * field, its value and the allowed range. */
ft_status ft_terrain_derive_frame(ft_terrain *t, ft_error *err);

/* 1 if v_m is a finite height inside FT_HEIGHT_MIN_M..FT_HEIGHT_MAX_M. */
int ft_terrain_height_ok(double v_m);

/* Checks every sample of a width x height grid (row 0 = south) with
 * ft_terrain_height_ok; the message names `name`, the first bad sample's row
 * and column and the allowed range. */
ft_status ft_terrain_check_heights(const float *heights_m, uint32_t width, uint32_t height,
                                   const char *name, ft_error *err);

/* Checks crs text: NUL-terminated within FT_CRS_TEXT_MAX bytes, printable
 * ASCII only; the message names the first bad byte's offset. */
ft_status ft_terrain_check_crs(const char *crs, size_t cap, const char *name, ft_error *err);

/* Makes crs text that ft_terrain_check_crs accepts out of any bytes: each
 * run of bytes outside 0x20..0x7e (e.g. one UTF-8 encoded "é") becomes a
 * single '?', and the text is cut to FT_CRS_TEXT_MAX - 1 bytes. Returns the
 * number of runs replaced (0: the text was already clean). */
uint32_t ft_terrain_sanitize_crs(const char *in, char out[FT_CRS_TEXT_MAX]);

/* Geodetic (deg) to world metres with the equirectangular rule above; the
 * longitude is taken in its turn nearest the grid (lon +- 360 k), so a
 * position just east of 180 deg (-179.9) lies east of a grid that crosses
 * the antimeridian. */
void ft_terrain_geo_to_world(const ft_terrain *t, double lat_deg, double lon_deg, double *x_m,
                             double *y_m);

/* Bilinear height at world (x, y); clamps to the grid edge outside. */
double ft_terrain_height_at(const ft_terrain *t, double x_m, double y_m);

/* Gradient (dH/dx, dH/dy) of the bilinear surface at world (x, y), of the
 * cell that holds the clamped point (one-sided on cell edges). */
void ft_terrain_gradient_at(const ft_terrain *t, double x_m, double y_m, double *dhdx,
                            double *dhdy);

/* Earth-curvature drop coefficient for a curvature mode: 1 / (2 R) for
 * FT_CURVATURE_SPHERE, 0 for FT_CURVATURE_FLAT; FT_CURVATURE_AUTO resolves to
 * sphere for a grid in degrees (geodetic) and flat for one in metres
 * (projected or local: the file does not say it lies on the earth). */
double ft_terrain_curvature_drop(ft_curvature mode, ft_spacing_unit unit);

/* 1 if world (x, y) lies inside the grid's extent. */
int ft_terrain_contains(const ft_terrain *t, double x_m, double y_m);

/* Bytes of ft_terrain.void_bits for a w x h grid. */
size_t ft_terrain_void_bits_bytes(uint32_t w, uint32_t h);
/* 1 when sample i (row-major) was void-filled. */
int ft_terrain_sample_filled(const ft_terrain *t, size_t i);
/* Packs a byte mask (1 = void) of w x h samples into bits (zeroed first);
 * returns the number of set bits. */
uint32_t ft_terrain_pack_void_bits(const uint8_t *mask, uint32_t w, uint32_t h, uint8_t *bits);
/* Checks bits against void_count: exactly that many set, none past the
 * last sample (FT_ERR_FORMAT naming `what` otherwise). */
ft_status ft_terrain_check_void_bits(const uint8_t *bits, uint32_t w, uint32_t h,
                                     uint32_t void_count, const char *what, ft_error *err);

#endif
