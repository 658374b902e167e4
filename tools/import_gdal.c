/* import_gdal.c - converts any raster DEM GDAL can read (GeoTIFF, SRTM .hgt,
 * DTED, netCDF, ...) into the project's terrain file (src/terrain/terrain_file.h).
 *
 * Rules (the runtime's conventions, src/terrain/terrain.h):
 *  - band 1, read as float32 metres;
 *  - voids: the band's nodata value, -32768 in Int16 sources even without a
 *    nodata tag, and NaN; filled with ft_void_fill (the runtime's own rule)
 *    and counted;
 *  - sample (0,0) is the centre of the south-west pixel: GDAL's geotransform
 *    origin is the top-left CORNER of the top-left pixel, so the centre is
 *    half a pixel in; rows are flipped when the raster is north-up;
 *  - geographic CRS -> unit degree, anchor = origin; projected -> unit
 *    metre, anchor = the SW sample transformed to WGS 84 lat/lon;
 *  - rotated or sheared geotransforms and grids larger than
 *    FT_GRID_SIDE_MAX are refused (no silent resampling or cropping).
 * This is an offline tool: it allocates with malloc and frees everything. */
#define _POSIX_C_SOURCE 200809L
#include "import_gdal.h"
#include "import_db.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <math.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/platform_api.h"
#include "terrain/dem_hgt.h"
#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "terrain/terrain_file.h"
#include "terrain/void_fill.h"

#define FT_EXIT_OK 0
#define FT_EXIT_ERROR 1
#define FT_EXIT_USAGE 2

static void usage(FILE *to)
{
    fprintf(to, "usage: fixterrain import IN OUT\n"
                "       fixterrain import --database OUT.ftd [--tile T] IN...  (--database --help)\n"
                "Converts a DEM that GDAL reads (GeoTIFF, SRTM .hgt, DTED, ...) into a\n"
                "fixterrain terrain file (.ftt): float32 heights plus avg/min/max pyramids,\n"
                "voids filled (8-direction inverse-distance rule) and counted.\n");
}

/* Fills crs text and, for projected CRSs, the geodetic anchor of (x, y). */
static int describe_crs(GDALDatasetH ds, double x, double y, ft_terrain *t, char *why,
                        size_t why_cap)
{
    OGRSpatialReferenceH srs = GDALGetSpatialRef(ds);
    if (srs == NULL) {
        (void)snprintf(why, why_cap, "the raster has no coordinate reference system");
        return 0;
    }
    const char *auth = OSRGetAuthorityName(srs, NULL);
    const char *code = OSRGetAuthorityCode(srs, NULL);
    /* The runtime takes printable ASCII only (ft_terrain_check_crs): a name
     * such as "Réseau géodésique français" is stored with each run of other
     * bytes replaced by '?' (ft_terrain_sanitize_crs), and the user is told. */
    char raw[256];
    if (auth != NULL && code != NULL) {
        (void)snprintf(raw, sizeof raw, "%s:%s", auth, code);
    } else {
        const char *name = OSRGetName(srs);
        (void)snprintf(raw, sizeof raw, "%s", name != NULL ? name : "unknown");
    }
    if (ft_terrain_sanitize_crs(raw, t->crs) > 0u || strlen(raw) >= sizeof t->crs) {
        fprintf(stderr,
                "fixterrain import: warning: CRS name \"%s\" stored as \"%s\" (printable ASCII, "
                "at most %u bytes)\n",
                raw, t->crs, FT_CRS_TEXT_MAX - 1u);
    }
    if (OSRIsGeographic(srs)) {
        t->unit = FT_UNIT_DEGREE;
        t->anchor_lat_deg = y;
        t->anchor_lon_deg = x;
        return 1;
    }
    t->unit = FT_UNIT_METRE;
    OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(NULL);
    OGRSpatialReferenceH src = OSRClone(srs);
    int ok = 0;
    if (wgs84 != NULL && src != NULL && OSRImportFromEPSG(wgs84, 4326) == OGRERR_NONE) {
        OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(src, wgs84);
        if (ct != NULL) {
            double px = x, py = y, pz = 0.0;
            if (OCTTransform(ct, 1, &px, &py, &pz)) {
                t->anchor_lon_deg = px;
                t->anchor_lat_deg = py;
                ok = 1;
            }
            OCTDestroyCoordinateTransformation(ct);
        }
    }
    if (!ok) {
        (void)snprintf(why, why_cap, "cannot transform the SW corner of CRS %s to WGS 84",
                       t->crs);
    }
    OSRDestroySpatialReference(src);
    OSRDestroySpatialReference(wgs84);
    return ok;
}

/* The void rule of the header comment: NaN/Inf, the band's nodata value,
 * -32768 in an Int16 band. */
static int void_value(float v, int has_nodata, double nodata, int int16)
{
    return !isfinite(v) || (has_nodata && (double)v == (double)(float)nodata) ||
           (int16 && v == -32768.0f);
}

int ft_cmd_import(int argc, char **argv)
{
    for (int a = 1; a < argc; ++a) {
        if (strcmp(argv[a], "--database") == 0) {
            return ft_cmd_import_db(argc, argv); /* many DEMs -> one tiled database */
        }
    }
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        usage(stdout);
        return FT_EXIT_OK;
    }
    if (argc != 3) {
        usage(stderr);
        return FT_EXIT_USAGE;
    }
    const char *in = argv[1], *out = argv[2];
    int rc = FT_EXIT_ERROR;
    float *heights = NULL;
    uint8_t *voids = NULL;
    uint8_t *void_bits = NULL;
    void *pyr = NULL;
    void *fill_scratch = NULL;
    ft_terrain t;
    ft_error err;
    char why[256] = "";
    memset(&t, 0, sizeof t);

    GDALAllRegister();
    CPLPushErrorHandler(CPLQuietErrorHandler); /* we report errors ourselves */
    GDALDatasetH ds = GDALOpen(in, GA_ReadOnly);
    CPLPopErrorHandler();
    if (ds == NULL) {
        fprintf(stderr, "fixterrain import: %s: GDAL cannot open it as a raster: %s\n", in,
                CPLGetLastErrorMsg());
        return FT_EXIT_ERROR;
    }
    const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
    double gt[6];
    if (GDALGetRasterCount(ds) < 1) {
        fprintf(stderr, "fixterrain import: %s: no raster band\n", in);
        goto close_dataset;
    }
    if (w < (int)FT_GRID_SIDE_MIN || h < (int)FT_GRID_SIDE_MIN || w > (int)FT_GRID_SIDE_MAX ||
        h > (int)FT_GRID_SIDE_MAX) {
        fprintf(stderr, "fixterrain import: %s: %dx%d samples; the runtime takes %u..%u per side "
                        "(split or resample the DEM first)\n",
                in, w, h, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
        goto close_dataset;
    }
    if (GDALGetGeoTransform(ds, gt) != CE_None) {
        fprintf(stderr, "fixterrain import: %s: no geotransform (georeferencing)\n", in);
        goto close_dataset;
    }
    if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || gt[5] == 0.0) {
        fprintf(stderr, "fixterrain import: %s: rotated, sheared or mirrored geotransform "
                        "(%g %g %g / %g %g %g) is not supported\n",
                in, gt[0], gt[1], gt[2], gt[3], gt[4], gt[5]);
        goto close_dataset;
    }
    const int north_up = gt[5] < 0.0;
    t.width = (uint32_t)w;
    t.height = (uint32_t)h;
    t.spacing_x = gt[1];
    t.spacing_y = fabs(gt[5]);
    t.origin_x = gt[0] + 0.5 * gt[1];
    /* centre of the southern-most row */
    t.origin_y = north_up ? gt[3] + ((double)h - 0.5) * gt[5] : gt[3] + 0.5 * gt[5];
    if (!describe_crs(ds, t.origin_x, t.origin_y, &t, why, sizeof why)) {
        fprintf(stderr, "fixterrain import: %s: %s\n", in, why);
        goto close_dataset;
    }
    if (ft_terrain_derive_frame(&t, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s: %s\n", in, err.text);
        goto close_dataset;
    }
    if (ft_terrain_check_crs(t.crs, sizeof t.crs, in, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s\n", err.text);
        goto close_dataset;
    }

    const size_t n = (size_t)w * (size_t)h;
    heights = malloc(n * sizeof(float));
    voids = malloc(n);
    size_t pyr_bytes = ft_pyramid_bytes(t.width, t.height);
    pyr = aligned_alloc(64, (pyr_bytes + 63u) & ~(size_t)63u);
    const size_t fill_bytes = ft_void_fill_scratch_bytes(t.width, t.height);
    fill_scratch = malloc(fill_bytes);
    if (heights == NULL || voids == NULL || pyr == NULL || fill_scratch == NULL) {
        fprintf(stderr, "fixterrain import: %s: out of memory for %dx%d samples\n", in, w, h);
        goto free_buffers;
    }
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    int has_nodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
    const int int16 = GDALGetRasterDataType(band) == GDT_Int16;
    /* Heights the runtime refuses are refused here (not imported and then
     * rejected at load): the shared range of terrain.h, or SRTM's own range
     * for an .hgt, which the runtime's .hgt reader applies. */
    GDALDriverH drv = GDALGetDatasetDriver(ds);
    const char *drv_name = drv != NULL ? GDALGetDriverShortName(drv) : NULL;
    const int srtm = drv_name != NULL && strcmp(drv_name, "SRTMHGT") == 0;
    const double h_lo = srtm ? (double)FT_HGT_MIN_VALID_M : FT_HEIGHT_MIN_M;
    const double h_hi = srtm ? (double)FT_HGT_MAX_VALID_M : FT_HEIGHT_MAX_M;
    /* Read north-up rows straight into their flipped place, row by row. */
    for (int row = 0; row < h; ++row) {
        int dst_row = north_up ? h - 1 - row : row;
        if (GDALRasterIO(band, GF_Read, 0, row, w, 1, heights + (size_t)dst_row * (size_t)w, w, 1,
                         GDT_Float32, 0, 0) != CE_None) {
            fprintf(stderr, "fixterrain import: %s: read of row %d failed: %s\n", in, row,
                    CPLGetLastErrorMsg());
            goto free_buffers;
        }
        const float *got = heights + (size_t)dst_row * (size_t)w;
        for (int c = 0; c < w; ++c) {
            float v = got[c];
            int is_void = void_value(v, has_nodata, nodata, int16);
            int ok = srtm ? ft_hgt_height_ok((double)v) : ft_terrain_height_ok((double)v);
            if (!is_void && !ok) {
                fprintf(stderr,
                        "fixterrain import: %s: height %g m at row %d col %d is outside the "
                        "%g..%g m the runtime accepts%s (mark it nodata or fix the source)\n",
                        in, (double)v, row, c, h_lo, h_hi, srtm ? " from an SRTM .hgt" : "");
                goto free_buffers;
            }
        }
    }
    uint32_t void_count = 0;
    for (size_t i = 0; i < n; ++i) {
        float v = heights[i];
        int is_void = void_value(v, has_nodata, nodata, int16);
        voids[i] = (uint8_t)is_void;
        void_count += (uint32_t)is_void;
        if (is_void) {
            heights[i] = 0.0f;
        }
    }
    int all_void = 0;
    uint32_t filled = ft_void_fill(heights, voids, t.width, t.height, fill_scratch, fill_bytes,
                                   &all_void);
    if (all_void) {
        fprintf(stderr, "fixterrain import: %s: every sample is a void\n", in);
        goto free_buffers;
    }
    if (filled != void_count) {
        fprintf(stderr, "fixterrain import: %s: void fill filled %u of %u voids\n", in, filled,
                void_count);
        goto free_buffers;
    }
    t.void_count = void_count;
    t.heights_m = heights;
    /* the file records which samples were invented (format version 2) */
    void_bits = malloc(ft_terrain_void_bits_bytes(t.width, t.height));
    if (void_bits == NULL) {
        fprintf(stderr, "fixterrain import: %s: out of memory for the void bits\n", in);
        goto free_buffers;
    }
    (void)ft_terrain_pack_void_bits(voids, t.width, t.height, void_bits);
    t.void_bits = void_count > 0u ? void_bits : NULL;
    if (ft_pyramid_layout(&t, pyr, pyr_bytes, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s\n", err.text);
        goto free_buffers;
    }
    ft_pyramid_build(&t);

    ft_file f;
    if (ft_plat_file_open_write(&f, out, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s\n", err.text);
        goto free_buffers;
    }
    if (ft_tfile_write(&t, has_nodata ? (float)nodata : -32768.0f, &f.writer, &err) != FT_OK ||
        ft_plat_file_finish_write(&f, &err) != FT_OK) {
        fprintf(stderr, "fixterrain import: %s: %s\n", out, err.text);
        ft_plat_file_close(&f);
        goto free_buffers;
    }
    printf("imported %s -> %s: %ux%u samples, spacing %.9g x %.9g %s, SW sample (%.9f, %.9f), "
           "crs %s, heights %.1f..%.1f m, %u voids filled\n",
           in, out, t.width, t.height, t.spacing_x, t.spacing_y,
           t.unit == FT_UNIT_DEGREE ? "deg" : "m", t.origin_x, t.origin_y, t.crs,
           (double)t.min_height_m, (double)t.max_height_m, t.void_count);
    rc = FT_EXIT_OK;

free_buffers:
    free(void_bits);
    free(fill_scratch);
    free(pyr);
    free(voids);
    free(heights);
close_dataset:
    GDALClose(ds);
    return rc;
}
