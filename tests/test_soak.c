/* test_soak.c - a long replay: 31 minutes of log time through `fixterrain
 * replay`'s own code path (ft_app_replay, src/app/replay.h) at 64x48, with
 * faults every minute, checking that nothing drifts. The scene is small on
 * purpose (a 129^2 synthetic terrain at 60 m, bintree with at most 256 tiles
 * at tau 2 px): the soak is about time, not about detail, and llvmpipe's
 * vertex stage is single-threaded (4096 tiles cost up to 40 ms a frame).
 *
 * With DB.ftd, the scene is the clipmap method over a window of that
 * database (a 1201-sample window, the cache reading the database past it),
 * so the same checks cover a cache that moves with the eye for the whole
 * replay: tests/soak.cmake runs it for 10 minutes over N42E001 on an orbit
 * of 8 km radius at 250 m/s (one revolution inside the warm-up).
 *
 * With METHOD pgm after DB.ftd, the scene is pgm reading its heights
 * through the same cache (pgm.heights = clipmap, a 64 x 128 grid).
 *
 * usage: test_soak RAW.log OUT_DIR [PERIOD_MS [MINUTES [DB.ftd [METHOD]]]]
 *   RAW.log  a fixterrain-flightgen log (tests/soak.cmake makes it: orbit,
 *            1860 s, with flightgen's own single faults: --gps-jump,
 *            --nan-at, --bad-dlc-at, --duplicate-at, --drop-every)
 *   OUT_DIR  where the faulted log is written (soak.log)
 *   MINUTES  log time required (default 30; less only to try the test out:
 *            the drift check needs >= 10)
 *
 * Faults added here, in every minute m >= 1 of log time (seconds into the
 * minute): 10 s a garbage line and a line cut in half (candump syntax errors),
 * 20 s a frame with DLC 7, 30 s a NaN pitch (311), 40..42.5 s nothing at all
 * (a dropped stretch: the attitude goes stale, the annunciation is drawn),
 * 50 s a frame sent twice, 55..56 s the latitude 500 m north (a GPS jump and
 * back: the high word of the DOUBLEH latitude raised by 150 units of
 * 2^-15 deg).
 *
 * The renderer checks glGetError after every frame (renderer.gl_error_checks
 * = 1: soak only; a GL error fails the frame and so the replay) and counts.
 * A frame observer (renderer.frame_done) samples, per minute of log time,
 * the deadline misses so far (frames over frame.budget_ms, counted by the
 * replay) and, after every frame, the bytes the process holds from the
 * C heap and its RSS (their lowest and highest value per minute), and the
 * arena's high water at the end of the warm-up (minute 5) and at the end.
 * Required:
 *   - the replay completes, >= 30 minutes of log time rendered, 0 GL errors;
 *   - every injected fault was seen (bad lines, decoder rejects,
 *     annunciated frames);
 *   - no leak: the heap bytes in use, at their lowest in the last
 *     HEAP_WINDOW_MIN whole minutes, <= their lowest in the warm-up's last
 *     HEAP_WINDOW_MIN minutes + HEAP_MARGIN_KIB (a block that is never freed
 *     raises every later value; the driver's per-frame blocks come and go
 *     and do not, but how low a minute gets depends on its views: a
 *     minute's lowest value moves by up to 640 KiB on the clipmap orbit,
 *     measured, so the windows hold a whole revolution of it);
 *   - flat RSS: at its lowest in the last whole minute <= its highest in
 *     minutes 0-5 + RSS_MARGIN_KIB. RSS is judged per minute, not by single
 *     samples: the driver holds a transient 1 MiB block over a frame
 *     boundary every few seconds (measured: one frame in 73 on the clipmap
 *     orbit), a single sample that lands on one measures that block, and an
 *     odd frame's larger transient (minute 11 of the bintree orbit, 1 MiB)
 *     raises a minute's highest value once. Over a database (the heap kept
 *     untrimmed, below) RSS is the heap's high water, and llvmpipe's
 *     binning memory depends on how many scenes are in flight, which
 *     depends on the load on the machine: beside another soak on 2 cores
 *     the pgm soak's RSS rose by 4 x 1028 KiB in minutes 3-6 with the heap
 *     in use flat (25,418 -> 25,419 KiB, measured on a fresh Debian 12
 *     run), alone it stays within 1 MiB; so those soaks allow
 *     RSS_MARGIN_DB_KIB, and the heap check above is their leak test;
 *   - arena high water unchanged after warm-up (and the arena stays locked);
 *   - deadline misses in the last 5 minutes <= those in the first 5 minutes +
 *     MISS_MARGIN (the first 5 include shader JIT and cache warm-up). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <malloc.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include "app/app.h"
#include "app/replay.h"
#include "test_app_util.h"

#define MINUTES_MAX 64u
#define WARMUP_MIN 5u
#define WINDOW_MIN 5u
#define RSS_MARGIN_KIB 1024u
#define RSS_MARGIN_DB_KIB 6144u
#define HEAP_MARGIN_KIB 256u
#define HEAP_WINDOW_MIN 4u
/* misses: 1% of a 5-minute window's frames, at least 10 (the machine is
 * shared: a busy neighbour can cost a few frames in any window) */
#define MISS_MARGIN_FRACTION 0.01
#define MISS_MARGIN_MIN 10u

static const char k_scene_fmt[] =
    "[scene]\nname = soak\nmethod = bintree\nbackend = egl-gles3\n"
    "[view]\nwidth_px = 64\nheight_px = 48\nfovy_deg = 60\n"
    "[terrain]\ndem =\nsynth_side = 129\nsynth_spacing_m = 60\nsynth_relief_m = 2000\n"
    "synth_seed = 3\nsynth_octaves = 8\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[gpu]\ntexture_bytes = 16M\n[metric]\nenabled = 0\n"
    "[bintree]\ntemplate_k = 3\ntiles_max = 256\ntau_px = 2.0\nmorph = 1\n"
    "[frame]\nperiod_ms = %g\nbudget_ms = %g\ndegrade = 0\n";

static const char k_scene_db_fmt[] =
    "[scene]\nname = soak-cache\nmethod = %s\nbackend = egl-gles3\n"
    "[view]\nwidth_px = 64\nheight_px = 48\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\ndb_level = 0\ndb_side_samples = 1201\n"
    "db_centre_lat_deg = 42.5\ndb_centre_lon_deg = 1.5\n"
    "[gpu]\ntexture_bytes = 16M\n[metric]\nenabled = 0\n"
    "[clipmap]\nside = 64\nlevels = 5\nupdate_samples_max = 1024\nupdates_per_frame = 4\n"
    "tile_slots = 8\n"
    "[pgm]\ngrid_cols = 64\ngrid_rows = 128\nheights = clipmap\n"
    "[budget]\nclip_bytes = 6M\n"
    "[frame]\nperiod_ms = %g\nbudget_ms = %g\ndegrade = 0\n";

/* ---- the faulted log -------------------------------------------------------- */

typedef struct fault_counts {
    unsigned garbage, cut, dlc7, nan, dropped_lines, duplicated, gps;
} fault_counts;

/* Hex digit value, or -1. */
static int hexval(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

static void write_faulted(const char *raw, const char *out, fault_counts *fc, double *log_s)
{
    FILE *in = fopen(raw, "r");
    if (in == NULL) fprintf(stderr, "cannot open %s\n", raw);
    REQUIRE(in != NULL);
    FILE *o = fopen(out, "w");
    REQUIRE(o != NULL);
    memset(fc, 0, sizeof *fc);
    static char line[512];
    double t0 = -1.0, t = 0.0;
    /* per minute: which faults were done (bit per fault) */
    static unsigned done[MINUTES_MAX + 8u];
    memset(done, 0, sizeof done);
    while (fgets(line, sizeof line, in) != NULL) {
        size_t n = strlen(line);
        while (n > 0u && (line[n - 1u] == '\n' || line[n - 1u] == '\r')) line[--n] = '\0';
        if (n < 3u || line[0] != '(') {
            fprintf(o, "%s\n", line);
            continue;
        }
        t = strtod(line + 1, NULL);
        if (t0 < 0.0) t0 = t;
        const double rel = t - t0;
        const unsigned m = (unsigned)(rel / 60.0);
        const double sec = rel - 60.0 * m;
        char *hash = strchr(line, '#');
        char *id = hash ? hash : NULL;
        while (id != NULL && id > line && id[-1] != ' ') --id;
        const size_t id_len = (hash && id) ? (size_t)(hash - id) : 0u;
        const char *pay = hash ? hash + 1 : NULL;
        const size_t pay_len = pay ? strlen(pay) : 0u;
        if (m >= 1u && m < MINUTES_MAX && pay_len == 16u) {
            unsigned *d = &done[m];
            if (sec >= 10.0 && !(*d & 1u)) {
                *d |= 1u;
                fprintf(o, "(%.6f) vcan0 137#ZZ\n", t);
                fprintf(o, "%.*s\n", (int)(n / 2u), line);
                fc->garbage += 1u;
                fc->cut += 1u;
            }
            if (sec >= 20.0 && !(*d & 2u)) {
                *d |= 2u;
                fprintf(o, "%.*s\n", (int)(n - 2u), line); /* 7 data bytes */
                fc->dlc7 += 1u;
                continue;
            }
            if (sec >= 30.0 && !(*d & 4u) && id_len == 3u && strncmp(id, "137", 3) == 0) {
                *d |= 4u;
                memcpy(hash + 1 + 8, "7FC00000", 8); /* a quiet NaN pitch */
                fc->nan += 1u;
            }
            if (sec >= 40.0 && sec < 42.5) {
                fc->dropped_lines += 1u;
                continue;
            }
            if (sec >= 50.0 && !(*d & 8u)) {
                *d |= 8u;
                fprintf(o, "%s\n", line);
                fc->duplicated += 1u;
            }
            if (sec >= 55.0 && sec < 56.0 && id_len == 3u && strncmp(id, "40C", 3) == 0 &&
                pay[2] == '1' && pay[3] == 'E') {
                /* DOUBLEH latitude: bytes 4..7 big endian = the double's high word */
                unsigned long hi = 0;
                int ok = 1;
                for (int i = 0; i < 8; ++i) {
                    int v = hexval(pay[8 + i]);
                    ok &= v >= 0;
                    hi = (hi << 4) | (unsigned long)(v < 0 ? 0 : v);
                }
                if (ok) {
                    char hex[9];
                    (void)snprintf(hex, sizeof hex, "%08lX", (hi + 150ul) & 0xFFFFFFFFul);
                    memcpy(hash + 1 + 8, hex, 8);
                    fc->gps += 1u;
                }
            }
        }
        fprintf(o, "%s\n", line);
    }
    REQUIRE(fclose(in) == 0);
    REQUIRE(fclose(o) == 0);
    *log_s = t - t0;
}

/* ---- the observer ----------------------------------------------------------- */

typedef struct soak_state {
    const ft_replay_result *res; /* the replay's live result */
    const ft_app *app;
    double period_ms;
    uint32_t minutes_seen;
    uint32_t misses_at[MINUTES_MAX + 1u]; /* over_budget before minute m's first frame */
    uint64_t wall_at_ns[MINUTES_MAX + 1u]; /* monotonic time at minute m's first frame */
    long rss_lo_kib[MINUTES_MAX + 1u];     /* lowest RSS after a frame of minute m */
    long rss_hi_kib[MINUTES_MAX + 1u];     /* highest RSS after a frame of minute m */
    long heap_lo_kib[MINUTES_MAX + 1u];    /* lowest heap bytes in use, the same */
    long heap_hi_kib[MINUTES_MAX + 1u];
    int statm_fd;                          /* /proc/self/statm, kept open */
    uint32_t rss_read_failures;
    size_t hw_warm, hw_end;
    uint64_t gl_error_checks_seen;
    uint64_t frames_seen;
} soak_state;

/* RSS from a kept descriptor: read after every frame, so reading it must
 * not allocate (fopen would) and so move what it measures */
static long rss_kib(int statm_fd)
{
    char text[128];
    const ssize_t n = pread(statm_fd, text, sizeof text - 1u, 0);
    if (n <= 0) return -1;
    text[n] = '\0';
    long pages_total = 0, pages_rss = 0;
    if (sscanf(text, "%ld %ld", &pages_total, &pages_rss) != 2 || pages_rss <= 0) return -1;
    return pages_rss * (sysconf(_SC_PAGESIZE) / 1024);
}

/* The C heap's bytes in use: the sanitizer's allocator when there is one
 * (its mallinfo is empty), else glibc's over all its arenas (the driver's
 * threads allocate in their own). Neither walk allocates. */
#if defined(__SANITIZE_ADDRESS__)
#define SOAK_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOAK_ASAN 1
#endif
#endif
#ifdef SOAK_ASAN
size_t __sanitizer_get_current_allocated_bytes(void);
static long heap_in_use_kib(void)
{
    return (long)(__sanitizer_get_current_allocated_bytes() / 1024u);
}
#else
static long heap_in_use_kib(void)
{
    const struct mallinfo2 mi = mallinfo2();
    return (long)((mi.uordblks + mi.hblkhd) / 1024u);
}
#endif

static void minmax_kib(long v, long *lo, long *hi)
{
    if (*lo < 0 || v < *lo) *lo = v;
    if (v > *hi) *hi = v;
}

static size_t arena_high_water(const ft_app *app)
{
    size_t sum = 0;
    for (unsigned p = 0; p < FT_POOL_COUNT; ++p) sum += app->arena.pools[p].high_water_bytes;
    return sum;
}

static void on_frame(void *ctx, const ft_renderer *r)
{
    soak_state *s = ctx;
    const uint64_t k = s->frames_seen++; /* this frame's index in the replay */
    const uint32_t m = (uint32_t)((double)k * s->period_ms / 60000.0);
    while (s->minutes_seen <= m && s->minutes_seen <= MINUTES_MAX) {
        s->misses_at[s->minutes_seen] = s->res->frame.degrade.over_budget;
        s->wall_at_ns[s->minutes_seen] = ft_plat_monotonic_ns();
        s->rss_lo_kib[s->minutes_seen] = -1;
        s->rss_hi_kib[s->minutes_seen] = -1;
        s->heap_lo_kib[s->minutes_seen] = -1;
        s->heap_hi_kib[s->minutes_seen] = -1;
        if (s->minutes_seen == WARMUP_MIN) s->hw_warm = arena_high_water(s->app);
        s->minutes_seen += 1u;
    }
    if (m <= MINUTES_MAX) {
        const long rss = rss_kib(s->statm_fd);
        if (rss < 0) {
            s->rss_read_failures += 1u;
        } else {
            minmax_kib(rss, &s->rss_lo_kib[m], &s->rss_hi_kib[m]);
        }
        minmax_kib(heap_in_use_kib(), &s->heap_lo_kib[m], &s->heap_hi_kib[m]);
    }
    s->gl_error_checks_seen += (uint64_t)(r->gl_error_checks != 0);
}

static ft_app g_app;
static ft_pose_feed g_feed;
static ft_replay_io g_replay_io; /* the replay's files and line reader */
static ft_replay_result g_res;
static soak_state g_soak;

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_soak RAW.log OUT_DIR [PERIOD_MS [MINUTES [DB.ftd [METHOD]]]]\n");
        return 2;
    }
    const double period_ms = argc >= 4 ? atof(argv[3]) : 50.0;
    const double minutes = argc >= 5 ? atof(argv[4]) : 30.0;
    REQUIRE(period_ms >= 10.0 && period_ms <= 1000.0);
    REQUIRE(minutes >= 0.0 && minutes <= 60.0);
    char log[FT_PATH_MAX];
    (void)snprintf(log, sizeof log, "%s/soak.log", argv[2]);
    fault_counts fc;
    double log_s = 0.0;
    write_faulted(argv[1], log, &fc, &log_s);
    printf("log: %.1f s; faults: %u garbage + %u cut lines, %u DLC 7, %u NaN, %u lines dropped, "
           "%u duplicated, %u GPS-jumped latitudes\n",
           log_s, fc.garbage, fc.cut, fc.dlc7, fc.nan, fc.dropped_lines, fc.duplicated, fc.gps);
    REQUIRE(log_s >= minutes * 60.0);
    const unsigned per_min = (unsigned)minutes; /* faults in minutes 1..30 at least */
    CHECK(fc.garbage >= per_min && fc.dlc7 >= per_min && fc.nan >= per_min &&
          fc.duplicated >= per_min && fc.gps >= per_min && fc.dropped_lines > 0u);

    const char *db = argc >= 6 ? argv[5] : NULL;
    const char *method = argc >= 7 ? argv[6] : "clipmap";
    const int pgm = strcmp(method, "pgm") == 0;
    REQUIRE(pgm || strcmp(method, "clipmap") == 0);
    if (db != NULL) {
        /* The clipmap's geometry changes from frame to frame (rings, stitch
         * strips, levels behind), and the driver's (llvmpipe's) per-frame
         * binning memory follows it: with glibc's defaults the same
         * allocations land in the trimmed heap or in their own mappings from
         * one minute to the next, and RSS swings by 1-2 MiB with no growth
         * under it (measured). Keeping freed memory in
         * the heap (no trim, no per-block mapping) makes RSS the heap's high
         * water: it rises until every kind of frame has been seen (the orbit
         * is one revolution inside the warm-up) and then stays; a leak still
         * raises it. The bintree soak's frames are alike and keep the
         * defaults. (A sanitizer's allocator ignores this; its quarantine and
         * release to the OS are set by tests/soak.cmake.) */
        (void)mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
        (void)mallopt(M_TRIM_THRESHOLD, 256 * 1024 * 1024);
    }
    char scene[2048];
    if (db != NULL) {
        (void)snprintf(scene, sizeof scene, k_scene_db_fmt, method, db, period_ms, period_ms);
    } else {
        (void)snprintf(scene, sizeof scene, k_scene_fmt, period_ms, period_ms);
    }
    g_soak.statm_fd = open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
    REQUIRE(g_soak.statm_fd >= 0);
    const long rss_before_init = rss_kib(g_soak.statm_fd);
    ft_test_app_init(&g_app, scene, "soak");
    g_app.renderer.gl_error_checks = 1; /* glGetError after every frame: soak only */
    {
        /* the check can fail: a GL error before a frame fails that frame and
         * is counted */
        ft_error e;
        ft_camera cam;
        ft_frame_stats fs;
        ft_pose p = g_app.scene.pose;
        g_app.gpu.gl.Enable(0x7FFFu); /* GL_INVALID_ENUM */
        const ft_status gs = ft_app_render(&g_app, &p, &cam, &fs, &e);
        printf("an injected GL error: %s\n", gs == FT_OK ? "not seen" : e.text);
        CHECK(gs == FT_ERR_GPU && g_app.renderer.gl_errors == 1u);
        g_app.renderer.gl_errors = 0u;
    }
    g_soak.res = &g_res;
    g_soak.app = &g_app;
    g_soak.period_ms = period_ms;
    g_app.renderer.frame_done = on_frame;
    g_app.renderer.frame_done_ctx = &g_soak;

    const uint64_t t_start = ft_plat_monotonic_ns();
    ft_replay_desc d = {log, NULL, NULL, 0};
    ft_error err;
    ft_status st = ft_app_replay(&g_app, &d, &g_feed, &g_replay_io, &g_res, &err);
    const double wall_s = (double)(ft_plat_monotonic_ns() - t_start) * 1e-9;
    struct rusage ru;
    double cpu_s = -1.0;
    if (getrusage(RUSAGE_SELF, &ru) == 0) {
        cpu_s = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
                (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
    }
    if (st != FT_OK) fprintf(stderr, "replay: %s\n", err.text);
    CHECK(st == FT_OK);
    g_soak.hw_end = arena_high_water(&g_app);

    const double rendered_min = (double)g_res.frames * period_ms / 60000.0;
    printf("replay: %u frames = %.2f min of log time in %.1f s wall (%.2f ms/frame; process CPU "
           "%.1f s), "
           "%u annunciated, %llu lines, %llu bad, %llu unsupported, %llu gaps, %llu rejected "
           "by the decoder\n",
           g_res.frames, rendered_min, wall_s, wall_s * 1e3 / (g_res.frames ? g_res.frames : 1u),
           cpu_s,
           g_res.frames_annunciated, (unsigned long long)g_res.lines,
           (unsigned long long)g_res.lines_bad, (unsigned long long)g_res.lines_unsupported,
           (unsigned long long)g_res.gaps, (unsigned long long)ft_pose_feed_rejected(&g_feed));
    CHECK(rendered_min >= minutes);
    CHECK(g_res.lines_bad >= (uint64_t)fc.garbage + fc.cut);
    CHECK(ft_pose_feed_rejected(&g_feed) >= (uint64_t)fc.dlc7 + fc.nan);
    CHECK(g_res.frames_annunciated >= per_min); /* at least one per dropped stretch */
    CHECK(g_res.gaps == 0u);

    /* GL errors: checked after every frame, none */
    printf("GL: error checks on %llu of %u frames, %llu errors\n",
           (unsigned long long)g_soak.gl_error_checks_seen, g_res.frames,
           (unsigned long long)g_app.renderer.gl_errors);
    CHECK(g_soak.gl_error_checks_seen == g_res.frames);
    CHECK(g_app.renderer.gl_errors == 0u);
    CHECK(ft_gl_check(&g_app.gpu.gl, "after the soak", NULL) == FT_OK);

    /* memory: the heap in use and RSS per minute, after the warm-up against
     * the warm-up */
    const uint32_t whole = (uint32_t)floor(rendered_min); /* minutes 0..whole-1 complete */
    REQUIRE(whole > WARMUP_MIN + 1u && whole <= MINUTES_MAX);
    long rss_ceil_warm_kib = -1;
    for (uint32_t m = 0u; m <= WARMUP_MIN; ++m) {
        if (g_soak.rss_hi_kib[m] > rss_ceil_warm_kib) rss_ceil_warm_kib = g_soak.rss_hi_kib[m];
    }
    REQUIRE(whole >= WARMUP_MIN + 1u + HEAP_WINDOW_MIN);
    long heap_floor_warm_kib = -1, heap_floor_end_kib = -1, unused_kib = -1;
    for (uint32_t k = 0u; k < HEAP_WINDOW_MIN; ++k) {
        minmax_kib(g_soak.heap_lo_kib[WARMUP_MIN - k], &heap_floor_warm_kib, &unused_kib);
        minmax_kib(g_soak.heap_lo_kib[whole - 1u - k], &heap_floor_end_kib, &unused_kib);
    }
    const long rss_floor_end_kib = g_soak.rss_lo_kib[whole - 1u];
    const unsigned rss_margin_kib = (db != NULL) ? RSS_MARGIN_DB_KIB : RSS_MARGIN_KIB;
    printf("heap in use, lowest: %ld KiB in minutes %u-%u, %ld KiB in minutes %u-%u "
           "(margin %u KiB)\n",
           heap_floor_warm_kib, WARMUP_MIN + 1u - HEAP_WINDOW_MIN, WARMUP_MIN, heap_floor_end_kib,
           whole - HEAP_WINDOW_MIN, whole - 1u, HEAP_MARGIN_KIB);
    printf("RSS: %ld KiB before init, at most %ld KiB in minutes 0-%u, at least %ld KiB in "
           "minute %u (margin %u KiB); %u failed reads; arena high water %zu -> %zu bytes\n",
           rss_before_init, rss_ceil_warm_kib, WARMUP_MIN, rss_floor_end_kib, whole - 1u,
           rss_margin_kib, g_soak.rss_read_failures, g_soak.hw_warm, g_soak.hw_end);
    printf("heap in use per minute, lowest..highest (KiB):");
    for (uint32_t m = 0u; m < whole; ++m) {
        printf(" %ld..%ld", g_soak.heap_lo_kib[m], g_soak.heap_hi_kib[m]);
    }
    printf("\nRSS per minute, lowest..highest (KiB):");
    for (uint32_t m = 0u; m < whole; ++m) {
        printf(" %ld..%ld", g_soak.rss_lo_kib[m], g_soak.rss_hi_kib[m]);
    }
    printf("\n");
    CHECK(g_soak.rss_read_failures == 0u);
    CHECK(heap_floor_warm_kib > 0 && heap_floor_end_kib > 0);
    CHECK(heap_floor_end_kib <= heap_floor_warm_kib + (long)HEAP_MARGIN_KIB);
    CHECK(rss_ceil_warm_kib > 0 && rss_floor_end_kib > 0);
    CHECK(rss_floor_end_kib <= rss_ceil_warm_kib + (long)rss_margin_kib);
    CHECK(g_soak.hw_end == g_soak.hw_warm);
    CHECK(g_app.arena.locked);

    /* deadline misses: the last 5 minutes against the first 5 */
    const uint32_t full = (uint32_t)floor(rendered_min); /* whole minutes rendered */
    REQUIRE(full >= 2u * WINDOW_MIN && full <= MINUTES_MAX);
    const uint32_t first = g_soak.misses_at[WINDOW_MIN] - g_soak.misses_at[0];
    const uint32_t last = g_soak.misses_at[full] - g_soak.misses_at[full - WINDOW_MIN];
    const double window_frames = WINDOW_MIN * 60000.0 / period_ms;
    uint32_t margin = (uint32_t)(MISS_MARGIN_FRACTION * window_frames);
    if (margin < MISS_MARGIN_MIN) margin = MISS_MARGIN_MIN;
    printf("deadline misses (budget %g ms): %u in minutes 0-%u, %u in minutes %u-%u (margin %u), "
           "%u in all; slowest frame %.2f ms\n",
           period_ms, first, WINDOW_MIN, last, full - WINDOW_MIN, full, margin,
           g_res.frame.degrade.over_budget, g_res.frame.timing.render_ms_max);
    CHECK(last <= first + margin);
    /* information: wall time per frame (replay work included) in the two
     * windows; not judged, the machine is shared */
    const double ms_first =
        (double)(g_soak.wall_at_ns[WINDOW_MIN] - g_soak.wall_at_ns[0]) * 1e-6 / window_frames;
    const double ms_last = (double)(g_soak.wall_at_ns[full] - g_soak.wall_at_ns[full - WINDOW_MIN]) *
                           1e-6 / window_frames;
    printf("wall per frame: %.3f ms in minutes 0-%u, %.3f ms in minutes %u-%u\n", ms_first,
           WINDOW_MIN, ms_last, full - WINDOW_MIN, full);

    if (db != NULL) {
        const ft_method *m = &g_app.renderer.method;
        const ft_clip_stats *cs = pgm ? &m->u.pgm.cl.cache.stats : &m->u.clipmap.cl.cache.stats;
        printf("%s's clipmap cache: %llu updates, %llu samples uploaded, at most %u levels behind\n",
               method, (unsigned long long)cs->updates, (unsigned long long)cs->samples_uploaded,
               cs->levels_behind_max);
        CHECK(cs->updates > 100u); /* the cache moved with the eye all along */
    }
    ft_app_shutdown(&g_app);
    (void)close(g_soak.statm_fd);
    return ft_test_result("test_soak");
}
