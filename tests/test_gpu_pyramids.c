/* test_gpu_pyramids.c - the heights and every avg/min/max pyramid level on
 * the GPU equal the CPU arrays, read back through a vertex-texture fetch (the
 * way the LOD methods read them).
 *
 * usage: test_gpu_pyramids BACKEND float|packed
 * For each texture, one GL_POINT per texel: the vertex shader fetches the
 * texel (texelFetch, packed decode as in terrain.vert.glsl) and writes it to
 * the matching pixel of an RGBA32F target; the test reads it back. Float
 * textures must match bit for bit; packed ones within one 24-bit step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "test_util.h"

static const char k_scene[] =
    "[scene]\nmethod = brute\n[view]\nwidth_px = 64\nheight_px = 64\n"
    "[terrain]\ndem =\nsynth_side = 97\nsynth_spacing_m = 25\nsynth_relief_m = 1800\n"
    "synth_seed = 11\nsynth_octaves = 7\n"
    "[gpu]\npyramid_textures = 1\ntexture_bytes = 8M\n"
    "[budget]\nheights_bytes = 64K\npyramids_bytes = 256K\nframe_rgba_bytes = 64K\n"
    "gpu_staging_bytes = 64K\nmethod_bytes = 128K\npng_bytes = 512K\n";

static const char k_vs[] =
    "#version 300 es\nprecision highp float;\n"
    "uniform highp sampler2D u_tex; uniform vec2 u_size; uniform vec2 u_pack;\n"
    "in vec2 a_texel; out float v_value;\n"
    "void main() {\n"
    "  vec4 t = texelFetch(u_tex, ivec2(a_texel), 0);\n"
    "  v_value = t.r;\n"
    "  if (u_pack.y > 0.0) {\n"
    "    float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));\n"
    "    v_value = u_pack.x + u_pack.y * (q / 16777215.0);\n"
    "  }\n"
    "  gl_Position = vec4((a_texel + 0.5) / u_size * 2.0 - 1.0, 0.0, 1.0);\n"
    "  gl_PointSize = 1.0;\n"
    "}\n";
static const char k_fs[] =
    "#version 300 es\nprecision highp float;\nin float v_value; out vec4 o;\n"
    "void main() { o = vec4(v_value, 0.0, 0.0, 1.0); }\n";

static ft_app g_app;
static GLuint g_prog, g_fbo, g_rb, g_vbo;
static GLint g_u_tex, g_u_size, g_u_pack;
#define SIDE_MAX 128u
static float g_points[SIDE_MAX * SIDE_MAX * 2u];
static float g_read[SIDE_MAX * SIDE_MAX * 4u];

static GLuint shader(const ft_gl *gl, GLenum type, const char *src)
{
    GLuint s = gl->CreateShader(type);
    gl->ShaderSource(s, 1, &src, NULL);
    gl->CompileShader(s);
    GLint ok = 0;
    gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512];
        gl->GetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "probe shader: %s\n", log);
    }
    REQUIRE(ok);
    return s;
}

static void setup(const ft_gl *gl)
{
    g_prog = gl->CreateProgram();
    gl->AttachShader(g_prog, shader(gl, GL_VERTEX_SHADER, k_vs));
    gl->AttachShader(g_prog, shader(gl, GL_FRAGMENT_SHADER, k_fs));
    gl->BindAttribLocation(g_prog, 0, "a_texel");
    gl->LinkProgram(g_prog);
    GLint ok = 0;
    gl->GetProgramiv(g_prog, GL_LINK_STATUS, &ok);
    REQUIRE(ok);
    g_u_tex = gl->GetUniformLocation(g_prog, "u_tex");
    g_u_size = gl->GetUniformLocation(g_prog, "u_size");
    g_u_pack = gl->GetUniformLocation(g_prog, "u_pack");
    gl->GenRenderbuffers(1, &g_rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, g_rb);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, SIDE_MAX, SIDE_MAX);
    gl->GenFramebuffers(1, &g_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g_fbo);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g_rb);
    REQUIRE(gl->CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    gl->GenBuffers(1, &g_vbo);
}

/* Returns the largest |gpu - cpu| over the texture; -1 on a missing texel. */
static double probe(const ft_gl *gl, GLuint tex, const float *cpu, uint32_t w, uint32_t h,
                    const ft_gpu_terrain *gt)
{
    REQUIRE(w <= SIDE_MAX && h <= SIDE_MAX && tex != 0);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            g_points[(y * w + x) * 2u] = (float)x;
            g_points[(y * w + x) * 2u + 1u] = (float)y;
        }
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, g_fbo);
    gl->Viewport(0, 0, (GLsizei)w, (GLsizei)h);
    gl->Disable(GL_DEPTH_TEST);
    gl->ClearColor(-12345.0f, 0.0f, 0.0f, 0.0f);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->UseProgram(g_prog);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, tex);
    gl->Uniform1i(g_u_tex, 0);
    gl->Uniform2f(g_u_size, (float)w, (float)h);
    gl->Uniform2f(g_u_pack, gt->pack_min_m,
                  gt->format == FT_HEIGHT_FORMAT_PACKED ? gt->pack_range_m : 0.0f);
    gl->BindBuffer(GL_ARRAY_BUFFER, g_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(w * h * 2u * sizeof(float)), g_points,
                   GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->DrawArrays(GL_POINTS, 0, (GLsizei)(w * h));
    gl->ReadPixels(0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_FLOAT, g_read);
    REQUIRE(gl->GetError() == GL_NO_ERROR);
    double worst = 0.0;
    for (uint32_t i = 0; i < w * h; ++i) {
        if (g_read[i * 4u + 3u] != 1.0f) {
            return -1.0; /* texel never written */
        }
        double d = fabs((double)g_read[i * 4u] - (double)cpu[i]);
        if (d > worst) worst = d;
    }
    return worst;
}

int main(int argc, char **argv)
{
    ft_scene s;
    ft_error err;
    REQUIRE(argc >= 3);
    ft_scene_defaults(&s);
    REQUIRE(ft_scene_parse(&s, k_scene, "k_scene", &err) == FT_OK);
    REQUIRE(ft_backend_from_name(argv[1], &s.backend));
    int packed = strcmp(argv[2], "packed") == 0;
    s.height_format = packed ? FT_HEIGHT_FORMAT_PACKED : FT_HEIGHT_FORMAT_FLOAT;
    ft_status st = ft_app_init(&g_app, &s, &err);
    if (st != FT_OK) fprintf(stderr, "init: %s\n", err.text);
    REQUIRE(st == FT_OK);
    const ft_gl *gl = &g_app.gpu.gl;
    REQUIRE(gl->api == FT_GL_API_ES3);
    setup(gl);
    const ft_terrain *t = &g_app.terrain;
    const ft_gpu_terrain *gt = &g_app.renderer.gt;
    /* one 24-bit step of the packed range (plus float rounding of the decode) */
    double tol = packed ? 1.01 * (double)gt->pack_range_m / 16777215.0 + 1e-4 : 0.0;

    CHECK(gt->pyramid_levels_avg == t->pyr.avg_levels);
    CHECK(gt->pyramid_levels_minmax == t->pyr.minmax_levels);
    double worst = probe(gl, gt->heights_tex, t->heights_m, t->width, t->height, gt);
    printf("heights %ux%u: max |gpu - cpu| = %.3g m\n", t->width, t->height, worst);
    CHECK(worst >= 0.0 && worst <= tol);
    int textures = 1;
    for (uint32_t l = 1; l < t->pyr.avg_levels; ++l) {
        const ft_pyramid_level *lv = &t->pyr.avg[l];
        worst = probe(gl, gt->avg_tex[l], lv->avg_m, lv->width, lv->height, gt);
        CHECK(worst >= 0.0 && worst <= tol);
        ++textures;
    }
    for (uint32_t l = 0; l < t->pyr.minmax_levels; ++l) {
        const ft_pyramid_level *lv = &t->pyr.minmax[l];
        double wmin = probe(gl, gt->min_tex[l], lv->min_m, lv->width, lv->height, gt);
        double wmax = probe(gl, gt->max_tex[l], lv->max_m, lv->width, lv->height, gt);
        CHECK(wmin >= 0.0 && wmin <= tol);
        CHECK(wmax >= 0.0 && wmax <= tol);
        textures += 2;
    }
    printf("%s %s: %d textures checked texel by texel (tolerance %.3g m)\n", argv[1], argv[2],
           textures, tol);
    /* A wrong texture must be caught: heights compared with level-0 max. */
    worst = probe(gl, gt->heights_tex, t->pyr.minmax[0].max_m, t->pyr.minmax[0].width,
                  t->pyr.minmax[0].height, gt);
    CHECK(worst > 1.0);
    ft_app_shutdown(&g_app);
    return ft_test_result("test_gpu_pyramids");
}
