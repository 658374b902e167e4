/* import_db.c - many DEMs -> one tiled multi-resolution terrain database
 * (src/terrain/terrain_db.h), tile by tile so memory stays bounded whatever
 * the region's size.
 *
 * Rules:
 *  - inputs: band 1 of each raster GDAL reads (files, every .hgt/.tif/.tiff
 *    of a directory in name order, or a VRT), in a geographic CRS (an input
 *    without a CRS, such as ETOPO5's netCDF, only with --assume-wgs84);
 *    voids and height ranges exactly as `fixterrain import` (import_gdal.c);
 *  - level 0 spacing 1/N degree, N the finest input's samples per degree
 *    (rounded when within 0.1 %, else rounded up so no input is coarsened);
 *    an input enters at its level: the first whose spacing is at least its
 *    own, so nothing is ever up-sampled;
 *  - a sample of level k comes from level k-1 where that has data (point
 *    sample: level k sample (i, j) IS level k-1 sample (2i, 2j), the same
 *    place, so a lattice point has one height on every level, neighbouring
 *    levels meet without cracks, and a shared SRTM edge row stays the
 *    measured row); else from the inputs entering at level k: a sample on
 *    the input's own grid is copied, any other is bilinear between the 4
 *    input samples around it (ETOPO5 is not exactly 5'), void if any of them
 *    with a weight is a void. Per-tile min/max bound every sample under the
 *    tile's footprint: the tile's own, the finer levels' (through the
 *    children's bounds) and the input samples the tile was resampled from
 *    (averaging, or bounds of the tile's own samples only, would lose the
 *    peaks an error bound needs);
 *  - inputs at one level: the first valid (non-void) sample wins; two valid
 *    samples of the same lattice point that differ by more than
 *    FT_IMPORT_DB_EDGE_TOL_M are reported naming both files (adjacent SRTM
 *    tiles share their edge rows: these must agree);
 *  - voids are filled with ft_void_fill (the runtime's rule) over the
 *    tile's input window widened by FT_IMPORT_DB_FILL_MARGIN samples, and
 *    marked in the tile's void bits; a window that is void throughout is left
 *    uncovered (no data), never invented;
 *  - no input, no data: tiles without a covered sample are "no data" in the
 *    index; uncovered samples of a data tile hold FT_TDB_NODATA_M.
 * This is an offline tool: it allocates with malloc and frees everything. */
#define _POSIX_C_SOURCE 200809L
#include "core/byte_codec.h"
#include "import_db.h"
#include "import_dev.h"

#include <cpl_conv.h>
#include <dirent.h>
#include <gdal.h>
#include <math.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "core/platform_api.h"
#include "terrain/dem_hgt.h"
#include "terrain/terrain.h"
#include "terrain/terrain_db.h"
#include "terrain/void_fill.h"

#define FT_EXIT_OK 0
#define FT_EXIT_ERROR 1
#define FT_EXIT_USAGE 2

#define FT_IMPORT_DB_INPUTS_MAX 4096u
#define FT_IMPORT_DB_TILE_DEFAULT 256u
/* Samples the void fill sees around a tile's window on each side: a void
 * whose nearest valid sample along a ray lies further out is filled from
 * the rays that do reach one (differs from the whole-grid .ftt import only
 * there). */
#define FT_IMPORT_DB_FILL_MARGIN 64
/* Two inputs' valid samples of one lattice point may differ this much. */
#define FT_IMPORT_DB_EDGE_TOL_M 0.5
/* A lattice point within this fraction of a pixel of an input sample IS it. */
#define FT_IMPORT_DB_ALIGN_TOL 1e-3
/* Relative spacing difference taken as equal (N rounding, level entry). */
#define FT_IMPORT_DB_SPACING_TOL 1e-3
#define FT_IMPORT_DB_PAIRS_MAX 64u
/* GDAL's block cache (its default is 5 % of RAM): with the tile buffers this
 * bounds the import's memory whatever the region's size. */
#define FT_IMPORT_DB_GDAL_CACHE_BYTES ((GIntBig)64 * 1024 * 1024)

typedef struct db_input {
    char path[FT_PATH_MAX];
    GDALDatasetH ds;
    GDALRasterBandH band;
    int w, h;
    double gt[6];
    int has_nodata;
    double nodata;
    int int16, srtm;
    double spacing_deg;                   /* the coarser axis */
    double lon_lo, lon_hi, lat_lo, lat_hi; /* sample centres, lon in -180.. */
    int full_lon;                         /* covers every longitude */
    uint32_t entry_level;
} db_input;

typedef struct db_pair {
    uint32_t a, b;
    uint64_t count;
    double max_diff_m;
} db_pair;

enum { ORIGIN_NONE = 0, ORIGIN_FINER = 1, ORIGIN_NATIVE = 2 };

typedef struct db_job {
    db_input *in;
    uint32_t n_in;
    uint32_t T, N;
    ft_tdb_header hdr;
    ft_tdb_entry *entries;
    const char *out_path;
    FILE *out;
    uint64_t offset;
    /* one tile */
    float *hv;
    uint8_t *vmask;
    uint8_t *origin;
    uint32_t *src_of;
    uint8_t *bits;
    uint8_t *bytes;
    size_t bytes_cap;
    /* one input window */
    float *win;
    uint8_t *win_void;
    size_t win_cap;
    void *fill_scratch;
    size_t fill_cap;
    uint8_t *subtree_data; /* per entry: it or a tile under it has data */
    ft_dev_stats *dev_stats; /* per level */
    db_pair pairs[FT_IMPORT_DB_PAIRS_MAX];
    uint32_t n_pairs;
    uint64_t all_void_windows;
} db_job;

static void usage(FILE *to)
{
    fprintf(to,
            "usage: fixterrain import --database OUT.ftd [--tile T] [--assume-wgs84] IN...\n"
            "Builds a tiled multi-resolution terrain database (.ftd) from DEMs GDAL reads:\n"
            "IN is a file (.hgt, GeoTIFF, netCDF, VRT, ...) or a directory of .hgt/.tif\n"
            "tiles. Level 0 has the finest input's spacing, each level doubles it; every\n"
            "level is cut into T x T sample tiles (T a power of two, %u..%u, default %u).\n"
            "--assume-wgs84 reads inputs without a CRS (ETOPO5) as lon/lat on WGS 84.\n",
            FT_TDB_TILE_MIN, FT_TDB_TILE_MAX, FT_IMPORT_DB_TILE_DEFAULT);
}

static double level_step_deg(const db_job *J, uint32_t k)
{
    return (double)((uint64_t)1u << k) / (double)J->N;
}

static void lattice_samples(const db_job *J, uint32_t k, uint64_t *nx, uint64_t *ny)
{
    const uint64_t step = (uint64_t)1u << k;
    *nx = ((uint64_t)360u * J->N + step - 1u) / step;
    *ny = (uint64_t)180u * J->N / step + 1u;
}

static int void_value(const db_input *s, float v)
{
    return !isfinite(v) || (s->has_nodata && (double)v == (double)(float)s->nodata) ||
           (s->int16 && v == -32768.0f);
}

/* ---- inputs ------------------------------------------------------------------- */

static int name_is_tile(const char *name)
{
    const char *dot = strrchr(name, '.');
    return dot != NULL && (strcasecmp(dot, ".hgt") == 0 || strcasecmp(dot, ".tif") == 0 ||
                           strcasecmp(dot, ".tiff") == 0);
}

static int cmp_names(const void *a, const void *b)
{
    return strcmp((const char *)a, (const char *)b);
}

/* Appends path (a file) or the tiles of a directory to J->in. */
static int add_input_paths(db_job *J, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        fprintf(stderr, "fixterrain import: %s: cannot open it\n", path);
        return 0;
    }
    if (!S_ISDIR(st.st_mode)) {
        if (J->n_in >= FT_IMPORT_DB_INPUTS_MAX || strlen(path) >= FT_PATH_MAX) {
            fprintf(stderr, "fixterrain import: %s: more than %u inputs or a path over %u bytes\n",
                    path, FT_IMPORT_DB_INPUTS_MAX, FT_PATH_MAX);
            return 0;
        }
        (void)snprintf(J->in[J->n_in++].path, FT_PATH_MAX, "%s", path);
        return 1;
    }
    DIR *d = opendir(path);
    if (d == NULL) {
        fprintf(stderr, "fixterrain import: %s: cannot list the directory\n", path);
        return 0;
    }
    const uint32_t first = J->n_in;
    int ok = 1;
    for (struct dirent *de = readdir(d); de != NULL; de = readdir(d)) {
        if (!name_is_tile(de->d_name)) {
            continue;
        }
        if (J->n_in >= FT_IMPORT_DB_INPUTS_MAX ||
            strlen(path) + 1u + strlen(de->d_name) >= FT_PATH_MAX) {
            fprintf(stderr, "fixterrain import: %s: more than %u inputs or a path over %u bytes\n",
                    path, FT_IMPORT_DB_INPUTS_MAX, FT_PATH_MAX);
            ok = 0;
            break;
        }
        (void)snprintf(J->in[J->n_in++].path, FT_PATH_MAX, "%s/%s", path, de->d_name);
    }
    (void)closedir(d);
    if (ok && J->n_in == first) {
        fprintf(stderr, "fixterrain import: %s: no .hgt or .tif file in the directory\n", path);
        return 0;
    }
    /* name order: the same database whatever order readdir gives */
    qsort(&J->in[first], J->n_in - first, sizeof J->in[0], cmp_names);
    return ok;
}

static int open_input(db_input *s, int assume_wgs84)
{
    CPLPushErrorHandler(CPLQuietErrorHandler);
    s->ds = GDALOpen(s->path, GA_ReadOnly);
    CPLPopErrorHandler();
    if (s->ds == NULL) {
        fprintf(stderr, "fixterrain import: %s: GDAL cannot open it as a raster: %s\n", s->path,
                CPLGetLastErrorMsg());
        return 0;
    }
    s->w = GDALGetRasterXSize(s->ds);
    s->h = GDALGetRasterYSize(s->ds);
    if (GDALGetRasterCount(s->ds) < 1 || s->w < 2 || s->h < 2) {
        fprintf(stderr, "fixterrain import: %s: no raster band of at least 2x2 samples\n",
                s->path);
        return 0;
    }
    double *gt = s->gt;
    if (GDALGetGeoTransform(s->ds, gt) != CE_None) {
        fprintf(stderr, "fixterrain import: %s: no geotransform (georeferencing)\n", s->path);
        return 0;
    }
    if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || gt[5] == 0.0 || !isfinite(gt[0]) ||
        !isfinite(gt[3]) || !isfinite(gt[1]) || !isfinite(gt[5])) {
        fprintf(stderr, "fixterrain import: %s: rotated, sheared or mirrored geotransform "
                        "(%g %g %g / %g %g %g) is not supported\n",
                s->path, gt[0], gt[1], gt[2], gt[3], gt[4], gt[5]);
        return 0;
    }
    OGRSpatialReferenceH srs = GDALGetSpatialRef(s->ds);
    if (srs == NULL && !assume_wgs84) {
        fprintf(stderr, "fixterrain import: %s: the raster has no coordinate reference system "
                        "(--assume-wgs84 reads it as lon/lat degrees)\n",
                s->path);
        return 0;
    }
    if (srs != NULL && !OSRIsGeographic(srs)) {
        fprintf(stderr, "fixterrain import: %s: a projected CRS; the database is lon/lat "
                        "(warp it to EPSG:4326 first, e.g. gdalwarp -t_srs EPSG:4326)\n",
                s->path);
        return 0;
    }
    s->band = GDALGetRasterBand(s->ds, 1);
    s->nodata = GDALGetRasterNoDataValue(s->band, &s->has_nodata);
    s->int16 = GDALGetRasterDataType(s->band) == GDT_Int16;
    GDALDriverH drv = GDALGetDatasetDriver(s->ds);
    const char *drv_name = drv != NULL ? GDALGetDriverShortName(drv) : NULL;
    s->srtm = drv_name != NULL && strcmp(drv_name, "SRTMHGT") == 0;
    const double sx = gt[1], sy = fabs(gt[5]);
    s->spacing_deg = sx > sy ? sx : sy;
    s->lon_lo = gt[0] + 0.5 * sx;
    s->lon_hi = s->lon_lo + (double)(s->w - 1) * sx;
    const double lat_a = gt[3] + 0.5 * gt[5], lat_b = gt[3] + ((double)s->h - 0.5) * gt[5];
    s->lat_lo = lat_a < lat_b ? lat_a : lat_b;
    s->lat_hi = lat_a < lat_b ? lat_b : lat_a;
    if (fabs(s->lon_lo) > 720.0 || fabs(s->lon_hi) > 720.0 || s->lat_lo < -90.0 - 0.5 * sy ||
        s->lat_hi > 90.0 + 0.5 * sy || !(sx < 10.0) || !(sy < 10.0)) {
        fprintf(stderr, "fixterrain import: %s: lon %g..%g, lat %g..%g at %g x %g deg is not a "
                        "lon/lat grid on the earth\n",
                s->path, s->lon_lo, s->lon_hi, s->lat_lo, s->lat_hi, sx, sy);
        return 0;
    }
    s->full_lon = (s->lon_hi - s->lon_lo) >= 360.0 - 1.5 * sx;
    for (int guard = 0; guard < 4 && s->lon_lo >= 180.0; ++guard) {
        s->lon_lo -= 360.0;
        s->lon_hi -= 360.0;
    }
    for (int guard = 0; guard < 4 && s->lon_lo < -180.0; ++guard) {
        s->lon_lo += 360.0;
        s->lon_hi += 360.0;
    }
    if (s->lon_hi > 180.0) {
        s->full_lon = 1; /* crosses the antimeridian: the box spans every longitude */
    }
    return 1;
}

/* Inclusive tile box of input s on level k. */
static void input_box(const db_job *J, const db_input *s, uint32_t k, uint32_t *tx0,
                      uint32_t *tx1, uint32_t *ty0, uint32_t *ty1)
{
    uint64_t nx = 0u, ny = 0u;
    lattice_samples(J, k, &nx, &ny);
    const double d = level_step_deg(J, k);
    double ilo = ceil((s->lon_lo + 180.0) / d - 1e-6), ihi = floor((s->lon_hi + 180.0) / d + 1e-6);
    double jlo = ceil((s->lat_lo + 90.0) / d - 1e-6), jhi = floor((s->lat_hi + 90.0) / d + 1e-6);
    if (s->full_lon) {
        ilo = 0.0;
        ihi = (double)(nx - 1u);
    }
    ilo = ilo < 0.0 ? 0.0 : ilo;
    jlo = jlo < 0.0 ? 0.0 : jlo;
    ihi = ihi > (double)(nx - 1u) ? (double)(nx - 1u) : ihi;
    jhi = jhi > (double)(ny - 1u) ? (double)(ny - 1u) : jhi;
    ihi = ihi < ilo ? ilo : ihi;
    jhi = jhi < jlo ? jlo : jhi;
    *tx0 = (uint32_t)((uint64_t)ilo / J->T);
    *tx1 = (uint32_t)((uint64_t)ihi / J->T);
    *ty0 = (uint32_t)((uint64_t)jlo / J->T);
    *ty1 = (uint32_t)((uint64_t)jhi / J->T);
}

/* Levels and their boxes: the union of the inputs entered so far, up to
 * the level where one tile holds it all. */
static int plan_levels(db_job *J)
{
    double finest = J->in[0].spacing_deg;
    for (uint32_t n = 1u; n < J->n_in; ++n) {
        finest = J->in[n].spacing_deg < finest ? J->in[n].spacing_deg : finest;
    }
    const double per_deg = 1.0 / finest;
    const double rounded = floor(per_deg + 0.5);
    double N = fabs(per_deg - rounded) <= FT_IMPORT_DB_SPACING_TOL * per_deg ? rounded
                                                                               : ceil(per_deg);
    if (!(N >= 1.0) || N > (double)FT_TDB_SAMPLES_PER_DEG_MAX) {
        fprintf(stderr, "fixterrain import: the finest input has %g samples per degree; the "
                        "database takes 1..%u\n",
                per_deg, FT_TDB_SAMPLES_PER_DEG_MAX);
        return 0;
    }
    J->N = (uint32_t)N;
    uint32_t max_entry = 0u;
    for (uint32_t n = 0u; n < J->n_in; ++n) {
        db_input *s = &J->in[n];
        uint32_t k = 0u;
        while (k + 1u < FT_TDB_LEVELS_MAX &&
               level_step_deg(J, k) < s->spacing_deg * (1.0 - FT_IMPORT_DB_SPACING_TOL)) {
            ++k;
        }
        s->entry_level = k;
        max_entry = k > max_entry ? k : max_entry;
    }
    uint64_t entries = 0u;
    uint32_t L = 0u;
    for (uint32_t k = 0u; k < FT_TDB_LEVELS_MAX; ++k) {
        uint32_t bx0 = UINT32_MAX, bx1 = 0u, by0 = UINT32_MAX, by1 = 0u;
        for (uint32_t n = 0u; n < J->n_in; ++n) {
            if (J->in[n].entry_level > k) {
                continue;
            }
            uint32_t x0, x1, y0, y1;
            input_box(J, &J->in[n], k, &x0, &x1, &y0, &y1);
            bx0 = x0 < bx0 ? x0 : bx0;
            by0 = y0 < by0 ? y0 : by0;
            bx1 = x1 > bx1 ? x1 : bx1;
            by1 = y1 > by1 ? y1 : by1;
        }
        ft_tdb_level *lv = &J->hdr.levels[k];
        lv->tx0 = bx0;
        lv->ty0 = by0;
        lv->cols = bx1 - bx0 + 1u;
        lv->rows = by1 - by0 + 1u;
        lv->first_entry = (uint32_t)entries;
        entries += (uint64_t)lv->cols * lv->rows;
        L = k + 1u;
        if (entries > FT_TDB_ENTRIES_MAX) {
            fprintf(stderr, "fixterrain import: levels 0..%u need %llu index entries, more than "
                            "%u (a larger --tile, or a smaller region)\n",
                    k, (unsigned long long)entries, FT_TDB_ENTRIES_MAX);
            return 0;
        }
        if (k >= max_entry && lv->cols == 1u && lv->rows == 1u) {
            break;
        }
    }
    if (max_entry >= L) {
        fprintf(stderr, "fixterrain import: an input enters at level %u, past the %u levels\n",
                max_entry, FT_TDB_LEVELS_MAX);
        return 0;
    }
    J->hdr.level_count = L;
    J->hdr.entry_count = (uint32_t)entries;
    return 1;
}

/* ---- one tile ------------------------------------------------------------------ */

static void note_pair(db_job *J, uint32_t a, uint32_t b, double diff_m)
{
    for (uint32_t p = 0u; p < J->n_pairs; ++p) {
        if (J->pairs[p].a == a && J->pairs[p].b == b) {
            J->pairs[p].count++;
            J->pairs[p].max_diff_m = diff_m > J->pairs[p].max_diff_m ? diff_m : J->pairs[p].max_diff_m;
            return;
        }
    }
    if (J->n_pairs < FT_IMPORT_DB_PAIRS_MAX) {
        J->pairs[J->n_pairs++] = (db_pair){a, b, 1u, diff_m};
    }
}

static float le_f32(const uint8_t *p)
{
    uint32_t u = (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
                 ((uint32_t)p[3] << 24);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Point-samples the four level k-1 children of tile (k, tx, ty) into the
 * tile; widens the footprint bounds with theirs. */
static int take_children(db_job *J, uint32_t k, uint32_t tx, uint32_t ty, float *fmin,
                         float *fmax)
{
    const uint32_t T = J->T, half = T / 2u;
    const ft_tdb_level *cl = &J->hdr.levels[k - 1u];
    for (uint32_t b = 0u; b < 2u; ++b) {
        for (uint32_t a = 0u; a < 2u; ++a) {
            const uint32_t cx = 2u * tx + a, cy = 2u * ty + b;
            if (cx < cl->tx0 || cy < cl->ty0 || cx - cl->tx0 >= cl->cols ||
                cy - cl->ty0 >= cl->rows) {
                continue;
            }
            const ft_tdb_entry *e =
                &J->entries[cl->first_entry + (cy - cl->ty0) * cl->cols + (cx - cl->tx0)];
            if (e->state != FT_TDB_DATA) {
                continue;
            }
            *fmin = e->min_m < *fmin ? e->min_m : *fmin;
            *fmax = e->max_m > *fmax ? e->max_m : *fmax;
            if (fseeko(J->out, (off_t)e->offset, SEEK_SET) != 0 ||
                fread(J->bytes, 1, e->byte_size, J->out) != e->byte_size) {
                fprintf(stderr, "fixterrain import: %s: reading back tile (level %u, %u, %u) "
                                "failed\n",
                        J->out_path, k - 1u, cx, cy);
                return 0;
            }
            const uint8_t *vb = e->void_count > 0u ? J->bytes + (size_t)T * T * 4u : NULL;
            for (uint32_t cj = 0u; cj < T; cj += 2u) {
                for (uint32_t ci = 0u; ci < T; ci += 2u) {
                    const size_t c = (size_t)cj * T + ci;
                    const float v = le_f32(J->bytes + c * 4u);
                    if (v == FT_TDB_NODATA_M) {
                        continue;
                    }
                    const size_t p = (size_t)(b * half + cj / 2u) * T + (a * half + ci / 2u);
                    J->hv[p] = v;
                    J->vmask[p] = (uint8_t)(vb != NULL && ((vb[c >> 3] >> (c & 7u)) & 1u));
                    J->origin[p] = ORIGIN_FINER;
                }
            }
        }
    }
    return 1;
}

/* Reads input s's window around the tile, fills its voids, and samples it
 * onto the tile's lattice points not taken from a finer level. */
static int take_input(db_job *J, uint32_t src, uint32_t k, uint32_t tx, uint32_t ty,
                      double shift, float *fmin, float *fmax)
{
    const db_input *s = &J->in[src];
    const uint32_t T = J->T;
    const double d = level_step_deg(J, k);
    const double lon_a = -180.0 + (double)tx * T * d, lon_b = lon_a + (double)(T - 1u) * d;
    const double lat_a = -90.0 + (double)ty * T * d, lat_b = lat_a + (double)(T - 1u) * d;
    const double *gt = s->gt;
    double fx_a = (lon_a + shift - gt[0]) / gt[1] - 0.5;
    double fx_b = (lon_b + shift - gt[0]) / gt[1] - 0.5;
    double fy_a = (lat_a - gt[3]) / gt[5] - 0.5, fy_b = (lat_b - gt[3]) / gt[5] - 0.5;
    double ylo = fy_a < fy_b ? fy_a : fy_b, yhi = fy_a < fy_b ? fy_b : fy_a;
    const double m = (double)FT_IMPORT_DB_FILL_MARGIN;
    double x0 = floor(fx_a) - m, x1 = ceil(fx_b) + m, y0 = floor(ylo) - m, y1 = ceil(yhi) + m;
    x0 = x0 < 0.0 ? 0.0 : x0;
    y0 = y0 < 0.0 ? 0.0 : y0;
    x1 = x1 > (double)(s->w - 1) ? (double)(s->w - 1) : x1;
    y1 = y1 > (double)(s->h - 1) ? (double)(s->h - 1) : y1;
    if (x1 < x0 || y1 < y0) {
        return 1; /* no overlap after all */
    }
    const int wx0 = (int)x0, wy0 = (int)y0, ww = (int)(x1 - x0) + 1, wh = (int)(y1 - y0) + 1;
    const size_t wn = (size_t)ww * (size_t)wh;
    const size_t fill_bytes = ft_void_fill_scratch_bytes((uint32_t)ww, (uint32_t)wh);
    if (wn > J->win_cap || fill_bytes > J->fill_cap) {
        fprintf(stderr, "fixterrain import: %s: a %dx%d window for tile (level %u, %u, %u) "
                        "exceeds the planned %zu samples\n",
                s->path, ww, wh, k, tx, ty, J->win_cap);
        return 0;
    }
    if (GDALRasterIO(s->band, GF_Read, wx0, wy0, ww, wh, J->win, ww, wh, GDT_Float32, 0, 0) !=
        CE_None) {
        fprintf(stderr, "fixterrain import: %s: read of %dx%d samples at col %d row %d failed: "
                        "%s\n",
                s->path, ww, wh, wx0, wy0, CPLGetLastErrorMsg());
        return 0;
    }
    uint32_t voids = 0u;
    for (size_t i = 0u; i < wn; ++i) {
        const float v = J->win[i];
        const int is_void = void_value(s, v);
        const int ok = s->srtm ? ft_hgt_height_ok((double)v) : ft_terrain_height_ok((double)v);
        if (!is_void && !ok) {
            fprintf(stderr,
                    "fixterrain import: %s: height %g m at row %d col %d is outside the %g..%g m "
                    "the runtime accepts%s (mark it nodata or fix the source)\n",
                    s->path, (double)v, wy0 + (int)(i / (size_t)ww), wx0 + (int)(i % (size_t)ww),
                    s->srtm ? (double)FT_HGT_MIN_VALID_M : FT_HEIGHT_MIN_M,
                    s->srtm ? (double)FT_HGT_MAX_VALID_M : FT_HEIGHT_MAX_M,
                    s->srtm ? " from an SRTM .hgt" : "");
            return 0;
        }
        J->win_void[i] = (uint8_t)is_void;
        voids += (uint32_t)is_void;
        if (is_void) {
            J->win[i] = 0.0f;
        }
    }
    if (voids == wn) {
        J->all_void_windows++;
        return 1; /* nothing measured here: left uncovered, not invented */
    }
    if (voids > 0u) {
        int all_void = 0;
        uint32_t filled = ft_void_fill(J->win, J->win_void, (uint32_t)ww, (uint32_t)wh,
                                       J->fill_scratch, J->fill_cap, &all_void);
        if (filled != voids || all_void) {
            fprintf(stderr, "fixterrain import: %s: void fill filled %u of %u voids\n", s->path,
                    filled, voids);
            return 0;
        }
    }
    uint64_t nx = 0u, ny = 0u;
    lattice_samples(J, k, &nx, &ny);
    const double tol = FT_IMPORT_DB_ALIGN_TOL;
    /* A global input (ETOPO5: 0 .. 359.92 deg E) leaves a seam between its
     * last and first column: points there take the nearer edge column (the
     * bilinear weights clamp), instead of a strip of no data around the
     * globe. Each side reaches half the seam. */
    const double seam_px = 360.0 / gt[1] - (double)(s->w - 1);
    const double xtol = (s->full_lon && seam_px > 0.0) ? 0.5 * seam_px + tol : tol;
    for (uint32_t tj = 0u; tj < T; ++tj) {
        const uint64_t j = (uint64_t)ty * T + tj;
        if (j >= ny) {
            break;
        }
        const double lat = -90.0 + (double)j * d;
        const double gy = (lat - gt[3]) / gt[5] - 0.5;
        if (gy < -tol || gy > (double)(s->h - 1) + tol) {
            continue;
        }
        for (uint32_t ti = 0u; ti < T; ++ti) {
            const uint64_t i = (uint64_t)tx * T + ti;
            if (i >= nx) {
                break;
            }
            const size_t p = (size_t)tj * T + ti;
            if (J->origin[p] == ORIGIN_FINER) {
                continue; /* the finer level's sample wins */
            }
            if (J->origin[p] == ORIGIN_NATIVE && J->src_of[p] == src) {
                continue; /* this input gave it already, under another shift */
            }
            const double lon = -180.0 + (double)i * d + shift;
            const double gx = (lon - gt[0]) / gt[1] - 0.5;
            if (gx < -xtol || gx > (double)(s->w - 1) + xtol) {
                continue;
            }
            double rx = floor(gx + 0.5), ry = floor(gy + 0.5);
            float v;
            int is_void;
            if (fabs(gx - rx) <= tol && fabs(gy - ry) <= tol) {
                rx = rx < 0.0 ? 0.0 : (rx > (double)(s->w - 1) ? (double)(s->w - 1) : rx);
                ry = ry < 0.0 ? 0.0 : (ry > (double)(s->h - 1) ? (double)(s->h - 1) : ry);
                const size_t q = (size_t)((int)ry - wy0) * (size_t)ww + (size_t)((int)rx - wx0);
                v = J->win[q];
                is_void = J->win_void[q];
            } else {
                double bx = floor(gx), by = floor(gy);
                bx = bx < 0.0 ? 0.0 : (bx > (double)(s->w - 2) ? (double)(s->w - 2) : bx);
                by = by < 0.0 ? 0.0 : (by > (double)(s->h - 2) ? (double)(s->h - 2) : by);
                double fx = gx - bx, fy = gy - by;
                fx = fx < 0.0 ? 0.0 : (fx > 1.0 ? 1.0 : fx);
                fy = fy < 0.0 ? 0.0 : (fy > 1.0 ? 1.0 : fy);
                const int cx = (int)bx - wx0, cy = (int)by - wy0;
                if (cx < 0 || cy < 0 || cx + 1 >= ww || cy + 1 >= wh) {
                    continue; /* cannot happen: the window holds the margin */
                }
                const size_t q = (size_t)cy * (size_t)ww + (size_t)cx;
                const double w00 = (1.0 - fx) * (1.0 - fy), w10 = fx * (1.0 - fy);
                const double w01 = (1.0 - fx) * fy, w11 = fx * fy;
                v = (float)(w00 * J->win[q] + w10 * J->win[q + 1u] +
                            w01 * J->win[q + (size_t)ww] + w11 * J->win[q + (size_t)ww + 1u]);
                is_void = (w00 > 0.0 && J->win_void[q]) || (w10 > 0.0 && J->win_void[q + 1u]) ||
                          (w01 > 0.0 && J->win_void[q + (size_t)ww]) ||
                          (w11 > 0.0 && J->win_void[q + (size_t)ww + 1u]);
            }
            if (J->origin[p] == ORIGIN_NATIVE) {
                /* a second input of this level here: a valid sample beats a
                 * filled one; two valid ones must agree (shared edge rows) */
                if (!J->vmask[p] && !is_void) {
                    const double diff = fabs((double)J->hv[p] - (double)v);
                    if (diff > FT_IMPORT_DB_EDGE_TOL_M) {
                        note_pair(J, J->src_of[p], src, diff);
                    }
                    continue;
                }
                if (!(J->vmask[p] && !is_void)) {
                    continue;
                }
            }
            J->hv[p] = v;
            J->vmask[p] = (uint8_t)is_void;
            J->origin[p] = ORIGIN_NATIVE;
            J->src_of[p] = src;
        }
    }
    /* The bounds cover the input's own samples too, not only the lattice
     * points sampled from them: a resampled (coarser) input's peak between
     * lattice points must not escape the tile's max. Each input sample
     * counts for the tile of its nearest lattice point when this input
     * supplied that point (not a finer level, not another input). */
    for (int y = 0; y < wh; ++y) {
        const double lat = gt[3] + ((double)(wy0 + y) + 0.5) * gt[5];
        const double fj = floor((lat - lat_a) / d + 0.5);
        if (fj < 0.0 || fj >= (double)T || (uint64_t)ty * T + (uint64_t)fj >= ny) {
            continue;
        }
        for (int x = 0; x < ww; ++x) {
            const double lon = gt[0] + ((double)(wx0 + x) + 0.5) * gt[1] - shift;
            const double fi = floor((lon - lon_a) / d + 0.5);
            if (fi < 0.0 || fi >= (double)T || (uint64_t)tx * T + (uint64_t)fi >= nx) {
                continue;
            }
            const size_t p = (size_t)fj * T + (size_t)fi;
            if (J->origin[p] != ORIGIN_NATIVE || J->src_of[p] != src) {
                continue; /* that point came from a finer level or another input */
            }
            const float v = J->win[(size_t)y * (size_t)ww + (size_t)x];
            *fmin = v < *fmin ? v : *fmin;
            *fmax = v > *fmax ? v : *fmax;
        }
    }
    return 1;
}

static int input_overlaps(const db_job *J, const db_input *s, uint32_t k, uint32_t tx,
                          uint32_t ty, double shift)
{
    const double d = level_step_deg(J, k), T = (double)J->T;
    const double lon_a = -180.0 + (double)tx * T * d + shift, lon_b = lon_a + (T - 1.0) * d;
    const double lat_a = -90.0 + (double)ty * T * d, lat_b = lat_a + (T - 1.0) * d;
    const double olo = s->gt[0] + 0.5 * s->gt[1];
    const double ohi = olo + (double)(s->w - 1) * s->gt[1];
    const double e = 0.5 * s->spacing_deg;
    return lon_b >= olo - e && lon_a <= ohi + e && lat_b >= s->lat_lo - e &&
           lat_a <= s->lat_hi + e;
}

static const double k_shifts[3] = {0.0, 360.0, -360.0};

/* 1 when a child tile has data or an input entering at level k overlaps
 * tile (k, tx, ty): most tiles of a sparse region have neither, and are
 * recorded as no data without touching the tile buffers. */
static int tile_has_sources(const db_job *J, uint32_t k, uint32_t tx, uint32_t ty)
{
    if (k > 0u) {
        const ft_tdb_level *cl = &J->hdr.levels[k - 1u];
        for (uint32_t c = 0u; c < 4u; ++c) {
            const uint32_t cx = 2u * tx + (c & 1u), cy = 2u * ty + (c >> 1);
            if (cx >= cl->tx0 && cy >= cl->ty0 && cx - cl->tx0 < cl->cols &&
                cy - cl->ty0 < cl->rows &&
                J->entries[cl->first_entry + (cy - cl->ty0) * cl->cols + (cx - cl->tx0)]
                        .state == FT_TDB_DATA) {
                return 1;
            }
        }
    }
    for (uint32_t src = 0u; src < J->n_in; ++src) {
        for (uint32_t sh = 0u; sh < 3u && J->in[src].entry_level == k; ++sh) {
            if (input_overlaps(J, &J->in[src], k, tx, ty, k_shifts[sh])) {
                return 1;
            }
        }
    }
    return 0;
}

/* 1 when a level k-1 tile under tile (k, tx, ty), or one under that, has
 * data (their flags are set: levels are built upwards). */
static int children_have_data(const db_job *J, uint32_t k, uint32_t tx, uint32_t ty)
{
    if (k == 0u) {
        return 0;
    }
    const ft_tdb_level *cl = &J->hdr.levels[k - 1u];
    for (uint32_t c = 0u; c < 4u; ++c) {
        const uint32_t cx = 2u * tx + (c & 1u), cy = 2u * ty + (c >> 1);
        if (cx >= cl->tx0 && cy >= cl->ty0 && cx - cl->tx0 < cl->cols &&
            cy - cl->ty0 < cl->rows &&
            J->subtree_data[cl->first_entry + (cy - cl->ty0) * cl->cols + (cx - cl->tx0)]) {
            return 1;
        }
    }
    return 0;
}

static int build_tile(db_job *J, uint32_t k, uint32_t tx, uint32_t ty, ft_tdb_entry *e)
{
    const uint32_t T = J->T;
    const size_t n = (size_t)T * T;
    memset(e, 0, sizeof *e);
    if (!tile_has_sources(J, k, tx, ty)) {
        return 1; /* no data: recorded in the index, nothing written */
    }
    for (size_t i = 0u; i < n; ++i) {
        J->hv[i] = FT_TDB_NODATA_M;
    }
    memset(J->vmask, 0, n);
    memset(J->origin, 0, n);
    float fmin = INFINITY, fmax = -INFINITY;
    if (k > 0u && !take_children(J, k, tx, ty, &fmin, &fmax)) {
        return 0;
    }
    for (uint32_t src = 0u; src < J->n_in; ++src) {
        if (J->in[src].entry_level != k) {
            continue;
        }
        for (uint32_t sh = 0u; sh < 3u; ++sh) {
            if (input_overlaps(J, &J->in[src], k, tx, ty, k_shifts[sh]) &&
                !take_input(J, src, k, tx, ty, k_shifts[sh], &fmin, &fmax)) {
                return 0;
            }
        }
    }
    int covered = 0;
    for (size_t i = 0u; i < n && !covered; ++i) {
        covered = J->hv[i] != FT_TDB_NODATA_M;
    }
    if (!covered) {
        return 1; /* no data: recorded in the index, nothing written */
    }
    (void)ft_terrain_pack_void_bits(J->vmask, T, T, J->bits);
    char what[FT_PATH_MAX + 64];
    (void)snprintf(what, sizeof what, "%s: tile (level %u, %u, %u)", J->out_path, k, tx, ty);
    ft_error err;
    /* dev: "not known" until the level's deviation pass (import_dev.c) */
    if (ft_tdb_encode_tile(J->hv, J->bits, NULL, T, k, J->bytes, J->bytes_cap, e, what, &err) !=
        FT_OK) {
        fprintf(stderr, "fixterrain import: %s\n", err.text);
        return 0;
    }
    /* footprint bounds: the tile's own samples and every finer one under it */
    e->min_m = fmin < e->min_m ? fmin : e->min_m;
    e->max_m = fmax > e->max_m ? fmax : e->max_m;
    e->offset = J->offset;
    if (fseeko(J->out, (off_t)J->offset, SEEK_SET) != 0 ||
        fwrite(J->bytes, 1, e->byte_size, J->out) != e->byte_size) {
        fprintf(stderr, "fixterrain import: %s: writing tile (level %u, %u, %u) failed\n",
                J->out_path, k, tx, ty);
        return 0;
    }
    J->offset += e->byte_size;
    return 1;
}

/* ---- the command ----------------------------------------------------------------- */

static int plan_buffers(db_job *J)
{
    const size_t n = (size_t)J->T * J->T;
    size_t win_w = 2u, win_h = 2u;
    for (uint32_t i = 0u; i < J->n_in; ++i) {
        const db_input *s = &J->in[i];
        const double span = (double)J->T * level_step_deg(J, s->entry_level);
        double ww = ceil(span / s->gt[1]) + 3.0 + 2.0 * FT_IMPORT_DB_FILL_MARGIN;
        double wh = ceil(span / fabs(s->gt[5])) + 3.0 + 2.0 * FT_IMPORT_DB_FILL_MARGIN;
        ww = ww > (double)s->w ? (double)s->w : ww;
        wh = wh > (double)s->h ? (double)s->h : wh;
        win_w = (size_t)ww > win_w ? (size_t)ww : win_w;
        win_h = (size_t)wh > win_h ? (size_t)wh : win_h;
    }
    J->win_cap = win_w * win_h;
    J->fill_cap = ft_void_fill_scratch_bytes((uint32_t)win_w, (uint32_t)win_h);
    J->bytes_cap = ft_tdb_tile_bytes(J->T, 1u, 1u);
    J->hv = malloc(n * sizeof(float));
    J->vmask = malloc(n);
    J->origin = malloc(n);
    J->src_of = malloc(n * sizeof(uint32_t));
    J->bits = malloc(n / 8u);
    J->bytes = malloc(J->bytes_cap);
    J->win = malloc(J->win_cap * sizeof(float));
    J->win_void = malloc(J->win_cap);
    J->fill_scratch = malloc(J->fill_cap > 0u ? J->fill_cap : 1u);
    J->entries = calloc(J->hdr.entry_count, sizeof(ft_tdb_entry));
    J->subtree_data = calloc(J->hdr.entry_count, 1u);
    return J->subtree_data != NULL && J->hv != NULL && J->vmask != NULL && J->origin != NULL && J->src_of != NULL &&
           J->bits != NULL && J->bytes != NULL && J->win != NULL && J->win_void != NULL &&
           J->fill_scratch != NULL && J->entries != NULL;
}

static void free_job(db_job *J)
{
    free(J->hv);
    free(J->vmask);
    free(J->origin);
    free(J->src_of);
    free(J->bits);
    free(J->bytes);
    free(J->win);
    free(J->win_void);
    free(J->fill_scratch);
    free(J->entries);
    free(J->subtree_data);
    free(J->dev_stats);
    for (uint32_t i = 0u; J->in != NULL && i < J->n_in; ++i) {
        if (J->in[i].ds != NULL) {
            GDALClose(J->in[i].ds);
        }
    }
    free(J->in);
}

static int write_index_and_header(db_job *J)
{
    uint8_t rec[FT_TDB_ENTRY_BYTES];
    uint32_t crc = ft_crc32(0u, NULL, 0u);
    if (fseeko(J->out, (off_t)FT_TDB_HEADER_BYTES, SEEK_SET) != 0) {
        return 0;
    }
    float lo = INFINITY, hi = -INFINITY;
    uint32_t data = 0u;
    for (uint32_t n = 0u; n < J->hdr.entry_count; ++n) {
        const ft_tdb_entry *e = &J->entries[n];
        ft_tdb_encode_entry(e, rec);
        crc = ft_crc32(crc, rec, sizeof rec);
        if (fwrite(rec, 1, sizeof rec, J->out) != sizeof rec) {
            return 0;
        }
        if (e->state == FT_TDB_DATA) {
            ++data;
            lo = e->min_m < lo ? e->min_m : lo;
            hi = e->max_m > hi ? e->max_m : hi;
        }
    }
    J->hdr.index_crc32 = crc;
    J->hdr.data_tiles = data;
    J->hdr.min_height_m = data > 0u ? lo : 0.0f;
    J->hdr.max_height_m = data > 0u ? hi : 0.0f;
    J->hdr.file_bytes = J->offset;
    uint8_t hb[FT_TDB_HEADER_BYTES];
    ft_error err;
    if (ft_tdb_encode_header(&J->hdr, hb, J->out_path, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s\n", err.text);
        return 0;
    }
    return fseeko(J->out, 0, SEEK_SET) == 0 && fwrite(hb, 1, sizeof hb, J->out) == sizeof hb;
}

int ft_cmd_import_db(int argc, char **argv)
{
    db_job J;
    memset(&J, 0, sizeof J);
    J.T = FT_IMPORT_DB_TILE_DEFAULT;
    int assume_wgs84 = 0;
    J.in = calloc(FT_IMPORT_DB_INPUTS_MAX, sizeof(db_input));
    if (J.in == NULL) {
        fprintf(stderr, "fixterrain import: out of memory\n");
        return FT_EXIT_ERROR;
    }
    int rc = FT_EXIT_USAGE;
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            free_job(&J);
            return FT_EXIT_OK;
        }
        if (strcmp(arg, "--database") == 0 && a + 1 < argc) {
            J.out_path = argv[++a];
        } else if (strcmp(arg, "--tile") == 0 && a + 1 < argc) {
            char *end = NULL;
            unsigned long t = strtoul(argv[++a], &end, 10);
            if (end == argv[a] || *end != '\0' || t < FT_TDB_TILE_MIN || t > FT_TDB_TILE_MAX ||
                (t & (t - 1u)) != 0u) {
                fprintf(stderr, "fixterrain import: --tile %s is not a power of two within "
                                "%u..%u\n",
                        argv[a], FT_TDB_TILE_MIN, FT_TDB_TILE_MAX);
                goto done;
            }
            J.T = (uint32_t)t;
        } else if (strcmp(arg, "--assume-wgs84") == 0) {
            assume_wgs84 = 1;
        } else if (strcmp(arg, "--database") == 0 || strcmp(arg, "--tile") == 0) {
            fprintf(stderr, "fixterrain import: %s needs a value\n", arg);
            usage(stderr);
            goto done;
        } else if (arg[0] == '-' && arg[1] == '-') {
            fprintf(stderr, "fixterrain import: unknown option %s\n", arg);
            usage(stderr);
            goto done;
        } else if (!add_input_paths(&J, arg)) {
            rc = FT_EXIT_ERROR;
            goto done;
        }
    }
    if (J.out_path == NULL || J.n_in == 0u) {
        usage(stderr);
        goto done;
    }
    rc = FT_EXIT_ERROR;
    const uint64_t t0_ns = ft_plat_monotonic_ns();
    GDALAllRegister();
    GDALSetCacheMax64(FT_IMPORT_DB_GDAL_CACHE_BYTES);
    for (uint32_t i = 0u; i < J.n_in; ++i) {
        if (!open_input(&J.in[i], assume_wgs84)) {
            goto done;
        }
    }
    if (!plan_levels(&J)) {
        goto done;
    }
    J.hdr.tile_samples = J.T;
    J.hdr.samples_per_deg = J.N;
    J.hdr.void_fill_rule = FT_VOID_FILL_RULE_IDW8;
    if (!plan_buffers(&J)) {
        fprintf(stderr, "fixterrain import: out of memory for %u-sample tiles\n", J.T);
        goto done;
    }
    char tmp[FT_PATH_MAX + 8];
    if (strlen(J.out_path) >= FT_PATH_MAX) {
        fprintf(stderr, "fixterrain import: output path longer than %u bytes\n", FT_PATH_MAX);
        goto done;
    }
    (void)snprintf(tmp, sizeof tmp, "%s.tmp", J.out_path);
    J.out = fopen(tmp, "w+b");
    if (J.out == NULL) {
        fprintf(stderr, "fixterrain import: %s: cannot create it\n", tmp);
        goto done;
    }
    J.offset = (uint64_t)FT_TDB_HEADER_BYTES + (uint64_t)J.hdr.entry_count * FT_TDB_ENTRY_BYTES;
    J.dev_stats = calloc(J.hdr.level_count, sizeof(ft_dev_stats));
    ft_dev_pass dev;
    memset(&dev, 0, sizeof dev);
    int ok = J.dev_stats != NULL &&
             ft_dev_pass_init(&dev, J.out, J.out_path, &J.hdr, J.entries, J.subtree_data);
    if (!ok) {
        fprintf(stderr, "fixterrain import: out of memory for the deviation pass\n");
    }
    for (uint32_t k = 0u; k < J.hdr.level_count && ok; ++k) {
        const ft_tdb_level *lv = &J.hdr.levels[k];
        for (uint32_t r = 0u; r < lv->rows && ok; ++r) {
            for (uint32_t c = 0u; c < lv->cols && ok; ++c) {
                const uint32_t n = lv->first_entry + r * lv->cols + c;
                ok = build_tile(&J, k, lv->tx0 + c, lv->ty0 + r, &J.entries[n]);
                J.subtree_data[n] = (uint8_t)(J.entries[n].state == FT_TDB_DATA ||
                                              children_have_data(&J, k, lv->tx0 + c, lv->ty0 + r));
            }
        }
        /* the level is written: bound how far it departs from the finest data */
        ok = ok && (k == 0u || ft_dev_pass_level(&dev, k, &J.dev_stats[k]));
    }
    ft_dev_pass_free(&dev);
    ok = ok && write_index_and_header(&J);
    ok = ok && fflush(J.out) == 0 && fsync(fileno(J.out)) == 0;
    if (fclose(J.out) != 0) {
        ok = 0;
    }
    J.out = NULL;
    if (!ok || rename(tmp, J.out_path) != 0) {
        fprintf(stderr, "fixterrain import: %s: the database was not written\n", J.out_path);
        (void)unlink(tmp);
        goto done;
    }
    for (uint32_t p = 0u; p < J.n_pairs; ++p) {
        fprintf(stderr, "fixterrain import: warning: %s and %s disagree at %llu shared samples "
                        "by up to %.2f m (more than %.2f m); %s was kept\n",
                J.in[J.pairs[p].a].path, J.in[J.pairs[p].b].path,
                (unsigned long long)J.pairs[p].count, J.pairs[p].max_diff_m,
                FT_IMPORT_DB_EDGE_TOL_M, J.in[J.pairs[p].a].path);
    }
    const double secs = (double)(ft_plat_monotonic_ns() - t0_ns) * 1e-9;
    printf("imported %u inputs -> %s: %u levels, %ux%u-sample tiles, level 0 spacing 1/%u deg, "
           "%u of %u tiles with data, heights %.1f..%.1f m, %llu bytes, %.2f s\n",
           J.n_in, J.out_path, J.hdr.level_count, J.T, J.T, J.N, J.hdr.data_tiles,
           J.hdr.entry_count, (double)J.hdr.min_height_m, (double)J.hdr.max_height_m,
           (unsigned long long)J.hdr.file_bytes, secs);
    for (uint32_t k = 0u; k < J.hdr.level_count; ++k) {
        const ft_tdb_level *lv = &J.hdr.levels[k];
        uint32_t data = 0u;
        for (uint32_t n = 0u; n < lv->cols * lv->rows; ++n) {
            data += J.entries[lv->first_entry + n].state == FT_TDB_DATA ? 1u : 0u;
        }
        printf("  level %u: spacing %.6g arc-s, tiles x %u+%u y %u+%u: %u data, %u no data\n", k,
               3600.0 * level_step_deg(&J, k), lv->tx0, lv->cols, lv->ty0, lv->rows, data,
               lv->cols * lv->rows - data);
        const ft_dev_stats *ds = &J.dev_stats[k];
        const uint64_t cells =
            ds->bound_cells + ds->partial_cells + ds->none_cells + ds->coarser_cells;
        if (k > 0u && cells > 0u) {
            printf("    dev from the finest data: %llu cells bound, p50 %.1f p99 %.1f max %.2f "
                   "mean %.2f m; %llu at a data edge, %llu coarser data only, %llu no bound "
                   "(%.3f %%)\n",
                   (unsigned long long)ds->bound_cells, ft_dev_stats_quantile(ds, 0.5),
                   ft_dev_stats_quantile(ds, 0.99), (double)ds->max_m,
                   ds->bound_cells > 0u ? ds->sum_m / (double)ds->bound_cells : 0.0,
                   (unsigned long long)ds->partial_cells, (unsigned long long)ds->coarser_cells,
                   (unsigned long long)ds->none_cells,
                   100.0 * (double)ds->none_cells / (double)cells);
        }
    }
    if (J.all_void_windows > 0u) {
        printf("  %llu input windows were void throughout: left as no data\n",
               (unsigned long long)J.all_void_windows);
    }
    rc = FT_EXIT_OK;
done:
    if (J.out != NULL) {
        (void)fclose(J.out);
    }
    free_job(&J);
    return rc;
}
