/* test_db_window.c - a scene's window of a terrain database (.ftd), built in
 * the test from N41E001 + N42E001 (SRTM3) with `fixterrain import
 * --database`, the .hgt files read in place (src/terrain/db_window.h).
 *  samples: (a) windows inside the mosaic: every sample is the .hgt's at
 *    the same lattice point; a window without source voids marks nothing,
 *    one across both files marks exactly the source voids (the database
 *    filled them); (b) a window half past the mosaic's east edge: exactly
 *    the samples east of 2 deg E are marked and drawn at the window's lowest
 *    height, the covered half as in (a); (c) a level past the database's, a
 *    window without data, one past a pole and a corrupt tile are refused,
 *    each naming the key or the file and tile, and the reason; (d) with
 *    ETOPO5 under N42E001, the half past N42E001 is drawn from level 7 and
 *    marked, none at the floor; without a centre, the window sits on the
 *    middle of the data tiles.
 *  render BACKEND METHOD: a nadir frame over the mosaic's edge hatches the
 *    missing half and counts it (unmeasured_px), one inside counts 0. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/import_db.h"
#include "app/app.h"
#include "gpu/shade.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "terrain/db_window.h"
#include "terrain/dem_hgt.h"
#include "test_app_util.h"
#include "test_clip_util.h"

#define HGT_SIDE 1201
#define SIDE_MAX 1201u
#define IO_BYTES (2u << 20)

static int16_t g_hgt[2][HGT_SIDE * HGT_SIDE]; /* N41E001, N42E001; row 0 = north */
static float g_heights[SIDE_MAX * SIDE_MAX];
static uint8_t g_bits[(SIDE_MAX * SIDE_MAX + 7u) / 8u];
static double g_io[IO_BYTES / sizeof(double)];
static char g_text[4096];
static ft_app g_app;

/* one database per mode: CTest may run the modes at once */
static char k_db[256], k_db_bad[256];

/* The .hgt sample at level-0 lattice point (i, j) (N = 1200): 1 when either
 * file covers it (the shared edge row is the same in both), 0 outside. */
static int hgt_at(int64_t i, int64_t j, int *v)
{
    for (int f = 0; f < 2; ++f) {
        const int64_t c = i - (int64_t)(1 + 180) * 1200;
        const int64_t r = (int64_t)(41 + f + 1 + 90) * 1200 - j; /* row 0 = north */
        if (c >= 0 && c < HGT_SIDE && r >= 0 && r < HGT_SIDE) {
            *v = g_hgt[f][r * HGT_SIDE + c];
            return 1;
        }
    }
    return 0;
}

static void build_db(void)
{
    char *argv[] = {(char *)"import", (char *)"--database", (char *)k_db,
                    (char *)FT_SHARED_DATA_DIR "/N41E001.hgt",
                    (char *)FT_SHARED_DATA_DIR "/N42E001.hgt"};
    REQUIRE(ft_cmd_import_db(5, argv) == 0);
}

/* Loads the window with the module itself (no GPU). */
static ft_status load_window(const char *path, uint32_t level, uint32_t side, double lat,
                             double lon, ft_dbw *w, ft_terrain *t, ft_dbw_counts *c,
                             ft_error *err)
{
    ft_file f;
    memset(&f, 0, sizeof f);
    f.fd = -1;
    ft_status st = ft_plat_file_open_read(&f, path, err);
    const ft_dbw_desc d = {level, side, lat, lon};
    if (st == FT_OK) {
        st = ft_dbw_probe(&f.reader_at, &d, w, t, err);
    }
    if (st == FT_OK) {
        t->heights_m = g_heights;
        t->void_bits = g_bits;
        memset(g_bits, 0, ft_terrain_void_bits_bytes(t->width, t->height));
        REQUIRE(ft_dbw_index_bytes(w) + ft_dbw_staging_bytes(w) <= sizeof g_io);
        st = ft_dbw_load(&f.reader_at, w, t, g_io, sizeof g_io, c, err);
    }
    ft_plat_file_close(&f);
    return st;
}

/* Compares the window with the .hgt files: covered samples equal and marked
 * exactly where the source was void; uncovered ones marked (and, with
 * at_floor, at the floor). Returns the number of uncovered samples. */
static uint64_t compare_window(const ft_dbw *w, const ft_terrain *t, const ft_dbw_counts *c,
                               int at_floor, uint64_t *voids_out)
{
    uint64_t uncovered = 0u, voids = 0u, wrong = 0u;
    for (uint32_t y = 0; y < t->height; ++y) {
        for (uint32_t x = 0; x < t->width; ++x) {
            const size_t k = (size_t)y * t->width + x;
            const int marked = ft_terrain_sample_filled(t, k);
            int v = 0;
            if (!hgt_at(w->i0 + x, w->j0 + y, &v)) {
                ++uncovered;
                wrong += !(marked && (!at_floor || t->heights_m[k] == c->fill_m));
            } else if (v == FT_HGT_VOID) {
                ++voids;
                wrong += !marked;
            } else {
                wrong += !(!marked && t->heights_m[k] == (float)v);
            }
        }
    }
    CHECK(wrong == 0u);
    if (wrong != 0u) {
        fprintf(stderr, "%llu samples differ from the .hgt files\n", (unsigned long long)wrong);
    }
    *voids_out = voids;
    return uncovered;
}

static void expect_error(const char *scene_text, const char *what, const char *s1,
                         const char *s2)
{
    static ft_scene s;
    ft_error err;
    ft_scene_defaults(&s);
    ft_status st = ft_scene_parse(&s, scene_text, "test scene", &err);
    CHECK(st == FT_OK);
    if (st != FT_OK) {
        fprintf(stderr, "%s: scene: %s\n", what, err.text);
        return;
    }
    st = ft_app_init(&g_app, &s, &err);
    if (st == FT_OK) {
        ft_app_shutdown(&g_app);
    }
    CHECK(st != FT_OK);
    printf("%s: %s\n", what, st != FT_OK ? err.text : "(accepted)");
    CHECK(st != FT_OK && strstr(err.text, s1) != NULL);
    CHECK(st != FT_OK && strstr(err.text, s2) != NULL);
}

static const char k_scene[] =
    "[scene]\nname = dbw\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\ndb_level = %u\ndb_side_samples = %u\n"
    "db_centre_lat_deg = %s\ndb_centre_lon_deg = %s\n"
    "[gpu]\ntexture_bytes = 32M\n";

static const char *scene(const char *method, const char *backend, const char *db,
                         uint32_t level, uint32_t side, const char *lat, const char *lon)
{
    (void)snprintf(g_text, sizeof g_text, k_scene, method, backend, db, level, side, lat, lon);
    return g_text;
}

/* Patches one byte inside the first data tile of level 0 that the window
 * centred at 41.5 N 1.5 E reads, in a copy of the database. */
static void corrupt_copy(void)
{
    FILE *in = fopen(k_db, "rb");
    REQUIRE(in != NULL);
    REQUIRE(fseek(in, 0, SEEK_END) == 0);
    const long size = ftell(in);
    REQUIRE(size > 0 && fseek(in, 0, SEEK_SET) == 0);
    uint8_t *bytes = malloc((size_t)size); /* test code: the runtime never allocates */
    REQUIRE(bytes != NULL && fread(bytes, 1, (size_t)size, in) == (size_t)size);
    fclose(in);
    ft_file f;
    ft_error err;
    ft_tdb db;
    REQUIRE(ft_plat_file_open_read(&f, k_db, &err) == FT_OK);
    static ft_tdb_entry entries[256];
    REQUIRE(ft_tdb_open(&db, &f.reader_at, entries, 256u, &err) == FT_OK);
    /* 41.5 N 1.5 E at level 0: lattice (217800, 157800), tile (850, 616) */
    const ft_tdb_entry *e = ft_tdb_find(&db, 0u, 217800u / 256u, 157800u / 256u);
    REQUIRE(e != NULL && e->state == FT_TDB_DATA);
    bytes[e->offset + 1000u] ^= 0x40u;
    ft_plat_file_close(&f);
    FILE *out = fopen(k_db_bad, "wb");
    REQUIRE(out != NULL && fwrite(bytes, 1, (size_t)size, out) == (size_t)size);
    REQUIRE(fclose(out) == 0);
    free(bytes);
}

/* N42E001 (3") over ETOPO5 (5', levels 7 and up), when ferret-datasets is
 * installed: a level-0 window half east of N42E001 draws that half from
 * level 7 (bilinear between its samples), marks it, and leaves no sample
 * at the floor; on level 7's own lattice points it is level 7's sample. */
/* The clipmap cache over the database (clip_source.h), filled around the
 * window's middle: every sample of its levels 0..2 that falls on a window
 * sample has the window's height and marking, bit for bit (the window's
 * rule and the source's are one function). Returns the samples compared. */
#define CLIP_SIDE 256u
#define CLIP_LEVELS 3u
static float g_clip_tex[CLIP_LEVELS][CLIP_SIDE * CLIP_SIDE];
static uint8_t g_clip_mark[CLIP_LEVELS][CLIP_SIDE * CLIP_SIDE];
static _Alignas(64) uint8_t g_clip_arena[4u << 20]; /* FT_ARENA_ALIGN */

static uint64_t compare_clip_cache(const char *path, const ft_dbw *w, const ft_terrain *t,
                                   float fill_m, uint64_t *missing)
{
    ft_file f;
    ft_tdb db;
    static ft_tdb_entry entries[4096];
    ft_error err;
    REQUIRE(ft_plat_file_open_read(&f, path, &err) == FT_OK);
    REQUIRE(ft_tdb_open(&db, &f.reader_at, entries, 4096u, &err) == FT_OK);
    ft_arena a;
    memset(&a, 0, sizeof a);
    a.pools[FT_POOL_CLIP].budget_bytes = sizeof g_clip_arena;
    REQUIRE(ft_arena_bind(&a, g_clip_arena, sizeof g_clip_arena, &err) == FT_OK);
    const ft_clip_desc d = {CLIP_SIDE, CLIP_LEVELS, 4u * CLIP_SIDE, 0};
    ft_clip_db_source dbs;
    ft_clip_source src;
    REQUIRE(ft_clip_source_db(&src, &dbs, &db, w->level, w->i0, w->j0, fill_m, 4u, &d, &a,
                              &err) == FT_OK);
    ft_clip_cache c;
    REQUIRE(ft_clip_init(&c, &d, &src, &a, &err) == FT_OK);
    ft_clip_recentre(&c, (double)w->i0 + 0.5 * (t->width - 1u),
                     (double)w->j0 + 0.5 * (t->height - 1u));
    ft_test_clip_fill(&c, &g_clip_tex[0][0], &g_clip_mark[0][0]);
    CHECK(c.stats.levels_behind == 0u);
    uint64_t compared = 0u, wrong = 0u;
    for (uint32_t l = 0; l < CLIP_LEVELS; ++l) {
        const ft_clip_box *v = &c.level[l].valid;
        for (int64_t b = v->j0; b < v->j1; ++b) {
            for (int64_t q = v->i0; q < v->i1; ++q) {
                const int64_t x = q * ((int64_t)1 << l) - w->i0;
                const int64_t y = b * ((int64_t)1 << l) - w->j0;
                if (x < 0 || y < 0 || x >= (int64_t)t->width || y >= (int64_t)t->height) {
                    continue;
                }
                const size_t k = (size_t)y * t->width + (size_t)x;
                const size_t o = (size_t)ft_clip_texel(&c, b) * CLIP_SIDE + ft_clip_texel(&c, q);
                ++compared;
                wrong += g_clip_tex[l][o] != t->heights_m[k] ||
                         (g_clip_mark[l][o] != 0u) != (ft_terrain_sample_filled(t, k) != 0);
            }
        }
    }
    ft_plat_file_close(&f);
    CHECK(compared > 0u && wrong == 0u);
    if (wrong != 0u) {
        fprintf(stderr, "clip cache: %llu of %llu samples differ from the window\n",
                (unsigned long long)wrong, (unsigned long long)compared);
    }
    *missing = dbs.counts.missing_samples;
    return compared;
}

static void mixed_levels(void)
{
    const char *etopo = "/usr/share/ferret-vis/data/etopo5.cdf";
    FILE *probe = fopen(etopo, "rb");
    if (probe == NULL) {
        printf("(d) %s missing: coarser-level fill not checked\n", etopo);
        return;
    }
    fclose(probe);
    char db_path[300];
    (void)snprintf(db_path, sizeof db_path, "%s/dbw_mixed.ftd", FT_TEST_OUT_DIR);
    char *argv[] = {(char *)"import", (char *)"--database", db_path, (char *)"--assume-wgs84",
                    (char *)FT_SHARED_DATA_DIR "/N42E001.hgt", (char *)etopo};
    REQUIRE(ft_cmd_import_db(6, argv) == 0);
    ft_dbw w;
    ft_terrain t;
    ft_dbw_counts c;
    ft_error err;
    uint64_t voids = 0u;
    REQUIRE(load_window(db_path, 0u, 1201u, 42.5, 2.0, &w, &t, &c, &err) == FT_OK);
    const uint64_t uncovered = compare_window(&w, &t, &c, 0, &voids);
    CHECK(uncovered == 600u * 1201u);
    CHECK(c.coarser_samples == uncovered && c.missing_samples == 0u);
    CHECK(t.void_count == uncovered + voids);
    printf("(d) 1201 samples at 42.5 N 2 E over N42E001 + ETOPO5: %llu from coarser levels, "
           "%llu at the floor, %u marked\n",
           (unsigned long long)c.coarser_samples, (unsigned long long)c.missing_samples,
           t.void_count);
    /* level 7's lattice points east of the .hgt: level 7's own samples */
    ft_file f;
    ft_tdb db;
    static ft_tdb_entry entries[512];
    static float tile_m[256u * 256u];
    static uint8_t tile_bits[256u * 256u / 8u];
    REQUIRE(ft_plat_file_open_read(&f, db_path, &err) == FT_OK);
    REQUIRE(ft_tdb_open(&db, &f.reader_at, entries, 512u, &err) == FT_OK);
    uint32_t on_lattice = 0u, wrong = 0u;
    for (uint32_t y = 0; y < t.height; ++y) {
        for (uint32_t x = 0; x < t.width; ++x) {
            const int64_t i = w.i0 + x, j = w.j0 + y;
            int v = 0;
            if (i % 128 != 0 || j % 128 != 0 || hgt_at(i, j, &v)) {
                continue;
            }
            const uint64_t ci = (uint64_t)(i / 128), cj = (uint64_t)(j / 128);
            ft_tdb_tile tile;
            REQUIRE(ft_tdb_read_tile(&db, 7u, (uint32_t)(ci / 256u), (uint32_t)(cj / 256u),
                                     tile_m, 256u * 256u, tile_bits, sizeof tile_bits, &tile,
                                     &err) == FT_OK);
            REQUIRE(tile.state == FT_TDB_DATA);
            ++on_lattice;
            wrong += t.heights_m[(size_t)y * t.width + x] != tile_m[(cj % 256u) * 256u + ci % 256u];
        }
    }
    ft_plat_file_close(&f);
    CHECK(on_lattice > 0u && wrong == 0u);
    printf("(d) %u samples on level 7's lattice equal its samples\n", on_lattice);
    uint64_t missing = 0u;
    const uint64_t n = compare_clip_cache(db_path, &w, &t, c.fill_m, &missing);
    CHECK(missing == 0u);
    printf("(e) clipmap cache over N42E001 + ETOPO5, levels 0..2: %llu samples equal the "
           "window's\n", (unsigned long long)n);
}

static int run_samples(void)
{
    ft_dbw w;
    ft_terrain t;
    ft_dbw_counts c;
    ft_error err;
    uint64_t voids = 0u;

    /* (a) inside N41E001, no source void in it: nothing marked */
    REQUIRE(load_window(k_db, 0u, 601u, 41.5, 1.35, &w, &t, &c, &err) == FT_OK);
    CHECK(compare_window(&w, &t, &c, 1, &voids) == 0u);
    CHECK(voids == 0u && t.void_count == 0u && c.missing_samples == 0u);
    CHECK_NEAR(t.origin_y, 41.25, 1e-9);
    CHECK_NEAR(t.origin_x, 1.1, 1e-9);
    printf("(a) 601 samples at 41.5 N 1.35 E: %u tiles read, %u samples marked\n", c.tiles_read,
           t.void_count);

    /* (a) across both files: the source voids and nothing else marked */
    const uint64_t t0_ns = ft_plat_monotonic_ns();
    REQUIRE(load_window(k_db, 0u, 1201u, 42.0, 1.5, &w, &t, &c, &err) == FT_OK);
    const double load_ms = (double)(ft_plat_monotonic_ns() - t0_ns) * 1e-6;
    CHECK(compare_window(&w, &t, &c, 1, &voids) == 0u);
    CHECK(voids > 0u && t.void_count == voids && c.filled_samples == voids);
    CHECK(c.missing_samples == 0u);
    printf("(a) 1201 samples at 42 N 1.5 E: %u tiles read in %.1f ms (probe + load), %u marked "
           "= %llu source voids\n",
           c.tiles_read, load_ms, t.void_count, (unsigned long long)voids);

    /* (b) half past the east edge (2 deg E): 600 of 1201 columns uncovered */
    REQUIRE(load_window(k_db, 0u, 1201u, 42.0, 2.0, &w, &t, &c, &err) == FT_OK);
    const uint64_t uncovered = compare_window(&w, &t, &c, 1, &voids);
    CHECK(uncovered == 600u * 1201u);
    CHECK(c.missing_samples == uncovered && c.coarser_samples == 0u); /* none has data there */
    CHECK(t.void_count == uncovered + voids);
    CHECK(c.tiles_no_data > 0u); /* east of the listed tiles */
    CHECK(c.fill_m == t.min_height_m);
    {
        uint64_t missing = 0u;
        const uint64_t n = compare_clip_cache(k_db, &w, &t, c.fill_m, &missing);
        CHECK(missing > 0u); /* east of 2 deg E: the floor, marked */
        printf("(e) clipmap cache over the window's database, levels 0..2: %llu samples equal "
               "the window's (%llu at the floor)\n", (unsigned long long)n,
               (unsigned long long)missing);
    }
    printf("(b) 1201 samples at 42 N 2 E: %u tiles read, %u without data; %llu samples missing "
           "(drawn at %.1f m) + %llu source voids = %u marked\n",
           c.tiles_read, c.tiles_no_data, (unsigned long long)c.missing_samples, (double)c.fill_m,
           (unsigned long long)voids, t.void_count);

    /* no centre given: the middle of level 0's data tiles, x 848..853 and
     * y 614..623 of 256 samples (lattice 217855.5, 158463.5, rounded up),
     * 56 columns east of 2 deg E uncovered */
    REQUIRE(load_window(k_db, 0u, 1201u, NAN, NAN, &w, &t, &c, &err) == FT_OK);
    CHECK(w.i0 == 217856 - 600 && w.j0 == 158464 - 600);
    CHECK_NEAR(t.origin_x, -180.0 + 217256.0 / 1200.0, 1e-9);
    CHECK_NEAR(t.origin_y, -90.0 + 157864.0 / 1200.0, 1e-9);
    CHECK(compare_window(&w, &t, &c, 1, &voids) == 56u * 1201u);
    CHECK(c.missing_samples == 56u * 1201u);
    printf("default centre: south-west corner %.6f N %.6f E, %llu samples missing\n",
           t.origin_y, t.origin_x, (unsigned long long)c.missing_samples);

    /* level 2: every 4th level-0 sample; the window's samples are the .hgt's */
    REQUIRE(load_window(k_db, 2u, 301u, 42.0, 1.5, &w, &t, &c, &err) == FT_OK);
    uint64_t wrong = 0u;
    for (uint32_t y = 0; y < t.height; ++y) {
        for (uint32_t x = 0; x < t.width; ++x) {
            int v = 0;
            const size_t k = (size_t)y * t.width + x;
            REQUIRE(hgt_at((w.i0 + x) * 4, (w.j0 + y) * 4, &v));
            wrong += (v != FT_HGT_VOID) && t.heights_m[k] != (float)v;
        }
    }
    CHECK(wrong == 0u && c.missing_samples == 0u);
    CHECK_NEAR(t.spacing_x, 4.0 / 1200.0, 1e-15);

    mixed_levels();

    /* (c) errors, through the app as a scene meets them */
    expect_error(scene("brute", "egl-gles3", k_db, 5u, 1201u, "42", "1.5"), "level past",
                 "terrain.db_level 5", "has levels 0..4");
    expect_error(scene("brute", "egl-gles3", k_db, 0u, 1201u, "30", "1.5"), "no data",
                 "holds no data", k_db);
    expect_error(scene("brute", "egl-gles3", k_db, 0u, 1201u, "89.9", "1.5"), "past a pole",
                 "terrain.db_centre_lat_deg", "past a pole");
    corrupt_copy();
    expect_error(scene("brute", "egl-gles3", k_db_bad, 0u, 1201u, "41.5", "1.5"), "corrupt tile",
                 k_db_bad, ": tile (level 0, 850, 616) crc32 is");
    return ft_test_result("db window samples");
}

/* Hatch or grey (the marking) by colour: no ramp colour is grey. */
static int looks_marked(const uint8_t *p)
{
    const int grey = abs(p[0] - p[1]) <= 1 && abs(p[1] - p[2]) <= 1;
    const int hatch = p[0] == (uint8_t)(FT_HATCH_R * 255.0f + 0.5f) && p[1] == 0u &&
                      p[2] == (uint8_t)(FT_HATCH_B * 255.0f + 0.5f);
    return grey || hatch;
}

/* Marked pixels in columns [x0, x1) of the last frame. */
static uint32_t marked_in(uint32_t x0, uint32_t x1)
{
    const uint32_t W = g_app.scene.width_px, H = g_app.scene.height_px;
    uint32_t n = 0u;
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = x0; x < x1; ++x) {
            n += (uint32_t)looks_marked(g_app.renderer.rgba + 4u * ((size_t)y * W + x));
        }
    }
    return n;
}

static int run_render(const char *backend, const char *method)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_app_init(&g_app, scene(method, backend, k_db, 0u, 1201u, "41.5", "2"), "edge window");
    printf("init of a 1201-sample window: %.1f ms\n%s", (double)g_app.init_ns * 1e-6,
           g_app.pool_table);
    /* the database stays open for a cache to read past the window */
    REQUIRE(g_app.terrain.db != NULL);
    CHECK(g_app.terrain.db_level == 0u && g_app.terrain.db_i0 == g_app.dbw.i0 &&
          g_app.terrain.db_j0 == g_app.dbw.j0 && g_app.terrain.db_fill_m == g_app.dbw_counts.fill_m);
    {
        const ft_tdb_entry *e = ft_tdb_find(g_app.terrain.db, 0u, 850u, 616u);
        CHECK(e != NULL && e->state == FT_TDB_DATA);
    }
    /* nadir over 41.5 N 2 E (the mosaic's edge), 3 km above the ground */
    double x = 0.0, y = 0.0;
    ft_terrain_geo_to_world(&g_app.terrain, 41.5, 2.0, &x, &y);
    const double h = ft_terrain_height_at(&g_app.terrain, x, y);
    ft_pose p = ft_test_pose(41.5, 2.0, h + 3000.0, 0.0, -90.0, 0.0);
    ft_test_frame(&g_app, &p, &cam, &fs);
    const uint32_t W = g_app.scene.width_px, H = g_app.scene.height_px;
    const uint32_t west = marked_in(0u, W * 2u / 5u), east = marked_in(W * 3u / 5u, W);
    printf("edge: unmeasured_px %llu of %u; marked pixels west %u, east %u of %u each\n",
           (unsigned long long)fs.unmeasured_px, W * H, west, east, (W * 2u / 5u) * H);
    CHECK(fs.unmeasured_px > 0u);
    CHECK(west == 0u);                   /* measured terrain: no marking */
    CHECK(east == (W - W * 3u / 5u) * H); /* the missing half: all marked */

    /* wholly inside (41.5 N 1.9 E): nothing marked, nothing counted */
    ft_terrain_geo_to_world(&g_app.terrain, 41.5, 1.9, &x, &y);
    p = ft_test_pose(41.5, 1.9, ft_terrain_height_at(&g_app.terrain, x, y) + 3000.0, 0.0, -90.0,
                     0.0);
    ft_test_frame(&g_app, &p, &cam, &fs);
    printf("inside: unmeasured_px %llu, marked pixels %u\n", (unsigned long long)fs.unmeasured_px,
           marked_in(0u, W));
    CHECK(fs.unmeasured_px == 0u);
    CHECK(marked_in(0u, W) == 0u);
    ft_app_shutdown(&g_app);
    return ft_test_result("db window render");
}

int main(int argc, char **argv)
{
    if (!ft_test_have_data(FT_SHARED_DATA_DIR "/N41E001.hgt") ||
        !ft_test_have_data(FT_SHARED_DATA_DIR "/N42E001.hgt")) {
        return FT_TEST_SKIP;
    }
    ft_test_read_srtm3(FT_SHARED_DATA_DIR "/N41E001.hgt", g_hgt[0]);
    ft_test_read_srtm3(FT_SHARED_DATA_DIR "/N42E001.hgt", g_hgt[1]);
    const char *mode = argc >= 2 ? argv[1] : "";
    (void)snprintf(k_db, sizeof k_db, "%s/dbw_%s.ftd", FT_TEST_OUT_DIR, mode);
    (void)snprintf(k_db_bad, sizeof k_db_bad, "%s/dbw_%s_badtile.ftd", FT_TEST_OUT_DIR, mode);
    if (argc >= 2 && strcmp(argv[1], "samples") == 0) {
        build_db();
        return run_samples();
    }
    if (argc >= 4 && strcmp(argv[1], "render") == 0) {
        build_db();
        return run_render(argv[2], argv[3]);
    }
    fprintf(stderr, "usage: test_db_window samples | render BACKEND METHOD\n");
    return 2;
}
