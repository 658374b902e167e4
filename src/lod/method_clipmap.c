/* method_clipmap.c - geometry clipmaps (the layout and the per-vertex rule
 * are src/lod/clipmap.h; the vertex stage shaders/clipmap.vert.glsl).
 *
 * GPU state, all made once at init:
 *  - the clip cache with one side x side height texture per level on unit
 *    1 (lod/clip_levels.h: R32F on GLES 3, LUMINANCE float or packed RGBA8
 *    on GLES 2), filled strip by strip; init fills every level whole, so the
 *    first frame is complete;
 *  - one vertex buffer with the block template ((B+1)^2 vertices) then the
 *    stitch strip's (inner row at half cells, outer row), and one 16-bit
 *    index buffer: the block's triangles then the strip's. A corner cell is
 *    the block's first 6 indices.
 * Per frame, select moves the cache's wanted boxes to the eye and runs at
 * most clipmap.updates_per_frame updates (the frame loop's job queue is the
 * app's, which a method cannot reach; the update count bounds the time
 * instead), then whatever the coarsest level still lacks (so terrain is
 * never drawn as sky: after a jump past every level's box the frame pays
 * for one whole level, at most side + 2 updates); draw lays out the drawn
 * boxes from the valid boxes and draws coarsest level first. CPU memory:
 * the cache's (clip_levels.h) and the template's staging at init, nothing
 * after init. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lod/clipmap.h"
#include "lod/method.h"
#include "terrain/clip_source.h"

static const ft_uniform_name k_cm_uniforms[] = {FT_CM_UNIFORMS(FT_UNIFORM_ROW)};
_Static_assert(FT_CM_U_COUNT <= FT_METHOD_UNIFORMS_MAX, "clipmap's uniforms fit the table");
_Static_assert(FT_CM_BLOCK_VERTICES + FT_CM_STRIP_VERTICES <= 65536u, "16-bit indices");

static size_t template_bytes(void)
{
    const size_t v = (size_t)(FT_CM_BLOCK_VERTICES + FT_CM_STRIP_VERTICES) * 2u * sizeof(float);
    const size_t i = (size_t)(FT_CM_BLOCK_INDICES + FT_CM_STRIP_INDICES) * sizeof(uint16_t);
    return v > i ? v : i;
}

static void cm_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    ft_clip_levels_plan(s, t, FT_CLIP_BOUNDS_ALWAYS, a);
    ft_arena_plan(a, FT_POOL_METHOD, template_bytes());
}

static ft_status check_units(const ft_gl *gl, ft_error *err)
{
    if (gl->caps.max_vertex_texture_units < 3) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "clipmap fetches two levels in the vertex shader (units 1 and 2): it "
                       "needs 3 vertex texture units, this device has %d",
                       gl->caps.max_vertex_texture_units);
    }
    return FT_OK;
}

static ft_status make_template(ft_clipmap_method *m, const ft_gl *gl, ft_arena *a, ft_error *err)
{
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    void *buf = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, template_bytes(), &buf, err);
    if (st != FT_OK) {
        return st;
    }
    float *uv = buf;
    const uint32_t nb = FT_CM_BLOCK_VERTICES, ns = FT_CM_STRIP_VERTICES;
    for (uint32_t k = 0; k < nb; ++k) {
        ft_cm_template_vertex(FT_CM_BLOCK, k, uv + 2u * k);
    }
    for (uint32_t k = 0; k < ns; ++k) {
        ft_cm_template_vertex(FT_CM_STRIP, k, uv + 2u * (nb + k));
    }
    const size_t vbytes = (size_t)(nb + ns) * 2u * sizeof(float);
    gl->GenBuffers(1, &m->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)vbytes, uv, GL_STATIC_DRAW);

    uint16_t *idx = buf;
    const uint32_t bi = ft_cm_template_indices(FT_CM_BLOCK, idx);
    const uint32_t si = ft_cm_template_indices(FT_CM_STRIP, idx + bi);
    for (uint32_t k = 0; k < si; ++k) {
        idx[bi + k] = (uint16_t)(idx[bi + k] + nb); /* the strip's vertices follow the block's */
    }
    const size_t ibytes = (size_t)(bi + si) * sizeof(uint16_t);
    gl->GenBuffers(1, &m->ibo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)ibytes, idx, GL_STATIC_DRAW);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    m->block_indices = bi;
    m->strip_indices = si;
    m->gpu_bytes += vbytes + ibytes;
    return FT_OK;
}

static ft_status cm_init(ft_clipmap_method *m, const ft_gl *gl, const ft_scene *s,
                         const ft_terrain *t, ft_arena *a, ft_error *err)
{
    memset(m, 0, sizeof *m);
    ft_status st = check_units(gl, err);
    if (st == FT_OK) {
        st = ft_clip_levels_init(&m->cl, gl, s, t, FT_CLIP_TEX_PER_LEVEL, FT_CLIP_BOUNDS_ALWAYS,
                                 GL_TEXTURE1, a, err);
    }
    if (st == FT_OK) {
        st = make_template(m, gl, a, err);
    }
    if (st != FT_OK) {
        return st;
    }
    m->transition_samples = s->clipmap_transition_samples;
    return ft_gl_check(gl, "clipmap init (templates)", err);
}

static void layout_now(ft_clipmap_method *m)
{
    ft_clip_box valid[FT_CLIP_LEVELS_MAX];
    const ft_clip_levels *c = &m->cl;
    for (uint32_t l = 0; l < c->levels; ++l) {
        valid[l] = c->cache.level[l].valid;
    }
    const int64_t lo[2] = {c->src.data_i_lo, c->src.data_j_lo};
    const int64_t hi[2] = {c->src.data_i_hi, c->src.data_j_hi};
    ft_cm_layout_make(&m->layout, c->levels, valid, lo, hi, m->transition_samples);
}

typedef struct draw_ctx {
    ft_clipmap_method *m;
    const ft_gl *gl;
    const ft_terrain_program *p;
    ft_method_draw_stats *st;
} draw_ctx;

static void draw_one(void *ctx, const ft_cm_draw *d)
{
    draw_ctx *c = ctx;
    const ft_gl *gl = c->gl;
    const GLint *u = c->p->method_u;
    gl->Uniform4f(u[FT_CM_U_PLACE], (float)d->origin[0], (float)d->origin[1], 0.0f, 0.0f);
    gl->Uniform4f(u[FT_CM_U_AXES], (float)d->axis_u[0], (float)d->axis_u[1],
                  (float)d->axis_v[0], (float)d->axis_v[1]);
    gl->Uniform4f(u[FT_CM_U_CLAMP], (float)d->clamp.x0, (float)d->clamp.y0, (float)d->clamp.x1,
                  (float)d->clamp.y1);
    GLsizei count = (GLsizei)c->m->block_indices;
    size_t first = 0;
    if (d->kind == FT_CM_STRIP) {
        count = (GLsizei)c->m->strip_indices;
        first = c->m->block_indices;
    } else if (d->kind == FT_CM_CORNER) {
        count = 6;
    }
    gl->DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_SHORT,
                     (const void *)(first * sizeof(uint16_t)));
    c->st->draw_calls += 1u;
}

static void cm_draw(ft_clipmap_method *m, const ft_gl *gl, const ft_terrain_program *p,
                    const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    if (!ft_view_key_matches(&m->sel_view, cam)) {
        ft_clip_levels_select(&m->cl, t, cam);
        ft_view_key_take(&m->sel_view, cam);
    }
    const ft_clip_levels *c = &m->cl;
    layout_now(m);
    const GLint *u = p->method_u;
    gl->Uniform1i(u[FT_CM_U_TEX0], 1);
    gl->Uniform1i(u[FT_CM_U_TEX1], 2);
    const float pack_range = (c->fmt.format == FT_HEIGHT_FORMAT_PACKED) ? c->fmt.pack_range : 0.0f;
    gl->Uniform4f(u[FT_CM_U_LATTICE], (float)c->src.lattice_i0, (float)c->src.lattice_j0,
                  c->fmt.pack_min, pack_range);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    draw_ctx ctx = {m, gl, p, st};
    const ft_cm_layout *lay = &m->layout;
    /* coarsest first; bounded by the level count */
    for (uint32_t k = 0; k < c->levels; ++k) {
        const uint32_t l = c->levels - 1u - k;
        if (!lay->level[l].drawn) {
            continue;
        }
        ft_cm_draw any = {l, FT_CM_BLOCK, {0, 0}, {1, 0}, {0, 1}, {0, 0, 0, 0}, 0u};
        ft_cm_uniforms cu;
        ft_cm_uniforms_of(lay, &any, &cu);
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, c->tex[l]);
        gl->ActiveTexture(GL_TEXTURE2);
        gl->BindTexture(GL_TEXTURE_2D, c->tex[(l + 1u < c->levels) ? l + 1u : l]);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->Uniform4f(u[FT_CM_U_DATA], cu.data[0], cu.data[1], cu.data[2], cu.data[3]);
        gl->Uniform4f(u[FT_CM_U_MBOX], cu.mbox[0], cu.mbox[1], cu.mbox[2], cu.mbox[3]);
        gl->Uniform4f(u[FT_CM_U_LEVEL], cu.level[0], cu.level[1], cu.level[2], (float)c->side);
        st->triangles += ft_cm_level_draws(lay, l, draw_one, &ctx);
    }
    /* the bound of what was drawn (clipmap.h): reported, not targeted */
    const ft_clip_world w = ft_clip_levels_world(t);
    const double origin_m[2] = {w.origin_x_m, w.origin_y_m};
    ft_view_bound vb;
    ft_view_bound_from_camera(cam, origin_m, t->curv_drop_per_m2, &vb);
    const double zmin = (t->db != NULL) ? (double)t->db->hdr.min_height_m : t->min_height_m;
    const double zmax = (t->db != NULL) ? (double)t->db->hdr.max_height_m : t->max_height_m;
    ft_cm_frame_bound(lay, &c->cache, &w, &vb, pack_range / 16777215.0, zmin, zmax, &m->bound);
    st->tau_achieved_px = m->bound.bound_px;
    st->tiles = lay->drawn_count;
    st->cache_levels_behind = c->cache.stats.levels_behind;
    st->cache_samples_outstanding = c->cache.stats.samples_outstanding;
    st->cache_coarser = lay->drawn_count == 0u || lay->finest > 0u;
    st->cache_forced_updates = c->forced_last;
}

static void cm_shutdown(ft_clipmap_method *m, const ft_gl *gl)
{
    if (m->vbo) gl->DeleteBuffers(1, &m->vbo);
    if (m->ibo) gl->DeleteBuffers(1, &m->ibo);
    m->vbo = m->ibo = 0u;
    ft_clip_levels_shutdown(&m->cl, gl);
}

/* ---- the method table ---------------------------------------------------------- */

static ft_status ops_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                          ft_arena *a, ft_error *err)
{
    return cm_init(&m->u.clipmap, gl, s, t, a, err);
}

/* Every frame, the view changed or not: a level that lags catches up while
 * the eye hovers. (draw selects only for a view select did not see.) */
static void ops_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    ft_clipmap_method *c = &m->u.clipmap;
    ft_clip_levels_select(&c->cl, t, cam);
    ft_view_key_take(&c->sel_view, cam);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    cm_draw(&m->u.clipmap, gl, p, t, cam, st);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    return m->u.clipmap.gpu_bytes + m->u.clipmap.cl.gpu_bytes;
}

/* Every level drawn whole: the finest side^2 cells, each ring at most
 * side^2 cells with its stitch cells at 3 triangles. */
static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    (void)t;
    const uint64_t s = m->u.clipmap.cl.side, n = m->u.clipmap.cl.levels;
    w->triangles = n * s * s * 3u;
    (void)snprintf(w->rule, sizeof w->rule,
                   "levels x side^2 cells, at most 3 triangles a cell (stitch cells)");
}

static void ops_shutdown(ft_method *m, const ft_gl *gl)
{
    cm_shutdown(&m->u.clipmap, gl);
}

static void ops_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    cm_plan(s, t, a);
}

/* Over a database the drawn terrain is the cache's, not the scene's grid. */
static int ops_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                         double corner_cos)
{
    return ft_clip_levels_fit_depth(&m->u.clipmap.cl, t, cam, corner_cos);
}

static void ops_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    ft_clip_levels_spare(&m->u.clipmap.cl, now, deadline_ns);
}

const ft_method_ops ft_clipmap_ops = {
    .vertex_shader = "clipmap.vert.glsl",
    .uniforms = {k_cm_uniforms, sizeof k_cm_uniforms / sizeof k_cm_uniforms[0]},
    .plan = ops_plan,
    .init = ops_init,
    .select = ops_select,
    .draw = ops_draw,
    .spare = ops_spare,
    .fit_depth = ops_fit_depth,
    .gpu_bytes = ops_gpu_bytes,
    .worst = ops_worst,
    .shutdown = ops_shutdown,
};
