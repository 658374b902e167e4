/* test_clipmap_gl.c - the clipmap method on real contexts over a real DEM
 * (argv[2], e.g. ../shared/data/N42E001.hgt), 320 x 240, with glGetError
 * checked after every frame step (0 GL errors required).
 *
 * 1. Coverage beside brute force: for a set of views (nadir, oblique, low
 *    over a valley, towards the terrain's edge) the pixels clipmap covers
 *    and brute covers agree, except within SILHOUETTE_PX of brute's own
 *    terrain/sky boundary (a coarse level's ridge line differs from the
 *    full-resolution one by a pixel or two); at most OFF_SILHOUETTE_MAX
 *    pixels may differ elsewhere (a hole would be many more).
 * 2. Image crack test: clear colour magenta; on views the terrain covers
 *    completely not one magenta pixel, while the eye flies 60 frames across
 *    the tile with few updates a frame, so levels move, lag (valid smaller
 *    than wanted) and catch up while the eye then hovers (checked from the
 *    cache's stats). A view
 *    above the horizon must show magenta (the counter works).
 *    A jump past every level's box (3 levels: the coarsest spans 512
 *    samples; the eye moves 720) with no update budget: the frame completes
 *    the coarsest level before it draws, so it shows terrain, not the clear
 *    colour, while the finer levels are still behind.
 * 3. Transform feedback (es3): after real frames along the flight, every
 *    template vertex of every draw of every level is captured as the shader
 *    places it (v_pos_rel_eye_m); each fine vertex on a transition side of
 *    its drawn box and each coarse stitch vertex (matched by the CPU
 *    mirror's lattice position) have the same captured position, to the
 *    bit, and every coarse stitch vertex has its fine partner.
 * 4. The reported bound (es3, with the metric): every frame's measured
 *    error within the bound clipmap reports (bound_check below).
 * es3 runs with float texels; es2 (run under MESA_GLES_VERSION_OVERRIDE=2.0,
 * a true ES 2.0 context) with float and with packed texels.
 *
 * Usage: test_clipmap_gl es3|es2 DEM */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/platform_api.h"
#include "test_app_util.h"

#define W_PX 320u
#define H_PX 240u
#define SILHOUETTE_PX 2
#define OFF_SILHOUETTE_MAX 16u
#define VIEWS 8u

static ft_app g_app;
static char g_text[4096];
static uint8_t g_brute_mask[VIEWS][W_PX * H_PX];

static const char k_scene_fmt[] =
    "[scene]\nmethod = %s\nbackend = %s\n"
    "[view]\nwidth_px = %u\nheight_px = %u\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\nheight_format = %s\ntexture_bytes = 64M\n[metric]\nenabled = %d\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 1442401\n"
    "[pgm]\nheights = clipmap\n"
    "[pgrid]\nheights = clipmap\nerror_bound = %s\nray_casting = %d\ngamma_px = 1\n"
    "raycast_max_px = 76800\n"
    "[clipmap]\nside = %u\nlevels = %u\nupdate_samples_max = 4096\nupdates_per_frame = %u\n"
    "transition_samples = 12\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 1M\nframe_pos_bytes = 2M\nreference_bytes = 4M\nmetric_bytes = 2M\n"
    "gpu_staging_bytes = 8M\nmethod_bytes = 8M\npng_bytes = 512K\nclip_bytes = 12M\n";

/* pgrid's ray caster over the cache (on for pgrid_rc_bound_check) and its
 * error bound (residual for pgrid_tight_check) */
static int g_ray_casting;
static const char *g_error_bound = "relief";

static void app_init_metric(const char *method, const char *backend, const char *dem,
                            const char *format, uint32_t side, uint32_t levels,
                            uint32_t per_frame, int metric)
{
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, method, backend, W_PX, H_PX, dem, format,
                   metric, g_error_bound, g_ray_casting, side, levels, per_frame);
    ft_test_app_init(&g_app, g_text, method);
    g_app.renderer.gl_error_checks = 1;
    ft_test_clear_magenta(&g_app);
}

static void app_init(const char *method, const char *backend, const char *dem,
                     const char *format, uint32_t side, uint32_t levels, uint32_t per_frame)
{
    app_init_metric(method, backend, dem, format, side, levels, per_frame, 0);
}

static ft_pose view_of(uint32_t i)
{
    if (i < FT_TEST_COVERED_VIEWS) return ft_test_covered_view(i);
    static const double v[VIEWS - FT_TEST_COVERED_VIEWS][6] = {
        {42.30, 1.50, 3800.0, 0.0, -14.0, 0.0},   /* the pyrenees scene's view */
        {42.45, 1.30, 2200.0, 120.0, -5.0, 0.0},  /* low, the horizon in view */
        {42.10, 1.90, 5000.0, 135.0, -20.0, 0.0}, /* towards the south-east corner */
    };
    const double *a = v[i - FT_TEST_COVERED_VIEWS];
    return ft_test_pose(a[0], a[1], a[2], a[3], a[4], a[5]);
}

static void mask_of(uint8_t *m)
{
    const uint8_t *p = g_app.renderer.rgba;
    for (size_t i = 0; i < (size_t)W_PX * H_PX; ++i) {
        m[i] = !(p[4u * i] == 255u && p[4u * i + 1u] == 0u && p[4u * i + 2u] == 255u);
    }
}

/* 1 when a pixel within r of (x, y) differs from mask value at (x, y) */
static int near_edge(const uint8_t *m, int x, int y, int r)
{
    const uint8_t v = m[(size_t)y * W_PX + (size_t)x];
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= (int)W_PX || yy >= (int)H_PX) continue;
            if (m[(size_t)yy * W_PX + (size_t)xx] != v) return 1;
        }
    }
    return 0;
}

/* The cache of the method under test: clipmap's, or pgm's or pgrid's
 * (pgm.heights = clipmap and pgrid.heights = clipmap read the same cache,
 * per vertex, from an atlas). */
static const ft_clip_levels *levels_of(const char *method)
{
    const ft_method *m = &g_app.renderer.method;
    if (strcmp(method, "pgrid") == 0) return &m->u.pgrid.pgm.cl;
    return strcmp(method, "pgm") == 0 ? &m->u.pgm.cl : &m->u.clipmap.cl;
}

/* pgrid over the cache bounds its error per vertex from the cache's cell
 * and block ranges on the GPU (clip_levels.h, FT_CLIP_BOUNDS_RANGES): read
 * back, every cell whose four corners are resident holds its CPU range
 * (ft_clip_cell_range, the unbounded ends as the texture stores them) bit
 * for bit, and every block its block bound widened by its error. Returns
 * the cells compared; counts mismatches into *bad. */
static float g_rb[768u * 768u * 4u];

static void read_texture(const ft_gl *gl, GLuint tex, uint32_t w, uint32_t h)
{
    GLuint fbo = 0u;
    gl->GenFramebuffers(1, &fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    REQUIRE(gl->CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    REQUIRE((size_t)w * h * 4u <= sizeof g_rb / sizeof g_rb[0]);
    gl->ReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_FLOAT, g_rb);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0u);
    gl->DeleteFramebuffers(1, &fbo);
}

static uint64_t ranges_check(const ft_clip_levels *cl, uint64_t *bad)
{
    const ft_gl *gl = g_app.renderer.gl;
    const ft_clip_cache *c = &cl->cache;
    uint64_t cells = 0u;
    read_texture(gl, cl->range_tex, cl->tex_w, cl->tex_h);
    for (uint32_t l = 0; l < cl->levels; ++l) {
        const ft_clip_box *v = &c->level[l].valid;
        for (int64_t b = v->j0; b + 1 < v->j1; ++b) {
            for (int64_t a = v->i0; a + 1 < v->i1; ++a) {
                float lo, hi;
                ft_clip_cell_range(c, l, a, b, &lo, &hi);
                lo = fmaxf(lo, -FT_CLIP_RANGE_UNBOUNDED_M);
                hi = fminf(hi, FT_CLIP_RANGE_UNBOUNDED_M);
                const size_t x = cl->origin_px[l][0] + ft_clip_texel(c, a);
                const size_t y = cl->origin_px[l][1] + ft_clip_texel(c, b);
                const float *t = &g_rb[(y * cl->tex_w + x) * 4u];
                *bad += t[0] != lo || t[1] != hi;
                cells++;
            }
        }
    }
    const uint32_t n = cl->side / FT_CLIP_BOUND_BLOCK;
    read_texture(gl, cl->block_range_tex, cl->tex_w / FT_CLIP_BOUND_BLOCK,
                 cl->tex_h / FT_CLIP_BOUND_BLOCK);
    for (uint32_t l = 0; l < cl->levels; ++l) {
        for (uint32_t k = 0; k < n * n; ++k) {
            const size_t x = cl->origin_px[l][0] / FT_CLIP_BOUND_BLOCK + k % n;
            const size_t y = cl->origin_px[l][1] / FT_CLIP_BOUND_BLOCK + k / n;
            const float *t = &g_rb[(y * (cl->tex_w / FT_CLIP_BOUND_BLOCK) + x) * 4u];
            const double e = c->block_err_m[l][k];
            if (isinf(e)) {
                *bad += t[0] != -FT_CLIP_RANGE_UNBOUNDED_M || t[1] != FT_CLIP_RANGE_UNBOUNDED_M;
            } else {
                *bad += (double)t[0] > (double)c->block_lo_m[l][k] - e ||
                        (double)t[1] < (double)c->block_hi_m[l][k] + e ||
                        (double)t[1] - (double)t[0] >
                            (double)c->block_hi_m[l][k] - (double)c->block_lo_m[l][k] + 2.0 * e +
                                1e-3;
            }
        }
    }
    return cells;
}

static void render(const ft_pose *p)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, p, &cam, &fs);
    CHECK(g_app.renderer.gl_errors == 0u);
}

static void brute_masks(const char *backend, const char *dem)
{
    app_init("brute", backend, dem, "auto", 256u, 5u, 8u);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        render(&p);
        mask_of(g_brute_mask[v]);
    }
    ft_app_shutdown(&g_app);
}

static void coverage(const char *method, const char *backend, const char *dem,
                     const char *format)
{
    static uint8_t mask[W_PX * H_PX];
    app_init(method, backend, dem, format, 256u, 5u, 8u);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        /* twice: the first frame after a jump fills every level */
        render(&p);
        render(&p);
        mask_of(mask);
        uint32_t diff = 0, off = 0, terrain = 0;
        for (int y = 0; y < (int)H_PX; ++y) {
            for (int x = 0; x < (int)W_PX; ++x) {
                const size_t i = (size_t)y * W_PX + (size_t)x;
                terrain += g_brute_mask[v][i];
                if (mask[i] == g_brute_mask[v][i]) continue;
                ++diff;
                off += !near_edge(g_brute_mask[v], x, y, SILHOUETTE_PX);
            }
        }
        printf("%s %s %s view %u: brute terrain %u px, differs on %u px, %u of them "
               "off brute's silhouette (+-%d px)\n",
               method, backend, format, v, terrain, diff, off, SILHOUETTE_PX);
        CHECK(off <= OFF_SILHOUETTE_MAX);
        if (v < FT_TEST_COVERED_VIEWS) CHECK(ft_test_clear_pixels(&g_app) == 0u);
    }
    ft_app_shutdown(&g_app);
}

/* The eye flies across the tile looking down at 50 deg: the terrain covers
 * every frame; few updates a frame make the levels lag. */
static void fly(const char *method, const char *backend, const char *dem, const char *format)
{
    app_init(method, backend, dem, format, 128u, 5u, 2u);
    uint32_t cracked_frames = 0, worst = 0;
    const uint32_t frames = 60u;
    uint64_t range_cells = 0u, range_bad = 0u;
    uint32_t range_checks_lagging = 0u;
    for (uint32_t f = 0; f < frames; ++f) {
        const double t = (double)f / (double)(frames - 1u);
        const ft_pose p = ft_test_pose(42.25 + 0.5 * t, 1.25 + 0.45 * t, 4200.0 - 1500.0 * t,
                                       35.0 + 40.0 * t, -50.0, 0.0);
        render(&p);
        const uint32_t c = ft_test_clear_pixels(&g_app);
        cracked_frames += (c > 0u);
        worst = (c > worst) ? c : worst;
        if (strcmp(method, "pgrid") == 0 && f % 6u == 5u) {
            range_cells += ranges_check(levels_of(method), &range_bad);
            range_checks_lagging += levels_of(method)->cache.stats.levels_behind > 0u;
        }
    }
    if (strcmp(method, "pgrid") == 0) {
        printf("pgrid %s %s cell ranges on the GPU: %llu cells compared in 10 frames (%u with "
               "levels behind), %llu differ from the CPU's\n",
               backend, format, (unsigned long long)range_cells, range_checks_lagging,
               (unsigned long long)range_bad);
        CHECK(range_bad == 0u && range_cells > 100000u && range_checks_lagging >= 3u);
    }
    const ft_clip_stats *cs = &levels_of(method)->cache.stats;
    printf("%s %s %s flight: %u frames, %u with magenta (worst %u px); cache: %llu recentres "
           "moved, %llu updates, levels behind at most %u, %llu samples outstanding at most\n",
           method, backend, format, frames, cracked_frames, worst,
           (unsigned long long)cs->recentres_moved, (unsigned long long)cs->updates,
           cs->levels_behind_max, (unsigned long long)cs->samples_outstanding_max);
    CHECK(cracked_frames == 0u);
    CHECK(cs->recentres_moved >= 10u);
    CHECK(cs->levels_behind_max >= 1u); /* the lagging case was drawn */

    /* hovering at the last pose, the lagging levels catch up */
    const ft_pose last = ft_test_pose(42.75, 1.70, 2700.0, 75.0, -50.0, 0.0);
    uint32_t hover = 0;
    for (; hover < 400u && (hover < 2u || cs->samples_outstanding > 0u); ++hover) {
        render(&last);
        CHECK(ft_test_clear_pixels(&g_app) == 0u);
    }
    printf("%s %s %s hover: current after %u frames (levels behind %u)\n", method, backend,
           format, hover, cs->levels_behind);
    CHECK(cs->samples_outstanding == 0u && cs->levels_behind == 0u);

    /* the counter works: a view above the horizon shows the clear colour */
    const ft_pose sky = ft_test_pose(42.5, 1.5, 3000.0, 0.0, 10.0, 0.0);
    render(&sky);
    CHECK(ft_test_clear_pixels(&g_app) > 1000u);
    ft_app_shutdown(&g_app);
}

/* A jump past every level's box: nothing resident is near the new eye. */
static void jump(const char *method, const char *backend, const char *dem, const char *format)
{
    app_init(method, backend, dem, format, 128u, 3u, 0u);
    const ft_clip_levels *cl = levels_of(method);
    const ft_pose a = ft_test_pose(42.10, 1.20, 4200.0, 35.0, -50.0, 0.0);
    const ft_pose b = ft_test_pose(42.70, 1.65, 4000.0, 75.0, -50.0, 0.0);
    render(&a);
    render(&a);
    CHECK(ft_test_clear_pixels(&g_app) == 0u);
    const int64_t span = (int64_t)cl->side << (cl->levels - 1u); /* level-0 samples */
    const int64_t before_j0 = cl->cache.level[cl->levels - 1u].want.j0 * ((int64_t)1 << (cl->levels - 1u));
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, &b, &cam, &fs);
    const int64_t after_j0 = cl->cache.level[cl->levels - 1u].want.j0 * ((int64_t)1 << (cl->levels - 1u));
    const uint32_t clear = ft_test_clear_pixels(&g_app);
    printf("%s %s %s jump of %lld samples north (the coarsest box spans %lld): the frame ran %u "
           "updates to complete the coarsest level, %u levels behind, %u clear pixels\n",
           method, backend, format, (long long)(after_j0 - before_j0), (long long)span,
           fs.cache_forced_updates, fs.cache_levels_behind, clear);
    CHECK(after_j0 - before_j0 >= span);      /* past every level's box */
    CHECK(fs.cache_forced_updates > 0u);
    CHECK(ft_clip_level_current(&cl->cache, cl->levels - 1u));
    CHECK(fs.cache_levels_behind >= 1u);      /* the finer levels wait for their turn */
    CHECK(clear == 0u);
    ft_app_shutdown(&g_app);
}

/* ---- 3. transform feedback ------------------------------------------------------- */

typedef struct cap_vert {
    float g[2];     /* the mirror's level-0 position */
    float pos[3];   /* captured */
    uint32_t level;
    int inner;      /* a stitch strip's inner vertex */
    int boundary;   /* on a transition side of its level's drawn box */
} cap_vert;

#define CAP_MAX (1u << 20)
static cap_vert g_cap[CAP_MAX];
static size_t g_ncap;

typedef struct cap_ctx {
    const ft_clipmap_method *m;
    const ft_terrain_program *p;
    GLuint tfb;
    float *tmp;
    uint32_t overflow;
} cap_ctx;

static int on_transition_side(const ft_cm_level *lv, uint32_t l, const float g[2])
{
    const float s = ldexpf(1.0f, (int)l);
    const float x0 = (float)lv->box.x0 * s, x1 = (float)lv->box.x1 * s;
    const float y0 = (float)lv->box.y0 * s, y1 = (float)lv->box.y1 * s;
    const int inx = g[0] >= x0 && g[0] <= x1, iny = g[1] >= y0 && g[1] <= y1;
    return (lv->transition[FT_CM_W] && g[0] == x0 && iny) ||
           (lv->transition[FT_CM_E] && g[0] == x1 && iny) ||
           (lv->transition[FT_CM_S] && g[1] == y0 && inx) ||
           (lv->transition[FT_CM_N] && g[1] == y1 && inx);
}

static float no_texel(void *ctx, uint32_t level, int64_t a, int64_t b)
{
    (void)ctx; (void)level; (void)a; (void)b;
    return 0.0f;
}

/* strictly inside the data (a clamped vertex on its edge may lack a partner) */
static int lay_inside_data(const ft_cm_layout *lay, const float g[2])
{
    return g[0] > (float)lay->data_lo[0] && g[0] < (float)lay->data_hi[0] &&
           g[1] > (float)lay->data_lo[1] && g[1] < (float)lay->data_hi[1];
}

static void capture_draw(void *ctx, const ft_cm_draw *d)
{
    cap_ctx *c = ctx;
    const ft_gl *gl = g_app.renderer.gl;
    const GLint *u = c->p->method_u;
    const ft_cm_kind kind = (d->kind == FT_CM_STRIP) ? FT_CM_STRIP : FT_CM_BLOCK;
    const uint32_t n = ft_cm_template_vertex_count(kind);
    const GLint first = (kind == FT_CM_STRIP) ? (GLint)FT_CM_BLOCK_VERTICES : 0;
    if (g_ncap + n > CAP_MAX) {
        c->overflow++;
        return;
    }
    gl->Uniform4f(u[FT_CM_U_PLACE], (float)d->origin[0], (float)d->origin[1], 0.0f, 0.0f);
    gl->Uniform4f(u[FT_CM_U_AXES], (float)d->axis_u[0], (float)d->axis_u[1],
                  (float)d->axis_v[0], (float)d->axis_v[1]);
    gl->Uniform4f(u[FT_CM_U_CLAMP], (float)d->clamp.x0, (float)d->clamp.y0, (float)d->clamp.x1,
                  (float)d->clamp.y1);
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, c->tfb);
    gl->BeginTransformFeedback(GL_POINTS);
    gl->DrawArrays(GL_POINTS, first, (GLsizei)n);
    gl->EndTransformFeedback();
    const void *mapped = gl->MapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0,
                                            (GLsizeiptr)(n * 3u * sizeof(float)), GL_MAP_READ_BIT);
    REQUIRE(mapped != NULL);
    memcpy(c->tmp, mapped, n * 3u * sizeof(float));
    REQUIRE(gl->UnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER) == GL_TRUE);
    ft_cm_uniforms cu;
    ft_cm_uniforms_of(&c->m->layout, d, &cu);
    const ft_cm_level *lv = &c->m->layout.level[d->level];
    for (uint32_t k = 0; k < n; ++k) {
        float t[2];
        ft_cm_vertex_out o;
        ft_cm_template_vertex(kind, k, t);
        ft_cm_vertex(&cu, d->level, t, no_texel, NULL, &o);
        cap_vert *v = &g_cap[g_ncap++];
        v->g[0] = o.g[0];
        v->g[1] = o.g[1];
        memcpy(v->pos, c->tmp + 3u * k, sizeof v->pos);
        v->level = d->level;
        v->inner = (kind == FT_CM_STRIP && t[1] == 0.0f);
        v->boundary = on_transition_side(lv, d->level, o.g);
    }
}

static int cmp_cap(const void *pa, const void *pb)
{
    const cap_vert *a = pa, *b = pb;
    if (a->g[0] != b->g[0]) return a->g[0] < b->g[0] ? -1 : 1;
    if (a->g[1] != b->g[1]) return a->g[1] < b->g[1] ? -1 : 1;
    if (a->level != b->level) return a->level < b->level ? -1 : 1;
    return 0;
}

/* Captures every draw of the method's last frame (its layout and the
 * program's shared uniforms are in place) and checks the boundaries. */
static void capture_and_check(uint32_t *pairs, uint32_t *bad)
{
    const ft_gl *gl = g_app.renderer.gl;
    const ft_clipmap_method *m = &g_app.renderer.method.u.clipmap;
    const ft_terrain_program *p = &g_app.renderer.prog_color;
    static float tmp[FT_CM_BLOCK_VERTICES * 3u];
    cap_ctx c = {m, p, 0u, tmp, 0u};
    gl->UseProgram(p->program);
    gl->GenBuffers(1, &c.tfb);
    gl->BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, c.tfb);
    gl->BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (GLsizeiptr)sizeof tmp, NULL, GL_STREAM_READ);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->EnableVertexAttribArray(FT_ATTRIB_UV);
    gl->VertexAttribPointer(FT_ATTRIB_UV, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->Enable(GL_RASTERIZER_DISCARD);
    g_ncap = 0;
    const ft_cm_layout *lay = &m->layout;
    for (uint32_t l = 0; l < m->cl.levels; ++l) {
        if (!lay->level[l].drawn) continue;
        ft_cm_draw any = {l, FT_CM_BLOCK, {0, 0}, {1, 0}, {0, 1}, {0, 0, 0, 0}, 0u};
        ft_cm_uniforms cu;
        ft_cm_uniforms_of(lay, &any, &cu);
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, m->cl.tex[l]);
        gl->ActiveTexture(GL_TEXTURE2);
        gl->BindTexture(GL_TEXTURE_2D, m->cl.tex[(l + 1u < m->cl.levels) ? l + 1u : l]);
        gl->ActiveTexture(GL_TEXTURE0);
        const GLint *u = p->method_u;
        gl->Uniform4f(u[FT_CM_U_DATA], cu.data[0], cu.data[1], cu.data[2], cu.data[3]);
        gl->Uniform4f(u[FT_CM_U_MBOX], cu.mbox[0], cu.mbox[1], cu.mbox[2], cu.mbox[3]);
        gl->Uniform4f(u[FT_CM_U_LEVEL], cu.level[0], cu.level[1], cu.level[2], (float)m->cl.side);
        (void)ft_cm_level_draws(lay, l, capture_draw, &c);
    }
    gl->Disable(GL_RASTERIZER_DISCARD);
    gl->BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    gl->DeleteBuffers(1, &c.tfb);
    ft_error err;
    REQUIRE(ft_gl_check(gl, "transform feedback capture", &err) == FT_OK);
    CHECK(c.overflow == 0u);
    qsort(g_cap, g_ncap, sizeof g_cap[0], cmp_cap);
    /* runs of one lattice position: fine boundary vs coarse stitch vertices */
    for (size_t i = 0; i < g_ncap;) {
        size_t j = i;
        while (j < g_ncap && g_cap[j].g[0] == g_cap[i].g[0] && g_cap[j].g[1] == g_cap[i].g[1]) ++j;
        for (size_t a = i; a < j; ++a) {
            if (!g_cap[a].inner) continue;
            int partner = 0;
            for (size_t b = i; b < j; ++b) {
                if (g_cap[b].level + 1u != g_cap[a].level || !g_cap[b].boundary) continue;
                partner = 1;
                ++*pairs;
                if (memcmp(g_cap[a].pos, g_cap[b].pos, sizeof g_cap[a].pos) != 0) {
                    if (*bad < 5u) {
                        fprintf(stderr, "stitch (%g, %g): level %u z %.9g, level %u z %.9g\n",
                                (double)g_cap[a].g[0], (double)g_cap[a].g[1], g_cap[b].level,
                                (double)g_cap[b].pos[2], g_cap[a].level, (double)g_cap[a].pos[2]);
                    }
                    ++*bad;
                }
            }
            /* a stitch vertex clamped onto the data's edge may have none */
            if (!partner && lay_inside_data(&m->layout, g_cap[a].g)) {
                if (*bad < 5u) {
                    fprintf(stderr, "stitch vertex (%g, %g) of level %u has no partner\n",
                            (double)g_cap[a].g[0], (double)g_cap[a].g[1], g_cap[a].level);
                }
                ++*bad;
            }
        }
        i = j;
    }
}

static void tf_check(const char *dem)
{
    ft_error err;
    static const char *const varyings[1] = {"v_pos_rel_eye_m"};
    app_init("clipmap", "egl-gles3", dem, "float", 128u, 5u, 2u);
    REQUIRE(ft_renderer_enable_capture_of(&g_app.renderer, varyings, 1u, &err) == FT_OK);
    uint32_t pairs = 0, bad = 0;
    for (uint32_t f = 0; f < 12u; ++f) {
        const double t = (double)f / 11.0;
        const ft_pose p = ft_test_pose(42.25 + 0.4 * t, 1.25 + 0.4 * t, 4000.0, 40.0, -50.0, 0.0);
        render(&p);
        if (f % 3u == 2u) capture_and_check(&pairs, &bad);
    }
    printf("transform feedback: %u boundary vertex pairs compared, %u differ or lack a partner\n",
           pairs, bad);
    CHECK(pairs > 1000u);
    CHECK(bad == 0u);
    ft_app_shutdown(&g_app);
}

/* 4. The reported bound (es3, the metric on): clipmap bounds what it drew
 * from the cache's per-block errors against the terrain (clipmap.h); over
 * a .hgt every level's deviation is known, so a frame has a finite bound
 * unless a lagging cache leaves a coarse cell holding the eye, and the
 * measured error keeps it (+ BOUND_SLACK_PX, the metric's rounding) on the
 * coverage views, along a flight whose levels lag (few updates a frame,
 * so morphs and partly resident levels are drawn) and on low views 60-300
 * m above the ground once the cache has caught up there. */
#define BOUND_SLACK_PX 0.05

typedef struct bound_tally {
    uint32_t frames, infinite, infinite_current, over;
    double ratio_min, ratio_max, err_max, bound_max;
    /* pgrid ray casting: frames whose bound is gamma (1 px), that ray cast,
     * and the largest leaf bound (pgrid.h 7) */
    uint32_t at_gamma, ray_cast;
    double leaf_max;
} bound_tally;

static ft_camera g_bound_cam; /* the last bound frame's */

static void bound_frame(const ft_pose *p, bound_tally *t)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_error_stats es;
    ft_test_frame(&g_app, p, &cam, &fs);
    ft_test_measure(&g_app, &cam, &es);
    CHECK(g_app.renderer.gl_errors == 0u);
    g_bound_cam = cam;
    const double b = fs.tau_achieved_px;
    t->frames += 1u;
    if (g_app.renderer.method.kind == FT_METHOD_PGRID) {
        const ft_pgrid_method *pg = &g_app.renderer.method.u.pgrid;
        t->at_gamma += (b <= 1.0);
        t->ray_cast += (pg->thr < FT_PGRID_CODES);
        t->leaf_max = fmax(t->leaf_max, pg->leaf_px);
    }
    if (!isfinite(b)) {
        if (g_app.renderer.method.kind == FT_METHOD_CLIPMAP) {
            const ft_cm_bound *cb = &g_app.renderer.method.u.clipmap.bound;
            printf("  no bound: %.4f N %.4f E %.0f m heading %.0f pitch %.0f: %llu pieces, %llu "
                   "unbounded, %u bounded cell by cell, worst level %u\n",
                   p->lat_deg, p->lon_deg, p->alt_m, p->heading_deg, p->pitch_deg,
                   (unsigned long long)cb->pieces, (unsigned long long)cb->unbounded,
                   cb->refined, cb->worst_level);
        } else {
            printf("  no bound: %.4f N %.4f E %.0f m heading %.0f pitch %.0f (measured %.3f "
                   "px)\n",
                   p->lat_deg, p->lon_deg, p->alt_m, p->heading_deg, p->pitch_deg, es.max_px);
        }
        t->infinite += 1u;
        /* a level behind may leave a coarse cell holding the eye (no bound);
         * a current cache over a .hgt never does at these heights */
        t->infinite_current += fs.cache_levels_behind == 0u;
        return;
    }
    /* the metric scores a pixel a sub-pixel shift flips at 0.5 px */
    const double allowed = fmax(b, FT_METRIC_FLIP_PX) + BOUND_SLACK_PX;
    t->over += es.max_px > allowed;
    if (es.max_px > allowed) {
        printf("  over: %.4f N %.4f E %.0f m heading %.0f pitch %.0f: measured %.3f px, bound "
               "%.3f px\n",
               p->lat_deg, p->lon_deg, p->alt_m, p->heading_deg, p->pitch_deg, es.max_px, b);
    }
    const double r = b / fmax(es.max_px, 1e-6);
    t->ratio_min = fmin(t->ratio_min, r);
    t->ratio_max = fmax(t->ratio_max, r);
    t->err_max = fmax(t->err_max, es.max_px);
    t->bound_max = fmax(t->bound_max, b);
}

/* The frames a reported bound is held on, for the method under test (its
 * cache: levels_of(method)): the coverage views; a flight whose levels lag
 * (few updates a frame, so morphs and partly resident levels are drawn);
 * and the first low_views low views 60-300 m above the ground, each once
 * the cache has caught up there, as a display hovering there would.
 * Returns the low views whose cache was still behind. */
static uint32_t bound_frames(const char *method, uint32_t low_views, bound_tally *t)
{
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        bound_frame(&p, t);
    }
    const uint32_t frames = 24u;
    for (uint32_t f = 0; f < frames; ++f) {
        const double s = (double)f / (double)(frames - 1u);
        const ft_pose p = ft_test_pose(42.25 + 0.5 * s, 1.25 + 0.45 * s, 4200.0 - 1500.0 * s,
                                       35.0 + 40.0 * s, -50.0 + 40.0 * s, 0.0);
        bound_frame(&p, t);
    }
    const ft_terrain *tr = &g_app.terrain;
    static const double k_low[4][4] = {
        {42.55, 1.50, 60.0, 45.0},   /* over a valley floor, level */
        {42.60, 1.60, 120.0, 200.0}, /* towards the ridges */
        {42.40, 1.40, 300.0, 315.0},
        {42.70, 1.80, 80.0, 90.0},
    };
    const ft_clip_stats *cs = &levels_of(method)->cache.stats;
    uint32_t behind = 0u;
    for (uint32_t k = 0; k < low_views && k < 4u; ++k) {
        double x = 0.0, y = 0.0;
        ft_terrain_geo_to_world(tr, k_low[k][0], k_low[k][1], &x, &y);
        const double ground = ft_terrain_height_at(tr, x, y);
        const ft_pose p = ft_test_pose(k_low[k][0], k_low[k][1], ground + k_low[k][2],
                                       k_low[k][3], -8.0, 0.0);
        for (uint32_t f = 0; f < 400u && (f < 2u || cs->samples_outstanding > 0u); ++f) {
            render(&p);
        }
        behind += cs->levels_behind != 0u;
        bound_frame(&p, t);
    }
    return behind;
}

static void bound_check(const char *dem)
{
    app_init_metric("clipmap", "egl-gles3", dem, "float", 128u, 5u, 2u, 1);
    bound_tally t = {0u, 0u, 0u, 0u, INFINITY, 0.0, 0.0, 0.0, 0u, 0u, 0.0};
    CHECK(bound_frames("clipmap", 4u, &t) == 0u);
    const ft_terrain *tr = &g_app.terrain;
    const uint32_t frames = 24u;
    const ft_clipmap_method *cm = &g_app.renderer.method.u.clipmap;
    /* what the bound costs a frame (printed, not asserted): the last view
     * again, 200 times */
    {
        const ft_clip_world w = ft_clip_levels_world(tr);
        const double origin_m[2] = {w.origin_x_m, w.origin_y_m};
        ft_view_bound vb;
        ft_view_bound_from_camera(&g_bound_cam, origin_m, tr->curv_drop_per_m2, &vb);
        ft_cm_bound again;
        const uint64_t t0 = ft_plat_monotonic_ns();
        for (int k = 0; k < 200; ++k) {
            ft_cm_frame_bound(&cm->layout, &cm->cl.cache, &w, &vb, 0.0, tr->min_height_m,
                              tr->max_height_m, &again);
        }
        const double us = (double)(ft_plat_monotonic_ns() - t0) * 1e-3 / 200.0;
        printf("clipmap bound of the last view: %.1f us a frame (%llu pieces, %u bounded "
               "cell by cell; side 128, 5 levels)\n",
               us, (unsigned long long)again.pieces, again.refined);
        CHECK(again.bound_px == cm->bound.bound_px); /* the same inputs, the same bound */
    }
    printf("clipmap bound: %u frames, %u without a bound (%u of them with the cache "
           "current), %u over it; measured max %.3f px, bound max %.3f px, bound / measured "
           "%.2f .. %.2f; last frame %llu pieces, %u bounded cell by cell\n",
           t.frames, t.infinite, t.infinite_current, t.over, t.err_max, t.bound_max,
           t.ratio_min, t.ratio_max, (unsigned long long)cm->bound.pieces, cm->bound.refined);
    CHECK(t.over == 0u);
    CHECK(t.infinite_current == 0u);
    CHECK(t.frames - t.infinite >= VIEWS + frames / 2u + 4u);
    CHECK(t.frames == VIEWS + frames + 4u);
    ft_app_shutdown(&g_app);
}

/* pgrid over the cache refuses a GLES 2 context, naming it: its cell ranges
 * are float RG textures. */
static void pgrid_refusals(const char *backend, const char *dem, int es3)
{
    if (es3) {
        return;
    }
    static ft_scene sc;
    ft_error err;
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, "pgrid", backend, W_PX, H_PX, dem,
                   "float", 0, "relief", 0, 128u, 5u, 2u);
    ft_scene_defaults(&sc);
    REQUIRE(ft_scene_parse(&sc, g_text, "refusals", &err) == FT_OK);
    const ft_status st = ft_app_init(&g_app, &sc, &err);
    printf("pgrid over the cache on GLES 2: \"%s\"\n", err.text);
    CHECK(st == FT_ERR_UNSUPPORTED && strstr(err.text, "need GLES 3") != NULL);
}

/* 5. pgrid over the cache (es3, the metric on) reports the bound its mesh
 * achieved, from the cache's cell and block ranges of the finest data
 * (pgrid.h, shaders/pgrid.vert.glsl): on the same views, flight and low
 * views as clipmap's, the measured error keeps it on every frame that has
 * one, and over a .hgt (every deviation known) most frames have one (the
 * codes saturate at 256 px: a relief bound that large is reported as none). */
static void pgrid_bound_check(const char *dem)
{
    app_init_metric("pgrid", "egl-gles3", dem, "float", 128u, 5u, 2u, 1);
    bound_tally t = {0u, 0u, 0u, 0u, INFINITY, 0.0, 0.0, 0.0, 0u, 0u, 0.0};
    (void)bound_frames("pgrid", 3u, &t);
    printf("pgrid over the cache, bound: %u frames, %u without a bound, %u over it; measured "
           "max %.3f px, bound max %.3f px, bound / measured %.2f .. %.2f\n",
           t.frames, t.infinite, t.over, t.err_max, t.bound_max, t.ratio_min, t.ratio_max);
    CHECK(t.over == 0u);
    /* not vacuous: most frames have a bound (a frame's is infinite only when
     * it saturates the error codes, over 256 px somewhere) */
    CHECK(t.infinite * 4u <= t.frames);
    ft_app_shutdown(&g_app);
}

/* The share of the terrain pixels pgrid ray casts on the fixed views: each
 * view drawn twice, since the count a frame reports is the previous
 * frame's (the late decision, src/lod/pgrid.h 5). */
static double rc_share(void)
{
    uint64_t rc = 0u, terrain = 0u;
    const ft_pgrid_method *pg = &g_app.renderer.method.u.pgrid;
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        render(&p);
        render(&p);
        rc += pg->rc_px;
        terrain += pg->terrain_px;
    }
    return (double)rc / (double)(terrain > 0u ? terrain : 1u);
}

/* 6. pgrid over the cache with ray casting (src/lod/pgrid.h 7): the pixels
 * whose code passes gamma (1 px) are ray cast through the cache's levels,
 * exact where level 0 holds them and within the level's deviation past
 * it, and the frame reports max(gamma, the leaves' bound). On the same
 * views, flight and low views: every frame ray casts and has a bound (the
 * relief mesh alone had none on a third of them: its codes saturate), and
 * the measured error keeps it. Looking steeply down once the cache has
 * caught up, every ray ends in level 0: the frame reports gamma itself and
 * the measured error keeps it. */
static void pgrid_rc_bound_check(const char *dem)
{
    g_ray_casting = 1;
    app_init_metric("pgrid", "egl-gles3", dem, "float", 128u, 5u, 2u, 1);
    bound_tally t = {0u, 0u, 0u, 0u, INFINITY, 0.0, 0.0, 0.0, 0u, 0u, 0.0};
    (void)bound_frames("pgrid", 3u, &t);
    printf("pgrid over the cache, ray casting at gamma 1: %u frames, %u ray cast, %u at gamma, "
           "%u without a bound, %u over it; measured max %.3f px, bound max %.3f px, bound / "
           "measured %.2f .. %.2f\n",
           t.frames, t.ray_cast, t.at_gamma, t.infinite, t.over, t.err_max, t.bound_max,
           t.ratio_min, t.ratio_max);
    CHECK(t.over == 0u);
    CHECK(t.infinite == 0u);
    CHECK(t.ray_cast == t.frames);
    printf("pgrid over the cache, relief bound: %.1f%% of the terrain pixels ray cast on the "
           "fixed views\n", 100.0 * rc_share());
    /* steeply down over the middle of the tile, 1500-2500 m up: the view
     * stays inside level 0's 128 samples */
    static const double k_steep[3][5] = {
        {42.50, 1.50, 1500.0, 30.0, -80.0},
        {42.45, 1.55, 2000.0, 200.0, -70.0},
        {42.55, 1.45, 2500.0, 300.0, -85.0},
    };
    const ft_terrain *tr = &g_app.terrain;
    const ft_clip_stats *cs = &levels_of("pgrid")->cache.stats;
    bound_tally steep = {0u, 0u, 0u, 0u, INFINITY, 0.0, 0.0, 0.0, 0u, 0u, 0.0};
    for (uint32_t k = 0; k < 3u; ++k) {
        double x = 0.0, y = 0.0;
        ft_terrain_geo_to_world(tr, k_steep[k][0], k_steep[k][1], &x, &y);
        const ft_pose p = ft_test_pose(k_steep[k][0], k_steep[k][1],
                                       ft_terrain_height_at(tr, x, y) + k_steep[k][2],
                                       k_steep[k][3], k_steep[k][4], 0.0);
        for (uint32_t f = 0; f < 400u && (f < 2u || cs->samples_outstanding > 0u); ++f) {
            render(&p);
        }
        bound_frame(&p, &steep);
    }
    printf("pgrid over the cache, ray casting, steep views: %u frames, %u at gamma, %u ray "
           "cast, %u over it; measured max %.3f px, leaves' bound max %.3f px\n",
           steep.frames, steep.at_gamma, steep.ray_cast, steep.over, steep.err_max,
           steep.leaf_max);
    CHECK(steep.at_gamma == steep.frames);
    CHECK(steep.ray_cast == steep.frames);
    CHECK(steep.over == 0u);
    /* what the leaves' bound costs a frame (printed, not asserted): the last
     * view again, 200 times */
    {
        const ft_pgrid_method *pg = &g_app.renderer.method.u.pgrid;
        const ft_clip_world w = ft_clip_levels_world(tr);
        const uint64_t t0 = ft_plat_monotonic_ns();
        double again = 0.0;
        for (int k = 0; k < 200; ++k) {
            again = ft_pgrid_cache_leaf_bound_px(&pg->pgm.cl.cache, &pg->pgm.clip_view, &w,
                                                 &g_bound_cam, tr->curv_drop_per_m2,
                                                 (double)tr->max_height_m, 1.0);
        }
        const double us = (double)(ft_plat_monotonic_ns() - t0) * 1e-3 / 200.0;
        printf("pgrid leaves' bound of the last view: %.1f us a frame (side 128, 5 levels)\n",
               us);
        CHECK(again == pg->leaf_px); /* the same inputs, the same bound */
    }
    ft_app_shutdown(&g_app);
    g_ray_casting = 0;
}

/* 7. pgrid over the cache with the tight bound (src/lod/pgrid.h 6): every
 * quad bounded on the cache's level where it fits 4 x 4 cells, exactly
 * against that level's surface plus the level's deviation from the finest
 * data. (a) Every quad's bound, read back, is at least |drawn - truth| at
 * 15 points of each of its triangles, the truth being the .hgt's bilinear
 * surface (the cache's finest data), on the fixed views. (b) The frames of
 * the bound check keep their reported bound as measured by the metric, and
 * every frame has one. (c) At most 30% of the terrain pixels are ray cast
 * on the fixed views (the relief bound casts nearly all). Side 512: at 128
 * the deviation of the levels past level 0's 128 samples is over gamma on
 * most of the view, and so is the mesh's bound there. */
#define TIGHT_COLS 200u /* pgrid.grid_cols, the scene's default */
#define TIGHT_ROWS 800u
static float g_tvtx[4u * TIGHT_COLS * TIGHT_ROWS];
static float g_tquad[4u * TIGHT_COLS * TIGHT_ROWS];

typedef struct quad_truth {
    uint32_t quads, unbounded, under;
    uint32_t relief; /* bounded by the relief rule: no level holds them in 4 x 4 cells */
    double worst_over_m; /* largest measured - bound (<= 0: held) */
    double ratio_sum;    /* sum over bounded quads of measured / bound */
} quad_truth;

static void quad_truth_frame(const ft_camera *cam, quad_truth *q)
{
    const ft_pgrid_method *m = &g_app.renderer.method.u.pgrid;
    const ft_gl *gl = &g_app.gpu.gl;
    const ft_terrain *t = &g_app.terrain;
    const uint32_t cols = m->pgm.cols, rows = m->pgm.rows;
    REQUIRE(cols <= TIGHT_COLS && rows <= TIGHT_ROWS);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->vtx_fbo);
    gl->ReadPixels(0, 0, (GLsizei)cols, (GLsizei)rows, GL_RGBA, GL_FLOAT, g_tvtx);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->quad_fbo);
    gl->ReadPixels(0, 0, (GLsizei)(cols - 1u), (GLsizei)(rows - 1u), GL_RGBA, GL_FLOAT, g_tquad);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    CHECK(ft_gl_check(gl, "reading the tight passes back", NULL) == FT_OK);
    static const int k_tri[2][3] = {{0, 1, 3}, {0, 3, 2}}; /* the grid's order */
    for (uint32_t j = 0; j + 1u < rows; ++j) {
        for (uint32_t i = 0; i + 1u < cols; ++i) {
            const double e = (double)g_tquad[4u * (j * (cols - 1u) + i)];
            q->quads += 1u;
            q->relief += g_tquad[4u * (j * (cols - 1u) + i) + 1u] < 0.0f; /* G: the level */
            if (!(e < 1e29)) {
                q->unbounded += 1u;
                continue;
            }
            const float *v[4];
            for (int c = 0; c < 4; ++c) {
                v[c] = g_tvtx + 4u * ((j + (uint32_t)(c / 2)) * cols + i + (uint32_t)(c % 2));
            }
            double worst = 0.0;
            for (int tri = 0; tri < 2; ++tri) {
                for (int a = 0; a <= 4; ++a) {
                    for (int b = 0; a + b <= 4; ++b) {
                        const double w[3] = {a / 4.0, b / 4.0, (4 - a - b) / 4.0};
                        double x = cam->eye_m[0], y = cam->eye_m[1], l = 0.0;
                        for (int k = 0; k < 3; ++k) {
                            const float *c = v[k_tri[tri][k]];
                            x += w[k] * c[0];
                            y += w[k] * c[1];
                            l += w[k] * c[2];
                        }
                        worst = fmax(worst, fabs(l - ft_terrain_height_at(t, x, y)));
                    }
                }
            }
            /* 1 mm: the float positions the vertex pass wrote */
            if (worst > e + 1e-3) {
                if (q->under < 5u) {
                    printf("  quad (%u, %u): bound %.4f m, measured %.4f m\n", i, j, e, worst);
                }
                q->under += 1u;
            }
            q->worst_over_m = fmax(q->worst_over_m, worst - e);
            q->ratio_sum += worst / fmax(e, 1e-6);
        }
    }
}

static void pgrid_tight_check(const char *dem)
{
    g_ray_casting = 1;
    g_error_bound = "residual";
    app_init_metric("pgrid", "egl-gles3", dem, "float", 512u, 5u, 2u, 1);
    REQUIRE(g_app.renderer.method.u.pgrid.tight);
    quad_truth q = {0u, 0u, 0u, 0u, -INFINITY, 0.0};
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose p = view_of(v);
        ft_camera cam;
        ft_frame_stats fs;
        ft_test_frame(&g_app, &p, &cam, &fs);
        quad_truth_frame(&cam, &q);
    }
    const uint32_t bounded = q.quads - q.unbounded;
    printf("pgrid over the cache, tight bound vs the truth: %u quads, %u unbounded, %u by the "
           "relief rule, %u under the truth (largest measured - bound %.4f m), measured / "
           "bound %.3f on the mean quad\n", q.quads, q.unbounded, q.relief, q.under,
           q.worst_over_m, q.ratio_sum / (double)(bounded > 0u ? bounded : 1u));
    CHECK(q.under == 0u);
    CHECK(q.unbounded == 0u); /* over a .hgt every deviation is known */
    CHECK(q.quads > 100000u);
    CHECK(q.relief * 100u < q.quads); /* the exact rule bounds nearly all of them */
    bound_tally t = {0u, 0u, 0u, 0u, INFINITY, 0.0, 0.0, 0.0, 0u, 0u, 0.0};
    (void)bound_frames("pgrid", 3u, &t);
    printf("pgrid over the cache, tight bound, ray casting at gamma 1: %u frames, %u ray cast, "
           "%u at gamma, %u without a bound, %u over it; measured max %.3f px, bound max %.3f "
           "px\n", t.frames, t.ray_cast, t.at_gamma, t.infinite, t.over, t.err_max, t.bound_max);
    CHECK(t.over == 0u);
    CHECK(t.infinite == 0u);
    const double share = rc_share();
    printf("pgrid over the cache, tight bound: %.1f%% of the terrain pixels ray cast on the "
           "fixed views\n", 100.0 * share);
    /* the relief bound casts nearly all of them (pgrid_rc_bound_check);
     * measured 22.6% */
    CHECK(share <= 0.30);
    ft_app_shutdown(&g_app);
    g_ray_casting = 0;
    g_error_bound = "relief";
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_clipmap_gl es3|es2 DEM\n");
        return 2;
    }
    if (!ft_test_have_data(argv[2])) return FT_TEST_SKIP;
    const int es3 = strcmp(argv[1], "es3") == 0;
    const char *backend = es3 ? "egl-gles3" : "egl-gles2";
    pgrid_refusals(backend, argv[2], es3);
    brute_masks(backend, argv[2]);
    /* pgrid over the cache: GLES 3 only (its cell ranges are float RG) */
    static const char *const k_methods[] = {"clipmap", "pgm", "pgrid"};
    for (uint32_t k = 0; k < (es3 ? 3u : 2u); ++k) {
        coverage(k_methods[k], backend, argv[2], "float");
        fly(k_methods[k], backend, argv[2], "float");
        jump(k_methods[k], backend, argv[2], "float");
        if (!es3) {
            coverage(k_methods[k], backend, argv[2], "packed");
            fly(k_methods[k], backend, argv[2], "packed");
            jump(k_methods[k], backend, argv[2], "packed");
        }
    }
    if (es3) {
        tf_check(argv[2]);
        bound_check(argv[2]);
        pgrid_bound_check(argv[2]);
        pgrid_rc_bound_check(argv[2]);
        pgrid_tight_check(argv[2]);
    }
    return ft_test_result(es3 ? "test_clipmap_gl es3" : "test_clipmap_gl es2");
}
