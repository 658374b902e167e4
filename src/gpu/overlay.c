#include "gpu/overlay.h"

#include <math.h>
#include <string.h>

#include "core/invariant.h"
#include "gpu/program.h" /* ft_program_link: the one shader compile/link path */

#define FT_OVERLAY_PAD_GLYPH_PX 2u /* box padding around the text, in glyph pixels */

/* ---- layout (CPU only) ------------------------------------------------------ */

/* Length of s, scanning at most max + 1 characters (s may be huge or, past
 * that, unterminated). */
static uint32_t bounded_len(const char *s, uint32_t max)
{
    uint32_t n = 0;
    while (n <= max && s[n] != '\0') {
        ++n;
    }
    return n;
}

static uint32_t box_width_glyph_px(uint32_t chars)
{
    /* 5-wide glyphs on a 6 advance, no gap after the last, padding each side */
    return FT_FONT5X7_ADVANCE * chars - 1u + 2u * FT_OVERLAY_PAD_GLYPH_PX;
}

ft_status ft_overlay_layout_for(uint32_t width_px, uint32_t height_px, const char *reason,
                                ft_overlay_layout *out, ft_error *err)
{
    memset(out, 0, sizeof *out);
    if (width_px == 0u || height_px == 0u || width_px > FT_OVERLAY_VIEW_MAX_PX ||
        height_px > FT_OVERLAY_VIEW_MAX_PX) {
        return ft_fail(err, FT_ERR_ARG, "overlay: view %ux%u outside 1..%u px per side",
                       width_px, height_px, FT_OVERLAY_VIEW_MAX_PX);
    }
    const uint32_t short_side = width_px < height_px ? width_px : height_px;
    const uint32_t t = (uint32_t)(0.03 * (double)short_side + 0.5);
    out->thickness_px = t > 2u ? t : 2u;

    const uint32_t n = (reason == NULL) ? 0u : bounded_len(reason, FT_OVERLAY_TEXT_MAX);
    if (n == 0u) {
        return FT_OK;
    }
    /* Most characters whose box fits the width at glyph pixel 1. */
    const uint32_t min_box = box_width_glyph_px(1u);
    uint32_t cap = 0u;
    if (width_px >= min_box) {
        cap = (width_px - min_box) / FT_FONT5X7_ADVANCE + 1u;
    }
    if (cap > FT_OVERLAY_TEXT_MAX) {
        cap = FT_OVERLAY_TEXT_MAX;
    }
    uint32_t shown;
    if (n <= cap) {
        shown = n;
        memcpy(out->text, reason, n);
    } else {
        out->truncated = 1;
        shown = cap;
        const uint32_t keep = cap >= 3u ? cap - 3u : 0u;
        memcpy(out->text, reason, keep);
        for (uint32_t i = keep; i < cap; ++i) {
            out->text[i] = '.';
        }
    }
    out->text[shown] = '\0';
    out->chars = shown;
    if (shown == 0u) {
        return FT_OK; /* too narrow for even one character */
    }
    const uint32_t box_units = box_width_glyph_px(shown);
    uint32_t s = height_px / 240u;
    if (s < 1u) {
        s = 1u;
    }
    if (s > width_px / box_units) {
        s = width_px / box_units; /* >= 1: shown <= cap */
    }
    out->scale_px = s;
    out->box_w = box_units * s;
    out->box_h = (FT_FONT5X7_ROWS + 2u * FT_OVERLAY_PAD_GLYPH_PX) * s;
    out->box_x = (int32_t)((width_px - out->box_w) / 2u);
    const uint32_t top = height_px / 16u;
    out->box_y = (int32_t)(top > 2u * s ? top : 2u * s);
    out->text_x = out->box_x + (int32_t)(FT_OVERLAY_PAD_GLYPH_PX * s);
    out->text_y = out->box_y + (int32_t)(FT_OVERLAY_PAD_GLYPH_PX * s);
    return FT_OK;
}

/* ---- vertices ------------------------------------------------------------------ */

typedef struct vbuild {
    int16_t (*v)[2];
    uint32_t n, cap;
} vbuild;

static void put(vbuild *b, int32_t x, int32_t y)
{
    FT_INVARIANT(b->n < b->cap, "overlay vertices over their worst case");
    if (b->n < b->cap) {
        b->v[b->n][0] = (int16_t)x;
        b->v[b->n][1] = (int16_t)y;
        b->n += 1u;
    }
}

/* Quad a-b-c-d (in order around its edge) as two triangles. */
static void quad(vbuild *b, const int32_t q[4][2])
{
    static const unsigned k_order[6] = {0, 1, 2, 0, 2, 3};
    for (unsigned i = 0; i < 6u; ++i) {
        put(b, q[k_order[i]][0], q[k_order[i]][1]);
    }
}

static void rect(vbuild *b, int32_t x0, int32_t y0, int32_t x1, int32_t y1)
{
    const int32_t q[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    quad(b, q);
}

static int32_t round_px(double v)
{
    return (int32_t)floor(v + 0.5);
}

/* Bar of thickness t along the segment (x0,y0)-(x1,y1). Every pixel of the
 * view within t/2 of the line projects inside the segment (it runs corner to
 * corner), so the bar needs no end caps. */
static void bar(vbuild *b, double x0, double y0, double x1, double y1, double t)
{
    const double dx = x1 - x0, dy = y1 - y0;
    const double len = sqrt(dx * dx + dy * dy);
    const double nx = -dy / len * 0.5 * t, ny = dx / len * 0.5 * t;
    const int32_t q[4][2] = {{round_px(x0 + nx), round_px(y0 + ny)},
                             {round_px(x1 + nx), round_px(y1 + ny)},
                             {round_px(x1 - nx), round_px(y1 - ny)},
                             {round_px(x0 - nx), round_px(y0 - ny)}};
    quad(b, q);
}

static void build(ft_overlay *ov, uint32_t width_px, uint32_t height_px)
{
    const ft_overlay_layout *l = &ov->layout;
    vbuild b = {ov->verts, 0u, FT_OVERLAY_VERTICES_MAX};
    const double w = (double)width_px, h = (double)height_px, t = (double)l->thickness_px;
    bar(&b, 0.0, 0.0, w, h, t);
    bar(&b, w, 0.0, 0.0, h, t);
    ov->cross_vertices = b.n;
    if (l->chars > 0u) {
        rect(&b, l->box_x, l->box_y, l->box_x + (int32_t)l->box_w, l->box_y + (int32_t)l->box_h);
    }
    ov->box_vertices = b.n - ov->cross_vertices;
    const int32_t s = (int32_t)l->scale_px;
    for (uint32_t i = 0; i < l->chars; ++i) {
        const uint8_t *g = ft_font5x7_glyph(l->text[i]);
        const int32_t gx = l->text_x + (int32_t)(i * FT_FONT5X7_ADVANCE) * s;
        for (uint32_t r = 0; r < FT_FONT5X7_ROWS; ++r) {
            const int32_t y0 = l->text_y + (int32_t)r * s;
            /* one quad per run of set pixels in the row */
            uint32_t c = 0;
            while (c < FT_FONT5X7_COLS) {
                const unsigned bit = 1u << (FT_FONT5X7_COLS - 1u - c);
                if ((g[r] & bit) == 0u) {
                    ++c;
                    continue;
                }
                uint32_t e = c + 1u;
                while (e < FT_FONT5X7_COLS && (g[r] & (1u << (FT_FONT5X7_COLS - 1u - e))) != 0u) {
                    ++e;
                }
                rect(&b, gx + (int32_t)c * s, y0, gx + (int32_t)e * s, y0 + s);
                c = e;
            }
        }
    }
    ov->text_vertices = b.n - ov->cross_vertices - ov->box_vertices;
}

/* ---- GL ------------------------------------------------------------------------ */

static void set_attrib(const ft_gl *gl)
{
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_SHORT, GL_FALSE, 0, (const void *)0);
}

ft_status ft_overlay_init(ft_overlay *ov, const ft_gl *gl, ft_error *err)
{
    memset(ov, 0, sizeof *ov);
    GLuint prog = 0;
    ft_status st =
        ft_program_link(gl, "overlay.vert.glsl", "overlay.frag.glsl", NULL, "a_pos", &prog, err);
    if (st != FT_OK) {
        return st;
    }
    const GLint u_px_to_ndc = gl->GetUniformLocation(prog, "u_px_to_ndc");
    const GLint u_color = gl->GetUniformLocation(prog, "u_color");
    if (u_px_to_ndc < 0 || u_color < 0) {
        gl->DeleteProgram(prog);
        return ft_fail(err, FT_ERR_GPU, "overlay program: uniform u_px_to_ndc or u_color missing");
    }
    ov->program = prog;
    ov->u_px_to_ndc = u_px_to_ndc;
    ov->u_color = u_color;

    GLint prev_buffer = 0, prev_vao = 0;
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev_buffer);
    gl->GenBuffers(1, &ov->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, ov->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)FT_OVERLAY_GPU_BYTES, NULL, GL_DYNAMIC_DRAW);
    if (gl->caps.has_vao) {
        gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
        gl->GenVertexArrays(1, &ov->vao);
        gl->BindVertexArray(ov->vao);
        set_attrib(gl);
        gl->BindVertexArray((GLuint)prev_vao);
    }
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)prev_buffer);
    st = ft_gl_check(gl, "overlay init", err);
    if (st != FT_OK) {
        ft_overlay_shutdown(ov, gl);
    }
    return st;
}

/* The GL state every overlay draw sets (the renderer sets it every frame). */
static void begin_draw(const ft_overlay *ov, const ft_gl *gl, uint32_t width_px,
                       uint32_t height_px)
{
    set_attrib(gl);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_STENCIL_TEST);
    gl->Disable(GL_SCISSOR_TEST);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_CULL_FACE);
    gl->Viewport(0, 0, (GLsizei)width_px, (GLsizei)height_px);
    gl->UseProgram(ov->program);
    gl->Uniform2f(ov->u_px_to_ndc, 2.0f / (float)width_px, 2.0f / (float)height_px);
}

#if FT_WITH_HORIZON
ft_status ft_overlay_draw_line(ft_overlay *ov, const ft_gl *gl, uint32_t width_px,
                               uint32_t height_px, const double p0[2], const double p1[2],
                               double thickness_px, const float rgba[4], ft_error *err)
{
    if (ov->program == 0u) {
        return ft_fail(err, FT_ERR_ARG, "overlay: not initialised");
    }
    const double lim = (double)FT_OVERLAY_VIEW_MAX_PX;
    for (int k = 0; k < 2; ++k) {
        if (!(fabs(p0[k]) <= lim && fabs(p1[k]) <= lim) || !(thickness_px >= 1.0) ||
            !(thickness_px <= 64.0)) {
            return ft_fail(err, FT_ERR_ARG, "overlay line: ends or thickness out of range");
        }
    }
    if (p0[0] == p1[0] && p0[1] == p1[1]) {
        return ft_fail(err, FT_ERR_ARG, "overlay line: both ends at one point");
    }
    vbuild b = {ov->line_verts, 0u, FT_OVERLAY_LINE_VERTICES};
    bar(&b, p0[0], p0[1], p1[0], p1[1], thickness_px);
    GLint prev_vao = 0;
    if (ov->vao != 0u) {
        gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
        gl->BindVertexArray(ov->vao);
    }
    gl->BindBuffer(GL_ARRAY_BUFFER, ov->vbo);
    gl->BufferSubData(GL_ARRAY_BUFFER,
                      (GLintptr)((size_t)FT_OVERLAY_VERTICES_MAX * sizeof ov->verts[0]),
                      (GLsizeiptr)sizeof ov->line_verts, ov->line_verts);
    begin_draw(ov, gl, width_px, height_px);
    gl->Uniform4f(ov->u_color, rgba[0], rgba[1], rgba[2], rgba[3]);
    gl->DrawArrays(GL_TRIANGLES, (GLint)FT_OVERLAY_VERTICES_MAX, (GLsizei)b.n);
    if (ov->vao != 0u) {
        gl->BindVertexArray((GLuint)prev_vao);
    }
    return FT_OK;
}
#endif

ft_status ft_overlay_draw_annunciation(ft_overlay *ov, const ft_gl *gl, uint32_t width_px,
                                       uint32_t height_px, const char *reason, ft_error *err)
{
    if (ov->program == 0u) {
        return ft_fail(err, FT_ERR_ARG, "overlay: not initialised");
    }
    ft_overlay_layout l;
    ft_status st = ft_overlay_layout_for(width_px, height_px, reason, &l, err);
    if (st != FT_OK) {
        return st;
    }
    const int rebuild = !ov->cache_valid || ov->cache_w != width_px || ov->cache_h != height_px ||
                        strcmp(ov->layout.text, l.text) != 0;
    if (rebuild) {
        ov->layout = l;
        build(ov, width_px, height_px);
    }
    const uint32_t total = ov->cross_vertices + ov->box_vertices + ov->text_vertices;

    GLint prev_vao = 0;
    if (ov->vao != 0u) {
        gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &prev_vao);
        gl->BindVertexArray(ov->vao);
    }
    gl->BindBuffer(GL_ARRAY_BUFFER, ov->vbo);
    if (rebuild) {
        gl->BufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)((size_t)total * sizeof ov->verts[0]),
                          ov->verts);
        ov->cache_valid = 1;
        ov->cache_w = width_px;
        ov->cache_h = height_px;
    }
    begin_draw(ov, gl, width_px, height_px);
    gl->Uniform4f(ov->u_color, 1.0f, 0.0f, 0.0f, 1.0f);
    gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)ov->cross_vertices);
    if (ov->box_vertices > 0u) {
        gl->Uniform4f(ov->u_color, 0.0f, 0.0f, 0.0f, 1.0f);
        gl->DrawArrays(GL_TRIANGLES, (GLint)ov->cross_vertices, (GLsizei)ov->box_vertices);
    }
    if (ov->text_vertices > 0u) {
        gl->Uniform4f(ov->u_color, 1.0f, 0.0f, 0.0f, 1.0f);
        gl->DrawArrays(GL_TRIANGLES, (GLint)(ov->cross_vertices + ov->box_vertices),
                       (GLsizei)ov->text_vertices);
    }
    if (ov->vao != 0u) {
        gl->BindVertexArray((GLuint)prev_vao);
    }
    /* No glGetError here: the frame path does not branch on it (the
     * renderer reads errors once per frame at the readback, when asked). */
    return FT_OK;
}

void ft_overlay_shutdown(ft_overlay *ov, const ft_gl *gl)
{
    if (gl == NULL) {
        return;
    }
    if (ov->program != 0u) {
        gl->DeleteProgram(ov->program);
    }
    if (ov->vbo != 0u) {
        gl->DeleteBuffers(1, &ov->vbo);
    }
    if (ov->vao != 0u && gl->DeleteVertexArrays != NULL) {
        gl->DeleteVertexArrays(1, &ov->vao);
    }
    ov->program = 0u;
    ov->vbo = 0u;
    ov->vao = 0u;
    ov->cache_valid = 0;
}
