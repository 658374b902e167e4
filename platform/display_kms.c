/* display_kms.c - the cockpit display path: the renderer owns the screen
 * through DRM/KMS, renders with EGL on a GBM surface and page-flips itself
 * (no X11, no Wayland). Written like the kernel's DRM examples and kmscube.
 *
 * Open (all allocation happens here, once):
 *   1. the card: desc->device, or the first /dev/dri/cardN (N < 16) with KMS
 *      resources; we must be (or become) the DRM master;
 *   2. connector (desc->connector or the first connected one), mode (see
 *      ft_kms_pick_mode: its size must be the view size, frames are shown
 *      1:1), a CRTC its encoders can drive; the CRTC's current state is saved;
 *   3. a GBM device and an XRGB8888 scanout gbm_surface of the mode size; EGL
 *      on EGL_PLATFORM_GBM_KHR with a config whose native visual id is
 *      GBM_FORMAT_XRGB8888, an OpenGL ES 3 (or 2) context, the GL table (the
 *      bring-up shared with gpu_egl.c: egl_context.c);
 *   4. the framebuffer ring: black frames are swapped until the surface has
 *      no free buffer, and every buffer it handed out is registered as a DRM
 *      framebuffer in a fixed table (Mesa's GBM surfaces hold at most 4);
 *      the last one is set on the CRTC (drmModeSetCrtc): the mode is set and
 *      the screen is black before the first terrain frame.
 * Present (per frame, no allocation): eglSwapBuffers, lock the front buffer,
 * look up its framebuffer in the table, drmModePageFlip with a flip event,
 * wait for the event (poll, bounded by FT_KMS_FLIP_TIMEOUT_MS), release the
 * buffer that was on screen. Present therefore returns when the frame is on
 * screen: the frame loop's clock reading after present includes the flip, so
 * a flip that completes after the frame's period is that frame's deadline
 * miss (live.c), and the heartbeat it toggles after present means "shown".
 * The emulated GPUs have no vblank (flip events arrive when the flip is done);
 * on real hardware the flip completes at the next vblank. Pacing is the
 * frame loop's, on the monotonic clock; DRM event times are monotonic too.
 * Legacy KMS only (SetCrtc + PageFlip): every KMS driver has it; an atomic
 * commit would add nothing for one primary plane with a fixed mode.
 * Close (also after SIGINT/SIGTERM, which end `fixterrain run`'s loop): wait
 * for a pending flip, put the saved CRTC back (framebuffer, position, mode:
 * the console comes back), remove our framebuffers, tear down EGL and GBM,
 * close the card. One display per process (the state is static). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <gbm.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include "display_kms.h"
#include "egl_context.h"
#include "gpu_backends.h"
#include "core/platform_api.h"
#include "gpu/gpu.h"

#ifndef DRM_FORMAT_MOD_INVALID
#define DRM_FORMAT_MOD_INVALID 0x00ffffffffffffffULL
#endif
#ifndef DRM_FORMAT_MOD_LINEAR
#define DRM_FORMAT_MOD_LINEAR 0ULL
#endif

#define FT_KMS_CARDS_MAX 16u        /* /dev/dri/card0..15 when no device is named */
#define FT_KMS_FB_MAX 8u            /* framebuffer table (Mesa GBM surfaces: <= 4 buffers) */
#define FT_KMS_FLIP_TIMEOUT_MS 1000 /* a flip that takes longer is an error */

typedef struct kms_fb {
    struct gbm_bo *bo;
    uint32_t fb_id;
} kms_fb;

static struct {
    int fd;
    char path[FT_DISPLAY_DEVICE_MAX];
    char connector_name[FT_DISPLAY_CONNECTOR_MAX];
    uint32_t connector_id, crtc_id;
    drmModeModeInfo mode;
    drmModeCrtc *saved_crtc; /* libdrm allocation at open, freed at close */
    int crtc_set;            /* our framebuffer is (or was) on the CRTC */
    int takes_modifiers;     /* DRM_CAP_ADDFB2_MODIFIERS */
    int monotonic_events;    /* DRM_CAP_TIMESTAMP_MONOTONIC */
    struct gbm_device *gbm;
    struct gbm_surface *surface;
    ft_egl egl; /* on the GBM device, window surface on surface */
    kms_fb fbs[FT_KMS_FB_MAX];
    uint32_t fb_count;
    struct gbm_bo *front; /* locked, on screen */
    volatile int flip_pending;
    uint64_t flip_event_ns;
    uint64_t open_ns;
    uint32_t late_registrations; /* buffers first seen after open (expected 0) */
    double flip_ms_sum;
} g_kms = {.fd = -1, .egl = FT_EGL_CLOSED};

/* ---- decisions without a device (display_kms.h) --------------------------- */

void ft_kms_connector_name(const drmModeConnector *c, char *buf, size_t cap)
{
    const char *type = drmModeGetConnectorTypeName(c->connector_type);
    (void)snprintf(buf, cap, "%s-%u", type != NULL ? type : "Unknown", c->connector_type_id);
}

static const char *connection_word(drmModeConnection s)
{
    switch (s) {
    case DRM_MODE_CONNECTED: return "connected";
    case DRM_MODE_DISCONNECTED: return "disconnected";
    default: return "unknown";
    }
}

/* Appends "NAME: status" for every connector, as far as it fits. */
static void list_connectors(drmModeConnector *const *conns, uint32_t n, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (uint32_t i = 0; i < n && used + 1u < cap; ++i) {
        char name[FT_DISPLAY_CONNECTOR_MAX];
        if (conns[i] == NULL) {
            continue;
        }
        ft_kms_connector_name(conns[i], name, sizeof name);
        int w = snprintf(buf + used, cap - used, "%s%s: %s", used ? ", " : "", name,
                         connection_word(conns[i]->connection));
        if (w < 0) {
            break;
        }
        used += (size_t)w;
    }
    if (used >= cap && cap > 4u) {
        memcpy(buf + cap - 4u, "...", 4u);
    }
}

int ft_kms_pick_connector(drmModeConnector *const *conns, uint32_t n, const char *want,
                          char *why, size_t why_cap)
{
    char list[160];
    list_connectors(conns, n, list, sizeof list);
    if (want == NULL || want[0] == '\0') {
        for (uint32_t i = 0; i < n; ++i) {
            if (conns[i] != NULL && conns[i]->connection == DRM_MODE_CONNECTED &&
                conns[i]->count_modes > 0) {
                return (int)i;
            }
        }
        (void)snprintf(why, why_cap,
                       "no connected connector with modes: connect a display, or name one "
                       "with display.connector; connectors: %s",
                       n ? list : "none (the card has no connectors)");
        return -1;
    }
    char *end = NULL;
    unsigned long id = strtoul(want, &end, 10);
    const int by_id = (end != want && *end == '\0');
    for (uint32_t i = 0; i < n; ++i) {
        char name[FT_DISPLAY_CONNECTOR_MAX];
        if (conns[i] == NULL) {
            continue;
        }
        ft_kms_connector_name(conns[i], name, sizeof name);
        if (by_id ? (conns[i]->connector_id != id) : (strcasecmp(name, want) != 0)) {
            continue;
        }
        if (conns[i]->connection == DRM_MODE_DISCONNECTED ||
            (conns[i]->connection != DRM_MODE_CONNECTED && conns[i]->count_modes <= 0)) {
            (void)snprintf(why, why_cap, "connector %s (id %u) is %s", name,
                           conns[i]->connector_id, connection_word(conns[i]->connection));
            return -1;
        }
        if (conns[i]->count_modes <= 0) {
            (void)snprintf(why, why_cap, "connector %s (id %u) offers no modes", name,
                           conns[i]->connector_id);
            return -1;
        }
        return (int)i;
    }
    (void)snprintf(why, why_cap, "no connector '%s' (display.connector) on this card; "
                   "connectors: %s", want, n ? list : "none");
    return -1;
}

static void list_modes(const drmModeConnector *c, char *buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < c->count_modes && used + 1u < cap; ++i) {
        const drmModeModeInfo *m = &c->modes[i];
        int w = snprintf(buf + used, cap - used, "%s%ux%u@%u%s", used ? " " : "", m->hdisplay,
                         m->vdisplay, m->vrefresh,
                         (m->type & DRM_MODE_TYPE_PREFERRED) ? "*" : "");
        if (w < 0) {
            break;
        }
        used += (size_t)w;
    }
    if (used >= cap && cap > 4u) {
        memcpy(buf + cap - 4u, "...", 4u);
    }
}

int ft_kms_pick_mode(const drmModeConnector *c, uint32_t view_w, uint32_t view_h,
                     const char *want, char *why, size_t why_cap)
{
    char name[FT_DISPLAY_CONNECTOR_MAX];
    char modes[120];
    ft_display_mode m;
    int pick = -1;
    ft_kms_connector_name(c, name, sizeof name);
    list_modes(c, modes, sizeof modes);
    if (want == NULL || want[0] == '\0') {
        m.preferred = 0;
        m.width_px = view_w;
        m.height_px = view_h;
        m.refresh_hz = 0;
    } else if (!ft_display_mode_parse(want, &m)) {
        (void)snprintf(why, why_cap, "display.mode '%s': expected WxH, WxH@HZ or preferred",
                       want);
        return -1;
    }
    if (m.preferred) {
        for (int i = 0; i < c->count_modes && pick < 0; ++i) {
            if (c->modes[i].type & DRM_MODE_TYPE_PREFERRED) {
                pick = i;
            }
        }
        if (pick < 0 && c->count_modes > 0) {
            pick = 0; /* no mode flagged: the kernel lists the best first */
        }
    } else {
        for (int pass = 0; pass < 2 && pick < 0; ++pass) {
            for (int i = 0; i < c->count_modes && pick < 0; ++i) {
                const drmModeModeInfo *mi = &c->modes[i];
                if (mi->hdisplay != m.width_px || mi->vdisplay != m.height_px ||
                    (m.refresh_hz != 0u && mi->vrefresh != m.refresh_hz)) {
                    continue;
                }
                /* pass 0: the preferred mode if it matches; pass 1: first match */
                if (pass == 1 || (mi->type & DRM_MODE_TYPE_PREFERRED)) {
                    pick = i;
                }
            }
        }
    }
    if (pick < 0) {
        if (m.preferred) {
            (void)snprintf(why, why_cap, "connector %s offers no modes", name);
        } else if (m.refresh_hz != 0u) {
            (void)snprintf(why, why_cap, "connector %s offers no %ux%u@%u mode; modes: %s", name,
                           m.width_px, m.height_px, m.refresh_hz, modes);
        } else {
            (void)snprintf(why, why_cap,
                           "connector %s offers no %ux%u mode for the %ux%u view; frames are "
                           "shown 1:1, so set the view size (--size, view.width_px/height_px) "
                           "to one of its modes (* = preferred): %s",
                           name, m.width_px, m.height_px, view_w, view_h, modes);
        }
        return -1;
    }
    if (c->modes[pick].hdisplay != view_w || c->modes[pick].vdisplay != view_h) {
        (void)snprintf(why, why_cap,
                       "mode %ux%u@%u on %s is not the view size %ux%u: frames are shown 1:1 "
                       "(never scaled), so set the view size (--size %ux%u) or display.mode",
                       c->modes[pick].hdisplay, c->modes[pick].vdisplay, c->modes[pick].vrefresh,
                       name, view_w, view_h, c->modes[pick].hdisplay, c->modes[pick].vdisplay);
        return -1;
    }
    return pick;
}

ft_kms_fb_call ft_kms_fb_call_for(uint64_t modifier, int driver_takes_modifiers)
{
    if (modifier == DRM_FORMAT_MOD_INVALID) {
        return FT_KMS_FB_PLAIN;
    }
    if (driver_takes_modifiers) {
        return FT_KMS_FB_WITH_MODIFIERS;
    }
    return (modifier == DRM_FORMAT_MOD_LINEAR) ? FT_KMS_FB_PLAIN : FT_KMS_FB_IMPOSSIBLE;
}

/* ---- the device ------------------------------------------------------------ */

static ft_status open_error(const char *path, int e, ft_error *err)
{
    const char *hint = "";
    if (e == ENOENT) {
        hint = " (no such DRM card: is the display driver loaded? see ls /dev/dri)";
    } else if (e == EACCES || e == EPERM) {
        hint = " (run as root or as a member of the 'video' group)";
    }
    return ft_fail(err, FT_ERR_UNSUPPORTED, "KMS: cannot open %s: %s%s", path, strerror(e), hint);
}

/* Opens desc->device, or the first /dev/dri/cardN with CRTCs and connectors.
 * On success g_kms.fd/path are set and *res holds the card's resources. */
static ft_status open_card(const char *device, drmModeRes **res, ft_error *err)
{
    if (device != NULL && device[0] != '\0') {
        int fd = open(device, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            return open_error(device, errno, err);
        }
        *res = drmModeGetResources(fd);
        if (*res == NULL || (*res)->count_crtcs <= 0 || (*res)->count_connectors <= 0) {
            int e = errno;
            if (*res != NULL) {
                drmModeFreeResources(*res);
                *res = NULL;
            }
            (void)close(fd);
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "KMS: %s has no display outputs (drmModeGetResources: %s): a "
                           "render-only GPU? name the display controller's card",
                           device, e ? strerror(e) : "no CRTCs or connectors");
        }
        g_kms.fd = fd;
        (void)snprintf(g_kms.path, sizeof g_kms.path, "%s", device);
        return FT_OK;
    }
    char seen[160];
    size_t used = 0;
    seen[0] = '\0';
    for (uint32_t i = 0; i < FT_KMS_CARDS_MAX; ++i) {
        char path[32];
        (void)snprintf(path, sizeof path, "/dev/dri/card%u", i);
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            if (errno != ENOENT && used + 1u < sizeof seen) {
                int w = snprintf(seen + used, sizeof seen - used, "%s%s: %s", used ? ", " : "",
                                 path, strerror(errno));
                used += (w > 0) ? (size_t)w : 0u;
            }
            continue;
        }
        *res = drmModeGetResources(fd);
        if (*res != NULL && (*res)->count_crtcs > 0 && (*res)->count_connectors > 0) {
            g_kms.fd = fd;
            (void)snprintf(g_kms.path, sizeof g_kms.path, "%s", path);
            return FT_OK;
        }
        if (*res != NULL) {
            drmModeFreeResources(*res);
            *res = NULL;
        }
        if (used + 1u < sizeof seen) {
            int w = snprintf(seen + used, sizeof seen - used, "%s%s: no display outputs",
                             used ? ", " : "", path);
            used += (w > 0) ? (size_t)w : 0u;
        }
        (void)close(fd);
    }
    return ft_fail(err, FT_ERR_UNSUPPORTED,
                   "KMS: no DRM card with display outputs in /dev/dri/card0..%u (%s); name one "
                   "with --display kms:/dev/dri/cardN",
                   FT_KMS_CARDS_MAX - 1u, used ? seen : "none present");
}

static ft_status become_master(ft_error *err)
{
    if (drmIsMaster(g_kms.fd)) {
        return FT_OK;
    }
    if (drmSetMaster(g_kms.fd) != 0) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "KMS: %s: not the DRM master and cannot become it (drmSetMaster: %s): "
                       "another process (X, a Wayland compositor, another fixterrain) owns "
                       "the display",
                       g_kms.path, strerror(errno));
    }
    return FT_OK;
}

/* A CRTC for the connector: its encoder's current CRTC, else the first CRTC
 * one of its encoders can drive. */
static ft_status find_crtc(const drmModeRes *res, const drmModeConnector *conn, ft_error *err)
{
    if (conn->encoder_id != 0u) {
        drmModeEncoder *enc = drmModeGetEncoder(g_kms.fd, conn->encoder_id);
        if (enc != NULL) {
            uint32_t crtc = enc->crtc_id;
            drmModeFreeEncoder(enc);
            if (crtc != 0u) {
                g_kms.crtc_id = crtc;
                return FT_OK;
            }
        }
    }
    for (int e = 0; e < conn->count_encoders; ++e) {
        drmModeEncoder *enc = drmModeGetEncoder(g_kms.fd, conn->encoders[e]);
        if (enc == NULL) {
            continue;
        }
        const uint32_t possible = enc->possible_crtcs;
        drmModeFreeEncoder(enc);
        for (int c = 0; c < res->count_crtcs && c < 32; ++c) {
            if (possible & (1u << c)) {
                g_kms.crtc_id = res->crtcs[c];
                return FT_OK;
            }
        }
    }
    return ft_fail(err, FT_ERR_UNSUPPORTED, "KMS: %s: no CRTC can drive connector %s",
                   g_kms.path, g_kms.connector_name);
}

static ft_status pick_output(const ft_gpu_desc *desc, const drmModeRes *res, ft_error *err)
{
    drmModeConnector *conns[FT_KMS_CONNECTORS_MAX];
    char why[FT_ERROR_TEXT_MAX - 48];
    uint32_t n = 0;
    ft_status s = FT_OK;
    for (int i = 0; i < res->count_connectors && n < FT_KMS_CONNECTORS_MAX; ++i) {
        conns[n++] = drmModeGetConnector(g_kms.fd, res->connectors[i]); /* NULL: skipped */
    }
    int ci = ft_kms_pick_connector(conns, n, desc->connector, why, sizeof why);
    if (ci < 0) {
        s = ft_fail(err, FT_ERR_UNSUPPORTED, "KMS: %s: %s", g_kms.path, why);
        goto done;
    }
    const drmModeConnector *conn = conns[ci];
    ft_kms_connector_name(conn, g_kms.connector_name, sizeof g_kms.connector_name);
    g_kms.connector_id = conn->connector_id;
    int mi = ft_kms_pick_mode(conn, desc->width_px, desc->height_px, desc->mode, why, sizeof why);
    if (mi < 0) {
        s = ft_fail(err, FT_ERR_CONFIG, "KMS: %s", why);
        goto done;
    }
    g_kms.mode = conn->modes[mi];
    s = find_crtc(res, conn, err);
done:
    for (uint32_t i = 0; i < n; ++i) {
        if (conns[i] != NULL) {
            drmModeFreeConnector(conns[i]);
        }
    }
    return s;
}

/* EGL on the GBM device, rendering into the scanout surface. */
static ft_status open_egl(ft_backend backend, ft_gpu_context *ctx, ft_error *err)
{
    /* Window configs with 8-bit RGB and no alpha; the one whose native visual
     * is the scanout format (XRGB8888) renders into buffers KMS can show. */
    const ft_egl_desc egl_desc = {.platform = FT_EGL_PLATFORM_GBM,
                                  .native_display = g_kms.gbm,
                                  .native_window = g_kms.surface,
                                  .es3 = (backend == FT_BACKEND_EGL_GLES3),
                                  .alpha_bits = 0,
                                  .native_visual = GBM_FORMAT_XRGB8888,
                                  .native_visual_name = "GBM_FORMAT_XRGB8888"};
    return ft_egl_open(&egl_desc, &g_kms.egl, ctx, err);
}

/* The table entry of bo, registering it (drmModeAddFB2[WithModifiers]) when
 * it is new and there is room. NULL with err set otherwise. */
static const kms_fb *fb_for_bo(struct gbm_bo *bo, ft_error *err)
{
    for (uint32_t i = 0; i < g_kms.fb_count; ++i) {
        if (g_kms.fbs[i].bo == bo) {
            return &g_kms.fbs[i];
        }
    }
    if (g_kms.fb_count >= FT_KMS_FB_MAX) {
        (void)ft_fail(err, FT_ERR_GPU, "KMS: GBM handed out more than %u buffers",
                      FT_KMS_FB_MAX);
        return NULL;
    }
    uint32_t handles[4] = {0}, pitches[4] = {0}, offsets[4] = {0};
    uint64_t modifiers[4] = {0};
    const uint64_t modifier = gbm_bo_get_modifier(bo);
    const int planes = gbm_bo_get_plane_count(bo);
    if (planes < 1 || planes > 4) {
        (void)ft_fail(err, FT_ERR_GPU, "KMS: GBM buffer with %d planes", planes);
        return NULL;
    }
    for (int p = 0; p < planes; ++p) {
        handles[p] = gbm_bo_get_handle_for_plane(bo, p).u32;
        pitches[p] = gbm_bo_get_stride_for_plane(bo, p);
        offsets[p] = gbm_bo_get_offset(bo, p);
        modifiers[p] = modifier;
    }
    const uint32_t w = gbm_bo_get_width(bo), h = gbm_bo_get_height(bo);
    const uint32_t format = gbm_bo_get_format(bo);
    uint32_t fb_id = 0;
    int rc;
    switch (ft_kms_fb_call_for(modifier, g_kms.takes_modifiers)) {
    case FT_KMS_FB_PLAIN:
        rc = drmModeAddFB2(g_kms.fd, w, h, format, handles, pitches, offsets, &fb_id, 0);
        break;
    case FT_KMS_FB_WITH_MODIFIERS:
        rc = drmModeAddFB2WithModifiers(g_kms.fd, w, h, format, handles, pitches, offsets,
                                        modifiers, &fb_id, DRM_MODE_FB_MODIFIERS);
        break;
    default:
        (void)ft_fail(err, FT_ERR_UNSUPPORTED,
                      "KMS: GBM buffer has modifier 0x%llx but %s takes no modifiers",
                      (unsigned long long)modifier, g_kms.path);
        return NULL;
    }
    if (rc != 0) {
        (void)ft_fail(err, FT_ERR_GPU,
                      "KMS: drmModeAddFB2 %ux%u format 0x%08x modifier 0x%llx: %s", w, h,
                      format, (unsigned long long)modifier, strerror(errno));
        return NULL;
    }
    g_kms.fbs[g_kms.fb_count].bo = bo;
    g_kms.fbs[g_kms.fb_count].fb_id = fb_id;
    return &g_kms.fbs[g_kms.fb_count++];
}

static void on_page_flip(int fd, unsigned int frame, unsigned int sec, unsigned int usec,
                         void *data)
{
    (void)fd;
    (void)frame;
    (void)data;
    g_kms.flip_event_ns = g_kms.monotonic_events
                              ? (uint64_t)sec * 1000000000ull + (uint64_t)usec * 1000ull
                              : ft_plat_monotonic_ns();
    g_kms.flip_pending = 0;
}

/* Waits for the pending flip's event, at most FT_KMS_FLIP_TIMEOUT_MS
 * (signals only restart the wait: the deadline is absolute). */
static ft_status wait_flip(ft_error *err)
{
    drmEventContext ev;
    memset(&ev, 0, sizeof ev);
    ev.version = 2;
    ev.page_flip_handler = on_page_flip;
    const uint64_t deadline = ft_plat_monotonic_ns() + (uint64_t)FT_KMS_FLIP_TIMEOUT_MS * 1000000u;
    while (g_kms.flip_pending) {
        const uint64_t now = ft_plat_monotonic_ns();
        if (now >= deadline) {
            return ft_fail(err, FT_ERR_GPU, "KMS: page flip on CRTC %u did not complete in %d ms",
                           g_kms.crtc_id, FT_KMS_FLIP_TIMEOUT_MS);
        }
        struct pollfd pfd = {g_kms.fd, POLLIN, 0};
        int timeout_ms = (int)((deadline - now + 999999u) / 1000000u);
        int rc = poll(&pfd, 1, timeout_ms);
        if (rc < 0 && errno != EINTR) {
            return ft_fail(err, FT_ERR_GPU, "KMS: poll on %s: %s", g_kms.path, strerror(errno));
        }
        if (rc > 0 && drmHandleEvent(g_kms.fd, &ev) != 0) {
            return ft_fail(err, FT_ERR_GPU, "KMS: reading the flip event: %s", strerror(errno));
        }
    }
    return FT_OK;
}

/* Swaps black frames until the surface has no free buffer, registering a
 * framebuffer for each; sets the mode with the last one and releases the
 * others. Afterwards every buffer the surface will hand out has its entry. */
static ft_status fill_ring_and_set_mode(ft_gpu_context *ctx, ft_error *err)
{
    struct gbm_bo *locked[FT_KMS_FB_MAX];
    uint32_t n = 0;
    ft_status s = FT_OK;
    const ft_gl *gl = &ctx->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->Viewport(0, 0, (GLsizei)g_kms.mode.hdisplay, (GLsizei)g_kms.mode.vdisplay);
    gl->ClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    while (n < FT_KMS_FB_MAX && (n == 0u || gbm_surface_has_free_buffers(g_kms.surface))) {
        gl->Clear(GL_COLOR_BUFFER_BIT);
        s = ft_egl_present(&g_kms.egl, err);
        if (s != FT_OK) {
            break;
        }
        struct gbm_bo *bo = gbm_surface_lock_front_buffer(g_kms.surface);
        if (bo == NULL) {
            s = ft_fail(err, FT_ERR_GPU, "GBM: gbm_surface_lock_front_buffer failed");
            break;
        }
        locked[n++] = bo;
        if (fb_for_bo(bo, err) == NULL) {
            s = FT_ERR_GPU;
            break;
        }
    }
    if (s == FT_OK) {
        const kms_fb *fb = fb_for_bo(locked[n - 1u], err);
        uint32_t conn = g_kms.connector_id;
        if (drmModeSetCrtc(g_kms.fd, g_kms.crtc_id, fb->fb_id, 0, 0, &conn, 1, &g_kms.mode) !=
            0) {
            s = ft_fail(err, FT_ERR_GPU, "KMS: drmModeSetCrtc(CRTC %u, %s, %s) failed: %s",
                        g_kms.crtc_id, g_kms.connector_name, g_kms.mode.name, strerror(errno));
        } else {
            g_kms.crtc_set = 1;
            g_kms.front = locked[n - 1u];
            n -= 1u;
        }
    }
    for (uint32_t i = 0; i < n; ++i) {
        gbm_surface_release_buffer(g_kms.surface, locked[i]);
    }
    return s;
}

ft_status ft_plat_kms_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err)
{
    drmModeRes *res = NULL;
    uint64_t cap = 0;
    if (g_kms.fd >= 0) {
        return ft_fail(err, FT_ERR_ARG, "KMS: the display is already open");
    }
    g_kms.open_ns = ft_plat_monotonic_ns();
    ft_status s = open_card(desc->device, &res, err);
    if (s != FT_OK) {
        return s;
    }
    s = become_master(err);
    if (s == FT_OK) {
        s = pick_output(desc, res, err);
    }
    drmModeFreeResources(res);
    if (s != FT_OK) {
        goto fail;
    }
    g_kms.takes_modifiers = drmGetCap(g_kms.fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 && cap;
    cap = 0;
    g_kms.monotonic_events = drmGetCap(g_kms.fd, DRM_CAP_TIMESTAMP_MONOTONIC, &cap) == 0 && cap;
    g_kms.saved_crtc = drmModeGetCrtc(g_kms.fd, g_kms.crtc_id);
    if (g_kms.saved_crtc == NULL) {
        s = ft_fail(err, FT_ERR_GPU, "KMS: drmModeGetCrtc(%u): %s", g_kms.crtc_id,
                    strerror(errno));
        goto fail;
    }
    g_kms.gbm = gbm_create_device(g_kms.fd);
    if (g_kms.gbm == NULL) {
        s = ft_fail(err, FT_ERR_GPU, "GBM: gbm_create_device(%s) failed", g_kms.path);
        goto fail;
    }
    g_kms.surface = gbm_surface_create(g_kms.gbm, g_kms.mode.hdisplay, g_kms.mode.vdisplay,
                                       GBM_FORMAT_XRGB8888,
                                       GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (g_kms.surface == NULL) {
        s = ft_fail(err, FT_ERR_GPU, "GBM: no %ux%u XRGB8888 scanout surface on %s: %s",
                    g_kms.mode.hdisplay, g_kms.mode.vdisplay, g_kms.path, strerror(errno));
        goto fail;
    }
    s = open_egl(desc->backend, ctx, err);
    if (s != FT_OK) {
        goto fail;
    }
    s = fill_ring_and_set_mode(ctx, err);
    if (s != FT_OK) {
        goto fail;
    }
    ctx->backend = desc->backend;
    ctx->display = FT_DISPLAY_KMS;
    ctx->flips = 0;
    ctx->flip_submit_ns = ctx->flip_done_ns = 0;
    ctx->flip_ms_last = ctx->flip_ms_max = 0.0;
    ctx->open = 1;
    g_kms.flip_ms_sum = 0.0;
    g_kms.late_registrations = 0;
    (void)fprintf(stderr,
                  "kms: %s: connector %s (id %u), CRTC %u, mode %s@%u, XRGB8888 %s, %u "
                  "framebuffers, %s; set in %.1f ms\n",
                  g_kms.path, g_kms.connector_name, g_kms.connector_id, g_kms.crtc_id,
                  g_kms.mode.name, g_kms.mode.vrefresh,
                  g_kms.takes_modifiers ? "(driver takes modifiers)" : "(no modifiers)",
                  g_kms.fb_count, ctx->renderer,
                  (double)(ft_plat_monotonic_ns() - g_kms.open_ns) * 1e-6);
    return FT_OK;

fail:
    ft_plat_kms_close(ctx);
    return s;
}

ft_status ft_plat_kms_present(ft_gpu_context *ctx, ft_error *err)
{
    ft_status s = ft_egl_present(&g_kms.egl, err);
    if (s != FT_OK) {
        return s;
    }
    struct gbm_bo *bo = gbm_surface_lock_front_buffer(g_kms.surface);
    if (bo == NULL) {
        return ft_fail(err, FT_ERR_GPU, "GBM: gbm_surface_lock_front_buffer failed");
    }
    const uint32_t known = g_kms.fb_count;
    const kms_fb *fb = fb_for_bo(bo, err);
    if (fb == NULL) {
        gbm_surface_release_buffer(g_kms.surface, bo);
        return FT_ERR_GPU;
    }
    g_kms.late_registrations += (g_kms.fb_count != known);
    const uint64_t t_submit = ft_plat_monotonic_ns();
    g_kms.flip_pending = 1;
    if (drmModePageFlip(g_kms.fd, g_kms.crtc_id, fb->fb_id, DRM_MODE_PAGE_FLIP_EVENT, NULL) !=
        0) {
        int e = errno;
        g_kms.flip_pending = 0;
        gbm_surface_release_buffer(g_kms.surface, bo);
        return ft_fail(err, FT_ERR_GPU, "KMS: drmModePageFlip(CRTC %u, fb %u): %s",
                       g_kms.crtc_id, fb->fb_id, strerror(e));
    }
    s = wait_flip(err);
    if (s != FT_OK) {
        /* still pending: keep bo locked (it may yet be scanned out); close
         * waits again before it restores the CRTC */
        return s;
    }
    gbm_surface_release_buffer(g_kms.surface, g_kms.front);
    g_kms.front = bo;
    const uint64_t t_done = g_kms.flip_event_ns > t_submit ? g_kms.flip_event_ns : t_submit;
    ctx->flip_submit_ns = t_submit;
    ctx->flip_done_ns = t_done;
    ctx->flip_ms_last = (double)(t_done - t_submit) * 1e-6;
    if (ctx->flip_ms_last > ctx->flip_ms_max) {
        ctx->flip_ms_max = ctx->flip_ms_last;
    }
    g_kms.flip_ms_sum += ctx->flip_ms_last;
    ctx->flips += 1u;
    if (ctx->flips == 1u) {
        (void)fprintf(stderr, "kms: first frame on screen %.1f ms after open (flip %.2f ms)\n",
                      (double)(t_done - g_kms.open_ns) * 1e-6, ctx->flip_ms_last);
    }
    return FT_OK;
}

void ft_plat_kms_close(ft_gpu_context *ctx)
{
    ft_error err;
    if (g_kms.fd >= 0 && g_kms.flip_pending) {
        if (wait_flip(&err) != FT_OK) {
            (void)fprintf(stderr, "kms: %s\n", err.text);
        }
    }
    if (g_kms.fd >= 0 && g_kms.crtc_set && g_kms.saved_crtc != NULL) {
        drmModeCrtc *c = g_kms.saved_crtc;
        uint32_t conn = g_kms.connector_id;
        int rc;
        if (c->buffer_id != 0u && c->mode_valid) {
            rc = drmModeSetCrtc(g_kms.fd, c->crtc_id, c->buffer_id, c->x, c->y, &conn, 1,
                                &c->mode);
        } else {
            rc = drmModeSetCrtc(g_kms.fd, c->crtc_id, 0, 0, 0, NULL, 0, NULL);
        }
        if (rc != 0) {
            (void)fprintf(stderr, "kms: restoring CRTC %u (fb %u) failed: %s\n", c->crtc_id,
                          c->buffer_id, strerror(errno));
        } else {
            (void)fprintf(stderr,
                          "kms: restored CRTC %u (fb %u, %ux%u); %llu flips, flip time mean "
                          "%.2f ms, max %.2f ms; %u framebuffers, %u registered after open\n",
                          c->crtc_id, c->buffer_id, c->mode.hdisplay, c->mode.vdisplay,
                          (unsigned long long)ctx->flips,
                          ctx->flips ? g_kms.flip_ms_sum / (double)ctx->flips : 0.0,
                          ctx->flip_ms_max, g_kms.fb_count, g_kms.late_registrations);
        }
        g_kms.crtc_set = 0;
    }
    for (uint32_t i = 0; i < g_kms.fb_count; ++i) {
        (void)drmModeRmFB(g_kms.fd, g_kms.fbs[i].fb_id);
        g_kms.fbs[i].bo = NULL;
        g_kms.fbs[i].fb_id = 0;
    }
    g_kms.fb_count = 0;
    if (g_kms.front != NULL) {
        gbm_surface_release_buffer(g_kms.surface, g_kms.front);
        g_kms.front = NULL;
    }
    ft_egl_close(&g_kms.egl);
    if (g_kms.surface != NULL) {
        gbm_surface_destroy(g_kms.surface);
        g_kms.surface = NULL;
    }
    if (g_kms.gbm != NULL) {
        gbm_device_destroy(g_kms.gbm);
        g_kms.gbm = NULL;
    }
    if (g_kms.saved_crtc != NULL) {
        drmModeFreeCrtc(g_kms.saved_crtc);
        g_kms.saved_crtc = NULL;
    }
    if (g_kms.fd >= 0) {
        (void)close(g_kms.fd); /* drops DRM master */
        g_kms.fd = -1;
    }
    g_kms.flip_pending = 0;
    ctx->open = 0;
}
