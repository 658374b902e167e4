/* method_brute.c - the baseline: the whole grid (or a window of it) as one
 * regular mesh, every sample a vertex, heights from the vertex texture.
 *
 * One template patch of patch_cells^2 cells ((patch_cells+1)^2 vertices,
 * 16-bit indices, so it works on GLES 2 without OES_element_index_uint) is
 * drawn once per patch with the patch origin as a uniform. Template vertices
 * past the grid edge are clamped onto it in the shader: the degenerate
 * triangles there cost a little and draw nothing.
 *
 * When the grid has more samples than brute.max_vertices, a square window
 * of samples centred under the eye is drawn (clamped into the grid). */
#include <math.h>
#include <stdio.h>

#include "gpu/program.h"
#include "lod/method.h"

static uint32_t vertex_count(uint32_t p)
{
    return (p + 1u) * (p + 1u);
}

static uint32_t index_count(uint32_t p)
{
    return p * p * 6u;
}

static void brute_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    (void)t;
    uint32_t p = s->brute_patch_cells;
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)vertex_count(p) * 2u * sizeof(float));
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)index_count(p) * sizeof(uint16_t));
}

static ft_status brute_init(ft_brute *b, const ft_gl *gl, const ft_scene *s,
                            const ft_terrain *t, ft_arena *a, ft_error *err)
{
    uint32_t p = s->brute_patch_cells;
    float *uv = NULL;
    uint16_t *idx = NULL;
    ft_status st;

    b->patch_cells = p;
    b->index_count = index_count(p);
    b->window_side = (uint32_t)floor(sqrt((double)s->brute_max_vertices));
    if (b->window_side < 2u) {
        b->window_side = 2u;
    }
    (void)t;
    st = ft_arena_take(a, FT_POOL_METHOD, (size_t)vertex_count(p) * 2u * sizeof(float),
                       (void **)&uv, err);
    if (st != FT_OK) {
        return st;
    }
    st = ft_arena_take(a, FT_POOL_METHOD, (size_t)index_count(p) * sizeof(uint16_t),
                       (void **)&idx, err);
    if (st != FT_OK) {
        return st;
    }
    for (uint32_t y = 0; y <= p; ++y) {
        for (uint32_t x = 0; x <= p; ++x) {
            uv[(y * (p + 1u) + x) * 2u + 0u] = (float)x;
            uv[(y * (p + 1u) + x) * 2u + 1u] = (float)y;
        }
    }
    uint32_t k = 0;
    for (uint32_t y = 0; y < p; ++y) {
        for (uint32_t x = 0; x < p; ++x) {
            uint16_t v00 = (uint16_t)(y * (p + 1u) + x);
            uint16_t v10 = (uint16_t)(v00 + 1u);
            uint16_t v01 = (uint16_t)(v00 + (p + 1u));
            uint16_t v11 = (uint16_t)(v01 + 1u);
            /* counter-clockwise seen from above */
            idx[k++] = v00; idx[k++] = v10; idx[k++] = v11;
            idx[k++] = v00; idx[k++] = v11; idx[k++] = v01;
        }
    }
    gl->GenBuffers(1, &b->vbo);
    gl->GenBuffers(1, &b->ibo);
    gl->BindBuffer(GL_ARRAY_BUFFER, b->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)vertex_count(p) * 2u * sizeof(float)),
                   uv, GL_STATIC_DRAW);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, b->ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER,
                   (GLsizeiptr)((size_t)index_count(p) * sizeof(uint16_t)), idx, GL_STATIC_DRAW);
    b->gpu_bytes = (uint64_t)vertex_count(p) * 8u + (uint64_t)index_count(p) * 2u;
    return ft_gl_check(gl, "brute init (template buffers)", err);
}

/* Window [x0, x1] x [y0, y1] in samples around the eye, at most side wide. */
static void pick_window(const ft_brute *b, const ft_terrain *t, const ft_camera *cam,
                        uint32_t *x0, uint32_t *x1, uint32_t *y0, uint32_t *y1)
{
    uint32_t side_x = (t->width < b->window_side) ? t->width : b->window_side;
    uint32_t side_y = (t->height < b->window_side) ? t->height : b->window_side;
    double gx = (cam->eye_m[0] - t->origin_world_x_m) / t->cell_x_m;
    double gy = (cam->eye_m[1] - t->origin_world_y_m) / t->cell_y_m;
    double cx = gx - 0.5 * (double)side_x;
    double cy = gy - 0.5 * (double)side_y;
    double max_x = (double)(t->width - side_x);
    double max_y = (double)(t->height - side_y);
    cx = (cx > 0.0) ? ((cx < max_x) ? cx : max_x) : 0.0; /* NaN-safe clamp */
    cy = (cy > 0.0) ? ((cy < max_y) ? cy : max_y) : 0.0;
    *x0 = (uint32_t)cx;
    *y0 = (uint32_t)cy;
    *x1 = *x0 + side_x - 1u;
    *y1 = *y0 + side_y - 1u;
}

static void brute_draw(ft_brute *b, const ft_gl *gl, const struct ft_terrain_program *p,
                       const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    uint32_t x0, x1, y0, y1;
    pick_window(b, t, cam, &x0, &x1, &y0, &y1);
    gl->BindBuffer(GL_ARRAY_BUFFER, b->vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, b->ibo);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->Uniform1f(p->u_patch_stride, 1.0f);
    gl->Uniform4f(p->u_clamp_box, (float)x0, (float)y0, (float)x1, (float)y1);
    const uint32_t pc = b->patch_cells;
    const uint32_t cells_x = x1 - x0;
    const uint32_t cells_y = y1 - y0;
    /* Bounded: at most (FT_GRID_SIDE_MAX / 1)^2 patches. */
    for (uint32_t py = 0; py < cells_y; py += pc) {
        for (uint32_t px = 0; px < cells_x; px += pc) {
            gl->Uniform2f(p->u_patch_origin, (float)(x0 + px), (float)(y0 + py));
            gl->DrawElements(GL_TRIANGLES, (GLsizei)b->index_count, GL_UNSIGNED_SHORT,
                             (const void *)0);
            uint32_t wx = (cells_x - px < pc) ? cells_x - px : pc;
            uint32_t wy = (cells_y - py < pc) ? cells_y - py : pc;
            st->triangles += 2ull * wx * wy; /* non-degenerate ones */
            st->draw_calls += 1u;
        }
    }
}

static void brute_shutdown(ft_brute *b, const ft_gl *gl)
{
    if (b->vbo != 0u) {
        gl->DeleteBuffers(1, &b->vbo);
    }
    if (b->ibo != 0u) {
        gl->DeleteBuffers(1, &b->ibo);
    }
    b->vbo = b->ibo = 0u;
}

/* ---- the method table ---------------------------------------------------------- */

static ft_status ops_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                          ft_arena *a, ft_error *err)
{
    return brute_init(&m->u.brute, gl, s, t, a, err);
}

static void ops_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                     const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    brute_draw(&m->u.brute, gl, p, t, cam, st);
}

static uint64_t ops_gpu_bytes(const ft_method *m)
{
    return m->u.brute.gpu_bytes;
}

/* The window (brute.max_vertices) rounded up to whole patches. */
static void ops_worst(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    const uint64_t p = m->u.brute.patch_cells, win = m->u.brute.window_side;
    const uint64_t cw = (t->width < win ? t->width : win) - 1u;
    const uint64_t ch = (t->height < win ? t->height : win) - 1u;
    w->triangles = ((cw + p - 1u) / p) * ((ch + p - 1u) / p) * p * p * 2u;
    (void)snprintf(w->rule, sizeof w->rule,
                   "whole patches covering the drawn window, 2 per cell");
}

static void ops_shutdown(ft_method *m, const ft_gl *gl)
{
    brute_shutdown(&m->u.brute, gl);
}

const ft_method_ops ft_brute_ops = {
    .vertex_shader = "terrain.vert.glsl",
    .plan = brute_plan,
    .init = ops_init,
    .draw = ops_draw,
    .gpu_bytes = ops_gpu_bytes,
    .worst = ops_worst,
    .shutdown = ops_shutdown,
};
