/* gpu_egl.c - EGL on Mesa's surfaceless platform (the headless path).
 *
 * Facts this code relies on (../shared/PLATFORM-NOTES.md, re-checked here):
 * eglGetDisplay(EGL_DEFAULT_DISPLAY) fails without EGL_PLATFORM set, so we ask
 * for EGL_PLATFORM_SURFACELESS_MESA explicitly; framebuffer 0 is incomplete
 * there, so the renderer always draws into its own FBO; an ES 2 request may
 * return an ES 3.2 context, so the ES2 path is chosen by the *requested* API
 * (the renderer then uses only ES 2 calls and GLSL ES 1.00), and the version
 * actually obtained is reported. */
#define _POSIX_C_SOURCE 200809L
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <string.h>

#include "gpu/gpu.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

#ifndef EGL_PLATFORM_X11_KHR
#define EGL_PLATFORM_X11_KHR 0x31D5
#endif

ft_status ft_plat_egl_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err);
ft_status ft_plat_egl_present(ft_gpu_context *ctx, ft_error *err);
void ft_plat_egl_close(ft_gpu_context *ctx);
#if FT_WITH_X11
ft_status ft_x11_open(uint32_t width_px, uint32_t height_px, void **native_display,
                      void **native_window, ft_error *err);
void ft_x11_close(void);
#endif

static struct {
    EGLDisplay display;
    EGLContext context;
    EGLSurface surface; /* window surface, or EGL_NO_SURFACE (surfaceless) */
    int x11_open;
} g_egl = {EGL_NO_DISPLAY, EGL_NO_CONTEXT, EGL_NO_SURFACE, 0};

static int has_word(const char *list, const char *word)
{
    size_t n = strlen(word);
    if (list == NULL) {
        return 0;
    }
    for (const char *p = strstr(list, word); p != NULL; p = strstr(p + 1, word)) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) {
            return 1;
        }
    }
    return 0;
}

static ft_gl_proc egl_get_proc(const char *name)
{
    return (ft_gl_proc)eglGetProcAddress(name);
}

/* The native display and window for desc->display (X11), or the surfaceless
 * platform. Fails with a clear reason when the display is not available. */
static ft_status open_native(const ft_gpu_desc *desc, void **native_window, ft_error *err)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    *native_window = NULL;
    if (desc->display == FT_DISPLAY_X11) {
#if FT_WITH_X11
        void *native_display = NULL;
        if (!has_word(client, "EGL_KHR_platform_x11") && !has_word(client, "EGL_EXT_platform_x11")) {
            return ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: no X11 platform in this libEGL");
        }
        ft_status s = ft_x11_open(desc->width_px, desc->height_px, &native_display,
                                  native_window, err);
        if (s != FT_OK) {
            return s;
        }
        g_egl.x11_open = 1;
        g_egl.display = eglGetPlatformDisplay(EGL_PLATFORM_X11_KHR, native_display, NULL);
#else
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "display 'x11' was left out of this build (FIXTERRAIN_WITH_X11=OFF)");
#endif
    } else if (desc->display == FT_DISPLAY_NONE) {
        if (!has_word(client, "EGL_MESA_platform_surfaceless")) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "EGL: client extension EGL_MESA_platform_surfaceless is missing "
                           "(needs Mesa's libEGL)");
        }
        g_egl.display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                              (void *)EGL_DEFAULT_DISPLAY, NULL);
    } else {
        return ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: display '%s' not supported",
                       ft_display_name(desc->display));
    }
    if (g_egl.display == EGL_NO_DISPLAY) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglGetPlatformDisplay(%s) failed: 0x%x",
                       ft_display_name(desc->display), (unsigned)eglGetError());
    }
    return FT_OK;
}

static void close_native(void)
{
#if FT_WITH_X11
    if (g_egl.x11_open) {
        ft_x11_close();
        g_egl.x11_open = 0;
    }
#endif
}

ft_status ft_plat_egl_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err)
{
    ft_status s;
    const ft_backend backend = desc->backend;
    const int es3 = (backend == FT_BACKEND_EGL_GLES3);
    const int windowed = (desc->display != FT_DISPLAY_NONE);
    void *native_window = NULL;

    s = open_native(desc, &native_window, err);
    if (s != FT_OK) {
        goto fail_display;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(g_egl.display, &major, &minor)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglInitialize failed: 0x%x", (unsigned)eglGetError());
        goto fail_display;
    }
    if (!windowed && !has_word(eglQueryString(g_egl.display, EGL_EXTENSIONS),
                               "EGL_KHR_surfaceless_context")) {
        s = ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: EGL_KHR_surfaceless_context is missing");
        goto fail_initialized;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglBindAPI(GLES) failed: 0x%x",
                    (unsigned)eglGetError());
        goto fail_initialized;
    }
    /* Pbuffer configs: the surfaceless platform has no window configs, and
     * EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT. Alpha 8 explicitly:
     * without it Mesa offers a 10/10/10/2 config first.
     * We never draw to the config's surface (FBOs only), but keep it plain. */
    const EGLint config_attribs[] = {EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_ALPHA_SIZE, 8, EGL_SURFACE_TYPE,
                                     windowed ? EGL_WINDOW_BIT : EGL_PBUFFER_BIT,
                                     EGL_RENDERABLE_TYPE,
                                     es3 ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_ES2_BIT, EGL_NONE};
    EGLConfig config;
    EGLint n_configs = 0;
    if (!eglChooseConfig(g_egl.display, config_attribs, &config, 1, &n_configs) ||
        n_configs < 1) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: no RGBA8 config for OpenGL ES %d", es3 ? 3 : 2);
        goto fail_initialized;
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, es3 ? 3 : 2,
                                      EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    g_egl.context = eglCreateContext(g_egl.display, config, EGL_NO_CONTEXT, context_attribs);
    if (g_egl.context == EGL_NO_CONTEXT) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: OpenGL ES %d.0 context creation failed: 0x%x",
                    es3 ? 3 : 2, (unsigned)eglGetError());
        goto fail_initialized;
    }
    if (windowed) {
        g_egl.surface = eglCreatePlatformWindowSurface(g_egl.display, config, native_window, NULL);
        if (g_egl.surface == EGL_NO_SURFACE) {
            s = ft_fail(err, FT_ERR_GPU, "EGL: window surface creation failed: 0x%x",
                        (unsigned)eglGetError());
            goto fail_context;
        }
    }
    if (!eglMakeCurrent(g_egl.display, g_egl.surface, g_egl.surface, g_egl.context)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglMakeCurrent(%s) failed: 0x%x",
                    windowed ? "window" : "surfaceless", (unsigned)eglGetError());
        goto fail_surface;
    }
    s = ft_gl_load(&ctx->gl, es3 ? FT_GL_API_ES3 : FT_GL_API_ES2, 0, egl_get_proc, err);
    if (s != FT_OK) {
        goto fail_current;
    }
    const char *version = (const char *)ctx->gl.GetString(GL_VERSION);
    const char *renderer = (const char *)ctx->gl.GetString(GL_RENDERER);
    (void)snprintf(ctx->version, sizeof ctx->version, "%s", version ? version : "?");
    (void)snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "?");
    ctx->backend = backend;
    ctx->display = desc->display;
    ctx->open = 1;
    return FT_OK;

fail_current:
    (void)eglMakeCurrent(g_egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
fail_surface:
    if (g_egl.surface != EGL_NO_SURFACE) {
        (void)eglDestroySurface(g_egl.display, g_egl.surface);
        g_egl.surface = EGL_NO_SURFACE;
    }
fail_context:
    (void)eglDestroyContext(g_egl.display, g_egl.context);
    g_egl.context = EGL_NO_CONTEXT;
fail_initialized:
    (void)eglTerminate(g_egl.display);
fail_display:
    g_egl.display = EGL_NO_DISPLAY;
    close_native();
    return s;
}

ft_status ft_plat_egl_present(ft_gpu_context *ctx, ft_error *err)
{
    (void)ctx;
    if (g_egl.surface == EGL_NO_SURFACE) {
        return FT_OK;
    }
    if (!eglSwapBuffers(g_egl.display, g_egl.surface)) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglSwapBuffers failed: 0x%x",
                       (unsigned)eglGetError());
    }
    return FT_OK;
}

void ft_plat_egl_close(ft_gpu_context *ctx)
{
    if (g_egl.display != EGL_NO_DISPLAY) {
        (void)eglMakeCurrent(g_egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (g_egl.surface != EGL_NO_SURFACE) {
            (void)eglDestroySurface(g_egl.display, g_egl.surface);
        }
        if (g_egl.context != EGL_NO_CONTEXT) {
            (void)eglDestroyContext(g_egl.display, g_egl.context);
        }
        (void)eglTerminate(g_egl.display);
    }
    g_egl.display = EGL_NO_DISPLAY;
    g_egl.context = EGL_NO_CONTEXT;
    g_egl.surface = EGL_NO_SURFACE;
    close_native();
    ctx->open = 0;
}
