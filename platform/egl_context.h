/* egl_context.h - the EGL bring-up that the surfaceless/X11 path (gpu_egl.c)
 * and the GBM/KMS path (display_kms.c) share: display, config, OpenGL ES
 * context, optional window surface, the GL table. Written once so the two
 * paths cannot drift apart in what they check, ask for and tear down; each
 * caller keeps only what is its own (the X11 window, the surfaceless checks;
 * DRM, GBM, page flips) and describes the differences in ft_egl_desc.
 * Platform-internal: src/ never includes it. */
#ifndef FT_EGL_CONTEXT_H
#define FT_EGL_CONTEXT_H

#include <EGL/egl.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "gpu/gpu.h"

typedef enum ft_egl_platform {
    FT_EGL_PLATFORM_SURFACELESS, /* Mesa's headless platform: no window, FBOs only */
    FT_EGL_PLATFORM_X11,         /* native display Display *, native window Window * */
    FT_EGL_PLATFORM_GBM          /* native display struct gbm_device *, window struct gbm_surface * */
} ft_egl_platform;

/* What the caller wants; everything else is the same on every platform. */
typedef struct ft_egl_desc {
    ft_egl_platform platform;
    void *native_display; /* unused for FT_EGL_PLATFORM_SURFACELESS */
    /* NULL: no surface (pbuffer configs, surfaceless context; needs
     * EGL_KHR_surfaceless_context); else a window surface on it, and present
     * swaps it. */
    void *native_window;
    int es3;              /* 1: request OpenGL ES 3.0, 0: ES 2.0 */
    EGLint alpha_bits;    /* EGL_ALPHA_SIZE asked for: 8 or 0 */
    /* 0: the first config that matches; else the config's EGL_NATIVE_VISUAL_ID
     * must equal it (a GBM format), named in messages by native_visual_name. */
    uint32_t native_visual;
    const char *native_visual_name;
} ft_egl_desc;

/* Owned by the caller (one per display); FT_EGL_CLOSED when nothing is open. */
typedef struct ft_egl {
    EGLDisplay display;
    EGLContext context;
    EGLSurface surface; /* EGL_NO_SURFACE without a native window */
} ft_egl;

#define FT_EGL_CLOSED {EGL_NO_DISPLAY, EGL_NO_CONTEXT, EGL_NO_SURFACE}

/* FT_OK when this libEGL has the client extension for the platform. Also
 * checked by ft_egl_open; exposed so a caller can fail before it creates the
 * native display (no X11 window appears for a libEGL that cannot use it). */
ft_status ft_egl_check_platform(ft_egl_platform platform, ft_error *err);

/* Initializes EGL on desc's platform, creates the OpenGL ES context (and the
 * window surface when desc has a native window), makes it current and loads
 * ctx->gl (ES 3 or ES 2 API as requested: an ES 2 request may be granted ES
 * 3.2, the API loaded is what was asked for), ctx->version and ctx->renderer.
 * Leaves ctx->backend, display and open to the caller. On failure egl is
 * FT_EGL_CLOSED again: whatever was made is unmade. */
ft_status ft_egl_open(const ft_egl_desc *desc, ft_egl *egl, ft_gpu_context *ctx, ft_error *err);

/* eglSwapBuffers when there is a window surface; FT_OK (nothing to show)
 * without one. */
ft_status ft_egl_present(const ft_egl *egl, ft_error *err);

/* Releases the context, destroys surface and context, terminates the display;
 * safe on a closed egl. Leaves egl FT_EGL_CLOSED. */
void ft_egl_close(ft_egl *egl);

#endif
