/* gpu.h - a GPU context as src/ sees it: which backend, what it reported, and
 * the loaded GL table. platform/ opens and closes it (gpu_egl.c,
 * gpu_osmesa.c); everything else in src/ only calls through ctx->gl. */
#ifndef FT_GPU_H
#define FT_GPU_H

#include "ft_status.h"
#include "gl_api.h"

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
 * with a display the frame is then drawn onto the window surface and
 * presented (eglSwapBuffers). KMS (GBM) comes with the cockpit display path. */
#define FT_DISPLAY_LIST(X)                                     \
    X(FT_DISPLAY_NONE, "none", "offscreen only (headless)")    \
    X(FT_DISPLAY_X11, "x11", "an X11 window (EGL window surface)")

typedef enum ft_display {
#define FT_DISPLAY_ENUM(id, name, what) id,
    FT_DISPLAY_LIST(FT_DISPLAY_ENUM)
#undef FT_DISPLAY_ENUM
    FT_DISPLAY_COUNT
} ft_display;

const char *ft_display_name(ft_display d);
int ft_display_from_name(const char *name, ft_display *out);

typedef struct ft_gpu_desc {
    ft_backend backend;
    ft_display display;
    uint32_t width_px, height_px; /* window size when display != NONE */
} ft_gpu_desc;

#define FT_GPU_TEXT_MAX 128u

typedef struct ft_gpu_context {
    ft_backend backend;
    ft_display display;
    ft_gl gl;
    char version[FT_GPU_TEXT_MAX];  /* GL_VERSION as reported */
    char renderer[FT_GPU_TEXT_MAX]; /* GL_RENDERER as reported */
    int open;
} ft_gpu_context;

/* Implemented in platform/: opens the backend (and the window when
 * desc->display asks for one), makes it current, loads the GL table (ES2 API
 * for egl-gles2, ES3 otherwise). FT_ERR_UNSUPPORTED when the backend or
 * display was left out of this build or does not fit (OSMesa has no window). */
ft_status ft_plat_gpu_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err);
/* Shows what was drawn to framebuffer 0 (eglSwapBuffers); a no-op offscreen. */
ft_status ft_plat_gpu_present(ft_gpu_context *ctx, ft_error *err);
void ft_plat_gpu_close(ft_gpu_context *ctx);

#endif
