/* test_terrain_db.c - `fixterrain import --database` on real data, read back
 * with the runtime's .ftd reader (src/terrain/terrain_db.h) through pread.
 *  - mosaic N41E001 + N42E001: every sample of both .hgt files is in level 0
 *    (voids filled and flagged), so the joined edge row equals the shared
 *    row of both files sample by sample; coarser levels are point samples of
 *    level 0; footprint bounds reach the mosaic's -20..3100 m; the same from a
 *    directory of the tiles (byte for byte) and from a VRT mosaic; two
 *    disagreeing sources of one tile are reported naming both files;
 *  - holes N42E001 + N49E011: the tiles between them are "no data" in the
 *    index and reading one says so (not an error);
 *  - mixed resolution N42E001 (3") + ETOPO5 (5', if ferret-datasets is
 *    installed): where both cover, the coarse level holds the SRTM samples;
 *    elsewhere ETOPO5 (the ocean is below 0 m);
 *  - corrupt databases (bytes patched in a valid one, crcs recomputed where
 *    the damage must sit behind a valid crc) are refused with the reason;
 *  - a 3-tile database made with the encoders (runs without ../shared/data):
 *    tiles, no data, void bits read back; the encoders refuse what the
 *    reader refuses; patched headers and entries are refused, each with its
 *    reason. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "ftd_synth.h"
#include "../tools/import_db.h"
#include "core/byte_codec.h"
#include "core/platform_api.h"
#include "terrain/terrain_db.h"
#include "test_stderr.h"
#include "test_util.h"

#define HGT_SIDE 1201
#define ENTRIES_CAP 8192u
#define TILE 256u

static ft_tdb_entry g_entries[ENTRIES_CAP];
static float g_tile[TILE * TILE];
static uint8_t g_bits[TILE * TILE / 8u];
static int16_t g_hgt[2][HGT_SIDE * HGT_SIDE];

static int run_import(const char *out, const char *opt, const char *in1, const char *in2)
{
    char *argv[8];
    int argc = 0;
    argv[argc++] = (char *)"import";
    argv[argc++] = (char *)"--database";
    argv[argc++] = (char *)out;
    if (opt != NULL) {
        argv[argc++] = (char *)opt;
    }
    argv[argc++] = (char *)in1;
    if (in2 != NULL) {
        argv[argc++] = (char *)in2;
    }
    return ft_cmd_import_db(argc, argv);
}

/* The .hgt sample at level-0 lattice point (i, j), N = 1200: 1 inside, 0 outside. */
static int hgt_at(const int16_t *hgt, int lon0, int lat0, uint64_t i, uint64_t j, int *v)
{
    const int64_t c = (int64_t)i - (int64_t)(lon0 + 180) * 1200;
    const int64_t r = (int64_t)(lat0 + 1 + 90) * 1200 - (int64_t)j; /* row 0 = north */
    if (c < 0 || c >= HGT_SIDE || r < 0 || r >= HGT_SIDE) {
        return 0;
    }
    *v = hgt[r * HGT_SIDE + c];
    return 1;
}

static int bit(const uint8_t *bits, size_t i)
{
    return (bits[i >> 3] >> (i & 7u)) & 1;
}

static void open_db(const char *path, ft_file *f, ft_tdb *db)
{
    ft_error err;
    REQUIRE(ft_plat_file_open_read(f, path, &err) == FT_OK);
    if (ft_tdb_open(db, &f->reader_at, g_entries, ENTRIES_CAP, &err) != FT_OK) {
        fprintf(stderr, "%s\n", err.text);
        REQUIRE(0);
    }
}

static void read_tile(const ft_tdb *db, uint32_t k, uint32_t tx, uint32_t ty, ft_tdb_tile *t)
{
    ft_error err;
    ft_status st = ft_tdb_read_tile(db, k, tx, ty, g_tile, TILE * TILE, g_bits, sizeof g_bits, t,
                                    &err);
    if (st != FT_OK) {
        fprintf(stderr, "%s\n", err.text);
    }
    REQUIRE(st == FT_OK);
}

/* ---- the N41E001 + N42E001 mosaic ------------------------------------------------ */
/* Checks a database made from N41E001 + N42E001 against both .hgt files
 * (in g_hgt). strict: made from the two files, so every valid sample of each
 * is there, voids are filled and flagged, counts are exact. Not strict (a
 * VRT mosaic, in which one source overwrites the shared row): a sample is
 * checked where every file covering it has it valid. */
static void mosaic_check(const char *path, int strict)
{
    const int lat0[2] = {41, 42};
    ft_file f;
    ft_tdb db;
    open_db(path, &f, &db);
    CHECK(db.hdr.samples_per_deg == 1200u && db.hdr.tile_samples == TILE);
    CHECK(db.hdr.min_height_m == -20.0f && db.hdr.max_height_m == 3100.0f);
    uint64_t seen[2] = {0, 0}, voids_flagged = 0, edge_both = 0, uncovered = 0, compared = 0;
    const uint64_t edge_j = (uint64_t)(42 + 90) * 1200u;
    for (uint32_t k = 0u; k < db.hdr.level_count; ++k) {
        const ft_tdb_level *lv = &db.hdr.levels[k];
        for (uint32_t ty = lv->ty0; ty < lv->ty0 + lv->rows; ++ty) {
            for (uint32_t tx = lv->tx0; tx < lv->tx0 + lv->cols; ++tx) {
                ft_tdb_tile t;
                read_tile(&db, k, tx, ty, &t);
                REQUIRE(t.state == FT_TDB_DATA);
                for (uint32_t tj = 0u; tj < TILE; ++tj) {
                    for (uint32_t ti = 0u; ti < TILE; ++ti) {
                        /* level k point (i, j) is level 0 point (i << k, j << k) */
                        const uint64_t i = ((uint64_t)tx * TILE + ti) << k;
                        const uint64_t j = ((uint64_t)ty * TILE + tj) << k;
                        const size_t s = (size_t)tj * TILE + ti;
                        const float v = t.heights_m[s];
                        int hv[2], in[2] = {0, 0}, valid = 0, voided = 0;
                        for (int h = 0; h < 2; ++h) {
                            in[h] = hgt_at(g_hgt[h], 1, lat0[h], i, j, &hv[h]);
                            valid += in[h] && hv[h] != -32768;
                            voided += in[h] && hv[h] == -32768;
                        }
                        if (!in[0] && !in[1]) {
                            CHECK(v == FT_TDB_NODATA_M);
                            uncovered += k == 0u;
                            continue;
                        }
                        if (!strict && voided > 0) {
                            continue;
                        }
                        if (valid == 0) {
                            CHECK(bit(t.void_bits, s) && v != FT_TDB_NODATA_M);
                            voids_flagged += k == 0u;
                            continue;
                        }
                        for (int h = 0; h < 2; ++h) {
                            if (!in[h] || hv[h] == -32768) {
                                continue;
                            }
                            if (v != (float)hv[h] || bit(t.void_bits, s)) {
                                fprintf(stderr, "%s: level %u tile %u,%u sample %u,%u: %g vs %d\n",
                                        path, k, tx, ty, ti, tj, (double)v, hv[h]);
                                REQUIRE(0);
                            }
                            ++compared;
                            seen[h] += k == 0u;
                            edge_both += (k == 0u && j == edge_j);
                        }
                    }
                }
            }
        }
    }
    printf("%s: %llu + %llu measured samples on level 0, %llu checked on all levels, %llu "
           "void-filled, %llu edge checks, %llu uncovered on level 0\n",
           path, (unsigned long long)seen[0], (unsigned long long)seen[1],
           (unsigned long long)compared, (unsigned long long)voids_flagged,
           (unsigned long long)edge_both, (unsigned long long)uncovered);
    /* the shared row: N41E001's first (northern) row, N42E001's last */
    uint64_t edge_want = 0;
    for (int c = 0; c < HGT_SIDE; ++c) {
        edge_want += g_hgt[0][c] != -32768;
        edge_want += g_hgt[1][(HGT_SIDE - 1) * HGT_SIDE + c] != -32768;
    }
    CHECK(uncovered > 0u);
    if (strict) {
        /* 134 and 7652 voids (../shared/data/README.md) */
        CHECK(seen[0] == (uint64_t)HGT_SIDE * HGT_SIDE - 134u);
        CHECK(seen[1] == (uint64_t)HGT_SIDE * HGT_SIDE - 7652u);
        CHECK(voids_flagged > 0u && voids_flagged <= 134u + 7652u);
        CHECK(edge_both == edge_want && edge_want > 2u * 1100u);
    } else {
        CHECK(seen[0] > (uint64_t)HGT_SIDE * (HGT_SIDE - 2) - 134u);
        CHECK(seen[1] > (uint64_t)HGT_SIDE * (HGT_SIDE - 2) - 7652u);
    }
    /* the top tile bounds the whole mosaic, from the finer levels */
    const ft_tdb_level *top = &db.hdr.levels[db.hdr.level_count - 1u];
    CHECK(top->cols == 1u && top->rows == 1u);
    const ft_tdb_entry *te = ft_tdb_find(&db, db.hdr.level_count - 1u, top->tx0, top->ty0);
    REQUIRE(te != NULL);
    CHECK(te->min_m == -20.0f && te->max_m == 3100.0f);
    ft_plat_file_close(&f);
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    REQUIRE(fputs(text, f) >= 0);
    REQUIRE(fclose(f) == 0);
}

static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    REQUIRE(fa != NULL && fb != NULL);
    int same = 1;
    for (;;) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb) {
            same = 0;
            break;
        }
        if (ca == EOF) {
            break;
        }
    }
    fclose(fa);
    fclose(fb);
    return same;
}

/* One .hgt as a VRT band (lon0/lat0: SW corner), optionally shifted by
 * offset_m (a second, disagreeing source of the same samples). */
static void hgt_vrt(const char *vrt, const char *hgt, int lon0, int lat0, double offset_m)
{
    char text[2048];
    (void)snprintf(text, sizeof text,
                   "<VRTDataset rasterXSize=\"1201\" rasterYSize=\"1201\">\n"
                   "  <SRS>EPSG:4326</SRS>\n"
                   "  <GeoTransform>%.12f, %.12f, 0, %.12f, 0, %.12f</GeoTransform>\n"
                   "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n"
                   "    <NoDataValue>-32768</NoDataValue>\n"
                   "    <ComplexSource>\n"
                   "      <SourceFilename relativeToVRT=\"0\">%s</SourceFilename>\n"
                   "      <SourceBand>1</SourceBand>\n"
                   "      <NODATA>-32768</NODATA>\n"
                   "      <ScaleOffset>%g</ScaleOffset><ScaleRatio>1</ScaleRatio>\n"
                   "    </ComplexSource>\n"
                   "  </VRTRasterBand>\n"
                   "</VRTDataset>\n",
                   lon0 - 0.5 / 1200.0, 1.0 / 1200.0, lat0 + 1 + 0.5 / 1200.0, -1.0 / 1200.0,
                   hgt, offset_m);
    write_text(vrt, text);
}

/* Runs the import with stderr captured into msg; returns its exit status. */
static int run_import_msg(const char *out, const char *in1, const char *in2, char *msg,
                          size_t cap)
{
    const char *log = FT_TEST_OUT_DIR "/import-db-stderr.txt";
    ft_test_stderr cap_err;
    ft_test_stderr_begin(&cap_err, log);
    int rc = run_import(out, NULL, in1, in2);
    ft_test_stderr_end(&cap_err, msg, cap);
    printf("  import %s + %s -> %d: %s", in1, in2, rc, msg);
    return rc;
}

static void mosaic(void)
{
    ft_test_read_srtm3(FT_SHARED_DATA_DIR "/N41E001.hgt", g_hgt[0]);
    ft_test_read_srtm3(FT_SHARED_DATA_DIR "/N42E001.hgt", g_hgt[1]);
    /* a list of files */
    const char *out = FT_TEST_OUT_DIR "/mosaic.ftd";
    CHECK(run_import(out, NULL, FT_SHARED_DATA_DIR "/N42E001.hgt",
                     FT_SHARED_DATA_DIR "/N41E001.hgt") == 0);
    mosaic_check(out, 1);
    /* a directory of the same tiles (links to the shared data): in name
     * order, so the same bytes as the list in that order */
    const char *dir = FT_TEST_OUT_DIR "/mosaic_dir";
    (void)mkdir(dir, 0755);
    (void)unlink(FT_TEST_OUT_DIR "/mosaic_dir/N41E001.hgt");
    (void)unlink(FT_TEST_OUT_DIR "/mosaic_dir/N42E001.hgt");
    REQUIRE(symlink(FT_SHARED_DATA_DIR "/N41E001.hgt", FT_TEST_OUT_DIR "/mosaic_dir/N41E001.hgt") == 0);
    REQUIRE(symlink(FT_SHARED_DATA_DIR "/N42E001.hgt", FT_TEST_OUT_DIR "/mosaic_dir/N42E001.hgt") == 0);
    const char *out_dir = FT_TEST_OUT_DIR "/mosaic_from_dir.ftd";
    CHECK(run_import(out_dir, NULL, dir, NULL) == 0);
    const char *out_sorted = FT_TEST_OUT_DIR "/mosaic_sorted.ftd";
    CHECK(run_import(out_sorted, NULL, FT_SHARED_DATA_DIR "/N41E001.hgt",
                     FT_SHARED_DATA_DIR "/N42E001.hgt") == 0);
    CHECK(same_file(out_dir, out_sorted));
    /* a GDAL VRT mosaic of both (one dataset, windows read from it) */
    const char *vrt = FT_TEST_OUT_DIR "/mosaic.vrt";
    write_text(vrt, "<VRTDataset rasterXSize=\"1201\" rasterYSize=\"2401\">\n"
                    "  <SRS>EPSG:4326</SRS>\n"
                    "  <GeoTransform>0.999583333333, 0.000833333333333, 0, 43.000416666667, 0, "
                    "-0.000833333333333</GeoTransform>\n"
                    "  <VRTRasterBand dataType=\"Int16\" band=\"1\">\n"
                    "    <NoDataValue>-32768</NoDataValue>\n"
                    "    <SimpleSource>\n"
                    "      <SourceFilename relativeToVRT=\"0\">" FT_SHARED_DATA_DIR
                    "/N41E001.hgt</SourceFilename>\n"
                    "      <SourceBand>1</SourceBand>\n"
                    "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"1201\" ySize=\"1201\"/>\n"
                    "      <DstRect xOff=\"0\" yOff=\"1200\" xSize=\"1201\" ySize=\"1201\"/>\n"
                    "    </SimpleSource>\n"
                    "    <SimpleSource>\n"
                    "      <SourceFilename relativeToVRT=\"0\">" FT_SHARED_DATA_DIR
                    "/N42E001.hgt</SourceFilename>\n"
                    "      <SourceBand>1</SourceBand>\n"
                    "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"1201\" ySize=\"1201\"/>\n"
                    "      <DstRect xOff=\"0\" yOff=\"0\" xSize=\"1201\" ySize=\"1201\"/>\n"
                    "    </SimpleSource>\n"
                    "  </VRTRasterBand>\n"
                    "</VRTDataset>\n");
    const char *out_vrt = FT_TEST_OUT_DIR "/mosaic_from_vrt.ftd";
    CHECK(run_import(out_vrt, NULL, vrt, NULL) == 0);
    mosaic_check(out_vrt, 0);

    /* two sources of the same samples that disagree: a warning naming both,
     * and the first one's samples kept */
    const char *shifted = FT_TEST_OUT_DIR "/N42E001_plus5.vrt";
    hgt_vrt(shifted, FT_SHARED_DATA_DIR "/N42E001.hgt", 1, 42, 5.0);
    char msg[4096];
    const char *out_warn = FT_TEST_OUT_DIR "/disagree.ftd";
    CHECK(run_import_msg(out_warn, shifted, FT_SHARED_DATA_DIR "/N42E001.hgt", msg,
                         sizeof msg) == 0);
    CHECK(strstr(msg, "warning: " FT_TEST_OUT_DIR "/N42E001_plus5.vrt and " FT_SHARED_DATA_DIR
                      "/N42E001.hgt disagree at") != NULL);
    CHECK(strstr(msg, "by up to 5.00 m") != NULL);
    ft_file f;
    ft_tdb db;
    open_db(out_warn, &f, &db);
    /* the bounds come from the samples used: the shifted ones */
    CHECK(db.hdr.min_height_m == 349.0f + 5.0f && db.hdr.max_height_m == 3100.0f + 5.0f);
    ft_plat_file_close(&f);
    /* agreeing sources: no warning */
    hgt_vrt(shifted, FT_SHARED_DATA_DIR "/N42E001.hgt", 1, 42, 0.0);
    CHECK(run_import_msg(out_warn, shifted, FT_SHARED_DATA_DIR "/N42E001.hgt", msg,
                         sizeof msg) == 0);
    CHECK(strstr(msg, "disagree") == NULL);
}

/* ---- N42E001 + N49E011: holes between them ------------------------------------------ */
static void holes(void)
{
    const char *out = FT_TEST_OUT_DIR "/holes.ftd";
    CHECK(run_import(out, NULL, FT_SHARED_DATA_DIR "/N42E001.hgt",
                     FT_SHARED_DATA_DIR "/N49E011.hgt") == 0);
    ft_file f;
    ft_tdb db;
    open_db(out, &f, &db);
    uint32_t no_data = 0u;
    const ft_tdb_level *l0 = &db.hdr.levels[0];
    for (uint32_t n = 0u; n < l0->cols * l0->rows; ++n) {
        no_data += g_entries[n].state == FT_TDB_NO_DATA;
    }
    printf("holes: level 0 lists %u tiles, %u no data\n", l0->cols * l0->rows, no_data);
    CHECK(no_data > 0u && no_data < l0->cols * l0->rows);
    /* lon 5, lat 45: inside the box, outside both tiles */
    const uint32_t tx = (185u * 1200u) / TILE, ty = (135u * 1200u) / TILE;
    const ft_tdb_entry *e = ft_tdb_find(&db, 0u, tx, ty);
    REQUIRE(e != NULL);
    CHECK(e->state == FT_TDB_NO_DATA);
    ft_tdb_tile t;
    g_tile[0] = 1234.0f;
    read_tile(&db, 0u, tx, ty, &t);
    CHECK(t.state == FT_TDB_NO_DATA && g_tile[0] == 1234.0f);
    /* lon 11.5, lat 49.5: inside N49E011 */
    read_tile(&db, 0u, (uint32_t)((191.5 * 1200) / TILE), (uint32_t)((139.5 * 1200) / TILE), &t);
    CHECK(t.state == FT_TDB_DATA);
    /* outside the level's box but on the lattice: no data too */
    CHECK(ft_tdb_find(&db, 0u, 0u, 0u) == NULL);
    read_tile(&db, 0u, 0u, 0u, &t);
    CHECK(t.state == FT_TDB_NO_DATA);
    /* outside the lattice: an error */
    ft_error err;
    CHECK(ft_tdb_read_tile(&db, 0u, 100000u, 0u, g_tile, TILE * TILE, g_bits, sizeof g_bits, &t,
                           &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "outside the lattice") != NULL);
    CHECK(ft_tdb_read_tile(&db, 99u, 0u, 0u, g_tile, TILE * TILE, g_bits, sizeof g_bits, &t,
                           &err) == FT_ERR_ARG);
    ft_plat_file_close(&f);
}

/* ---- N42E001 (3") over ETOPO5 (5') ------------------------------------------------------ */
static void mixed(void)
{
    const char *etopo = "/usr/share/ferret-vis/data/etopo5.cdf";
    FILE *probe = fopen(etopo, "rb");
    if (probe == NULL) {
        printf("%s missing (package ferret-datasets): skipped the mixed-resolution part\n",
               etopo);
        return;
    }
    fclose(probe);
    const char *out = FT_TEST_OUT_DIR "/mixed.ftd";
    /* no CRS in the netCDF: refused unless told */
    CHECK(run_import(out, NULL, FT_SHARED_DATA_DIR "/N42E001.hgt", etopo) == 1);
    CHECK(run_import(out, "--assume-wgs84", FT_SHARED_DATA_DIR "/N42E001.hgt", etopo) == 0);
    ft_test_read_srtm3(FT_SHARED_DATA_DIR "/N42E001.hgt", g_hgt[1]);
    ft_file f;
    ft_tdb db;
    open_db(out, &f, &db);
    CHECK(db.hdr.samples_per_deg == 1200u);
    CHECK(db.hdr.min_height_m == -10376.0f && db.hdr.max_height_m == 7833.0f);
    /* ETOPO5 enters at level 7 (384" >= 300"): the first level covering the globe */
    REQUIRE(db.hdr.level_count > 7u);
    const uint32_t k = 7u;
    CHECK(db.hdr.levels[k].cols * db.hdr.levels[k].rows > 50u);
    CHECK(db.hdr.levels[6].cols == 1u && db.hdr.levels[6].rows == 1u);
    uint64_t srtm_wins = 0;
    const ft_tdb_level *lv = &db.hdr.levels[k];
    for (uint32_t ty = lv->ty0; ty < lv->ty0 + lv->rows; ++ty) {
        for (uint32_t tx = lv->tx0; tx < lv->tx0 + lv->cols; ++tx) {
            ft_tdb_tile t;
            read_tile(&db, k, tx, ty, &t);
            CHECK(t.state == FT_TDB_DATA);
            if (t.state != FT_TDB_DATA) {
                continue;
            }
            /* a global input covers every lattice point, the seam between
             * its last and first column and both poles included */
            if (t.entry.nodata_count != 0u) {
                uint32_t lattice_cols = 0u, lattice_rows = 0u;
                ft_tdb_lattice_tiles(1200u, TILE, k, &lattice_cols, &lattice_rows);
                /* only the lattice's east and north edge tiles reach past it */
                CHECK(tx == lattice_cols - 1u || ty == lattice_rows - 1u);
                for (uint32_t s = 0u; s < TILE * TILE; ++s) {
                    const uint64_t li = (uint64_t)tx * TILE + s % TILE;
                    const uint64_t lj = (uint64_t)ty * TILE + s / TILE;
                    if (li < 3375u && lj <= 1687u && t.heights_m[s] == FT_TDB_NODATA_M) {
                        fprintf(stderr, "mixed: level 7 sample %llu,%llu uncovered\n",
                                (unsigned long long)li, (unsigned long long)lj);
                        CHECK(0);
                        break;
                    }
                }
            }
            for (uint32_t s = 0u; s < TILE * TILE; ++s) {
                const uint64_t i = ((uint64_t)tx * TILE + s % TILE) << k;
                const uint64_t j = ((uint64_t)ty * TILE + s / TILE) << k;
                int hv = 0;
                if (hgt_at(g_hgt[1], 1, 42, i, j, &hv) && hv != -32768) {
                    CHECK(t.heights_m[s] == (float)hv); /* the finest data wins */
                    ++srtm_wins;
                }
            }
        }
    }
    printf("mixed: %llu level-%u samples from SRTM where ETOPO5 also covers\n",
           (unsigned long long)srtm_wins, k);
    CHECK(srtm_wins > 50u);
    /* lon -150, lat -30 (South Pacific): ETOPO5 only, ocean floor */
    const double d = 128.0 / 1200.0;
    const uint64_t i = (uint64_t)((-150.0 + 180.0) / d), j = (uint64_t)((-30.0 + 90.0) / d);
    ft_tdb_tile t;
    read_tile(&db, k, (uint32_t)(i / TILE), (uint32_t)(j / TILE), &t);
    REQUIRE(t.state == FT_TDB_DATA);
    const float sea = t.heights_m[(j % TILE) * TILE + i % TILE];
    printf("mixed: ETOPO5 at -150 E, -30 N: %g m\n", (double)sea);
    CHECK(sea < -1000.0f && sea > -10376.0f);
    ft_plat_file_close(&f);
}

/* ---- corrupt databases ------------------------------------------------------------------ */
static uint8_t *g_good;
static uint8_t *g_bad;
static size_t g_size;

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}
static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}
static uint64_t get64(const uint8_t *p)
{
    return (uint64_t)get32(p) | ((uint64_t)get32(p + 4) << 32);
}
static void put64(uint8_t *p, uint64_t v)
{
    put32(p, (uint32_t)v);
    put32(p + 4, (uint32_t)(v >> 32));
}

static uint8_t *entry_at(uint8_t *db, uint32_t n)
{
    return db + FT_TDB_HEADER_BYTES + (size_t)n * FT_TDB_ENTRY_BYTES;
}

/* Recomputes the index crc and the header crc, so damage sits behind them. */
static void refresh_crcs(uint8_t *db)
{
    const uint32_t entries = get32(db + 28);
    put32(db + 36, (uint32_t)crc32(0L, entry_at(db, 0u), entries * FT_TDB_ENTRY_BYTES));
    put32(db + 124, 0u);
    put32(db + 124, (uint32_t)crc32(0L, db, FT_TDB_HEADER_BYTES));
}

static uint32_t data_entry(const uint8_t *db, uint32_t nth)
{
    const uint32_t entries = get32(db + 28);
    for (uint32_t n = 0u; n < entries; ++n) {
        if (get32(db + FT_TDB_HEADER_BYTES + (size_t)n * FT_TDB_ENTRY_BYTES) == 1u &&
            nth-- == 0u) {
            return n;
        }
    }
    REQUIRE(0);
    return 0u;
}

static ft_status open_bad(size_t size, ft_tdb *db, ft_mem_reader *m, ft_reader_at *r,
                          ft_error *err)
{
    ft_mem_reader_at_init(r, m, g_bad, size, "small.ftd");
    return ft_tdb_open(db, r, g_entries, ENTRIES_CAP, err);
}

static void expect_open(size_t size, ft_status want, const char *phrase)
{
    ft_tdb db;
    ft_mem_reader m;
    ft_reader_at r;
    ft_error err = {FT_OK, ""};
    ft_status st = open_bad(size, &db, &m, &r, &err);
    printf("  open: %s\n", err.text);
    CHECK(st == want);
    CHECK(strstr(err.text, "small.ftd") != NULL);
    CHECK(strstr(err.text, phrase) != NULL);
}

/* Opens fine, then reading data tile `n` fails with want. */
static void expect_read(uint32_t n, ft_status want, const char *phrase)
{
    ft_tdb db;
    ft_mem_reader m;
    ft_reader_at r;
    ft_error err = {FT_OK, ""};
    REQUIRE(open_bad(g_size, &db, &m, &r, &err) == FT_OK);
    uint32_t k = 0u, tx = 0u, ty = 0u;
    for (uint32_t l = 0u; l < db.hdr.level_count; ++l) {
        const ft_tdb_level *lv = &db.hdr.levels[l];
        if (n >= lv->first_entry && n < lv->first_entry + lv->cols * lv->rows) {
            k = l;
            tx = lv->tx0 + (n - lv->first_entry) % lv->cols;
            ty = lv->ty0 + (n - lv->first_entry) / lv->cols;
        }
    }
    ft_tdb_tile t;
    ft_status st = ft_tdb_read_tile(&db, k, tx, ty, g_tile, TILE * TILE, g_bits, sizeof g_bits,
                                    &t, &err);
    printf("  read: %s\n", err.text);
    CHECK(st == want);
    CHECK(strstr(err.text, "small.ftd: tile (level") != NULL);
    CHECK(strstr(err.text, phrase) != NULL);
}

static void reset(void)
{
    memcpy(g_bad, g_good, g_size);
}

static void corrupt(void)
{
    const char *out = FT_TEST_OUT_DIR "/small.ftd";
    REQUIRE(run_import(out, NULL, FT_SHARED_DATA_DIR "/N41E001.hgt", NULL) == 0);
    FILE *f = fopen(out, "rb");
    REQUIRE(f != NULL);
    fseek(f, 0, SEEK_END);
    g_size = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    g_good = malloc(g_size);
    g_bad = malloc(g_size);
    REQUIRE(g_good != NULL && g_bad != NULL);
    REQUIRE(fread(g_good, 1, g_size, f) == g_size);
    fclose(f);

    /* the intact copy opens and every tile reads */
    reset();
    {
        ft_tdb db;
        ft_mem_reader m;
        ft_reader_at r;
        ft_error err;
        REQUIRE(open_bad(g_size, &db, &m, &r, &err) == FT_OK);
        uint32_t read = 0u;
        for (uint32_t k = 0u; k < db.hdr.level_count; ++k) {
            const ft_tdb_level *lv = &db.hdr.levels[k];
            for (uint32_t n = 0u; n < lv->cols * lv->rows; ++n) {
                ft_tdb_tile t;
                read_tile(&db, k, lv->tx0 + n % lv->cols, lv->ty0 + n / lv->cols, &t);
                read += t.state == FT_TDB_DATA;
            }
        }
        CHECK(read == db.hdr.data_tiles && read > 0u);
        /* the caller's index capacity is a named limit, not an overrun */
        CHECK(ft_tdb_open(&db, &r, g_entries, db.hdr.entry_count - 1u, &err) == FT_ERR_BUDGET);
    }
    const uint32_t d0 = data_entry(g_good, 0u), d1 = data_entry(g_good, 1u);
    const uint64_t off0 = get64(entry_at(g_good, d0) + 8);

    printf("truncated by one byte\n");
    reset();
    expect_open(g_size - 1u, FT_ERR_TRUNCATED, "the header says");
    printf("truncated inside the header\n");
    expect_open(300u, FT_ERR_TRUNCATED, "truncated inside the header");

    printf("bad magic\n");
    reset();
    g_bad[0] = 'X';
    expect_open(g_size, FT_ERR_FORMAT, "bad magic");

    printf("bad header crc\n");
    reset();
    g_bad[16] ^= 0x01u; /* tile_samples */
    expect_open(g_size, FT_ERR_CHECKSUM, "header crc32");

    printf("bad index crc\n");
    reset();
    entry_at(g_bad, d0)[20] ^= 0x01u;
    expect_open(g_size, FT_ERR_CHECKSUM, "index crc32");

    printf("index offset past the end\n");
    reset();
    put64(entry_at(g_bad, d1) + 8, (uint64_t)g_size + 4096u);
    refresh_crcs(g_bad);
    expect_open(g_size, FT_ERR_FORMAT, "runs past the end");

    printf("overlapping tiles\n");
    reset();
    put64(entry_at(g_bad, d1) + 8, off0 + 4u);
    refresh_crcs(g_bad);
    expect_open(g_size, FT_ERR_FORMAT, "overlaps tile (level 0");

    printf("a tile over the index\n");
    reset();
    put64(entry_at(g_bad, d0) + 8, 512u);
    refresh_crcs(g_bad);
    expect_open(g_size, FT_ERR_FORMAT, "overlaps the header and index");

    printf("min above max\n");
    reset();
    put32(entry_at(g_bad, d0) + 20, 0x45000000u); /* 2048 m, above the tile's max */
    refresh_crcs(g_bad);
    expect_open(g_size, FT_ERR_NUMERIC, "min");

    printf("a wrong byte size\n");
    reset();
    put32(entry_at(g_bad, d0) + 4, get32(entry_at(g_good, d0) + 4) + 4u);
    refresh_crcs(g_bad);
    expect_open(g_size, FT_ERR_FORMAT, "bytes, a 256x256 tile");

    printf("bad tile crc\n");
    reset();
    g_bad[off0 + 1000u] ^= 0x40u;
    expect_read(d0, FT_ERR_CHECKSUM, "crc32");

    printf("a non-finite height behind a valid crc\n");
    reset();
    {
        const float nan_v = NAN;
        uint8_t b[4];
        memcpy(b, &nan_v, 4u); /* little-endian host: the file's byte order */
        memcpy(g_bad + off0 + 4u * (100u * TILE + 200u), b, 4u);
        const uint32_t bytes = get32(entry_at(g_bad, d0) + 4);
        put32(entry_at(g_bad, d0) + 16, (uint32_t)crc32(0L, g_bad + off0, bytes));
        refresh_crcs(g_bad);
    }
    expect_read(d0, FT_ERR_NUMERIC, "is nan");

    printf("a height outside the tile's bounds behind a valid crc\n");
    reset();
    {
        const float high = 8000.0f;
        memcpy(g_bad + off0 + 4u * (100u * TILE + 200u), &high, 4u);
        const uint32_t bytes = get32(entry_at(g_bad, d0) + 4);
        put32(entry_at(g_bad, d0) + 16, (uint32_t)crc32(0L, g_bad + off0, bytes));
        refresh_crcs(g_bad);
    }
    expect_read(d0, FT_ERR_FORMAT, "heights span");

    free(g_good);
    free(g_bad);
}

/* ---- a database made here (no shared data needed) ------------------------------------ */
/* tests/ftd_synth.h: a small database made with the encoders */
#define SYN_T FT_SYNTH_FTD_T
static uint8_t g_syn[8192];

static size_t synth_db(void)
{
    ft_tdb_header h;
    ft_error err;
    const size_t size = ft_synth_ftd(g_syn, sizeof g_syn, 0.0f, &h, &err);
    if (size == 0u) fprintf(stderr, "synth_db: %s\n", err.text);
    REQUIRE(size > 0u);
    CHECK(h.min_height_m == -20.0f && h.max_height_m == 76.0f);
    /* the encoder refuses what the reader refuses */
    ft_tdb_header bad = h;
    bad.levels[0].tx0 = 23u; /* level 0 has 23 tile columns: 0..22 */
    uint8_t scratch[FT_TDB_HEADER_BYTES];
    CHECK(ft_tdb_encode_header(&bad, scratch, "syn", &err) == FT_ERR_FORMAT);
    bad = h;
    bad.tile_samples = 24u;
    CHECK(ft_tdb_encode_header(&bad, scratch, "syn", &err) == FT_ERR_FORMAT);
    float hv[SYN_T * SYN_T];
    uint8_t bits[SYN_T * SYN_T / 8u];
    memset(bits, 0, sizeof bits);
    ft_synth_ftd_heights(hv);
    hv[7] = NAN;
    ft_tdb_entry e;
    CHECK(ft_tdb_encode_tile(hv, bits, NULL, SYN_T, 0u, scratch, sizeof scratch, &e, "syn",
                             &err) == FT_ERR_NUMERIC);
    ft_synth_ftd_heights(hv);
    static float dev[SYN_T * SYN_T];
    static uint8_t tile_bytes[SYN_T * SYN_T * 8u + SYN_T * SYN_T / 8u];
    for (uint32_t i = 0u; i < SYN_T * SYN_T; ++i) {
        dev[i] = 0.5f;
    }
    CHECK(ft_tdb_encode_tile(hv, bits, dev, SYN_T, 1u, tile_bytes, sizeof tile_bytes, &e, "syn",
                             &err) == FT_OK);
    CHECK(e.byte_size == SYN_T * SYN_T * 8u);
    dev[9] = FT_TDB_DEV_MAX_M * 2.0f; /* no two heights differ this much */
    CHECK(ft_tdb_encode_tile(hv, bits, dev, SYN_T, 1u, tile_bytes, sizeof tile_bytes, &e, "syn",
                             &err) == FT_ERR_NUMERIC);
    CHECK(strstr(err.text, "dev 42000 m at row 0 col 9") != NULL);
    return size;
}

static ft_status syn_open(const uint8_t *b, size_t size, ft_tdb *db, ft_mem_reader *m,
                          ft_reader_at *r, ft_error *err)
{
    ft_mem_reader_at_init(r, m, b, size, "syn.ftd");
    return ft_tdb_open(db, r, g_entries, ENTRIES_CAP, err);
}

static void synthetic(void)
{
    const size_t size = synth_db();
    static uint8_t bad[sizeof g_syn + 1u];
    ft_tdb db;
    ft_mem_reader m;
    ft_reader_at r;
    ft_error err = {FT_OK, ""};
    float h[SYN_T * SYN_T];
    uint8_t bits[SYN_T * SYN_T / 8u];
    ft_tdb_tile t;
    REQUIRE(syn_open(g_syn, size, &db, &m, &r, &err) == FT_OK);
    CHECK(ft_tdb_read_tile(&db, 0u, 10u, 5u, h, SYN_T * SYN_T, bits, sizeof bits, &t, &err) ==
          FT_OK);
    CHECK(t.state == FT_TDB_DATA && t.entry.void_count == 3u && t.entry.nodata_count == 6u);
    CHECK(h[0] == FT_TDB_NODATA_M && h[40] == 20.0f && bit(bits, 40) && !bit(bits, 42));
    CHECK(ft_tdb_read_tile(&db, 0u, 11u, 5u, h, SYN_T * SYN_T, bits, sizeof bits, &t, &err) ==
          FT_OK);
    CHECK(t.state == FT_TDB_NO_DATA);
    CHECK(ft_tdb_read_tile(&db, 1u, 5u, 2u, h, SYN_T * SYN_T, bits, sizeof bits, &t, &err) ==
          FT_OK);
    CHECK(t.state == FT_TDB_DATA && t.entry.void_count == 0u && t.dev_m == NULL);
    /* the level-1 tile's dev: written as "not known" by an encoder given none */
    static float dev[SYN_T * SYN_T];
    CHECK(ft_tdb_read_tile_dev(&db, 1u, 5u, 2u, h, SYN_T * SYN_T, bits, sizeof bits, dev,
                               SYN_T * SYN_T, &t, &err) == FT_OK);
    CHECK(t.dev_m == dev && dev[0] == FT_TDB_DEV_NONE && dev[SYN_T * SYN_T - 1u] == FT_TDB_DEV_NONE);
    CHECK(ft_tdb_read_tile_dev(&db, 1u, 5u, 2u, h, SYN_T * SYN_T, bits, sizeof bits, dev,
                               SYN_T * SYN_T - 1u, &t, &err) == FT_ERR_ARG);
    /* buffers smaller than a tile: refused before any read */
    CHECK(ft_tdb_read_tile(&db, 0u, 10u, 5u, h, SYN_T * SYN_T - 1u, bits, sizeof bits, &t,
                           &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "tile buffers hold") != NULL);

    struct {
        const char *what;
        size_t at;     /* byte to patch (SIZE_MAX: none) */
        uint32_t value; /* u32 written there */
        int refresh;   /* recompute the crcs after */
        size_t size;   /* bytes given to the reader */
        ft_status want;
        const char *phrase;
    } cases[] = {
        {"version 3", 8u, 3u, 1, size, FT_ERR_VERSION, "database version 3"},
        {"version 1 (no dev)", 8u, 1u, 1, size, FT_ERR_VERSION, "import the inputs again"},
        {"a level box past the lattice", 128u, 23u, 1, size, FT_ERR_FORMAT, "the lattice has"},
        {"a no-data entry with an offset", FT_TDB_HEADER_BYTES + 40u + 8u, 1000u, 1, size,
         FT_ERR_FORMAT, "not all zero"},
        {"state 2", FT_TDB_HEADER_BYTES + 80u, 2u, 1, size, FT_ERR_FORMAT, "has state 2"},
        {"entry_count off by one", 28u, 4u, 1, size, FT_ERR_FORMAT, "entry_count 4"},
        {"data_tiles off by one", 32u, 1u, 1, size, FT_ERR_FORMAT, "data tiles, the header says 1"},
        {"a reserved byte", 70u, 1u, 1, size, FT_ERR_FORMAT, "reserved header byte 70"},
        {"a trailing byte", SIZE_MAX, 0u, 0, size + 1u, FT_ERR_OVERSIZED, "1 more than"},
        {"header only", SIZE_MAX, 0u, 0, FT_TDB_HEADER_BYTES, FT_ERR_TRUNCATED, "index ends at"},
    };
    for (size_t c = 0u; c < sizeof cases / sizeof cases[0]; ++c) {
        memcpy(bad, g_syn, size);
        bad[size] = 0u;
        if (cases[c].at != SIZE_MAX) {
            put32(bad + cases[c].at, cases[c].value);
        }
        if (cases[c].refresh) {
            refresh_crcs(bad);
        }
        err = (ft_error){FT_OK, ""};
        ft_status st = syn_open(bad, cases[c].size, &db, &m, &r, &err);
        printf("synthetic, %s: %s\n", cases[c].what, err.text);
        CHECK(st == cases[c].want);
        CHECK(strstr(err.text, "syn.ftd: ") == err.text);
        CHECK(strstr(err.text, cases[c].phrase) != NULL);
    }
    /* a void bit on an uncovered sample, behind valid crcs */
    memcpy(bad, g_syn, size);
    uint8_t *rec = bad + FT_TDB_HEADER_BYTES;
    const uint64_t off = get64(rec + 8);
    bad[off + SYN_T * SYN_T * 4u] |= 0x01u; /* sample 0 is uncovered */
    bad[off + SYN_T * SYN_T * 4u + 5u] &= (uint8_t)~0x01u; /* keep 3 bits set */
    put32(rec + 16, (uint32_t)crc32(0L, bad + off, get32(rec + 4)));
    refresh_crcs(bad);
    REQUIRE(syn_open(bad, size, &db, &m, &r, &err) == FT_OK);
    CHECK(ft_tdb_read_tile(&db, 0u, 10u, 5u, h, SYN_T * SYN_T, bits, sizeof bits, &t, &err) ==
          FT_ERR_FORMAT);
    printf("synthetic, a void bit on an uncovered sample: %s\n", err.text);
    CHECK(strstr(err.text, "void bit on an uncovered sample") != NULL);
    /* a dev that is no bound (NaN), behind valid crcs: refused on read, with
     * or without a dev buffer */
    memcpy(bad, g_syn, size);
    rec = bad + FT_TDB_HEADER_BYTES + 2u * FT_TDB_ENTRY_BYTES; /* the level-1 tile */
    const uint64_t off1 = get64(rec + 8);
    put32(bad + off1 + SYN_T * SYN_T * 4u + (3u * SYN_T + 2u) * 4u, 0x7fc00000u);
    put32(rec + 16, (uint32_t)crc32(0L, bad + off1, get32(rec + 4)));
    refresh_crcs(bad);
    REQUIRE(syn_open(bad, size, &db, &m, &r, &err) == FT_OK);
    CHECK(ft_tdb_read_tile(&db, 1u, 5u, 2u, h, SYN_T * SYN_T, bits, sizeof bits, &t, &err) ==
          FT_ERR_NUMERIC);
    printf("synthetic, a NaN dev: %s\n", err.text);
    CHECK(strstr(err.text, "dev at row 3 col 2 is nan") != NULL);
    CHECK(ft_tdb_read_tile_dev(&db, 1u, 5u, 2u, h, SYN_T * SYN_T, bits, sizeof bits, dev,
                               SYN_T * SYN_T, &t, &err) == FT_ERR_NUMERIC);
}

int main(void)
{
    synthetic();
    FILE *probe = fopen(FT_SHARED_DATA_DIR "/N41E001.hgt", "rb");
    if (probe == NULL) {
        printf("%s missing: skipped the real-data part\n", FT_SHARED_DATA_DIR "/N41E001.hgt");
        int rc = ft_test_result("test_terrain_db");
        return rc != 0 ? rc : FT_TEST_SKIP;
    }
    fclose(probe);
    mosaic();
    holes();
    mixed();
    corrupt();
    return ft_test_result("test_terrain_db");
}
