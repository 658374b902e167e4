/* test_kms_pick.c - the KMS display's decisions that need no device
 * (platform/display_kms.h): connector choice, mode choice (1:1, mode size =
 * view size), framebuffer call for a GBM modifier; and the display / mode
 * spellings of gpu.h and the scene keys. Runs on the host (no /dev/dri). */
#include <string.h>
#include <xf86drm.h>

#include "display_kms.h"
#include "core/scene.h"
#include "gpu/gpu.h"
#include "test_util.h"

static drmModeModeInfo mode(uint16_t w, uint16_t h, uint32_t hz, int preferred)
{
    drmModeModeInfo m;
    memset(&m, 0, sizeof m);
    m.hdisplay = w;
    m.vdisplay = h;
    m.vrefresh = hz;
    m.type = DRM_MODE_TYPE_DRIVER | (preferred ? DRM_MODE_TYPE_PREFERRED : 0u);
    (void)snprintf(m.name, sizeof m.name, "%ux%u", w, h);
    return m;
}

static drmModeConnector conn(uint32_t id, uint32_t type, uint32_t type_id,
                             drmModeConnection status, drmModeModeInfo *modes, int n)
{
    drmModeConnector c;
    memset(&c, 0, sizeof c);
    c.connector_id = id;
    c.connector_type = type;
    c.connector_type_id = type_id;
    c.connection = status;
    c.modes = modes;
    c.count_modes = n;
    return c;
}

static void test_connector(void)
{
    char why[256];
    drmModeModeInfo m[3] = {mode(1024, 768, 60, 1), mode(800, 600, 60, 0),
                            mode(640, 480, 60, 0)};
    drmModeConnector hdmi = conn(40, DRM_MODE_CONNECTOR_HDMIA, 1, DRM_MODE_DISCONNECTED, m, 3);
    drmModeConnector dp = conn(41, DRM_MODE_CONNECTOR_DisplayPort, 2, DRM_MODE_CONNECTED, m, 3);
    drmModeConnector virt = conn(42, DRM_MODE_CONNECTOR_VIRTUAL, 1, DRM_MODE_CONNECTED, m, 0);
    drmModeConnector *all[4] = {&hdmi, NULL, &virt, &dp};

    char name[32];
    ft_kms_connector_name(&hdmi, name, sizeof name);
    CHECK(strcmp(name, "HDMI-A-1") == 0);
    ft_kms_connector_name(&dp, name, sizeof name);
    CHECK(strcmp(name, "DP-2") == 0);

    /* default: the first connected one with modes (skips NULL, no-mode) */
    CHECK(ft_kms_pick_connector(all, 4, NULL, why, sizeof why) == 3);
    CHECK(ft_kms_pick_connector(all, 4, "", why, sizeof why) == 3);
    /* by name (any case) and by id */
    CHECK(ft_kms_pick_connector(all, 4, "dp-2", why, sizeof why) == 3);
    CHECK(ft_kms_pick_connector(all, 4, "41", why, sizeof why) == 3);
    /* named but disconnected / without modes / absent: clear reasons */
    CHECK(ft_kms_pick_connector(all, 4, "HDMI-A-1", why, sizeof why) == -1);
    CHECK(strstr(why, "HDMI-A-1") != NULL && strstr(why, "disconnected") != NULL);
    CHECK(ft_kms_pick_connector(all, 4, "Virtual-1", why, sizeof why) == -1);
    CHECK(strstr(why, "no modes") != NULL);
    CHECK(ft_kms_pick_connector(all, 4, "DP-9", why, sizeof why) == -1);
    CHECK(strstr(why, "no connector 'DP-9'") != NULL && strstr(why, "DP-2: connected") != NULL);
    /* nothing connected */
    drmModeConnector *none[2] = {&hdmi, &virt};
    CHECK(ft_kms_pick_connector(none, 2, NULL, why, sizeof why) == -1);
    CHECK(strstr(why, "no connected connector") != NULL &&
          strstr(why, "HDMI-A-1: disconnected") != NULL);
    CHECK(ft_kms_pick_connector(none, 0, NULL, why, sizeof why) == -1);
    CHECK(strstr(why, "has no connectors") != NULL);
}

static void test_mode(void)
{
    char why[320];
    /* the kernel's order: preferred first, then by size and refresh */
    drmModeModeInfo m[5] = {mode(1024, 768, 60, 1), mode(800, 600, 75, 0),
                            mode(800, 600, 60, 0), mode(640, 480, 75, 0),
                            mode(640, 480, 60, 1)};
    drmModeConnector c = conn(42, DRM_MODE_CONNECTOR_VIRTUAL, 1, DRM_MODE_CONNECTED, m, 5);
    /* default: a mode of the view size; the preferred one among them first */
    CHECK(ft_kms_pick_mode(&c, 1024, 768, NULL, why, sizeof why) == 0);
    CHECK(ft_kms_pick_mode(&c, 800, 600, "", why, sizeof why) == 1);
    CHECK(ft_kms_pick_mode(&c, 640, 480, NULL, why, sizeof why) == 4);
    /* a view size the connector has no mode for: the modes are listed */
    CHECK(ft_kms_pick_mode(&c, 1280, 1024, NULL, why, sizeof why) == -1);
    CHECK(strstr(why, "no 1280x1024 mode") != NULL && strstr(why, "1024x768@60*") != NULL &&
          strstr(why, "--size") != NULL);
    /* WxH@HZ picks the refresh; WxH must still be the view size */
    CHECK(ft_kms_pick_mode(&c, 800, 600, "800x600@60", why, sizeof why) == 2);
    CHECK(ft_kms_pick_mode(&c, 800, 600, "800x600", why, sizeof why) == 1);
    CHECK(ft_kms_pick_mode(&c, 800, 600, "800x600@50", why, sizeof why) == -1);
    CHECK(strstr(why, "no 800x600@50 mode") != NULL);
    CHECK(ft_kms_pick_mode(&c, 640, 480, "800x600", why, sizeof why) == -1);
    CHECK(strstr(why, "not the view size 640x480") != NULL && strstr(why, "never scaled"));
    /* preferred: the first flagged mode, which must have the view size */
    CHECK(ft_kms_pick_mode(&c, 1024, 768, "preferred", why, sizeof why) == 0);
    CHECK(ft_kms_pick_mode(&c, 640, 480, "preferred", why, sizeof why) == -1);
    CHECK(strstr(why, "--size 1024x768") != NULL);
    CHECK(ft_kms_pick_mode(&c, 640, 480, "1024 x 768", why, sizeof why) == -1);
    CHECK(strstr(why, "expected WxH") != NULL);
}

static void test_fb_call(void)
{
    const uint64_t invalid = 0x00ffffffffffffffull, linear = 0, tiled = 0x0100000000000001ull;
    /* bochs: no explicit modifier from GBM -> plain AddFB2, even if the
     * driver advertises modifier support */
    CHECK(ft_kms_fb_call_for(invalid, 0) == FT_KMS_FB_PLAIN);
    CHECK(ft_kms_fb_call_for(invalid, 1) == FT_KMS_FB_PLAIN);
    CHECK(ft_kms_fb_call_for(linear, 0) == FT_KMS_FB_PLAIN);
    CHECK(ft_kms_fb_call_for(linear, 1) == FT_KMS_FB_WITH_MODIFIERS);
    CHECK(ft_kms_fb_call_for(tiled, 1) == FT_KMS_FB_WITH_MODIFIERS);
    CHECK(ft_kms_fb_call_for(tiled, 0) == FT_KMS_FB_IMPOSSIBLE);
}

static void test_spellings(void)
{
    ft_display d = FT_DISPLAY_NONE;
    char dev[FT_DISPLAY_DEVICE_MAX];
    CHECK(ft_display_parse("kms", &d, dev, sizeof dev) && d == FT_DISPLAY_KMS && dev[0] == 0);
    CHECK(ft_display_parse("kms:/dev/dri/card1", &d, dev, sizeof dev) && d == FT_DISPLAY_KMS &&
          strcmp(dev, "/dev/dri/card1") == 0);
    CHECK(ft_display_parse("x11", &d, dev, sizeof dev) && d == FT_DISPLAY_X11 && dev[0] == 0);
    CHECK(!ft_display_parse("kms:", &d, dev, sizeof dev));
    CHECK(!ft_display_parse("kms:card1", &d, dev, sizeof dev));
    CHECK(!ft_display_parse("x11:/dev/dri/card1", &d, dev, sizeof dev));
    CHECK(!ft_display_parse("gbm", &d, dev, sizeof dev));
    char longpath[FT_DISPLAY_DEVICE_MAX + 16];
    memset(longpath, 'a', sizeof longpath);
    memcpy(longpath, "kms:/dev/", 9);
    longpath[sizeof longpath - 1] = '\0';
    CHECK(!ft_display_parse(longpath, &d, dev, sizeof dev));

    ft_display_mode m;
    CHECK(ft_display_mode_parse("1024x768", &m) && m.width_px == 1024 && m.height_px == 768 &&
          m.refresh_hz == 0 && !m.preferred);
    CHECK(ft_display_mode_parse("640x480@75", &m) && m.refresh_hz == 75);
    CHECK(ft_display_mode_parse("preferred", &m) && m.preferred);
    CHECK(!ft_display_mode_parse("1024x", &m));
    CHECK(!ft_display_mode_parse("x768", &m));
    CHECK(!ft_display_mode_parse("1024x768@", &m));
    CHECK(!ft_display_mode_parse("1024x768@60Hz", &m));
    CHECK(!ft_display_mode_parse("-1x768", &m));
    CHECK(!ft_display_mode_parse("0x768", &m));

    ft_scene s;
    ft_error err;
    ft_scene_defaults(&s);
    CHECK(ft_scene_parse(&s,
                         "[scene]\ndisplay = kms:/dev/dri/card2\n[display]\nconnector = HDMI-A-1\n"
                         "mode = 1024x768@60\n",
                         "t", &err) == FT_OK);
    CHECK(s.display == FT_DISPLAY_KMS && strcmp(s.display_device, "/dev/dri/card2") == 0 &&
          strcmp(s.display_connector, "HDMI-A-1") == 0 &&
          strcmp(s.display_mode, "1024x768@60") == 0);
    ft_scene_defaults(&s);
    CHECK(ft_scene_parse(&s, "[display]\nmode = 1024by768\n", "t", &err) == FT_ERR_CONFIG);
    CHECK(strstr(err.text, "display.mode") != NULL && strstr(err.text, "t:2:") != NULL);
    ft_scene_defaults(&s);
    CHECK(ft_scene_parse(&s, "[scene]\ndisplay = kms:card0\n", "t", &err) == FT_ERR_CONFIG);
    CHECK(strstr(err.text, "kms:/dev/dri/cardN") != NULL);
    ft_scene_defaults(&s);
    CHECK(ft_scene_parse(&s, "[display]\nsize = 3\n", "t", &err) == FT_ERR_CONFIG);
}

int main(void)
{
    test_connector();
    test_mode();
    test_fb_call();
    test_spellings();
    return ft_test_result("test_kms_pick");
}
