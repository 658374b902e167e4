/* test_tdb_dev.c - a database's deviation bounds (dev_m, terrain_db.h)
 * against the finest data, on databases built here with `fixterrain import
 * --database` from real DEMs:
 *   mosaic: N41E001 + N42E001 (SRTM3) in 64-sample tiles (many tile edges),
 *     the whole mosaic and a margin past it;
 *   mixed: N42E001 over ETOPO5 (which enters at level 7), N42E001 and a
 *     margin of ETOPO5-only terrain around it.
 * The truth is level 0 read by the runtime's rule (ft_dbw_read_rect: data,
 * else the nearest coarser level's bilinear value); B_k is level k read the
 * same way. For every level k >= 1 and every cell of the region:
 *   - a bound (dev >= 0): every level-0 lattice point p of the closed cell
 *     has a truth, and |T(p) - B_k(p)| <= dev (the float rounding of the
 *     comparison aside); exact (within 1e-3 m) on level 1, on every cell
 *     that level 0 covers, and on the levels a region names;
 *   - at a data edge (a corner without data at level k): |T(p) - r| <= dev
 *     at the points that take finer data, r the mean of its data corners;
 *   - COARSER: level 0 has no data in the closed cell off the level-k
 *     points, and a corner lacks data;
 *   - NONE: never, in these databases.
 * It reports, per level, how tight the bounds are (largest measured over
 * stored, the mean ratio) and how many cells have none. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../tools/import_db.h"
#include "core/platform_api.h"
#include "terrain/db_window.h"
#include "terrain/terrain_db.h"
#include "test_util.h"

#define REGION_MAX (1800u * 2700u)
#define TILE_MAX 256u
#define CACHE_SLOTS 16u
#define ENTRIES_CAP 20000u
/* float rounding of heights and of the comparison */
#define TOL_M 1e-3

static float g_truth[REGION_MAX];   /* level 0 by the rule */
static uint8_t g_fine[REGION_MAX];  /* level 0 has data there */
static float g_level[REGION_MAX];   /* level k by the rule */
static uint8_t g_bits[(REGION_MAX + 7u) / 8u];
static float g_coarse[REGION_MAX];
static float g_tile_h[TILE_MAX * TILE_MAX];
static uint8_t g_tile_bits[TILE_MAX * TILE_MAX / 8u];
static float g_tile_dev[TILE_MAX * TILE_MAX];
static ft_tdb_entry g_entries[ENTRIES_CAP];
static float g_cache_mem[CACHE_SLOTS * (TILE_MAX * TILE_MAX + TILE_MAX * TILE_MAX / 32u)];

typedef struct region {
    const char *name;
    int64_t i0, j0; /* level-0 lattice index of (0, 0) */
    uint32_t w, h;
    uint32_t global_level; /* a global input enters here (data at every sample); 0 none */
    uint32_t exact_mask;   /* levels whose bounds must be exact (bit k) */
} region;

static uint64_t g_nx0; /* level 0 lattice columns: 180 deg */
static uint32_t g_per_deg;

static size_t at(const region *g, int64_t x, int64_t y)
{
    return (size_t)y * g->w + (size_t)x;
}

/* A rect of `level` read by the runtime's rule into out (w * h). */
static void read_rule(const ft_tdb *db, ft_tdb_tile_cache *tc, uint32_t level, int64_t i0,
                      int64_t j0, uint32_t w, uint32_t h, float *out)
{
    REQUIRE((size_t)w * h <= REGION_MAX);
    memset(g_bits, 0, ((size_t)w * h + 7u) / 8u);
    const ft_dbw_rect r = {level, i0, j0, w, h, out, g_bits, NULL};
    ft_dbw_counts c;
    memset(&c, 0, sizeof c);
    uint64_t remaining = 0u;
    ft_error err;
    const size_t cb = ft_dbw_rect_coarse_bytes(&db->hdr, level, w, h);
    REQUIRE(cb <= sizeof g_coarse);
    const ft_status st = ft_dbw_read_rect(db, &r, tc, g_coarse, cb, &c, &remaining, &err);
    if (st != FT_OK) {
        fprintf(stderr, "read_rule: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
}

/* g_fine: where level 0 itself has data (its tiles read raw). */
static void read_fine(const ft_tdb *db, const region *g)
{
    const uint32_t T = db->hdr.tile_samples;
    memset(g_fine, 0, (size_t)g->w * g->h);
    uint32_t cols = 0u, rows = 0u;
    ft_tdb_lattice_tiles(db->hdr.samples_per_deg, T, 0u, &cols, &rows);
    for (int64_t ty = g->j0 / T; ty <= (g->j0 + g->h - 1) / T; ++ty) {
        for (int64_t tx = g->i0 / T; tx <= (g->i0 + g->w - 1) / T; ++tx) {
            ft_tdb_tile t;
            ft_error err;
            /* level 0 closes: a tile past 180 deg holds the columns from 0 */
            const int64_t wx = tx % (int64_t)cols;
            if (wx != tx) {
                continue; /* the regions here have no level-0 data past 180 deg */
            }
            REQUIRE(ft_tdb_read_tile(db, 0u, (uint32_t)wx, (uint32_t)ty, g_tile_h,
                                     TILE_MAX * TILE_MAX, g_tile_bits, sizeof g_tile_bits, &t,
                                     &err) == FT_OK);
            if (t.state != FT_TDB_DATA) {
                continue;
            }
            for (uint32_t s = 0u; s < T * T; ++s) {
                const int64_t x = tx * T + s % T - g->i0, y = ty * T + s / T - g->j0;
                if (x >= 0 && y >= 0 && x < g->w && y < g->h) {
                    g_fine[at(g, x, y)] = g_tile_h[s] != FT_TDB_NODATA_M;
                }
            }
        }
    }
}

typedef struct level_report {
    uint64_t bound, edge, coarser, none, wrong, exact;
    double max_measured_m, max_stored_m, ratio_sum, max_slack_m;
    uint64_t ratio_n;
} level_report;

static void wrong(level_report *rep, uint32_t k, int64_t ci, int64_t cj, const char *what,
                  double measured, double stored)
{
    if (rep->wrong < 5u) {
        fprintf(stderr, "level %u cell %lld,%lld: %s (measured %.4f m, stored %.4f m)\n", k,
                (long long)ci, (long long)cj, what, measured, stored);
    }
    rep->wrong++;
}

/* Level-k data at level-0 point (x, y) of the region: level 0's (point
 * samples carry it up), or a global input's from its level on. */
static int raw_at(const region *g, uint32_t k, int64_t x, int64_t y)
{
    const int inside = g->i0 + x < (int64_t)g_nx0 || ft_tdb_lattice_closes(g_per_deg, k);
    return inside && (g_fine[at(g, x, y)] || (g->global_level > 0u && k >= g->global_level));
}

/* The point resolves finer than level k (its data, or a bilinear mix of
 * level-m data for m < k; in these regions only level 0 and the global
 * input's levels have data of their own). */
static int finer_at(const region *g, uint32_t k, int64_t x, int64_t y)
{
    return g_fine[at(g, x, y)] || (g->global_level > 0u && k > g->global_level);
}

/* One level-k cell (ci, cj) with stored dev d: the checks in the header. */
static void check_cell(const region *g, uint32_t k, int64_t ci, int64_t cj, int64_t li0,
                       int64_t lj0, uint32_t lw, float d, float tile_avg_m, level_report *rep)
{
    const int64_t s = (int64_t)1 << k;
    const int64_t x0 = ci * s - g->i0, y0 = cj * s - g->j0;
    int corners = 0, finer = 0;
    double r = 0.0;
    for (int64_t y = 0; y <= s; ++y) {
        for (int64_t x = 0; x <= s; ++x) {
            const int on_lattice = (x == 0 || x == s) && (y == 0 || y == s);
            if (on_lattice && raw_at(g, k, x0 + x, y0 + y)) {
                ++corners;
                r += (double)g_truth[at(g, x0 + x, y0 + y)];
            }
            finer |= !on_lattice && g_fine[at(g, x0 + x, y0 + y)];
        }
    }
    if (d == FT_TDB_DEV_NONE) {
        rep->none++;
        wrong(rep, k, ci, cj, "no bound, where the data give one", 0.0, (double)d);
        return;
    }
    if (d == FT_TDB_DEV_COARSER) {
        rep->coarser++;
        if (corners == 4 || finer) {
            wrong(rep, k, ci, cj, "marked coarser, but it has data", 0.0, (double)d);
        }
        return;
    }
    double worst = 0.0;
    if (corners < 4) {
        /* at a data edge: |T - r| over the points with level-0 data (no
         * level between 0 and k has other data in these regions) */
        rep->edge++;
        r = corners > 0 ? r / (double)corners : (double)tile_avg_m;
        for (int64_t y = 0; y <= s; ++y) {
            for (int64_t x = 0; x <= s; ++x) {
                if (finer_at(g, k, x0 + x, y0 + y)) {
                    const double e = fabs((double)g_truth[at(g, x0 + x, y0 + y)] - r);
                    worst = e > worst ? e : worst;
                }
            }
        }
        if (worst > (double)d + TOL_M) {
            wrong(rep, k, ci, cj, "edge bound exceeded", worst, (double)d);
        }
        return;
    }
    rep->bound++;
    int covered = g->i0 + x0 + s < (int64_t)g_nx0; /* west of 180 deg */
    const float *c0 = &g_level[(cj - lj0) * lw + (ci - li0)], *c1 = c0 + lw;
    const double h00 = c0[0], h10 = c0[1], h01 = c1[0], h11 = c1[1];
    for (int64_t y = 0; y <= s; ++y) {
        for (int64_t x = 0; x <= s; ++x) {
            const float t = g_truth[at(g, x0 + x, y0 + y)];
            if (t == FT_TDB_NODATA_M) {
                wrong(rep, k, ci, cj, "a point without truth", 0.0, (double)d);
                continue;
            }
            const double fx = (double)x / (double)s, fy = (double)y / (double)s;
            const double b = (1.0 - fy) * ((1.0 - fx) * h00 + fx * h10) +
                             fy * ((1.0 - fx) * h01 + fx * h11);
            const double e = fabs((double)t - b);
            worst = e > worst ? e : worst;
            covered &= g_fine[at(g, x0 + x, y0 + y)];
        }
    }
    if (worst > (double)d + TOL_M) {
        wrong(rep, k, ci, cj, "bound exceeded", worst, (double)d);
    }
    /* where level 0 covers the closed cell the importer measures it */
    if ((covered || ((g->exact_mask >> k) & 1u) != 0u) && (double)d - worst > TOL_M) {
        wrong(rep, k, ci, cj, "not exact", worst, (double)d);
    }
    rep->exact += covered ? 1u : 0u;
    rep->max_measured_m = worst > rep->max_measured_m ? worst : rep->max_measured_m;
    rep->max_stored_m = (double)d > rep->max_stored_m ? (double)d : rep->max_stored_m;
    rep->max_slack_m = (double)d - worst > rep->max_slack_m ? (double)d - worst : rep->max_slack_m;
    if (d > 0.0f) {
        rep->ratio_sum += worst / (double)d;
        rep->ratio_n++;
    }
}

static void check_db(const char *path, const region *g)
{
    const char *name = g->name;
    ft_file f;
    memset(&f, 0, sizeof f);
    f.fd = -1;
    ft_error err;
    REQUIRE(ft_plat_file_open_read(&f, path, &err) == FT_OK);
    ft_tdb db;
    REQUIRE(ft_tdb_open(&db, &f.reader_at, g_entries, ENTRIES_CAP, &err) == FT_OK);
    const uint32_t T = db.hdr.tile_samples;
    REQUIRE(T <= TILE_MAX);
    REQUIRE(ft_tdb_tile_cache_bytes(&db.hdr, CACHE_SLOTS, 0) <= sizeof g_cache_mem);
    ft_tdb_tile_cache tc;
    ft_tdb_tile_cache_init(&tc, &db.hdr, CACHE_SLOTS, 0, g_cache_mem);
    REQUIRE((size_t)g->w * g->h <= REGION_MAX);
    uint64_t ny0 = 0u;
    ft_tdb_lattice_samples(db.hdr.samples_per_deg, 0u, &g_nx0, &ny0);
    g_per_deg = db.hdr.samples_per_deg;
    read_rule(&db, &tc, 0u, g->i0, g->j0, g->w, g->h, g_truth);
    read_fine(&db, g);
    uint64_t bound_all = 0u;
    for (uint32_t k = 1u; k < db.hdr.level_count; ++k) {
        const int64_t s = (int64_t)1 << k;
        /* cells whose closed extent lies inside the region */
        const int64_t ci0 = (g->i0 + s - 1) / s, cj0 = (g->j0 + s - 1) / s;
        const int64_t ci1 = (g->i0 + g->w - 1) / s - 1, cj1 = (g->j0 + g->h - 1) / s - 1;
        if (ci1 < ci0 || cj1 < cj0) {
            break;
        }
        const uint32_t lw = (uint32_t)(ci1 - ci0 + 2), lh = (uint32_t)(cj1 - cj0 + 2);
        read_rule(&db, &tc, k, ci0, cj0, lw, lh, g_level);
        level_report rep;
        memset(&rep, 0, sizeof rep);
        uint64_t no_tile = 0u, nxk = 0u, nyk = 0u;
        ft_tdb_lattice_samples(db.hdr.samples_per_deg, k, &nxk, &nyk);
        /* on a level that closes, the cells east of 180 deg are those from
         * 0 deg on: two runs of stored columns, each with its offset */
        const int closes = ft_tdb_lattice_closes(g_per_deg, k);
        const int64_t last = closes ? (int64_t)nxk - 1 : ci1; /* a level that does not
                                                                 * close stores its own */
        const int64_t run[2][3] = {
            {ci0, ci1 < last ? ci1 : last, 0},
            {(ci0 > (int64_t)nxk ? ci0 : (int64_t)nxk) - (int64_t)nxk,
             closes ? ci1 - (int64_t)nxk : -1, (int64_t)nxk}};
        for (int q = 0; q < 2; ++q) {
            const int64_t a0 = run[q][0], a1 = run[q][1], add = run[q][2];
            for (int64_t ty = cj0 / T; a0 <= a1 && ty <= cj1 / T; ++ty) {
                for (int64_t tx = a0 / T; tx <= a1 / T; ++tx) {
                    ft_tdb_tile t;
                    REQUIRE(ft_tdb_read_tile_dev(&db, k, (uint32_t)tx, (uint32_t)ty, g_tile_h,
                                                 TILE_MAX * TILE_MAX, g_tile_bits,
                                                 sizeof g_tile_bits, g_tile_dev,
                                                 TILE_MAX * TILE_MAX, &t, &err) == FT_OK);
                    for (uint32_t c = 0u; c < T * T; ++c) {
                        const int64_t wi = tx * T + c % T, cj = ty * T + c / T;
                        if (wi < a0 || wi > a1 || cj < cj0 || cj > cj1) {
                            continue;
                        }
                        if (t.state != FT_TDB_DATA) {
                            ++no_tile;
                            continue;
                        }
                        check_cell(g, k, wi + add, cj, ci0, cj0, lw, g_tile_dev[c],
                                   t.entry.avg_m, &rep);
                    }
                }
            }
        }
        const uint64_t cells = rep.bound + rep.edge + rep.coarser + rep.none;
        printf("%s level %u: %llu cells: %llu bound (%llu covered by level 0, exact; measured "
               "max %.2f m, stored max %.2f m, "
               "mean measured/stored %.3f, largest slack %.2f m), %llu at a data edge, "
               "%llu coarser, %llu none, %llu in no-data tiles; %llu wrong\n",
               name, k, (unsigned long long)cells, (unsigned long long)rep.bound,
               (unsigned long long)rep.exact, rep.max_measured_m, rep.max_stored_m,
               rep.ratio_n > 0u ? rep.ratio_sum / (double)rep.ratio_n : 1.0, rep.max_slack_m,
               (unsigned long long)rep.edge, (unsigned long long)rep.coarser,
               (unsigned long long)rep.none, (unsigned long long)no_tile,
               (unsigned long long)rep.wrong);
        CHECK(rep.wrong == 0u);
        bound_all += rep.bound;
    }
    CHECK(bound_all > 100u);
    ft_plat_file_close(&f);
}

int main(void)
{
    FILE *probe = fopen(FT_SHARED_DATA_DIR "/N41E001.hgt", "rb");
    if (probe == NULL) {
        printf("%s missing: skipped\n", FT_SHARED_DATA_DIR "/N41E001.hgt");
        return FT_TEST_SKIP;
    }
    fclose(probe);
    const char *mosaic = FT_TEST_OUT_DIR "/dev_mosaic.ftd";
    {
        char *argv[] = {(char *)"import", (char *)"--database", (char *)mosaic,
                        (char *)"--tile", (char *)"64",
                        (char *)FT_SHARED_DATA_DIR "/N41E001.hgt",
                        (char *)FT_SHARED_DATA_DIR "/N42E001.hgt"};
        REQUIRE(ft_cmd_import_db(7, argv) == 0);
    }
    /* the mosaic (lon 1..2, lat 41..43) and 100 samples past it all round */
    const region m = {"mosaic", (1 + 180) * 1200 - 100, (41 + 90) * 1200 - 100, 1201u + 200u,
                      2401u + 200u, 0u, 1u << 1};
    check_db(mosaic, &m);

    const char *etopo = "/usr/share/ferret-vis/data/etopo5.cdf";
    probe = fopen(etopo, "rb");
    if (probe == NULL) {
        printf("%s missing (package ferret-datasets): skipped the mixed part\n", etopo);
        return ft_test_result("test_tdb_dev");
    }
    fclose(probe);
    const char *mixed = FT_TEST_OUT_DIR "/dev_mixed.ftd";
    {
        char *argv[] = {(char *)"import", (char *)"--database", (char *)mixed,
                        (char *)"--assume-wgs84", (char *)FT_SHARED_DATA_DIR "/N42E001.hgt",
                        (char *)etopo};
        REQUIRE(ft_cmd_import_db(6, argv) == 0);
    }
    /* N42E001 and 256 samples (two level-7 cells) of ETOPO5 past it */
    const region x = {"mixed", (1 + 180) * 1200 - 256, (42 + 90) * 1200 - 256, 1201u + 512u,
                      1201u + 512u, 7u, 1u << 1};
    check_db(mixed, &x);
    /* ETOPO5 alone across the antimeridian (level 0 column 432000 is 180
     * deg): the truth is level 7's surface, so level 8 is exact; the cells
     * whose east corner is at 180 deg read it as column 0 */
    const region am = {"antimeridian", 432000 - 1024, (0 + 90) * 1200 - 512, 2048u, 1024u, 7u,
                       1u << 8};
    check_db(mixed, &am);
    return ft_test_result("test_tdb_dev");
}
