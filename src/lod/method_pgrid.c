/* method_pgrid.c - the error-bounded projective grid (src/lod/pgrid.h).
 *
 * Per frame, in each pass (colour and position) with the pass's program p:
 *  1. the grid is drawn as pgm draws it (ft_pgm_method_draw: bands, avg
 *     atlas, sampling camera) with shaders/pgrid.vert.glsl (row distribution,
 *     per-vertex delta);
 *  2. the error buffer: the same grid with pgrid_err.frag.glsl into an RGBA8
 *     texture with its own depth buffer (R = normalised error, G = code);
 *  3. colour pass only (the position pass reuses the decision of the same
 *     view): the error buffer is read back, the dilated-code histogram gives
 *     the ray-cast threshold inside raycast_max_px (src/lod/pgrid.h 5);
 *  4. GLES 3 with ray_casting = 1: a full-screen pass (pgrid_rc.frag.glsl)
 *     ray casts the pixels over the threshold and writes their colour (or
 *     position) and gl_FragDepth over the mesh (DepthFunc ALWAYS).
 * GLES 2 (no gl_FragDepth, no texelFetch): steps 1-3 only; init says so
 * on stderr and the stats report the mesh's error bound (tau_achieved_px)
 * instead of gamma. pgrid.heights = clipmap (GLES 3): the grid's heights
 * and each vertex's range of the finest data from the clipmap cache (pgm's
 * cache, with its cell ranges: lod/clip_levels.h FT_CLIP_BOUNDS_RANGES;
 * src/lod/pgrid.h 2), the tight bound's quads from the cache's levels
 * (src/lod/pgrid.h 6), and step 4 through the cache's levels (src/lod/pgrid.h
 * 7); the stats report the bound achieved, with the ray caster's leaves'
 * bound in it. All GL objects and CPU buffers are made at init. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "gpu/gpu_texture.h"
#include "gpu/program.h"
#include "gpu/shade.h"
#include "lod/method.h"
#include "terrain/terrain_db.h"

/* pgrid's uniforms (shaders/pgrid.vert.glsl, pgrid_pass.vert.glsl): pgm's
 * first (it draws with the pgm grid), then its own row distribution, min/max
 * atlas and tight-bound inputs. */
#define FT_PGRID_UNIFORMS(X)                                   \
    X(FT_PGRID_U_DIST, "u_pgrid_dist", 1u)                    \
    X(FT_PGRID_U_MM, "u_pgrid_mm", 1u)                        \
    X(FT_PGRID_U_MM_INFO, "u_pgrid_mm_info", 1u)              \
    X(FT_PGRID_U_MM_LEVELS, "u_pgrid_mm_levels", 1u)          \
    X(FT_PGRID_U_VTX, "u_pgrid_vtx", 1u)                      \
    X(FT_PGRID_U_SLOPE, "u_pgrid_slope", 1u)                  \
    X(FT_PGRID_U_ERR, "u_pgrid_err", 1u)                      \
    X(FT_PGRID_U_FWD, "u_pgrid_fwd", 1u)                      \
    X(FT_PGRID_U_ENVELOPE, "u_pgrid_envelope", 1u)            \
    X(FT_PGRID_U_COLS, "u_pgrid_cols", 1u)                    \
    X(FT_PGRID_U_COLS_ON, "u_pgrid_cols_on", 1u)              \
    X(FT_PGRID_U_RANGE, "u_pgrid_range", 1u)                  \
    X(FT_PGRID_U_BLOCK_RANGE, "u_pgrid_block_range", 1u)      \
    X(FT_PGRID_U_TOP_RANGE, "u_pgrid_top_range", 1u)          \
    X(FT_PGRID_U_MM_LEVEL, "u_pgrid_mm_level", FT_PYRAMID_LEVELS_MAX)
enum { FT_PGRID_U_BEFORE_ = FT_PCM_U_COUNT - 1, FT_PGRID_UNIFORMS(FT_UNIFORM_ENUM) FT_PGRID_U_COUNT };
/* pgm's rows and its cache rows first, at pgm's indices (pgrid draws with
 * ft_pgm_method_draw, which sets them) */
static const ft_uniform_name k_pgrid_uniforms[] = {FT_PGM_UNIFORMS(FT_UNIFORM_ROW)
                                                       FT_PCM_UNIFORMS(FT_UNIFORM_ROW)
                                                           FT_PGRID_UNIFORMS(FT_UNIFORM_ROW)};
static const ft_uniform_list k_pgrid_uniform_list = {
    k_pgrid_uniforms, sizeof k_pgrid_uniforms / sizeof k_pgrid_uniforms[0]};
_Static_assert(FT_PGRID_U_COUNT <= FT_METHOD_UNIFORMS_MAX, "pgrid's uniforms fit the table");
_Static_assert(FT_CLIP_BOUND_BLOCK == 16u, "shaders/pgrid.vert.glsl's FT_CLIP_BLOCK");

/* The ray-cast program's uniform locations, looked up once at init (a frame
 * makes no glGetUniformLocation call). They live in the same arena block as
 * the error pass's program, right after it: m->err_prog points at the first
 * member of this struct. */
typedef struct pgrid_rc_locs {
    GLint err, heights, rc_max, thr, pack, grid_size, levels, eye_g, cell_m, drop;
    GLint fwd, right, up, tan, size, view_proj, mode, sky, tiles, tile_px, tiles_w;
    ft_shade_locs shade;
    GLint max_level[FT_PYRAMID_LEVELS_MAX];
    /* over the cache: its heights atlas, levels and cell ranges */
    GLint atlas, atlas_pack, clamp, misc, range;
    GLint clip_level[FT_CLIP_LEVELS_MAX], clip_box[FT_CLIP_LEVELS_MAX];
} pgrid_rc_locs;

typedef struct pgrid_programs {
    ft_terrain_program err; /* first: m->err_prog == &block->err */
    /* the envelopes into the picture's framebuffer (its colour attachment 1) */
    ft_terrain_program env;
    pgrid_rc_locs rc;
} pgrid_programs;

static pgrid_rc_locs *rc_locs(const ft_pgrid_method *m)
{
    return &((pgrid_programs *)(void *)m->err_prog)->rc;
}

static ft_terrain_program *env_prog(const ft_pgrid_method *m)
{
    return &((pgrid_programs *)(void *)m->err_prog)->env;
}

static void locate_rc(const ft_gl *gl, GLuint prog, pgrid_rc_locs *u)
{
#define U(field, name) u->field = gl->GetUniformLocation(prog, name)
    U(err, "u_err");
    U(heights, "u_heights");
    U(rc_max, "u_rc_max");
    U(thr, "u_rc_thr");
    U(pack, "u_pack");
    U(grid_size, "u_grid_size");
    U(levels, "u_rc_levels");
    U(tiles, "u_rc_tiles");
    U(tile_px, "u_rc_tile_px");
    U(tiles_w, "u_rc_tiles_w");
    U(eye_g, "u_rc_eye_g");
    U(cell_m, "u_cell_m");
    U(drop, "u_earth_drop_per_m2");
    U(fwd, "u_rc_fwd");
    U(right, "u_rc_right");
    U(up, "u_rc_up");
    U(tan, "u_rc_tan");
    U(size, "u_rc_size");
    U(view_proj, "u_view_proj");
    U(mode, "u_rc_mode");
    U(sky, "u_rc_sky");
    U(atlas, "u_pgm_atlas");
    U(atlas_pack, "u_pgm_atlas_pack");
    U(clamp, "u_pcm_clamp");
    U(misc, "u_pcm_misc");
    U(range, "u_pgrid_range");
#undef U
    ft_program_shade_locate(gl, prog, &u->shade);
    for (uint32_t l = 0; l < FT_PYRAMID_LEVELS_MAX; ++l) {
        char name[40];
        (void)snprintf(name, sizeof name, "u_rc_max_level[%u]", l);
        u->max_level[l] = gl->GetUniformLocation(prog, name);
    }
    for (uint32_t l = 0; l < FT_CLIP_LEVELS_MAX; ++l) {
        char name[40];
        (void)snprintf(name, sizeof name, "u_pgm_level[%u]", l);
        u->clip_level[l] = gl->GetUniformLocation(prog, name);
        (void)snprintf(name, sizeof name, "u_pcm_box[%u]", l);
        u->clip_box[l] = gl->GetUniformLocation(prog, name);
    }
}

/* pgrid's grid (pgrid.grid), drawn by pgm's code */
/* The tight bound (src/lod/pgrid.h 6) is a compile-time variant of the
 * grid's vertex shader, chosen from the scene alone so the renderer's colour
 * and position programs and the error pass's agree: it serves ray casting on
 * GLES 3 (the bound it tightens decides which pixels are ray cast). */
static int pgrid_tight(const ft_scene *s, int es3)
{
    return s->pgrid_residual_bound && s->pgrid_ray_casting && es3;
}

static const char *pgrid_vertex_defines(const ft_scene *s, int es3)
{
    if (s->pgrid_heights_clipmap) {
        /* over the cache: heights and ranges from the cache's levels */
        return pgrid_tight(s, es3) ? "#define FT_PGRID_TIGHT 1\n#define FT_PGM_CLIP 1\n"
                                   : "#define FT_PGRID_TIGHT 0\n#define FT_PGM_CLIP 1\n";
    }
    return pgrid_tight(s, es3) ? "#define FT_PGRID_TIGHT 1\n" : "#define FT_PGRID_TIGHT 0\n";
}

/* A mesh pixel's bound is its quad's, flat (the tight bound; every program
 * that reads v_delta_m says so, the vertex shader from FT_PGRID_TIGHT), and
 * the error pass's buffer is at colour attachment 1 (src/lod/pgrid.h 6). */
#define PGRID_FLAT_DEFINE "#define FT_PGRID_FLAT_DELTA 1\n"
#define PGRID_AT1_DEFINE "#define FT_PGRID_ERR_LOCATION 1\n"

/* On GLES 3 the picture pass writes the error buffer too (a second colour
 * attachment, terrain.frag.glsl's FT_PGRID_ERR_OUT): the grid goes through
 * the pipeline once for both, and the envelopes test against the picture's
 * own depth. With the tight bound its pixels take their quad's bound, flat
 * (src/lod/pgrid.h 6). */
static const char *pgrid_colour_defines(const ft_scene *s, int es3)
{
    if (!es3) {
        return "";
    }
    return pgrid_tight(s, es3) ? "#define FT_PGRID_ERR_OUT 1\n" PGRID_FLAT_DEFINE
                               : "#define FT_PGRID_ERR_OUT 1\n";
}

static ft_pgm_grid_desc pgm_grid(const ft_scene *s)
{
    const ft_pgm_grid_desc g = {s->pgrid_grid_cols, s->pgrid_grid_rows, s->height_format,
                                s->pgrid_heights_clipmap};
    return g;
}

static void pgrid_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    const ft_pgm_grid_desc g = pgm_grid(s);
    ft_pgm_method_plan(&g, t, a);
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)s->width_px * s->height_px * 5u +
                                         sizeof(pgrid_programs) + 64u);
    ft_arena_plan(a, FT_POOL_METHOD, sizeof(ft_terrain_program) + 64u);
    if (g.clip) {
        /* the cache and its cell ranges instead of the window's pyramids */
        ft_clip_levels_plan(s, t, FT_CLIP_BOUNDS_RANGES, a);
        ft_arena_plan(a, FT_POOL_METHOD, sizeof(ft_terrain_program) + 64u); /* quad pass */
        return;
    }
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2], hw = 1u, h = 1u;
    if (t->pyr.minmax_levels > 0u) {
        ft_pgrid_minmax_layout(t, origin, &hw, &h);
    }
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)hw * 2u * h * sizeof(float));
    /* the residual atlas's staging (reset after upload, like the min/max
     * atlas's: the larger of the two is what the pool must hold) */
    uint32_t rw = 1u, rh = 1u;
    if (t->pyr.minmax_levels > 0u) {
        ft_pgrid_residual_layout(t, origin, &rw, &rh);
    }
    const size_t res_bytes = (size_t)rw * rh * sizeof(float);
    const size_t mm_bytes = (size_t)hw * 2u * h * sizeof(float);
    if (res_bytes > mm_bytes) {
        ft_arena_plan(a, FT_POOL_METHOD, res_bytes - mm_bytes);
    }
}

/* ---- the tight bound (src/lod/pgrid.h 6) ------------------------------------------ */

static ft_status upload_residuals(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                                  ft_arena *a, ft_error *err)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2];
    uint32_t w = 1u, h = 1u;
    memset(m->res_level_px, 0, sizeof m->res_level_px);
    ft_pgrid_residual_layout(t, origin, &w, &h);
    if (w > (uint32_t)gl->caps.max_texture_size || h > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgrid: the residual atlas %ux%u exceeds GL_MAX_TEXTURE_SIZE %d", w, h,
                       gl->caps.max_texture_size);
    }
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    float *img = NULL;
    ft_status st =
        ft_arena_take(a, FT_POOL_METHOD, (size_t)w * h * sizeof(float), (void **)&img, err);
    if (st != FT_OK) {
        return st;
    }
    ft_pgrid_residual_fill(t, img, w, h);
    const ft_pyramid *p = &t->pyr;
    m->res_levels = p->minmax_levels;
    for (uint32_t l = FT_PGRID_RES_L0; l < p->minmax_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        m->res_level_px[l][0] = (float)origin[l][0];
        m->res_level_px[l][1] = (float)origin[l][1];
        m->res_level_px[l][2] = (float)p->minmax[l].width;
        m->res_level_px[l][3] = (float)p->minmax[l].height;
    }
    const ft_scalar_format f = {FT_HEIGHT_FORMAT_FLOAT, 0.0f, 1.0f};
    st = ft_gpu_upload_scalar(gl, &f, img, w, h, GL_TEXTURE6, a, &m->res_tex, &m->gpu_bytes, err);
    gl->ActiveTexture(GL_TEXTURE0);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    return st;
}

/* The error pass's fragment defines: its error buffer at colour attachment
 * 1 (the picture's framebuffer) or 0, a mesh pixel's bound its quad's (the
 * tight bound's, flat) or interpolated. */
static const char k_flat[] = PGRID_FLAT_DEFINE;
static const char k_at1[] = PGRID_AT1_DEFINE;
static const char k_flat_at1[] = PGRID_FLAT_DEFINE PGRID_AT1_DEFINE;

/* A framebuffer of one or two grid-sized RGBA32F textures (tex1 = NULL: one). */
static ft_status make_float_target(ft_pgrid_method *m, const ft_gl *gl, GLenum unit0,
                                   GLenum unit1, uint32_t w, uint32_t h, GLuint *tex0,
                                   GLuint *tex1, GLuint *fbo, const char *what, ft_error *err)
{
    if (w > (uint32_t)gl->caps.max_texture_size || h > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED, "pgrid: the %s target %ux%u exceeds "
                       "GL_MAX_TEXTURE_SIZE %d", what, w, h, gl->caps.max_texture_size);
    }
    const ft_texture_desc d0 = {unit0, w, h, GL_RGBA32F, GL_RGBA, GL_FLOAT, 4u * sizeof(float)};
    ft_gpu_texture_create(gl, &d0, NULL, tex0, &m->gpu_bytes);
    if (tex1 != NULL) {
        ft_texture_desc d1 = d0;
        d1.unit = unit1;
        ft_gpu_texture_create(gl, &d1, NULL, tex1, &m->gpu_bytes);
    }
    gl->GenFramebuffers(1, fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, *fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex0, 0);
    if (tex1 != NULL) {
        static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, *tex1, 0);
        gl->DrawBuffers(2, both);
    }
    const GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        return ft_fail(err, FT_ERR_GPU, "pgrid: the %s target %ux%u (RGBA32F) is incomplete: "
                       "0x%04x", what, w, h, (unsigned)st);
    }
    return FT_OK;
}

/* Over the cache the quad-bound pass is the cache's variant (src/lod/pgrid.h
 * 6): a terrain program with pgm's and pgrid's uniforms, set per frame as the
 * grid's are. */
static ft_status init_quad_clip(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                                const ft_gpu_terrain *gt, ft_arena *a, ft_error *err)
{
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, sizeof(ft_terrain_program),
                                 (void **)&m->quad_clip_prog, err);
    if (st != FT_OK) {
        return st;
    }
    memset(m->quad_clip_prog, 0, sizeof *m->quad_clip_prog);
    const ft_terrain_program_desc d = {.vert_name = "pgrid_pass.vert.glsl",
                                       .frag_name = "pgrid_quad.frag.glsl",
                                       .frag_defines = "#define FT_PGM_CLIP 1\n",
                                       .method_uniforms = &k_pgrid_uniform_list};
    st = ft_terrain_program_build(gl, t, gt, &d, m->quad_clip_prog, err);
    if (st == FT_OK) {
        m->quad_clip_built = 1;
    }
    return st;
}

static ft_status init_tight(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                            const ft_gpu_terrain *gt, ft_arena *a, ft_error *err)
{
    /* over the cache the quads are bounded from its levels: no residual atlas */
    ft_status st = m->pgm.clip ? FT_OK : upload_residuals(m, gl, t, a, err);
    if (st == FT_OK) {
        st = make_float_target(m, gl, GL_TEXTURE4, GL_TEXTURE7, m->pgm.cols, m->pgm.rows,
                               &m->vtx_tex, &m->slope_tex, &m->vtx_fbo, "vertex pass", err);
    }
    if (st == FT_OK) {
        st = make_float_target(m, gl, GL_TEXTURE5, GL_TEXTURE5, m->pgm.cols - 1u,
                               m->pgm.rows - 1u, &m->quad_tex, NULL, &m->quad_fbo, "quad bound",
                               err);
    }
    if (st == FT_OK) {
        st = make_float_target(m, gl, GL_TEXTURE7, GL_TEXTURE7, m->pgm.cols, m->pgm.rows,
                               &m->shape_tex, NULL, &m->shape_fbo, "vertex bound", err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, sizeof(ft_terrain_program),
                           (void **)&m->vtx_prog, err);
    }
    if (st != FT_OK) {
        return st;
    }
    memset(m->vtx_prog, 0, sizeof *m->vtx_prog);
    const ft_terrain_program_desc vtx = {.vert_name = "pgrid_pass.vert.glsl",
                                         .frag_name = "pgrid_vtx.frag.glsl",
                                         .frag_defines = m->pgm.clip ? "#define FT_PGM_CLIP 1\n"
                                                                     : NULL,
                                         .method_uniforms = &k_pgrid_uniform_list};
    st = ft_terrain_program_build(gl, t, gt, &vtx, m->vtx_prog, err);
    if (st != FT_OK) {
        return st;
    }
    m->vtx_prog_built = 1;
    st = m->pgm.clip ? init_quad_clip(m, gl, t, gt, a, err)
                     : ft_program_link(gl, "pgrid_pass.vert.glsl", "pgrid_quad.frag.glsl", NULL,
                                       "a_uv", &m->quad_prog, err);
    if (st == FT_OK) {
        st = ft_program_link(gl, "pgrid_pass.vert.glsl", "pgrid_shape.frag.glsl", NULL, "a_uv",
                             &m->shape_prog, err);
    }
    if (st != FT_OK) {
        return st;
    }
    const GLuint sp = m->shape_prog;
    gl->UseProgram(sp);
    gl->Uniform1i(gl->GetUniformLocation(sp, "u_pgrid_quad"), 5);
    gl->Uniform1i(gl->GetUniformLocation(sp, "u_pgrid_slope"), 7);
    gl->Uniform2f(gl->GetUniformLocation(sp, "u_pgrid_cells"), (float)(m->pgm.cols - 1u),
                  (float)(m->pgm.rows - 1u));
    if (m->pgm.clip) {
        gl->UseProgram(0);
        m->tight = 1;
        return ft_gl_check(gl, "pgrid init (tight bound over the cache: vertex and quad passes)",
                           err);
    }
    const GLuint q = m->quad_prog;
    m->uq_vtx = gl->GetUniformLocation(q, "u_pgrid_vtx");
    m->uq_res = gl->GetUniformLocation(q, "u_pgrid_res");
    m->uq_heights = gl->GetUniformLocation(q, "u_heights");
    m->uq_grid_size = gl->GetUniformLocation(q, "u_grid_size");
    m->uq_cell_m = gl->GetUniformLocation(q, "u_cell_m");
    m->uq_origin = gl->GetUniformLocation(q, "u_origin_rel_eye_m");
    m->uq_pack = gl->GetUniformLocation(q, "u_pack");
    m->uq_drop = gl->GetUniformLocation(q, "u_earth_drop_per_m2");
    m->uq_res_levels = gl->GetUniformLocation(q, "u_pgrid_res_levels");
    for (uint32_t l = 0; l < FT_PYRAMID_LEVELS_MAX; ++l) {
        char name[40];
        (void)snprintf(name, sizeof name, "u_pgrid_res_level[%u]", l);
        m->uq_res_level[l] = gl->GetUniformLocation(q, name);
    }
    /* the uniforms that never change */
    gl->UseProgram(q);
    gl->Uniform1i(m->uq_heights, 0);
    gl->Uniform1i(m->uq_vtx, 4);
    gl->Uniform1i(m->uq_res, 6);
    gl->Uniform2f(m->uq_grid_size, (float)t->width, (float)t->height);
    gl->Uniform2f(m->uq_cell_m, (float)t->cell_x_m, (float)t->cell_y_m);
    gl->Uniform2f(m->uq_pack, gt->pack_min_m,
                  gt->format == FT_HEIGHT_FORMAT_PACKED ? gt->pack_range_m : 0.0f);
    gl->Uniform1f(m->uq_drop, (float)t->curv_drop_per_m2);
    gl->Uniform1f(m->uq_res_levels, (float)m->res_levels);
    for (uint32_t l = 0; l < m->res_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        gl->Uniform4f(m->uq_res_level[l], m->res_level_px[l][0], m->res_level_px[l][1],
                      m->res_level_px[l][2], m->res_level_px[l][3]);
    }
    gl->UseProgram(0);
    m->tight = 1;
    return ft_gl_check(gl, "pgrid init (tight bound: residual atlas, vertex and quad passes)",
                       err);
}

/* Copies a w x h level into a row-major atlas atlas_w texels wide, its
 * corner at (x0, y0). */
static void atlas_put(float *atlas, uint32_t atlas_w, uint32_t x0, uint32_t y0, const float *src,
                      uint32_t w, uint32_t h)
{
    for (uint32_t y = 0; y < h; ++y) {
        memcpy(atlas + (size_t)(y0 + y) * atlas_w + x0, src + (size_t)y * w,
               (size_t)w * sizeof(float));
    }
}

static ft_status upload_minmax(ft_pgrid_method *m, const ft_gl *gl, const ft_scene *s,
                               const ft_terrain *t, ft_arena *a, ft_error *err)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2];
    uint32_t hw = 1u, h = 1u;
    const ft_pyramid *p = &t->pyr;
    memset(m->mm_level_px, 0, sizeof m->mm_level_px);
    ft_pgrid_minmax_layout(t, origin, &hw, &h);
    m->mm_half_w = hw;
    m->mm_h = h;
    m->mm_levels = p->minmax_levels;
    if (2u * hw > (uint32_t)gl->caps.max_texture_size || h > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgrid: the min/max atlas %ux%u exceeds GL_MAX_TEXTURE_SIZE %d", 2u * hw, h,
                       gl->caps.max_texture_size);
    }
    m->mm_fmt = ft_gpu_height_format(gl, s->height_format, t->min_height_m, t->max_height_m);
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    float *img = NULL;
    const size_t n = (size_t)hw * 2u * h;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, n * sizeof(float), (void **)&img, err);
    if (st != FT_OK) {
        return st;
    }
    for (size_t i = 0; i < n; ++i) {
        img[i] = t->min_height_m;
    }
    for (uint32_t l = FT_PGRID_ATLAS_L0; l < p->minmax_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        const ft_pyramid_level *lv = &p->minmax[l];
        atlas_put(img, hw * 2u, origin[l][0], origin[l][1], lv->min_m, lv->width, lv->height);
        atlas_put(img, hw * 2u, origin[l][0] + hw, origin[l][1], lv->max_m, lv->width,
                  lv->height);
        m->mm_level_px[l][0] = (float)origin[l][0];
        m->mm_level_px[l][1] = (float)origin[l][1];
        m->mm_level_px[l][2] = (float)lv->width;
        m->mm_level_px[l][3] = (float)lv->height;
    }
    for (uint32_t l = 0; l < FT_PGRID_ATLAS_L0 && l < p->minmax_levels; ++l) {
        m->mm_level_px[l][2] = (float)p->minmax[l].width;
        m->mm_level_px[l][3] = (float)p->minmax[l].height;
    }
    st = ft_gpu_upload_scalar(gl, &m->mm_fmt, img, hw * 2u, h, GL_TEXTURE2, a, &m->mm_tex,
                              &m->gpu_bytes, err);
    gl->ActiveTexture(GL_TEXTURE0);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    return st;
}

/* The ray caster's max atlas (src/lod/pgrid.h 4): the max pyramid's levels
 * >= 1 in the residual atlas's layout (level 0 is the cell's 4 samples, which
 * the traversal reads anyway), so each visit of its loop makes one atlas
 * fetch whatever the level. Its staging is the residual atlas's (planned). */
static ft_status upload_rc_max(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                               ft_arena *a, ft_error *err)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2];
    uint32_t w = 1u, h = 1u;
    const ft_pyramid *p = &t->pyr;
    ft_pgrid_rc_max_layout(t, origin, &w, &h);
    memset(m->rc_max_level_px, 0, sizeof m->rc_max_level_px);
    if (w > (uint32_t)gl->caps.max_texture_size || h > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgrid: the ray caster's max atlas %ux%u exceeds GL_MAX_TEXTURE_SIZE %d",
                       w, h, gl->caps.max_texture_size);
    }
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    float *img = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, (size_t)w * h * sizeof(float),
                                 (void **)&img, err);
    if (st != FT_OK) {
        return st;
    }
    for (size_t i = 0; i < (size_t)w * h; ++i) {
        img[i] = t->min_height_m;
    }
    for (uint32_t l = 1u; l < p->minmax_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        const ft_pyramid_level *lv = &p->minmax[l];
        atlas_put(img, w, origin[l][0], origin[l][1], lv->max_m, lv->width, lv->height);
        m->rc_max_level_px[l][0] = (float)origin[l][0];
        m->rc_max_level_px[l][1] = (float)origin[l][1];
        m->rc_max_level_px[l][2] = (float)lv->width;
        m->rc_max_level_px[l][3] = (float)lv->height;
    }
    m->rc_max_level_px[0][2] = (float)p->minmax[0].width;
    m->rc_max_level_px[0][3] = (float)p->minmax[0].height;
    st = ft_gpu_upload_scalar(gl, &m->mm_fmt, img, w, h, GL_TEXTURE0 + FT_TEX_UNIT_RC_MAX, a,
                              &m->rc_max_tex, &m->gpu_bytes, err);
    gl->ActiveTexture(GL_TEXTURE0);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    return st;
}

/* The tile pass's target (one R8 texel a tile: its largest dilated code) and
 * program. */
static ft_status init_tiles(ft_pgrid_method *m, const ft_gl *gl, const ft_scene *s,
                            ft_error *err)
{
    m->tile_px = s->pgrid_raycast_tile_px;
    m->tiles_w = (m->w_px + m->tile_px - 1u) / m->tile_px;
    m->tiles_h = (m->h_px + m->tile_px - 1u) / m->tile_px;
    const ft_texture_desc d = {GL_TEXTURE0 + FT_TEX_UNIT_RC_TILES, m->tiles_w, m->tiles_h,
                               GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1u};
    ft_gpu_texture_create(gl, &d, NULL, &m->tile_tex, &m->gpu_bytes);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->GenFramebuffers(1, &m->tile_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->tile_fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m->tile_tex, 0);
    const GLenum fst = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (fst != GL_FRAMEBUFFER_COMPLETE) {
        return ft_fail(err, FT_ERR_GPU, "pgrid: ray-cast tile target %ux%u incomplete: 0x%04x",
                       m->tiles_w, m->tiles_h, (unsigned)fst);
    }
    ft_status st = ft_program_link(gl, "pgrid_pass.vert.glsl", "pgrid_rc_tiles.frag.glsl", NULL,
                                   "a_uv", &m->tile_prog, err);
    if (st != FT_OK) {
        return st;
    }
    m->ut_err = gl->GetUniformLocation(m->tile_prog, "u_err");
    m->ut_size = gl->GetUniformLocation(m->tile_prog, "u_rc_size");
    m->ut_tile_px = gl->GetUniformLocation(m->tile_prog, "u_rc_tile_px");
    return FT_OK;
}

static ft_status make_error_target(ft_pgrid_method *m, const ft_gl *gl, ft_error *err)
{
    const GLsizei w = (GLsizei)m->w_px, h = (GLsizei)m->h_px;
    gl->GenRenderbuffers(1, &m->err_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, m->err_depth);
    gl->RenderbufferStorage(GL_RENDERBUFFER,
                            gl->caps.has_depth24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT16,
                            w, h);
    const ft_texture_desc d = {GL_TEXTURE3, m->w_px, m->h_px, m->es3 ? GL_RGBA8 : GL_RGBA,
                               GL_RGBA, GL_UNSIGNED_BYTE, 4u};
    ft_gpu_texture_create(gl, &d, NULL, &m->err_tex, &m->gpu_bytes);
    gl->GenFramebuffers(1, &m->err_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->err_fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m->err_tex, 0);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                m->err_depth);
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        return ft_fail(err, FT_ERR_GPU, "pgrid: error buffer %ux%u incomplete: 0x%04x", m->w_px,
                       m->h_px, (unsigned)st);
    }
    m->gpu_bytes += (uint64_t)w * (uint64_t)h * 4u; /* the depth (colour counted above) */
    return FT_OK;
}

static ft_status pgrid_init(ft_pgrid_method *m, const ft_gl *gl, const ft_scene *s,
                            const ft_terrain *t, ft_arena *a, ft_error *err)
{
    memset(m, 0, sizeof *m);
    if (t->pyr.minmax_levels < 1u) {
        return ft_fail(err, FT_ERR_ARG, "pgrid needs the terrain's min/max pyramid in memory");
    }
    if (gl->caps.max_vertex_texture_units < 3) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgrid samples heights, avg and min/max atlases in the vertex shader: "
                       "it needs 3 vertex texture units, this device has %d",
                       gl->caps.max_vertex_texture_units);
    }
    const ft_pgm_grid_desc g = pgm_grid(s);
    ft_status st = ft_pgm_method_init(&m->pgm, gl, &g, t, a, err);
    if (st == FT_OK && g.clip) {
        st = ft_pgm_method_clip_init(&m->pgm, gl, s, t, FT_CLIP_BOUNDS_RANGES, a, err);
    }
    if (st != FT_OK) {
        return st;
    }
    m->w_px = s->width_px;
    m->h_px = s->height_px;
    m->distribution = s->pgrid_view_distribution ? FT_PGRID_DIST_VIEW : FT_PGRID_DIST_UNIFORM;
    m->gamma_px = s->pgrid_gamma_px;
    m->lod_scale = 1.0;
    m->raycast_max_px = s->pgrid_raycast_max_px;
    m->es3 = (gl->api == FT_GL_API_ES3);
    m->ray_casting = s->pgrid_ray_casting && m->es3;
    if (s->pgrid_ray_casting && !m->es3) {
        (void)fprintf(stderr,
                      "pgrid: GLES 2 context (no gl_FragDepth, no texelFetch): running WITHOUT "
                      "ray casting; the error is the mesh's (reported as tau_achieved_px), "
                      "gamma_px = %g is not guaranteed\n",
                      s->pgrid_gamma_px);
    }
    if (!g.clip) {
        st = upload_minmax(m, gl, s, t, a, err);
        if (st != FT_OK) {
            return st;
        }
    }
    st = make_error_target(m, gl, err);
    if (st != FT_OK) {
        return st;
    }
    const size_t px = (size_t)m->w_px * m->h_px;
    st = ft_arena_take(a, FT_POOL_METHOD, px * 4u, (void **)&m->readback, err);
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, px, (void **)&m->work, err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, sizeof(pgrid_programs), (void **)&m->err_prog,
                           err);
    }
    if (st != FT_OK) {
        return st;
    }
    memset(m->err_prog, 0, sizeof(pgrid_programs));
    ft_gpu_terrain gt;
    memset(&gt, 0, sizeof gt);
    const ft_scalar_format *hf = g.clip ? &m->pgm.cl.fmt : &m->mm_fmt;
    gt.format = hf->format;
    gt.pack_min_m = hf->pack_min;
    gt.pack_range_m = hf->pack_range;
    const int tight = pgrid_tight(s, m->es3);
    const ft_terrain_program_desc errd = {.vert_name = "pgrid.vert.glsl",
                                          .vert_defines = pgrid_vertex_defines(s, m->es3),
                                          .frag_name = "pgrid_err.frag.glsl",
                                          .frag_defines = tight ? k_flat : NULL,
                                          .method_uniforms = &k_pgrid_uniform_list};
    st = ft_terrain_program_build(gl, t, &gt, &errd, m->err_prog, err);
    if (st != FT_OK) {
        return st;
    }
    m->err_prog_built = 1;
    m->mrt = m->es3;
    if (m->mrt && m->ray_casting) {
        const ft_terrain_program_desc envd = {.vert_name = "pgrid.vert.glsl",
                                              .vert_defines = pgrid_vertex_defines(s, m->es3),
                                              .frag_name = "pgrid_err.frag.glsl",
                                              .frag_defines = tight ? k_flat_at1 : k_at1,
                                              .method_uniforms = &k_pgrid_uniform_list};
        st = ft_terrain_program_build(gl, t, &gt, &envd, env_prog(m), err);
        if (st != FT_OK) {
            return st;
        }
        m->env_prog_built = 1;
    }
    char frag_buf[FT_SHADE_DEFINES_MAX];
    if (m->ray_casting) {
        static const float corners[8] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f};
        /* over the cache the traversal reads the cache's levels and cell
         * ranges (src/lod/pgrid.h 7), not the window's max pyramid */
        char rc_defines[FT_SHADE_DEFINES_MAX + 32];
        (void)snprintf(rc_defines, sizeof rc_defines, "%s%s",
                       g.clip ? "#define FT_RC_CLIP 1\n" : "",
                       ft_program_shade_defines(s, t, frag_buf));
        st = ft_program_link(gl, "pgrid_rc.vert.glsl", "pgrid_rc.frag.glsl", rc_defines,
                             "a_corner", &m->rc_prog, err);
        if (st != FT_OK) {
            return st;
        }
        locate_rc(gl, m->rc_prog, rc_locs(m));
        if (!g.clip) {
            st = upload_rc_max(m, gl, t, a, err);
        }
        if (st == FT_OK) {
            st = init_tiles(m, gl, s, err);
        }
        if (st != FT_OK) {
            return st;
        }
        gl->GenBuffers(1, &m->quad_vbo);
        gl->BindBuffer(GL_ARRAY_BUFFER, m->quad_vbo);
        gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof corners, corners, GL_STATIC_DRAW);
        m->gpu_bytes += sizeof corners;
        if (pgrid_tight(s, m->es3)) {
            /* the grid's vertex shader then reads 6 textures, two of them
             * float render targets */
            if (!gl->caps.has_float_color_buffer || !gl->caps.has_float_textures ||
                gl->caps.max_vertex_texture_units < 6) {
                return ft_fail(err, FT_ERR_UNSUPPORTED,
                               "pgrid.error_bound = residual needs float render targets and 6 "
                               "vertex texture units (this context: float targets %s, %d "
                               "units); set pgrid.error_bound = relief",
                               gl->caps.has_float_color_buffer ? "yes" : "no",
                               gl->caps.max_vertex_texture_units);
            }
            st = init_tight(m, gl, t, &gt, a, err);
            if (st != FT_OK) {
                return st;
            }
        }
    }
    if (m->ray_casting) {
        /* the late decision's two pixel-pack buffers (src/lod/pgrid.h 5) */
        const GLsizeiptr bytes = (GLsizeiptr)m->w_px * (GLsizeiptr)m->h_px * 4;
        gl->GenBuffers(2, m->pack_pbo);
        for (int k = 0; k < 2; ++k) {
            gl->BindBuffer(GL_PIXEL_PACK_BUFFER, m->pack_pbo[k]);
            gl->BufferData(GL_PIXEL_PACK_BUFFER, bytes, NULL, GL_STREAM_READ);
            m->gpu_bytes += (uint64_t)bytes;
        }
        gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        m->late = 1;
    }
    m->thr = FT_PGRID_CODES;
    /* uniform columns until a frame's codes say otherwise */
    for (uint32_t b = 0; b <= FT_PGRID_COL_BANDS; ++b) {
        const float t_b = (float)b / (float)FT_PGRID_COL_BANDS;
        m->col_t[b] = m->col_t_next[b] = m->col_t_pbo[0][b] = m->col_t_pbo[1][b] = t_b;
    }
    m->col_warp = m->late && s->pgrid_columns_error;
    if (s->pgrid_columns_error && !m->col_warp) {
        (void)fprintf(stderr, "pgrid: columns = error moves the columns by the ray-cast error "
                              "buffer (GLES 3, ray_casting = 1); this context has none: the "
                              "columns stay uniform\n");
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return ft_gl_check(gl, "pgrid init (min/max atlas, error buffer, ray caster)", err);
}

static void pgrid_set_lod_scale(ft_pgrid_method *m, double scale)
{
    const double s = scale < 1.0 ? 1.0 : scale;
    if (s != m->lod_scale) {
        m->lod_scale = s;
        m->have_decision = 0; /* decide again for the same view */
    }
}

static void pgrid_select(ft_pgrid_method *m, const ft_terrain *t, const ft_camera *cam)
{
    ft_pgm_method_select(&m->pgm, t, cam);
}

/* Over the cache: its spare-time updates, and the depth range of what it
 * holds (the window's grid does not bound it). */
static void ops_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    ft_pgm_method_spare(&m->u.pgrid.pgm, now, deadline_ns);
}

static int ops_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                         double corner_cos)
{
    return ft_pgm_method_fit_depth(&m->u.pgrid.pgm, t, cam, corner_cos);
}

/* Uniforms of pgrid.vert.glsl beyond pgm's, on program p (locations from
 * init: ft_terrain_program carries them). */
static void set_grid_uniforms(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain_program *p)
{
    const ft_pgm_sampling *s = &m->pgm.sampling;
    float s0 = 0.0f, s1 = 0.0f;
    if (m->distribution == FT_PGRID_DIST_VIEW) {
        s0 = (float)ft_pgrid_row_s(s->depression_rad, s->rect[1]);
        s1 = (float)ft_pgrid_row_s(s->depression_rad, s->rect[3]);
    }
    gl->Uniform4f(p->method_u[FT_PGRID_U_DIST], (float)m->distribution, s0, s1, (float)s->depression_rad);
    gl->Uniform1i(p->method_u[FT_PGRID_U_MM], 2);
    gl->Uniform4f(p->method_u[FT_PGRID_U_MM_INFO], (float)m->mm_half_w, (float)m->mm_h, m->mm_fmt.pack_min,
                  m->mm_fmt.format == FT_HEIGHT_FORMAT_PACKED ? m->mm_fmt.pack_range : 0.0f);
    gl->Uniform1f(p->method_u[FT_PGRID_U_MM_LEVELS], (float)m->mm_levels);
    for (uint32_t l = 0; l < m->mm_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        gl->Uniform4f(p->method_u[FT_PGRID_U_MM_LEVEL + l], m->mm_level_px[l][0], m->mm_level_px[l][1],
                      m->mm_level_px[l][2], m->mm_level_px[l][3]);
    }
    gl->Uniform1i(p->method_u[FT_PGRID_U_RANGE], 2); /* over the cache (pgrid_draw) */
    gl->Uniform1i(p->method_u[FT_PGRID_U_BLOCK_RANGE], 3);
    gl->Uniform2f(p->method_u[FT_PGRID_U_TOP_RANGE], m->pgm.cl.top_range_m[0],
                  m->pgm.cl.top_range_m[1]);
    gl->Uniform1i(p->method_u[FT_PGRID_U_VTX], 4);
    gl->Uniform1i(p->method_u[FT_PGRID_U_SLOPE], 7);
    gl->Uniform1fv(p->method_u[FT_PGRID_U_COLS], (GLsizei)(FT_PGRID_COL_BANDS + 1u), m->col_t);
    gl->Uniform1f(p->method_u[FT_PGRID_U_COLS_ON], m->col_warp ? 1.0f : 0.0f);
}

/* The tight bound's passes (src/lod/pgrid.h 6), before the grid is drawn:
 * the grid's vertices into vtx_tex, every quad's bound into quad_tex, every
 * vertex's slope and delta (the largest bound of its quads) into shape_tex.
 * The grid's vertex shader then reads vtx_tex (unit 4) and shape_tex (unit
 * 7). */
static void tight_passes(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                         const ft_camera *cam, GLint fb)
{
    GLint vp[4];
    gl->GetIntegerv(GL_VIEWPORT, vp);
    const float ox = (float)(t->origin_world_x_m - cam->eye_m[0]);
    const float oy = (float)(t->origin_world_y_m - cam->eye_m[1]);
    const float oz = (float)(0.0 - cam->eye_m[2]);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->quad_vbo);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    /* the vertex pass */
    const ft_terrain_program *v = m->vtx_prog;
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->vtx_fbo);
    gl->Viewport(0, 0, (GLsizei)m->pgm.cols, (GLsizei)m->pgm.rows);
    gl->UseProgram(v->program);
    gl->Uniform3f(v->u_origin_rel_eye_m, ox, oy, oz);
    set_grid_uniforms(m, gl, v);
    ft_pgm_method_bind(&m->pgm, gl, v);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->quad_vbo);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    /* the quad bounds */
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->quad_fbo);
    gl->Viewport(0, 0, (GLsizei)(m->pgm.cols - 1u), (GLsizei)(m->pgm.rows - 1u));
    gl->ActiveTexture(GL_TEXTURE4);
    gl->BindTexture(GL_TEXTURE_2D, m->vtx_tex);
    if (m->pgm.clip) {
        /* the cache's levels (unit 1, bound with pgm's uniforms) and its
         * cell and block ranges (units 2 and 3, bound by pgrid_draw) */
        const ft_terrain_program *q = m->quad_clip_prog;
        gl->UseProgram(q->program);
        set_grid_uniforms(m, gl, q);
        ft_pgm_method_bind(&m->pgm, gl, q);
    } else {
        gl->ActiveTexture(GL_TEXTURE6);
        gl->BindTexture(GL_TEXTURE_2D, m->res_tex);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->UseProgram(m->quad_prog);
        gl->Uniform3f(m->uq_origin, ox, oy, oz);
    }
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    /* the vertex bounds (vtx_tex on 4, quad_tex on 5, slope_tex on 7) */
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->shape_fbo);
    gl->Viewport(0, 0, (GLsizei)m->pgm.cols, (GLsizei)m->pgm.rows);
    gl->UseProgram(m->shape_prog);
    gl->ActiveTexture(GL_TEXTURE5);
    gl->BindTexture(GL_TEXTURE_2D, m->quad_tex);
    gl->ActiveTexture(GL_TEXTURE7);
    gl->BindTexture(GL_TEXTURE_2D, m->slope_tex);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl->BindTexture(GL_TEXTURE_2D, m->shape_tex); /* unit 7 from here on */
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, (GLuint)fb);
    gl->Viewport(vp[0], vp[1], vp[2], vp[3]);
}

static int same_decision_view(const ft_pgrid_method *m, const ft_camera *cam)
{
    return m->have_decision && memcmp(m->dec_eye_m, cam->eye_m, sizeof m->dec_eye_m) == 0 &&
           memcmp(m->dec_fwd, cam->forward, sizeof m->dec_fwd) == 0 &&
           memcmp(m->dec_up, cam->up, sizeof m->dec_up) == 0;
}

/* The dilated-code histogram and terrain pixels of m->readback. */
static void count_codes(ft_pgrid_method *m)
{
    ft_pgrid_histogram(m->readback, m->w_px, m->h_px, m->work, m->hist);
    uint64_t terrain = 0u; /* pixels the mesh (or an envelope) covers: code > 0 */
    for (size_t k = 0; k < (size_t)m->w_px * m->h_px; ++k) {
        terrain += (m->readback[4u * k + 1u] != 0u);
    }
    m->terrain_px = terrain;
}

static void remember_view(ft_pgrid_method *m, const ft_camera *cam)
{
    memcpy(m->dec_eye_m, cam->eye_m, sizeof m->dec_eye_m);
    memcpy(m->dec_fwd, cam->forward, sizeof m->dec_fwd);
    memcpy(m->dec_up, cam->up, sizeof m->dec_up);
    m->have_decision = 1;
}

/* The column warp (src/lod/pgrid.h 1) from the codes of pack buffer slot's
 * frame, in m->readback: the band of a pixel is that of its column t (the
 * error buffer's B), through the knots that frame was drawn with. */
static void warp_columns(ft_pgrid_method *m, uint32_t slot, double gamma)
{
    memset(m->band_hist, 0, sizeof m->band_hist);
    const float *knots = m->col_t_pbo[slot];
    /* the band of each 8-bit column value, once, not once a pixel */
    uint8_t band_of[256];
    for (uint32_t v = 0; v < 256u; ++v) {
        double bf = floor(ft_pgrid_col_u(knots, (double)v / 255.0) * (double)FT_PGRID_COL_BANDS);
        bf = bf < 0.0 ? 0.0 : (bf > FT_PGRID_COL_BANDS - 1.0 ? FT_PGRID_COL_BANDS - 1.0 : bf);
        band_of[v] = (uint8_t)bf;
    }
    for (size_t k = 0; k < (size_t)m->w_px * m->h_px; ++k) {
        const uint8_t code = m->readback[4u * k + 1u];
        if (code == 0u) continue;
        m->band_hist[band_of[m->readback[4u * k + 2u]]][code] += 1u;
    }
    ft_pgrid_col_warp((const uint32_t (*)[256])m->band_hist, knots, gamma, m->col_t_next);
}

/* The late decision (src/lod/pgrid.h 5; GLES 3 with ray casting). This frame's
 * error buffer goes into a pixel-pack buffer without waiting for it; the
 * previous frame's, complete by now, is mapped and gives the histogram that
 * sets this frame's threshold. The threshold is applied per pixel on the GPU
 * to this frame's own buffer, so the bound reported below holds for this
 * frame whatever its count; what comes one frame late is the count: a view
 * that changes abruptly can ray cast more than raycast_max_px for one frame
 * (time, not error), and the pixels reported (raycast_px, terrain_px) are the
 * previous frame's, at the threshold it used. The first frame has no
 * histogram: it ray casts everything over gamma. */
static void decide_late(ft_pgrid_method *m, const ft_gl *gl, const ft_camera *cam)
{
    const uint32_t cur = m->pbo_next, prev = cur ^ 1u;
    const size_t bytes = (size_t)m->w_px * m->h_px * 4u;
    const double gamma = m->gamma_px * m->lod_scale; /* degradation raises gamma */
    int have = 0;
    if (m->pbo_full[prev]) {
        gl->BindBuffer(GL_PIXEL_PACK_BUFFER, m->pack_pbo[prev]);
        const void *p = gl->MapBufferRange(GL_PIXEL_PACK_BUFFER, 0, (GLsizeiptr)bytes,
                                           GL_MAP_READ_BIT);
        if (p != NULL) {
            memcpy(m->readback, p, bytes);
            have = 1;
        }
        (void)gl->UnmapBuffer(GL_PIXEL_PACK_BUFFER);
        m->pbo_full[prev] = 0;
    }
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, m->pack_pbo[cur]);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, (GLsizei)m->w_px, (GLsizei)m->h_px, GL_RGBA, GL_UNSIGNED_BYTE,
                   (void *)0);
    gl->BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    m->pbo_full[cur] = 1;
    m->pbo_next = prev;
    memcpy(m->col_t_pbo[cur], m->col_t, sizeof m->col_t); /* what this frame drew */
    if (have) {
        count_codes(m);
        if (m->col_warp) {
            warp_columns(m, prev, gamma);
        }
        /* the previous frame's pixels at the threshold it used */
        uint64_t last = 0u;
        for (uint32_t c = m->thr; c < FT_PGRID_CODES; ++c) last += m->hist[c];
        m->rc_px = last;
        uint64_t unused;
        m->thr = ft_pgrid_budget_threshold(m->hist, gamma, m->raycast_max_px, &unused,
                                           &m->budget_hit);
    } else {
        m->rc_px = 0u;
        m->terrain_px = 0u;
        m->thr = ft_pgrid_code(gamma);
        m->budget_hit = 0;
    }
    /* pixels under the threshold have codes <= thr - 1 */
    m->achieved_px = m->budget_hit ? ft_pgrid_code_rho_hi(m->thr - 1u) : gamma;
    remember_view(m, cam);
}

/* Over the cache, a frame that ray casts reports its leaves' error too
 * (src/lod/pgrid.h 7): rays that end on a coarser level's surface. */
static void add_leaf_bound(ft_pgrid_method *m, const ft_terrain *t, const ft_camera *cam)
{
    m->leaf_px = 0.0;
    if (!m->pgm.clip || !m->ray_casting || m->thr >= FT_PGRID_CODES) {
        return;
    }
    const ft_clip_world w = ft_clip_levels_world(t);
    /* the finest data's top: the database's (its data tiles'), or the
     * terrain's own when the cache reads it */
    const double top_m = (t->db != NULL) ? (double)t->db->hdr.max_height_m : (double)t->max_height_m;
    /* pieces under gamma need no second look: the frame reports gamma */
    m->leaf_px = ft_pgrid_cache_leaf_bound_px(&m->pgm.cl.cache, &m->pgm.clip_view, &w, cam,
                                              t->curv_drop_per_m2, top_m,
                                              m->gamma_px * m->lod_scale);
    if (m->leaf_px > m->achieved_px) {
        m->achieved_px = m->leaf_px; /* +INF where a deviation is unknown */
    }
}

static void decide(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain *t,
                   const ft_camera *cam)
{
    if (m->late) {
        decide_late(m, gl, cam);
        add_leaf_bound(m, t, cam);
        return;
    }
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, (GLsizei)m->w_px, (GLsizei)m->h_px, GL_RGBA, GL_UNSIGNED_BYTE,
                   m->readback);
    count_codes(m);
    uint32_t top = 0u; /* largest dilated code present */
    for (uint32_t c = 1; c < FT_PGRID_CODES; ++c) {
        if (m->hist[c] != 0u) top = c;
    }
    if (m->ray_casting) {
        /* the degradation policy trades error for time: it raises gamma */
        const double gamma = m->gamma_px * m->lod_scale;
        m->thr = ft_pgrid_budget_threshold(m->hist, gamma, m->raycast_max_px, &m->rc_px,
                                           &m->budget_hit);
        /* pixels under the threshold have codes <= thr - 1 */
        const uint32_t below = (m->thr < top + 1u) ? m->thr - 1u : top;
        const double hi = (below >= 1u) ? ft_pgrid_code_rho_hi(below) : 0.0;
        m->achieved_px = m->budget_hit ? hi : ((hi < gamma) ? hi : gamma);
    } else {
        m->thr = FT_PGRID_CODES;
        m->rc_px = 0u;
        m->budget_hit = 0;
        m->achieved_px = (top >= 1u) ? ft_pgrid_code_rho_hi(top) : 0.0;
    }
    add_leaf_bound(m, t, cam);
    remember_view(m, cam);
}

/* The tile pass (src/lod/pgrid.h 4): each tile's largest code over the tile
 * and a one-pixel border, from the error buffer, into tile_tex. */
static void mark_tiles(ft_pgrid_method *m, const ft_gl *gl)
{
    GLint fb = 0, vp[4];
    gl->GetIntegerv(GL_FRAMEBUFFER_BINDING, &fb);
    gl->GetIntegerv(GL_VIEWPORT, vp);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->tile_fbo);
    gl->Viewport(0, 0, (GLsizei)m->tiles_w, (GLsizei)m->tiles_h);
    gl->UseProgram(m->tile_prog);
    gl->Uniform1i(m->ut_err, 3);
    gl->Uniform2f(m->ut_size, (float)m->w_px, (float)m->h_px);
    gl->Uniform1f(m->ut_tile_px, (float)m->tile_px);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4); /* no depth attachment: every tile drawn */
    gl->BindFramebuffer(GL_FRAMEBUFFER, (GLuint)fb);
    gl->Viewport(vp[0], vp[1], vp[2], vp[3]);
}

static void ray_cast(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam)
{
    const GLuint prog = m->rc_prog;
    const int pos_pass = (p->shade.ramp_h < 0);
    gl->ActiveTexture(GL_TEXTURE3);
    gl->BindTexture(GL_TEXTURE_2D, m->err_tex);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->quad_vbo);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    mark_tiles(m, gl);
    gl->UseProgram(prog);
    const pgrid_rc_locs *u = rc_locs(m);
    gl->Uniform1i(u->err, 3);
    gl->Uniform1i(u->heights, 0);
    gl->Uniform1i(u->tiles, FT_TEX_UNIT_RC_TILES);
    gl->Uniform1f(u->tile_px, (float)m->tile_px);
    gl->Uniform1f(u->tiles_w, (float)m->tiles_w);
    gl->Uniform1f(u->thr, (float)m->thr);
    if (m->pgm.clip) {
        /* the cache as the grid saw it (src/lod/pgrid.h 7): heights atlas on
         * unit 1, cell ranges on unit 2; the ray starts at the eye */
        const ft_pgm_method *pm = &m->pgm;
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, pm->cl.tex[0]);
        gl->ActiveTexture(GL_TEXTURE2);
        gl->BindTexture(GL_TEXTURE_2D, pm->cl.range_tex);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->Uniform1i(u->atlas, 1);
        gl->Uniform1i(u->range, 2);
        gl->Uniform2f(u->atlas_pack, pm->cl.fmt.pack_min,
                      pm->cl.fmt.format == FT_HEIGHT_FORMAT_PACKED ? pm->cl.fmt.pack_range : 0.0f);
        gl->Uniform1f(u->levels, (float)pm->levels);
        for (uint32_t l = 0; l < pm->levels && l < FT_CLIP_LEVELS_MAX; ++l) {
            float lv[4], box[4];
            ft_pgm_method_clip_level(pm, l, lv, box);
            gl->Uniform4fv(u->clip_level[l], 1, lv);
            gl->Uniform4fv(u->clip_box[l], 1, box);
        }
        const double *cb = pm->clip_view.clamp_m;
        gl->Uniform4f(u->clamp, (float)cb[0], (float)cb[1], (float)cb[2], (float)cb[3]);
        gl->Uniform4f(u->misc, (float)pm->cl.side, (float)pm->transition_samples,
                      (float)pm->levels, (float)pm->cl.atlas_cols);
        gl->Uniform3f(u->eye_g, 0.0f, 0.0f, (float)cam->eye_m[2]);
    } else {
        gl->Uniform1i(u->rc_max, FT_TEX_UNIT_RC_MAX);
        gl->Uniform2f(u->pack, m->mm_fmt.pack_min,
                      m->mm_fmt.format == FT_HEIGHT_FORMAT_PACKED ? m->mm_fmt.pack_range : 0.0f);
        gl->Uniform2f(u->grid_size, (float)t->width, (float)t->height);
        gl->Uniform1f(u->levels, (float)m->mm_levels);
        for (uint32_t l = 0; l < m->mm_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
            gl->Uniform4f(u->max_level[l], m->rc_max_level_px[l][0], m->rc_max_level_px[l][1],
                          m->rc_max_level_px[l][2], m->rc_max_level_px[l][3]);
        }
        gl->Uniform3f(u->eye_g, (float)((cam->eye_m[0] - t->origin_world_x_m) / t->cell_x_m),
                      (float)((cam->eye_m[1] - t->origin_world_y_m) / t->cell_y_m),
                      (float)cam->eye_m[2]);
    }
    gl->Uniform2f(u->cell_m, (float)t->cell_x_m, (float)t->cell_y_m);
    gl->Uniform1f(u->drop, (float)t->curv_drop_per_m2);
    gl->Uniform3f(u->fwd, (float)cam->forward[0], (float)cam->forward[1],
                  (float)cam->forward[2]);
    gl->Uniform3f(u->right, (float)cam->right[0], (float)cam->right[1],
                  (float)cam->right[2]);
    gl->Uniform3f(u->up, (float)cam->up[0], (float)cam->up[1], (float)cam->up[2]);
    const double ty = tan(0.5 * cam->fovy_rad);
    gl->Uniform3f(u->tan, (float)(ty * (double)cam->width_px / (double)cam->height_px),
                  (float)ty, 0.0f);
    gl->Uniform2f(u->size, (float)m->w_px, (float)m->h_px);
    gl->UniformMatrix4fv(u->view_proj, 1, GL_FALSE, cam->view_proj);
    gl->Uniform1f(u->mode, pos_pass ? 1.0f : 0.0f);
    float sky[3] = {FT_SKY_R, FT_SKY_G, FT_SKY_B};
    if (!pos_pass && p->shade_state != NULL) {
        ft_shade_palette_sky(p->shade_state->palette, sky);
        ft_program_shade_uniforms(gl, &u->shade, p->shade_state);
    }
    gl->Uniform4f(u->sky, sky[0], sky[1], sky[2], 1.0f);
    gl->DepthFunc(GL_ALWAYS);
    gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)(m->tiles_w * m->tiles_h));
    gl->DepthFunc(GL_LESS);
}

/* The viewing camera's transform on program e (a pass pgrid draws with a
 * program of its own). */
static void set_pass_uniforms(const ft_gl *gl, const ft_terrain_program *e, const ft_terrain *t,
                              const ft_camera *cam)
{
    gl->UniformMatrix4fv(e->u_view_proj, 1, GL_FALSE, cam->view_proj);
    gl->Uniform3f(e->u_origin_rel_eye_m, (float)(t->origin_world_x_m - cam->eye_m[0]),
                  (float)(t->origin_world_y_m - cam->eye_m[1]), (float)(0.0 - cam->eye_m[2]));
}

/* The error texel's inputs (shaders/pgrid_err_code.glsl) on program e. */
static void set_error_uniforms(const ft_pgrid_method *m, const ft_gl *gl,
                               const ft_terrain_program *e, const ft_camera *cam)
{
    gl->Uniform2f(e->method_u[FT_PGRID_U_ERR], (float)cam->px_per_rad_k, (float)m->gamma_px);
    gl->Uniform3f(e->method_u[FT_PGRID_U_FWD], (float)cam->forward[0], (float)cam->forward[1],
                  (float)cam->forward[2]);
    gl->Uniform1f(e->method_u[FT_PGRID_U_ENVELOPE], 0.0f);
}

/* The upper and lower envelopes (src/lod/pgrid.h 3) with program e (in use,
 * its uniforms set), into the bound framebuffer whose depth holds the mesh:
 * where one lies in front of the mesh, the pixel may show a ridge the mesh's
 * skyline missed (or, from under the ground, a surface the mesh leaves out):
 * the pixel takes the larger code (GLES 3 MAX blending); depth writes off,
 * the mesh's depth decides. */
static void draw_envelopes(ft_pgrid_method *m, const ft_gl *gl, const ft_terrain_program *e,
                           const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    const GLint env = e->method_u[FT_PGRID_U_ENVELOPE];
    gl->DepthMask(GL_FALSE);
    gl->Enable(GL_BLEND);
    gl->BlendEquation(GL_MAX);
    /* the lower one only where the surface may be seen from below */
    int lower = ft_pgrid_lower_envelope_needed(t, &m->pgm.sampling);
    if (m->lower_envelope_force != 0) lower = m->lower_envelope_force > 0;
    const int sides = lower ? 2 : 1;
    for (int side = 0; side < sides; ++side) {
        gl->Uniform1f(env, side == 0 ? 1.0f : -1.0f);
        ft_method_draw_stats dummy;
        memset(&dummy, 0, sizeof dummy);
        ft_pgm_method_draw(&m->pgm, gl, e, t, cam, &dummy);
        st->draw_calls += dummy.draw_calls;
    }
    st->envelopes = (uint32_t)sides;
    gl->Disable(GL_BLEND);
    gl->BlendEquation(GL_FUNC_ADD);
    gl->DepthMask(GL_TRUE);
    gl->Uniform1f(env, 0.0f);
}

static void pgrid_draw(ft_pgrid_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                       const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    GLint fb = 0;
    gl->GetIntegerv(GL_FRAMEBUFFER_BINDING, &fb);
    ft_pgm_method_view(&m->pgm, t, cam);
    if (p->shade.ramp_h >= 0) {
        /* the column warp the last decision chose; a position pass draws
         * the picture's grid */
        memcpy(m->col_t, m->col_t_next, sizeof m->col_t);
    }
    /* unit 2 holds the min/max atlas, or over the cache its cell ranges
     * (and unit 3 its block ranges, until the ray caster reads the error
     * buffer there), for the tight passes and the mesh */
    gl->ActiveTexture(GL_TEXTURE2);
    gl->BindTexture(GL_TEXTURE_2D, m->pgm.clip ? m->pgm.cl.range_tex : m->mm_tex);
    if (m->pgm.clip) {
        gl->ActiveTexture(GL_TEXTURE3);
        gl->BindTexture(GL_TEXTURE_2D, m->pgm.cl.block_range_tex);
    }
    gl->ActiveTexture(GL_TEXTURE0);
    if (m->tight) {
        tight_passes(m, gl, t, cam, fb);
        gl->UseProgram(p->program);
        st->draw_calls += 2u;
    }
    const int pos_pass = (p->shade.ramp_h < 0);
    /* the picture writes the error buffer too, into the framebuffer the
     * caller drew into (the window's own has no second attachment) */
    const int mrt = m->mrt && !pos_pass && fb != 0;
    /* 1. the mesh, with the pass's program (already in use) */
    set_grid_uniforms(m, gl, p);
    if (mrt) {
        set_error_uniforms(m, gl, p, cam);
        static const GLenum errors_only[2] = {GL_NONE, GL_COLOR_ATTACHMENT1};
        static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, m->err_tex,
                                 0);
        gl->DrawBuffers(2, errors_only);
        gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        gl->Clear(GL_COLOR_BUFFER_BIT); /* the picture was cleared by the caller */
        gl->DrawBuffers(2, both);
    }
    ft_pgm_method_draw(&m->pgm, gl, p, t, cam, st);
    if (mrt) {
        /* 2. the envelopes into attachment 1 against the picture's depth */
        if (m->ray_casting) {
            static const GLenum errors_only[2] = {GL_NONE, GL_COLOR_ATTACHMENT1};
            const ft_terrain_program *e = env_prog(m);
            gl->DrawBuffers(2, errors_only);
            gl->UseProgram(e->program);
            set_pass_uniforms(gl, e, t, cam);
            set_grid_uniforms(m, gl, e);
            set_error_uniforms(m, gl, e, cam);
            draw_envelopes(m, gl, e, t, cam, st);
        }
        static const GLenum picture[1] = {GL_COLOR_ATTACHMENT0};
        gl->DrawBuffers(1, picture);
        gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0u, 0);
        /* 3. the decision, from the error buffer's own framebuffer */
        gl->BindFramebuffer(GL_FRAMEBUFFER, m->err_fbo);
        decide(m, gl, t, cam);
        gl->BindFramebuffer(GL_FRAMEBUFFER, (GLuint)fb);
    } else if (!pos_pass || !same_decision_view(m, cam)) {
        /* 2. the error buffer drawn on its own (GLES 2, a window's own
         * framebuffer, a position pass of a view the picture did not see);
         * a position pass of the picture's view reuses the picture's */
        const ft_terrain_program *e = m->err_prog;
        gl->BindFramebuffer(GL_FRAMEBUFFER, m->err_fbo);
        gl->ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl->UseProgram(e->program);
        set_pass_uniforms(gl, e, t, cam);
        set_grid_uniforms(m, gl, e);
        set_error_uniforms(m, gl, e, cam);
        ft_method_draw_stats dummy;
        memset(&dummy, 0, sizeof dummy);
        ft_pgm_method_draw(&m->pgm, gl, e, t, cam, &dummy);
        st->draw_calls += dummy.draw_calls;
        if (m->ray_casting) {
            draw_envelopes(m, gl, e, t, cam, st);
        }
        /* 3. the decision */
        decide(m, gl, t, cam);
        gl->BindFramebuffer(GL_FRAMEBUFFER, (GLuint)fb);
    }
    /* 4. ray casting */
    /* (not on the count: with the late decision it is the previous frame's;
     * the pass leaves every pixel under the threshold alone) */
    if (m->ray_casting && m->thr < FT_PGRID_CODES) {
        ray_cast(m, gl, p, t, cam);
        st->draw_calls += 1u;
    }
    gl->UseProgram(p->program);
    st->raycast_px = m->rc_px;
    st->terrain_px = m->terrain_px;
    st->tau_achieved_px = m->achieved_px;
    st->budget_hit = m->budget_hit;
}

static void pgrid_shutdown(ft_pgrid_method *m, const ft_gl *gl)
{
    ft_pgm_method_shutdown(&m->pgm, gl);
    if (m->mm_tex) gl->DeleteTextures(1, &m->mm_tex);
    if (m->err_tex) gl->DeleteTextures(1, &m->err_tex);
    if (m->err_depth) gl->DeleteRenderbuffers(1, &m->err_depth);
    if (m->err_fbo) gl->DeleteFramebuffers(1, &m->err_fbo);
    if (m->rc_prog) gl->DeleteProgram(m->rc_prog);
    if (m->quad_vbo) gl->DeleteBuffers(1, &m->quad_vbo);
    if (m->pack_pbo[0]) gl->DeleteBuffers(2, m->pack_pbo);
    m->pack_pbo[0] = m->pack_pbo[1] = 0u;
    m->pbo_full[0] = m->pbo_full[1] = 0;
    m->late = 0;
    if (m->env_prog_built && env_prog(m)->program) gl->DeleteProgram(env_prog(m)->program);
    if (m->err_prog_built && m->err_prog->program) gl->DeleteProgram(m->err_prog->program);
    if (m->vtx_prog_built && m->vtx_prog->program) gl->DeleteProgram(m->vtx_prog->program);
    if (m->quad_prog) gl->DeleteProgram(m->quad_prog);
    if (m->quad_clip_built && m->quad_clip_prog->program) {
        gl->DeleteProgram(m->quad_clip_prog->program);
    }
    m->quad_clip_built = 0;
    if (m->shape_prog) gl->DeleteProgram(m->shape_prog);
    if (m->shape_tex) gl->DeleteTextures(1, &m->shape_tex);
    if (m->shape_fbo) gl->DeleteFramebuffers(1, &m->shape_fbo);
    m->shape_prog = m->shape_tex = m->shape_fbo = 0u;
    if (m->res_tex) gl->DeleteTextures(1, &m->res_tex);
    if (m->vtx_tex) gl->DeleteTextures(1, &m->vtx_tex);
    if (m->slope_tex) gl->DeleteTextures(1, &m->slope_tex);
    if (m->quad_tex) gl->DeleteTextures(1, &m->quad_tex);
    if (m->vtx_fbo) gl->DeleteFramebuffers(1, &m->vtx_fbo);
    if (m->quad_fbo) gl->DeleteFramebuffers(1, &m->quad_fbo);
    m->quad_prog = m->res_tex = m->vtx_tex = m->slope_tex = m->quad_tex = 0u;
    m->vtx_fbo = m->quad_fbo = 0u;
    m->vtx_prog_built = 0;
    m->tight = 0;
    if (m->rc_max_tex) gl->DeleteTextures(1, &m->rc_max_tex);
    if (m->tile_tex) gl->DeleteTextures(1, &m->tile_tex);
    if (m->tile_fbo) gl->DeleteFramebuffers(1, &m->tile_fbo);
    if (m->tile_prog) gl->DeleteProgram(m->tile_prog);
    m->rc_max_tex = m->tile_tex = m->tile_fbo = m->tile_prog = 0u;
    m->mm_tex = m->err_tex = m->err_depth = m->err_fbo = m->rc_prog = m->quad_vbo = 0u;
    m->err_prog_built = m->env_prog_built = 0;
    m->mrt = 0;
}

/* ---- the method table ---------------------------------------------------------- */

static ft_status ops_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                          ft_arena *a, ft_error *err)
{
    return pgrid_init(&m->u.pgrid, gl, s, t, a, err);
}

static void ops_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    pgrid_select(&m->u.pgrid, t, cam);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    pgrid_draw(&m->u.pgrid, gl, p, t, cam, st);
}

static void ops_set_lod_scale(ft_method *m, double scale)
{
    pgrid_set_lod_scale(&m->u.pgrid, scale);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    return m->u.pgrid.gpu_bytes + m->u.pgrid.pgm.gpu_bytes + m->u.pgrid.pgm.cl.gpu_bytes;
}

/* The grid goes through the pipeline once for the picture and the error
 * buffer (GLES 3: one draw writes both; GLES 2: two draws) and, with ray
 * casting, twice more as the envelopes. With the late decision a frame's
 * ray-cast count is set from the previous frame's buffer, so the first frame
 * and one frame after an abrupt view change may ray cast every pixel over
 * gamma: the worst case is the whole image. */
static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    (void)t;
    const ft_pgrid_method *g = &m->u.pgrid;
    const uint64_t grid = 2ull * (g->pgm.cols - 1u) * (g->pgm.rows - 1u);
    const uint64_t image = (uint64_t)g->w_px * g->h_px;
    const uint64_t picture = g->mrt ? 1u : 2u;
    const uint64_t passes = picture + (g->ray_casting ? 2u : 0u);
    const char *what = g->mrt ? "picture with its error buffer" : "picture, error buffer";
    /* plus 2 triangles a full-target pass: the tight bound's 3, ray casting */
    w->triangles = grid * passes + (g->tight ? 6u : 0u) + (g->ray_casting ? 2u : 0u);
    if (!g->ray_casting) {
        w->raycast_px = 0u;
        (void)snprintf(w->rule, sizeof w->rule, "the grid drawn %llu time(s) (%s); no ray casting",
                       (unsigned long long)passes, what);
    } else if (g->late) {
        w->raycast_px = image;
        (void)snprintf(w->rule, sizeof w->rule,
                       "the grid drawn %llu times (%s, 2 envelopes); ray casting within "
                       "pgrid.raycast_max_px = %llu but the whole image on a first or "
                       "abruptly changed view (the count is a frame late)",
                       (unsigned long long)passes, what, (unsigned long long)g->raycast_max_px);
    } else {
        w->raycast_px = g->raycast_max_px < image ? g->raycast_max_px : image;
        (void)snprintf(w->rule, sizeof w->rule,
                       "the grid drawn %llu times (%s, 2 envelopes); ray casting within "
                       "pgrid.raycast_max_px",
                       (unsigned long long)passes, what);
    }
}

static void ops_shutdown(ft_method *m, const ft_gl *gl)
{
    pgrid_shutdown(&m->u.pgrid, gl);
}

const ft_method_ops ft_pgrid_ops = {
    .vertex_shader = "pgrid.vert.glsl",
    .vertex_defines = pgrid_vertex_defines,
    .colour_defines = pgrid_colour_defines,
    .uniforms = {k_pgrid_uniforms, sizeof k_pgrid_uniforms / sizeof k_pgrid_uniforms[0]},
    .plan = pgrid_plan,
    .init = ops_init,
    .select = ops_select,
    .draw = ops_draw,
    .set_lod_scale = ops_set_lod_scale,
    .spare = ops_spare,
    .fit_depth = ops_fit_depth,
    .gpu_bytes = ops_gpu_bytes,
    .worst = ops_worst,
    .shutdown = ops_shutdown,
};
