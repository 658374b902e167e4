/* test_app_util.h - the few steps every real-context test takes with an
 * ft_app (tests/test_*_gl.c): a pose, init from scene text, a frame, its
 * error, and the skip when ../shared/data is not there. Each REQUIRE's
 * message names the step and GL/init error text. */
#ifndef FT_TEST_APP_UTIL_H
#define FT_TEST_APP_UTIL_H

#include <stdio.h>

#include "app/app.h"
#include "test_util.h"

static inline ft_pose ft_test_pose(double lat, double lon, double alt, double heading,
                                   double pitch, double roll)
{
    ft_pose p = {lat, lon, alt, heading, pitch, roll};
    return p;
}

/* The crack tests' views over N42E001, which the terrain covers completely:
 * nadir, and oblique views steep enough that the top edge of the frustum
 * meets the ground well inside the grid (about 20 km away at most; the grid
 * is about 80 x 110 km). */
#define FT_TEST_COVERED_VIEWS 5u
static inline ft_pose ft_test_covered_view(uint32_t i)
{
    static const double v[FT_TEST_COVERED_VIEWS][6] = {
        {42.50, 1.50, 6000.0, 0.0, -90.0, 0.0},    {42.45, 1.45, 4500.0, 30.0, -89.0, 0.0},
        {42.50, 1.50, 4000.0, 45.0, -45.0, 0.0},   {42.40, 1.60, 4200.0, 200.0, -50.0, 10.0},
        {42.60, 1.40, 4000.0, 300.0, -60.0, -15.0},
    };
    const double *a = v[i % FT_TEST_COVERED_VIEWS];
    return ft_test_pose(a[0], a[1], a[2], a[3], a[4], a[5]);
}

/* Clears to magenta, never a terrain colour, so that a crack or a hole in
 * the drawn surface shows as clear pixels (ft_test_clear_pixels). */
static inline void ft_test_clear_magenta(ft_app *app)
{
    app->renderer.clear_rgb[0] = 1.0f;
    app->renderer.clear_rgb[1] = 0.0f;
    app->renderer.clear_rgb[2] = 1.0f;
}

/* Pixels of the clear colour in the app's last frame. */
static inline uint32_t ft_test_clear_pixels(const ft_app *app)
{
    const uint8_t *p = app->renderer.rgba;
    const size_t n = (size_t)app->scene.width_px * app->scene.height_px;
    uint32_t c = 0;
    for (size_t i = 0; i < n; ++i) {
        c += (p[4u * i] == 255u && p[4u * i + 1u] == 0u && p[4u * i + 2u] == 255u);
    }
    return c;
}

/* Parses scene_text over the defaults and inits app; what names the set-up
 * in the failure message. */
static inline void ft_test_app_init(ft_app *app, const char *scene_text, const char *what)
{
    static ft_scene s; /* large: not on the stack */
    ft_error err;
    ft_scene_defaults(&s);
    ft_status st = ft_scene_parse(&s, scene_text, "test scene", &err);
    if (st == FT_OK) st = ft_app_init(app, &s, &err);
    if (st != FT_OK) fprintf(stderr, "init (%s): %s\n", what, err.text);
    REQUIRE(st == FT_OK);
}

static inline void ft_test_frame(ft_app *app, const ft_pose *p, ft_camera *cam,
                                 ft_frame_stats *fs)
{
    ft_error err;
    ft_status st = ft_app_render(app, p, cam, fs, &err);
    if (st != FT_OK) fprintf(stderr, "frame: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

static inline void ft_test_measure(ft_app *app, const ft_camera *cam, ft_error_stats *es)
{
    ft_error err;
    ft_status st = ft_app_measure(app, cam, es, &err);
    if (st != FT_OK) fprintf(stderr, "measure: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

/* 1 when path can be opened; else says the test is skipped (return
 * FT_TEST_SKIP then). */
static inline int ft_test_have_data(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        printf("%s missing: skipped (needs ../shared/data)\n", path);
        return 0;
    }
    fclose(f);
    return 1;
}

/* The bintree's template expanded to triangle lists (flat: tmpl_verts x
 * (a, b)) in the method's batch layout: batch_tiles copies, each vertex
 * (a, b, slot), as the capture below draws it (GLES 3 transform feedback
 * takes DrawArrays only). The caller deletes the buffer. */
static inline GLuint ft_test_bintree_flat_vbo(const ft_app *app, const float *flat,
                                              uint32_t tmpl_verts)
{
    const ft_gl *gl = app->renderer.gl;
    const uint32_t batch = app->renderer.method.u.bintree.batch_tiles;
    REQUIRE(batch > 0u);
    const size_t n = (size_t)batch * tmpl_verts;
    float *v = (float *)malloc(n * 3u * sizeof(float));
    REQUIRE(v != NULL);
    for (uint32_t s = 0; s < batch; ++s) {
        for (uint32_t i = 0; i < tmpl_verts; ++i) {
            float *o = v + 3u * ((size_t)s * tmpl_verts + i);
            o[0] = flat[2u * i];
            o[1] = flat[2u * i + 1u];
            o[2] = (float)s;
        }
    }
    GLuint vbo = 0;
    gl->GenBuffers(1, &vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 3u * sizeof(float)), v, GL_STATIC_DRAW);
    free(v);
    return vbo;
}

/* Transform feedback of the bintree's last frame: its selected tiles drawn
 * again as triangle lists (tmpl_vbo from ft_test_bintree_flat_vbo) into tfb
 * (bytes long, floats_per_vertex floats a vertex, in tile order), in the
 * method's batches, each tile through the program the frame drew it with:
 * the coarse tiles through the pass's coarse program when it has one, the
 * rest through the colour program (both still hold the frame's uniforms).
 * Returns the primitives the GPU reports written, or the expected count
 * without queries. */
static inline uint64_t ft_test_bintree_capture(const ft_app *app, GLuint tfb, size_t bytes,
                                               GLuint tmpl_vbo, uint32_t tmpl_verts,
                                               uint32_t floats_per_vertex)
{
    const ft_gl *gl = app->renderer.gl;
    const ft_bintree_method *bm = &app->renderer.method.u.bintree;
    const ft_terrain_program *p = &app->renderer.prog_color;
    const uint32_t n_coarse = (p->coarse != NULL) ? bm->sel.tiles_coarse : 0u;
    const struct {
        GLuint program;
        uint32_t first, count;
    } groups[2] = {{p->coarse != NULL ? p->coarse->program : 0u, 0u, n_coarse},
                   {p->program, n_coarse, bm->sel.tiles - n_coarse}};
    const size_t vertex_bytes = (size_t)floats_per_vertex * sizeof(float);
    GLuint query = 0;
    if (gl->GenQueries != NULL) {
        gl->GenQueries(1, &query);
        gl->BeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
    }
    gl->Enable(GL_RASTERIZER_DISCARD);
    gl->BindBuffer(GL_ARRAY_BUFFER, tmpl_vbo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 3, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    for (int g = 0; g < 2; ++g) {
        if (groups[g].count == 0u) {
            continue;
        }
        const size_t out = (size_t)groups[g].first * tmpl_verts * vertex_bytes;
        REQUIRE(out < bytes);
        gl->UseProgram(groups[g].program);
        const GLint tiles_u = gl->GetUniformLocation(groups[g].program, "u_bt_tiles");
        REQUIRE(tiles_u >= 0);
        gl->BindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb, (GLintptr)out,
                            (GLsizeiptr)(bytes - out));
        gl->BeginTransformFeedback(GL_TRIANGLES);
        for (uint32_t done = 0; done < groups[g].count; done += bm->batch_tiles) {
            const uint32_t left = groups[g].count - done;
            const uint32_t n = left < bm->batch_tiles ? left : bm->batch_tiles;
            gl->Uniform4fv(tiles_u, (GLsizei)n, bm->inst + 4u * (size_t)(groups[g].first + done));
            gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)(n * tmpl_verts));
        }
        gl->EndTransformFeedback();
    }
    gl->UseProgram(p->program);
    gl->Disable(GL_RASTERIZER_DISCARD);
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    uint64_t prims = (uint64_t)bm->sel.tiles * tmpl_verts / 3u;
    if (query != 0u) {
        gl->EndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
        GLuint n = 0;
        gl->GetQueryObjectuiv(query, GL_QUERY_RESULT, &n);
        prims = n;
        gl->DeleteQueries(1, &query);
    }
    return prims;
}

#endif
