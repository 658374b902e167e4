/* egl_context.c - the shared EGL bring-up (egl_context.h): client extension,
 * platform display, ES config and context, optional window surface, the GL
 * table through eglGetProcAddress. Used by gpu_egl.c (surfaceless, X11) and
 * display_kms.c (GBM); see ../shared/PLATFORM-NOTES.md for the Mesa facts
 * behind the choices below. */
#define _POSIX_C_SOURCE 200809L
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <string.h>

#include "egl_context.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef EGL_PLATFORM_X11_KHR
#define EGL_PLATFORM_X11_KHR 0x31D5
#endif
#ifndef EGL_PLATFORM_GBM_KHR
#define EGL_PLATFORM_GBM_KHR 0x31D7
#endif

#define FT_EGL_CONFIGS_MAX 64 /* configs examined for the native visual */

/* 1 when word is one of the space-separated names in list (NULL: none). */
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

/* The platform's name in messages. */
static const char *platform_name(ft_egl_platform platform)
{
    switch (platform) {
    case FT_EGL_PLATFORM_SURFACELESS: return "surfaceless";
    case FT_EGL_PLATFORM_X11: return "X11";
    case FT_EGL_PLATFORM_GBM: return "GBM";
    default: return "?";
    }
}

ft_status ft_egl_check_platform(ft_egl_platform platform, ft_error *err)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    switch (platform) {
    case FT_EGL_PLATFORM_SURFACELESS:
        if (!has_word(client, "EGL_MESA_platform_surfaceless")) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "EGL: client extension EGL_MESA_platform_surfaceless is missing "
                           "(needs Mesa's libEGL)");
        }
        return FT_OK;
    case FT_EGL_PLATFORM_X11:
        if (!has_word(client, "EGL_KHR_platform_x11") && !has_word(client, "EGL_EXT_platform_x11")) {
            return ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: no X11 platform in this libEGL");
        }
        return FT_OK;
    case FT_EGL_PLATFORM_GBM:
        if (!has_word(client, "EGL_KHR_platform_gbm") && !has_word(client, "EGL_MESA_platform_gbm")) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "EGL: no GBM platform in this libEGL (EGL_KHR_platform_gbm missing)");
        }
        return FT_OK;
    default:
        return ft_fail(err, FT_ERR_ARG, "EGL: unknown platform %d", (int)platform);
    }
}

static EGLDisplay get_display(const ft_egl_desc *desc)
{
    switch (desc->platform) {
    case FT_EGL_PLATFORM_SURFACELESS:
        return eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, (void *)EGL_DEFAULT_DISPLAY,
                                     NULL);
    case FT_EGL_PLATFORM_X11:
        return eglGetPlatformDisplay(EGL_PLATFORM_X11_KHR, desc->native_display, NULL);
    case FT_EGL_PLATFORM_GBM:
        return eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, desc->native_display, NULL);
    default:
        return EGL_NO_DISPLAY;
    }
}

/* The config for desc on an initialized display: the first RGB8 one with
 * desc's alpha, surface type and ES version, and with desc->native_visual
 * when one is asked for. */
static ft_status choose_config(const ft_egl_desc *desc, EGLDisplay display, EGLConfig *config,
                               ft_error *err)
{
    const int windowed = (desc->native_window != NULL);
    const int es_major = desc->es3 ? 3 : 2;
    /* Pbuffer configs without a window: the surfaceless platform has no
     * window configs, and EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT.
     * We never draw to the config's surface (FBOs only), but keep it plain. */
    const EGLint config_attribs[] = {EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
                                     EGL_ALPHA_SIZE, desc->alpha_bits, EGL_SURFACE_TYPE,
                                     windowed ? EGL_WINDOW_BIT : EGL_PBUFFER_BIT,
                                     EGL_RENDERABLE_TYPE,
                                     desc->es3 ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_ES2_BIT, EGL_NONE};
    EGLConfig configs[FT_EGL_CONFIGS_MAX];
    EGLint n_configs = 0;
    if (!eglChooseConfig(display, config_attribs, configs, FT_EGL_CONFIGS_MAX, &n_configs)) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglChooseConfig failed: 0x%x",
                       (unsigned)eglGetError());
    }
    for (EGLint i = 0; i < n_configs; ++i) {
        EGLint visual = 0;
        if (desc->native_visual == 0u ||
            (eglGetConfigAttrib(display, configs[i], EGL_NATIVE_VISUAL_ID, &visual) &&
             (uint32_t)visual == desc->native_visual)) {
            *config = configs[i];
            return FT_OK;
        }
    }
    const char *rgb = desc->alpha_bits > 0 ? "RGBA8" : "RGB8";
    if (desc->native_visual == 0u) {
        return ft_fail(err, FT_ERR_GPU, "EGL: no %s config for OpenGL ES %d", rgb, es_major);
    }
    return ft_fail(err, FT_ERR_GPU,
                   "EGL: none of %d %s %s configs for OpenGL ES %d has the native visual %s",
                   (int)n_configs, rgb, windowed ? "window" : "pbuffer", es_major,
                   desc->native_visual_name != NULL ? desc->native_visual_name : "asked for");
}

ft_status ft_egl_open(const ft_egl_desc *desc, ft_egl *egl, ft_gpu_context *ctx, ft_error *err)
{
    const int windowed = (desc->native_window != NULL);
    const int es_major = desc->es3 ? 3 : 2;
    const char *name = platform_name(desc->platform);
    EGLConfig config;
    ft_status s;

    *egl = (ft_egl)FT_EGL_CLOSED;
    s = ft_egl_check_platform(desc->platform, err);
    if (s != FT_OK) {
        return s;
    }
    egl->display = get_display(desc);
    if (egl->display == EGL_NO_DISPLAY) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglGetPlatformDisplay(%s) failed: 0x%x", name,
                       (unsigned)eglGetError());
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(egl->display, &major, &minor)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglInitialize on %s failed: 0x%x", name,
                    (unsigned)eglGetError());
        goto fail_display;
    }
    if (!windowed && !has_word(eglQueryString(egl->display, EGL_EXTENSIONS),
                               "EGL_KHR_surfaceless_context")) {
        s = ft_fail(err, FT_ERR_UNSUPPORTED, "EGL: EGL_KHR_surfaceless_context is missing");
        goto fail_initialized;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglBindAPI(GLES) failed: 0x%x",
                    (unsigned)eglGetError());
        goto fail_initialized;
    }
    s = choose_config(desc, egl->display, &config, err);
    if (s != FT_OK) {
        goto fail_initialized;
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, es_major,
                                      EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    egl->context = eglCreateContext(egl->display, config, EGL_NO_CONTEXT, context_attribs);
    if (egl->context == EGL_NO_CONTEXT) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: OpenGL ES %d.0 context creation failed: 0x%x",
                    es_major, (unsigned)eglGetError());
        goto fail_initialized;
    }
    if (windowed) {
        egl->surface = eglCreatePlatformWindowSurface(egl->display, config, desc->native_window,
                                                      NULL);
        if (egl->surface == EGL_NO_SURFACE) {
            s = ft_fail(err, FT_ERR_GPU, "EGL: window surface creation on %s failed: 0x%x", name,
                        (unsigned)eglGetError());
            goto fail_context;
        }
    }
    if (!eglMakeCurrent(egl->display, egl->surface, egl->surface, egl->context)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglMakeCurrent(%s %s) failed: 0x%x", name,
                    windowed ? "window" : "context", (unsigned)eglGetError());
        goto fail_surface;
    }
    s = ft_gl_load(&ctx->gl, desc->es3 ? FT_GL_API_ES3 : FT_GL_API_ES2, 0, egl_get_proc, err);
    if (s != FT_OK) {
        goto fail_current;
    }
    const char *version = (const char *)ctx->gl.GetString(GL_VERSION);
    const char *renderer = (const char *)ctx->gl.GetString(GL_RENDERER);
    (void)snprintf(ctx->version, sizeof ctx->version, "%s", version ? version : "?");
    (void)snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "?");
    return FT_OK;

fail_current:
    (void)eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
fail_surface:
    if (egl->surface != EGL_NO_SURFACE) {
        (void)eglDestroySurface(egl->display, egl->surface);
        egl->surface = EGL_NO_SURFACE;
    }
fail_context:
    (void)eglDestroyContext(egl->display, egl->context);
    egl->context = EGL_NO_CONTEXT;
fail_initialized:
    (void)eglTerminate(egl->display);
fail_display:
    egl->display = EGL_NO_DISPLAY;
    return s;
}

ft_status ft_egl_present(const ft_egl *egl, ft_error *err)
{
    if (egl->surface == EGL_NO_SURFACE) {
        return FT_OK;
    }
    if (!eglSwapBuffers(egl->display, egl->surface)) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglSwapBuffers failed: 0x%x",
                       (unsigned)eglGetError());
    }
    return FT_OK;
}

void ft_egl_close(ft_egl *egl)
{
    if (egl->display != EGL_NO_DISPLAY) {
        (void)eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (egl->surface != EGL_NO_SURFACE) {
            (void)eglDestroySurface(egl->display, egl->surface);
        }
        if (egl->context != EGL_NO_CONTEXT) {
            (void)eglDestroyContext(egl->display, egl->context);
        }
        (void)eglTerminate(egl->display);
    }
    *egl = (ft_egl)FT_EGL_CLOSED;
}
