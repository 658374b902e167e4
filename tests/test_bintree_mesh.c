/* test_bintree_mesh.c - the CPU mirror of the bintree vertex shader
 * (src/lod/bintree_mesh.h) against the real shader, and the bench's oracle
 * (tools/bench_oracle.h) against the real frame, on a real DEM (argv[1],
 * N42E001.hgt: 1201 x 1201, so the padding clamp is exercised too).
 *
 * 1. Per view (GLES 3): after the real frame, the colour program relinked
 *    with transform feedback of v_pos_rel_eye_m, v_normal, v_height_m and
 *    v_morph draws the frame's tiles once more (the template expanded to
 *    triangle lists); every captured vertex is compared with the mirror's
 *    vertex for the same (tile, template vertex):
 *      position  |gpu - cpu| <= 1e-3 * max(|cpu|, 1 m) (relative to the
 *                distance from the eye), and, much tighter,
 *                |gpu - cpu| <= POS_TOL * (|origin - eye| + |(g * cell, h)|):
 *                float rounding of the shader's sum, whose terms are up to
 *                about 1e5 m on this grid (about 0.01 m), not of the result
 *                (which may be a few hundred metres from the eye)
 *      normal    each component within NORMAL_TOL
 *      height    within HEIGHT_REL_TOL * max(|h|, 1 m), plus the weight's
 *                float error times the height a unit of weight moves
 *      morph     weight within MORPH_TOL plus its float error: 2 dQ / W,
 *                dQ = Q_ULPS ulps of the size of Q's operands (Q is a
 *                difference of distances over the diamond's box, W the
 *                morph width: metres below the samples)
 *    The GPU computes in float, the mirror in double; the tolerances are a
 *    few times the float rounding measured here (printed), far below what a
 *    wrong rule moves a vertex. Triangle counts: the mirror's (tiles x
 *    template, from its own index list), the frame's reported count and the
 *    primitives the GPU wrote (query) must be equal, and the capture must
 *    have written exactly that many vertices.
 *    Configurations with bintree.subsample_levels S > 0 (tile coordinates
 *    in fine units) check the sub-sample path the same way: vertices
 *    between samples (bilinear height, normal and morph endpoints of their
 *    cell) and the closed-form errors of the diamonds inserting them; one
 *    view looks along the grid's last sample row, where the cell is clamped.
 *    Every morphing vertex's error must also equal its diamond's error in
 *    the selection (ft_bt_diamond_error: the table, or the closed form over
 *    the whole closure, which the shader reads from <= 4 atlas texels).
 * 2. The test can fail: the same captures against a mirror with the wrong
 *    morph rule (geomorph off where the method morphs) must show position
 *    mismatches, and the views must catch vertices mid-morph (0 < w < 1),
 *    or they would not exercise the geomorph; with S > 0 many of them
 *    between samples. Where the method does not morph, the mirror with the
 *    geomorph must give the same mesh (a diamond splits only where its
 *    vertices would be at their own heights).
 * 3. The oracle frame (the mirror's mesh, trivial vertex shader, the same
 *    fragment shader and target) against the real frame: almost every
 *    pixel equal (differences only where float rounding moves a triangle
 *    edge across a pixel centre), and more than half of the real frame's
 *    pixels terrain (not the clear colour).
 * 4. The bintree over the clipmap cache (bintree.heights = clipmap,
 *    k = 3, tau = 1, no geomorph, no sub-sample levels; clipmap.side 256):
 *    the same views, the captures of shaders/bintree_clip.vert.glsl against
 *    ft_btc_mesh_build (its mirror, the oracle's over the cache) for the
 *    frame's tiles, with float texels and again with packed ones
 *    (gpu.height_format = packed: 24-bit fixed point, which the mirror's
 *    float copy of the levels differs from by up to half a step), then the
 *    oracle frame as in 3 (view_cache). The views must read level 0 and
 *    coarser levels and reach past the data box (the shader's clamp); a
 *    mirror reading the wrong levels must mismatch.
 *
 * Usage: test_bintree_mesh DEM */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "bench_oracle.h"
#include "lod/bintree_mesh.h"
#include "lod/bintree_template.h"
#include "test_app_util.h"

#define POS_REL_TOL 1e-3 /* of the distance from the eye */
#define POS_TOL 1e-6     /* of the magnitude of the shader's float operands */
#define NORMAL_TOL 1e-5
#define HEIGHT_REL_TOL 1e-6
#define MORPH_TOL 1e-4
/* the shader's Q (a float difference of distances) within this many ulps of
 * its operands' size */
#define Q_ULPS 16.0
#define CAP_FLOATS 8u /* v_pos_rel_eye_m (3), v_normal (3), v_height_m, v_morph */
/* over the cache with packed texels (24-bit fixed point over the cache's
 * range): heights within this many steps of range / (2^24 - 1) (half a step
 * of rounding on upload, a few ulps of the range in the float decode) */
#define PACKED_STEPS 4.0
/* oracle image: pixels whose colour differs from the real frame's by more
 * than PIXEL_DIFF in a channel, at most this fraction of the image */
#define PIXEL_DIFF 2
#define PIXEL_FRACTION_MAX 0.002

static ft_app g_app;
static char g_text[4096];

static const char k_scene_fmt[] =
    "[scene]\nmethod = bintree\nbackend = egl-gles3\n"
    "[view]\nwidth_px = %u\nheight_px = %u\nfovy_deg = 60\n"
    "[terrain]\ndem = %s\n"
    "[gpu]\ntexture_bytes = 64M\n[metric]\nenabled = 0\n"
    "[bintree]\ntemplate_k = %u\nsubsample_levels = %u\ntiles_max = 65536\ntau_px = %.3f\n"
    "morph = %d\nmorph_width = %.4f\n"
    "[budget]\nheights_bytes = 6M\npyramids_bytes = 18M\ndem_io_bytes = 2M\n"
    "frame_rgba_bytes = 1M\nframe_pos_bytes = 1M\nreference_bytes = 1M\nmetric_bytes = 1M\n"
    "gpu_staging_bytes = 8M\nmethod_bytes = 32M\npng_bytes = 512K\n%s";

typedef struct totals {
    uint64_t vertices, midmorph, triangles;
    double pos_abs_max, pos_rel_max, pos_op_max, normal_max, height_rel_max, morph_max;
    uint64_t pos_rel_bad, pos_bad, normal_bad, height_bad, morph_bad, unwritten, overrun;
    uint64_t wrong_rule_bad; /* position mismatches against the wrong morph rule */
    uint64_t between, between_midmorph; /* vertices between samples (S > 0), mid-morph */
    uint64_t closed_form;  /* morphing vertices whose diamond error is the closed form */
    uint64_t err_checked, err_bad; /* mirror's morph error vs the selection's diamond error */
    uint64_t oracle_px, oracle_diff_px, oracle_terrain_px;
    /* over the cache (view_cache) */
    double height_abs_max;
    uint64_t clamped;         /* vertices the shader clamps into the data box */
    uint64_t wrong_level_bad; /* mismatches against a mirror reading the wrong levels */
    uint64_t level_vertices[FT_CLIP_LEVELS_MAX]; /* by the cache level they read */
} totals;

static double len3(const double *v)
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static double dist3(const float *gpu, const double *cpu)
{
    const double d[3] = {gpu[0] - cpu[0], gpu[1] - cpu[1], gpu[2] - cpu[2]};
    return len3(d);
}

/* |u_origin_rel_eye_m| + |(gs * cell, h)|: the size of the terms the shader
 * adds in float for template vertex (a, b) of tile, gs (grid units) as the
 * shader clamps it */
static double operand_scale(const ft_bintree *bt, const ft_bt_mesh_uniforms *u,
                            const ft_bt_tile *tile, double a, double b, double h)
{
    const double f = (double)(1u << bt->sub);
    const double size[2] = {(double)bt->width, (double)bt->height};
    double q[3] = {0.0, 0.0, h};
    for (int i = 0; i < 2; ++i) {
        double g = tile->apex[i] + a * (tile->left[i] - tile->apex[i]) +
                   b * (tile->right[i] - tile->apex[i]);
        g = fmin(g, (size[i] - 1.0) * f);
        q[i] = g / f * u->cell_m[i];
    }
    return len3(u->origin_rel_eye_m) + len3(q);
}

/* The selection's error of the diamond that inserts template vertex (a, b)
 * of tile (ft_bt_diamond_error at that diamond's level), or -1 when the
 * vertex never morphs. The level from the diamond's square side sd = 2 s 2^k
 * (s the vertex's lowest set bit): even when the vertex is a square's
 * centre, sd = fine_side >> (level / 2). */
static double selection_error(const ft_bintree *bt, const ft_bt_tile *tile, double a, double b)
{
    int32_t g[2], e0[2], e1[2], c[2];
    uint32_t level = 0;
    for (int i = 0; i < 2; ++i) {
        g[i] = (int32_t)(tile->apex[i] + a * (tile->left[i] - tile->apex[i]) +
                         b * (tile->right[i] - tile->apex[i]));
    }
    if (!ft_bt_vertex_morph(bt, g[0], g[1], e0, e1, c, &level)) {
        return -1.0;
    }
    const int32_t s = (g[0] | g[1]) & -(g[0] | g[1]);
    const int even = ((g[0] / s) & 1) != 0 && ((g[1] / s) & 1) != 0;
    const uint32_t sd = 2u * (uint32_t)s * bt->step;
    uint32_t half = 0; /* level / 2 */
    while ((bt->fine_side >> half) > sd) {
        ++half;
    }
    REQUIRE((bt->fine_side >> half) == sd);
    float box[FT_BT_BOX_FLOATS];
    return ft_bt_diamond_error(bt, 2u * half + (even ? 0u : 1u), c, box);
}

/* Captures the frame's vertices: tiles x expanded template, CAP_FLOATS each,
 * into cap (verts + slack vertices, NaN-filled first). Returns the
 * primitives the GPU reports written (or the expected count when the
 * context has no queries). */
static uint64_t capture(GLuint tmpl_vbo, uint32_t tmpl_verts, size_t verts, size_t slack,
                        float *cap)
{
    const ft_gl *gl = g_app.renderer.gl;
    const size_t bytes = (verts + slack) * CAP_FLOATS * sizeof(float);
    memset(cap, 0xff, bytes); /* NaN: a vertex the capture did not write stays NaN */
    GLuint tfb = 0;
    gl->GenBuffers(1, &tfb);
    gl->BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
    gl->BufferData(GL_TRANSFORM_FEEDBACK_BUFFER, (GLsizeiptr)bytes, cap, GL_STREAM_READ);
    const uint64_t prims =
        ft_test_bintree_capture(&g_app, tfb, bytes, tmpl_vbo, tmpl_verts, CAP_FLOATS);
    gl->BindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, tfb);
    const void *mapped =
        gl->MapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, (GLsizeiptr)bytes, GL_MAP_READ_BIT);
    REQUIRE(mapped != NULL);
    memcpy(cap, mapped, bytes);
    REQUIRE(gl->UnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER) == GL_TRUE);
    gl->DeleteBuffers(1, &tfb);
    ft_error err;
    REQUIRE(ft_gl_check(gl, "transform feedback capture", &err) == FT_OK);
    return prims;
}

/* The views, each config's (poses: lat, lon, alt m, heading, pitch, roll) */
#define VIEWS 7u
static ft_pose view_pose(uint32_t i)
{
    static const double v[VIEWS][6] = {
        {42.50, 1.50, 3600.0, 0.0, -20.0, 0.0},
        {42.40, 1.30, 3300.0, 135.0, -8.0, 5.0},
        {42.55, 1.65, 5000.0, 250.0, -45.0, 0.0},
        {42.20, 1.10, 2400.0, 60.0, -12.0, -20.0},
        {42.50, 1.50, 9000.0, 0.0, -90.0, 0.0},
        {42.02, 1.97, 3000.0, 225.0, -15.0, 0.0}, /* near the grid corner */
        /* low, over the last sample row, looking east along it to the far
         * corner and the padding: sub-sample vertices on the last row and
         * column (their cell is clamped to size - 2). Not lower: the morph
         * weight's float rounding grows as the vertices near the eye (the
         * shader's distance is a difference of ~1e5 m operands); here it is
         * under half of MORPH_TOL */
        {42.998, 1.98, 900.0, 80.0, -35.0, 0.0},
    };
    const double *a = v[i % VIEWS];
    return ft_test_pose(a[0], a[1], a[2], a[3], a[4], a[5]);
}

typedef struct tmpl {
    uint32_t nv, nt;
    float *uv;     /* nv x (a, b) */
    uint16_t *idx; /* 3 nt */
    GLuint flat_vbo; /* the template expanded to triangle lists */
} tmpl;

/* The oracle frame (tools/bench_oracle.h: the mirror's mesh of the last
 * frame's tiles) against the real frame in the renderer's image: adds the
 * pixels, those differing by more than PIXEL_DIFF in a channel and the
 * terrain pixels (not the clear colour) of the real one to tot; returns the
 * differing pixels, *ms the oracle frame's time. */
static uint64_t oracle_compare(bench_oracle *oracle, const ft_camera *cam, uint32_t tiles,
                               size_t verts, double *ms, totals *tot)
{
    ft_renderer *r = &g_app.renderer;
    const size_t px = (size_t)r->width_px * r->height_px;
    uint8_t *real = malloc(px * 4u);
    REQUIRE(real != NULL);
    memcpy(real, r->rgba, px * 4u);
    ft_error err;
    *ms = 0.0;
    REQUIRE(bench_oracle_prepare(oracle, r, cam, &err) == FT_OK);
    CHECK(oracle->tiles == tiles && oracle->index_count == verts);
    REQUIRE(bench_oracle_frame(oracle, r, cam, ms, &err) == FT_OK);
    CHECK(*ms > 0.0);
    uint64_t diff = 0, terrain = 0;
    for (size_t i = 0; i < px; ++i) {
        const uint8_t *a = real + 4u * i, *b = r->rgba + 4u * i;
        int d = 0;
        for (int ch = 0; ch < 3; ++ch) d = (abs(a[ch] - b[ch]) > d) ? abs(a[ch] - b[ch]) : d;
        diff += (d > PIXEL_DIFF);
        /* the clear colour within a unit: its 8 bits are the GPU's rounding of
         * clear_rgb * 255 (0.7f * 255 is 178.5 in float, stored as 178) */
        int sky = 1;
        for (int ch = 0; ch < 3; ++ch) {
            sky = sky && fabs((double)a[ch] - 255.0 * (double)r->clear_rgb[ch]) <= 1.0;
        }
        terrain += !sky;
    }
    tot->oracle_px += px;
    tot->oracle_diff_px += diff;
    tot->oracle_terrain_px += terrain;
    free(real);
    return diff;
}

static void view(const ft_pose *pose, const tmpl *tp, bench_oracle *oracle, totals *tot)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, pose, &cam, &fs); /* the real draw: tiles uploaded, uniforms set */
    const ft_renderer *r = &g_app.renderer;
    const ft_bintree_method *bm = &r->method.u.bintree;
    const uint32_t tiles = bm->sel.tiles;
    REQUIRE(tiles > 0u);
    const size_t verts = (size_t)tiles * tp->nt * 3u, slack = 3u * tp->nt;
    float *cap = malloc((verts + slack) * CAP_FLOATS * sizeof(float));
    REQUIRE(cap != NULL);
    const uint64_t prims = capture(tp->flat_vbo, tp->nt * 3u, verts, slack, cap);

    /* the mirror: the bench's path (floats + indices) and, per vertex, in double */
    ft_bt_mesh_uniforms u, wrong;
    ft_bt_mesh_uniforms_for(&g_app.terrain, &cam, bm->sel.tau_used_px, bm->morph, &u);
    ft_bt_mesh_uniforms_for(&g_app.terrain, &cam, bm->sel.tau_used_px, !bm->morph, &wrong);
    u.vertex_table = wrong.vertex_table = bm->vertex_table;
    REQUIRE(u.morph == bm->morph && wrong.morph == !bm->morph);
    const size_t mverts = (size_t)tiles * tp->nv;
    float *mesh = malloc(mverts * FT_BT_MESH_FLOATS * sizeof(float));
    uint32_t *idx = malloc((size_t)tiles * tp->nt * 3u * sizeof(uint32_t));
    REQUIRE(mesh != NULL && idx != NULL);
    CHECK(ft_bt_mesh_build(&bm->bt, tiles, &u, tp->uv, tp->nv, mesh,
                           mverts * FT_BT_MESH_FLOATS) == mverts);
    CHECK(ft_bt_mesh_build(&bm->bt, tiles, &u, tp->uv, tp->nv, mesh,
                           mverts * FT_BT_MESH_FLOATS - 1u) == 0u); /* too small: nothing */
    const size_t nidx = ft_bt_mesh_indices(tiles, tp->idx, tp->nt * 3u, tp->nv, idx,
                                           (size_t)tiles * tp->nt * 3u);
    CHECK(nidx == verts);
    /* the same triangle count: mirror, the frame's report, the GPU's primitives */
    CHECK(nidx / 3u == fs.triangles);
    CHECK(prims == fs.triangles);
    tot->triangles += fs.triangles;

    uint64_t bad_before = tot->pos_bad + tot->normal_bad + tot->height_bad + tot->morph_bad;
    uint64_t wrong_before = tot->wrong_rule_bad;
    for (uint32_t t = 0; t < tiles; ++t) {
        const ft_bt_tile *tile = &bm->bt.tiles[t];
        for (uint32_t j = 0; j < tp->nt * 3u; ++j) {
            const size_t ci = (size_t)t * tp->nt * 3u + j;   /* captured vertex */
            const uint32_t mi = idx[ci];                     /* mirror vertex */
            const uint32_t v = tp->idx[j];
            REQUIRE(mi == (uint32_t)t * tp->nv + v);
            const float *c = cap + ci * CAP_FLOATS;
            ++tot->vertices;
            if (c[7] != c[7] || c[0] != c[0]) {
                ++tot->unwritten;
                continue;
            }
            ft_bt_mesh_vertex m, mw;
            ft_bt_mesh_vertex_of(&bm->bt, &u, tile, tp->uv[2u * v], tp->uv[2u * v + 1u], &m);
            ft_bt_mesh_vertex_of(&bm->bt, &wrong, tile, tp->uv[2u * v], tp->uv[2u * v + 1u],
                                 &mw);
            /* the bench's float mesh is the same vertex */
            const float *mf = mesh + (size_t)mi * FT_BT_MESH_FLOATS;
            CHECK(mf[0] == (float)m.pos_rel_eye_m[0] && mf[2] == (float)m.pos_rel_eye_m[2] &&
                  mf[5] == (float)m.normal[2] && mf[6] == (float)m.height_m);
            const double a = dist3(c, m.pos_rel_eye_m);
            const double rel = a / fmax(len3(m.pos_rel_eye_m), 1.0);
            const double scale = operand_scale(&bm->bt, &u, tile, tp->uv[2u * v],
                                               tp->uv[2u * v + 1u], m.height_m);
            if (rel > tot->pos_rel_max) tot->pos_rel_max = rel;
            if (a > tot->pos_abs_max) tot->pos_abs_max = a;
            if (a / scale > tot->pos_op_max) tot->pos_op_max = a / scale;
            tot->pos_rel_bad += !(rel <= POS_REL_TOL);
            if (!(a <= POS_TOL * scale)) {
                if (tot->pos_bad < 5u) {
                    fprintf(stderr, "tile %u vertex %u: gpu (%.6f %.6f %.6f) cpu (%.6f %.6f %.6f),"
                                    " w gpu %.6f cpu %.6f\n",
                            t, v, c[0], c[1], c[2], m.pos_rel_eye_m[0], m.pos_rel_eye_m[1],
                            m.pos_rel_eye_m[2], c[7], m.morph_w);
                }
                ++tot->pos_bad;
            }
            double dn = 0.0;
            for (int i = 0; i < 3; ++i) dn = fmax(dn, fabs(c[3 + i] - m.normal[i]));
            if (dn > tot->normal_max) tot->normal_max = dn;
            tot->normal_bad += !(dn <= NORMAL_TOL);
            /* the weight's float error: 2 dQ / W, dQ a few ulps of Q's operands
             * (a difference of distances, bintree_mesh.h), and the height it moves */
            const double w_float = (m.w_m > 0.0) ? 2.0 * Q_ULPS * 0x1p-24 * m.q_scale_m / m.w_m
                                                 : 0.0;
            const double dh = fabs(c[6] - m.height_m) / fmax(fabs(m.height_m), 1.0);
            const double dh_allowed =
                HEIGHT_REL_TOL + w_float * m.morph_span_m / fmax(fabs(m.height_m), 1.0);
            if (dh > tot->height_rel_max) tot->height_rel_max = dh;
            tot->height_bad += !(dh <= dh_allowed);
            const double dw = fabs(c[7] - m.morph_w);
            if (dw > tot->morph_max) tot->morph_max = dw;
            tot->morph_bad += !(dw <= MORPH_TOL + w_float);
            tot->midmorph += (m.morph_w > 0.0 && m.morph_w < 1.0);
            tot->between += !m.on_sample;
            tot->between_midmorph += (!m.on_sample && m.morph_w > 0.0 && m.morph_w < 1.0);
            if (m.err_m >= 0.0) {
                /* the morph error is the one the selection split the diamond at */
                const double e = selection_error(&bm->bt, tile, tp->uv[2u * v],
                                                 tp->uv[2u * v + 1u]);
                tot->closed_form += (m.err_closed_form != 0);
                ++tot->err_checked;
                tot->err_bad += !(e == m.err_m);
            }
            /* the wrong rule must be caught by the same position test */
            tot->wrong_rule_bad += !(dist3(c, mw.pos_rel_eye_m) <= POS_TOL * scale);
        }
    }
    /* nothing past the frame's vertices */
    for (size_t i = verts * CAP_FLOATS; i < (verts + slack) * CAP_FLOATS; ++i) {
        if (cap[i] == cap[i]) {
            ++tot->overrun;
            break;
        }
    }

    /* 3. the oracle frame against the real one */
    double ms = 0.0;
    const uint64_t diff = oracle_compare(oracle, &cam, tiles, verts, &ms, tot);
    const size_t px = (size_t)r->width_px * r->height_px;
    printf("  view (%.3f, %.3f, %.0f m, hdg %.0f, pitch %.0f): %u tiles, %llu triangles, "
           "%llu mismatches, %llu with the wrong morph rule; oracle %.2f ms (frame %.2f ms), "
           "%llu of %zu pixels differ\n",
           pose->lat_deg, pose->lon_deg, pose->alt_m, pose->heading_deg, pose->pitch_deg, tiles,
           (unsigned long long)fs.triangles,
           (unsigned long long)(tot->pos_bad + tot->normal_bad + tot->height_bad +
                                tot->morph_bad - bad_before),
           (unsigned long long)(tot->wrong_rule_bad - wrong_before), ms, fs.gpu_ms,
           (unsigned long long)diff, px);
    free(idx);
    free(mesh);
    free(cap);
}

/* After init: the colour program relinked to capture the shader's outputs,
 * the template of k (the method's) and its expanded vertex buffer, and the
 * oracle. */
static void capture_begin(uint32_t k, tmpl *tp, bench_oracle *oracle)
{
    ft_error err;
    static const char *const varyings[4] = {"v_pos_rel_eye_m", "v_normal", "v_height_m",
                                            "v_morph"};
    REQUIRE(ft_renderer_enable_capture_of(&g_app.renderer, varyings, 4u, &err) == FT_OK);
    memset(tp, 0, sizeof *tp);
    tp->nv = ft_bt_template_vertices(k);
    tp->nt = ft_bt_template_triangles(k);
    tp->uv = malloc((size_t)tp->nv * 2u * sizeof(float));
    tp->idx = malloc((size_t)tp->nt * 3u * sizeof(uint16_t));
    int16_t *scratch = malloc((size_t)ft_bt_template_scratch(k) * sizeof(int16_t));
    float *flat = malloc((size_t)tp->nt * 6u * sizeof(float));
    REQUIRE(tp->uv && tp->idx && scratch && flat);
    REQUIRE(ft_bt_template_build(k, tp->uv, tp->idx, scratch, &err) == FT_OK);
    for (uint32_t i = 0; i < tp->nt * 3u; ++i) {
        flat[2u * i] = tp->uv[2u * tp->idx[i]];
        flat[2u * i + 1u] = tp->uv[2u * tp->idx[i] + 1u];
    }
    tp->flat_vbo = ft_test_bintree_flat_vbo(&g_app, flat, tp->nt * 3u);
    free(flat);
    free(scratch);
    REQUIRE(bench_oracle_init(oracle, &g_app.renderer, &err) == FT_OK);
}

/* capture_begin's undone, and the app shut down. */
static void capture_end(tmpl *tp, bench_oracle *oracle)
{
    bench_oracle_shutdown(oracle);
    g_app.renderer.gl->DeleteBuffers(1, &tp->flat_vbo);
    free(tp->idx);
    free(tp->uv);
    ft_app_shutdown(&g_app);
}

typedef struct config {
    uint32_t k;
    uint32_t sub; /* bintree.subsample_levels */
    double tau;
    int morph;
    double morph_width; /* bintree.morph_width */
} config;

static void run_config(const char *dem, const config *cf)
{
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, 256u, 192u, dem, cf->k, cf->sub,
                   cf->tau, cf->morph, cf->morph_width, "");
    ft_test_app_init(&g_app, g_text, "bintree mesh");
    REQUIRE(g_app.renderer.method.u.bintree.bt.morph_width == cf->morph_width);
    tmpl tp;
    bench_oracle oracle;
    capture_begin(cf->k, &tp, &oracle);

    totals tot;
    memset(&tot, 0, sizeof tot);
    REQUIRE(g_app.renderer.method.u.bintree.bt.sub == cf->sub);
    printf("k = %u, S = %u, tau = %.1f, morph = %d, morph_width %.4f:\n", cf->k, cf->sub,
           cf->tau, cf->morph, cf->morph_width);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose pose = view_pose(v);
        view(&pose, &tp, &oracle, &tot);
    }
    printf("k = %u S = %u tau = %.1f morph = %d: %llu vertices (%llu mid-morph; between "
           "samples %llu, %llu of them mid-morph), %llu triangles; morph errors: %llu checked "
           "against the selection's (%llu closed form), %llu differ; max "
           "position error %.3g m (relative to the distance %.3g, allowed %.1g; to the operands "
           "%.3g, allowed %.1g), normal %.3g (%.1g), height "
           "relative %.3g (%.1g), morph weight %.3g (%.1g); mismatches: position %llu, normal "
           "%llu, height %llu, morph %llu; unwritten %llu, overrun %llu; the wrong morph rule: "
           "%llu position mismatches; oracle image: %llu of %llu pixels differ by more than %d "
           "(%llu terrain pixels)\n",
           cf->k, cf->sub, cf->tau, cf->morph, (unsigned long long)tot.vertices,
           (unsigned long long)tot.midmorph, (unsigned long long)tot.between,
           (unsigned long long)tot.between_midmorph, (unsigned long long)tot.triangles,
           (unsigned long long)tot.err_checked, (unsigned long long)tot.closed_form,
           (unsigned long long)tot.err_bad, tot.pos_abs_max,
           tot.pos_rel_max, POS_REL_TOL, tot.pos_op_max, POS_TOL, tot.normal_max, NORMAL_TOL, tot.height_rel_max,
           HEIGHT_REL_TOL, tot.morph_max, MORPH_TOL, (unsigned long long)tot.pos_bad,
           (unsigned long long)tot.normal_bad, (unsigned long long)tot.height_bad,
           (unsigned long long)tot.morph_bad, (unsigned long long)tot.unwritten,
           (unsigned long long)tot.overrun, (unsigned long long)tot.wrong_rule_bad,
           (unsigned long long)tot.oracle_diff_px, (unsigned long long)tot.oracle_px, PIXEL_DIFF,
           (unsigned long long)tot.oracle_terrain_px);
    CHECK(tot.vertices > 10000u);
    CHECK(tot.unwritten == 0u);
    CHECK(tot.overrun == 0u);
    CHECK(tot.pos_rel_bad == 0u);
    CHECK(tot.pos_bad == 0u);
    CHECK(tot.normal_bad == 0u);
    CHECK(tot.height_bad == 0u);
    CHECK(tot.morph_bad == 0u);
    /* the comparison has teeth: the views catch vertices mid-morph, and the
     * wrong morph rule moves enough of them beyond the tolerance */
    if (cf->morph) CHECK(tot.midmorph > 100u);
    if (cf->morph) {
        CHECK(tot.wrong_rule_bad > 100u);
    } else {
        /* without the geomorph a diamond splits only where its Q > 0, where
         * the geomorph has its vertices at their own heights already: the
         * same mesh (bintree.h) */
        CHECK(tot.wrong_rule_bad == 0u);
    }
    /* the morph error of every morphing vertex is its diamond's in the
     * selection (the table, or the closed form from the whole closure) */
    if (cf->morph) CHECK(tot.err_checked > 1000u);
    CHECK(tot.err_bad == 0u);
    /* with sub-sample levels the views exercise that path: vertices between
     * samples, mid-morph, with closed-form errors */
    if (cf->sub > 0u) {
        CHECK(tot.between > 1000u);
        CHECK(tot.between_midmorph > 100u && tot.closed_form > 100u);
    } else {
        CHECK(tot.between == 0u && tot.closed_form == 0u);
    }
    CHECK(tot.oracle_terrain_px > tot.oracle_px / 2u);
    CHECK((double)tot.oracle_diff_px <= PIXEL_FRACTION_MAX * (double)tot.oracle_px);
    capture_end(&tp, &oracle);
}

/* ---- the bintree over the clipmap cache ----------------------------------------------- */

/* The cache's scene keys, appended to k_scene_fmt: bintree.heights =
 * clipmap (morph and sub-sample levels off, which it needs), a level side
 * of 256 (the least for template_k 3 is 12 * 2^3 + 8 = 104) and levels up
 * to 2^4 samples apart (level 3 already spans the 1201-sample grid), their
 * CPU mirrors (2 x 5 x 256^2 floats), blocks and staging in
 * budget.clip_bytes (about 2.7 MB). Updates enough for a whole refill a
 * frame (5 x 256^2 samples, update_samples_max 16384 each): each view jumps
 * far from the last, and with the default 8 the cache would lag and the
 * frames would draw few, coarse tiles. %s: gpu.height_format (auto or
 * packed). */
static const char k_cache_keys[] =
    "[bintree]\nheights = clipmap\n[clipmap]\nside = 256\nlevels = 5\nupdates_per_frame = 64\n"
    "[budget]\nclip_bytes = 3M\n[gpu]\nheight_format = %s\n";

/* 1. and 3. over the cache: the frame's tiles (bm->btc.tiles) captured from
 * shaders/bintree_clip.vert.glsl against ft_btc_mesh_build's mirror of
 * them (bintree_mesh.h), and the oracle frame against the real one.
 *   position  |gpu - cpu| <= POS_REL_TOL * max(|cpu|, 1 m) and
 *             <= POS_TOL * (|(x, y)| + cell + |h| + |eye z|): the shader's
 *             float operands (lattice offsets from the eye's integer part,
 *             its fraction, the height and the eye's height), plus the
 *             packed height's tolerance
 *   normal    each component within NORMAL_TOL (plus, packed, the slope
 *             the height's tolerance makes over the central difference)
 *   height    exact with float texels (the mirror reads the very texels);
 *             packed, within PACKED_STEPS steps of range / (2^24 - 1) plus
 *             HEIGHT_REL_TOL of it
 *   morph     exactly 1 (no geomorphing over the cache)
 * The test can fail: the same captures against the mirror reading every
 * level's neighbour (d xor 1) must mismatch almost everywhere. */
static void view_cache(const ft_pose *pose, const tmpl *tp, bench_oracle *oracle, totals *tot)
{
    ft_camera cam;
    ft_frame_stats fs;
    ft_test_frame(&g_app, pose, &cam, &fs);
    const ft_renderer *r = &g_app.renderer;
    const ft_bintree_method *bm = &r->method.u.bintree;
    const ft_bt_cache *bc = &bm->btc;
    const ft_clip_levels *cl = &bm->cl;
    const uint32_t tiles = bm->sel.tiles;
    REQUIRE(tiles > 0u);
    const size_t verts = (size_t)tiles * tp->nt * 3u, slack = 3u * tp->nt;
    float *cap = malloc((verts + slack) * CAP_FLOATS * sizeof(float));
    REQUIRE(cap != NULL);
    const uint64_t prims = capture(tp->flat_vbo, tp->nt * 3u, verts, slack, cap);

    /* the mirror, as the oracle calls it, and one reading the wrong levels */
    const double eye_i = bm->eye_rel[0] + (double)bc->origin[0];
    const double eye_j = bm->eye_rel[1] + (double)bc->origin[1];
    const double drop = g_app.terrain.curv_drop_per_m2;
    const size_t mverts = (size_t)tiles * tp->nv, mfloats = mverts * FT_BT_MESH_FLOATS;
    float *mesh = malloc(mfloats * sizeof(float));
    float *wrong_mesh = malloc(mfloats * sizeof(float));
    uint32_t *idx = malloc(verts * sizeof(uint32_t));
    REQUIRE(mesh != NULL && wrong_mesh != NULL && idx != NULL);
    CHECK(ft_btc_mesh_build(bc, &cl->cache, tiles, eye_i, eye_j, cam.eye_m[2], drop, tp->uv,
                            tp->nv, mesh, mfloats) == mverts);
    CHECK(ft_btc_mesh_build(bc, &cl->cache, tiles, eye_i, eye_j, cam.eye_m[2], drop, tp->uv,
                            tp->nv, mesh, mfloats - 1u) == 0u); /* too small: nothing */
    static ft_clip_cache wrong; /* large: not on the stack */
    wrong = cl->cache;
    for (uint32_t d = 0; d < cl->levels; ++d) {
        const uint32_t e = ((d ^ 1u) < cl->levels) ? (d ^ 1u) : d;
        wrong.mirror_m[d] = cl->cache.mirror_m[e];
    }
    CHECK(ft_btc_mesh_build(bc, &wrong, tiles, eye_i, eye_j, cam.eye_m[2], drop, tp->uv, tp->nv,
                            wrong_mesh, mfloats) == mverts);
    CHECK(ft_bt_mesh_indices(tiles, tp->idx, tp->nt * 3u, tp->nv, idx, verts) == verts);
    CHECK(verts / 3u == fs.triangles);
    CHECK(prims == fs.triangles);
    tot->triangles += fs.triangles;

    const int packed = cl->fmt.format == FT_HEIGHT_FORMAT_PACKED;
    const double step_m = packed ? (double)cl->fmt.pack_range / 16777215.0 : 0.0;
    const double cell_lo = fmin(bc->cell_m[0], bc->cell_m[1]);
    const double cell_hi = fmax(bc->cell_m[0], bc->cell_m[1]);
    const double box[4] = {(double)(bc->data[0] - bc->origin[0]),
                           (double)(bc->data[1] - bc->origin[1]),
                           (double)(bc->data[2] - bc->origin[0]),
                           (double)(bc->data[3] - bc->origin[1])};
    const uint64_t bad_before = tot->pos_bad + tot->pos_rel_bad + tot->normal_bad +
                                tot->height_bad + tot->morph_bad;
    const uint64_t wrong_before = tot->wrong_level_bad, clamped_before = tot->clamped;
    for (uint32_t t = 0; t < tiles; ++t) {
        const ft_bt_tile *tile = &bc->tiles[t];
        const double leg[2] = {(double)tile->left[0] - tile->apex[0],
                               (double)tile->left[1] - tile->apex[1]};
        const uint32_t tm = ft_btc_table_of(bc, tile->level); /* the level it reads: */
        tot->level_vertices[tm < bc->top ? tm : bc->top] += 3u * tp->nt; /* min(m, Lc) */
        for (uint32_t j = 0; j < tp->nt * 3u; ++j) {
            const size_t ci = (size_t)t * tp->nt * 3u + j;
            const uint32_t v = tp->idx[j];
            REQUIRE(idx[ci] == (uint32_t)t * tp->nv + v);
            const float *c = cap + ci * CAP_FLOATS;
            const float *m = mesh + (size_t)idx[ci] * FT_BT_MESH_FLOATS;
            const float *mw = wrong_mesh + (size_t)idx[ci] * FT_BT_MESH_FLOATS;
            ++tot->vertices;
            if (c[7] != c[7] || c[0] != c[0]) {
                ++tot->unwritten;
                continue;
            }
            /* the vertex on the lattice (the shader's g): past the data box? */
            const double a = tp->uv[2u * v], b = tp->uv[2u * v + 1u];
            const double g[2] = {tile->apex[0] + a * leg[0] - b * leg[1],
                                 tile->apex[1] + a * leg[1] + b * leg[0]};
            tot->clamped += (g[0] < box[0] || g[0] > box[2] || g[1] < box[1] || g[1] > box[3]);

            const double h = m[6];
            const double htol = packed ? PACKED_STEPS * step_m + HEIGHT_REL_TOL * fmax(fabs(h), 1.0)
                                       : 0.0;
            const double cpu[3] = {m[0], m[1], m[2]};
            const double dp = dist3(c, cpu);
            const double rel = dp / fmax(len3(cpu), 1.0);
            const double scale =
                sqrt(cpu[0] * cpu[0] + cpu[1] * cpu[1]) + cell_hi + fabs(h) + fabs(cam.eye_m[2]);
            if (rel > tot->pos_rel_max) tot->pos_rel_max = rel;
            if (dp > tot->pos_abs_max) tot->pos_abs_max = dp;
            if (dp / scale > tot->pos_op_max) tot->pos_op_max = dp / scale;
            tot->pos_rel_bad += !(rel <= POS_REL_TOL);
            if (!(dp <= POS_TOL * scale + htol)) {
                if (tot->pos_bad < 5u) {
                    fprintf(stderr, "cache tile %u (tree level %u) vertex %u: gpu (%.6f %.6f %.6f) "
                                    "cpu (%.6f %.6f %.6f)\n",
                            t, tile->level, v, c[0], c[1], c[2], cpu[0], cpu[1], cpu[2]);
                }
                ++tot->pos_bad;
            }
            double dn = 0.0;
            for (int i = 0; i < 3; ++i) dn = fmax(dn, fabs((double)c[3 + i] - m[3 + i]));
            if (dn > tot->normal_max) tot->normal_max = dn;
            tot->normal_bad += !(dn <= NORMAL_TOL + htol / cell_lo);
            const double dh = fabs((double)c[6] - h);
            if (dh > tot->height_abs_max) tot->height_abs_max = dh;
            if (dh / fmax(fabs(h), 1.0) > tot->height_rel_max) {
                tot->height_rel_max = dh / fmax(fabs(h), 1.0);
            }
            tot->height_bad += !(dh <= htol);
            if (fabs(c[7] - 1.0) > tot->morph_max) tot->morph_max = fabs(c[7] - 1.0);
            tot->morph_bad += !(c[7] == 1.0f);
            /* the wrong levels' heights must be caught by the same tests */
            const double cw[3] = {mw[0], mw[1], mw[2]};
            tot->wrong_level_bad += !(dist3(c, cw) <= POS_TOL * scale + htol &&
                                      fabs((double)c[6] - mw[6]) <= htol);
        }
    }
    for (size_t i = verts * CAP_FLOATS; i < (verts + slack) * CAP_FLOATS; ++i) {
        if (cap[i] == cap[i]) {
            ++tot->overrun;
            break;
        }
    }

    double ms = 0.0;
    const uint64_t diff = oracle_compare(oracle, &cam, tiles, verts, &ms, tot);
    printf("  view (%.3f, %.3f, %.0f m, hdg %.0f, pitch %.0f): %u tiles, %llu triangles, "
           "%llu clamped vertices, %llu mismatches, %llu with the wrong levels; oracle %.2f ms "
           "(frame %.2f ms), %llu of %u pixels differ; cache levels behind %u\n",
           pose->lat_deg, pose->lon_deg, pose->alt_m, pose->heading_deg, pose->pitch_deg, tiles,
           (unsigned long long)fs.triangles, (unsigned long long)(tot->clamped - clamped_before),
           (unsigned long long)(tot->pos_bad + tot->pos_rel_bad + tot->normal_bad +
                                tot->height_bad + tot->morph_bad - bad_before),
           (unsigned long long)(tot->wrong_level_bad - wrong_before), ms, fs.gpu_ms,
           (unsigned long long)diff, r->width_px * r->height_px,
           (unsigned)fs.cache_levels_behind);
    free(idx);
    free(wrong_mesh);
    free(mesh);
    free(cap);
}

/* packed: the cache's texels as 24-bit fixed point (gpu.height_format =
 * packed), else as the context has them (float here) */
static void run_cache_config(const char *dem, int packed)
{
    const config cf = {3, 0, 1.0, 0, 0.25};
    char keys[256];
    (void)snprintf(keys, sizeof keys, k_cache_keys, packed ? "packed" : "auto");
    (void)snprintf(g_text, sizeof g_text, k_scene_fmt, 256u, 192u, dem, cf.k, cf.sub, cf.tau,
                   cf.morph, cf.morph_width, keys);
    ft_test_app_init(&g_app, g_text, "bintree mesh over the cache");
    const ft_bintree_method *bm = &g_app.renderer.method.u.bintree;
    REQUIRE(bm->clip && bm->btc.k == cf.k && bm->cl.side == 256u);
    tmpl tp;
    bench_oracle oracle;
    capture_begin(cf.k, &tp, &oracle);
    const ft_scalar_format *fmt = &bm->cl.fmt;
    REQUIRE(!packed || fmt->format == FT_HEIGHT_FORMAT_PACKED);
    printf("over the cache: k = %u, tau = %.1f, %u levels of %u^2 samples, texels %s",
           bm->btc.k, cf.tau, bm->cl.levels, bm->cl.side,
           fmt->format == FT_HEIGHT_FORMAT_PACKED ? "packed" : "float");
    if (fmt->format == FT_HEIGHT_FORMAT_PACKED) {
        printf(" over [%.1f, %.1f] m", fmt->pack_min, fmt->pack_min + fmt->pack_range);
    }
    printf(":\n");
    totals tot;
    memset(&tot, 0, sizeof tot);
    for (uint32_t v = 0; v < VIEWS; ++v) {
        const ft_pose pose = view_pose(v);
        view_cache(&pose, &tp, &oracle, &tot);
    }
    char levels[FT_CLIP_LEVELS_MAX * 24u] = ""; /* 16 counts of up to 20 digits */
    for (uint32_t d = 0, n = 0; d < bm->cl.levels; ++d) {
        n += (uint32_t)snprintf(levels + n, sizeof levels - n, "%s%llu", d > 0u ? " " : "",
                                (unsigned long long)tot.level_vertices[d]);
    }
    printf("over the cache (%s texels) k = %u tau = %.1f: %llu vertices (by the level they read "
           "%s; %llu clamped into the data box), "
           "%llu triangles; max position error %.3g m (relative to the distance %.3g, allowed "
           "%.1g; to the operands %.3g, allowed %.1g), normal %.3g (%.1g), height %.3g m "
           "(relative %.3g), morph weight %.3g; mismatches: position %llu (relative %llu), "
           "normal %llu, height %llu, morph %llu; unwritten %llu, overrun %llu; the wrong "
           "levels: %llu mismatches; oracle image: %llu of %llu pixels differ by more than %d "
           "(%llu terrain pixels)\n",
           fmt->format == FT_HEIGHT_FORMAT_PACKED ? "packed" : "float", bm->btc.k, cf.tau,
           (unsigned long long)tot.vertices, levels, (unsigned long long)tot.clamped,
           (unsigned long long)tot.triangles, tot.pos_abs_max, tot.pos_rel_max, POS_REL_TOL,
           tot.pos_op_max, POS_TOL, tot.normal_max, NORMAL_TOL, tot.height_abs_max,
           tot.height_rel_max, tot.morph_max, (unsigned long long)tot.pos_bad,
           (unsigned long long)tot.pos_rel_bad, (unsigned long long)tot.normal_bad,
           (unsigned long long)tot.height_bad, (unsigned long long)tot.morph_bad,
           (unsigned long long)tot.unwritten, (unsigned long long)tot.overrun,
           (unsigned long long)tot.wrong_level_bad, (unsigned long long)tot.oracle_diff_px,
           (unsigned long long)tot.oracle_px, PIXEL_DIFF,
           (unsigned long long)tot.oracle_terrain_px);
    CHECK(tot.vertices > 10000u);
    CHECK(tot.unwritten == 0u);
    CHECK(tot.overrun == 0u);
    CHECK(tot.pos_rel_bad == 0u);
    CHECK(tot.pos_bad == 0u);
    CHECK(tot.normal_bad == 0u);
    CHECK(tot.height_bad == 0u);
    CHECK(tot.morph_bad == 0u);
    /* the comparison has teeth: the wrong levels move most vertices; and
     * the views reach the data box's edge (the shader's clamp) and read
     * level 0 and coarser levels */
    CHECK(tot.wrong_level_bad > tot.vertices / 2u);
    CHECK(tot.clamped > 1000u);
    CHECK(tot.level_vertices[0] > 10000u && tot.level_vertices[1] > 10000u);
    CHECK(tot.oracle_terrain_px > tot.oracle_px / 2u);
    CHECK((double)tot.oracle_diff_px <= PIXEL_FRACTION_MAX * (double)tot.oracle_px);
    capture_end(&tp, &oracle);
}

int main(int argc, char **argv)
{
    REQUIRE(argc >= 2);
    const char *dem = argv[1];
    if (!ft_test_have_data(dem)) return FT_TEST_SKIP;
    static const config configs[] = {
        {3, 0, 1.0, 1, 0.25},
        {2, 0, 2.0, 1, 0.25},
        {4, 0, 0.5, 1, 0.0625}, /* a narrow morph band */
        {3, 0, 1.0, 0, 0.25},   /* no geomorph: the mirror without it; the wrong rule morphs */
        {3, 2, 1.0, 1, 0.5},    /* sub-sample levels */
        {2, 3, 1.0, 1, 0.25},
    };
    for (size_t i = 0; i < sizeof configs / sizeof configs[0]; ++i) {
        run_config(dem, &configs[i]);
    }
    run_cache_config(dem, 0);
    run_cache_config(dem, 1);
    return ft_test_result("test_bintree_mesh");
}
