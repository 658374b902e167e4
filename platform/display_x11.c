/* display_x11.c - an X11 window for the EGL window-surface path (desktop
 * development and any display that runs X). Kept apart from gpu_egl.c so
 * Xlib's headers never meet the GL ones. A cockpit display computer uses the
 * GBM/KMS path instead (no window system). */
#define _POSIX_C_SOURCE 200809L
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <stdint.h>
#include <stdio.h>

#include "gpu_backends.h"
#include "core/ft_status.h"

static Display *g_x11_display;
static Window g_x11_window;

ft_status ft_x11_open(uint32_t width_px, uint32_t height_px, void **native_display,
                      void **native_window, ft_error *err)
{
    g_x11_display = XOpenDisplay(NULL);
    if (g_x11_display == NULL) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "X11: cannot open display '%s' (is DISPLAY set and the server running?)",
                       XDisplayName(NULL));
    }
    int screen = DefaultScreen(g_x11_display);
    g_x11_window = XCreateSimpleWindow(g_x11_display, RootWindow(g_x11_display, screen), 0, 0,
                                       width_px, height_px, 0, BlackPixel(g_x11_display, screen),
                                       BlackPixel(g_x11_display, screen));
    /* A fixed-size window: the renderer's targets are sized at init. */
    XSizeHints hints;
    hints.flags = PMinSize | PMaxSize;
    hints.min_width = hints.max_width = (int)width_px;
    hints.min_height = hints.max_height = (int)height_px;
    XSetWMNormalHints(g_x11_display, g_x11_window, &hints);
    XStoreName(g_x11_display, g_x11_window, "fixterrain");
    XMapWindow(g_x11_display, g_x11_window);
    XSync(g_x11_display, False);
    *native_display = g_x11_display;
    *native_window = &g_x11_window; /* EGL's X11 platform takes a Window* */
    return FT_OK;
}

void ft_x11_close(void)
{
    if (g_x11_display != NULL) {
        XDestroyWindow(g_x11_display, g_x11_window);
        XCloseDisplay(g_x11_display);
        g_x11_display = NULL;
    }
}
