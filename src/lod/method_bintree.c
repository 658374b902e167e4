/* method_bintree.c - draws the tiles the bintree selection (src/lod/bintree.h)
 * picked, every tile with the same template (src/lod/bintree_template.h).
 *
 * Tiles go to the GPU in batches: the vertex buffer holds batch_tiles copies
 * of the template, each vertex (a, b, slot), and a draw sets the uniform
 * array u_bt_tiles[slot] to its tiles' (apex, left) grid coordinates (exact
 * integers; the right corner follows, shaders/bintree.vert.glsl) and draws
 * the first count x template indices. The same on GLES 2 and 3. The reason
 * is measured: llvmpipe runs an instanced draw one instance at a time through
 * its vertex pipeline, so a tile drawn as an instance of 15 or 45 vertices
 * costs a pipeline run of its own. Heights and the diamond errors (for
 * geomorphing) are vertex textures; on GLES 3 a vertex on a sample reads all
 * it needs from one texel of the vertex table (bintree.h, ft_bt_sample_texel).
 *
 * Grids that are not (2^n+1)^2 are padded by clamping (see bintree.h): the
 * vertex shader clamps grid coordinates into the real grid, so the padded
 * area collapses onto the grid's edge and is never drawn.
 *
 * bintree.heights = clipmap: the same template, batches and slots, with the
 * tiles of the bintree over the clipmap cache (lod/bintree_cache.h) on its
 * level-0 lattice relative to the domain's origin, and heights from the
 * cache's levels side by side in one atlas on unit 1 (lod/clip_levels.h),
 * read by shaders/bintree_clip.vert.glsl from the level of each tile's
 * template spacing. None of the window's tables or textures is built then;
 * no geomorphing, no sub-sample levels, no back-face culling. The cache
 * moves to the eye and runs its updates in every selection (a level that
 * lags catches up while the eye hovers) and in the frame's spare time. */
#include <stdio.h>
#include <math.h>
#include <string.h>

#include "core/view_scale.h"
#include "gpu/gpu_texture.h"
#include "gpu/program.h"
#include "lod/bintree_template.h"
#include "lod/method.h"

/* a tile as the shader gets it: apex.xy, left.xy (the right corner is the
 * apex plus left - apex turned a quarter counter-clockwise) */
#define FT_BT_FLOATS_PER_TILE 4u
/* Tiles a draw (bintree.tiles_per_draw; 0: these): the length of the
 * shader's u_bt_tiles (one vec4 a tile). The vertex shader's other uniforms
 * take under 48 vectors (over the cache too: 16 levels and 10 more), and the
 * spec's least GL_MAX_VERTEX_UNIFORM_VECTORS is 128 on GLES 2 and 256 on
 * GLES 3, so the defaults link on every conforming device (init checks the
 * device's value). */
#define FT_BT_BATCH_TILES_ES2 64u
#define FT_BT_BATCH_TILES_ES3 192u
#define FT_BT_UNIFORM_VECTORS_OTHER 48u

static uint32_t batch_tiles_of(const ft_scene *s, int es3)
{
    if (s->bintree_tiles_per_draw > 0u) {
        return s->bintree_tiles_per_draw;
    }
    return es3 ? FT_BT_BATCH_TILES_ES3 : FT_BT_BATCH_TILES_ES2;
}
/* The one-fetch vertex table goes up in strips of this many rows through
 * FT_POOL_GPU_STAGING (width * rows * 16 bytes), not in one copy of the grid. */
#define FT_BT_VTX_STRIP_ROWS 8u

/* The bintree's uniforms (shaders/bintree.vert.glsl): tile corners per draw
 * (one array), the diamond, height-block and twist textures, the morph, the
 * view axis and the vertical gain's caps (core/view_scale.h); over the cache
 * (shaders/bintree_clip.vert.glsl) the tile array and the u_btc_ rows. */
#define FT_BT_UNIFORMS(X)                                      \
    X(FT_BT_U_TILES, "u_bt_tiles", 1u)                        \
    X(FT_BT_U_DIA, "u_bt_dia", 1u)                            \
    X(FT_BT_U_ZB, "u_bt_zb", 1u)                              \
    X(FT_BT_U_GAP, "u_bt_gap", 1u)                            \
    X(FT_BT_U_LATTICE, "u_bt_lattice", 1u)                    \
    X(FT_BT_U_MORPH, "u_bt_morph", 1u)                        \
    X(FT_BT_U_AXIS, "u_bt_axis", 1u)                          \
    X(FT_BT_U_GAIN_CAP, "u_bt_gain_cap", 1u)                  \
    X(FT_BT_U_SUB, "u_bt_sub", 1u)                            \
    X(FT_BT_U_TWIST, "u_bt_twist", 1u)                        \
    X(FT_BT_U_TWIST_PACK, "u_bt_twist_pack", 1u)              \
    X(FT_BT_U_VTX, "u_bt_vtx", 1u)                            \
    X(FT_BT_U_TWIST_OFF, "u_bt_twist_off", FT_BT_TWIST_LEVELS_MAX) \
    X(FT_BTC_U_ATLAS, "u_btc_atlas", 1u)                           \
    X(FT_BTC_U_LEVEL, "u_btc_level", FT_CLIP_LEVELS_MAX)           \
    X(FT_BTC_U_EYE, "u_btc_eye", 1u)                               \
    X(FT_BTC_U_MISC, "u_btc_misc", 1u)                             \
    X(FT_BTC_U_PACK, "u_btc_pack", 1u)                             \
    X(FT_BTC_U_DATA, "u_btc_data", 1u)
enum { FT_BT_UNIFORMS(FT_UNIFORM_ENUM) FT_BT_U_COUNT };
static const ft_uniform_name k_bt_uniforms[] = {FT_BT_UNIFORMS(FT_UNIFORM_ROW)};
_Static_assert(FT_BT_U_COUNT <= FT_METHOD_UNIFORMS_MAX, "the bintree's uniforms fit the table");

/* GLES 3: the one-fetch vertex table (bintree.h, ft_bt_sample_texel) as an
 * RGBA32F texture on unit 3. */
static ft_texture_desc vertex_table_desc(uint32_t width, uint32_t height)
{
    const ft_texture_desc d = {GL_TEXTURE3, width, height, GL_RGBA32F, GL_RGBA, GL_FLOAT,
                               4u * sizeof(float)};
    return d;
}

static void fill_vertex_rows(void *ctx, uint32_t y0, uint32_t rows, void *strip)
{
    const ft_bintree *bt = ctx;
    float *texel = strip;
    for (uint32_t y = 0; y < rows; ++y) {
        for (uint32_t x = 0; x < bt->width; ++x, texel += 4) {
            ft_bt_sample_texel(bt, x, y0 + y, texel);
        }
    }
}

static void bintree_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    uint32_t k = s->bintree_template_k;
    if (k < FT_BT_TEMPLATE_K_MIN || k > FT_BT_TEMPLATE_K_MAX) {
        return; /* ft_bintree_init reports it */
    }
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_vertices(k) * 2u * sizeof(float));
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_triangles(k) * 3u * sizeof(uint16_t));
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_scratch(k) * sizeof(int16_t));
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_vertices(k) * 3u * sizeof(float));
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)ft_bt_template_triangles(k) * 3u * sizeof(uint16_t));
    ft_arena_plan(a, FT_POOL_METHOD,
                  (size_t)s->bintree_tiles_max * FT_BT_FLOATS_PER_TILE * sizeof(float));
    if (s->bintree_heights_clipmap) {
        /* the cache's bounds are what its tiles' errors come from */
        ft_clip_levels_plan(s, t, FT_CLIP_BOUNDS_ALWAYS, a);
        ft_btc_plan(a, s->clipmap_side, s->clipmap_levels, k, s->bintree_tiles_max);
        return;
    }
    ft_bintree_plan(a, t->width, t->height, k, s->bintree_subsample_levels, s->bintree_tiles_max);
    if (s->bintree_vertex_table && s->backend != FT_BACKEND_EGL_GLES2) {
        const ft_texture_desc d = vertex_table_desc(t->width, t->height);
        ft_arena_plan(a, FT_POOL_GPU_STAGING, ft_gpu_texture_strip_bytes(&d, FT_BT_VTX_STRIP_ROWS));
    }
}

/* Over the cache: what is not built there is refused, naming the keys. */
static ft_status clip_check_scene(const ft_scene *s, ft_error *err)
{
    if (s->bintree_morph) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "bintree.heights = clipmap: geomorphing over the cache is not built: set "
                       "bintree.morph = 0");
    }
    if (s->bintree_subsample_levels > 0u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "bintree.heights = clipmap: tiles below the cache's level-0 samples are "
                       "not built: set bintree.subsample_levels = 0 (it is %u)",
                       s->bintree_subsample_levels);
    }
    return FT_OK;
}

/* The template's batches (vbo, ibo), the tile list the draws read (inst) and
 * the uniform vectors they need: the same over the window and the cache. */
static ft_status template_init(ft_bintree_method *m, const ft_gl *gl, const ft_scene *s,
                               ft_arena *a, ft_error *err)
{
    const uint32_t k = s->bintree_template_k;
    if (k < FT_BT_TEMPLATE_K_MIN || k > FT_BT_TEMPLATE_K_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.template_k = %u outside %u..%u", k,
                       FT_BT_TEMPLATE_K_MIN, FT_BT_TEMPLATE_K_MAX);
    }
    const uint32_t nv = ft_bt_template_vertices(k), nt = ft_bt_template_triangles(k);
    float *uv = NULL;
    uint16_t *idx = NULL;
    int16_t *scratch = NULL;
    ft_status st =
        ft_arena_take(a, FT_POOL_METHOD, (size_t)nv * 2u * sizeof(float), (void **)&uv, err);
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)nt * 3u * sizeof(uint16_t), (void **)&idx,
                           err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)ft_bt_template_scratch(k) * sizeof(int16_t),
                           (void **)&scratch, err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD,
                           (size_t)s->bintree_tiles_max * FT_BT_FLOATS_PER_TILE * sizeof(float),
                           (void **)&m->inst, err);
    }
    float *slot_v = NULL;
    uint16_t *slot_i = NULL;
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)nv * 3u * sizeof(float), (void **)&slot_v,
                           err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, (size_t)nt * 3u * sizeof(uint16_t),
                           (void **)&slot_i, err);
    }
    if (st == FT_OK) {
        st = ft_bt_template_build(k, uv, idx, scratch, err);
    }
    if (st != FT_OK) {
        return st;
    }
    m->index_count = nt * 3u;
    m->triangles_per_tile = nt;
    /* A batch's vertices are addressed by 16-bit indices. */
    const uint32_t batch_max = batch_tiles_of(s, m->es3);
    m->batch_tiles = (65536u / nv < batch_max) ? 65536u / nv : batch_max;
    GLint vectors = 0;
    gl->GetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &vectors);
    if (vectors < (GLint)(batch_max + FT_BT_UNIFORM_VECTORS_OTHER)) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "bintree: the vertex shader needs %u uniform vectors (%u tiles a draw); "
                       "this device has GL_MAX_VERTEX_UNIFORM_VECTORS %d: lower "
                       "bintree.tiles_per_draw",
                       batch_max + FT_BT_UNIFORM_VECTORS_OTHER, batch_max, vectors);
    }
    const size_t vbytes = (size_t)nv * 3u * sizeof(float);
    const size_t ibytes = (size_t)nt * 3u * sizeof(uint16_t);
    gl->GenBuffers(1, &m->vbo);
    gl->GenBuffers(1, &m->ibo);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(vbytes * m->batch_tiles), NULL, GL_STATIC_DRAW);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(ibytes * m->batch_tiles), NULL,
                   GL_STATIC_DRAW);
    for (uint32_t v = 0; v < nv; ++v) {
        slot_v[3u * v] = uv[2u * v];
        slot_v[3u * v + 1u] = uv[2u * v + 1u];
    }
    /* bounded: batch_tiles <= 1024 slots (the key's range) */
    for (uint32_t slot = 0; slot < m->batch_tiles; ++slot) {
        for (uint32_t v = 0; v < nv; ++v) {
            slot_v[3u * v + 2u] = (float)slot;
        }
        for (uint32_t i = 0; i < nt * 3u; ++i) {
            slot_i[i] = (uint16_t)(slot * nv + idx[i]); /* < 65536 by batch_tiles */
        }
        gl->BufferSubData(GL_ARRAY_BUFFER, (GLintptr)(vbytes * slot), (GLsizeiptr)vbytes, slot_v);
        gl->BufferSubData(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)(ibytes * slot), (GLsizeiptr)ibytes,
                          slot_i);
    }
    m->gpu_bytes = (uint64_t)(vbytes + ibytes) * m->batch_tiles;
    return ft_gl_check(gl, "bintree template batches", err);
}

/* bintree.heights = clipmap: the cache (its bounds kept: the tiles' errors
 * come from them) with its levels in one atlas on unit 1, which no other
 * part of the method uses over the cache, and the tables over its lattice. */
static ft_status clip_init(ft_bintree_method *m, const ft_gl *gl, const ft_scene *s,
                           const ft_terrain *t, ft_arena *a, ft_error *err)
{
    ft_status st = ft_clip_levels_init(&m->cl, gl, s, t, FT_CLIP_TEX_ATLAS, FT_CLIP_BOUNDS_ALWAYS,
                                       GL_TEXTURE1, a, err);
    if (st != FT_OK) {
        return st;
    }
    m->clip = 1; /* shutdown deletes the cache's textures from here on */
    st = ft_btc_init(&m->btc, &m->cl.cache, t, s->bintree_template_k, s->bintree_tiles_max, a,
                     err);
    if (st != FT_OK) {
        return st;
    }
    return ft_gl_check(gl, "bintree over the clipmap cache init", err);
}

static ft_status bintree_init(ft_bintree_method *m, const ft_gl *gl, const ft_scene *s,
                              const ft_terrain *t, ft_arena *a, ft_error *err)
{
    memset(m, 0, sizeof *m);
    m->tau_px = s->bintree_tau_px;
    m->lod_scale = 1.0;
    m->morph = s->bintree_morph;
    m->cull_back_faces = s->bintree_cull_back_faces;
    m->morph_width = s->bintree_morph_width;
    m->es3 = (gl->api == FT_GL_API_ES3);
    if (s->bintree_heights_clipmap) {
        ft_status st = clip_check_scene(s, err);
        if (st == FT_OK) {
            st = template_init(m, gl, s, a, err);
        }
        return (st == FT_OK) ? clip_init(m, gl, s, t, a, err) : st;
    }
    m->vertex_table = m->es3 && s->bintree_vertex_table;
    ft_status st =
        ft_bintree_init(&m->bt, t, s->bintree_template_k, s->bintree_subsample_levels,
                        s->bintree_morph_width, s->bintree_tiles_max, a, err);
    if (st == FT_OK) {
        st = template_init(m, gl, s, a, err);
    }
    if (st != FT_OK) {
        return st;
    }
    /* The geomorph reads each diamond's error and height range (its box,
     * bintree.h), and below the samples the height blocks, as float RGBA
     * texels: one fetch a diamond. */
    if (m->morph) {
        if (!gl->caps.has_float_textures || gl->caps.max_vertex_texture_units < 5) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "bintree.morph needs float vertex textures on 5 units (this device: "
                           "float %s, %d units); set bintree.morph = 0",
                           gl->caps.has_float_textures ? "yes" : "no",
                           gl->caps.max_vertex_texture_units);
        }
        const ft_texture_desc dd = {GL_TEXTURE1, m->bt.lattice_side, m->bt.lattice_side,
                                    m->es3 ? GL_RGBA32F : GL_RGBA, GL_RGBA, GL_FLOAT,
                                    4u * sizeof(float)};
        ft_gpu_texture_create(gl, &dd, m->bt.dia, &m->dia_tex, &m->gpu_bytes);
        if (m->bt.sub > 0u) {
            const ft_texture_desc zd = {GL_TEXTURE4, m->bt.zblock_w, m->bt.zblock_h,
                                        m->es3 ? GL_RGBA32F : GL_RGBA, GL_RGBA, GL_FLOAT,
                                        4u * sizeof(float)};
            ft_gpu_texture_create(gl, &zd, m->bt.zblock, &m->zb_tex, &m->gpu_bytes);
        }
        st = ft_gl_check(gl, "bintree diamond textures", err);
        if (st != FT_OK) {
            return st;
        }
    }
    if (m->vertex_table) {
        if (gl->caps.max_vertex_texture_units < 4) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "bintree on GLES 3 needs 4 vertex texture units; this device has %d",
                           gl->caps.max_vertex_texture_units);
        }
        const ft_texture_desc d = vertex_table_desc(m->bt.width, m->bt.height);
        st = ft_gpu_texture_create_strips(gl, &d, FT_BT_VTX_STRIP_ROWS, fill_vertex_rows, &m->bt,
                                          a, &m->vtx_tex, &m->gpu_bytes,
                                          "bintree vertex table upload", err);
        if (st != FT_OK) {
            return st;
        }
    }
    if (m->bt.sub > 0u) {
        /* the twist atlas the closed-form errors below the samples read */
        const ft_bt_twist_layout *tl = &m->bt.twist;
        if (gl->caps.max_vertex_texture_units < 3) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "bintree.subsample_levels needs 3 vertex texture units; this device "
                           "has %d", gl->caps.max_vertex_texture_units);
        }
        if (tl->atlas_w > (uint32_t)gl->caps.max_texture_size ||
            tl->atlas_h > (uint32_t)gl->caps.max_texture_size) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "bintree.subsample_levels: the twist atlas %ux%u exceeds "
                           "GL_MAX_TEXTURE_SIZE %d (use subsample_levels = 0 for this grid)",
                           tl->atlas_w, tl->atlas_h, gl->caps.max_texture_size);
        }
        float dmax = 0.0f;
        const uint32_t top = tl->levels - 1u;
        for (uint32_t y = 0; y < tl->h[top]; ++y) {
            for (uint32_t x = 0; x < tl->w[top]; ++x) {
                const float d = m->bt.twist_atlas[(size_t)(tl->oy[top] + y) * tl->atlas_w +
                                                  tl->ox[top] + x];
                dmax = (d > dmax) ? d : dmax;
            }
        }
        m->twist_fmt.format = gl->caps.has_float_textures ? FT_HEIGHT_FORMAT_FLOAT
                                                          : FT_HEIGHT_FORMAT_PACKED;
        m->twist_fmt.pack_min = 0.0f;
        m->twist_fmt.pack_range = (dmax > 0.0f) ? dmax : 1.0f;
        st = ft_gpu_upload_scalar(gl, &m->twist_fmt, m->bt.twist_atlas, tl->atlas_w, tl->atlas_h,
                                  GL_TEXTURE2, a, &m->twist_tex, &m->gpu_bytes, err);
        if (st != FT_OK) {
            return st;
        }
    }
    return ft_gl_check(gl, "bintree init (template batch, error textures)", err);
}

/* The selection's tiles as the draws' uniform rows: (apex, left) a tile. */
static void pack_tiles(ft_bintree_method *m, const ft_bt_tile *tiles)
{
    for (uint32_t i = 0; i < m->sel.tiles; ++i) {
        float *o = m->inst + (size_t)i * FT_BT_FLOATS_PER_TILE;
        o[0] = (float)tiles[i].apex[0];
        o[1] = (float)tiles[i].apex[1];
        o[2] = (float)tiles[i].left[0];
        o[3] = (float)tiles[i].left[1];
    }
}

/* Floor of a / 2^d (a may be negative), mod side (a power of two). */
static int64_t level_index_mod(int64_t a, uint32_t d, uint32_t side)
{
    const int64_t step = (int64_t)1 << d;
    int64_t q = a / step;
    if (a % step != 0 && a < 0) {
        q -= 1;
    }
    const int64_t r = q % (int64_t)side;
    return (r < 0) ? r + (int64_t)side : r;
}

/* Over the cache, every call: the cache moves to the eye and runs this
 * frame's updates, its tables fold in what became resident and the domain
 * follows the eye, then the tiles are selected. */
static void clip_select(ft_bintree_method *m, const ft_terrain *t, const ft_camera *cam)
{
    ft_clip_levels_select(&m->cl, t, cam);
    double ei = 0.0, ej = 0.0;
    ft_clip_levels_eye(&m->cl, t, cam->eye_m, &ei, &ej);
    ft_btc_update(&m->btc, &m->cl.cache, ei, ej);
    ft_bt_view v;
    ft_bt_view_from_camera(cam, t, 1, 0, &v);
    ft_btc_select(&m->btc, &v, m->tau_px * m->lod_scale, &m->sel);
    /* the eye may be below the cache's surface off the window's grid, which
     * the rule for hidden back faces (bintree.h) does not cover */
    m->sel.back_faces_hidden = 0;
    m->eye_rel[0] = ei - (double)m->btc.origin[0];
    m->eye_rel[1] = ej - (double)m->btc.origin[1];
    pack_tiles(m, m->btc.tiles);
    ft_view_key_take(&m->sel_view, cam);
}

static void bintree_select(ft_bintree_method *m, const ft_terrain *t, const ft_camera *cam)
{
    if (m->clip) {
        clip_select(m, t, cam);
        return;
    }
    if (ft_view_key_matches(&m->sel_view, cam)) {
        return;
    }
    ft_bt_view v;
    ft_bt_view_from_camera(cam, t, 1, m->morph, &v);
    ft_bintree_select(&m->bt, &v, m->tau_px * m->lod_scale, &m->sel);
    pack_tiles(m, m->bt.tiles);
    ft_view_key_take(&m->sel_view, cam);
}

static void bintree_set_lod_scale(ft_bintree_method *m, double scale)
{
    const double s = scale < 1.0 ? 1.0 : scale;
    if (s != m->lod_scale) {
        m->lod_scale = s;
        m->sel_view.valid = 0; /* select again for the same view */
    }
}

/* The method's uniforms on program p (current). */
static void set_uniforms(const ft_bintree_method *m, const ft_gl *gl,
                         const struct ft_terrain_program *p, const ft_camera *cam)
{
    const double tau = m->sel.tau_used_px; /* the morph is the selection's */
    gl->Uniform1i(p->method_u[FT_BT_U_DIA], 1);
    gl->Uniform1i(p->method_u[FT_BT_U_ZB], 4);
    gl->Uniform4f(p->method_u[FT_BT_U_GAP], (float)m->bt.morph_width, (float)m->bt.fine_m,
                  (float)(1u << m->bt.zblock_shift), 0.0f);
    gl->Uniform3f(p->method_u[FT_BT_U_LATTICE], (float)m->bt.step, (float)m->bt.lattice_side,
                  (float)m->bt.fine_side);
    const ft_bt_twist_layout *tl = &m->bt.twist;
    gl->Uniform4f(p->method_u[FT_BT_U_SUB], (float)(1u << m->bt.sub), (float)(m->bt.step << m->bt.sub),
                  (float)tl->levels, m->bt.sub > 0u ? 1.0f : 0.0f);
    if (m->vertex_table) {
        gl->Uniform1i(p->method_u[FT_BT_U_VTX], 3);
    }
    if (m->bt.sub > 0u) {
        gl->Uniform1i(p->method_u[FT_BT_U_TWIST], 2);
        gl->Uniform4f(p->method_u[FT_BT_U_TWIST_PACK], m->twist_fmt.pack_min,
                      m->twist_fmt.format == FT_HEIGHT_FORMAT_PACKED ? m->twist_fmt.pack_range
                                                                     : 0.0f,
                      (float)tl->atlas_w, (float)tl->atlas_h);
        for (uint32_t l = 0; l < tl->levels; ++l) {
            gl->Uniform2f(p->method_u[FT_BT_U_TWIST_OFF + l], (float)tl->ox[l], (float)tl->oy[l]);
        }
    }
    gl->Uniform4f(p->method_u[FT_BT_U_MORPH], (float)cam->px_per_rad_k,
                  isfinite(tau) ? (float)tau : 0.0f, 0.0f,
                  (m->morph && isfinite(tau) && tau > 0.0) ? 1.0f : 0.0f);
    ft_view_gain_frame gain;
    ft_view_gain_frame_from_camera(cam, &gain);
    gl->Uniform3f(p->method_u[FT_BT_U_AXIS], (float)gain.fwd[0], (float)gain.fwd[1],
                  (float)gain.fwd[2]);
    gl->Uniform2f(p->method_u[FT_BT_U_GAIN_CAP], (float)gain.a_cap, (float)gain.b_cap);
}

/* Tiles [first, first + count) of the selection through program p (current),
 * batch_tiles a draw: bounded by tiles_max / batch_tiles + 1 draws. */
static uint32_t draw_tiles(const ft_bintree_method *m, const ft_gl *gl,
                           const struct ft_terrain_program *p, uint32_t first, uint32_t count)
{
    uint32_t draws = 0u;
    for (uint32_t done = 0; done < count; done += m->batch_tiles) {
        const uint32_t n = (count - done < m->batch_tiles) ? count - done : m->batch_tiles;
        gl->Uniform4fv(p->method_u[FT_BT_U_TILES], (GLsizei)n,
                       m->inst + (size_t)(first + done) * FT_BT_FLOATS_PER_TILE);
        gl->DrawElements(GL_TRIANGLES, (GLsizei)(n * m->index_count), GL_UNSIGNED_SHORT,
                         (const void *)0);
        draws += 1u;
    }
    return draws;
}

/* Over the cache: the atlas on unit 1 and the uniforms of
 * shaders/bintree_clip.vert.glsl on program p (current). The eye is split
 * into the integer and fractional parts of its offset from the domain's
 * origin, so the shader's positions near the eye are differences of small
 * numbers wherever the origin is. */
static void clip_bind(const ft_bintree_method *m, const ft_gl *gl,
                      const struct ft_terrain_program *p)
{
    const ft_clip_levels *c = &m->cl;
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, c->tex[0]);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->Uniform1i(p->method_u[FT_BTC_U_ATLAS], 1);
    /* the origin is a multiple of 2^d for every level d <= Lc (bintree_cache.h) */
    for (uint32_t d = 0; d < c->levels; ++d) {
        gl->Uniform4f(p->method_u[FT_BTC_U_LEVEL + d], (float)c->origin_px[d][0],
                      (float)c->origin_px[d][1],
                      (float)level_index_mod(m->btc.origin[0], d, c->side),
                      (float)level_index_mod(m->btc.origin[1], d, c->side));
    }
    const double fi = floor(m->eye_rel[0]), fj = floor(m->eye_rel[1]);
    gl->Uniform4f(p->method_u[FT_BTC_U_EYE], (float)fi, (float)fj, (float)(m->eye_rel[0] - fi),
                  (float)(m->eye_rel[1] - fj));
    gl->Uniform4f(p->method_u[FT_BTC_U_MISC], (float)c->side, (float)m->btc.top,
                  (float)m->btc.k, 0.0f);
    /* the data box relative to the origin (far outside it over a database:
     * clamping is then a no-op) */
    const ft_bt_cache *bc = &m->btc;
    gl->Uniform4f(p->method_u[FT_BTC_U_DATA], (float)(bc->data[0] - bc->origin[0]),
                  (float)(bc->data[1] - bc->origin[1]), (float)(bc->data[2] - bc->origin[0]),
                  (float)(bc->data[3] - bc->origin[1]));
    gl->Uniform4f(p->method_u[FT_BTC_U_PACK], c->fmt.pack_min,
                  c->fmt.format == FT_HEIGHT_FORMAT_PACKED ? c->fmt.pack_range : 0.0f,
                  (float)c->tex_w, (float)c->tex_h);
}

/* Over the cache: the selection's tiles in the window path's batches. */
static void clip_draw(ft_bintree_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                      const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    /* a view the selection did not see (a set LOD scale too) is selected
     * here, the cache moved with it, as clipmap's draw does */
    if (!ft_view_key_matches(&m->sel_view, cam)) {
        clip_select(m, t, cam);
    }
    clip_bind(m, gl, p);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    const uint32_t tiles = m->sel.tiles;
    st->draw_calls = draw_tiles(m, gl, p, 0u, tiles);
    st->triangles = (uint64_t)tiles * m->triangles_per_tile;
    st->tiles = tiles;
    st->tau_achieved_px = m->sel.tau_achieved_px;
    st->tau_target_px = m->sel.tau_used_px;
    st->budget_hit = m->sel.budget_hit;
    st->back_faces_culled = 0;
    st->cache_levels_behind = m->cl.cache.stats.levels_behind;
    st->cache_samples_outstanding = m->cl.cache.stats.samples_outstanding;
    /* level 0's usable box does not reach around the eye (bintree_cache.h) */
    st->cache_coarser = ft_btc_eye_coarser(&m->btc, m->eye_rel[0] + (double)m->btc.origin[0],
                                           m->eye_rel[1] + (double)m->btc.origin[1]);
    st->cache_forced_updates = m->cl.forced_last;
}

static void bintree_draw(ft_bintree_method *m, const ft_gl *gl,
                         const struct ft_terrain_program *p, const ft_terrain *t,
                         const ft_camera *cam, ft_method_draw_stats *st)
{
    if (m->clip) {
        clip_draw(m, gl, p, t, cam, st);
        return;
    }
    bintree_select(m, t, cam);
    if (m->morph) {
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, m->dia_tex);
        if (m->bt.sub > 0u) {
            gl->ActiveTexture(GL_TEXTURE4);
            gl->BindTexture(GL_TEXTURE_2D, m->zb_tex);
        }
    }
    if (m->bt.sub > 0u) {
        gl->ActiveTexture(GL_TEXTURE2);
        gl->BindTexture(GL_TEXTURE_2D, m->twist_tex);
    }
    if (m->vertex_table) {
        gl->ActiveTexture(GL_TEXTURE3);
        gl->BindTexture(GL_TEXTURE_2D, m->vtx_tex);
    }
    gl->ActiveTexture(GL_TEXTURE0);
    /* Coarse tiles (every vertex on a sample) go through the pass's coarse
     * program when it has one: the sub-sample code is not in it. */
    const struct ft_terrain_program *coarse = m->vertex_table ? p->coarse : NULL;
    if (coarse != NULL) {
        gl->UseProgram(coarse->program);
        set_uniforms(m, gl, coarse, cam);
        gl->UseProgram(p->program);
    }
    set_uniforms(m, gl, p, cam);

    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->ibo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    const uint32_t tiles = m->sel.tiles;
    /* every tile keeps the roots' counter-clockwise winding seen from above
     * (a bisection child lists its corners in its parent's turn), and GL's
     * front faces are counter-clockwise */
    const int cull = m->cull_back_faces && m->sel.back_faces_hidden;
    if (cull) {
        gl->Enable(GL_CULL_FACE);
        gl->CullFace(GL_BACK);
    }
    const uint32_t n_coarse = (coarse != NULL) ? m->sel.tiles_coarse : 0u;
    st->draw_calls = 0u;
    if (n_coarse > 0u) {
        gl->UseProgram(coarse->program);
        st->draw_calls += draw_tiles(m, gl, coarse, 0u, n_coarse);
        gl->UseProgram(p->program);
    }
    st->draw_calls += draw_tiles(m, gl, p, n_coarse, tiles - n_coarse);
    if (cull) {
        gl->Disable(GL_CULL_FACE);
    }
    st->triangles = (uint64_t)tiles * m->triangles_per_tile;
    st->tiles = tiles;
    st->tau_achieved_px = m->sel.tau_achieved_px;
    st->tau_target_px = m->sel.tau_used_px;
    st->budget_hit = m->sel.budget_hit;
    st->back_faces_culled = cull;
}

static void bintree_shutdown(ft_bintree_method *m, const ft_gl *gl)
{
    if (m->vbo) gl->DeleteBuffers(1, &m->vbo);
    if (m->ibo) gl->DeleteBuffers(1, &m->ibo);
    if (m->dia_tex) gl->DeleteTextures(1, &m->dia_tex);
    if (m->zb_tex) gl->DeleteTextures(1, &m->zb_tex);
    if (m->twist_tex) gl->DeleteTextures(1, &m->twist_tex);
    if (m->vtx_tex) gl->DeleteTextures(1, &m->vtx_tex);
    m->vbo = m->ibo = m->dia_tex = m->zb_tex = m->twist_tex = m->vtx_tex = 0u;
    if (m->clip) {
        ft_clip_levels_shutdown(&m->cl, gl);
    }
}

/* ---- the method table ---------------------------------------------------------- */

/* The compile-time vertex shader variant (sub-sample levels, vertex table,
 * tiles a draw) as #define lines, in buf (init only: the programs are
 * compiled from it before the next call). */
static const char *vertex_defines(char *buf, size_t cap, int sub, int vtx, const ft_scene *s,
                                  int es3)
{
    (void)snprintf(buf, cap, "#define FT_BT_SUB %d\n#define FT_BT_VTX %d\n#define FT_BT_BATCH %u\n",
                   sub, vtx, batch_tiles_of(s, es3));
    return buf;
}

static const char *ops_vertex_defines(const ft_scene *s, int es3)
{
    static char buf[128];
    if (s->bintree_heights_clipmap) {
        /* bintree_clip.vert.glsl has one variant a batch length */
        (void)snprintf(buf, sizeof buf, "#define FT_BT_BATCH %u\n", batch_tiles_of(s, es3));
        return buf;
    }
    return vertex_defines(buf, sizeof buf, s->bintree_subsample_levels > 0u,
                          es3 && s->bintree_vertex_table, s, es3);
}

static const char *ops_vertex_shader_of(const ft_scene *s)
{
    return s->bintree_heights_clipmap ? "bintree_clip.vert.glsl" : "bintree.vert.glsl";
}

/* Tiles with every vertex on a sample get a program without sub-sample code
 * (GLES 3, sub-sample levels and the vertex table). */
static const char *ops_vertex_defines_coarse(const ft_scene *s, int es3)
{
    static char buf[128];
    if (s->bintree_subsample_levels == 0u || !es3 || !s->bintree_vertex_table ||
        s->bintree_heights_clipmap) {
        return NULL;
    }
    return vertex_defines(buf, sizeof buf, 0, 1, s, es3);
}

static ft_status ops_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                          ft_arena *a, ft_error *err)
{
    return bintree_init(&m->u.bintree, gl, s, t, a, err);
}

static void ops_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    bintree_select(&m->u.bintree, t, cam);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    bintree_draw(&m->u.bintree, gl, p, t, cam, st);
}

static void ops_set_lod_scale(ft_method *m, double scale)
{
    bintree_set_lod_scale(&m->u.bintree, scale);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    const ft_bintree_method *b = &m->u.bintree;
    return b->gpu_bytes + (b->clip ? b->cl.gpu_bytes : 0u);
}

static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    (void)t;
    const ft_bintree_method *b = &m->u.bintree;
    const uint32_t tiles_max = b->clip ? b->btc.tiles_max : b->bt.tiles_max;
    w->triangles = (uint64_t)tiles_max * b->triangles_per_tile;
    (void)snprintf(w->rule, sizeof w->rule, "bintree.tiles_max x 4^template_k");
}

/* Over the cache: its updates in the frame's spare time, and the depth range
 * of what it holds (the window's grid does not bound what is drawn past it). */
static void ops_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    if (m->u.bintree.clip) {
        ft_clip_levels_spare(&m->u.bintree.cl, now, deadline_ns);
    }
}

static int ops_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                         double corner_cos)
{
    const ft_bintree_method *b = &m->u.bintree;
    return b->clip ? ft_clip_levels_fit_depth(&b->cl, t, cam, corner_cos) : 0;
}

static void ops_shutdown(ft_method *m, const ft_gl *gl)
{
    bintree_shutdown(&m->u.bintree, gl);
}

const ft_method_ops ft_bintree_ops = {
    .vertex_shader = "bintree.vert.glsl",
    .vertex_shader_of = ops_vertex_shader_of,
    .uniforms = {k_bt_uniforms, sizeof k_bt_uniforms / sizeof k_bt_uniforms[0]},
    .vertex_defines = ops_vertex_defines,
    .vertex_defines_coarse = ops_vertex_defines_coarse,
    .plan = bintree_plan,
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
