/* test_gl_discipline.c - the frame loop keeps to a safety-critical GL subset
 * (the GL SC 2.0 discipline: every object exists before the first frame).
 *
 * usage: test_gl_discipline BACKEND METHOD     (BACKEND egl-gles3 | egl-gles2 |
 *                                               osmesa; METHOD as scene.method)
 *
 * Inits the app from a synthetic scene (128x96), then records every GL call
 * through the table's recording layer (ft_gl_trace_start, src/gpu/gl_api.h) over
 * 120 frames along a moving path (position, heading, pitch, roll and height
 * change every frame, so every LOD method selects anew) and 120 more frames
 * with the failure annunciation over them (the reason text changes every 30
 * frames, so the overlay rebuilds its vertices), and requires after init:
 *   - no shader or program work: glCreateShader/ShaderSource/CompileShader,
 *     glCreateProgram/AttachShader/BindAttribLocation/LinkProgram/
 *     TransformFeedbackVaryings, glDeleteShader/DeleteProgram;
 *   - no object creation or deletion: glGen and glDelete of buffers, textures,
 *     framebuffers, renderbuffers, vertex arrays and queries;
 *   - no (re)allocation: glTexImage2D, glBufferData, glRenderbufferStorage
 *     (updates go through glBufferSubData only), no glMapBufferRange;
 *   - no init-time queries: glGetString(i), glGetShaderiv/GetProgramiv and
 *     their logs, glGetUniformLocation (locations are looked up at init);
 *   - no glGetError at all (renderer.gl_error_checks = 0, the Release default:
 *     no control flow may depend on it);
 *   - glReadPixels bytes per frame <= the method's bound: the colour frame
 *     (W x H x 4) for brute, bintree and pgm; pgrid also reads its error
 *     buffer (the view's size, RGBA8): 2 x W x H x 4.
 * A violation names the entry point, how often, and the first and last
 * frame. The checker is proven able to fail first: a canary frame that
 * creates and deletes a buffer must be reported with its name and frame.
 * k_exceptions below lists every allowed call with its reason. */
#include <stdio.h>
#include <string.h>

#include "app/app.h"
#include "test_app_util.h"

#define W_PX 128u
#define H_PX 96u
#define FRAMES 120u

static const char k_scene[] =
    "[scene]\nname = gl-discipline\nmethod = brute\nbackend = egl-gles3\n"
    "[view]\nwidth_px = 128\nheight_px = 96\nfovy_deg = 60\n"
    "[terrain]\ndem =\nsynth_side = 257\nsynth_spacing_m = 30\nsynth_relief_m = 2000\n"
    "synth_seed = 3\nsynth_octaves = 8\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[gpu]\ntexture_bytes = 16M\n[metric]\nenabled = 0\n"
    "[bintree]\ntemplate_k = 3\ntiles_max = 4096\ntau_px = 1.0\nmorph = 1\n"
    "[pgm]\ngrid_cols = 100\ngrid_rows = 300\n"
    "[pgrid]\ngrid_cols = 100\ngrid_rows = 300\n"
    "[clipmap]\nside = 64\nlevels = 4\nupdate_samples_max = 2048\nupdates_per_frame = 4\n"
    "[budget]\nclip_bytes = 256K\n";

/* Entry points a frame must not call, with the rule each breaks. */
typedef struct rule {
    ft_gl_entry e;
    const char *why;
} rule;

static const rule k_forbidden[] = {
    {FT_GLE_CreateShader, "shader work after init"},
    {FT_GLE_ShaderSource, "shader work after init"},
    {FT_GLE_CompileShader, "shader compile after init"},
    {FT_GLE_CreateProgram, "program creation after init"},
    {FT_GLE_AttachShader, "program link after init"},
    {FT_GLE_BindAttribLocation, "program link after init"},
    {FT_GLE_LinkProgram, "program link after init"},
    {FT_GLE_TransformFeedbackVaryings, "program relink after init"},
    {FT_GLE_DeleteShader, "object deletion after init"},
    {FT_GLE_DeleteProgram, "object deletion after init"},
    {FT_GLE_GenBuffers, "object creation after init"},
    {FT_GLE_GenTextures, "object creation after init"},
    {FT_GLE_GenFramebuffers, "object creation after init"},
    {FT_GLE_GenRenderbuffers, "object creation after init"},
    {FT_GLE_GenVertexArrays, "object creation after init"},
    {FT_GLE_GenQueries, "object creation after init"},
    {FT_GLE_DeleteBuffers, "object deletion after init"},
    {FT_GLE_DeleteTextures, "object deletion after init"},
    {FT_GLE_DeleteFramebuffers, "object deletion after init"},
    {FT_GLE_DeleteRenderbuffers, "object deletion after init"},
    {FT_GLE_DeleteVertexArrays, "object deletion after init"},
    {FT_GLE_DeleteQueries, "object deletion after init"},
    {FT_GLE_TexImage2D, "texture (re)allocation (only sub-image updates)"},
    {FT_GLE_BufferData, "buffer (re)allocation (only glBufferSubData)"},
    {FT_GLE_RenderbufferStorage, "renderbuffer (re)allocation"},
    {FT_GLE_MapBufferRange, "buffer mapping (only glBufferSubData)"},
    {FT_GLE_UnmapBuffer, "buffer mapping (only glBufferSubData)"},
    {FT_GLE_GetError, "glGetError in the frame path (control flow must not depend on it)"},
    {FT_GLE_GetString, "init-time query in a frame"},
    {FT_GLE_GetStringi, "init-time query in a frame"},
    {FT_GLE_GetShaderiv, "init-time query in a frame"},
    {FT_GLE_GetShaderInfoLog, "init-time query in a frame"},
    {FT_GLE_GetProgramiv, "init-time query in a frame"},
    {FT_GLE_GetProgramInfoLog, "init-time query in a frame"},
    {FT_GLE_GetUniformLocation, "init-time query in a frame (look locations up at init)"},
    {FT_GLE_CheckFramebufferStatus, "init-time query in a frame"},
};

/* Allowed exceptions: entry point, method ("" = every method) and reason.
 * Empty today: every method's frame loop keeps the rules. */
typedef struct exception {
    ft_gl_entry e;
    const char *method;
    const char *reason;
} exception;
static const exception k_exceptions[] = {
    /* pgrid's late decision (src/lod/pgrid.h 5): the previous frame's error
     * buffer, read into a pixel-pack buffer without a stall, is mapped for
     * reading once a frame; nothing is allocated (the buffers are made at
     * init) */
    {FT_GLE_MapBufferRange, "pgrid", "maps the previous frame's error buffer for reading"},
    {FT_GLE_UnmapBuffer, "pgrid", "unmaps it"},
};

static int excepted(ft_gl_entry e, const char *method)
{
    for (size_t i = 0; i < sizeof k_exceptions / sizeof k_exceptions[0]; ++i) {
        const exception *x = &k_exceptions[i];
        if (x->e == e && (x->method[0] == '\0' || strcmp(x->method, method) == 0)) {
            printf("  allowed: %s in %s: %s\n", ft_gl_entry_name(e), method, x->reason);
            return 1;
        }
    }
    return 0;
}

/* Prints every violation of tr; returns how many entry points broke a rule. */
static unsigned check_trace(const ft_gl_trace *tr, const char *method, uint64_t read_bound)
{
    unsigned bad = 0;
    for (size_t i = 0; i < sizeof k_forbidden / sizeof k_forbidden[0]; ++i) {
        const ft_gl_trace_count *c = &tr->count[k_forbidden[i].e];
        if (c->calls == 0u || excepted(k_forbidden[i].e, method)) {
            continue;
        }
        fprintf(stderr, "  VIOLATION %s: %llu call(s), first in frame %u, last in frame %u: %s\n",
                ft_gl_entry_name(k_forbidden[i].e), (unsigned long long)c->calls,
                c->first_frame, c->last_frame, k_forbidden[i].why);
        ++bad;
    }
    if (tr->read_bytes_max > read_bound) {
        fprintf(stderr, "  VIOLATION glReadPixels: %llu bytes in frame %u > bound %llu\n",
                (unsigned long long)tr->read_bytes_max, tr->read_bytes_max_frame,
                (unsigned long long)read_bound);
        ++bad;
    }
    return bad;
}

static ft_app g_app;

static ft_pose pose_at(uint32_t f)
{
    return ft_test_pose(46.5 + 0.02 + 0.0002 * f, 8.0 + 0.02 + 0.0001 * f, 2500.0 + 10.0 * f,
                        3.0 * f, -10.0 - 0.1 * f, (double)(f % 20u) - 10.0);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_gl_discipline BACKEND METHOD\n");
        return 2;
    }
    const char *backend = argv[1];
    /* pgrid-cache: pgrid over the clipmap cache, its tight bound's passes on
     * the cache's levels and ray casting through them (GLES 3); bintree-cache:
     * the bintree's tiles over the cache (bintree.heights = clipmap), its
     * updates and tables every frame (a level side of 128: the least for
     * template_k 3 is 12 * 2^3 + 8) */
    const int pgrid_cache = strcmp(argv[2], "pgrid-cache") == 0;
    const int bintree_cache = strcmp(argv[2], "bintree-cache") == 0;
    const char *method = pgrid_cache ? "pgrid" : bintree_cache ? "bintree" : argv[2];
    char scene[2048];
    (void)snprintf(scene, sizeof scene, "%s%s[scene]\nbackend = %s\nmethod = %s\n", k_scene,
                   pgrid_cache     ? "[pgrid]\nheights = clipmap\nerror_bound = residual\n"
                                     "ray_casting = 1\n[budget]\nclip_bytes = 1M\n"
                   : bintree_cache ? "[bintree]\nheights = clipmap\nmorph = 0\n"
                                     "[clipmap]\nside = 128\n[budget]\nclip_bytes = 2M\n"
                                   : "",
                   backend, method);
    ft_test_app_init(&g_app, scene, method);
    if (pgrid_cache) {
        const ft_pgrid_method *pg = &g_app.renderer.method.u.pgrid;
        REQUIRE(pg->pgm.clip && pg->ray_casting && pg->tight);
    }
    if (bintree_cache) {
        REQUIRE(g_app.renderer.method.u.bintree.clip);
    }
    ft_gl *gl = &g_app.gpu.gl;
    g_app.renderer.gl_error_checks = 0; /* the deployment frame loop */

    const uint64_t frame_bytes = (uint64_t)W_PX * H_PX * 4u;
    const uint64_t read_bound = strcmp(method, "pgrid") == 0 ? 2u * frame_bytes : frame_bytes;

    /* 1. The checker can fail: a canary frame breaking two rules. */
    static ft_gl_trace canary;
    REQUIRE(ft_gl_trace_start(gl, &canary));
    ft_gl_trace_frame(&canary, 777u);
    GLuint buf = 0;
    gl->GenBuffers(1, &buf);
    gl->DeleteBuffers(1, &buf);
    ft_gl_trace_stop(gl, &canary);
    printf("canary (must report glGenBuffers and glDeleteBuffers in frame 777):\n");
    CHECK(check_trace(&canary, "canary", read_bound) == 2u);
    CHECK(canary.count[FT_GLE_GenBuffers].calls == 1u &&
          canary.count[FT_GLE_GenBuffers].first_frame == 777u);
    CHECK(strcmp(ft_gl_entry_name(FT_GLE_GenBuffers), "glGenBuffers") == 0);
    CHECK(gl->GenBuffers != NULL && canary.calls_total == 2u);

    /* 2. The frame loop: plain frames, then annunciated ones. */
    static const char *const reasons[] = {"ATTITUDE STALE", "POSITION STALE", "NO POSE",
                                          "GPS JUMP"};
    static ft_gl_trace tr;
    REQUIRE(ft_gl_trace_start(gl, &tr));
    ft_camera cam;
    ft_frame_stats fs;
    uint64_t triangles = 0;
    uint32_t ok = 0;
    for (uint32_t f = 0; f < 2u * FRAMES; ++f) {
        ft_gl_trace_frame(&tr, f);
        ft_pose p = pose_at(f % FRAMES);
        const char *reason = (f < FRAMES) ? NULL : reasons[((f - FRAMES) / 30u) % 4u];
        ft_error err;
        ft_status st = ft_app_render_annunciated(&g_app, &p, reason, &cam, &fs, &err);
        if (st != FT_OK) {
            fprintf(stderr, "frame %u: %s\n", f, err.text);
        } else {
            ++ok;
            triangles += fs.triangles;
        }
    }
    ft_gl_trace_stop(gl, &tr);
    CHECK(ok == 2u * FRAMES);
    CHECK(triangles > 0u);

    printf("%s %s: %u frames, %llu GL calls (%.1f per frame), readback max %llu bytes "
           "(frame %u, bound %llu)\n",
           backend, method, tr.frames, (unsigned long long)tr.calls_total,
           (double)tr.calls_total / (double)tr.frames, (unsigned long long)tr.read_bytes_max,
           tr.read_bytes_max_frame, (unsigned long long)read_bound);
    /* the recording saw the frames: draws and the readback every frame */
    CHECK(tr.frames == 2u * FRAMES);
    CHECK(tr.count[FT_GLE_ReadPixels].calls >= 2u * FRAMES);
    CHECK(tr.count[FT_GLE_DrawElements].calls + tr.count[FT_GLE_DrawElementsInstanced].calls +
              tr.count[FT_GLE_DrawArrays].calls >=
          2u * FRAMES);
    CHECK(tr.read_bytes_max >= frame_bytes);
    unsigned bad = check_trace(&tr, method, read_bound);
    if (bad != 0u) {
        fprintf(stderr, "%s %s: %u rule(s) broken after init\n", backend, method, bad);
    }
    CHECK(bad == 0u);
    /* the table is back to the loaded entry points */
    CHECK(ft_gl_check(gl, "after the traced frames", NULL) == FT_OK);
    ft_app_shutdown(&g_app);
    return ft_test_result("test_gl_discipline");
}
