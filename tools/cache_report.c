/* cache_report.c - `fixterrain-tools cache-report`: what the clipmap cache
 * (src/terrain/clip_cache.h) reads from a terrain database on a straight
 * flight at several speeds, with the updates run only in a fixed share of
 * each frame (the frame's spare time), as the runtime runs them.
 *
 * Per speed, one line: samples and bytes read per frame (mean, max), the
 * read time per frame (median, max; CPU: pread, crc and checks, the coarser
 * fallback), the frames that ended with a level behind, the frames whose
 * finest current level was not level 0 (a method draws those from coarser
 * data), and the most samples outstanding. Before the flight the cache is
 * filled whole (reported once). The GPU side (sub-image uploads of the same
 * samples) is the method's and is not timed here. Timing is a ratio from
 * one run on one machine, not a pass/fail figure. */
#define _ISOC11_SOURCE
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cache_report.h"
#include "core/platform_api.h"
#include "core/units.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "terrain/terrain_db.h"

#define SPEEDS_MAX 8
#define FRAMES_MAX 200000u
#define ENTRIES_MAX (1u << 20)

static ft_tdb_entry g_entries[ENTRIES_MAX];
static uint64_t g_frame_ns[FRAMES_MAX];

typedef struct report_args {
    const char *db_path;
    uint32_t side, levels, update_samples, base_level, tile_slots;
    double from_lat, from_lon, to_lat, to_lon;
    double speeds[SPEEDS_MAX];
    int speed_count;
    double hz, spare_ms;
} report_args;

static void usage(void)
{
    fprintf(stderr,
            "usage: fixterrain-tools cache-report DB.ftd [--side N] [--levels L]\n"
            "         [--update-samples U] [--tile-slots S] [--level K] [--from LAT,LON]\n"
            "         [--to LAT,LON] [--speeds V1,V2,..] [--hz HZ] [--spare-ms MS]\n"
            "  defaults: side 256, levels 8, update samples 8192, 16 tile slots, level 0,\n"
            "  from 41.2,1.2 to 43.0,3.0 (across N41E001/N42E001 onto ETOPO5), speeds\n"
            "  100,250,600 m/s, 60 Hz, 4 ms of each frame for the cache\n");
}

static int parse_pair(const char *s, double *a, double *b)
{
    char *end = NULL;
    *a = strtod(s, &end);
    if (end == s || *end != ',') {
        return 0;
    }
    const char *t = end + 1;
    *b = strtod(t, &end);
    return end != t && *end == '\0' && isfinite(*a) && isfinite(*b);
}

static int parse_u32(const char *s, uint32_t *out)
{
    char *end = NULL;
    const unsigned long v = strtoul(s, &end, 10);
    if (end == s || *end != '\0' || v > 0xffffffffUL) {
        return 0;
    }
    *out = (uint32_t)v;
    return 1;
}

static int parse_args(int argc, char **argv, report_args *a)
{
    memset(a, 0, sizeof *a);
    a->side = 256u;
    a->levels = 8u;
    a->update_samples = 8192u;
    a->tile_slots = 16u;
    a->from_lat = 41.2;
    a->from_lon = 1.2;
    a->to_lat = 43.0;
    a->to_lon = 3.0;
    a->speeds[0] = 100.0;
    a->speeds[1] = 250.0;
    a->speeds[2] = 600.0;
    a->speed_count = 3;
    a->hz = 60.0;
    a->spare_ms = 4.0;
    for (int i = 1; i < argc; ++i) {
        const char *k = argv[i], *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        int ok = v != NULL;
        if (k[0] != '-') {
            a->db_path = k;
            continue;
        }
        if (strcmp(k, "--side") == 0) {
            ok = ok && parse_u32(v, &a->side);
        } else if (strcmp(k, "--levels") == 0) {
            ok = ok && parse_u32(v, &a->levels);
        } else if (strcmp(k, "--update-samples") == 0) {
            ok = ok && parse_u32(v, &a->update_samples);
        } else if (strcmp(k, "--tile-slots") == 0) {
            ok = ok && parse_u32(v, &a->tile_slots);
        } else if (strcmp(k, "--level") == 0) {
            ok = ok && parse_u32(v, &a->base_level);
        } else if (strcmp(k, "--from") == 0) {
            ok = ok && parse_pair(v, &a->from_lat, &a->from_lon);
        } else if (strcmp(k, "--to") == 0) {
            ok = ok && parse_pair(v, &a->to_lat, &a->to_lon);
        } else if (strcmp(k, "--hz") == 0) {
            a->hz = ok ? strtod(v, NULL) : 0.0;
            ok = ok && a->hz >= 1.0 && a->hz <= 1000.0;
        } else if (strcmp(k, "--spare-ms") == 0) {
            a->spare_ms = ok ? strtod(v, NULL) : -1.0;
            ok = ok && a->spare_ms > 0.0 && a->spare_ms <= 1000.0;
        } else if (strcmp(k, "--speeds") == 0 && ok) {
            a->speed_count = 0;
            const char *p = v;
            while (ok && *p != '\0' && a->speed_count < SPEEDS_MAX) {
                char *end = NULL;
                const double s = strtod(p, &end);
                ok = end != p && s > 0.0 && s <= 10000.0 && (*end == ',' || *end == '\0');
                a->speeds[a->speed_count++] = s;
                p = (*end == ',') ? end + 1 : end;
            }
            ok = ok && *p == '\0';
        } else {
            fprintf(stderr, "cache-report: unknown option %s\n", k);
            return 0;
        }
        if (!ok) {
            fprintf(stderr, "cache-report: bad value for %s\n", k);
            return 0;
        }
        ++i;
    }
    if (a->db_path == NULL) {
        fprintf(stderr, "cache-report: no database given\n");
        return 0;
    }
    return 1;
}

/* The plan checks the description only; it reads nothing. */
static ft_status no_read(void *ctx, uint32_t level, int64_t i0, int64_t j0, uint32_t w,
                         uint32_t h, float *heights_m, uint8_t *marks, float *dev_m,
                         ft_error *err)
{
    (void)ctx, (void)level, (void)i0, (void)j0, (void)w, (void)h, (void)heights_m, (void)marks;
    (void)dev_m;
    return ft_fail(err, FT_ERR_ARG, "cache-report: no source yet");
}

static int cmp_u64(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

/* Level-0 lattice position (base level) of a point, fractional. */
static void lattice_of(const ft_tdb *db, uint32_t base, double lat, double lon, double *i,
                       double *j)
{
    const double per_deg = (double)db->hdr.samples_per_deg / ldexp(1.0, (int)base);
    *i = (lon + 180.0) * per_deg;
    *j = (lat + 90.0) * per_deg;
}

typedef struct run_stats {
    uint64_t frames, samples, samples_max, behind_frames, coarser_frames, outstanding_max;
    uint64_t ns_max, ns_sum;
    double ns_median;
} run_stats;

static ft_status one_speed(const report_args *a, const ft_tdb *db, double speed_mps,
                           ft_arena *arena, void *mem, size_t mem_bytes, run_stats *rs,
                           uint64_t *fill_ns, uint64_t *fill_samples, ft_error *err)
{
    memset(rs, 0, sizeof *rs);
    memset(arena, 0, sizeof *arena);
    arena->pools[FT_POOL_CLIP].budget_bytes = mem_bytes;
    ft_status st = ft_arena_bind(arena, mem, mem_bytes, err);
    const ft_clip_desc d = {a->side, a->levels, a->update_samples, 0};
    ft_clip_db_source dbs;
    ft_clip_source src;
    ft_clip_cache c;
    if (st == FT_OK) {
        st = ft_clip_source_db(&src, &dbs, db, a->base_level, 0, 0, db->hdr.min_height_m,
                               a->tile_slots, &d, arena, err);
    }
    if (st == FT_OK) {
        st = ft_clip_init(&c, &d, &src, arena, err);
    }
    if (st != FT_OK) {
        return st;
    }
    const double deg_m = FT_EARTH_RADIUS_M * FT_RAD_PER_DEG;
    const double mid_lat = 0.5 * (a->from_lat + a->to_lat) * FT_RAD_PER_DEG;
    const double dy = (a->to_lat - a->from_lat) * deg_m;
    const double dx = (a->to_lon - a->from_lon) * deg_m * cos(mid_lat);
    const double length_m = sqrt(dx * dx + dy * dy);
    double ei = 0.0, ej = 0.0;
    lattice_of(db, a->base_level, a->from_lat, a->from_lon, &ei, &ej);
    ft_clip_recentre(&c, ei, ej);
    const uint64_t t0 = ft_plat_monotonic_ns();
    for (uint32_t k = 0u; k < 1000000u; ++k) {
        ft_clip_update u;
        int have = 0;
        st = ft_clip_next_update(&c, &u, &have, err);
        if (st != FT_OK) {
            return st;
        }
        if (!have) {
            break;
        }
        ft_clip_commit(&c, &u);
    }
    *fill_ns = ft_plat_monotonic_ns() - t0;
    *fill_samples = c.stats.samples_uploaded;
    const uint64_t frames64 = (uint64_t)ceil(length_m / speed_mps * a->hz);
    const uint32_t frames = frames64 < FRAMES_MAX ? (uint32_t)frames64 : FRAMES_MAX;
    const uint64_t spare_ns = (uint64_t)(a->spare_ms * 1e6);
    for (uint32_t f = 1u; f <= frames; ++f) {
        const double s = (double)f / (double)frames;
        lattice_of(db, a->base_level, a->from_lat + s * (a->to_lat - a->from_lat),
                   a->from_lon + s * (a->to_lon - a->from_lon), &ei, &ej);
        ft_clip_recentre(&c, ei, ej);
        const uint64_t before = c.stats.samples_uploaded;
        const uint64_t f0 = ft_plat_monotonic_ns();
        /* updates while the frame's spare time lasts (the first always runs:
         * a job queue that starts nothing never catches up) */
        for (uint32_t k = 0u; k < 4096u; ++k) {
            ft_clip_update u;
            int have = 0;
            st = ft_clip_next_update(&c, &u, &have, err);
            if (st != FT_OK) {
                return st;
            }
            if (!have) {
                break;
            }
            ft_clip_commit(&c, &u);
            if (ft_plat_monotonic_ns() - f0 >= spare_ns) {
                break;
            }
        }
        const uint64_t ns = ft_plat_monotonic_ns() - f0;
        const uint64_t n = c.stats.samples_uploaded - before;
        g_frame_ns[f - 1u] = ns;
        rs->samples += n;
        rs->samples_max = n > rs->samples_max ? n : rs->samples_max;
        rs->ns_max = ns > rs->ns_max ? ns : rs->ns_max;
        rs->ns_sum += ns;
        rs->behind_frames += c.stats.levels_behind > 0u;
        rs->coarser_frames += ft_clip_finest_current(&c) > 0u;
        rs->outstanding_max = c.stats.samples_outstanding > rs->outstanding_max
                                  ? c.stats.samples_outstanding
                                  : rs->outstanding_max;
    }
    rs->frames = frames;
    qsort(g_frame_ns, frames, sizeof g_frame_ns[0], cmp_u64);
    rs->ns_median = frames > 0u ? (double)g_frame_ns[frames / 2u] : 0.0;
    const double nf = (double)(frames ? frames : 1u);
    printf("%8.0f  %6.1f  %7u  %9.0f  %8llu  %9.4f  %8.3f  %8.3f  %9llu  %9llu  %10llu  "
           "%llu/%llu\n",
           speed_mps, length_m / 1000.0, frames, (double)rs->samples / nf,
           (unsigned long long)rs->samples_max, (double)rs->ns_sum / nf * 1e-6,
           rs->ns_median * 1e-6, (double)rs->ns_max * 1e-6,
           (unsigned long long)rs->behind_frames, (unsigned long long)rs->coarser_frames,
           (unsigned long long)rs->outstanding_max, (unsigned long long)dbs.tiles.reads,
           (unsigned long long)(dbs.tiles.reads + dbs.tiles.hits));
    return FT_OK;
}

int ft_cmd_cache_report(int argc, char **argv)
{
    report_args a;
    if (!parse_args(argc, argv, &a)) {
        usage();
        return 2;
    }
    ft_file f;
    memset(&f, 0, sizeof f);
    f.fd = -1;
    ft_error err;
    ft_tdb db;
    ft_status st = ft_plat_file_open_read(&f, a.db_path, &err);
    if (st == FT_OK) {
        st = ft_tdb_open(&db, &f.reader_at, g_entries, ENTRIES_MAX, &err);
    }
    const ft_clip_desc d = {a.side, a.levels, a.update_samples, 0};
    ft_clip_source probe_src = {no_read, NULL, 0u, 0, 0, 0, 0, 0, 0};
    if (st == FT_OK && a.base_level >= db.hdr.level_count) {
        st = ft_fail(&err, FT_ERR_CONFIG, "--level %u: %s has levels 0..%u", a.base_level,
                     a.db_path, db.hdr.level_count - 1u);
    }
    if (st == FT_OK) {
        probe_src.levels = db.hdr.level_count - a.base_level;
        st = ft_clip_plan(&d, &probe_src, NULL, &err);
    }
    if (st != FT_OK) {
        fprintf(stderr, "cache-report: %s\n", err.text);
        ft_plat_file_close(&f);
        return st == FT_ERR_CONFIG ? 2 : 1;
    }
    /* the source's tiles, grid and bits, the cache's heights and marks */
    const size_t mem_bytes =
        ft_clip_db_source_bytes(&db.hdr, a.tile_slots, &d) +
        ft_arena_round((size_t)a.update_samples * sizeof(float)) +
        ft_arena_round(a.update_samples);
    void *mem = aligned_alloc(FT_ARENA_ALIGN, ft_arena_round(mem_bytes));
    if (mem == NULL) {
        fprintf(stderr, "cache-report: out of memory\n");
        ft_plat_file_close(&f);
        return 1;
    }
    const double gpu_mb = (double)a.side * a.side * a.levels * 4.0 / 1048576.0;
    printf("database %s: %.1f MB, %u levels, tile %u; cache %u levels of %u^2 samples from level "
           "%u: %.1f MB as float32 textures (%.1f bytes per resident sample); %.1f ms of %.1f "
           "Hz frames for the cache\n",
           a.db_path, (double)db.hdr.file_bytes / 1048576.0, db.hdr.level_count,
           db.hdr.tile_samples, a.levels, a.side, a.base_level, gpu_mb, 4.0, a.spare_ms, a.hz);
    printf("   speed  length   frames  samples/f  max/f    read mean  read p50  read max  "
           "behind_f   coarser_f  outstanding  tile reads/uses\n"
           "   (m/s)    (km)                                  (ms)       (ms)      (ms)    "
           "(frames)   (frames)   (max samples)\n");
    int rc = 0;
    for (int i = 0; i < a.speed_count && rc == 0; ++i) {
        ft_arena arena;
        run_stats rs;
        uint64_t fill_ns = 0u, fill_samples = 0u;
        st = one_speed(&a, &db, a.speeds[i], &arena, mem, mem_bytes, &rs, &fill_ns,
                       &fill_samples, &err);
        if (st != FT_OK) {
            fprintf(stderr, "cache-report: %s\n", err.text);
            rc = 1;
        } else if (i == 0) {
            printf("initial fill: %llu samples in %.1f ms\n", (unsigned long long)fill_samples,
                   (double)fill_ns * 1e-6);
        }
    }
    free(mem);
    ft_plat_file_close(&f);
    return rc;
}
