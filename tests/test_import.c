/* test_import.c - `fixterrain import` on real data, checked against GDAL's own
 * reading and against the runtime's native .hgt reader.
 *  - rainier GeoTIFF: size, unit, spacing, SW sample centre, 9033 voids,
 *    heights within the file's 263..4371 m, samples equal GDAL's (row flip),
 *    pyramids equal a fresh build;
 *  - N42E001.hgt through GDAL vs src/terrain/dem_hgt.c: identical samples and voids;
 *  - errors: missing file, a text file, wrong arguments;
 *  - generated inputs (no shared data needed): an .asc with a 3e38 height
 *    and an all-32767 .hgt are refused with the runtime's range, a .prj whose
 *    CRS name is not ASCII is imported with the documented '?' substitution
 *    and loads, a 2049 x 2049 VRT that is all nodata but one pixel imports
 *    in linear time;
 *  - everything allocated is freed (the test runs clean under LeakSanitizer). */
#define _POSIX_C_SOURCE 200809L
#include <gdal.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../tools/import_gdal.h"
#include "terrain/dem_hgt.h"
#include "terrain/pyramid.h"
#include "terrain/terrain_file.h"
#include "test_stderr.h"
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
    /* where the voids were (a .hgt says how many only when read) */
    t->void_bits = calloc(ft_terrain_void_bits_bytes(t->width, t->height), 1);
    REQUIRE(t->void_bits != NULL);
}

static void free_terrain(ft_terrain *t)
{
    free(t->void_bits);
    t->void_bits = NULL;
    free(t->heights_m);
    if (t->pyr.avg_levels > 1u) {
        free(t->pyr.avg[1].avg_m); /* start of the pyramid block */
    }
    t->heights_m = NULL;
    t->pyr.avg_levels = 0u;
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

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    REQUIRE(fputs(text, f) >= 0);
    REQUIRE(fclose(f) == 0);
}

static int file_exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f != NULL) fclose(f);
    return f != NULL;
}

/* Runs the import with stderr captured to a file; returns the exit status
 * and leaves what it printed in msg. */
static int run_import_msg(const char *in, const char *out, char *msg, size_t cap)
{
    const char *log = FT_TEST_OUT_DIR "/import-stderr.txt";
    ft_test_stderr cap_err;
    ft_test_stderr_begin(&cap_err, log);
    int rc = run_import(in, out);
    ft_test_stderr_end(&cap_err, msg, cap);
    fprintf(stdout, "  import %s -> %d: %s", in, rc, msg);
    return rc;
}

static const char *k_prj_wgs84 =
    "GEOGCS[\"GCS_WGS_1984\",DATUM[\"D_WGS_1984\",SPHEROID[\"WGS_1984\",6378137,"
    "298.257223563]],PRIMEM[\"Greenwich\",0],UNIT[\"Degree\",0.017453292519943295]]";

/* Inputs made here, so they run without ../shared/data. */
static void generated_inputs(void)
{
    char msg[2048];
    /* ---- a height of 3e38 in an .asc: refused, named, nothing written ---- */
    const char *asc = FT_TEST_OUT_DIR "/huge_height.asc";
    const char *out = FT_TEST_OUT_DIR "/huge_height.ftt";
    remove(out);
    write_text(asc, "ncols 4\nnrows 3\nxllcorner 8.0\nyllcorner 46.0\ncellsize 0.001\n"
                    "NODATA_value -9999\n1 2 3 4\n5 3e38 7 8\n9 10 11 12\n");
    write_text(FT_TEST_OUT_DIR "/huge_height.prj", k_prj_wgs84);
    CHECK(run_import_msg(asc, out, msg, sizeof msg) == 1);
    CHECK(strstr(msg, "height 3e+38 m at row 1 col 1") != NULL);
    CHECK(strstr(msg, "-12000..9000") != NULL);
    CHECK(!file_exists(out));
    /* the same file with the height in range imports and loads */
    write_text(asc, "ncols 4\nnrows 3\nxllcorner 8.0\nyllcorner 46.0\ncellsize 0.001\n"
                    "NODATA_value -9999\n1 2 3 4\n5 8999 7 8\n9 10 -9999 12\n");
    CHECK(run_import_msg(asc, out, msg, sizeof msg) == 0);
    {
        ft_terrain t;
        load_ftt(out, &t);
        CHECK(t.width == 4u && t.height == 3u && t.void_count == 1u);
        CHECK(t.max_height_m == 8999.0f);
        /* the file says which sample was invented: row 0 (south) col 2 */
        for (size_t i = 0; i < 12u; ++i) {
            CHECK(ft_terrain_sample_filled(&t, i) == (i == 2u));
        }
        free_terrain(&t);
    }

    /* ---- an all-32767 .hgt: the runtime's .hgt reader refuses it, so does
     * the import (SRTM range -1000..9000 m) ---- */
    const char *hgt = FT_TEST_OUT_DIR "/N46W122.hgt";
    {
        FILE *f = fopen(hgt, "wb");
        REQUIRE(f != NULL);
        static const unsigned char v[2] = {0x7f, 0xff};
        for (int i = 0; i < 1201 * 1201; ++i) REQUIRE(fwrite(v, 1, 2, f) == 2);
        REQUIRE(fclose(f) == 0);
    }
    out = FT_TEST_OUT_DIR "/N46W122_32767.ftt";
    remove(out);
    CHECK(run_import_msg(hgt, out, msg, sizeof msg) == 1);
    CHECK(strstr(msg, "height 32767 m at row 0 col 0") != NULL);
    CHECK(strstr(msg, "-1000..9000") != NULL);
    CHECK(!file_exists(out));

    /* ---- a CRS name with non-ASCII bytes and no authority: stored with
     * each non-ASCII run as '?', with a warning; the runtime loads it ---- */
    asc = FT_TEST_OUT_DIR "/rgf.asc";
    out = FT_TEST_OUT_DIR "/rgf.ftt";
    write_text(asc, "ncols 3\nnrows 3\nxllcorner 2.0\nyllcorner 46.0\ncellsize 0.01\n"
                    "NODATA_value -9999\n1 2 3\n4 5 6\n7 8 9\n");
    write_text(FT_TEST_OUT_DIR "/rgf.prj",
               "GEOGCS[\"R\xc3\xa9seau g\xc3\xa9od\xc3\xa9sique fran\xc3\xa7" "ais\","
               "DATUM[\"D_Reseau_test\",SPHEROID[\"GRS_1980\",6378137,298.257222101]],"
               "PRIMEM[\"Greenwich\",0],UNIT[\"Degree\",0.017453292519943295]]");
    CHECK(run_import_msg(asc, out, msg, sizeof msg) == 0);
    {
        ft_terrain t;
        load_ftt(out, &t);
        printf("  crs stored as \"%s\"\n", t.crs);
        for (size_t k = 0; t.crs[k] != '\0'; ++k) {
            CHECK(t.crs[k] >= 0x20 && t.crs[k] <= 0x7e);
        }
        /* GDAL keeps the name (no authority to find): the substitution shows */
        if (strncmp(t.crs, "EPSG:", 5) != 0) {
            CHECK(strstr(t.crs, "R?seau g?od?sique fran?ais") != NULL);
            CHECK(strstr(msg, "stored as") != NULL);
        }
        free_terrain(&t);
    }

    /* ---- 2049 x 2049, all nodata but one pixel (a VRT over a 1x1 .asc):
     * the fill is linear, the import takes seconds at most (the ray walk
     * took minutes at this size) ---- */
    write_text(FT_TEST_OUT_DIR "/one.asc", "ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\n"
                                           "cellsize 1\nNODATA_value -9999\n1234\n");
    const char *vrt = FT_TEST_OUT_DIR "/one_pixel.vrt";
    write_text(vrt, "<VRTDataset rasterXSize=\"2049\" rasterYSize=\"2049\">\n"
                    "  <SRS>EPSG:4326</SRS>\n"
                    "  <GeoTransform>8.0, 0.0001, 0, 47.0, 0, -0.0001</GeoTransform>\n"
                    "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
                    "    <NoDataValue>-9999</NoDataValue>\n"
                    "    <SimpleSource>\n"
                    "      <SourceFilename relativeToVRT=\"1\">one.asc</SourceFilename>\n"
                    "      <SourceBand>1</SourceBand>\n"
                    "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"1\" ySize=\"1\"/>\n"
                    "      <DstRect xOff=\"1500\" yOff=\"700\" xSize=\"1\" ySize=\"1\"/>\n"
                    "    </SimpleSource>\n"
                    "  </VRTRasterBand>\n"
                    "</VRTDataset>\n");
    out = FT_TEST_OUT_DIR "/one_pixel.ftt";
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    CHECK(run_import_msg(vrt, out, msg, sizeof msg) == 0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double dt = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    printf("  2049x2049 one-pixel VRT imported in %.2f s\n", dt);
    CHECK(dt < 10.0);
    {
        ft_terrain t;
        load_ftt(out, &t);
        CHECK(t.void_count == 2049u * 2049u - 1u);
        CHECK(t.min_height_m == 1234.0f && t.max_height_m == 1234.0f);
        free_terrain(&t);
    }
    remove(out);
}

int main(void)
{
    generated_inputs();
    const char *tif = FT_SHARED_DATA_DIR "/rainier_N46W122_srtm3.tif";
    const char *hgt = FT_SHARED_DATA_DIR "/N42E001.hgt";
    FILE *probe = fopen(tif, "rb");
    if (probe == NULL) {
        printf("%s missing: skipped the real-data part\n", tif);
        GDALDestroyDriverManager();
        int r = ft_test_result("test_import");
        return r != 0 ? r : FT_TEST_SKIP;
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
    /* the same samples recorded as void-filled, by the import and the reader */
    CHECK(memcmp(g.void_bits, nat.void_bits, ft_terrain_void_bits_bytes(1201u, 1201u)) == 0);
    free(scratch);
    free_terrain(&nat);
    free_terrain(&g);
    free_terrain(&fresh);
    free_terrain(&t);

    /* ---- errors ---- */
    CHECK(run_import(FT_TEST_OUT_DIR "/no-such-file.tif", FT_TEST_OUT_DIR "/x.ftt") == 1);
    CHECK(run_import(FT_SHARED_DATA_DIR "/README.md", FT_TEST_OUT_DIR "/x.ftt") == 1);
    char *few[] = {(char *)"import", (char *)tif, NULL};
    CHECK(ft_cmd_import(2, few) == 2);
    FILE *none = fopen(FT_TEST_OUT_DIR "/x.ftt", "rb");
    CHECK(none == NULL); /* a failed import leaves no output */
    if (none) fclose(none);
    GDALDestroyDriverManager(); /* GDAL's driver registry, so LeakSanitizer sees only ours */
    return ft_test_result("test_import");
}
