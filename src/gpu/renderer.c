#include "gpu/renderer.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/units.h"
#include "gpu/gpu_texture.h"
#include "gpu/shade.h"
#include "gpu/shaders.h"

/* The annunciation's vertices are int16 pixels: every view the scene
 * accepts fits. */
_Static_assert(FT_VIEW_SIDE_MAX_PX <= FT_OVERLAY_VIEW_MAX_PX, "a view larger than the overlay's");

#ifndef FT_GL_ERROR_CHECKS_DEFAULT
#error "FT_GL_ERROR_CHECKS_DEFAULT comes from CMakeLists.txt (0 or 1 by build type)"
#endif

/* ---- planning ----------------------------------------------------------- */

static int may_need_packed(const ft_scene *s)
{
    return s->height_format == FT_HEIGHT_FORMAT_PACKED ||
           (s->height_format == FT_HEIGHT_FORMAT_AUTO && s->backend == FT_BACKEND_EGL_GLES2);
}

void ft_renderer_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    size_t px = (size_t)s->width_px * s->height_px;
    ft_arena_plan(a, FT_POOL_FRAME_RGBA, px * 4u);
    if (s->metric_enabled) {
        ft_arena_plan(a, FT_POOL_FRAME_POS, px * 4u * sizeof(float));
    }
    if (may_need_packed(s)) {
        ft_arena_plan(a, FT_POOL_GPU_STAGING, (size_t)t->width * t->height * 4u);
    }
    ft_method_plan(s, t, a);
}







/* ---- colour: shaders/shade.glsl ---------------------------------------------- */




void ft_renderer_set_palette(ft_renderer *r, ft_palette p)
{
    r->shade.palette = p;
    ft_shade_palette_sky(p, r->clear_rgb);
}

/* ---- terrain textures ------------------------------------------------------- */

static ft_status upload_array(ft_renderer *r, ft_arena *a, const float *data, uint32_t w_px,
                              uint32_t h_px, GLuint *tex, ft_error *err)
{
    const ft_scalar_format f = {r->gt.format, r->gt.pack_min_m, r->gt.pack_range_m};
    return ft_gpu_upload_scalar(r->gl, &f, data, w_px, h_px, GL_TEXTURE0, a, tex, &r->gt.bytes,
                                err);
}

size_t ft_renderer_void_staging_bytes(uint32_t width)
{
    return (size_t)(width > 1u ? width - 1u : 1u) * FT_VOID_STRIP_ROWS;
}

/* One byte per cell, 255 where a corner sample was void-filled: what the
 * FT_SHADE_VOID fragment variant looks up. Built strip by strip from the
 * terrain's void bits through FT_POOL_GPU_STAGING. */
static void fill_void_rows(void *ctx, uint32_t y0, uint32_t rows, void *strip)
{
    const ft_terrain *t = ctx;
    const uint32_t cw = t->width - 1u;
    uint8_t *cell = strip;
    for (uint32_t y = 0; y < rows; ++y) {
        const size_t s0 = (size_t)(y0 + y) * t->width, s1 = s0 + t->width;
        for (uint32_t x = 0; x < cw; ++x) {
            const int filled =
                ft_terrain_sample_filled(t, s0 + x) || ft_terrain_sample_filled(t, s0 + x + 1u) ||
                ft_terrain_sample_filled(t, s1 + x) || ft_terrain_sample_filled(t, s1 + x + 1u);
            *cell++ = filled ? 255u : 0u;
        }
    }
}

static ft_status upload_void_cells(ft_renderer *r, ft_arena *a, ft_error *err)
{
    const ft_gl *gl = r->gl;
    const ft_terrain *t = r->terrain;
    GLint units = 0;
    gl->GetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    if (units <= FT_TEX_UNIT_VOID) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "the terrain has %u void-filled samples and marking them needs texture "
                       "unit %d; this device has %d units",
                       t->void_count, FT_TEX_UNIT_VOID, units);
    }
    /* ES 2 has LUMINANCE, a core profile (OSMesa) and ES 3 have R8 */
    const int r8 = gl->api == FT_GL_API_ES3 || gl->caps.desktop_core;
    const ft_texture_desc d = {GL_TEXTURE0 + FT_TEX_UNIT_VOID, t->width - 1u, t->height - 1u,
                               r8 ? GL_R8 : GL_LUMINANCE, r8 ? GL_RED : GL_LUMINANCE,
                               GL_UNSIGNED_BYTE, 1u};
    return ft_gpu_texture_create_strips(gl, &d, FT_VOID_STRIP_ROWS, fill_void_rows, (void *)t, a,
                                        &r->void_tex, &r->gpu_bytes,
                                        "unmeasured-cell texture upload", err);
}

static ft_status upload_terrain(ft_renderer *r, const ft_scene *s, ft_arena *a, ft_error *err)
{
    const ft_gl *gl = r->gl;
    const ft_terrain *t = r->terrain;
    ft_gpu_terrain *gt = &r->gt;
    const ft_scalar_format f =
        ft_gpu_height_format(gl, s->height_format, t->min_height_m, t->max_height_m);
    if (f.format == FT_HEIGHT_FORMAT_FLOAT && !gl->caps.has_float_textures) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "gpu.height_format = float, but this context has no float textures "
                       "(use auto or packed)");
    }
    gt->format = f.format;
    gt->pack_min_m = f.pack_min;
    gt->pack_range_m = f.pack_range;
    ft_status st = upload_array(r, a, t->heights_m, t->width, t->height, &gt->heights_tex, err);
    if (st != FT_OK || !s->pyramid_textures) {
        return st;
    }
    const ft_pyramid *p = &t->pyr;
    gt->avg_tex[0] = gt->heights_tex;
    gt->pyramid_levels_avg = 1;
    for (uint32_t l = 1; l < p->avg_levels && st == FT_OK; ++l) {
        st = upload_array(r, a, p->avg[l].avg_m, p->avg[l].width, p->avg[l].height,
                          &gt->avg_tex[l], err);
        gt->pyramid_levels_avg = l + 1u;
    }
    for (uint32_t l = 0; l < p->minmax_levels && st == FT_OK; ++l) {
        st = upload_array(r, a, p->minmax[l].min_m, p->minmax[l].width, p->minmax[l].height,
                          &gt->min_tex[l], err);
        if (st == FT_OK) {
            st = upload_array(r, a, p->minmax[l].max_m, p->minmax[l].width, p->minmax[l].height,
                              &gt->max_tex[l], err);
        }
        gt->pyramid_levels_minmax = l + 1u;
    }
    return st;
}

/* ---- targets ------------------------------------------------------------------ */

/* Depth formats, most precise first. 32-bit float is core in GLES 3.0 (and
 * desktop GL 3.0, OSMesa); its far-plane resolution equals 24-bit fixed
 * point with the standard mapping (ft_camera_depth_step_m), and finer near
 * the eye. 24-bit needs GLES 3 or OES_depth24 on GLES 2; 16-bit is core
 * everywhere. */
typedef struct depth_format {
    GLenum internal_format;
    uint32_t bits;
    int is_float;
} depth_format;

static const depth_format k_depth_formats[3] = {
    {GL_DEPTH_COMPONENT32F, 32u, 1},
    {GL_DEPTH_COMPONENT24, 24u, 0},
    {GL_DEPTH_COMPONENT16, 16u, 0},
};

static void drain_gl_errors(const ft_gl *gl)
{
    for (int i = 0; i < 16 && gl->GetError() != GL_NO_ERROR; ++i) {
        /* GL keeps one flag per error kind */
    }
}

/* Gives rb_depth storage in the first format with which the colour target
 * (and the position target, when there is one) is complete, and records it
 * in r->depth_bits / r->depth_float. */
static ft_status pick_depth_format(ft_renderer *r, GLsizei w, GLsizei h, ft_error *err)
{
    const ft_gl *gl = r->gl;
    const int es3 = (gl->api == FT_GL_API_ES3);
    GLenum st = GL_FRAMEBUFFER_COMPLETE;
    for (size_t k = 0; k < sizeof k_depth_formats / sizeof k_depth_formats[0]; ++k) {
        const depth_format *f = &k_depth_formats[k];
        if ((f->is_float && !es3) || (f->bits == 24u && !gl->caps.has_depth24)) {
            continue;
        }
        gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_depth);
        gl->RenderbufferStorage(GL_RENDERBUFFER, f->internal_format, w, h);
        if (gl->GetError() != GL_NO_ERROR) {
            drain_gl_errors(gl);
            continue; /* the driver refused the format itself */
        }
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                    r->rb_depth);
        st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
        if (st == GL_FRAMEBUFFER_COMPLETE && r->fbo_pos != 0u) {
            gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_pos);
            gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                        r->rb_depth);
            st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
        }
        if (st == GL_FRAMEBUFFER_COMPLETE) {
            r->depth_bits = f->bits;
            r->depth_float = f->is_float;
            return FT_OK;
        }
    }
    return ft_fail(err, FT_ERR_GPU,
                   "%s framebuffer %ux%u incomplete with every depth format (32F, 24, 16): 0x%04x",
                   r->fbo_pos != 0u ? "colour or RGBA32F position" : "colour", r->width_px,
                   r->height_px, (unsigned)st);
}

static ft_status make_targets(ft_renderer *r, ft_error *err)
{
    const ft_gl *gl = r->gl;
    const GLsizei w = (GLsizei)r->width_px, h = (GLsizei)r->height_px;
    const int es3 = (gl->api == FT_GL_API_ES3);

    /* Colour as a texture: ES2 core has no RGBA8 renderbuffer, but RGBA
     * UNSIGNED_BYTE textures are colour-renderable everywhere. */
    const ft_texture_desc colour = {GL_TEXTURE0, r->width_px, r->height_px,
                                    es3 ? GL_RGBA8 : GL_RGBA, GL_RGBA, GL_UNSIGNED_BYTE, 4u};
    ft_gpu_texture_create(gl, &colour, NULL, &r->rb_color, &r->gpu_bytes);
    gl->GenFramebuffers(1, &r->fbo_color);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->rb_color, 0);
    r->gpu_bytes += (uint64_t)w * (uint64_t)h * 4u; /* depth (32F, 24 as 32) */

    r->has_pos_target = 0;
    if (r->scene->metric_enabled && gl->caps.has_float_color_buffer) {
        gl->GenRenderbuffers(1, &r->rb_pos);
        gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_pos);
        gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, w, h);
        gl->GenFramebuffers(1, &r->fbo_pos);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_pos);
        gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                    r->rb_pos);
        r->has_pos_target = 1;
        r->gpu_bytes += (uint64_t)w * (uint64_t)h * 16u;
    }
    /* Errors so far are the targets' own: report them before the depth
     * format probe clears the ones it causes. */
    ft_status s = ft_gl_check(gl, "render targets", err);
    if (s != FT_OK) {
        return s;
    }
    /* One depth buffer, shared by both targets. */
    gl->GenRenderbuffers(1, &r->rb_depth);
    s = pick_depth_format(r, w, h, err);
    if (s != FT_OK) {
        return s;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
    return ft_gl_check(gl, "render targets", err);
}

/* ---- init ------------------------------------------------------------------------ */

ft_status ft_renderer_init(ft_renderer *r, ft_gpu_context *gpu, const ft_scene *s,
                           const ft_terrain *t, ft_arena *a, ft_error *err)
{
    ft_status st;
    memset(r, 0, sizeof *r);
    r->gpu = gpu;
    r->gl = &gpu->gl;
    r->terrain = t;
    r->scene = s;
    ft_shade_state_from_scene(&r->shade, s);
    r->shade.void_map[2] = (float)(1.0 / t->cell_x_m);
    r->shade.void_map[3] = (float)(1.0 / t->cell_y_m);
    r->shade.void_size[0] = (float)(t->width - 1u);
    r->shade.void_size[1] = (float)(t->height - 1u);
    ft_renderer_set_palette(r, s->present_palette);
    r->width_px = s->width_px;
    r->height_px = s->height_px;
    const ft_gl *gl = r->gl;

    if (gl->caps.max_vertex_texture_units < 1) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "this device has no vertex texture units "
                       "(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS = 0); fixterrain fetches heights "
                       "in the vertex shader and cannot run here");
    }
    if (t->width > (uint32_t)gl->caps.max_texture_size ||
        t->height > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "terrain %ux%u exceeds GL_MAX_TEXTURE_SIZE %d of this device", t->width,
                       t->height, gl->caps.max_texture_size);
    }
    if (gl->caps.has_vao) {
        gl->GenVertexArrays(1, &r->vao);
        gl->BindVertexArray(r->vao);
    }
    st = upload_terrain(r, s, a, err);
    if (st != FT_OK) {
        return st;
    }
    r->gpu_bytes += r->gt.bytes;
    if (t->void_count > 0u && t->void_bits != NULL) {
        st = upload_void_cells(r, a, err);
        if (st != FT_OK) {
            return st;
        }
    }
    /* the colour pass, and its position twin for the metric; each with a
     * coarse variant when the method draws its coarse tiles with one */
    const int es3 = gl->api == FT_GL_API_ES3;
    const ft_method_ops *ops = ft_method_ops_of(s->method);
    char frag_buf[FT_SHADE_DEFINES_MAX];
    char colour_defines[FT_SHADE_DEFINES_MAX + FT_METHOD_COLOUR_DEFINES_MAX];
    const int n = snprintf(colour_defines, sizeof colour_defines, "%s%s",
                           ft_program_shade_defines(s, t, frag_buf),
                           ft_method_colour_defines(s, es3));
    if (n < 0 || (size_t)n >= sizeof colour_defines) {
        return ft_fail(err, FT_ERR_ARG, "the colour shader's defines do not fit (%d bytes)", n);
    }
    ft_terrain_program_desc d = {
        .vert_name = ft_method_vertex_shader(s),
        .vert_defines = ft_method_vertex_defines(s, es3),
        .frag_name = "terrain.frag.glsl",
        .frag_defines = colour_defines,
        .method_uniforms = ops != NULL ? &ops->uniforms : NULL,
    };
    const char *coarse_defines = ft_method_vertex_defines_coarse(s, es3);
    ft_terrain_program_desc dc = d;
    dc.vert_defines = coarse_defines;
    st = ft_terrain_program_build(gl, t, &r->gt, &d, &r->prog_color, err);
    if (st == FT_OK && coarse_defines != NULL) {
        st = ft_terrain_program_build(gl, t, &r->gt, &dc, &r->prog_color_coarse, err);
        r->prog_color.coarse = &r->prog_color_coarse;
    }
    if (st != FT_OK) {
        return st;
    }
    r->prog_color.shade_state = &r->shade;
    r->prog_color_coarse.shade_state = &r->shade;
    st = make_targets(r, err);
    if (st != FT_OK) {
        return st;
    }
    if (r->has_pos_target) {
        d.frag_name = dc.frag_name = "terrain_pos.frag.glsl";
        d.frag_defines = dc.frag_defines = NULL;
        st = ft_terrain_program_build(gl, t, &r->gt, &d, &r->prog_pos, err);
        if (st == FT_OK && coarse_defines != NULL) {
            st = ft_terrain_program_build(gl, t, &r->gt, &dc, &r->prog_pos_coarse, err);
            r->prog_pos.coarse = &r->prog_pos_coarse;
        }
        if (st != FT_OK) {
            return st;
        }
    }
    if (gpu->display != FT_DISPLAY_NONE) {
        static const float corners[8] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f};
        st = ft_program_link(gl, "present.vert.glsl", "present.frag.glsl", NULL, "a_corner",
                             &r->present_program, err);
        if (st != FT_OK) {
            return st;
        }
        gl->UseProgram(r->present_program);
        gl->Uniform1i(gl->GetUniformLocation(r->present_program, "u_frame"), 0);
        gl->GenBuffers(1, &r->present_vbo);
        gl->BindBuffer(GL_ARRAY_BUFFER, r->present_vbo);
        gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof corners, corners, GL_STATIC_DRAW);
        r->gpu_bytes += sizeof corners;
    }
    st = ft_method_init(&r->method, gl, s, t, a, err);
    if (st != FT_OK) {
        return st;
    }
    r->gpu_bytes += ft_method_gpu_bytes(&r->method);
    if (gl->caps.has_timer_query) {
        gl->GenQueries(1, &r->timer_query);
    }
    st = ft_overlay_init(&r->overlay, gl, err);
    if (st != FT_OK) {
        return st;
    }
    r->gpu_bytes += FT_OVERLAY_GPU_BYTES;
    if (r->gpu_bytes > s->gpu_texture_bytes) {
        return ft_fail(err, FT_ERR_BUDGET,
                       "GPU memory: textures, targets and buffers need %llu bytes but the scene "
                       "budgets %llu (raise gpu.texture_bytes)",
                       (unsigned long long)r->gpu_bytes, (unsigned long long)s->gpu_texture_bytes);
    }
    size_t px = (size_t)r->width_px * r->height_px;
    st = ft_arena_take(a, FT_POOL_FRAME_RGBA, px * 4u, (void **)&r->rgba, err);
    if (st != FT_OK) {
        return st;
    }
    if (r->has_pos_target) {
        st = ft_arena_take(a, FT_POOL_FRAME_POS, px * 4u * sizeof(float), (void **)&r->pos, err);
        if (st != FT_OK) {
            return st;
        }
    }
    r->gl_error_checks = FT_GL_ERROR_CHECKS_DEFAULT;
    return ft_gl_check(gl, "renderer init", err);
}

/* The frame path's only glGetError (r->gl_error_checks = 1): counts what it
 * drains and fails the frame naming the step. */
static ft_status frame_error_check(ft_renderer *r, const char *where, ft_error *err)
{
    if (!r->gl_error_checks) {
        return FT_OK;
    }
    ft_status st = ft_gl_check(r->gl, where, err);
    r->gl_errors += (st != FT_OK) ? 1u : 0u;
    return st;
}

/* ---- camera ------------------------------------------------------------------------ */

ft_status ft_camera_for_pose(const ft_terrain *t, const ft_pose *pose, double fovy_deg,
                             uint32_t width_px, uint32_t height_px, ft_camera *cam, ft_error *err)
{
    double eye[3];
    ft_terrain_geo_to_world(t, pose->lat_deg, pose->lon_deg, &eye[0], &eye[1]);
    eye[2] = pose->alt_m;
    const double d2r = FT_RAD_PER_DEG;
    const double ty = tan(0.5 * fovy_deg * d2r);
    const double tx = ty * (double)width_px / (double)(height_px > 0u ? height_px : 1u);
    double near_m, far_m;
    /* the terrain as drawn: lowered by the earth-curvature drop */
    ft_camera_depth_range_for_terrain(t, eye, 1.0 / sqrt(1.0 + tx * tx + ty * ty),
                                      t->curv_drop_per_m2, &near_m, &far_m);
    return ft_camera_init(cam, eye, pose->heading_deg * d2r, pose->pitch_deg * d2r,
                          pose->roll_deg * d2r, fovy_deg * d2r, width_px, height_px, near_m,
                          far_m, err);
}

ft_status ft_renderer_camera(const ft_renderer *r, const ft_pose *pose, ft_camera *cam,
                             ft_error *err)
{
    return ft_camera_for_pose(r->terrain, pose, r->scene->fovy_deg, r->width_px, r->height_px,
                              cam, err);
}

ft_status ft_renderer_enable_capture(ft_renderer *r, ft_error *err)
{
    static const char *const varyings[FT_CAPTURE_FLOATS_PER_VERTEX - 3] = {"gl_Position",
                                                                           "v_morph"};
    return ft_renderer_enable_capture_of(r, varyings, 2u, err);
}

ft_status ft_renderer_enable_capture_of(ft_renderer *r, const char *const *varyings,
                                        uint32_t count, ft_error *err)
{
    const ft_gl *gl = r->gl;
    if (gl->api != FT_GL_API_ES3 || gl->TransformFeedbackVaryings == NULL) {
        return ft_fail(err, FT_ERR_UNSUPPORTED, "vertex capture needs transform feedback (GLES 3)");
    }
    if (count == 0u || count > FT_CAPTURE_VARYINGS_MAX) {
        return ft_fail(err, FT_ERR_ARG, "vertex capture: %u varyings (1..%u)", count,
                       FT_CAPTURE_VARYINGS_MAX);
    }
    ft_terrain_program *progs[2] = {&r->prog_color, &r->prog_color_coarse};
    for (int i = 0; i < 2; ++i) {
        ft_terrain_program *p = progs[i];
        if (p->program == 0u) {
            continue;
        }
        gl->TransformFeedbackVaryings(p->program, (GLsizei)count, varyings,
                                      GL_INTERLEAVED_ATTRIBS);
        gl->LinkProgram(p->program); /* the shaders are still attached */
        GLint ok = 0;
        gl->GetProgramiv(p->program, GL_LINK_STATUS, &ok);
        if (!ok) {
            return ft_fail(err, FT_ERR_GPU, "relinking the colour program for capture failed");
        }
        ft_terrain_program_relocate(gl, r->terrain, &r->gt, p);
    }
    return ft_gl_check(gl, "vertex capture relink", err);
}

/* ---- frames ------------------------------------------------------------------------- */

void ft_renderer_begin_pass(const ft_renderer *r, GLuint fbo, const float clear_rgba[4])
{
    const ft_gl *gl = r->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->ClearColor(clear_rgba[0], clear_rgba[1], clear_rgba[2], clear_rgba[3]);
    gl->Viewport(0, 0, (GLsizei)r->width_px, (GLsizei)r->height_px);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->DepthMask(GL_TRUE);
    gl->ClearDepthf(1.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void ft_renderer_frame_shade(const ft_renderer *r, const ft_camera *cam, ft_shade_state *out)
{
    *out = r->shade;
    out->aircraft_alt_m = (float)cam->eye_m[2]; /* the pose's altitude */
    out->void_map[0] = (float)(r->terrain->origin_world_x_m - cam->eye_m[0]);
    out->void_map[1] = (float)(r->terrain->origin_world_y_m - cam->eye_m[1]);
    out->px_per_rad = (float)cam->px_per_rad_k;
}

/* Draws the method with program p (and its coarse companion) into the target
 * ft_renderer_begin_pass made ready. */
static void draw_pass(ft_renderer *r, const ft_terrain_program *p, const ft_camera *cam,
                      ft_method_draw_stats *ms)
{
    const ft_gl *gl = r->gl;
    const ft_terrain *t = r->terrain;
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->gt.heights_tex);
    /* the coarse companion first, so the pass's own program is current after */
    const ft_terrain_program *progs[2] = {p->coarse, p};
    for (int i = 0; i < 2; ++i) {
        if (progs[i] == NULL) {
            continue;
        }
        gl->UseProgram(progs[i]->program);
        gl->UniformMatrix4fv(progs[i]->u_view_proj, 1, GL_FALSE, cam->view_proj);
        /* Relative to eye: the subtraction happens here, in double. */
        gl->Uniform3f(progs[i]->u_origin_rel_eye_m,
                      (float)(t->origin_world_x_m - cam->eye_m[0]),
                      (float)(t->origin_world_y_m - cam->eye_m[1]), (float)(0.0 - cam->eye_m[2]));
        ft_program_shade_uniforms(gl, &progs[i]->shade, &r->shade);
    }
    ft_method_draw(&r->method, gl, p, t, cam, ms);
}

void ft_renderer_fit_depth(const ft_renderer *r, ft_camera *cam)
{
    const double ty = tan(0.5 * cam->fovy_rad);
    const double tx = ty * (double)cam->width_px / (double)(cam->height_px > 0u ? cam->height_px : 1u);
    (void)ft_method_fit_depth(&r->method, r->terrain, cam, 1.0 / sqrt(1.0 + tx * tx + ty * ty));
}

void ft_renderer_select(ft_renderer *r, const ft_camera *cam)
{
    ft_method_select(&r->method, r->terrain, cam);
}

#if FT_WITH_HORIZON
/* Liang-Barsky: clips segment a-b to [x0, x1] x [y0, y1]; 0 if outside. */
static int clip_segment(double a[2], double b[2], double x0, double y0, double x1, double y1)
{
    const double d[2] = {b[0] - a[0], b[1] - a[1]};
    const double p[4] = {-d[0], d[0], -d[1], d[1]};
    const double q[4] = {a[0] - x0, x1 - a[0], a[1] - y0, y1 - a[1]};
    double t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return 0;
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0.0) {
            if (t > t1) return 0;
            if (t > t0) t0 = t;
        } else {
            if (t < t0) return 0;
            if (t < t1) t1 = t;
        }
    }
    const double a0[2] = {a[0], a[1]};
    for (int k = 0; k < 2; ++k) {
        a[k] = a0[k] + t0 * d[k];
        b[k] = a0[k] + t1 * d[k];
    }
    return t1 > t0;
}

/* The conformal horizon (presentation.horizon): the zero-pitch line over
 * terrain and sky, where the view shows it. */
static ft_status draw_horizon(ft_renderer *r, const ft_camera *cam, ft_error *err)
{
    double p0[2], p1[2];
    const double m = FT_HORIZON_LINE_PX;
    if (!ft_camera_horizon_px(cam, p0, p1) ||
        !clip_segment(p0, p1, -m, -m, (double)r->width_px + m, (double)r->height_px + m)) {
        return FT_OK; /* looking straight up or down, or the line is off the view */
    }
    const float g = ft_palette_colours_of(r->shade.palette)->horizon_grey;
    const float rgba[4] = {g, g, g, 1.0f};
    return ft_overlay_draw_line(&r->overlay, r->gl, r->width_px, r->height_px, p0, p1,
                                FT_HORIZON_LINE_PX, rgba, err);
}
#endif

ft_status ft_renderer_draw(ft_renderer *r, const ft_camera *cam, ft_frame_stats *st,
                           ft_error *err)
{
    const ft_gl *gl = r->gl;
    ft_method_draw_stats ms;
    memset(&ms, 0, sizeof ms);
    if (cam->width_px != r->width_px || cam->height_px != r->height_px) {
        return ft_fail(err, FT_ERR_ARG, "camera viewport %ux%u != target %ux%u", cam->width_px,
                       cam->height_px, r->width_px, r->height_px);
    }
    if (r->timer_query != 0u) {
        gl->BeginQuery(GL_TIME_ELAPSED_EXT, r->timer_query);
    }
    const float sky[4] = {r->clear_rgb[0], r->clear_rgb[1], r->clear_rgb[2], 1.0f};
    ft_renderer_begin_pass(r, r->fbo_color, sky);
    ft_shade_state shade;
    ft_renderer_frame_shade(r, cam, &shade);
    r->shade = shade;
    draw_pass(r, &r->prog_color, cam, &ms);
#if FT_WITH_HORIZON
    if (r->scene->present_horizon) {
        const ft_status hs = draw_horizon(r, cam, err);
        if (hs != FT_OK) {
            return hs;
        }
    }
#endif
    if (r->timer_query != 0u) {
        gl->EndQuery(GL_TIME_ELAPSED_EXT);
    }
    st->triangles = ms.triangles;
    st->draw_calls = ms.draw_calls;
    st->tiles = ms.tiles;
    st->raycast_px = ms.raycast_px;
    st->terrain_px = ms.terrain_px;
    st->tau_achieved_px = ms.tau_achieved_px;
    st->tau_target_px = ms.tau_target_px;
    st->budget_hit = ms.budget_hit;
    st->back_faces_culled = ms.back_faces_culled;
    st->envelopes = ms.envelopes;
    st->cache_levels_behind = ms.cache_levels_behind;
    st->cache_samples_outstanding = ms.cache_samples_outstanding;
    st->cache_coarser = ms.cache_coarser;
    st->cache_forced_updates = ms.cache_forced_updates;
    st->depth_bits = r->depth_bits;
    st->depth_float = r->depth_float;
    st->near_m = cam->near_m;
    st->far_m = cam->far_m;
    st->depth_res_far_m =
        ft_camera_depth_step_m(cam->near_m, cam->far_m, r->depth_bits, r->depth_float, cam->far_m);
    r->frames += 1u;
    return FT_OK; /* GL errors, when checked, are read once at the readback */
}

/* Fragments over unmeasured terrain wrote alpha 0.5 (shaders/shade.glsl):
 * count them, then make the frame opaque for the PNG and the display. */
static void count_unmeasured(ft_renderer *r)
{
    uint64_t n = 0u;
    if (r->void_tex != 0u) {
        const size_t px = (size_t)r->width_px * r->height_px;
        for (size_t i = 0; i < px; ++i) {
            n += (uint64_t)(r->rgba[4u * i + 3u] != 255u);
            r->rgba[4u * i + 3u] = 255u;
        }
    }
    r->unmeasured_px = n;
}

/* GL rows run bottom-up; ours run top-down. Swap rows in place (no buffer). */
static void flip_rows(uint8_t *data, size_t row_bytes, uint32_t rows)
{
    for (uint32_t y = 0; y < rows / 2u; ++y) {
        uint8_t *a = data + (size_t)y * row_bytes;
        uint8_t *b = data + (size_t)(rows - 1u - y) * row_bytes;
        for (size_t i = 0; i < row_bytes; ++i) {
            uint8_t tmp = a[i];
            a[i] = b[i];
            b[i] = tmp;
        }
    }
}

double ft_renderer_gpu_timer_ms(ft_renderer *r)
{
    const ft_gl *gl = r->gl;
    if (r->timer_query == 0u) {
        return -1.0;
    }
    GLuint ready = 0;
    gl->GetQueryObjectuiv(r->timer_query, GL_QUERY_RESULT_AVAILABLE_EXT, &ready);
    if (!ready) {
        return -1.0;
    }
    uint64_t ns = 0;
    gl->GetQueryObjectui64v(r->timer_query, GL_QUERY_RESULT_EXT, &ns);
    GLint disjoint = 0;
    if (!gl->caps.desktop_core) {
        gl->GetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint); /* also clears the flag */
    }
    return disjoint ? -1.0 : (double)ns * 1e-6;
}

ft_status ft_renderer_draw_annunciation(ft_renderer *r, const char *reason, ft_error *err)
{
    r->gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
    return ft_overlay_draw_annunciation(&r->overlay, r->gl, r->width_px, r->height_px, reason,
                                        err);
}

ft_status ft_renderer_read_rgba(ft_renderer *r, ft_error *err)
{
    const ft_gl *gl = r->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, (GLsizei)r->width_px, (GLsizei)r->height_px, GL_RGBA, GL_UNSIGNED_BYTE,
                   r->rgba);
    flip_rows(r->rgba, (size_t)r->width_px * 4u, r->height_px);
    count_unmeasured(r);
    ft_status st = frame_error_check(r, "frame (draw, overlay, colour readback)", err);
    if (r->frame_done != NULL) {
        r->frame_done(r->frame_done_ctx, r);
    }
    return st;
}

ft_status ft_renderer_draw_positions(ft_renderer *r, const ft_camera *cam, ft_error *err)
{
    const ft_gl *gl = r->gl;
    ft_method_draw_stats ms;
    memset(&ms, 0, sizeof ms);
    if (!r->has_pos_target) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       r->scene->metric_enabled
                           ? "this context cannot render to float targets (GLES 2): no error "
                             "metric here"
                           : "metric.enabled = 0 in the scene: no position target");
    }
    static const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    ft_renderer_begin_pass(r, r->fbo_pos, nothing);
    draw_pass(r, &r->prog_pos, cam, &ms);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, (GLsizei)r->width_px, (GLsizei)r->height_px, GL_RGBA, GL_FLOAT, r->pos);
    flip_rows((uint8_t *)r->pos, (size_t)r->width_px * 16u, r->height_px);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo_color);
    return frame_error_check(r, "position pass", err);
}

ft_status ft_renderer_present(ft_renderer *r, ft_error *err)
{
    const ft_gl *gl = r->gl;
    if (r->present_program == 0u) {
        return ft_fail(err, FT_ERR_CONFIG, "present: the scene has no display (scene.display)");
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->Viewport(0, 0, (GLsizei)r->width_px, (GLsizei)r->height_px);
    gl->Disable(GL_DEPTH_TEST);
    gl->UseProgram(r->present_program);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->rb_color);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->present_vbo);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    return frame_error_check(r, "present", err);
}

void ft_renderer_shutdown(ft_renderer *r)
{
    const ft_gl *gl = r->gl;
    if (gl == NULL) {
        return;
    }
    ft_method_shutdown(&r->method, gl);
    ft_overlay_shutdown(&r->overlay, gl);
    if (r->timer_query) gl->DeleteQueries(1, &r->timer_query);
    if (r->prog_color.program) gl->DeleteProgram(r->prog_color.program);
    if (r->prog_color_coarse.program) gl->DeleteProgram(r->prog_color_coarse.program);
    if (r->prog_pos_coarse.program) gl->DeleteProgram(r->prog_pos_coarse.program);
    if (r->present_program) gl->DeleteProgram(r->present_program);
    if (r->present_vbo) gl->DeleteBuffers(1, &r->present_vbo);
    if (r->prog_pos.program) gl->DeleteProgram(r->prog_pos.program);
    if (r->fbo_color) gl->DeleteFramebuffers(1, &r->fbo_color);
    if (r->fbo_pos) gl->DeleteFramebuffers(1, &r->fbo_pos);
    if (r->rb_pos) gl->DeleteRenderbuffers(1, &r->rb_pos);
    if (r->rb_depth) gl->DeleteRenderbuffers(1, &r->rb_depth);
    if (r->rb_color) gl->DeleteTextures(1, &r->rb_color);
    if (r->gt.heights_tex) gl->DeleteTextures(1, &r->gt.heights_tex);
    for (uint32_t l = 1; l < r->gt.pyramid_levels_avg; ++l) gl->DeleteTextures(1, &r->gt.avg_tex[l]);
    for (uint32_t l = 0; l < r->gt.pyramid_levels_minmax; ++l) {
        if (r->gt.min_tex[l]) gl->DeleteTextures(1, &r->gt.min_tex[l]);
        if (r->gt.max_tex[l]) gl->DeleteTextures(1, &r->gt.max_tex[l]);
    }
    if (r->vao && gl->DeleteVertexArrays) gl->DeleteVertexArrays(1, &r->vao);
    r->gl = NULL;
}

