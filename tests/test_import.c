/* test_import.c - `fixterrain import` on real data, checked against GDAL's own
 * reading and against the runtime's native .hgt reader.
 *  - rainier GeoTIFF: size, unit, spacing, SW sample centre, 9033 voids,
 *    heights within the file's 263..4371 m, samples equal GDAL's (row flip),
 *    pyramids equal a fresh build;
 *  - N42E001.hgt through GDAL vs src/dem_hgt.c: identical samples and voids;
 *  - errors: missing file, a text file, wrong arguments. */
#include <gdal.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/import_gdal.h"
#include "dem_hgt.h"
#include "pyramid.h"
#include "terrain_file.h"
#include "test_util.h"

typedef struct stdio_src {
    FILE *f;
} stdio_src;

static ft_status stdio_read(void *ctx, void *dst, size_t bytes, size_t *got)
{
    *got = fread(dst, 1, bytes, ((stdio_src *)ctx)->f);
    return ferror(((stdio_src *)ctx)->f) ? FT_ERR_IO : FT_OK;
}

static void open_reader(const char *path, ft_reader *r, stdio_src *src)
{
    src->f = fopen(path, "rb");
    REQUIRE(src->f != NULL);
    fseek(src->f, 0, SEEK_END);
    r->size_bytes = (uint64_t)ftell(src->f);
    fseek(src->f, 0, SEEK_SET);
    r->ctx = src;
    r->read = stdio_read;
    r->name = path;
}

static void alloc_terrain(ft_terrain *t)
{
    t->heights_m = malloc((size_t)t->width * t->height * sizeof(float));
    size_t pb = ft_pyramid_bytes(t->width, t->height);
    void *pyr = aligned_alloc(64, (pb + 63u) & ~(size_t)63u);
    REQUIRE(t->heights_m != NULL && pyr != NULL);
    REQUIRE(ft_pyramid_layout(t, pyr, pb, NULL) == FT_OK);
}

static void load_ftt(const char *path, ft_terrain *t)
{
    ft_reader r;
    stdio_src src;
    ft_tfile_header hdr;
    ft_error err;
    open_reader(path, &r, &src);
    memset(t, 0, sizeof *t);
    ft_status st = ft_tfile_probe(&r, t, &hdr, &err);
    if (st == FT_OK) {
        alloc_terrain(t);
        st = ft_tfile_load_payload(&r, t, &hdr, &err);
    }
    if (st != FT_OK) fprintf(stderr, "%s: %s\n", path, err.text);
    REQUIRE(st == FT_OK);
    fclose(src.f);
}

static int run_import(const char *in, const char *out)
{
    char *argv[] = {(char *)"import", (char *)in, (char *)out, NULL};
    return ft_cmd_import(3, argv);
}

int main(void)
{
    const char *tif = FT_SHARED_DATA_DIR "/rainier_N46W122_srtm3.tif";
    const char *hgt = FT_SHARED_DATA_DIR "/N42E001.hgt";
    FILE *probe = fopen(tif, "rb");
    if (probe == NULL) {
        printf("%s missing: skipped\n", tif);
        return FT_TEST_SKIP;
    }
    fclose(probe);

    /* ---- Rainier GeoTIFF ---- */
    const char *ftt = FT_TEST_OUT_DIR "/rainier.ftt";
    REQUIRE(run_import(tif, ftt) == 0);
    ft_terrain t;
    load_ftt(ftt, &t);
    CHECK(t.width == 1201 && t.height == 1201);
    CHECK(t.unit == FT_UNIT_DEGREE);
    CHECK_NEAR(t.spacing_x, 1.0 / 1200.0, 1e-12);
    CHECK_NEAR(t.spacing_y, 1.0 / 1200.0, 1e-12);
    CHECK_NEAR(t.origin_x, -122.0, 1e-6);
    CHECK_NEAR(t.origin_y, 46.0, 1e-6);
    CHECK(strcmp(t.crs, "EPSG:4326") == 0);
    CHECK(t.void_count == 9033);
    CHECK(t.min_height_m >= 263.0f && t.max_height_m == 4371.0f);
    /* Samples equal GDAL's own read (row 0 of GDAL is north). */
    GDALAllRegister();
    GDALDatasetH ds = GDALOpen(tif, GA_ReadOnly);
    REQUIRE(ds != NULL);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    float *row = malloc(1201 * sizeof(float));
    REQUIRE(row != NULL);
    size_t compared = 0, same = 0;
    for (int r = 0; r < 1201; r += 97) {
        REQUIRE(GDALRasterIO(band, GF_Read, 0, r, 1201, 1, row, 1201, 1, GDT_Float32, 0, 0) ==
                CE_None);
        for (int c = 0; c < 1201; ++c) {
            if (row[c] == -32768.0f) continue; /* filled voids differ by design */
            ++compared;
            same += (t.heights_m[(size_t)(1200 - r) * 1201 + (size_t)c] == row[c]);
        }
    }
    printf("rainier: %zu valid samples compared with GDAL, %zu equal\n", compared, same);
    CHECK(compared > 10000 && same == compared);
    free(row);
    GDALClose(ds);
    /* Pyramids equal a fresh build of the loaded heights. */
    ft_terrain fresh = t;
    alloc_terrain(&fresh);
    memcpy(fresh.heights_m, t.heights_m, (size_t)1201 * 1201 * sizeof(float));
    ft_pyramid_build(&fresh);
    for (uint32_t l = 0; l < t.pyr.minmax_levels; ++l) {
        size_t nb = (size_t)t.pyr.minmax[l].width * t.pyr.minmax[l].height * sizeof(float);
        CHECK(memcmp(t.pyr.minmax[l].min_m, fresh.pyr.minmax[l].min_m, nb) == 0);
        CHECK(memcmp(t.pyr.minmax[l].max_m, fresh.pyr.minmax[l].max_m, nb) == 0);
    }
    for (uint32_t l = 1; l < t.pyr.avg_levels; ++l) {
        size_t nb = (size_t)t.pyr.avg[l].width * t.pyr.avg[l].height * sizeof(float);
        CHECK(memcmp(t.pyr.avg[l].avg_m, fresh.pyr.avg[l].avg_m, nb) == 0);
    }

    /* ---- the same .hgt through GDAL and through the runtime's reader ---- */
    const char *n42 = FT_TEST_OUT_DIR "/N42E001.ftt";
    REQUIRE(run_import(hgt, n42) == 0);
    ft_terrain g;
    load_ftt(n42, &g);
    ft_terrain nat;
    ft_reader r;
    stdio_src src;
    ft_error err;
    memset(&nat, 0, sizeof nat);
    open_reader(hgt, &r, &src);
    REQUIRE(ft_hgt_probe(&r, hgt, &nat, &err) == FT_OK);
    alloc_terrain(&nat);
    size_t sb = ft_hgt_scratch_bytes(nat.width, nat.height);
    void *scratch = malloc(sb);
    REQUIRE(scratch != NULL);
    REQUIRE(ft_hgt_load(&r, &nat, scratch, sb, &err) == FT_OK);
    fclose(src.f);
    CHECK(g.width == nat.width && g.height == nat.height);
    CHECK(g.void_count == 7652 && nat.void_count == 7652);
    CHECK_NEAR(g.origin_x, nat.origin_x, 1e-9);
    CHECK_NEAR(g.origin_y, nat.origin_y, 1e-9);
    CHECK(memcmp(g.heights_m, nat.heights_m, (size_t)1201 * 1201 * sizeof(float)) == 0);

    /* ---- errors ---- */
    CHECK(run_import(FT_TEST_OUT_DIR "/no-such-file.tif", FT_TEST_OUT_DIR "/x.ftt") == 1);
    CHECK(run_import(FT_SHARED_DATA_DIR "/README.md", FT_TEST_OUT_DIR "/x.ftt") == 1);
    char *few[] = {(char *)"import", (char *)tif, NULL};
    CHECK(ft_cmd_import(2, few) == 2);
    FILE *none = fopen(FT_TEST_OUT_DIR "/x.ftt", "rb");
    CHECK(none == NULL); /* a failed import leaves no output */
    if (none) fclose(none);
    return ft_test_result("test_import");
}
