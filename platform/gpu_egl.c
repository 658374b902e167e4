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

#include "gpu.h"

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

ft_status ft_plat_egl_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err);
void ft_plat_egl_close(ft_gpu_context *ctx);

static struct {
    EGLDisplay display;
    EGLContext context;
} g_egl = {EGL_NO_DISPLAY, EGL_NO_CONTEXT};

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

ft_status ft_plat_egl_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err)
{
    ft_status s;
    const int es3 = (backend == FT_BACKEND_EGL_GLES3);
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);

    if (!has_word(client, "EGL_MESA_platform_surfaceless")) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "EGL: client extension EGL_MESA_platform_surfaceless is missing "
                       "(needs Mesa's libEGL)");
    }
    g_egl.display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA,
                                          (void *)EGL_DEFAULT_DISPLAY, NULL);
    if (g_egl.display == EGL_NO_DISPLAY) {
        return ft_fail(err, FT_ERR_GPU, "EGL: eglGetPlatformDisplay(surfaceless) failed: 0x%x",
                       (unsigned)eglGetError());
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(g_egl.display, &major, &minor)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglInitialize failed: 0x%x", (unsigned)eglGetError());
        goto fail_display;
    }
    if (!has_word(eglQueryString(g_egl.display, EGL_EXTENSIONS),
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
                                     EGL_ALPHA_SIZE, 8, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
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
    if (!eglMakeCurrent(g_egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, g_egl.context)) {
        s = ft_fail(err, FT_ERR_GPU, "EGL: eglMakeCurrent(surfaceless) failed: 0x%x",
                    (unsigned)eglGetError());
        goto fail_context;
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
    ctx->open = 1;
    return FT_OK;

fail_current:
    (void)eglMakeCurrent(g_egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
fail_context:
    (void)eglDestroyContext(g_egl.display, g_egl.context);
    g_egl.context = EGL_NO_CONTEXT;
fail_initialized:
    (void)eglTerminate(g_egl.display);
fail_display:
    g_egl.display = EGL_NO_DISPLAY;
    return s;
}

void ft_plat_egl_close(ft_gpu_context *ctx)
{
    if (g_egl.display != EGL_NO_DISPLAY) {
        (void)eglMakeCurrent(g_egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (g_egl.context != EGL_NO_CONTEXT) {
            (void)eglDestroyContext(g_egl.display, g_egl.context);
        }
        (void)eglTerminate(g_egl.display);
    }
    g_egl.display = EGL_NO_DISPLAY;
    g_egl.context = EGL_NO_CONTEXT;
    ctx->open = 0;
}
