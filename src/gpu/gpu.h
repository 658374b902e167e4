/* gpu.h - a GPU context as src/ sees it: which backend, what it reported, and
 * the loaded GL table (the backend and display names: core/output.h).
 * platform/ opens and closes it (ft_plat_gpu_*: gpu_select.c picks the
 * backend, platform/gpu_backends.h lists them); everything else in src/ only
 * calls through ctx->gl. */
#ifndef FT_GPU_H
#define FT_GPU_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "core/output.h"
#include "gpu/gl_api.h"

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
