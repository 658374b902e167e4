/* test_antimeridian.c - terrain across 180 deg E over a database of ETOPO5
 * alone (N = 12 samples a degree, built in the test with `fixterrain import
 * --database`): every level the test reads closes around the globe
 * (4320 / 2^l whole for l <= 5), so the lattice wraps in longitude.
 *  (a) a window of 121 x 121 samples centred on 17 S 180 E: every sample is
 *      the database's own level-0 sample at lattice column i mod 4320, read
 *      here tile by tile with ft_tdb_read_tile; none is marked, none taken
 *      from a coarser level or the floor;
 *  (b) the clipmap cache over the database, 5 levels of 64^2 around the same
 *      point: every resident sample of every level is the database's sample
 *      at its wrapped column, unmarked;
 *  (c) frames (brute and clipmap, 320 x 240) from poses given with
 *      longitudes in -180..180 on both sides of the antimeridian, looking
 *      across it: the pose lands on the right side of the window (its
 *      position over the window), the frame covers what the reference covers
 *      (mismatch within the tolerance the flight test uses) and no pixel is
 *      hatched as unmeasured.
 *  (d) the clipmap 8-15 degrees past the window, 400 m above the sea floor,
 *      looking down 30 and 60 degrees: the frame's depth range comes from
 *      the cache's resident samples (the window's range put the near plane
 *      5 km out and the frame showed only the clear colour), and no pixel
 *      is the clear colour.
 * Before the wrap, (a) marked the 60 columns east of 180 and took them from
 * the floor, and (c)'s frames east of the seam drew the floor.
 *
 * usage: test_antimeridian */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/import_db.h"
#include "app/app.h"
#include "core/platform_api.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "terrain/db_window.h"
#include "test_app_util.h"
#include "test_clip_util.h"

#define WIN_SIDE 121u
#define CLIP_SIDE 64u
#define CLIP_LEVELS 5u
#define TILE_MAX (1024u * 1024u)
#define LAT_DEG (-17.0)

static const char *k_etopo = "/usr/share/ferret-vis/data/etopo5.cdf";
static char k_db[300];
static float g_heights[WIN_SIDE * WIN_SIDE];
static uint8_t g_bits[(WIN_SIDE * WIN_SIDE + 7u) / 8u];
static double g_io[(4u << 20) / sizeof(double)];
static float g_tile_m[TILE_MAX];
static uint8_t g_tile_bits[TILE_MAX / 8u];
static ft_tdb_entry g_entries[8192];
static float g_clip_tex[CLIP_LEVELS][CLIP_SIDE * CLIP_SIDE];
static uint8_t g_clip_mark[CLIP_LEVELS][CLIP_SIDE * CLIP_SIDE];
static _Alignas(64) uint8_t g_clip_arena[4u << 20]; /* FT_ARENA_ALIGN */
static char g_scene[4096];
static ft_app g_app;

/* The database's own sample (level, i mod nx, j), by a plain tile read. */
static float db_sample(const ft_tdb *db, uint32_t level, int64_t i, int64_t j)
{
    uint64_t nx = 0u, ny = 0u;
    ft_tdb_lattice_samples(db->hdr.samples_per_deg, level, &nx, &ny);
    const int64_t iw = ((i % (int64_t)nx) + (int64_t)nx) % (int64_t)nx;
    const uint32_t T = db->hdr.tile_samples;
    REQUIRE((size_t)T * T <= TILE_MAX && j >= 0 && (uint64_t)j < ny);
    ft_tdb_tile tile;
    ft_error err;
    REQUIRE(ft_tdb_read_tile(db, level, (uint32_t)(iw / T), (uint32_t)(j / T), g_tile_m, TILE_MAX,
                             g_tile_bits, sizeof g_tile_bits, &tile, &err) == FT_OK);
    REQUIRE(tile.state == FT_TDB_DATA);
    return g_tile_m[(size_t)(j % T) * T + (size_t)(iw % T)];
}

static void open_db(ft_file *f, ft_tdb *db)
{
    ft_error err;
    memset(f, 0, sizeof *f);
    f->fd = -1;
    REQUIRE(ft_plat_file_open_read(f, k_db, &err) == FT_OK);
    REQUIRE(ft_tdb_open(db, &f->reader_at, g_entries, 8192u, &err) == FT_OK);
}

/* (a) the window across the seam */
static void window(ft_dbw *w, ft_terrain *t)
{
    ft_file f;
    ft_tdb db;
    open_db(&f, &db);
    for (uint32_t l = 0u; l < CLIP_LEVELS; ++l) {
        CHECK(ft_tdb_lattice_closes(db.hdr.samples_per_deg, l));
    }
    ft_error err;
    const ft_dbw_desc d = {0u, WIN_SIDE, LAT_DEG, 180.0};
    REQUIRE(ft_dbw_probe(&f.reader_at, &d, w, t, &err) == FT_OK);
    t->heights_m = g_heights;
    t->void_bits = g_bits;
    memset(g_bits, 0, sizeof g_bits);
    REQUIRE(ft_dbw_index_bytes(w) + ft_dbw_staging_bytes(w) <= sizeof g_io);
    ft_dbw_counts c;
    const ft_status st = ft_dbw_load(&f.reader_at, w, t, g_io, sizeof g_io, &c, &err);
    if (st != FT_OK) fprintf(stderr, "load: %s\n", err.text);
    REQUIRE(st == FT_OK);
    uint64_t wrong = 0u, east = 0u;
    for (uint32_t y = 0u; y < t->height; ++y) {
        for (uint32_t x = 0u; x < t->width; ++x) {
            const int64_t i = w->i0 + x, j = w->j0 + y;
            const size_t k = (size_t)y * t->width + x;
            east += i >= (int64_t)w->nx;
            wrong += t->heights_m[k] != db_sample(&db, 0u, i, j) || ft_terrain_sample_filled(t, k);
        }
    }
    printf("(a) window of %u^2 at %.0f S 180 E: lattice columns %lld..%lld of %llu (%llu samples "
           "east of 180), %llu from coarser levels, %llu at the floor, %llu differ from the "
           "database's own samples\n",
           WIN_SIDE, -LAT_DEG, (long long)w->i0, (long long)(w->i0 + WIN_SIDE - 1u),
           (unsigned long long)w->nx, (unsigned long long)east,
           (unsigned long long)c.coarser_samples, (unsigned long long)c.missing_samples,
           (unsigned long long)wrong);
    CHECK(east > 0u && w->i0 < (int64_t)w->nx); /* the window crosses the seam */
    CHECK(c.coarser_samples == 0u && c.missing_samples == 0u && t->void_count == 0u);
    CHECK(wrong == 0u);
    ft_plat_file_close(&f);
}

/* (b) the clip cache over the database around the seam */
static void cache(const ft_dbw *w, const ft_terrain *t)
{
    ft_file f;
    ft_tdb db;
    open_db(&f, &db);
    ft_error err;
    ft_arena a;
    memset(&a, 0, sizeof a);
    a.pools[FT_POOL_CLIP].budget_bytes = sizeof g_clip_arena;
    REQUIRE(ft_arena_bind(&a, g_clip_arena, sizeof g_clip_arena, &err) == FT_OK);
    const ft_clip_desc d = {CLIP_SIDE, CLIP_LEVELS, 4u * CLIP_SIDE, 0};
    ft_clip_db_source dbs;
    ft_clip_source src;
    REQUIRE(ft_clip_source_db(&src, &dbs, &db, 0u, w->i0, w->j0, 0.0f, 4u, &d, &a, &err) ==
            FT_OK);
    CHECK(dbs.wraps == 1 && src.data_i_lo < 0 && src.data_i_hi > (int64_t)w->nx);
    ft_clip_cache c;
    REQUIRE(ft_clip_init(&c, &d, &src, &a, &err) == FT_OK);
    (void)ft_clip_recentre(&c, (double)w->i0 + 0.5 * (t->width - 1u),
                           (double)w->j0 + 0.5 * (t->height - 1u));
    ft_test_clip_fill(&c, &g_clip_tex[0][0], &g_clip_mark[0][0]);
    CHECK(c.stats.levels_behind == 0u);
    uint64_t compared = 0u, wrong = 0u, east = 0u;
    for (uint32_t l = 0; l < CLIP_LEVELS; ++l) {
        uint64_t nx = 0u, ny = 0u;
        ft_tdb_lattice_samples(db.hdr.samples_per_deg, l, &nx, &ny);
        const ft_clip_box *v = &c.level[l].valid;
        for (int64_t b = v->j0; b < v->j1; ++b) {
            for (int64_t q = v->i0; q < v->i1; ++q) {
                const size_t o = (size_t)ft_clip_texel(&c, b) * CLIP_SIDE + ft_clip_texel(&c, q);
                ++compared;
                east += q >= (int64_t)nx || q < 0;
                wrong += g_clip_tex[l][o] != db_sample(&db, l, q, b) || g_clip_mark[l][o] != 0u;
            }
        }
    }
    printf("(b) clip cache, %u levels of %u^2 around 180 E: %llu resident samples (%llu past "
           "the seam), %llu differ from the database's or are marked\n",
           CLIP_LEVELS, CLIP_SIDE, (unsigned long long)compared, (unsigned long long)east,
           (unsigned long long)wrong);
    CHECK(compared > 0u && east > 0u && wrong == 0u);
    ft_plat_file_close(&f);
}

/* (c) frames across the seam */
static void frames(const char *method)
{
    (void)snprintf(g_scene, sizeof g_scene,
                   "[scene]\nmethod = %s\nbackend = egl-gles3\n"
                   "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 50\n"
                   "[terrain]\ndem = %s\ndb_level = 0\ndb_side_samples = %u\n"
                   "db_centre_lat_deg = %.1f\ndb_centre_lon_deg = 180\n"
                   "[clipmap]\nside = %u\nlevels = %u\nupdate_samples_max = 4096\n"
                   "[gpu]\ntexture_bytes = 64M\n[metric]\nenabled = 1\n"
                   "[budget]\nheights_bytes = 2M\npyramids_bytes = 4M\ndem_io_bytes = 4M\n"
                   "frame_rgba_bytes = 512K\nframe_pos_bytes = 2M\nreference_bytes = 4M\n"
                   "metric_bytes = 1M\ngpu_staging_bytes = 4M\nmethod_bytes = 4M\n"
                   "clip_bytes = 12M\n",
                   method, k_db, WIN_SIDE, LAT_DEG, CLIP_SIDE, CLIP_LEVELS);
    ft_test_app_init(&g_app, g_scene, method);
    const ft_terrain *t = &g_app.terrain;
    /* west of the seam looking east, east of it looking west, above it
     * looking north along it */
    static const double poses[3][3] = {{179.2, 90.0, -12.0}, {-179.2, 270.0, -12.0},
                                       {180.0, 0.0, -30.0}};
    const double width_m = (double)(t->width - 1u) * t->cell_x_m;
    for (int k = 0; k < 3; ++k) {
        double x = 0.0, y = 0.0;
        ft_terrain_geo_to_world(t, LAT_DEG, poses[k][0], &x, &y);
        /* where the pose must land: its longitude's turn east of 180 deg
         * runs on past the window's middle (180 deg) */
        const double lon_e = poses[k][0] < 0.0 ? poses[k][0] + 360.0 : poses[k][0];
        const double want_x = 0.5 * width_m + (lon_e - 180.0) * 12.0 * t->cell_x_m;
        const ft_pose p = ft_test_pose(LAT_DEG, poses[k][0],
                                       fmax(ft_terrain_height_at(t, x, y), 0.0) + 3000.0,
                                       poses[k][1], poses[k][2], 0.0);
        ft_camera cam;
        ft_frame_stats fs;
        ft_error_stats es;
        ft_test_frame(&g_app, &p, &cam, &fs);
        ft_test_frame(&g_app, &p, &cam, &fs); /* the clipmap's levels current */
        ft_test_measure(&g_app, &cam, &es);
        const uint32_t mismatch = es.only_method_px + es.only_ref_px;
        const uint32_t ref_px = es.terrain_px + es.only_ref_px - es.only_method_px;
        const double allowed = fmax(16.0, 0.12 * (double)ref_px);
        printf("(c) %s at %.1f E heading %.0f: eye x %.0f m (expected %.0f, window middle "
               "%.0f m), mismatch %u+%u of %u px, unmeasured %llu px, max error %.2f px\n",
               method, poses[k][0], poses[k][1], x, want_x, 0.5 * width_m, es.only_method_px,
               es.only_ref_px, ref_px, (unsigned long long)fs.unmeasured_px, es.max_px);
        CHECK(fabs(x - want_x) < 1e-3 * t->cell_x_m);
        CHECK(ref_px > 1000u);
        CHECK((double)mismatch <= allowed);
        CHECK(fs.unmeasured_px == 0u);
    }
    if (strcmp(method, "clipmap") == 0) {
        /* past the window: the clipmap draws the database there */
        ft_test_clear_magenta(&g_app);
        static const double far_poses[3][2] = {{172.0, -30.0}, {-172.0, -30.0}, {165.0, -60.0}};
        for (int k = 0; k < 3; ++k) {
            ft_file f;
            ft_tdb db;
            open_db(&f, &db);
            const double lon_e = far_poses[k][0] < 0.0 ? far_poses[k][0] + 360.0 : far_poses[k][0];
            const float ground_m =
                db_sample(&db, 0u, (int64_t)floor((lon_e + 180.0) * 12.0 + 0.5),
                          (int64_t)floor((LAT_DEG + 90.0) * 12.0 + 0.5));
            ft_plat_file_close(&f);
            const ft_pose p = ft_test_pose(LAT_DEG, far_poses[k][0], (double)ground_m + 400.0,
                                           45.0, far_poses[k][1], 0.0);
            ft_camera cam;
            ft_frame_stats fs;
            ft_test_frame(&g_app, &p, &cam, &fs);
            ft_test_frame(&g_app, &p, &cam, &fs);
            const uint32_t clear = ft_test_clear_pixels(&g_app);
            printf("(d) clipmap at %.1f E, 400 m above the sea floor, pitch %.0f (past the "
                   "window): near %.2f m far %.0f m, %u clear px\n",
                   far_poses[k][0], far_poses[k][1], cam.near_m, cam.far_m, clear);
            CHECK(clear == 0u);
            CHECK(cam.near_m < 200.0); /* the terrain 400 m below is in front of it */
        }
    }
    ft_app_shutdown(&g_app);
}

int main(void)
{
    if (!ft_test_have_data(k_etopo)) {
        return FT_TEST_SKIP;
    }
    (void)snprintf(k_db, sizeof k_db, "%s/antimeridian.ftd", FT_TEST_OUT_DIR);
    char *argv[] = {(char *)"import", (char *)"--database", k_db, (char *)"--assume-wgs84",
                    (char *)k_etopo};
    REQUIRE(ft_cmd_import_db(5, argv) == 0);
    ft_dbw w;
    ft_terrain t;
    window(&w, &t);
    cache(&w, &t);
    frames("brute");
    frames("clipmap");
    return ft_test_result("antimeridian");
}
