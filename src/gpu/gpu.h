/* gpu.h - a GPU context as src/ sees it: which backend, what it reported, and
 * the loaded GL table. platform/ opens and closes it (gpu_egl.c,
 * gpu_osmesa.c); everything else in src/ only calls through ctx->gl. */
#ifndef FT_GPU_H
#define FT_GPU_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "gpu/gl_api.h"

#define FT_BACKEND_LIST(X)                                           \
    X(FT_BACKEND_EGL_GLES3, "egl-gles3", "EGL surfaceless, OpenGL ES 3.0") \
    X(FT_BACKEND_EGL_GLES2, "egl-gles2", "EGL surfaceless, OpenGL ES 2.0") \
    X(FT_BACKEND_OSMESA, "osmesa", "OSMesa offscreen, desktop GL core + GLSL ES")

typedef enum ft_backend {
#define FT_BACKEND_ENUM(id, name, what) id,
    FT_BACKEND_LIST(FT_BACKEND_ENUM)
#undef FT_BACKEND_ENUM
    FT_BACKEND_COUNT
} ft_backend;

const char *ft_backend_name(ft_backend b);
int ft_backend_from_name(const char *name, ft_backend *out);

/* Where frames are shown. Rendering always goes to the renderer's own FBO;
 * with a display the frame is then drawn onto framebuffer 0 of the display's
 * surface and presented: eglSwapBuffers on X11; on KMS eglSwapBuffers on a
 * GBM surface, then a page flip that present waits for (platform/display_kms.c). */
#define FT_DISPLAY_LIST(X)                                                  \
    X(FT_DISPLAY_NONE, "none", "offscreen only (headless)")                 \
    X(FT_DISPLAY_X11, "x11", "an X11 window (EGL window surface)")          \
    X(FT_DISPLAY_KMS, "kms", "DRM/KMS full screen (EGL on GBM, page flips)")

typedef enum ft_display {
#define FT_DISPLAY_ENUM(id, name, what) id,
    FT_DISPLAY_LIST(FT_DISPLAY_ENUM)
#undef FT_DISPLAY_ENUM
    FT_DISPLAY_COUNT
} ft_display;

#define FT_DISPLAY_DEVICE_MAX 64u    /* "/dev/dri/card0" */
#define FT_DISPLAY_CONNECTOR_MAX 32u /* "HDMI-A-1", "Virtual-1" or a connector id */
#define FT_DISPLAY_MODE_MAX 32u      /* "1024x768", "1024x768@60", "preferred" */

const char *ft_display_name(ft_display d);
int ft_display_from_name(const char *name, ft_display *out);
/* A display as the command line and scene.display spell it: "none", "x11",
 * "kms" or "kms:/dev/dri/cardN" (device written to device[cap], "" when not
 * given). Returns 0 for anything else (also a device path on none/x11, an
 * empty or too long path, or a path not under /dev/). */
int ft_display_parse(const char *text, ft_display *out, char *device, size_t device_cap);

/* A KMS mode request (display.mode): "WxH", "WxH@HZ" or "preferred". */
typedef struct ft_display_mode {
    int preferred;              /* 1: the connector's preferred mode */
    uint32_t width_px, height_px;
    uint32_t refresh_hz;        /* 0 = any */
} ft_display_mode;
/* Returns 0 unless text is one of the forms above (sizes 1..16384, rate 1..1000). */
int ft_display_mode_parse(const char *text, ft_display_mode *out);

typedef struct ft_gpu_desc {
    ft_backend backend;
    ft_display display;
    uint32_t width_px, height_px; /* window size; for KMS the mode size */
    /* KMS only (NULL or "" = default): the card (default: the first
     * /dev/dri/cardN with KMS resources), the connector (name as the kernel
     * spells it, e.g. "HDMI-A-1", or its id; default: the first connected),
     * the mode ("WxH", "WxH@HZ" or "preferred"; default: a mode of the view
     * size, the preferred one if it has that size). The mode's size must be
     * the view size: frames are shown 1:1, never scaled. */
    const char *device;
    const char *connector;
    const char *mode;
} ft_gpu_desc;

#define FT_GPU_TEXT_MAX 128u

typedef struct ft_gpu_context {
    ft_backend backend;
    ft_display display;
    ft_gl gl;
    char version[FT_GPU_TEXT_MAX];  /* GL_VERSION as reported */
    char renderer[FT_GPU_TEXT_MAX]; /* GL_RENDERER as reported */
    int open;
    /* KMS: every present returns when its page flip has completed, so a
     * frame loop that reads the clock after present counts a late flip as
     * its own deadline miss. The last flip's times (monotonic ns, the
     * completion time as the kernel stamped the flip event) and counters;
     * all zero on other displays. */
    uint64_t flip_submit_ns, flip_done_ns;
    uint64_t flips;
    double flip_ms_last, flip_ms_max; /* submit -> completion */
} ft_gpu_context;

/* Implemented in platform/: opens the backend (and the window when
 * desc->display asks for one), makes it current, loads the GL table (ES2 API
 * for egl-gles2, ES3 otherwise). FT_ERR_UNSUPPORTED when the backend or
 * display was left out of this build or does not fit (OSMesa has no window). */
ft_status ft_plat_gpu_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err);
/* Shows what was drawn to framebuffer 0 (eglSwapBuffers; on KMS also the page
 * flip, waited for); a no-op offscreen. */
ft_status ft_plat_gpu_present(ft_gpu_context *ctx, ft_error *err);
void ft_plat_gpu_close(ft_gpu_context *ctx);

#endif
