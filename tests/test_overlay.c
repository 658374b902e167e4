/* test_overlay.c - the failure annunciation overlay and its 5x7 font.
 *
 * usage: test_overlay cpu        font table and layout rules (no GPU)
 *        test_overlay BACKEND [WxH [OUT.rgba]]
 *                                the above, then real frames: the embedded
 *                                default scene at WxH (default 320x240, at
 *                                most 1024 per side), the annunciation drawn
 *                                into the renderer's colour target
 *                                (OUT.rgba: one of them, raw RGBA, row 0 at
 *                                the top, for a person to look at)
 *
 * Built twice (tests/overlay.cmake): FT_OVERLAY_TEST_GL = 0 links the core
 * only; FT_OVERLAY_TEST_GL = 1 links the app and accepts a backend.
 *
 * GL checks, per reason, on every pixel of the read-back frame:
 *   - inside the black box: exactly the font's pixels are pure red (each S x S),
 *     all others pure black;
 *   - outside it, within T/2 - 1 px of a diagonal: pure red (1,0,0);
 *   - farther than T/2 + 1 px from both diagonals: the terrain frame as it
 *     was before the overlay (which has no pure red pixel).
 * Pixels within 1 px of a bar edge are not judged (the bar corners are
 * rounded to whole pixels). */
#include <stdio.h>
#include <string.h>

#include "gpu/font5x7.h"
#include "gpu/overlay.h"
#include "test_util.h"

#ifndef FT_OVERLAY_TEST_GL
#define FT_OVERLAY_TEST_GL 0
#endif

#if FT_OVERLAY_TEST_GL
#include "app/app.h"
#include "core/scene.h"
#endif

/* ---- font ------------------------------------------------------------------ */

static int glyph_blank(const uint8_t *g)
{
    for (unsigned r = 0; r < FT_FONT5X7_ROWS; ++r) {
        if (g[r] != 0u) {
            return 0;
        }
    }
    return 1;
}

static int glyph_is_box(const uint8_t *g)
{
    for (unsigned r = 0; r < FT_FONT5X7_ROWS; ++r) {
        if (g[r] != 0x1Fu) {
            return 0;
        }
    }
    return 1;
}

static void test_font(void)
{
    const char *set = ft_font5x7_charset;
    const size_t n = strlen(set);
    CHECK(n == 1u + 10u + 26u + 19u);
    for (size_t i = 0; i < n; ++i) {
        const uint8_t *g = ft_font5x7_glyph(set[i]);
        REQUIRE(g != NULL);
        CHECK(ft_font5x7_has_glyph(set[i]));
        for (unsigned r = 0; r < FT_FONT5X7_ROWS; ++r) {
            CHECK(g[r] <= 0x1Fu); /* 5 columns */
        }
        if (set[i] == ' ') {
            CHECK(glyph_blank(g));
        } else {
            if (glyph_blank(g)) {
                fprintf(stderr, "glyph '%c' is empty\n", set[i]);
            }
            CHECK(!glyph_blank(g));
            CHECK(!glyph_is_box(g)); /* a real glyph, not the unknown box */
        }
        /* no two characters share a glyph (catches copy-paste slips) */
        for (size_t j = 0; j < i; ++j) {
            const uint8_t *h = ft_font5x7_glyph(set[j]);
            if (memcmp(g, h, FT_FONT5X7_ROWS) == 0) {
                fprintf(stderr, "glyphs '%c' and '%c' are identical\n", set[i], set[j]);
                CHECK(0);
            }
        }
    }
    for (char c = 'a'; c <= 'z'; ++c) {
        const char up = (char)(c - 'a' + 'A');
        CHECK(ft_font5x7_has_glyph(c));
        CHECK(memcmp(ft_font5x7_glyph(c), ft_font5x7_glyph(up), FT_FONT5X7_ROWS) == 0);
    }
    CHECK(ft_font5x7_glyph('a') == ft_font5x7_glyph('A'));
    const char unknown[] = {'@', '$', '&', '*', '[', '\\', ']', '^', '`', '{', '|', '}', '~',
                            '\n', '\t', '\x01', '\x7f', (char)0x80, (char)0xC3, (char)0xFF};
    for (size_t i = 0; i < sizeof unknown; ++i) {
        CHECK(!ft_font5x7_has_glyph(unknown[i]));
        CHECK(glyph_is_box(ft_font5x7_glyph(unknown[i])));
    }
    /* Every ASCII code either has a glyph from the set or draws the box. */
    for (int c = 0; c < 256; ++c) {
        const char ch = (char)c;
        const int in_set = (c != 0) && strchr(set, c >= 'a' && c <= 'z' ? c - 32 : c) != NULL;
        CHECK(ft_font5x7_has_glyph(ch) == in_set);
    }
}

/* ---- layout ----------------------------------------------------------------- */

static void check_layout_fits(uint32_t w, uint32_t h, const ft_overlay_layout *l)
{
    if (l->chars == 0u) {
        CHECK(l->box_w == 0u && l->box_h == 0u && l->scale_px == 0u);
        return;
    }
    CHECK(l->scale_px >= 1u);
    CHECK(strlen(l->text) == l->chars);
    CHECK(l->chars <= FT_OVERLAY_TEXT_MAX);
    CHECK(l->box_x >= 0 && (uint32_t)l->box_x + l->box_w <= w);
    CHECK(l->box_w == (6u * l->chars + 3u) * l->scale_px);
    CHECK(l->box_h == 11u * l->scale_px);
    CHECK(l->box_y >= (int32_t)(2u * l->scale_px));
    /* centred in x (to the pixel) */
    const int32_t left = l->box_x, right = (int32_t)w - (l->box_x + (int32_t)l->box_w);
    CHECK(right - left == 0 || right - left == 1);
    (void)h;
}

static void test_layout(void)
{
    ft_overlay_layout l;
    ft_error err;
    REQUIRE(ft_overlay_layout_for(320, 240, "NO HEADING 250 MS", &l, &err) == FT_OK);
    CHECK(l.thickness_px == 7u); /* 3 % of 240 = 7.2 */
    CHECK(l.scale_px == 1u);
    CHECK(l.chars == 17u && !l.truncated);
    CHECK(strcmp(l.text, "NO HEADING 250 MS") == 0);
    CHECK(l.box_y == 15); /* 240 / 16 */
    CHECK(l.text_x == l.box_x + 2 && l.text_y == l.box_y + 2);
    check_layout_fits(320, 240, &l);

    REQUIRE(ft_overlay_layout_for(1920, 1080, "pose invalid: pitch out of range", &l, &err) ==
            FT_OK);
    CHECK(l.scale_px == 4u); /* 1080 / 240 */
    CHECK(l.thickness_px == 32u); /* 32.4 */
    CHECK(strcmp(l.text, "pose invalid: pitch out of range") == 0); /* shown as given */
    check_layout_fits(1920, 1080, &l);

    /* a tall narrow view lowers the glyph pixel until the box fits */
    REQUIRE(ft_overlay_layout_for(640, 960, "0123456789012345678901234567890123456789", &l,
                                  &err) == FT_OK);
    CHECK(l.scale_px == 2u); /* 4 would be 972 px wide, 2 is 486 */
    check_layout_fits(640, 960, &l);

    /* 500 characters: cut at FT_OVERLAY_TEXT_MAX with "..." */
    char longr[501];
    for (unsigned i = 0; i < 500u; ++i) {
        longr[i] = (char)('A' + (char)(i % 26u));
    }
    longr[500] = '\0';
    REQUIRE(ft_overlay_layout_for(4096, 2160, longr, &l, &err) == FT_OK);
    CHECK(l.truncated && l.chars == FT_OVERLAY_TEXT_MAX);
    CHECK(strncmp(l.text, longr, FT_OVERLAY_TEXT_MAX - 3u) == 0);
    CHECK(strcmp(l.text + FT_OVERLAY_TEXT_MAX - 3u, "...") == 0);
    check_layout_fits(4096, 2160, &l);
    /* exactly FT_OVERLAY_TEXT_MAX fits uncut; one more is cut */
    longr[FT_OVERLAY_TEXT_MAX] = '\0';
    REQUIRE(ft_overlay_layout_for(4096, 2160, longr, &l, &err) == FT_OK);
    CHECK(!l.truncated && l.chars == FT_OVERLAY_TEXT_MAX);
    longr[FT_OVERLAY_TEXT_MAX] = 'X';
    longr[FT_OVERLAY_TEXT_MAX + 1u] = '\0';
    REQUIRE(ft_overlay_layout_for(4096, 2160, longr, &l, &err) == FT_OK);
    CHECK(l.truncated && l.chars == FT_OVERLAY_TEXT_MAX);

    /* at 320 px only (320 - 9) / 6 + 1 = 52 characters fit at glyph pixel 1 */
    longr[FT_OVERLAY_TEXT_MAX] = 'A';
    REQUIRE(ft_overlay_layout_for(320, 240, longr, &l, &err) == FT_OK);
    CHECK(l.truncated && l.chars == 52u && l.scale_px == 1u);
    CHECK(strcmp(l.text + 49, "...") == 0);
    check_layout_fits(320, 240, &l);

    /* empty, NULL, too narrow */
    REQUIRE(ft_overlay_layout_for(320, 240, "", &l, &err) == FT_OK);
    CHECK(l.chars == 0u && !l.truncated && l.box_w == 0u);
    REQUIRE(ft_overlay_layout_for(320, 240, NULL, &l, &err) == FT_OK);
    CHECK(l.chars == 0u && l.box_w == 0u);
    REQUIRE(ft_overlay_layout_for(8, 8, "NO HEADING", &l, &err) == FT_OK);
    CHECK(l.chars == 0u && l.truncated && l.thickness_px == 2u);
    REQUIRE(ft_overlay_layout_for(20, 8, "NO HEADING", &l, &err) == FT_OK);
    CHECK(l.chars == 2u && l.truncated && strcmp(l.text, "..") == 0);
    REQUIRE(ft_overlay_layout_for(40, 8, "NO HEADING", &l, &err) == FT_OK);
    CHECK(l.chars == 6u && strcmp(l.text, "NO ...") == 0);

    /* bad views */
    CHECK(ft_overlay_layout_for(0, 240, "X", &l, &err) == FT_ERR_ARG);
    CHECK(ft_overlay_layout_for(320, 0, "X", &l, &err) == FT_ERR_ARG);
    CHECK(ft_overlay_layout_for(FT_OVERLAY_VIEW_MAX_PX + 1u, 240, "X", &l, &err) == FT_ERR_ARG);
    REQUIRE(ft_overlay_layout_for(FT_OVERLAY_VIEW_MAX_PX, FT_OVERLAY_VIEW_MAX_PX, longr, &l,
                                  &err) == FT_OK);
    check_layout_fits(FT_OVERLAY_VIEW_MAX_PX, FT_OVERLAY_VIEW_MAX_PX, &l);
    /* vertices stay inside int16 */
    CHECK((uint32_t)l.box_x + l.box_w <= 32767u && (uint32_t)l.box_y + l.box_h <= 32767u);
}

/* ---- real frames --------------------------------------------------------------- */

#if FT_OVERLAY_TEST_GL

#define VIEW_MAX_PX 1024u

static uint32_t W = 320u, H = 240u; /* the view (argument WxH) */

static ft_app g_app;
static ft_overlay g_ov;
static uint8_t g_base[VIEW_MAX_PX * VIEW_MAX_PX * 4u];
static size_t g_frame_bytes;
static ft_scene g_scene;

static int is_red(const uint8_t *p)
{
    return p[0] == 255u && p[1] == 0u && p[2] == 0u && p[3] == 255u;
}

static int is_black(const uint8_t *p)
{
    return p[0] == 0u && p[1] == 0u && p[2] == 0u && p[3] == 255u;
}

/* Distance of pixel (x, y)'s centre from the nearer diagonal. */
static double diag_distance(uint32_t x, uint32_t y)
{
    const double px = (double)x + 0.5, py = (double)y + 0.5;
    const double w = (double)W, h = (double)H, len = sqrt(w * w + h * h);
    const double d1 = fabs(h * px - w * py) / len;       /* (0,0) - (W,H) */
    const double d2 = fabs(h * px + w * py - w * h) / len; /* (W,0) - (0,H) */
    return d1 < d2 ? d1 : d2;
}

/* Expected colour inside the box: 1 red (a font pixel), 0 black. */
static int expect_text_red(const ft_overlay_layout *l, uint32_t x, uint32_t y)
{
    const int32_t lx = (int32_t)x - l->text_x, ly = (int32_t)y - l->text_y;
    const int32_t s = (int32_t)l->scale_px;
    if (lx < 0 || ly < 0) {
        return 0;
    }
    const uint32_t gx = (uint32_t)(lx / s), gy = (uint32_t)(ly / s);
    const uint32_t i = gx / FT_FONT5X7_ADVANCE, col = gx % FT_FONT5X7_ADVANCE;
    if (i >= l->chars || col >= FT_FONT5X7_COLS || gy >= FT_FONT5X7_ROWS) {
        return 0;
    }
    return (ft_font5x7_glyph(l->text[i])[gy] >> (FT_FONT5X7_COLS - 1u - col)) & 1u;
}

static void render_base(void)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_error err;
    ft_status st = ft_app_render(&g_app, &g_scene.pose, &cam, &fs, &err);
    if (st != FT_OK) {
        fprintf(stderr, "render: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
}

typedef struct result {
    uint32_t red_in_box, black_in_box, box_mismatch;
    uint32_t band_checked, band_not_red;
    uint32_t far_checked, far_changed;
} result;

/* Fresh terrain frame, the annunciation over it, read back, every pixel judged. */
static result annunciate(const char *reason, ft_overlay_layout *l)
{
    ft_error err;
    result res;
    memset(&res, 0, sizeof res);
    render_base();
    memcpy(g_base, g_app.renderer.rgba, g_frame_bytes);
    const ft_gl *gl = &g_app.gpu.gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, g_app.renderer.fbo_color);
    ft_status st = ft_overlay_draw_annunciation(&g_ov, gl, W, H, reason, &err);
    if (st != FT_OK) {
        fprintf(stderr, "overlay draw: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    REQUIRE(ft_renderer_read_rgba(&g_app.renderer, &err) == FT_OK);
    REQUIRE(ft_overlay_layout_for(W, H, reason, l, &err) == FT_OK);
    CHECK(memcmp(l, &g_ov.layout, sizeof *l) == 0);
    CHECK(g_ov.cross_vertices == 12u);
    CHECK(g_ov.box_vertices == (l->chars > 0u ? 6u : 0u));
    CHECK(g_ov.cross_vertices + g_ov.box_vertices + g_ov.text_vertices <=
          FT_OVERLAY_VERTICES_MAX);

    const double half = 0.5 * (double)l->thickness_px;
    const uint8_t *px = g_app.renderer.rgba;
    for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) {
            const size_t o = ((size_t)y * W + x) * 4u;
            const uint8_t *p = px + o;
            const int in_box = l->chars > 0u && (int32_t)x >= l->box_x &&
                               (int32_t)x < l->box_x + (int32_t)l->box_w &&
                               (int32_t)y >= l->box_y && (int32_t)y < l->box_y + (int32_t)l->box_h;
            if (in_box) {
                const int want_red = expect_text_red(l, x, y);
                res.red_in_box += (uint32_t)is_red(p);
                res.black_in_box += (uint32_t)is_black(p);
                res.box_mismatch += (uint32_t)!(want_red ? is_red(p) : is_black(p));
                continue;
            }
            const double d = diag_distance(x, y);
            if (d < half - 1.0) {
                res.band_checked += 1u;
                res.band_not_red += (uint32_t)!is_red(p);
            } else if (d > half + 1.0) {
                res.far_checked += 1u;
                res.far_changed += (uint32_t)(memcmp(p, g_base + o, 4u) != 0);
            }
        }
    }
    printf("'%.40s%s': %u chars at %u px, box %ux%u at (%d,%d); box red %u black %u "
           "mismatch %u; band %u (not red %u); far %u (changed %u)\n",
           reason ? reason : "(null)", (reason && strlen(reason) > 40u) ? "..." : "", l->chars,
           l->scale_px, l->box_w, l->box_h, l->box_x, l->box_y, res.red_in_box,
           res.black_in_box, res.box_mismatch, res.band_checked, res.band_not_red,
           res.far_checked, res.far_changed);
    CHECK(res.box_mismatch == 0u);
    CHECK(res.band_not_red == 0u);
    CHECK(res.far_changed == 0u);
    CHECK(res.band_checked > 2u * W); /* two bars >= 5 px wide, each longer than W */
    CHECK(res.far_checked > W * H / 2u);
    return res;
}

/* Explicit samples: both diagonals red at many points outside the box. */
static void check_diagonals(const ft_overlay_layout *l)
{
    const uint8_t *px = g_app.renderer.rgba;
    uint32_t checked = 0;
    for (uint32_t k = 1; k < 20u; ++k) {
        const uint32_t y = H * k / 20u;
        const uint32_t xs[2] = {W * k / 20u, W - 1u - W * k / 20u};
        for (unsigned j = 0; j < 2u; ++j) {
            const int32_t x = (int32_t)xs[j];
            if (l->chars > 0u && x >= l->box_x - 1 && x <= l->box_x + (int32_t)l->box_w &&
                (int32_t)y >= l->box_y - 1 && (int32_t)y <= l->box_y + (int32_t)l->box_h) {
                continue;
            }
            CHECK(is_red(px + ((size_t)y * W + (uint32_t)x) * 4u));
            checked += 1u;
        }
    }
    CHECK(checked >= 30u);
    CHECK(is_red(px + ((size_t)(H / 2u) * W + W / 2u) * 4u)); /* where the bars cross */
}

static void test_gl(const char *backend, const char *out_path)
{
    ft_error err;
    ft_scene_defaults(&g_scene);
    REQUIRE(ft_scene_parse(&g_scene, ft_default_scene_text, "embedded", &err) == FT_OK);
    REQUIRE(ft_backend_from_name(backend, &g_scene.backend));
    g_scene.width_px = W;
    g_scene.height_px = H;
    g_frame_bytes = (size_t)W * H * 4u;
    ft_status st = ft_app_init(&g_app, &g_scene, &err);
    if (st != FT_OK) {
        fprintf(stderr, "init: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    printf("%s: GL_VERSION '%s', GL_RENDERER '%s'\n", backend, g_app.gpu.version,
           g_app.gpu.renderer);
    const ft_gl *gl = &g_app.gpu.gl;

    /* drawing before init fails cleanly */
    CHECK(ft_overlay_draw_annunciation(&g_ov, gl, W, H, "X", &err) == FT_ERR_ARG);
    st = ft_overlay_init(&g_ov, gl, &err);
    if (st != FT_OK) {
        fprintf(stderr, "overlay init: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    CHECK(g_ov.vao == 0u || gl->caps.has_vao);
    /* init left the renderer's VAO bound (core profile depends on it) */
    if (gl->caps.has_vao) {
        GLint vao = -1;
        gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        CHECK(vao == (GLint)g_app.renderer.vao);
    }

    /* the terrain frame has no pure red of its own */
    render_base();
    uint32_t base_red = 0;
    for (size_t i = 0; i < (size_t)W * H; ++i) {
        base_red += (uint32_t)is_red(g_app.renderer.rgba + i * 4u);
    }
    CHECK(base_red == 0u);

    ft_overlay_layout l_heading, l_position, l;
    const result r_heading = annunciate("NO HEADING", &l_heading);
    check_diagonals(&l_heading);
    CHECK(l_heading.chars == 10u);
    CHECK(r_heading.red_in_box > 0u && r_heading.black_in_box > 0u);
    if (gl->caps.has_vao) {
        GLint vao = -1;
        gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
        CHECK(vao == (GLint)g_app.renderer.vao); /* restored after the draw */
    }

    const result r_position = annunciate("NO POSITION", &l_position);
    check_diagonals(&l_position);
    CHECK(r_position.red_in_box > 0u && r_position.black_in_box > 0u);
    CHECK(r_position.red_in_box != r_heading.red_in_box); /* the text is really drawn */

    /* the same reason again (cached vertices, no upload) draws the same */
    const result r_again = annunciate("NO POSITION", &l);
    CHECK(r_again.red_in_box == r_position.red_in_box);
    CHECK(r_again.black_in_box == r_position.black_in_box);

    /* the terrain still renders normally after the overlay changed GL state */
    render_base();
    CHECK(memcmp(g_base, g_app.renderer.rgba, g_frame_bytes) == 0);

    /* lower case, digits, punctuation, an unknown character */
    const result r_mixed = annunciate("pose invalid: pitch 95.5 (>90) @", &l);
    CHECK(r_mixed.red_in_box > r_position.red_in_box);
    if (out_path != NULL) {
        FILE *f = fopen(out_path, "wb");
        REQUIRE(f != NULL);
        CHECK(fwrite(g_app.renderer.rgba, 1, g_frame_bytes, f) == g_frame_bytes);
        CHECK(fclose(f) == 0);
    }

    /* empty and NULL reasons: the cross only, no box */
    const result r_empty = annunciate("", &l);
    CHECK(l.chars == 0u && r_empty.red_in_box == 0u && r_empty.black_in_box == 0u);
    check_diagonals(&l);
    /* where the "NO HEADING" box was, only the bars changed the frame */
    (void)annunciate(NULL, &l);
    check_diagonals(&l);

    /* 500 characters: cut to what fits the view, ending in "..." */
    static char longr[501];
    for (unsigned i = 0; i < 500u; ++i) {
        longr[i] = "NO HEADING 250 MS "[i % 18u];
    }
    longr[500] = '\0';
    const result r_long = annunciate(longr, &l);
    const uint32_t fit = (W - 9u) / 6u + 1u; /* characters that fit at glyph pixel 1 */
    CHECK(l.truncated && l.chars == (fit < FT_OVERLAY_TEXT_MAX ? fit : FT_OVERLAY_TEXT_MAX));
    CHECK(strcmp(l.text + l.chars - 3u, "...") == 0);
    CHECK(r_long.red_in_box > r_heading.red_in_box);
    CHECK(strlen(longr) == 500u); /* the input is untouched */
    check_diagonals(&l);

    /* a view size the overlay cannot address is refused before any GL call */
    CHECK(ft_overlay_draw_annunciation(&g_ov, gl, 0u, H, "X", &err) == FT_ERR_ARG);
    CHECK(ft_gl_check(gl, "after the overlay tests", &err) == FT_OK);

    ft_overlay_shutdown(&g_ov, gl);
    CHECK(g_ov.program == 0u && g_ov.vbo == 0u && g_ov.vao == 0u);
    ft_overlay_shutdown(&g_ov, gl); /* twice is harmless */
    CHECK(ft_gl_check(gl, "overlay shutdown", &err) == FT_OK);
    ft_app_shutdown(&g_app);
}

#endif

int main(int argc, char **argv)
{
    test_font();
    test_layout();
    if (argc >= 2 && strcmp(argv[1], "cpu") != 0) {
#if FT_OVERLAY_TEST_GL
        if (argc >= 3) {
            unsigned w = 0, h = 0;
            char tail = 0;
            REQUIRE(sscanf(argv[2], "%ux%u%c", &w, &h, &tail) == 2);
            REQUIRE(w >= 64u && h >= 64u && w <= VIEW_MAX_PX && h <= VIEW_MAX_PX);
            W = w;
            H = h;
        }
        test_gl(argv[1], argc >= 4 ? argv[3] : NULL);
#else
        fprintf(stderr, "this build of test_overlay has no GL (FT_OVERLAY_TEST_GL = 0)\n");
        return 1;
#endif
    }
    return ft_test_result(argc >= 2 ? argv[1] : "cpu");
}
