/* display_kms.h - the parts of platform/display_kms.c that need no device:
 * connector, mode and framebuffer-format decisions on libdrm's own structs.
 * Declared here so tests/test_kms_pick.c checks them on the host, where
 * there is no DRM device. Each writes one sentence into why[] on failure. */
#ifndef FT_DISPLAY_KMS_H
#define FT_DISPLAY_KMS_H

#include <stddef.h>
#include <stdint.h>
#include <xf86drmMode.h>

#define FT_KMS_CONNECTORS_MAX 32u /* connectors looked at per card */

/* "HDMI-A-1", "Virtual-1": the kernel's name (type name - type id). */
void ft_kms_connector_name(const drmModeConnector *c, char *buf, size_t cap);

/* Index into conns of the connector to drive, or -1. want: NULL or "" = the
 * first connected connector that has modes; a name (case-insensitive) or a
 * decimal connector id = that one, which must be connected (or report
 * "unknown" and have modes). NULL entries in conns are skipped. */
int ft_kms_pick_connector(drmModeConnector *const *conns, uint32_t n, const char *want,
                          char *why, size_t why_cap);

/* Index into c->modes of the mode to set, or -1. want: NULL or "" = a mode
 * of exactly view_w x view_h (the preferred mode if it has that size, else
 * the kernel's first listed, i.e. its highest refresh); "preferred"; "WxH"
 * or "WxH@HZ". The chosen mode's size must be the view size (frames are
 * shown 1:1), else -1 with the offered modes in why. */
int ft_kms_pick_mode(const drmModeConnector *c, uint32_t view_w, uint32_t view_h,
                     const char *want, char *why, size_t why_cap);

/* How to register a GBM buffer as a DRM framebuffer. GBM reports
 * DRM_FORMAT_MOD_INVALID when the allocation has no explicit modifier, and
 * drivers without modifier support (bochs) reject the modifiers flag even
 * for LINEAR: plain drmModeAddFB2 then. */
typedef enum ft_kms_fb_call {
    FT_KMS_FB_PLAIN,          /* drmModeAddFB2 (implicit layout: linear here) */
    FT_KMS_FB_WITH_MODIFIERS, /* drmModeAddFB2WithModifiers + DRM_MODE_FB_MODIFIERS */
    FT_KMS_FB_IMPOSSIBLE      /* a tiled/compressed buffer the driver cannot take */
} ft_kms_fb_call;
ft_kms_fb_call ft_kms_fb_call_for(uint64_t modifier, int driver_takes_modifiers);

#endif
