/* gpu_backends.h - the entry points of the GPU backends and displays inside
 * platform/, declared once so caller and implementation are checked against
 * the same prototype. gpu_select.c dispatches ft_plat_gpu_* (src/gpu/gpu.h)
 * to them:
 *   ft_plat_egl_*     gpu_egl.c     EGL surfaceless (offscreen) or an X11 window
 *   ft_plat_kms_*     display_kms.c EGL on GBM, full screen through DRM/KMS
 *   ft_plat_osmesa_*  gpu_osmesa.c  OSMesa offscreen
 *   ft_x11_*          display_x11.c the X11 window gpu_egl.c renders into
 * Platform-internal: src/ never includes it (src/ declares the interface,
 * platform/ implements it). No GL header here, the structs are named by tag:
 * display_x11.c includes it too, and Xlib's headers never meet the GL ones. */
#ifndef FT_GPU_BACKENDS_H
#define FT_GPU_BACKENDS_H

#include <stdint.h>

#include "core/ft_status.h"
#include "core/output.h"

struct ft_gpu_desc;
struct ft_gpu_context;

ft_status ft_plat_egl_open(const struct ft_gpu_desc *desc, struct ft_gpu_context *ctx,
                           ft_error *err);
ft_status ft_plat_egl_present(struct ft_gpu_context *ctx, ft_error *err);
void ft_plat_egl_close(struct ft_gpu_context *ctx);

ft_status ft_plat_kms_open(const struct ft_gpu_desc *desc, struct ft_gpu_context *ctx,
                           ft_error *err);
ft_status ft_plat_kms_present(struct ft_gpu_context *ctx, ft_error *err);
void ft_plat_kms_close(struct ft_gpu_context *ctx);

ft_status ft_plat_osmesa_open(ft_backend backend, struct ft_gpu_context *ctx, ft_error *err);
void ft_plat_osmesa_close(struct ft_gpu_context *ctx);

/* A fixed-size window of width_px x height_px; *native_display is the
 * Display *, *native_window a Window * (what EGL's X11 platform takes). */
ft_status ft_x11_open(uint32_t width_px, uint32_t height_px, void **native_display,
                      void **native_window, ft_error *err);
void ft_x11_close(void);

#endif
