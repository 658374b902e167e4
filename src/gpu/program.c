#include "gpu/program.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gpu/shaders.h"

#define FT_SHADER_LOG_MAX 1024

/* ---- compile and link ------------------------------------------------------- */

static ft_status compile(const ft_gl *gl, GLenum stage, const char *body_name,
                         const char *defines, GLuint *out, ft_error *err)
{
    const char *prelude =
        ft_shader_find(gl->api == FT_GL_API_ES3 ? "prelude_es3.glsl" : "prelude_es2.glsl");
    const char *body = ft_shader_find(body_name);
    if (prelude == NULL || body == NULL) {
        return ft_fail(err, FT_ERR_ARG, "embedded shader %s missing", body_name);
    }
    GLuint sh = gl->CreateShader(stage);
    const GLchar *parts[3] = {prelude, defines != NULL ? defines : "", body};
    gl->ShaderSource(sh, 3, parts, NULL);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[FT_SHADER_LOG_MAX];
        GLsizei n = 0;
        gl->GetShaderInfoLog(sh, (GLsizei)sizeof log, &n, log);
        log[(n > 0 && n < FT_SHADER_LOG_MAX) ? n : 0] = '\0';
        gl->DeleteShader(sh);
        return ft_fail(err, FT_ERR_GPU, "shader %s (GLSL ES %s) failed to compile: %.200s",
                       body_name, gl->api == FT_GL_API_ES3 ? "3.00" : "1.00", log);
    }
    *out = sh;
    return FT_OK;
}

/* Compiles and links vert (after the lines vert_defines, may be NULL) + frag
 * with attribute slots 0, 1, 2 bound to attribs[0..2] (slot 0 always, 1 and 2
 * when named). */
static ft_status link_program_attribs(const ft_gl *gl, const char *vert_name,
                                      const char *vert_defines, const char *frag_name,
                                      const char *frag_defines, const char *const attribs[3],
                                      GLuint *out, ft_error *err)
{
    GLuint vs = 0, fs = 0;
    ft_status s = compile(gl, GL_VERTEX_SHADER, vert_name, vert_defines, &vs, err);
    if (s != FT_OK) {
        return s;
    }
    s = compile(gl, GL_FRAGMENT_SHADER, frag_name, frag_defines, &fs, err);
    if (s != FT_OK) {
        gl->DeleteShader(vs);
        return s;
    }
    GLuint prog = gl->CreateProgram();
    gl->AttachShader(prog, vs);
    gl->AttachShader(prog, fs);
    /* Fixed attribute slots for every program: 0 the template vertex, 1-2
     * a program's own (the bench's oracle). Unused names are ignored. */
    gl->BindAttribLocation(prog, FT_ATTRIB_UV, attribs[0]);
    if (attribs[1] != NULL) {
        gl->BindAttribLocation(prog, FT_ATTRIB_EXTRA1, attribs[1]);
    }
    if (attribs[2] != NULL) {
        gl->BindAttribLocation(prog, FT_ATTRIB_EXTRA2, attribs[2]);
    }
    gl->LinkProgram(prog);
    gl->DeleteShader(vs); /* flagged; freed with the program */
    gl->DeleteShader(fs);
    GLint ok = 0;
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[FT_SHADER_LOG_MAX];
        GLsizei n = 0;
        gl->GetProgramInfoLog(prog, (GLsizei)sizeof log, &n, log);
        log[(n > 0 && n < FT_SHADER_LOG_MAX) ? n : 0] = '\0';
        gl->DeleteProgram(prog);
        return ft_fail(err, FT_ERR_GPU, "program %s + %s failed to link: %.200s", vert_name,
                       frag_name, log);
    }
    *out = prog;
    return FT_OK;
}

ft_status ft_program_link(const ft_gl *gl, const char *vert_name, const char *frag_name,
                          const char *frag_defines, const char *attr0, GLuint *out,
                          ft_error *err)
{
    const char *const attribs[3] = {attr0, NULL, NULL};
    return link_program_attribs(gl, vert_name, NULL, frag_name, frag_defines, attribs, out,
                                err);
}

/* ---- terrain programs --------------------------------------------------------- */

static void locate_uniforms(const ft_gl *gl, ft_terrain_program *p)
{
    const GLuint prog = p->program;
#define FT_UNIFORM(name) p->name = gl->GetUniformLocation(prog, #name)
    FT_UNIFORM(u_heights);
    FT_UNIFORM(u_grid_size);
    FT_UNIFORM(u_patch_origin);
    FT_UNIFORM(u_patch_stride);
    FT_UNIFORM(u_cell_m);
    FT_UNIFORM(u_origin_rel_eye_m);
    FT_UNIFORM(u_view_proj);
    FT_UNIFORM(u_pack);
    FT_UNIFORM(u_clamp_box);
    FT_UNIFORM(u_earth_drop_per_m2);
#undef FT_UNIFORM
    ft_program_shade_locate(gl, prog, &p->shade);
    /* the method's own, in the order of its list */
    for (uint32_t i = 0; i < FT_METHOD_UNIFORMS_MAX; ++i) {
        p->method_u[i] = -1;
    }
    const ft_uniform_list *list = p->method_uniforms;
    uint32_t slot = 0u;
    for (uint32_t r = 0; list != NULL && r < list->row_count; ++r) {
        const ft_uniform_name *u = &list->rows[r];
        for (uint32_t e = 0; e < u->count && slot < FT_METHOD_UNIFORMS_MAX; ++e, ++slot) {
            char name[64];
            if (u->count == 1u) {
                (void)snprintf(name, sizeof name, "%s", u->name);
            } else {
                (void)snprintf(name, sizeof name, "%s[%u]", u->name, e);
            }
            p->method_u[slot] = gl->GetUniformLocation(prog, name);
        }
    }
}

/* Uniforms that never change for a terrain: set once at init. */
static void set_static_uniforms(const ft_gl *gl, const ft_terrain_program *p, const ft_terrain *t,
                                const ft_gpu_terrain *gt)
{
    gl->UseProgram(p->program);
    gl->Uniform1i(p->u_heights, 0);
    gl->Uniform2f(p->u_grid_size, (float)t->width, (float)t->height);
    gl->Uniform2f(p->u_cell_m, (float)t->cell_x_m, (float)t->cell_y_m);
    gl->Uniform4f(p->u_clamp_box, 0.0f, 0.0f, (float)(t->width - 1u), (float)(t->height - 1u));
    gl->Uniform1f(p->u_patch_stride, 1.0f);
    gl->Uniform1f(p->u_earth_drop_per_m2, (float)t->curv_drop_per_m2);
    gl->Uniform2f(p->u_pack, gt->pack_min_m,
                  gt->format == FT_HEIGHT_FORMAT_PACKED ? gt->pack_range_m : 0.0f);
}

/* Slots the list takes; more than FT_METHOD_UNIFORMS_MAX is refused at build. */
static uint32_t list_slots(const ft_uniform_list *list)
{
    uint32_t n = 0u;
    for (uint32_t r = 0; list != NULL && r < list->row_count; ++r) {
        n += list->rows[r].count;
    }
    return n;
}

ft_status ft_terrain_program_build(const ft_gl *gl, const ft_terrain *t, const ft_gpu_terrain *gt,
                                   const ft_terrain_program_desc *d, ft_terrain_program *p,
                                   ft_error *err)
{
    static const char *const terrain_attribs[3] = {"a_uv", NULL, NULL};
    if (list_slots(d->method_uniforms) > FT_METHOD_UNIFORMS_MAX) {
        return ft_fail(err, FT_ERR_OVERSIZED, "%s: %u method uniform locations (at most %u)",
                       d->vert_name, list_slots(d->method_uniforms), FT_METHOD_UNIFORMS_MAX);
    }
    GLuint prog = 0;
    ft_status s = link_program_attribs(gl, d->vert_name, d->vert_defines, d->frag_name,
                                       d->frag_defines,
                                       d->attribs != NULL ? d->attribs : terrain_attribs, &prog,
                                       err);
    if (s != FT_OK) {
        return s;
    }
    p->program = prog;
    p->method_uniforms = d->method_uniforms;
    locate_uniforms(gl, p);
    set_static_uniforms(gl, p, t, gt);
    return ft_gl_check(gl, d->frag_name, err);
}

void ft_terrain_program_relocate(const ft_gl *gl, const ft_terrain *t, const ft_gpu_terrain *gt,
                                 ft_terrain_program *p)
{
    locate_uniforms(gl, p);
    set_static_uniforms(gl, p, t, gt);
}

/* ---- colour: shaders/shade.glsl ------------------------------------------------ */

const char *ft_program_shade_defines(const ft_scene *s, const ft_terrain *t,
                                     char buf[FT_SHADE_DEFINES_MAX])
{
    const int unmeasured = t != NULL && t->void_count > 0u && t->void_bits != NULL;
    /* A part left out of the build is never asked for (the scene is refused
     * at init), and its define is not in the binary either. At most 4 lines
     * of 28 characters: always fits. */
    (void)snprintf(buf, FT_SHADE_DEFINES_MAX, "%s%s%s%s",
                   FT_WITH_RELATIVE_COLOURING && s->present_relative
                       ? "#define FT_SHADE_RELATIVE 1\n" : "",
                   FT_WITH_HAZE && s->present_haze_km > 0.0 ? "#define FT_SHADE_HAZE 1\n" : "",
                   FT_WITH_GROUND_GRID && s->present_grid_m > 0.0 ? "#define FT_SHADE_GRID 1\n"
                                                                   : "",
                   unmeasured ? "#define FT_SHADE_VOID 1\n" : "");
    return buf;
}

const char *ft_program_shade_parts(int built, char buf[FT_SHADE_PARTS_MAX])
{
    static const struct {
        const char *define;
        int built;
    } parts[] = {
        {"FT_SHADE_RELATIVE", FT_WITH_RELATIVE_COLOURING},
        {"FT_SHADE_GRID", FT_WITH_GROUND_GRID},
        {"FT_SHADE_HAZE", FT_WITH_HAZE},
        {"FT_SHADE_VOID", 1}, /* unmeasured terrain is always marked */
    };
    size_t n = 0u;
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; ++i) {
        if ((parts[i].built != 0) == (built != 0)) {
            /* 4 names of at most 18 characters and a space: always fits */
            n += (size_t)snprintf(buf + n, FT_SHADE_PARTS_MAX - n, "%s%s", n > 0u ? " " : "",
                                  parts[i].define);
        }
    }
    return n > 0u ? buf : "none";
}

void ft_program_shade_locate(const ft_gl *gl, GLuint prog, ft_shade_locs *u)
{
    u->ramp_h = gl->GetUniformLocation(prog, "u_ramp_height_m");
    u->ramp_rgb = gl->GetUniformLocation(prog, "u_ramp_rgb");
    u->sun = gl->GetUniformLocation(prog, "u_sun_dir");
    u->light = gl->GetUniformLocation(prog, "u_light");
#if FT_WITH_RELATIVE_COLOURING
    u->band_edge = gl->GetUniformLocation(prog, "u_band_edge_m");
    u->band_rgba = gl->GetUniformLocation(prog, "u_band_rgba");
    u->aircraft_alt = gl->GetUniformLocation(prog, "u_aircraft_alt_m");
#else
    u->band_edge = u->band_rgba = u->aircraft_alt = -1;
#endif
#if FT_WITH_HAZE
    u->haze = gl->GetUniformLocation(prog, "u_haze");
#else
    u->haze = -1;
#endif
    u->void_cells = gl->GetUniformLocation(prog, "u_void_cells");
    u->void_map = gl->GetUniformLocation(prog, "u_void_map");
    u->void_size = gl->GetUniformLocation(prog, "u_void_size");
#if FT_WITH_GROUND_GRID
    u->grid = gl->GetUniformLocation(prog, "u_ground_grid");
#else
    u->grid = -1;
#endif
}

/* Program must be current. A few dozen floats: set every frame, so a
 * palette switch takes effect on the next frame with no other state. */
void ft_program_shade_uniforms(const ft_gl *gl, const ft_shade_locs *u, const ft_shade_state *st)
{
    if (u->ramp_h < 0) {
        return;
    }
    float ramp[FT_RAMP_STOPS][3];
    ft_shade_palette_ramp(st->palette, ramp);
    gl->Uniform1fv(u->ramp_h, FT_RAMP_STOPS, ft_ramp_height_m);
    gl->Uniform3fv(u->ramp_rgb, FT_RAMP_STOPS, &ramp[0][0]);
    const float l = sqrtf(FT_SUN_DIR_X * FT_SUN_DIR_X + FT_SUN_DIR_Y * FT_SUN_DIR_Y +
                          FT_SUN_DIR_Z * FT_SUN_DIR_Z);
    gl->Uniform3f(u->sun, FT_SUN_DIR_X / l, FT_SUN_DIR_Y / l, FT_SUN_DIR_Z / l);
    gl->Uniform2f(u->light, FT_SHADE_AMBIENT, FT_SHADE_DIFFUSE);
    if (u->void_cells >= 0) {
        gl->Uniform1i(u->void_cells, FT_TEX_UNIT_VOID);
        gl->Uniform4f(u->void_map, st->void_map[0], st->void_map[1], st->void_map[2],
                      st->void_map[3]);
        gl->Uniform2f(u->void_size, st->void_size[0], st->void_size[1]);
    }
#if FT_WITH_GROUND_GRID
    if (u->grid >= 0) {
        gl->Uniform4f(u->grid, st->void_map[0], st->void_map[1], st->grid_m, st->px_per_rad);
    }
#endif
#if FT_WITH_HAZE
    if (u->haze >= 0) {
        float sky[3];
        ft_shade_palette_sky(st->palette, sky);
        gl->Uniform4f(u->haze, sky[0], sky[1], sky[2], st->haze_per_m);
    }
#endif
#if FT_WITH_RELATIVE_COLOURING
    if (u->band_rgba >= 0) {
        float edge_m[FT_BANDS_MAX - 1u], rgba[FT_BANDS_MAX][4];
        ft_shade_bands_gpu(st, edge_m, rgba);
        gl->Uniform1fv(u->band_edge, (GLsizei)(FT_BANDS_MAX - 1u), edge_m);
        gl->Uniform4fv(u->band_rgba, (GLsizei)FT_BANDS_MAX, &rgba[0][0]);
        gl->Uniform1f(u->aircraft_alt, st->aircraft_alt_m);
    }
#endif
}
