/* method_pgm.c - persistent grid mapping (the math is in src/lod/pgm.h, the
 * per-vertex part in shaders/pgm.vert.glsl).
 *
 * GPU state, all made once at init:
 *  - one template BAND of the grid: vbo (column, row within the band) for
 *    band_rows + 1 vertex rows, ibo the band's triangles as 16-bit indices,
 *    row by row. The grid (cols x rows, any shape) is drawn as band_count
 *    draws of that band with the band's first row as a uniform; the last band
 *    draws a prefix of the indices. 16-bit indices work on every GLES 2
 *    context (with or without OES_element_index_uint), so there is one code
 *    path to test, and the buffers hold at most 65536 vertices whatever the
 *    grid size. A 430 x 430 grid is 3 draws, 200 x 800 is 3.
 *  - the average pyramid's levels 1.. in one atlas texture (pgm.h,
 *    ft_pgm_atlas_layout), in the heights' texel format (float, or packed
 *    24-bit over the terrain's [min, max]: averages lie inside it). The method
 *    uploads it itself, so it does not need gpu.pyramid_textures = 1 (which
 *    would upload every level as its own texture, and min/max too, none of
 *    which a vertex shader can pick per vertex). Level 0 is the renderer's
 *    heights texture. Vertex texture units needed: 2.
 * With pgm.heights = clipmap the heights come from the clipmap cache
 * instead (lod/clip_levels.h: its levels side by side in one atlas on unit
 * 1, no avg atlas): the shader's FT_PGM_CLIP part picks each vertex's level
 * from its footprint raised to what is resident (shaders/pgm_grid.glsl,
 * pgm.h ft_pgm_clip_view), the selection moves the cache every frame and the
 * sampling camera is laid over what the cache holds (ft_pgm_setup_over).
 * The CPU side per frame is the sampling camera (ft_pgm_setup: O(pyramid
 * levels), no allocation), recomputed only when the view changes. */
#include <stdio.h>
#include <math.h>
#include <string.h>

#include "gpu/gpu_texture.h"
#include "lod/method.h"

/* A band's vertices are indexed by 16 bits, and a band holds at least 8
 * vertex rows of the widest grid. */
_Static_assert(FT_PGM_BAND_VERTICES_MAX <= 65536u, "band indices are 16-bit");
_Static_assert(FT_PGM_BAND_VERTICES_MAX / FT_PGM_GRID_SIDE_MAX >= 8u, "bands of 8 rows or more");
_Static_assert(FT_PGM_CLIP_LEVELS_MAX >= FT_CLIP_LEVELS_MAX, "the clip view holds every level");

typedef struct pgm_shape {
    uint32_t vrows;      /* vertex rows in the template band */
    uint32_t band_rows;  /* = vrows - 1 cell rows */
    uint32_t band_count;
    uint32_t atlas_w, atlas_h;
} pgm_shape;

static void shape_of(const ft_pgm_grid_desc *g, const ft_terrain *t, pgm_shape *sh)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2];
    const uint32_t cols = g->cols, rows = g->rows;
    uint32_t vrows = FT_PGM_BAND_VERTICES_MAX / cols; /* >= 8: cols <= 8192 */
    vrows = (vrows < rows) ? vrows : rows;
    sh->vrows = vrows;
    sh->band_rows = vrows - 1u;
    sh->band_count = (rows - 1u + sh->band_rows - 1u) / sh->band_rows;
    if (!ft_pgm_atlas_layout(t, origin, &sh->atlas_w, &sh->atlas_h)) {
        sh->atlas_w = sh->atlas_h = 0u;
    }
}

static size_t vbo_bytes(const ft_pgm_grid_desc *g, const pgm_shape *sh)
{
    return (size_t)sh->vrows * g->cols * 2u * sizeof(float);
}

static size_t ibo_bytes(const ft_pgm_grid_desc *g, const pgm_shape *sh)
{
    return (size_t)sh->band_rows * (g->cols - 1u) * 6u * sizeof(uint16_t);
}

void ft_pgm_method_plan(const ft_pgm_grid_desc *g, const ft_terrain *t, ft_arena *a)
{
    if (g->cols < FT_PGM_GRID_SIDE_MIN || g->cols > FT_PGM_GRID_SIDE_MAX ||
        g->rows < FT_PGM_GRID_SIDE_MIN || g->rows > FT_PGM_GRID_SIDE_MAX) {
        return; /* init reports it */
    }
    pgm_shape sh;
    shape_of(g, t, &sh);
    /* Init scratch, used one after the other and given back in between: the
     * atlas floats (none when the heights come from the clip cache), then
     * the band's vertices, then its indices. */
    size_t need = g->clip ? 0u : (size_t)sh.atlas_w * sh.atlas_h * sizeof(float);
    need = (vbo_bytes(g, &sh) > need) ? vbo_bytes(g, &sh) : need;
    need = (ibo_bytes(g, &sh) > need) ? ibo_bytes(g, &sh) : need;
    ft_arena_plan(a, FT_POOL_METHOD, need);
}

/* The avg levels 1.. copied into one w x h float image, then uploaded in
 * the format of the heights texture. */
static ft_status upload_atlas(ft_pgm_method *m, const ft_gl *gl, const ft_pgm_grid_desc *g,
                              const ft_terrain *t, ft_arena *a, ft_error *err)
{
    uint32_t origin[FT_PYRAMID_LEVELS_MAX][2];
    uint32_t w = 0, h = 0;
    const ft_pyramid *p = &t->pyr;
    memset(m->level_px, 0, sizeof m->level_px);
    m->level_px[0][2] = (float)t->width;
    m->level_px[0][3] = (float)t->height;
    if (!ft_pgm_atlas_layout(t, origin, &w, &h)) {
        return FT_OK; /* a single level: the shader never leaves level 0 */
    }
    if (w > (uint32_t)gl->caps.max_texture_size || h > (uint32_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgm: the avg-pyramid atlas %ux%u exceeds GL_MAX_TEXTURE_SIZE %d", w, h,
                       gl->caps.max_texture_size);
    }
    m->atlas_fmt = ft_gpu_height_format(gl, g->height_format, t->min_height_m, t->max_height_m);
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    float *img = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, (size_t)w * h * sizeof(float),
                                 (void **)&img, err);
    if (st != FT_OK) {
        return st;
    }
    for (uint32_t l = 1; l < p->avg_levels && l < FT_PYRAMID_LEVELS_MAX; ++l) {
        const ft_pyramid_level *lv = &p->avg[l];
        for (uint32_t y = 0; y < lv->height; ++y) {
            memcpy(img + (size_t)(origin[l][1] + y) * w + origin[l][0],
                   lv->avg_m + (size_t)y * lv->width, (size_t)lv->width * sizeof(float));
        }
        m->level_px[l][0] = (float)origin[l][0];
        m->level_px[l][1] = (float)origin[l][1];
        m->level_px[l][2] = (float)lv->width;
        m->level_px[l][3] = (float)lv->height;
    }
    /* packed: its staging comes from gpu_staging, which the renderer planned
     * for the (larger) heights texture and gives back after each upload */
    st = ft_gpu_upload_scalar(gl, &m->atlas_fmt, img, w, h, GL_TEXTURE1, a, &m->atlas_tex,
                              &m->gpu_bytes, err);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    m->atlas_w = w;
    m->atlas_h = h;
    return st;
}

static ft_status upload_band(ft_pgm_method *m, const ft_gl *gl, const ft_pgm_grid_desc *g,
                             const pgm_shape *sh, ft_arena *a, ft_error *err)
{
    const uint32_t cols = m->cols;
    const size_t mark = ft_arena_mark(a, FT_POOL_METHOD);
    float *uv = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, vbo_bytes(g, sh), (void **)&uv, err);
    if (st != FT_OK) {
        return st;
    }
    for (uint32_t y = 0; y < sh->vrows; ++y) {
        for (uint32_t x = 0; x < cols; ++x) {
            uv[((size_t)y * cols + x) * 2u + 0u] = (float)x;
            uv[((size_t)y * cols + x) * 2u + 1u] = (float)y;
        }
    }
    gl->GenBuffers(1, &m->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)vbo_bytes(g, sh), uv, GL_STATIC_DRAW);
    ft_arena_reset(a, FT_POOL_METHOD, mark);

    uint16_t *idx = NULL;
    st = ft_arena_take(a, FT_POOL_METHOD, ibo_bytes(g, sh), (void **)&idx, err);
    if (st != FT_OK) {
        return st;
    }
    size_t k = 0;
    for (uint32_t y = 0; y < sh->band_rows; ++y) {
        for (uint32_t x = 0; x + 1u < cols; ++x) {
            /* < 65536 vertices in the band, so every index fits 16 bits */
            const uint16_t v00 = (uint16_t)(y * cols + x), v10 = (uint16_t)(v00 + 1u);
            const uint16_t v01 = (uint16_t)(v00 + cols), v11 = (uint16_t)(v01 + 1u);
            /* both triangles end at v11: GLES 3 takes a flat output from a
             * triangle's last vertex, so vertex (x + 1, y + 1) speaks for
             * exactly this quad (pgrid's per-quad bound, src/lod/pgrid.h 6) */
            idx[k++] = v00; idx[k++] = v10; idx[k++] = v11;
            idx[k++] = v01; idx[k++] = v00; idx[k++] = v11;
        }
    }
    gl->GenBuffers(1, &m->ibo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)ibo_bytes(g, sh), idx, GL_STATIC_DRAW);
    ft_arena_reset(a, FT_POOL_METHOD, mark);
    m->gpu_bytes += vbo_bytes(g, sh) + ibo_bytes(g, sh);
    return FT_OK;
}

ft_status ft_pgm_method_init(ft_pgm_method *m, const ft_gl *gl, const ft_pgm_grid_desc *g,
                             const ft_terrain *t, ft_arena *a, ft_error *err)
{
    memset(m, 0, sizeof *m);
    if (g->cols < FT_PGM_GRID_SIDE_MIN || g->cols > FT_PGM_GRID_SIDE_MAX ||
        g->rows < FT_PGM_GRID_SIDE_MIN || g->rows > FT_PGM_GRID_SIDE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "pgm: grid %u x %u outside %u..%u per side",
                       g->cols, g->rows, FT_PGM_GRID_SIDE_MIN,
                       FT_PGM_GRID_SIDE_MAX);
    }
    const ft_pyramid *p = &t->pyr;
    if (!g->clip &&
        (p->avg_levels < 1u || p->avg_levels > FT_PYRAMID_LEVELS_MAX || p->minmax_levels < 1u)) {
        return ft_fail(err, FT_ERR_ARG,
                       "pgm needs the terrain's avg pyramid (levels: %u) and max pyramid "
                       "(levels: %u) in memory; the terrain was loaded without them",
                       p->avg_levels, p->minmax_levels);
    }
    for (uint32_t l = 1; !g->clip && l < p->avg_levels; ++l) {
        if (p->avg[l].avg_m == NULL) {
            return ft_fail(err, FT_ERR_ARG, "pgm: avg pyramid level %u is missing", l);
        }
    }
    if (gl->caps.max_vertex_texture_units < 2) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "pgm samples the heights and the avg-pyramid atlas in the vertex shader: "
                       "it needs 2 vertex texture units, this device has %d",
                       gl->caps.max_vertex_texture_units);
    }
    pgm_shape sh;
    shape_of(g, t, &sh);
    m->cols = g->cols;
    m->rows = g->rows;
    m->band_rows = sh.band_rows;
    m->band_count = sh.band_count;
    m->levels = p->avg_levels;
    ft_status st = g->clip ? FT_OK : upload_atlas(m, gl, g, t, a, err);
    if (st == FT_OK) {
        st = upload_band(m, gl, g, &sh, a, err);
    }
    if (st != FT_OK) {
        return st;
    }
    return ft_gl_check(gl, "pgm init (grid band, avg-pyramid atlas)", err);
}

uint32_t ft_pgm_band_cell_rows(const ft_pgm_method *m, uint32_t b)
{
    const uint32_t first = b * m->band_rows, total = m->rows - 1u;
    if (first >= total) {
        return 0u;
    }
    return (total - first < m->band_rows) ? total - first : m->band_rows;
}

/* ---- heights from the clip cache (pgm.heights = clipmap) ----------------------- */

static double clip_max_in(const void *ctx, double x0_m, double y0_m, double x1_m, double y1_m)
{
    const ft_pgm_method *m = ctx;
    return ft_clip_max_height_in(&m->cl.cache, &m->cl_world, x0_m, y0_m, x1_m, y1_m);
}

/* Per level: base (the level-L sample at or below the eye), the resident box
 * relative to it; what is drawn: the data inside the coarsest level's
 * resident box, in metres from the eye (pgm.h, ft_pgm_clip_view). */
static void clip_place(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam)
{
    const ft_clip_levels *c = &m->cl;
    ft_pgm_clip_view *cv = &m->clip_view;
    double ei = 0.0, ej = 0.0;
    ft_clip_levels_eye(c, t, cam->eye_m, &ei, &ej);
    cv->levels = c->levels;
    cv->transition_samples = m->transition_samples;
    for (uint32_t l = 0; l < c->levels; ++l) {
        const double scale = ldexp(1.0, (int)l);
        const int64_t bi = (int64_t)floor(ei / scale), bj = (int64_t)floor(ej / scale);
        cv->base[l][0] = bi;
        cv->base[l][1] = bj;
        cv->off[l][0] = ei - (double)bi * scale;
        cv->off[l][1] = ej - (double)bj * scale;
        const ft_clip_box *v = &c->cache.level[l].valid;
        if (v->i1 <= v->i0 || v->j1 <= v->j0) {
            cv->box[l][0] = cv->box[l][1] = 1.0; /* empty: x1 < x0 */
            cv->box[l][2] = cv->box[l][3] = 0.0;
            continue;
        }
        cv->box[l][0] = (double)(v->i0 - bi);
        cv->box[l][1] = (double)(v->j0 - bj);
        cv->box[l][2] = (double)(v->i1 - 1 - bi);
        cv->box[l][3] = (double)(v->j1 - 1 - bj);
    }
    /* the coarsest level is kept whole (clip_levels.h), so its box is there */
    const uint32_t top = c->levels - 1u;
    const int64_t s = (int64_t)1 << top;
    const ft_clip_box *v = &c->cache.level[top].valid;
    const double i0 = fmax((double)(v->i0 * s), (double)c->src.data_i_lo);
    double i1 = fmin((double)((v->i1 - 1) * s), (double)c->src.data_i_hi);
    const double j0 = fmax((double)(v->j0 * s), (double)c->src.data_j_lo);
    double j1 = fmin((double)((v->j1 - 1) * s), (double)c->src.data_j_hi);
    /* the coarsest level past the data (the eye far off a terrain's edge):
     * nothing to draw, the grid collapses onto the nearest edge */
    i1 = fmax(i1, i0);
    j1 = fmax(j1, j0);
    cv->clamp_m[0] = (i0 - ei) * t->cell_x_m;
    cv->clamp_m[1] = (j0 - ej) * t->cell_y_m;
    cv->clamp_m[2] = (i1 - ei) * t->cell_x_m;
    cv->clamp_m[3] = (j1 - ej) * t->cell_y_m;
}

/* What the grid is laid over: the drawn box; its heights from the resident
 * blocks' bounds over a database (the cache keeps them there), else from
 * the terrain's (every cached height is one of its samples). */
static ft_pgm_surface clip_surface(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam)
{
    ft_pgm_surface g = ft_pgm_surface_of_terrain(t);
    const double *cb = m->clip_view.clamp_m;
    g.x0_m = cam->eye_m[0] + cb[0];
    g.y0_m = cam->eye_m[1] + cb[1];
    g.x1_m = cam->eye_m[0] + cb[2];
    g.y1_m = cam->eye_m[1] + cb[3];
    double closest = 0.0, zmin = 0.0, zmax = 0.0, bmin[2], bmax[2];
    m->cl_world = ft_clip_levels_world(t);
    if (ft_clip_clearance_m(&m->cl.cache, &m->cl_world, cam->eye_m, t->curv_drop_per_m2,
                            &closest, bmin, bmax, &zmin, &zmax)) {
        g.zmin_m = zmin;
        g.zmax_m = zmax;
        g.max_in = clip_max_in;
        g.ctx = m;
    }
    return g;
}

/* The sampling camera over what the cache holds now. */
static void clip_view(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam)
{
    clip_place(m, t, cam);
    const ft_pgm_surface g = clip_surface(m, t, cam);
    ft_pgm_setup_over(&m->sampling, cam, &g);
    ft_view_key_take(&m->sel_view, cam);
}

void ft_pgm_method_view(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam)
{
    if (ft_view_key_matches(&m->sel_view, cam)) {
        return;
    }
    if (m->clip) {
        clip_view(m, t, cam);
        return;
    }
    ft_pgm_setup(&m->sampling, cam, t);
    ft_view_key_take(&m->sel_view, cam);
}

void ft_pgm_method_select(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam)
{
    if (m->clip) {
        /* every frame, the view changed or not: a level that lags catches
         * up while the eye hovers, and the sampling follows what is
         * resident */
        ft_clip_levels_select(&m->cl, t, cam);
        clip_view(m, t, cam);
        return;
    }
    ft_pgm_method_view(m, t, cam);
}

void ft_pgm_method_clip_level(const ft_pgm_method *m, uint32_t l, float level[4], float box[4])
{
    const ft_pgm_clip_view *cv = &m->clip_view;
    const int64_t side = (int64_t)m->cl.side;
    const int64_t mx = ((cv->base[l][0] % side) + side) % side;
    const int64_t my = ((cv->base[l][1] % side) + side) % side;
    level[0] = (float)mx;
    level[1] = (float)my;
    level[2] = (float)cv->off[l][0];
    level[3] = (float)cv->off[l][1];
    for (int k = 0; k < 4; ++k) {
        box[k] = (float)cv->box[l][k];
    }
}

void ft_pgm_method_bind(const ft_pgm_method *m, const ft_gl *gl,
                        const struct ft_terrain_program *p)
{
    const ft_pgm_sampling *s = &m->sampling;
    const ft_scalar_format *f = m->clip ? &m->cl.fmt : &m->atlas_fmt;
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, m->clip ? m->cl.tex[0] : m->atlas_tex);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->Uniform1i(p->method_u[FT_PGM_U_ATLAS], 1);
    gl->Uniform2f(p->method_u[FT_PGM_U_ATLAS_SIZE],
                  (float)(m->clip ? m->cl.tex_w : m->atlas_w),
                  (float)(m->clip ? m->cl.tex_h : m->atlas_h));
    gl->Uniform2f(p->method_u[FT_PGM_U_ATLAS_PACK], f->pack_min,
                  f->format == FT_HEIGHT_FORMAT_PACKED ? f->pack_range : 0.0f);
    if (m->clip) {
        /* from the doubles near the eye: every value here is small */
        const ft_pgm_clip_view *cv = &m->clip_view;
        for (uint32_t l = 0; l < m->levels; ++l) {
            float lv[4], box[4];
            ft_pgm_method_clip_level(m, l, lv, box);
            gl->Uniform4fv(p->method_u[FT_PGM_U_LEVEL + l], 1, lv);
            gl->Uniform4fv(p->method_u[FT_PCM_U_BOX + l], 1, box);
        }
        gl->Uniform4f(p->method_u[FT_PCM_U_CLAMP], (float)cv->clamp_m[0], (float)cv->clamp_m[1],
                      (float)cv->clamp_m[2], (float)cv->clamp_m[3]);
        gl->Uniform4f(p->method_u[FT_PCM_U_MISC], (float)m->cl.side,
                      (float)m->transition_samples, (float)m->levels, (float)m->cl.atlas_cols);
    } else {
        for (uint32_t l = 0; l < m->levels; ++l) {
            gl->Uniform4f(p->method_u[FT_PGM_U_LEVEL + l], m->level_px[l][0], m->level_px[l][1],
                          m->level_px[l][2], m->level_px[l][3]);
        }
    }
    gl->Uniform3f(p->method_u[FT_PGM_U_FWD], (float)s->forward[0], (float)s->forward[1],
                  (float)s->forward[2]);
    gl->Uniform3f(p->method_u[FT_PGM_U_RIGHT], (float)s->right[0], (float)s->right[1], (float)s->right[2]);
    gl->Uniform3f(p->method_u[FT_PGM_U_UP], (float)s->up[0], (float)s->up[1], (float)s->up[2]);
    gl->Uniform4f(p->method_u[FT_PGM_U_RECT], (float)s->rect[0], (float)s->rect[1], (float)s->rect[2],
                  (float)s->rect[3]);
    gl->Uniform2f(p->method_u[FT_PGM_U_EYE], (float)s->height_m, (float)s->min_neg_dz);
    gl->Uniform4f(p->method_u[FT_PGM_U_GRID], (float)(m->cols - 1u), (float)(m->rows - 1u), 0.0f,
                  (float)m->levels);
}

void ft_pgm_method_draw(ft_pgm_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                        const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    ft_pgm_method_view(m, t, cam);
    ft_pgm_method_bind(m, gl, p);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    /* bounded: band_count <= rows - 1 */
    for (uint32_t b = 0; b < m->band_count; ++b) {
        const uint32_t cells = ft_pgm_band_cell_rows(m, b);
        gl->Uniform4f(p->method_u[FT_PGM_U_GRID], (float)(m->cols - 1u), (float)(m->rows - 1u),
                      (float)(b * m->band_rows), (float)m->levels);
        gl->DrawElements(GL_TRIANGLES, (GLsizei)(cells * (m->cols - 1u) * 6u),
                         GL_UNSIGNED_SHORT, (const void *)0);
        st->draw_calls += 1u;
    }
    st->triangles = 2ull * (m->cols - 1u) * (m->rows - 1u);
    if (m->clip) {
        st->cache_levels_behind = m->cl.cache.stats.levels_behind;
        st->cache_samples_outstanding = m->cl.cache.stats.samples_outstanding;
        st->cache_coarser = ft_pgm_clip_eye_coarser(&m->clip_view);
        st->cache_forced_updates = m->cl.forced_last;
    }
}

void ft_pgm_method_shutdown(ft_pgm_method *m, const ft_gl *gl)
{
    if (m->vbo) gl->DeleteBuffers(1, &m->vbo);
    if (m->ibo) gl->DeleteBuffers(1, &m->ibo);
    if (m->atlas_tex) gl->DeleteTextures(1, &m->atlas_tex);
    m->vbo = m->ibo = m->atlas_tex = 0u;
    if (m->clip) {
        ft_clip_levels_shutdown(&m->cl, gl);
    }
}

ft_status ft_pgm_method_clip_init(ft_pgm_method *pm, const ft_gl *gl, const ft_scene *s,
                                  const ft_terrain *t, ft_clip_bounds_rule bounds, ft_arena *a,
                                  ft_error *err)
{
    const ft_status st = ft_clip_levels_init(&pm->cl, gl, s, t, FT_CLIP_TEX_ATLAS, bounds,
                                             GL_TEXTURE1, a, err);
    if (st != FT_OK) {
        return st;
    }
    pm->clip = 1;
    pm->levels = pm->cl.levels;
    pm->transition_samples = s->clipmap_transition_samples;
    return FT_OK;
}

void ft_pgm_method_spare(ft_pgm_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    if (m->clip) {
        ft_clip_levels_spare(&m->cl, now, deadline_ns);
    }
}

/* Over a database the drawn terrain is the cache's, not the scene's grid. */
int ft_pgm_method_fit_depth(const ft_pgm_method *m, const ft_terrain *t, ft_camera *cam,
                            double corner_cos)
{
    return m->clip ? ft_clip_levels_fit_depth(&m->cl, t, cam, corner_cos) : 0;
}

/* ---- the method table ---------------------------------------------------------- */

/* pgm's own keys (pgrid draws the same grid from its own) */
static ft_pgm_grid_desc grid_of(const ft_scene *s)
{
    const ft_pgm_grid_desc g = {s->pgm_grid_cols, s->pgm_grid_rows, s->height_format,
                                s->pgm_heights_clipmap};
    return g;
}

static void ops_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    const ft_pgm_grid_desc g = grid_of(s);
    ft_pgm_method_plan(&g, t, a);
    if (g.clip) {
        ft_clip_levels_plan(s, t, FT_CLIP_BOUNDS_OVER_DB, a);
    }
}

static ft_status ops_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                          ft_arena *a, ft_error *err)
{
    const ft_pgm_grid_desc g = grid_of(s);
    ft_pgm_method *pm = &m->u.pgm;
    ft_status st = ft_pgm_method_init(pm, gl, &g, t, a, err);
    if (st != FT_OK || !g.clip) {
        return st;
    }
    return ft_pgm_method_clip_init(pm, gl, s, t, FT_CLIP_BOUNDS_OVER_DB, a, err);
}

static void ops_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    ft_pgm_method_select(&m->u.pgm, t, cam);
}

static const char *ops_vertex_defines(const ft_scene *s, int es3)
{
    (void)es3;
    return s->pgm_heights_clipmap ? "#define FT_PGM_CLIP 1\n" : "";
}

static void ops_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    ft_pgm_method_spare(&m->u.pgm, now, deadline_ns);
}

static int ops_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                         double corner_cos)
{
    return ft_pgm_method_fit_depth(&m->u.pgm, t, cam, corner_cos);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    ft_pgm_method_draw(&m->u.pgm, gl, p, t, cam, st);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    return m->u.pgm.gpu_bytes + m->u.pgm.cl.gpu_bytes;
}

static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    (void)t;
    w->triangles = 2ull * (m->u.pgm.cols - 1u) * (m->u.pgm.rows - 1u);
    (void)snprintf(w->rule, sizeof w->rule, "the grid, (cols - 1) x (rows - 1) x 2, every frame");
}

static void ops_shutdown(ft_method *m, const ft_gl *gl)
{
    ft_pgm_method_shutdown(&m->u.pgm, gl);
}

static const ft_uniform_name k_pgm_uniforms[] = {FT_PGM_UNIFORMS(FT_UNIFORM_ROW)
                                                     FT_PCM_UNIFORMS(FT_UNIFORM_ROW)};
_Static_assert(FT_PCM_U_COUNT <= FT_METHOD_UNIFORMS_MAX, "pgm's uniforms fit the program's table");

const ft_method_ops ft_pgm_ops = {
    .vertex_shader = "pgm.vert.glsl",
    .uniforms = {k_pgm_uniforms, sizeof k_pgm_uniforms / sizeof k_pgm_uniforms[0]},
    .plan = ops_plan,
    .init = ops_init,
    .vertex_defines = ops_vertex_defines,
    .select = ops_select,
    .draw = ops_draw,
    .spare = ops_spare,
    .fit_depth = ops_fit_depth,
    .gpu_bytes = ops_gpu_bytes,
    .worst = ops_worst,
    .shutdown = ops_shutdown,
};
