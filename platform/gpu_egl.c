/* gpu_egl.c - EGL on Mesa's surfaceless platform (the headless path), or
 * in an X11 window (display_x11.c). This file picks the platform and owns the
 * window; the EGL bring-up itself is egl_context.c, shared with the KMS path.
 *
 * Facts this code relies on (../shared/PLATFORM-NOTES.md, re-checked here):
 * eglGetDisplay(EGL_DEFAULT_DISPLAY) fails without EGL_PLATFORM set, so we ask
 * for EGL_PLATFORM_SURFACELESS_MESA explicitly; framebuffer 0 is incomplete
 * there, so the renderer always draws into its own FBO; an ES 2 request may
 * return an ES 3.2 context, so the ES2 path is chosen by the *requested* API
 * (the renderer then uses only ES 2 calls and GLSL ES 1.00), and the version
 * actually obtained is reported. */
#define _POSIX_C_SOURCE 200809L
#include <stddef.h>

#include "egl_context.h"
#include "gpu_backends.h"
#include "gpu/gpu.h"

static struct {
    ft_egl egl;
    int x11_open;
} g_egl = {FT_EGL_CLOSED, 0};

static void close_native(void)
{
#if FT_WITH_X11
    if (g_egl.x11_open) {
        ft_x11_close();
        g_egl.x11_open = 0;
    }
#endif
}

/* The EGL platform and native display/window for desc->display (an X11
 * window, or the surfaceless platform). Fails with a clear reason when the
 * display is not available. */
static ft_status open_native(const ft_gpu_desc *desc, ft_egl_desc *egl_desc, ft_error *err)
{
    if (desc->display == FT_DISPLAY_X11) {
#if FT_WITH_X11
        egl_desc->platform = FT_EGL_PLATFORM_X11;
        /* before the window: none appears for a libEGL that cannot use it */
        ft_status s = ft_egl_check_platform(egl_desc->platform, err);
        if (s != FT_OK) {
            return s;
        }
        s = ft_x11_open(desc->width_px, desc->height_px, &egl_desc->native_display,
                        &egl_desc->native_window, err);
        if (s != FT_OK) {
            return s;
        }
        g_egl.x11_open = 1;
        return FT_OK;
#else
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "display 'x11' was left out of this build (FIXTERRAIN_WITH_X11=OFF)");
#endif
    }
    if (desc->display == FT_DISPLAY_NONE) {
        egl_desc->platform = FT_EGL_PLATFORM_SURFACELESS;
        return FT_OK;
    }
    return ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: display '%s' not supported",
                   ft_display_name(desc->display));
}

ft_status ft_plat_egl_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err)
{
    /* Alpha 8 explicitly: without it Mesa offers a 10/10/10/2 config first. */
    ft_egl_desc egl_desc = {.platform = FT_EGL_PLATFORM_SURFACELESS,
                            .native_display = NULL,
                            .native_window = NULL,
                            .es3 = (desc->backend == FT_BACKEND_EGL_GLES3),
                            .alpha_bits = 8,
                            .native_visual = 0u,
                            .native_visual_name = NULL};
    ft_status s = open_native(desc, &egl_desc, err);
    if (s == FT_OK) {
        s = ft_egl_open(&egl_desc, &g_egl.egl, ctx, err);
    }
    if (s != FT_OK) {
        close_native();
        return s;
    }
    ctx->backend = desc->backend;
    ctx->display = desc->display;
    ctx->open = 1;
    return FT_OK;
}

ft_status ft_plat_egl_present(ft_gpu_context *ctx, ft_error *err)
{
    (void)ctx;
    return ft_egl_present(&g_egl.egl, err);
}

void ft_plat_egl_close(ft_gpu_context *ctx)
{
    ft_egl_close(&g_egl.egl);
    close_native();
    ctx->open = 0;
}
