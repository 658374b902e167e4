/* bench_oracle.c - the bintree frame's floor (see bench_oracle.h). */
#include "bench_oracle.h"

#include <stdlib.h>
#include <string.h>

#include "core/platform_api.h"
#include "lod/bintree_mesh.h"
#include "lod/bintree_template.h"

#define ORACLE_STRIDE ((GLsizei)(FT_BT_MESH_FLOATS * sizeof(float)))

/* Slots 0, 1, 2 (the renderer binds them before linking). */
static const char *const k_oracle_attribs[3] = {"a_pos_rel_eye_m", "a_normal", "a_height_m"};

/* Makes *p hold at least need elements of elem bytes (contents not kept). */
static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) {
        return 1;
    }
    if (need > SIZE_MAX / elem) {
        return 0;
    }
    free(*p);
    *p = malloc(need * elem);
    *cap = (*p != NULL) ? need : 0u;
    return *p != NULL;
}

ft_status bench_oracle_init(bench_oracle *o, ft_renderer *r, ft_error *err)
{
    memset(o, 0, sizeof *o);
    const ft_gl *gl = r->gl;
    if (r->method.kind != FT_METHOD_BINTREE) {
        return ft_fail(err, FT_ERR_UNSUPPORTED, "oracle: only for the bintree method");
    }
    if (gl->api != FT_GL_API_ES3 && !ft_gl_has_extension(gl, "GL_OES_element_index_uint")) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "oracle: this GLES 2 context has no 32-bit indices "
                       "(GL_OES_element_index_uint)");
    }
    const ft_bintree_method *bm = &r->method.u.bintree;
    const uint32_t k = bm->clip ? bm->btc.k : bm->bt.k;
    o->gl = gl;
    o->tmpl_verts = ft_bt_template_vertices(k);
    o->tmpl_indices = 3u * ft_bt_template_triangles(k);
    o->tmpl_uv = malloc((size_t)o->tmpl_verts * 2u * sizeof(float));
    o->tmpl_idx = malloc((size_t)o->tmpl_indices * sizeof(uint16_t));
    int16_t *scratch = malloc((size_t)ft_bt_template_scratch(k) * sizeof(int16_t));
    ft_status st = FT_OK;
    if (o->tmpl_uv == NULL || o->tmpl_idx == NULL || scratch == NULL) {
        st = ft_fail(err, FT_ERR_BUDGET, "oracle: out of memory for the template");
    }
    if (st == FT_OK) {
        st = ft_bt_template_build(k, o->tmpl_uv, o->tmpl_idx, scratch, err);
    }
    free(scratch);
    char frag_buf[FT_SHADE_DEFINES_MAX];
    if (st == FT_OK) {
        const ft_terrain_program_desc d = {
            .vert_name = "oracle.vert.glsl",
            .frag_name = "terrain.frag.glsl",
            .frag_defines = ft_program_shade_defines(r->scene, r->terrain, frag_buf),
            .attribs = k_oracle_attribs,
        };
        st = ft_terrain_program_build(gl, r->terrain, &r->gt, &d, &o->prog, err);
    }
    if (st != FT_OK) {
        bench_oracle_shutdown(o);
        return st;
    }
    gl->GenBuffers(1, &o->vbo);
    gl->GenBuffers(1, &o->ibo);
    if (gl->caps.has_vao) {
        gl->GenVertexArrays(1, &o->vao);
    }
    o->ready = 1;
    st = ft_gl_check(gl, "oracle init", err);
    if (st != FT_OK) {
        bench_oracle_shutdown(o);
    }
    return st;
}

/* The vertex array in use for the oracle's draw: its own VAO where the
 * context has them, else the attribute state it shares with the renderer. */
static void bind_oracle_vao(const bench_oracle *o)
{
    if (o->vao != 0u) {
        o->gl->BindVertexArray(o->vao);
    }
}

static void restore_renderer_vao(const bench_oracle *o, const ft_renderer *r)
{
    const ft_gl *gl = o->gl;
    if (o->vao != 0u) {
        gl->BindVertexArray(r->vao);
    } else {
        /* no VAO: leave slots 1-2 as the method expects them (off) */
        gl->DisableVertexAttribArray(FT_ATTRIB_EXTRA1);
        gl->DisableVertexAttribArray(FT_ATTRIB_EXTRA2);
    }
}

ft_status bench_oracle_prepare(bench_oracle *o, ft_renderer *r, const ft_camera *cam,
                               ft_error *err)
{
    const uint64_t t0 = ft_plat_monotonic_ns();
    if (!o->ready) {
        return ft_fail(err, FT_ERR_ARG, "oracle: not initialised");
    }
    const ft_bintree_method *bm = &r->method.u.bintree;
    if (!bm->sel_view.valid) {
        return ft_fail(err, FT_ERR_ARG, "oracle: the method has not selected tiles yet");
    }
    const ft_gl *gl = o->gl;
    const uint32_t tiles = bm->sel.tiles;
    const size_t verts = (size_t)tiles * o->tmpl_verts;
    const size_t floats = verts * FT_BT_MESH_FLOATS;
    const size_t indices = (size_t)tiles * o->tmpl_indices;
    if (!grow((void **)&o->verts, &o->verts_cap, floats, sizeof(float)) ||
        !grow((void **)&o->idx, &o->idx_cap, indices, sizeof(uint32_t))) {
        return ft_fail(err, FT_ERR_BUDGET, "oracle: out of memory for %u tiles (%zu vertices)",
                       tiles, verts);
    }
    size_t built = 0u;
    if (bm->clip) {
        /* over the cache: its tiles, heights from the cache's copy of its levels */
        built = ft_btc_mesh_build(&bm->btc, &bm->cl.cache, tiles,
                                  bm->eye_rel[0] + (double)bm->btc.origin[0],
                                  bm->eye_rel[1] + (double)bm->btc.origin[1], cam->eye_m[2],
                                  r->terrain->curv_drop_per_m2, o->tmpl_uv, o->tmpl_verts,
                                  o->verts, o->verts_cap);
    } else {
        ft_bt_mesh_uniforms u;
        ft_bt_mesh_uniforms_for(r->terrain, cam, bm->sel.tau_used_px, bm->morph, &u);
        u.vertex_table = bm->vertex_table;
        built = ft_bt_mesh_build(&bm->bt, tiles, &u, o->tmpl_uv, o->tmpl_verts, o->verts,
                                 o->verts_cap);
    }
    if (built != verts) {
        return ft_fail(err, FT_ERR_ARG, "oracle: mirror of %u tiles failed", tiles);
    }
    bind_oracle_vao(o);
    gl->BindBuffer(GL_ARRAY_BUFFER, o->vbo);
    const size_t bytes = floats * sizeof(float);
    if (bytes > o->vbo_bytes) {
        gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)bytes, NULL, GL_STATIC_DRAW);
        o->vbo_bytes = bytes;
    }
    if (bytes > 0u) {
        gl->BufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, o->verts);
    }
    if (tiles > o->ibo_tiles) {
        /* the indices of tiles 0..n-1 are a prefix of those of more tiles */
        if (ft_bt_mesh_indices(tiles, o->tmpl_idx, o->tmpl_indices, o->tmpl_verts, o->idx,
                               o->idx_cap) != indices) {
            restore_renderer_vao(o, r);
            return ft_fail(err, FT_ERR_ARG, "oracle: indices of %u tiles do not fit", tiles);
        }
        gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, o->ibo);
        gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(indices * sizeof(uint32_t)), o->idx,
                       GL_STATIC_DRAW);
        o->ibo_tiles = tiles;
    }
    restore_renderer_vao(o, r);
    o->tiles = tiles;
    o->index_count = indices;
    gl->Finish(); /* the upload is done before the timed frame starts */
    o->prepare_ms = (double)(ft_plat_monotonic_ns() - t0) * 1e-6;
    return ft_gl_check(gl, "oracle upload", err);
}

ft_status bench_oracle_frame(bench_oracle *o, ft_renderer *r, const ft_camera *cam, double *ms,
                             ft_error *err)
{
    *ms = -1.0;
    if (!o->ready) {
        return ft_fail(err, FT_ERR_ARG, "oracle: not initialised");
    }
    const ft_gl *gl = o->gl;
    const uint64_t t0 = ft_plat_monotonic_ns();
    /* ft_renderer_draw's pass, with the oracle's program and mesh */
    const float sky[4] = {r->clear_rgb[0], r->clear_rgb[1], r->clear_rgb[2], 1.0f};
    ft_renderer_begin_pass(r, r->fbo_color, sky);
    gl->UseProgram(o->prog.program);
    gl->UniformMatrix4fv(o->prog.u_view_proj, 1, GL_FALSE, cam->view_proj);
    ft_shade_state shade; /* the renderer's colours at this frame's altitude */
    ft_renderer_frame_shade(r, cam, &shade);
    ft_program_shade_uniforms(gl, &o->prog.shade, &shade);
    bind_oracle_vao(o);
    gl->BindBuffer(GL_ARRAY_BUFFER, o->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, o->ibo);
    gl->EnableVertexAttribArray(0);
    gl->EnableVertexAttribArray(1);
    gl->EnableVertexAttribArray(2);
    gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, ORACLE_STRIDE, (const void *)0);
    gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, ORACLE_STRIDE,
                            (const void *)(3u * sizeof(float)));
    gl->VertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, ORACLE_STRIDE,
                            (const void *)(6u * sizeof(float)));
    /* the same triangles in the same state: culled when the method culled */
    const ft_bintree_method *bm = &r->method.u.bintree;
    const int cull = bm->cull_back_faces && bm->sel.back_faces_hidden;
    if (cull) {
        gl->Enable(GL_CULL_FACE);
        gl->CullFace(GL_BACK);
    }
    if (o->index_count > 0u) {
        gl->DrawElements(GL_TRIANGLES, (GLsizei)o->index_count, GL_UNSIGNED_INT, (const void *)0);
    }
    if (cull) {
        gl->Disable(GL_CULL_FACE);
    }
    restore_renderer_vao(o, r);
    const ft_status st = ft_renderer_read_rgba(r, err); /* waits for the GPU */
    *ms = (double)(ft_plat_monotonic_ns() - t0) * 1e-6;
    return st;
}

void bench_oracle_shutdown(bench_oracle *o)
{
    const ft_gl *gl = o->gl;
    if (gl != NULL) {
        if (o->prog.program != 0u) gl->DeleteProgram(o->prog.program);
        if (o->vbo != 0u) gl->DeleteBuffers(1, &o->vbo);
        if (o->ibo != 0u) gl->DeleteBuffers(1, &o->ibo);
        if (o->vao != 0u && gl->DeleteVertexArrays != NULL) gl->DeleteVertexArrays(1, &o->vao);
    }
    free(o->tmpl_uv);
    free(o->tmpl_idx);
    free(o->verts);
    free(o->idx);
    memset(o, 0, sizeof *o);
}
