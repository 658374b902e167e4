/* method_clipmap.c - geometry clipmaps (the layout and the per-vertex rule
 * are src/lod/clipmap.h; the vertex stage shaders/clipmap.vert.glsl).
 *
 * GPU state, all made once at init:
 *  - one side x side height texture per level (R32F on GLES 3, LUMINANCE
 *    float or packed RGBA8 on GLES 2: the renderer's format rule), filled
 *    from the clip cache strip by strip (ft_clip_next_update ->
 *    glTexSubImage2D -> ft_clip_commit); init fills every level whole, so the
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
 * boxes from the valid boxes and draws coarsest level first. CPU memory: the cache's staging (its pool) and the
 * packed-texel staging (FT_POOL_METHOD), nothing after init. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lod/clipmap.h"
#include "lod/method.h"
#include "terrain/clip_source.h"

static const ft_uniform_name k_cm_uniforms[] = {FT_CM_UNIFORMS(FT_UNIFORM_ROW)};
_Static_assert(FT_CM_U_COUNT <= FT_METHOD_UNIFORMS_MAX, "clipmap's uniforms fit the table");
_Static_assert(FT_CM_BLOCK_VERTICES + FT_CM_STRIP_VERTICES <= 65536u, "16-bit indices");

/* Over a database the levels reach past the scene's grid, whose bounds no
 * longer hold what is drawn: the cache keeps its own (fit_depth). */
static ft_clip_desc desc_of(const ft_scene *s, const ft_terrain *t)
{
    const ft_clip_desc d = {s->clipmap_side, s->clipmap_levels, s->clipmap_update_samples_max,
                            t->db != NULL};
    return d;
}

static size_t packed_bytes(const ft_scene *s)
{
    return (size_t)s->clipmap_update_samples_max * 4u;
}

static size_t template_bytes(void)
{
    const size_t v = (size_t)(FT_CM_BLOCK_VERTICES + FT_CM_STRIP_VERTICES) * 2u * sizeof(float);
    const size_t i = (size_t)(FT_CM_BLOCK_INDICES + FT_CM_STRIP_INDICES) * sizeof(uint16_t);
    return v > i ? v : i;
}

static void cm_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    ft_clip_source src;
    ft_error err;
    const ft_clip_desc d = desc_of(s, t);
    ft_clip_source_terrain(&src, t);
    if (t->db != NULL) { /* the database's levels past the window's */
        src.levels = t->db->hdr.level_count - t->db_level;
        ft_clip_db_source_plan(&t->db->hdr, s->clipmap_tile_slots, &d, a);
    }
    (void)ft_clip_plan(&d, &src, a, &err); /* init reports a bad description */
    ft_arena_plan(a, FT_POOL_METHOD, template_bytes());
    ft_arena_plan(a, FT_POOL_METHOD, packed_bytes(s));
}

static ft_status check_desc(const ft_scene *s, const ft_gl *gl, ft_error *err)
{
    const uint32_t side = s->clipmap_side;
    if (side < FT_CLIP_SIDE_MIN || side > FT_CLIP_SIDE_MAX || (side & (side - 1u)) != 0u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.side = %u: must be a power of two in %u..%u samples", side,
                       FT_CLIP_SIDE_MIN, FT_CLIP_SIDE_MAX);
    }
    if (side > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "clipmap.side = %u exceeds GL_MAX_TEXTURE_SIZE %d of this device", side,
                       gl->caps.max_texture_size);
    }
    if (s->clipmap_levels < 1u || s->clipmap_levels > FT_CLIP_LEVELS_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "clipmap.levels = %u: must be 1..%u",
                       s->clipmap_levels, FT_CLIP_LEVELS_MAX);
    }
    if (s->clipmap_update_samples_max < 2u * side ||
        (uint64_t)s->clipmap_update_samples_max > (uint64_t)side * side) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.update_samples_max = %u: must be %u..%llu (two rows of "
                       "clipmap.side = %u up to a whole level)",
                       s->clipmap_update_samples_max, 2u * side,
                       (unsigned long long)side * side, side);
    }
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

/* The renderer's rule: float texels when the context samples them in the
 * vertex stage, else 24-bit fixed point over the terrain's height range. */
static void pick_format(ft_clipmap_method *m, const ft_gl *gl, const ft_scene *s,
                        const ft_terrain *t)
{
    ft_height_format f = s->height_format;
    if (f == FT_HEIGHT_FORMAT_AUTO) {
        f = gl->caps.has_float_textures ? FT_HEIGHT_FORMAT_FLOAT : FT_HEIGHT_FORMAT_PACKED;
    }
    m->fmt.format = f;
    m->fmt.pack_min = t->min_height_m;
    m->fmt.pack_range = t->max_height_m - t->min_height_m;
    if (!(m->fmt.pack_range > 0.0f)) {
        m->fmt.pack_range = 1.0f;
    }
}

static ft_status make_textures(ft_clipmap_method *m, const ft_gl *gl)
{
    const int es3 = (gl->api == FT_GL_API_ES3);
    ft_texture_desc d = {GL_TEXTURE1, m->side, m->side, 0, 0, 0, 4u};
    if (m->fmt.format == FT_HEIGHT_FORMAT_FLOAT) {
        d.internal_format = es3 ? GL_R32F : GL_LUMINANCE;
        d.format = es3 ? GL_RED : GL_LUMINANCE;
        d.type = GL_FLOAT;
    } else {
        d.internal_format = es3 ? GL_RGBA8 : GL_RGBA;
        d.format = GL_RGBA;
        d.type = GL_UNSIGNED_BYTE;
    }
    m->tex_format = d.format;
    m->tex_type = d.type;
    for (uint32_t l = 0; l < m->levels; ++l) {
        ft_gpu_texture_create(gl, &d, NULL, &m->tex[l], &m->gpu_bytes);
    }
    return FT_OK;
}

/* One update's heights into its level's texels. */
static void upload(ft_clipmap_method *m, const ft_gl *gl, const ft_clip_update *u)
{
    const void *data = u->heights_m;
    if (m->fmt.format != FT_HEIGHT_FORMAT_FLOAT) {
        const size_t n = (size_t)u->w * u->h;
        for (size_t i = 0; i < n; ++i) {
            double f = ((double)u->heights_m[i] - m->fmt.pack_min) / m->fmt.pack_range;
            f = (f > 0.0) ? ((f < 1.0) ? f : 1.0) : 0.0;
            const uint32_t q = (uint32_t)(f * 16777215.0 + 0.5);
            m->packed[i * 4u + 0u] = (uint8_t)(q >> 16);
            m->packed[i * 4u + 1u] = (uint8_t)(q >> 8);
            m->packed[i * 4u + 2u] = (uint8_t)q;
            m->packed[i * 4u + 3u] = 255u;
        }
        data = m->packed;
    }
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, m->tex[u->level]);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, (GLint)u->tex_x, (GLint)u->tex_y, (GLsizei)u->w,
                      (GLsizei)u->h, m->tex_format, m->tex_type, data);
    gl->ActiveTexture(GL_TEXTURE0);
}

/* One update (read, upload, commit): 1 when one ran. Timed with now (when
 * not NULL), its time raises the declared cost of an update when it is the
 * slowest yet. */
static int run_one(ft_clipmap_method *m, const ft_gl *gl, uint64_t (*now)(void), ft_error *err,
                   ft_status *st)
{
    const uint64_t t0 = now != NULL ? now() : 0u;
    ft_clip_update u;
    int have = 0;
    *st = ft_clip_next_update(&m->cache, &u, &have, err);
    if (*st != FT_OK || !have) {
        return 0;
    }
    upload(m, gl, &u);
    ft_clip_commit(&m->cache, &u);
    if (now != NULL) {
        const uint64_t dt = now() - t0;
        m->update_ns_max = dt > m->update_ns_max ? dt : m->update_ns_max;
    }
    return 1;
}

/* Updates (coarsest level first) until the coarsest level is whole. Bound:
 * a whole level is side / rows bands of rows >= 2 rows (a band is split
 * where the texel rows wrap, adding one, and where the columns wrap, doubling
 * them), so at most side + 2 updates; a partial level's strips take fewer
 * samples and at most 4 more splits. */
static uint32_t complete_coarsest(ft_clipmap_method *m, const ft_gl *gl, ft_error *err,
                                  ft_status *st)
{
    const uint32_t most = m->side + 8u;
    uint32_t n = 0u;
    *st = FT_OK;
    while (n < most && !ft_clip_level_current(&m->cache, m->levels - 1u) &&
           run_one(m, gl, NULL, err, st)) {
        ++n;
    }
    return n;
}

/* Runs at most max_updates updates; returns how many ran. */
static uint32_t run_updates(ft_clipmap_method *m, const ft_gl *gl, uint32_t max_updates,
                            ft_error *err, ft_status *st)
{
    uint32_t n = 0;
    *st = FT_OK;
    while (n < max_updates && run_one(m, gl, NULL, err, st)) {
        ++n;
    }
    return n;
}

static void eye_lattice(const ft_clipmap_method *m, const ft_terrain *t, const ft_camera *cam,
                        double *ei, double *ej)
{
    *ei = (cam->eye_m[0] - t->origin_world_x_m) / t->cell_x_m + (double)m->src.lattice_i0;
    *ej = (cam->eye_m[1] - t->origin_world_y_m) / t->cell_y_m + (double)m->src.lattice_j0;
}

static ft_status cm_init(ft_clipmap_method *m, const ft_gl *gl, const ft_scene *s,
                         const ft_terrain *t, ft_arena *a, ft_error *err)
{
    memset(m, 0, sizeof *m);
    ft_status st = check_desc(s, gl, err);
    if (st != FT_OK) {
        return st;
    }
    const ft_clip_desc d = desc_of(s, t);
    /* over a .ftd window, the cache reads the database itself: the terrain
     * goes on past the window, from the finest level that has data */
    if (t->db != NULL) {
        st = ft_clip_source_db(&m->src, &m->db_src, t->db, t->db_level, t->db_i0, t->db_j0,
                               t->db_fill_m, s->clipmap_tile_slots, &d, a, err);
    } else {
        ft_clip_source_terrain(&m->src, t);
    }
    if (st == FT_OK) {
        st = ft_clip_init(&m->cache, &d, &m->src, a, err);
    }
    if (st != FT_OK) {
        return st;
    }
    m->gl = gl;
    m->side = d.side;
    m->levels = m->cache.desc.levels;
    m->updates_per_frame = s->clipmap_updates_per_frame;
    m->transition_samples = s->clipmap_transition_samples;
    st = ft_arena_take(a, FT_POOL_METHOD, packed_bytes(s), (void **)&m->packed, err);
    if (st != FT_OK) {
        return st;
    }
    pick_format(m, gl, s, t);
    st = make_template(m, gl, a, err);
    if (st == FT_OK) {
        st = make_textures(m, gl);
    }
    if (st != FT_OK) {
        return st;
    }
    /* the first frame is complete: every level filled around the terrain's
     * middle now, and again around the first eye by the first select */
    (void)ft_clip_recentre(&m->cache, (double)m->src.lattice_i0 + 0.5 * (t->width - 1u),
                           (double)m->src.lattice_j0 + 0.5 * (t->height - 1u));
    (void)run_updates(m, gl, UINT32_MAX, err, &st);
    if (st != FT_OK) {
        return st;
    }
    m->fill_whole = 1;
    return ft_gl_check(gl, "clipmap init (level textures, templates)", err);
}

static void cm_select(ft_clipmap_method *m, const ft_terrain *t, const ft_camera *cam)
{
    double ei, ej;
    ft_error err;
    ft_status st;
    eye_lattice(m, t, cam, &ei, &ej);
    (void)ft_clip_recentre(&m->cache, ei, ej);
    /* the first view is filled whole (init's promise); then the budget */
    const uint32_t n = m->fill_whole ? UINT32_MAX : m->updates_per_frame;
    m->fill_whole = 0;
    m->updates_last = run_updates(m, m->gl, n, &err, &st);
    if (st != FT_OK) {
        m->read_errors += 1u; /* the cache is unchanged: retried next frame */
    }
    /* What no level holds would be drawn as sky, which hides terrain: the
     * coarsest level is completed now, whatever the frame's budget. In
     * flight that is a strip of 2 x side samples when its box moves; after
     * a jump, the whole level. */
    m->forced_last = complete_coarsest(m, m->gl, &err, &st);
    if (st != FT_OK) {
        m->read_errors += 1u;
    }
    m->updates_last += m->forced_last;
    m->forced_updates += m->forced_last;
    m->forced_frames += m->forced_last > 0u;
}

/* The frame's spare time: updates while now() + the slowest update seen so
 * far fits before the deadline (the first call, with nothing measured yet,
 * runs one update and so learns the cost). Bounded by the updates a level
 * set can need (every level whole, in the smallest pieces). */
static void cm_spare(ft_clipmap_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    const uint64_t most = (uint64_t)m->levels * m->side * m->side /
                              (2u * m->side) + (uint64_t)m->levels * 4u;
    ft_error err;
    ft_status st = FT_OK;
    uint64_t n = 0u;
    while (n < most && now() + m->update_ns_max <= deadline_ns) {
        if (!run_one(m, m->gl, now, &err, &st)) {
            break;
        }
        ++n;
    }
    if (st != FT_OK) {
        m->read_errors += 1u; /* the cache is unchanged: retried later */
    }
    m->spare_updates += n;
    m->spare_deferred += m->cache.stats.levels_behind > 0u;
}

static void layout_now(ft_clipmap_method *m)
{
    ft_clip_box valid[FT_CLIP_LEVELS_MAX];
    for (uint32_t l = 0; l < m->levels; ++l) {
        valid[l] = m->cache.level[l].valid;
    }
    const int64_t lo[2] = {m->src.data_i_lo, m->src.data_j_lo};
    const int64_t hi[2] = {m->src.data_i_hi, m->src.data_j_hi};
    ft_cm_layout_make(&m->layout, m->levels, valid, lo, hi, m->transition_samples);
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
        cm_select(m, t, cam);
        ft_view_key_take(&m->sel_view, cam);
    }
    layout_now(m);
    const GLint *u = p->method_u;
    gl->Uniform1i(u[FT_CM_U_TEX0], 1);
    gl->Uniform1i(u[FT_CM_U_TEX1], 2);
    const float pack_range = (m->fmt.format == FT_HEIGHT_FORMAT_PACKED) ? m->fmt.pack_range : 0.0f;
    gl->Uniform4f(u[FT_CM_U_LATTICE], (float)m->src.lattice_i0, (float)m->src.lattice_j0,
                  m->fmt.pack_min, pack_range);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    draw_ctx ctx = {m, gl, p, st};
    const ft_cm_layout *lay = &m->layout;
    /* coarsest first; bounded by the level count */
    for (uint32_t k = 0; k < m->levels; ++k) {
        const uint32_t l = m->levels - 1u - k;
        if (!lay->level[l].drawn) {
            continue;
        }
        ft_cm_draw any = {l, FT_CM_BLOCK, {0, 0}, {1, 0}, {0, 1}, {0, 0, 0, 0}, 0u};
        ft_cm_uniforms cu;
        ft_cm_uniforms_of(lay, &any, &cu);
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, m->tex[l]);
        gl->ActiveTexture(GL_TEXTURE2);
        gl->BindTexture(GL_TEXTURE_2D, m->tex[(l + 1u < m->levels) ? l + 1u : l]);
        gl->ActiveTexture(GL_TEXTURE0);
        gl->Uniform4f(u[FT_CM_U_DATA], cu.data[0], cu.data[1], cu.data[2], cu.data[3]);
        gl->Uniform4f(u[FT_CM_U_MBOX], cu.mbox[0], cu.mbox[1], cu.mbox[2], cu.mbox[3]);
        gl->Uniform4f(u[FT_CM_U_LEVEL], cu.level[0], cu.level[1], cu.level[2], (float)m->side);
        st->triangles += ft_cm_level_draws(lay, l, draw_one, &ctx);
    }
    st->tiles = lay->drawn_count;
    st->cache_levels_behind = m->cache.stats.levels_behind;
    st->cache_samples_outstanding = m->cache.stats.samples_outstanding;
    st->cache_coarser = lay->drawn_count == 0u || lay->finest > 0u;
    st->cache_forced_updates = m->forced_last;
}

static void cm_shutdown(ft_clipmap_method *m, const ft_gl *gl)
{
    if (m->vbo) gl->DeleteBuffers(1, &m->vbo);
    if (m->ibo) gl->DeleteBuffers(1, &m->ibo);
    for (uint32_t l = 0; l < m->levels; ++l) {
        if (m->tex[l]) gl->DeleteTextures(1, &m->tex[l]);
        m->tex[l] = 0u;
    }
    m->vbo = m->ibo = 0u;
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
    cm_select(c, t, cam);
    ft_view_key_take(&c->sel_view, cam);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    cm_draw(&m->u.clipmap, gl, p, t, cam, st);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    return m->u.clipmap.gpu_bytes;
}

/* Every level drawn whole: the finest side^2 cells, each ring at most
 * side^2 cells with its stitch cells at 3 triangles. */
static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    (void)t;
    const uint64_t s = m->u.clipmap.side, n = m->u.clipmap.levels;
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

/* Over a database the drawn terrain is the cache's, not the scene's grid:
 * the depth range comes from the resident samples' bounds (the grid's
 * range put the near plane 5 km out once the eye left the window, and cut
 * away the terrain below it). Called after select, so it bounds what this
 * frame draws. */
static int ops_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                         double corner_cos)
{
    const ft_clipmap_method *cm = &m->u.clipmap;
    if (!cm->cache.desc.keep_bounds) {
        return 0;
    }
    const ft_clip_world w = {t->origin_world_x_m, t->origin_world_y_m, t->cell_x_m, t->cell_y_m};
    double closest = 0.0, zmin = 0.0, zmax = 0.0, box_min[2], box_max[2];
    if (!ft_clip_clearance_m(&cm->cache, &w, cam->eye_m, t->curv_drop_per_m2, &closest, box_min,
                             box_max, &zmin, &zmax)) {
        return 0;
    }
    double near_m = 0.0, far_m = 0.0;
    ft_camera_depth_range_from(cam->eye_m, closest, zmin, zmax, box_min, box_max, corner_cos,
                               t->curv_drop_per_m2, &near_m, &far_m);
    ft_error err;
    return ft_camera_set_depth_range(cam, near_m, far_m, &err) == FT_OK;
}

static void ops_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    cm_spare(&m->u.clipmap, now, deadline_ns);
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
