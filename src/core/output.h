/* output.h - where a frame goes and through what: the GPU backend and the
 * display, as the scene and the command line name them. Plain names and
 * parsers, no GL: the scene reads these, the GPU context (gpu/gpu.h) opens
 * them. */
#ifndef FT_OUTPUT_H
#define FT_OUTPUT_H

#include <stddef.h>
#include <stdint.h>

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

/* How heights reach the vertex shader (gpu.height_format). */
typedef enum ft_height_format {
    FT_HEIGHT_FORMAT_AUTO = 0,
    FT_HEIGHT_FORMAT_FLOAT,  /* R32F (ES3) or LUMINANCE/FLOAT (ES2 + OES_texture_float) */
    FT_HEIGHT_FORMAT_PACKED  /* RGBA8, 24-bit fixed point over [min, max] */
} ft_height_format;

#endif
