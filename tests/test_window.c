/* test_window.c - the EGL window-surface path (X11), run under Xvfb.
 *
 * usage: test_window BACKEND
 * Renders a frame into the offscreen target, presents it on an X11 window,
 * and checks (1) the window surface holds exactly the frame before the swap
 * (glReadPixels of framebuffer 0), and (2) after eglSwapBuffers the X server
 * shows exactly the frame (XGetImage of the screen where the window sits; no
 * window manager runs under xvfb-run, so the window is at 0,0). A black or
 * stale window fails both. */
#define _POSIX_C_SOURCE 200809L
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app/app.h"
#include "test_util.h"

static const char k_scene[] =
    "[scene]\nmethod = brute\ndisplay = x11\n[view]\nwidth_px = 200\nheight_px = 150\n"
    "[terrain]\ndem =\nsynth_side = 129\nsynth_spacing_m = 60\nsynth_seed = 5\n"
    "[pose]\nlat_deg = 46.501\nlon_deg = 8.04\nalt_m = 3000\nheading_deg = 10\n"
    "pitch_deg = -20\nroll_deg = 0\n"
    "[budget]\nheights_bytes = 128K\npyramids_bytes = 512K\nframe_rgba_bytes = 128K\n"
    "gpu_staging_bytes = 128K\nmethod_bytes = 128K\npng_bytes = 512K\n";

static ft_app g_app;
static uint8_t g_window[200 * 150 * 4];

int main(int argc, char **argv)
{
    ft_scene s;
    ft_error err;
    REQUIRE(argc >= 2);
    if (getenv("DISPLAY") == NULL) {
        printf("no DISPLAY: run under xvfb-run\n");
        return FT_TEST_SKIP;
    }
    ft_scene_defaults(&s);
    REQUIRE(ft_scene_parse(&s, k_scene, "k_scene", &err) == FT_OK);
    REQUIRE(ft_backend_from_name(argv[1], &s.backend));
    ft_status st = ft_app_init(&g_app, &s, &err);
    if (st != FT_OK) fprintf(stderr, "init: %s\n", err.text);
    REQUIRE(st == FT_OK);
    printf("%s on an X11 window: %s\n", argv[1], g_app.gpu.version);

    ft_camera cam;
    ft_frame_stats fs;
    const ft_gl *gl = &g_app.gpu.gl;
    REQUIRE(ft_renderer_camera(&g_app.renderer, &s.pose, &cam, &err) == FT_OK);
    REQUIRE(ft_renderer_draw(&g_app.renderer, &cam, &fs, &err) == FT_OK);
    REQUIRE(ft_renderer_read_rgba(&g_app.renderer, &err) == FT_OK);
    REQUIRE(ft_renderer_present(&g_app.renderer, &err) == FT_OK);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->ReadPixels(0, 0, 200, 150, GL_RGBA, GL_UNSIGNED_BYTE, g_window);
    CHECK(gl->GetError() == GL_NO_ERROR);
    const uint8_t *frame = g_app.renderer.rgba; /* row 0 = top */
    size_t surface_diff = 0;
    for (int y = 0; y < 150; ++y) {
        const uint8_t *wrow = g_window + (size_t)(149 - y) * 200 * 4; /* GL rows bottom-up */
        const uint8_t *frow = frame + (size_t)y * 200 * 4;
        for (int i = 0; i < 200 * 4; i += 4) {
            surface_diff += memcmp(wrow + i, frow + i, 3) != 0;
        }
    }
    printf("window surface vs frame: %zu of 30000 pixels differ\n", surface_diff);
    CHECK(surface_diff == 0);
    REQUIRE(ft_plat_gpu_present(&g_app.gpu, &err) == FT_OK);

    /* What the X server shows now. */
    Display *d = XOpenDisplay(NULL);
    REQUIRE(d != NULL);
    struct timespec pause = {0, 100 * 1000000L};
    nanosleep(&pause, NULL);
    XImage *img = XGetImage(d, DefaultRootWindow(d), 0, 0, 200, 150, AllPlanes, ZPixmap);
    REQUIRE(img != NULL);
    size_t screen_diff = 0;
    for (int y = 0; y < 150; ++y) {
        for (int x = 0; x < 200; ++x) {
            unsigned long p = XGetPixel(img, x, y);
            const uint8_t *f = frame + ((size_t)y * 200 + (size_t)x) * 4;
            uint8_t r = (uint8_t)((p & img->red_mask) >> 16);
            uint8_t g = (uint8_t)((p & img->green_mask) >> 8);
            uint8_t b = (uint8_t)(p & img->blue_mask);
            screen_diff += (r != f[0] || g != f[1] || b != f[2]);
        }
    }
    printf("X server screen vs frame: %zu of 30000 pixels differ\n", screen_diff);
    CHECK(screen_diff == 0);
    XDestroyImage(img);
    XCloseDisplay(d);
    ft_app_shutdown(&g_app);
    return ft_test_result("test_window");
}
