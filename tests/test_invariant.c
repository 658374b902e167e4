/* test_invariant.c - a broken invariant ends in the fail-safe annunciation.
 *
 * usage: test_invariant BACKEND
 *   1. FT_INVARIANT latches the first failure (its what and line), counts
 *      the later ones, and the annunciation text names it;
 *   2. with aborts on (FT_INVARIANT_ABORTS = 1, Debug builds) the process
 *      stops at once with SIGABRT (checked in a child);
 *   3. on a real context: frames before the fault report internal_fault = 0
 *      and show no pure red pixel; after a fault raised through the macro,
 *      every frame reports internal_fault = 1 and shows the red cross (pure
 *      red pixels along both diagonals), and the terrain picture under it is
 *      still drawn (the fault does not stop the frame loop). */
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/app.h"
#include "core/invariant.h"
#include "test_app_util.h"

/* %s: the backend */
static const char k_scene_fmt[] =
    "[scene]\nname = invariant-test\nmethod = brute\nbackend = %s\n"
    "[view]\nwidth_px = 160\nheight_px = 120\nfovy_deg = 60\n"
    "[pose]\nlat_deg = 46.5035\nlon_deg = 8.0501\nalt_m = 2600\n"
    "heading_deg = 30\npitch_deg = -12\nroll_deg = 0\n"
    "[terrain]\ndem =\nsynth_side = 129\nsynth_spacing_m = 60\nsynth_relief_m = 2000\n"
    "synth_seed = 7\nsynth_octaves = 6\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[gpu]\ntexture_bytes = 8M\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 100000\n"
    "[budget]\nheights_bytes = 512K\npyramids_bytes = 2M\nframe_rgba_bytes = 512K\n"
    "gpu_staging_bytes = 512K\nmethod_bytes = 128K\npng_bytes = 512K\n";

static ft_app g_app;

static int is_red(const uint8_t *p)
{
    return p[0] == 255u && p[1] == 0u && p[2] == 0u;
}

/* Pure red pixels in the whole frame, and on each diagonal (where the
 * cross's bars run corner to corner). */
static void count_red(uint32_t *all, uint32_t *diag_a, uint32_t *diag_b)
{
    const uint32_t w = g_app.scene.width_px, h = g_app.scene.height_px;
    const uint8_t *rgba = g_app.renderer.rgba;
    *all = *diag_a = *diag_b = 0u;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            *all += (uint32_t)is_red(&rgba[4u * ((size_t)y * w + x)]);
        }
        const uint32_t xa = (uint32_t)((double)y * w / h), xb = w - 1u - xa;
        *diag_a += (uint32_t)is_red(&rgba[4u * ((size_t)y * w + xa)]);
        *diag_b += (uint32_t)is_red(&rgba[4u * ((size_t)y * w + xb)]);
    }
}

static void frame(ft_frame_stats *fs)
{
    ft_camera cam;
    ft_test_frame(&g_app, &g_app.scene.pose, &cam, fs);
}

static void test_latch(void)
{
    ft_fault_clear_for_test();
    CHECK(ft_fault_latched() == NULL);
    FT_INVARIANT(1 + 1 == 2, "holds");
    CHECK(ft_fault_latched() == NULL);
    const int line = __LINE__ + 1;
    FT_INVARIANT(1 + 1 == 3, "first broken");
    FT_INVARIANT(0, "second broken");
    const ft_fault *f = ft_fault_latched();
    REQUIRE(f != NULL);
    CHECK(strcmp(f->what, "first broken") == 0);
    CHECK(f->line == line);
    CHECK(strstr(f->file, "test_invariant.c") != NULL);
    CHECK(f->count == 2u);
    char text[FT_FAULT_TEXT_MAX];
    CHECK(strcmp(ft_fault_text(text), "INTERNAL FAULT first broken") == 0);
    ft_fault_clear_for_test();
    CHECK(ft_fault_latched() == NULL);
}

static void test_abort(void)
{
    fflush(NULL);
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        /* quiet: the child's message is expected */
        if (freopen("/dev/null", "w", stderr) == NULL) _exit(3);
        ft_fault_raise("abort path", __FILE__, __LINE__, 1);
        _exit(0); /* not reached when abort works */
    }
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT);
}

static void test_annunciation(const char *backend)
{
    static char text[sizeof k_scene_fmt + 32];
    REQUIRE(snprintf(text, sizeof text, k_scene_fmt, backend) < (int)sizeof text);
    ft_test_app_init(&g_app, text, backend);
    ft_fault_clear_for_test();

    ft_frame_stats fs;
    uint32_t red, da, db;
    frame(&fs);
    count_red(&red, &da, &db);
    CHECK(fs.internal_fault == 0);
    CHECK(red == 0u); /* the terrain and sky have no pure red */
    const uint64_t tris_ok = fs.triangles;

    FT_INVARIANT(tris_ok == UINT64_MAX, "test fault");
    for (int k = 0; k < 3; ++k) { /* every frame after the fault */
        frame(&fs);
        count_red(&red, &da, &db);
        CHECK(fs.internal_fault == 1);
        CHECK(fs.triangles == tris_ok); /* the picture is still drawn */
        /* both bars cover their diagonal (but where the text box hides it) */
        CHECK(da > g_app.scene.height_px / 2u);
        CHECK(db > g_app.scene.height_px / 2u);
        CHECK(red > 4u * g_app.scene.height_px);
        printf("frame %d after the fault: %u red pixels, diagonals %u and %u of %u rows\n", k,
               red, da, db, g_app.scene.height_px);
    }
    ft_app_shutdown(&g_app);
    ft_fault_clear_for_test();
}

int main(int argc, char **argv)
{
    REQUIRE(argc >= 2);
    test_latch();
    test_abort();
    test_annunciation(argv[1]);
    return ft_test_result("test_invariant");
}
