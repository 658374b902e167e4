/* test_pgm_gl.c - the pgm method on real GPU contexts over a real DEM
 * (argv[2], e.g. ../shared/data/N42E001.hgt, SRTM3 1201 x 1201).
 *
 * es3 mode:
 * 1. Shader = mirror: the colour program is relinked with transform feedback
 *    (gl_Position, v_morph = the vertex's continuous level L + w); after a
 *    real frame every grid vertex is captured once (GL_POINTS, band by band)
 *    and compared with src/lod/pgm.c's ft_pgm_vertex_at for the same sampling
 *    camera: screen position within FT_MIRROR_PX, L + w within 1e-3. Grids
 *    200 x 800 and 430 x 430, float and packed texels.
 * 2. Sweep: view pitch -90..+90 deg, fov 1..170 deg, camera 1 m .. 100 km
 *    above the ground under it, several headings and rolls, both grid
 *    shapes; and a camera 50 m under the ground and at z = -500 m (under the
 *    base plane: the mirrored sampling camera). Per view: no captured vertex is NaN or Inf, the position pass
 *    has no non-finite pixel, and whenever the reference ray caster has
 *    terrain in view the frame has terrain too (terrain present). The
 *    fraction of the reference's terrain pixels the frame covers is printed
 *    (per-pixel coverage is not claimed: close terrain far above the base
 *    plane, fovs near 170 deg and the 88 deg rectangle cap lose some).
 * 3. Image crack test: clear colour magenta (never a terrain colour); views
 *    the terrain covers completely must show none of it, for both grid
 *    shapes and a coarse 64 x 48 grid; a view above the horizon must (the
 *    counter works).
 * 1b. The same with pgm.heights = clipmap (ft_pgm_clip_vertex_at), after
 *    frames that leave finer levels lagging: L + w within 1e-3, position
 *    within FT_MIRROR_PX, and every vertex drawn from a level whose resident
 *    samples hold it.
 * 4. The error against the reference (foundation metric) along a path, pgm
 *    (both grids) beside brute force: printed, not a bound (pgm has none).
 * es2 mode (run with MESA_GLES_VERSION_OVERRIDE=2.0): a true ES 2.0 context;
 *    crack test and the sweep's terrain-present check from the colour image
 *    (no float targets, no transform feedback there).
 *
 * Usage: test_pgm_gl es3|es2 DEM */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "test_app_util.h"

/* float rounding in the shader: the mirror is double (0.0007 px seen) */
#define FT_MIRROR_PX 0.01

static ft_app g_app;
static char g_text[4096];

static const char k_scene_fmt[] =
    "[scene]\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = %u\nheight_px = %u\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\nheight_format = %s\ntexture_bytes = 64M\n[metric]\nenabled = %d\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 1442401\n"
    "[pgm]\ngrid_cols = %u\ngrid_rows = %u\nheights = %s\n"
    "[clipmap]\nside = 128\nlevels = 5\nupdate_samples_max = 4096\nupdates_per_frame = 2\n"
    "transition_samples = 12\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 1M\nframe_pos_bytes = 2M\nreference_bytes = 4M\nmetric_bytes = 2M\n"
    "gpu_staging_bytes = 8M\nmethod_bytes = 8M\npng_bytes = 512K\nclip_bytes = 64K\n";

/* pgm.heights of the next app_init (the clip-cache mirror sets it) */
static const char *g_heights = "pyramid";

typedef struct setup {
    const char *method, *backend, *dem, *format;
    uint32_t w, h, cols, rows;
    int metric;
} setup;

static void app_init(const setup *c)
{
    char what[64];
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, c->method, c->backend, c->w, c->h, c->dem,
                   c->format, c->metric, c->cols, c->rows, g_heights);
    (void)snprintf(what, sizeof what, "%s %ux%u (%s)", c->method, c->cols, c->rows, g_heights);
    ft_test_app_init(&g_app, g_text, what);
}

/* Camera for pose with any fov (the scene's fovy is only the default). */
static void camera_for(const ft_pose *p, double fovy_deg, ft_camera *cam)
{
    ft_error err;
    ft_status st = ft_camera_for_pose(&g_app.terrain, p, fovy_deg, g_app.scene.width_px,
                                      g_app.scene.height_px, cam, &err);
    if (st != FT_OK) fprintf(stderr, "camera: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

/* Draws a colour frame (the program stays in use with this frame's uniforms). */
static void draw(const ft_camera *cam, ft_frame_stats *fs)
{
    ft_error err;
    ft_renderer_select(&g_app.renderer, cam);
    ft_status st = ft_renderer_draw(&g_app.renderer, cam, fs, &err);
    if (st != FT_OK) fprintf(stderr, "draw: %s\n", err.text);
    REQUIRE(st == FT_OK);
}

static void read_rgba(void)
{
    ft_error err;
    REQUIRE(ft_renderer_read_rgba(&g_app.renderer, &err) == FT_OK);
}

static uint32_t clear_pixels(void)
{
    const uint8_t *p = g_app.renderer.rgba;
    const size_t n = (size_t)g_app.scene.width_px * g_app.scene.height_px;
    uint32_t c = 0;
    for (size_t i = 0; i < n; ++i) {
        c += (p[4u * i] == 255u && p[4u * i + 1u] == 0u && p[4u * i + 2u] == 255u);
    }
    return c;
}

static void magenta(void)
{
    g_app.renderer.clear_rgb[0] = 1.0f;
    g_app.renderer.clear_rgb[1] = 0.0f;
    g_app.renderer.clear_rgb[2] = 1.0f;
}

/* ---- transform feedback capture ------------------------------------------------ */

/* Every grid vertex once, row-major (rows bottom to top), 5 floats each:
 * gl_Position and v_morph. Right after draw() (its uniforms are in place). */
static void capture(float *out)
{
    const ft_gl *gl = g_app.renderer.gl;
    const ft_pgm_method *m = &g_app.renderer.method.u.pgm;
    const ft_terrain_program *p = &g_app.renderer.prog_color;
    const size_t n = (size_t)m->cols * m->rows;
    const size_t bytes = n * FT_CAPTURE_FLOATS_PER_VERTEX * sizeof(float);
    memset(out, 0xff, bytes); /* NaN: a vertex the capture did not write stays NaN */
    GLuint tfb = 0;
    gl->GenBuffers(1, &tfb);
    gl->BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
    gl->BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (GLsizeiptr)bytes, out, GL_STREAM_READ);
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, tfb);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->Enable(GL_RASTERIZER_DISCARD);
    gl->BeginTransformFeedback(GL_POINTS);
    for (uint32_t b = 0; b < m->band_count; ++b) {
        /* a band's first vertex row is the previous band's last: skip it */
        const uint32_t first_row = (b == 0u) ? 0u : 1u;
        const uint32_t vrows = ft_pgm_band_cell_rows(m, b) + 1u - first_row;
        gl->Uniform4f(p->method_u[FT_PGM_U_GRID], (float)(m->cols - 1u), (float)(m->rows - 1u),
                      (float)(b * m->band_rows), (float)m->levels);
        gl->DrawArrays(GL_POINTS, (GLint)(first_row * m->cols), (GLsizei)(vrows * m->cols));
    }
    gl->EndTransformFeedback();
    gl->Disable(GL_RASTERIZER_DISCARD);
    const void *mapped =
        gl->MapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, (GLsizeiptr)bytes, GL_MAP_READ_BIT);
    REQUIRE(mapped != NULL);
    memcpy(out, mapped, bytes);
    REQUIRE(gl->UnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER) == GL_TRUE);
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->DeleteBuffers(1, &tfb);
    ft_error err;
    REQUIRE(ft_gl_check(gl, "transform feedback capture", &err) == FT_OK);
}

static uint64_t count_nonfinite(const float *cap, size_t n)
{
    uint64_t bad = 0;
    for (size_t i = 0; i < n * FT_CAPTURE_FLOATS_PER_VERTEX; ++i) {
        bad += !isfinite(cap[i]);
    }
    return bad;
}

/* ---- 1. shader = mirror ------------------------------------------------------------ */

typedef struct mirror_stats {
    double worst_px, worst_level;
    uint64_t compared, fractional;
} mirror_stats;

static void compare_mirror(const ft_camera *cam, const float *cap, mirror_stats *ms)
{
    const ft_pgm_method *m = &g_app.renderer.method.u.pgm;
    const float *vp = cam->view_proj;
    for (uint32_t j = 0; j < m->rows; ++j) {
        for (uint32_t i = 0; i < m->cols; ++i) {
            const float *o = cap + ((size_t)j * m->cols + i) * FT_CAPTURE_FLOATS_PER_VERTEX;
            ft_pgm_vertex v;
            ft_pgm_vertex_at(&m->sampling, &g_app.terrain, m->cols, m->rows, i, j, &v);
            double clip[4];
            for (int r = 0; r < 4; ++r) {
                clip[r] = vp[r] * v.pos_rel_eye_m[0] + vp[4 + r] * v.pos_rel_eye_m[1] +
                          vp[8 + r] * v.pos_rel_eye_m[2] + vp[12 + r];
            }
            const double dl = fabs(o[4] - (v.level + v.parent_w));
            ms->worst_level = (dl > ms->worst_level) ? dl : ms->worst_level;
            ms->fractional += (v.parent_w > 0.05 && v.parent_w < 0.95);
            /* on screen (a little margin) and not at the eye: off screen, where w
             * is near 0, a float rounding in w is magnified without bound */
            if (!(clip[3] > 10.0 && fabs(clip[0]) < 1.2 * clip[3] && fabs(clip[1]) < 1.2 * clip[3])) {
                continue;
            }
            const double dx = (o[0] / o[3] - clip[0] / clip[3]) * 0.5 * cam->width_px;
            const double dy = (o[1] / o[3] - clip[1] / clip[3]) * 0.5 * cam->height_px;
            const double d = sqrt(dx * dx + dy * dy);
            if (d > ms->worst_px) {
                ms->worst_px = d;
                if (d > FT_MIRROR_PX) {
                    fprintf(stderr, "vertex (%u, %u): GPU and mirror %.4f px apart (level %u "
                            "w %.3f, grid %.3f %.3f)\n", i, j, d, v.level, v.parent_w,
                            v.grid[0], v.grid[1]);
                }
            }
            ++ms->compared;
        }
    }
}

static void test_mirror(const char *dem)
{
    static const struct {
        uint32_t cols, rows;
        const char *format;
    } grids[] = {{200, 800, "auto"}, {430, 430, "auto"}, {200, 800, "packed"}};
    const ft_pose views[] = {
        ft_test_pose(42.50, 1.50, 3600.0, 0.0, -20.0, 0.0),
        ft_test_pose(42.40, 1.30, 3300.0, 135.0, -8.0, 5.0),
        ft_test_pose(42.55, 1.65, 5000.0, 250.0, -45.0, 0.0),
        ft_test_pose(42.20, 1.10, 2400.0, 60.0, 3.0, -20.0),  /* above the horizon */
        ft_test_pose(42.50, 1.50, 9000.0, 0.0, -90.0, 0.0),   /* nadir */
        ft_test_pose(42.60, 1.40, 30000.0, 300.0, -30.0, 0.0),
    };
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
        setup c = {"pgm", "egl-gles3", dem, grids[g].format, 320, 240, grids[g].cols,
                   grids[g].rows, 0};
        app_init(&c);
        ft_error err;
        REQUIRE(ft_renderer_enable_capture(&g_app.renderer, &err) == FT_OK);
        const size_t n = (size_t)grids[g].cols * grids[g].rows;
        float *cap = malloc(n * FT_CAPTURE_FLOATS_PER_VERTEX * sizeof(float));
        REQUIRE(cap != NULL);
        mirror_stats ms;
        memset(&ms, 0, sizeof ms);
        uint64_t bad = 0;
        for (size_t v = 0; v < sizeof views / sizeof views[0]; ++v) {
            ft_camera cam;
            ft_frame_stats fs;
            camera_for(&views[v], 60.0, &cam);
            draw(&cam, &fs);
            CHECK(fs.triangles == 2ull * (grids[g].cols - 1u) * (grids[g].rows - 1u));
            CHECK(fs.draw_calls == g_app.renderer.method.u.pgm.band_count);
            capture(cap);
            bad += count_nonfinite(cap, n);
            compare_mirror(&cam, cap, &ms);
        }
        printf("mirror %ux%u (%s texels): %llu vertices compared, %llu with a fractional parent "
               "weight; GPU vs CPU mirror: worst %.4f px, worst L + w %.2g\n",
               grids[g].cols, grids[g].rows, grids[g].format, (unsigned long long)ms.compared,
               (unsigned long long)ms.fractional, ms.worst_px, ms.worst_level);
        CHECK(bad == 0u);
        CHECK(ms.compared > n); /* most vertices of several views were in front */
        CHECK(ms.fractional > n / 10u);
        CHECK(ms.worst_px <= FT_MIRROR_PX);
        CHECK(ms.worst_level <= 1e-3);
        free(cap);
        ft_app_shutdown(&g_app);
    }
}

/* ---- 1b. shader = mirror with the heights from the clip cache --------------------- */

/* The cached height of level-L sample (a, b), read through the cache's own
 * source: what was uploaded (the source gives the same value every time). */
static double cache_texel(const void *ctx, uint32_t level, int64_t a, int64_t b)
{
    const ft_clip_source *src = ctx;
    float h = 0.0f;
    ft_error err;
    REQUIRE(src->read(src->ctx, level, a, b, 1u, 1u, &h, NULL, NULL, &err) == FT_OK);
    return (double)h;
}

/* After real frames (the eye jumping between views, 2 cache updates a frame,
 * so finer levels lag and are refilled), every grid vertex as the shader
 * places it equals ft_pgm_clip_vertex_at (screen position within
 * FT_MIRROR_PX, L + w within 1e-3), and the level it drew from holds its
 * point among its resident samples (so nothing is drawn from texels that
 * are not there). Vertices whose level was raised to what is resident are
 * counted: the lagging case must occur. */
static void test_clip_mirror(const char *dem)
{
    static const struct {
        uint32_t cols, rows;
        const char *format;
    } grids[] = {{200, 800, "auto"}, {430, 430, "packed"}};
    const ft_pose views[] = {
        ft_test_pose(42.50, 1.50, 3600.0, 0.0, -20.0, 0.0),
        ft_test_pose(42.40, 1.30, 3300.0, 135.0, -8.0, 5.0),
        ft_test_pose(42.55, 1.65, 5000.0, 250.0, -45.0, 0.0),
        ft_test_pose(42.20, 1.10, 2400.0, 60.0, 3.0, -20.0),
        ft_test_pose(42.70, 1.65, 1500.0, 75.0, -30.0, 0.0),
        ft_test_pose(42.60, 1.40, 30000.0, 300.0, -30.0, 0.0),
    };
    g_heights = "clipmap";
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
        setup c = {"pgm", "egl-gles3", dem, grids[g].format, 320, 240, grids[g].cols,
                   grids[g].rows, 0};
        app_init(&c);
        ft_error err;
        REQUIRE(ft_renderer_enable_capture(&g_app.renderer, &err) == FT_OK);
        ft_pgm_method *m = &g_app.renderer.method.u.pgm;
        REQUIRE(m->clip);
        const size_t n = (size_t)grids[g].cols * grids[g].rows;
        float *cap = malloc(n * FT_CAPTURE_FLOATS_PER_VERTEX * sizeof(float));
        REQUIRE(cap != NULL);
        double worst_px = 0.0, worst_level = 0.0;
        uint64_t compared = 0u, raised = 0u, unresident = 0u, bad = 0u, captured = 0u;
        for (size_t v = 0; v < sizeof views / sizeof views[0]; ++v) {
            ft_camera cam;
            ft_frame_stats fs;
            camera_for(&views[v], 60.0, &cam);
            draw(&cam, &fs);
            capture(cap);
            bad += count_nonfinite(cap, n);
            ft_pgm_clip_view cv = m->clip_view;
            cv.texel = cache_texel;
            cv.ctx = &m->cl.src;
            const float *vp = cam.view_proj;
            const ft_terrain *t = &g_app.terrain;
            for (uint32_t j = 0; j < m->rows; ++j) {
                for (uint32_t i = 0; i < m->cols; ++i) {
                    const float *o = cap + ((size_t)j * m->cols + i) * FT_CAPTURE_FLOATS_PER_VERTEX;
                    ft_pgm_vertex x;
                    ft_pgm_clip_vertex_at(&m->sampling, &cv, t->cell_x_m, t->cell_y_m,
                                          t->curv_drop_per_m2, m->cols, m->rows, i, j, &x);
                    const double dl = fabs(o[4] - (x.level + x.parent_w));
                    worst_level = dl > worst_level ? dl : worst_level;
                    ++captured;
                    raised += (x.r_cells > 1.0 ? log2(x.r_cells) : 0.0) + 0.5 <
                              ft_pgm_clip_resident(&cv, x.grid[0], x.grid[1]);
                    /* the GPU's level holds the point among its resident samples */
                    const uint32_t l = (uint32_t)floor(o[4] + 1e-4);
                    if (l < cv.levels) {
                        const double sc = ldexp(1.0, (int)l);
                        const double ux = (x.grid[0] + cv.off[l][0]) / sc;
                        const double uy = (x.grid[1] + cv.off[l][1]) / sc;
                        const double *b = cv.box[l];
                        unresident += !(ux >= b[0] && ux <= b[2] && uy >= b[1] && uy <= b[3]);
                    }
                    double clip[4];
                    for (int r = 0; r < 4; ++r) {
                        clip[r] = vp[r] * x.pos_rel_eye_m[0] + vp[4 + r] * x.pos_rel_eye_m[1] +
                                  vp[8 + r] * x.pos_rel_eye_m[2] + vp[12 + r];
                    }
                    if (!(clip[3] > 10.0 && fabs(clip[0]) < 1.2 * clip[3] &&
                          fabs(clip[1]) < 1.2 * clip[3])) {
                        continue;
                    }
                    const double dx = (o[0] / o[3] - clip[0] / clip[3]) * 0.5 * cam.width_px;
                    const double dy = (o[1] / o[3] - clip[1] / clip[3]) * 0.5 * cam.height_px;
                    const double d = sqrt(dx * dx + dy * dy);
                    if (d > worst_px && d > FT_MIRROR_PX) {
                        fprintf(stderr, "clip vertex (%u, %u) view %zu: GPU and mirror %.4f px "
                                "apart (level %u w %.3f)\n", i, j, v, d, x.level, x.parent_w);
                    }
                    worst_px = d > worst_px ? d : worst_px;
                    ++compared;
                }
            }
        }
        printf("clip-cache mirror %ux%u (%s texels): of %llu vertices captured, %llu drawn "
               "from a level raised to what is resident, %llu from a level that does not hold "
               "them; %llu on screen compared, GPU vs CPU mirror: worst %.4f px, worst L + w "
               "%.2g\n",
               grids[g].cols, grids[g].rows, grids[g].format, (unsigned long long)captured,
               (unsigned long long)raised, (unsigned long long)unresident,
               (unsigned long long)compared, worst_px, worst_level);
        CHECK(bad == 0u);
        CHECK(compared > n);
        CHECK(raised > 0u);
        CHECK(unresident == 0u);
        CHECK(worst_px <= FT_MIRROR_PX);
        CHECK(worst_level <= 1e-3);
        free(cap);
        ft_app_shutdown(&g_app);
    }
    g_heights = "pyramid";
}

/* ---- 2. sweep ------------------------------------------------------------------------ */

static double ground_at(double lat, double lon)
{
    double x, y;
    ft_terrain_geo_to_world(&g_app.terrain, lat, lon, &x, &y);
    return ft_terrain_height_at(&g_app.terrain, x, y);
}

/* Reference terrain pixels and how many of them the colour frame covers. */
static void ref_coverage(const ft_camera *cam, uint32_t *ref_px, uint32_t *covered_px)
{
    ft_error err;
    const size_t n = (size_t)cam->width_px * cam->height_px;
    REQUIRE(ft_reference_render(&g_app.terrain, cam, g_app.ref, n, &err) == FT_OK);
    const uint8_t *p = g_app.renderer.rgba;
    *ref_px = *covered_px = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!g_app.ref[i].hit) continue;
        ++*ref_px;
        *covered_px += !(p[4u * i] == 255u && p[4u * i + 1u] == 0u && p[4u * i + 2u] == 255u);
    }
}

typedef struct sweep_totals {
    uint64_t bad_vertices, bad_px;
    uint32_t views, with_terrain, missing, below_90;
    double cov_sum, cov_min;
} sweep_totals;

/* One sweep view: frame, capture (ES 3), reference coverage, metric (ES 3). */
static void sweep_view(const ft_pose *p, double fov_deg, int es3, float *cap, size_t n,
                       sweep_totals *tot, const char *what)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_error err;
    camera_for(p, fov_deg, &cam);
    draw(&cam, &fs);
    if (es3) {
        capture(cap);
        const uint64_t b = count_nonfinite(cap, n);
        if (b > 0u && tot->bad_vertices == 0u) {
            fprintf(stderr, "non-finite vertices: %s\n", what);
        }
        tot->bad_vertices += b;
    }
    read_rgba();
    uint32_t ref_px, covered;
    ref_coverage(&cam, &ref_px, &covered);
    if (es3) {
        ft_error_stats es;
        REQUIRE(ft_app_measure(&g_app, &cam, &es, &err) == FT_OK);
        tot->bad_px += es.nonfinite_px;
    }
    ++tot->views;
    if (ref_px == 0u) return;
    ++tot->with_terrain;
    const double cov = (double)covered / ref_px;
    tot->cov_sum += cov;
    tot->cov_min = (cov < tot->cov_min) ? cov : tot->cov_min;
    tot->below_90 += (cov < 0.9);
    if (covered == 0u) {
        fprintf(stderr, "no terrain drawn, %u reference pixels: %s\n", ref_px, what);
        ++tot->missing;
    }
}

static void test_sweep(const char *backend, const char *dem)
{
    static const double pitches[] = {-90.0, -75.0, -45.0, -20.0, -10.0, -5.0, -1.0,
                                     0.0,   1.0,   5.0,   20.0,  45.0,  90.0};
    static const double fovs[] = {1.0, 20.0, 60.0, 120.0, 170.0};
    static const double heights[] = {1.0, 10.0, 100.0, 1000.0, 10000.0, 100000.0};
    static const struct {
        uint32_t cols, rows;
    } grids[] = {{200, 800}, {430, 430}};
    const int es3 = strcmp(backend, "egl-gles3") == 0;
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
        /* metric on everywhere: the reference buffer (ES 2 has no position pass) */
        setup c = {"pgm", backend, dem, "auto", 160, 120, grids[g].cols, grids[g].rows, 1};
        app_init(&c);
        magenta();
        ft_error err;
        if (es3) {
            REQUIRE(ft_renderer_enable_capture(&g_app.renderer, &err) == FT_OK);
        } else {
            CHECK(strstr(g_app.gpu.version, "OpenGL ES 2.0") != NULL);
        }
        const size_t n = (size_t)grids[g].cols * grids[g].rows;
        float *cap = es3 ? malloc(n * FT_CAPTURE_FLOATS_PER_VERTEX * sizeof(float)) : NULL;
        REQUIRE(!es3 || cap != NULL);
        sweep_totals tot;
        memset(&tot, 0, sizeof tot);
        tot.cov_min = 1.0;
        char what[160];
        int k = 0;
        for (size_t pi = 0; pi < sizeof pitches / sizeof pitches[0]; ++pi) {
            for (size_t fi = 0; fi < sizeof fovs / sizeof fovs[0]; ++fi) {
                for (size_t hi = 0; hi < sizeof heights / sizeof heights[0]; ++hi, ++k) {
                    const double lat = 42.15 + 0.7 * fmod(k * 0.37, 1.0);
                    const double lon = 1.15 + 0.7 * fmod(k * 0.61, 1.0);
                    const double heading = fmod(k * 47.0, 360.0);
                    const double roll = (k % 4 == 0) ? 0.0 : fmod(k * 29.0, 120.0) - 60.0;
                    const ft_pose p = ft_test_pose(lat, lon, ground_at(lat, lon) + heights[hi],
                                              heading, pitches[pi], roll);
                    (void)snprintf(what, sizeof what, "pitch %.0f fov %.0f height %.0f m roll %.0f",
                                   pitches[pi], fovs[fi], heights[hi], roll);
                    sweep_view(&p, fovs[fi], es3, cap, n, &tot, what);
                }
            }
        }
        /* the camera under the terrain (50 m below the ground under it) and
         * below z = 0 (under the base plane: the sampling eye is lifted) */
        for (int u = 0; u < 8; ++u) {
            const double lat = 42.3 + 0.05 * u, lon = 1.3 + 0.04 * u;
            const double alt = (u < 4) ? ground_at(lat, lon) - 50.0 : -500.0;
            const ft_pose p = ft_test_pose(lat, lon, alt, 40.0 * u, -45.0 + 30.0 * (u % 4), 0.0);
            (void)snprintf(what, sizeof what, "eye %s, pitch %.0f",
                           (u < 4) ? "50 m under the ground" : "at z = -500 m", p.pitch_deg);
            sweep_view(&p, 60.0, es3, cap, n, &tot, what);
        }
        const uint64_t bad_vertices = tot.bad_vertices, bad_px = tot.bad_px;
        const uint32_t views = tot.views, with_terrain = tot.with_terrain;
        const uint32_t missing = tot.missing, below_90 = tot.below_90;
        const double cov_sum = tot.cov_sum, cov_min = tot.cov_min;
        char finite[96] = "vertices and pixels not captured on ES 2";
        if (es3) {
            (void)snprintf(finite, sizeof finite, "%llu non-finite vertices, %llu non-finite pixels",
                           (unsigned long long)bad_vertices, (unsigned long long)bad_px);
        }
        printf("sweep %s %ux%u: %u views (%u with terrain in the reference): %s, %u views "
               "without terrain; reference terrain covered: mean %.3f, min %.3f, %u views "
               "below 0.9\n",
               backend, grids[g].cols, grids[g].rows, views, with_terrain, finite, missing,
               with_terrain ? cov_sum / with_terrain : 0.0, cov_min, below_90);
        CHECK(with_terrain > views / 3u);
        CHECK(bad_vertices == 0u);
        CHECK(bad_px == 0u);
        CHECK(missing == 0u);
        free(cap);
        ft_app_shutdown(&g_app);
    }
}

/* ---- 3. image crack test ---------------------------------------------------------------- */

static void test_cracks(const char *backend, const char *dem)
{
    /* views the terrain covers completely (the frustum's top edge meets the
     * ground well inside the grid, about 80 x 110 km) */
    const ft_pose covered[] = {
        ft_test_pose(42.50, 1.50, 6000.0, 0.0, -90.0, 0.0),
        ft_test_pose(42.45, 1.45, 4500.0, 30.0, -89.0, 0.0),
        ft_test_pose(42.50, 1.50, 4000.0, 45.0, -45.0, 0.0),
        ft_test_pose(42.40, 1.60, 4200.0, 200.0, -50.0, 10.0),
        ft_test_pose(42.60, 1.40, 4000.0, 300.0, -60.0, -15.0),
        ft_test_pose(42.50, 1.50, 3500.0, 100.0, -35.0, 0.0),
        ft_test_pose(42.30, 1.30, 5000.0, 10.0, -50.0, 20.0),
    };
    static const struct {
        uint32_t cols, rows;
    } grids[] = {{200, 800}, {430, 430}, {64, 48}};
    uint32_t worst = 0;
    const int es2 = strcmp(backend, "egl-gles2") == 0;
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; ++g) {
        setup c = {"pgm", backend, dem, "auto", 320, 240, grids[g].cols, grids[g].rows, 0};
        app_init(&c);
        if (es2) CHECK(strstr(g_app.gpu.version, "OpenGL ES 2.0") != NULL);
        magenta();
        for (size_t v = 0; v < sizeof covered / sizeof covered[0]; ++v) {
            ft_camera cam;
            ft_frame_stats fs;
            camera_for(&covered[v], 60.0, &cam);
            draw(&cam, &fs);
            read_rgba();
            const uint32_t n = clear_pixels();
            if (n > 0u) {
                fprintf(stderr, "%ux%u view %zu: %u clear-colour pixels\n", grids[g].cols,
                        grids[g].rows, v, n);
            }
            worst = (n > worst) ? n : worst;
            CHECK(n == 0u);
        }
        ft_camera cam;
        ft_frame_stats fs;
        camera_for(&covered[0], 60.0, &cam);
        const ft_pose sky = ft_test_pose(42.5, 1.5, 4000.0, 0.0, 5.0, 0.0);
        camera_for(&sky, 60.0, &cam);
        draw(&cam, &fs);
        read_rgba();
        CHECK(clear_pixels() > 1000u);
        ft_app_shutdown(&g_app);
    }
    printf("image crack test (%s): most clear-colour pixels in a covered view: %u\n", backend,
           worst);
}

/* ---- 4. error against the reference, beside brute force ------------------------------- */

#define PATH_FRAMES 8

static ft_pose path_pose(int f)
{
    const double s = (double)f / (PATH_FRAMES - 1);
    return ft_test_pose(42.30 + 0.30 * s, 1.25 + 0.45 * s, 3500.0 + 1500.0 * s, 40.0 + 25.0 * f,
                   -8.0 - 4.0 * f, (f % 3) * 8.0 - 8.0);
}

static void test_error(const char *dem)
{
    static const struct {
        const char *method;
        uint32_t cols, rows;
    } runs[] = {{"brute", 430, 430}, {"pgm", 200, 800}, {"pgm", 430, 430}};
    printf("screen-space error along an %d-frame path (256x192, max / mean px per frame):\n",
           PATH_FRAMES);
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; ++r) {
        setup c = {runs[r].method, "egl-gles3", dem, "auto", 256, 192, runs[r].cols,
                   runs[r].rows, 1};
        app_init(&c);
        double worst = 0.0, mean = 0.0;
        printf("  %-5s %s:", runs[r].method,
               strcmp(runs[r].method, "pgm") == 0 ? (runs[r].cols == 200 ? "200x800" : "430x430")
                                                  : "       ");
        for (int f = 0; f < PATH_FRAMES; ++f) {
            ft_camera cam;
            ft_frame_stats fs;
            ft_error_stats es;
            ft_error err;
            const ft_pose p = path_pose(f);
            REQUIRE(ft_app_render(&g_app, &p, &cam, &fs, &err) == FT_OK);
            REQUIRE(ft_app_measure(&g_app, &cam, &es, &err) == FT_OK);
            CHECK(es.nonfinite_px == 0u);
            CHECK(es.terrain_px > 1000u);
            printf(" %.1f/%.2f", es.max_px, es.mean_px);
            worst = (es.max_px > worst) ? es.max_px : worst;
            mean += es.mean_px / PATH_FRAMES;
        }
        printf("   worst max %.1f px, mean %.3f px\n", worst, mean);
        ft_app_shutdown(&g_app);
    }
}

int main(int argc, char **argv)
{
    REQUIRE(argc >= 3);
    const char *mode = argv[1], *dem = argv[2];
    if (!ft_test_have_data(dem)) return FT_TEST_SKIP;
    if (strcmp(mode, "es2") == 0) {
        test_cracks("egl-gles2", dem);
        test_sweep("egl-gles2", dem);
        return ft_test_result("test_pgm_gl es2");
    }
    test_mirror(dem);
    test_clip_mirror(dem);
    test_sweep("egl-gles3", dem);
    test_cracks("egl-gles3", dem);
    test_error(dem);
    return ft_test_result("test_pgm_gl es3");
}
