/* test_no_heap.c - proof that the renderer's own code takes no heap memory
 * (and maps no memory) after init, over a multi-frame run.
 *
 * This binary is linked with -Wl,--wrap=malloc,... so every allocator call
 * made by OUR objects (src/, platform/, this test) goes through the counters
 * below. Calls made inside shared libraries (Mesa, libpng's own code paths,
 * libc internals) are not redirected by --wrap: driver allocations are not
 * ours and are not counted, as the issue states. libpng is given the arena
 * through png_create_write_struct_2, so the PNG write after the frames is
 * counted too.
 *
 * The test first proves the wrapping works (a deliberate malloc is counted),
 * then runs init, then 120 frames along a moving path plus a position pass
 * and a PNG write with counting on, and requires zero calls.
 * Usage: test_no_heap OUT.png [BACKEND [METHOD [replay]]] (METHOD as in
 * scene.method: brute, bintree, pgm, ..., or pgm-cache: pgm with pgm.heights =
 * clipmap, or pgrid-cache: pgrid over the cache, or bintree-cache: the bintree
 * with bintree.heights = clipmap, or pgrid-columns: pgrid with pgrid.columns =
 * error; the path
 * changes the view every
 * frame, so a LOD method selects anew each frame). With
 * "replay", a candump log with a stall is then replayed too (decoder, pose
 * feed, annunciation overlay, pose CSV, one PNG per frame), counting on. */
#define _GNU_SOURCE
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>

#include "app/app.h"
#include "app/replay.h"
#include "input/candump.h"
#include "test_util.h"

/* volatile: GCC knows malloc does not read our globals and would otherwise
 * merge the stores around the probe call below. */
static volatile int g_counting;
static volatile unsigned long g_calls;
static const char *g_first;

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t m);
void *__real_realloc(void *p, size_t n);
void __real_free(void *p);
char *__real_strdup(const char *s);
int __real_posix_memalign(void **p, size_t a, size_t n);
void *__real_aligned_alloc(size_t a, size_t n);
void *__real_mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off);

void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t m);
void *__wrap_realloc(void *p, size_t n);
void __wrap_free(void *p);
char *__wrap_strdup(const char *s);
int __wrap_posix_memalign(void **p, size_t a, size_t n);
void *__wrap_aligned_alloc(size_t a, size_t n);
void *__wrap_mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off);

static void count(const char *what)
{
    if (g_counting) {
        if (g_calls == 0) {
            g_first = what;
        }
        ++g_calls;
    }
}

void *__wrap_malloc(size_t n) { count("malloc"); return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t m) { count("calloc"); return __real_calloc(n, m); }
void *__wrap_realloc(void *p, size_t n) { count("realloc"); return __real_realloc(p, n); }
void __wrap_free(void *p) { if (p) count("free"); __real_free(p); }
char *__wrap_strdup(const char *s) { count("strdup"); return __real_strdup(s); }
int __wrap_posix_memalign(void **p, size_t a, size_t n)
{
    count("posix_memalign");
    return __real_posix_memalign(p, a, n);
}
void *__wrap_aligned_alloc(size_t a, size_t n) { count("aligned_alloc"); return __real_aligned_alloc(a, n); }
void *__wrap_mmap(void *addr, size_t len, int prot, int flags, int fd, off_t off)
{
    count("mmap");
    return __real_mmap(addr, len, prot, flags, fd, off);
}

static const char k_scene[] =
    "[scene]\nname = no-heap\nmethod = brute\nbackend = egl-gles3\n"
    "[view]\nwidth_px = 256\nheight_px = 192\nfovy_deg = 60\n"
    "[terrain]\ndem =\nsynth_side = 257\nsynth_spacing_m = 30\nsynth_relief_m = 2000\n"
    "synth_seed = 3\nsynth_octaves = 8\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[gpu]\ntexture_bytes = 16M\n[metric]\nenabled = 1\n"
    "[bintree]\ntemplate_k = 3\ntiles_max = 4096\ntau_px = 1.0\nmorph = 1\nsubsample_levels = 2\n"
    "[pgm]\ngrid_cols = 200\ngrid_rows = 800\n"
    "[clipmap]\nside = 64\nlevels = 4\nupdate_samples_max = 2048\nupdates_per_frame = 4\n"
    "[budget]\nclip_bytes = 256K\nheights_bytes = 512K\npyramids_bytes = 2M\nframe_rgba_bytes = 256K\n"
    "frame_pos_bytes = 1M\nreference_bytes = 2M\nmetric_bytes = 1M\n"
    "gpu_staging_bytes = 512K\nmethod_bytes = 1M\npng_bytes = 512K\n";

/* The terrain as a window of a database (DB.ftd, argument 5): the window
 * around 42.5 N 1.5 E and the clipmap cache reading the database past it;
 * the flight and the log move there. */
static const char k_db_terrain[] =
    "[terrain]\ndem = %s\ndb_level = 0\ndb_side_samples = 257\n"
    "db_centre_lat_deg = 42.5\ndb_centre_lon_deg = 1.5\n"
    "[clipmap]\ntile_slots = 4\n[budget]\nclip_bytes = 3M\nreference_bytes = 4M\n";
static double g_lat0 = 46.5, g_lon0 = 8.0;

static ft_app g_app;
static ft_pose_feed g_feed;
static ft_replay_io g_replay_io; /* the replay's files and line reader */
static ft_replay_result g_res;

/* A 4 s CANaerospace log (attitude, rates 80 Hz; altitude, lat/lon FLOAT and
 * the velocity 10 Hz, so the position is predicted too) with a 0.6 s stall,
 * written before init (stdio may allocate). */
static void write_log(const char *path)
{
    FILE *f = fopen(path, "w");
    REQUIRE(f != NULL);
    static const uint16_t ids[] = {311, 312, 321, 303, 304, 305, 320, 1036, 1037, 1039, 1040, 314};
    const float vals[] = {-10.0f, 5.0f, 0.0f,  0.0f,  0.0f,   20.0f,
                          3500.0f, (float)(g_lat0 + 0.05), (float)(g_lon0 + 0.2), 100.0f,
                          45.0f, 2.0f};
    uint8_t code[12] = {0};
    for (int i = 0; i < 320; ++i) {
        if (i >= 160 && i < 208) continue; /* stall */
        for (int q = 0; q < 12; ++q) {
            if (q >= 6 && i % 8 != 0) continue;
            ft_candump_record rec;
            memset(&rec, 0, sizeof rec);
            (void)snprintf(rec.iface, sizeof rec.iface, "vcan0");
            rec.frame.can_id = ids[q];
            rec.frame.dlc = 8;
            rec.frame.t_ns = 1700000000000000000ull + (uint64_t)i * 12500000ull + (uint64_t)q * 100000u;
            float v = (q == 2) ? (float)(i * 0.25) : vals[q];
            uint32_t bits;
            memcpy(&bits, &v, sizeof bits);
            uint8_t *d = rec.frame.data;
            d[0] = 1; d[1] = FT_CAN_TYPE_FLOAT; d[2] = 0; d[3] = code[q]++;
            d[4] = (uint8_t)(bits >> 24); d[5] = (uint8_t)(bits >> 16);
            d[6] = (uint8_t)(bits >> 8); d[7] = (uint8_t)bits;
            char line[64];
            REQUIRE(ft_candump_format(&rec, line, sizeof line, NULL, NULL) == FT_OK);
            fprintf(f, "%s\n", line);
        }
        if (i == 100) fprintf(f, "(1700000001.250000) vcan0 137#ZZZZ\n"); /* a bad line */
    }
    REQUIRE(fclose(f) == 0);
}

int main(int argc, char **argv)
{
    ft_scene s;
    ft_error err;
    REQUIRE(argc >= 2);
    const char *png_path = argv[1];

    /* 1. The wrapper sees our calls (otherwise a zero below proves nothing). */
    g_counting = 1;
    void *volatile probe = malloc(16);
    free(probe);
    g_counting = 0;
    CHECK(g_calls == 2);
    g_calls = 0;

    /* 2. Init may allocate (it does not, but it is allowed to). */
    ft_scene_defaults(&s);
    REQUIRE(ft_scene_parse(&s, k_scene, "k_scene", &err) == FT_OK);
    if (argc >= 6) {
        char text[1024];
        (void)snprintf(text, sizeof text, k_db_terrain, argv[5]);
        REQUIRE(ft_scene_parse(&s, text, "k_db_terrain", &err) == FT_OK);
        g_lat0 = 42.5;
        g_lon0 = 1.5;
        s.pose.lat_deg = g_lat0;
        s.pose.lon_deg = g_lon0;
        s.pose.alt_m = 4500.0;
    }
    if (argc >= 3) {
        REQUIRE(ft_backend_from_name(argv[2], &s.backend));
    }
    if (argc >= 4 && strcmp(argv[3], "pgm-cache") == 0) {
        s.method = FT_METHOD_PGM; /* pgm reading its heights through the clip cache */
        s.pgm_heights_clipmap = 1;
    } else if (argc >= 4 && strcmp(argv[3], "pgrid-cache") == 0) {
        /* pgrid over the clip cache: its cell ranges too, the tight
         * bound's passes on its levels, and the ray caster through them
         * with the leaves' bound every frame */
        s.method = FT_METHOD_PGRID;
        s.pgrid_heights_clipmap = 1;
        s.pgrid_residual_bound = 1;
        s.pgrid_ray_casting = 1;
        /* the ranges' staging (an update's cells) on top of the readback */
        REQUIRE(ft_scene_parse(&s, "[budget]\nmethod_bytes = 2M\n", "pgrid-cache", &err) ==
                FT_OK);
    } else if (argc >= 4 && strcmp(argv[3], "bintree-cache") == 0) {
        /* the bintree's tiles over the clip cache: its tables folded and
         * selected every frame, no geomorphing or sub-sample levels there;
         * a level side of 128, the least for template_k 3 (12 * 2^3 + 8) */
        s.method = FT_METHOD_BINTREE;
        s.bintree_heights_clipmap = 1;
        s.bintree_morph = 0;
        s.bintree_subsample_levels = 0;
        REQUIRE(ft_scene_parse(&s, "[clipmap]\nside = 128\n[budget]\nclip_bytes = 4M\n"
                                   "method_bytes = 2M\n",
                               "bintree-cache", &err) == FT_OK);
    } else if (argc >= 4 && strcmp(argv[3], "pgrid-columns") == 0) {
        s.method = FT_METHOD_PGRID; /* pgrid with its columns moved by the error */
        s.pgrid_columns_error = 1;
    } else if (argc >= 4) {
        REQUIRE(ft_method_from_name(argv[3], &s.method));
    }
    ft_status st = ft_app_init(&g_app, &s, &err);
    if (st != FT_OK) {
        fprintf(stderr, "init: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    printf("init made %lu allocator calls in our code\n", g_calls);
    REQUIRE(g_app.arena.locked);

    /* 3. Frames: counting on. A path over the terrain, turning and climbing. */
    g_calls = 0;
    g_counting = 1;
    ft_camera cam;
    ft_frame_stats fs;
    ft_pose pose = s.pose;
    int frames_ok = 0;
    for (int f = 0; f < 120; ++f) {
        pose.lat_deg = g_lat0 + 0.02 + 0.0002 * f;
        pose.lon_deg = g_lon0 + 0.02 + 0.0001 * f;
        pose.alt_m = (g_lat0 < 45.0 ? 4500.0 : 2500.0) + 10.0 * f;
        pose.heading_deg = 3.0 * f;
        pose.pitch_deg = -10.0 - 0.1 * f;
        pose.roll_deg = (f % 20) - 10.0;
        if (ft_app_render(&g_app, &pose, &cam, &fs, &err) == FT_OK) {
            ++frames_ok;
        }
    }
    ft_error_stats es;
    ft_status ms = ft_app_measure(&g_app, &cam, &es, &err);
    ft_status ps = ft_plat_png_write(png_path, g_app.renderer.rgba, s.width_px, s.height_px,
                                     &g_app.arena, &err);
    int replay = argc >= 5 && strcmp(argv[4], "replay") == 0;
    ft_status rs = FT_OK;
    if (replay) {
        /* beside the PNG, named after it: the no-heap tests run in
         * parallel and must not share the log, the CSV or the frames */
        char log[FT_PATH_MAX], csv[FT_PATH_MAX], dir[FT_PATH_MAX];
        const size_t len = strlen(png_path);
        const int n = (int)((len > 4u && strcmp(png_path + len - 4u, ".png") == 0) ? len - 4u : len);
        (void)snprintf(log, sizeof log, "%.*s.replay.log", n, png_path);
        (void)snprintf(csv, sizeof csv, "%.*s.replay.csv", n, png_path);
        (void)snprintf(dir, sizeof dir, "%.*s.frames", n, png_path);
        g_counting = 0;
        write_log(log); /* test set-up, not the renderer */
        REQUIRE(mkdir(dir, 0755) == 0 || errno == EEXIST);
        g_counting = 1;
        ft_replay_desc d = {log, dir, csv, 0};
        rs = ft_app_replay(&g_app, &d, &g_feed, &g_replay_io, &g_res, &err);
        if (rs != FT_OK) fprintf(stderr, "replay: %s\n", err.text);
    }
    /* A request to the locked arena is refused, not served from the heap. */
    void *late = NULL;
    ft_status ls = ft_arena_take(&g_app.arena, FT_POOL_METHOD, 64, &late, NULL);
    g_counting = 0;

    CHECK(frames_ok == 120);
    CHECK(rs == FT_OK);
    if (replay) {
        printf("replay: %u frames (%u annunciated), %llu lines, %llu bad\n", g_res.frames,
               g_res.frames_annunciated, (unsigned long long)g_res.lines,
               (unsigned long long)g_res.lines_bad);
        CHECK(g_res.frames > 200u && g_res.frames_annunciated > 20u && g_res.lines_bad == 1u);
    }
    /* GLES 2 cannot render the float position pass: then the metric is
     * refused (with a message), which must not allocate either. */
    CHECK(ms == FT_OK || (ms == FT_ERR_UNSUPPORTED && !g_app.renderer.has_pos_target));
    CHECK(ps == FT_OK);
    CHECK(ls == FT_ERR_ARENA_LOCKED && late == NULL);
    if (g_calls != 0) {
        fprintf(stderr, "%lu allocator calls after init (first: %s)\n", g_calls, g_first);
    }
    CHECK(g_calls == 0);
    printf("120 frames + position pass + reference + metric + PNG: %lu allocator calls "
           "after init\n", g_calls);
    ft_app_shutdown(&g_app);
    return ft_test_result("test_no_heap");
}
