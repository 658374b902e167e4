/* renderer.h - GPU side of a scene: terrain textures, offscreen targets,
 * programs, and one frame of the selected method.
 *
 * Everything GPU-side is created in ft_renderer_init (inside the GPU budget
 * gpu.texture_bytes); a frame only sets uniforms and draws. The default
 * framebuffer is never used (it is incomplete on EGL surfaceless): colour
 * frames go to an RGBA8 target, position frames (for the error metric) to
 * an RGBA32F target where the context can render float. */
#ifndef FT_RENDERER_H
#define FT_RENDERER_H

#include <stdint.h>

#include "core/camera.h"
#include "core/mem_budget.h"
#include "core/scene.h"
#include "gpu/gpu.h"
#include "gpu/overlay.h"
#include "gpu/program.h"
#include "gpu/shade.h"
#include "lod/method.h"
#include "terrain/terrain.h"

#define FT_TERRAIN_TEXTURES_MAX (1u + 3u * FT_PYRAMID_LEVELS_MAX)

#define FT_VOID_STRIP_ROWS 16u /* rows of cells built and uploaded at a time */

typedef struct ft_frame_stats {
    uint64_t triangles;
    uint32_t draw_calls;
    uint32_t tiles;         /* bintree: tiles drawn (0 for other methods) */
    uint64_t raycast_px;    /* pgrid: pixels ray cast this frame */
    uint64_t unmeasured_px; /* pixels showing void-filled (invented) terrain */
    int internal_fault;     /* an invariant failed (core/invariant.h): annunciated */
    uint64_t terrain_px;    /* pgrid: terrain pixels of the error buffer (its mesh
                               and envelopes): raycast_px's denominator */
    double tau_achieved_px; /* bintree: screen-space bound the selection meets */
    double tau_target_px;   /* bintree: the selection's target (method.h) */
    int budget_hit;         /* bintree: the tile budget forced a coarser tau */
    int back_faces_culled;  /* bintree: back faces culled (the eye above the surface) */
    uint32_t envelopes;     /* pgrid: envelopes drawn (2: the lower one too) */
    uint32_t cache_levels_behind;       /* clipmap: its cache's levels behind */
    uint64_t cache_samples_outstanding; /* clipmap: samples still to upload */
    int cache_coarser;      /* clipmap: the eye's surroundings drawn from a level > 0 */
    uint32_t cache_forced_updates; /* clipmap: updates run in the frame to keep the
                                      coarsest level whole */
    double select_ms; /* LOD selection on the CPU (0 when the view did not change) */
    double cpu_ms;   /* frame submission on the CPU */
    double gpu_ms;   /* submission + glFinish (measurement mode) */
    double gpu_timer_ms; /* GPU time of the draw from a timer query; -1 if none */
    /* depth buffer of the frame: bits, float or fixed point, the camera's
     * near/far, and the eye-depth span of one depth step at the far plane
     * (ft_camera_depth_step_m): the worst depth resolution of the frame */
    uint32_t depth_bits;
    int depth_float;
    double near_m, far_m;
    double depth_res_far_m;
} ft_frame_stats;

typedef struct ft_renderer {
    ft_gpu_context *gpu;
    const ft_gl *gl;
    const ft_terrain *terrain;
    const ft_scene *scene;
    uint32_t width_px, height_px;
    GLuint vao; /* one VAO when the context has them (core profile needs one) */
    GLuint fbo_color, rb_color, rb_depth;
    uint32_t depth_bits; /* the depth buffer the targets got: 32 (float), 24 or 16 */
    int depth_float;     /* 1: GL_DEPTH_COMPONENT32F */
    GLuint fbo_pos, rb_pos;
    int has_pos_target;
    ft_gpu_terrain gt;
    ft_terrain_program prog_color, prog_pos;
    ft_terrain_program prog_color_coarse, prog_pos_coarse; /* see ft_terrain_program.coarse */
    ft_method method;
    GLuint present_program, present_vbo; /* display != none only */
    uint8_t *rgba;  /* FT_POOL_FRAME_RGBA, width*height*4, row 0 = top */
    float *pos;     /* FT_POOL_FRAME_POS, width*height*4 (NULL if no float target) */
    ft_overlay overlay; /* the failure annunciation (red cross + reason) */
    GLuint timer_query; /* GL_TIME_ELAPSED around the frame's draw (0: none) */
    float clear_rgb[3]; /* colour frames' background (sky); tests may change it */
    ft_shade_state shade; /* palette, bands, aircraft altitude (set each frame) */
    GLuint void_tex;        /* unmeasured cells (0: the terrain has no filled sample) */
    uint64_t unmeasured_px; /* pixels of the last readback showing unmeasured terrain */
    uint64_t gpu_bytes;
    uint64_t frames;
    /* glGetError in the frame path. 0: none (the safety-critical frame loop
     * never branches on glGetError: after init a frame only sets state,
     * draws and reads back). 1: one drain at the end of each frame (colour
     * readback) and of present, each error counted in gl_errors and the
     * frame failed with FT_ERR_GPU naming the step. Default set by
     * ft_renderer_init: 1 in Debug and RelWithDebInfo builds (development
     * and tests), 0 in Release and MinSizeRel (deployment); a test or soak
     * may set either. */
    int gl_error_checks;
    uint64_t gl_errors;
    /* Optional observer called at the end of every colour readback (the
     * frame's last GL step), for soak tests and instrumentation; NULL: none. */
    void (*frame_done)(void *ctx, const struct ft_renderer *r);
    void *frame_done_ctx;
} ft_renderer;

/* Adds this scene's CPU pool needs (readback, staging, method) to the plan. */
void ft_renderer_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a);

ft_status ft_renderer_init(ft_renderer *r, ft_gpu_context *gpu, const ft_scene *s,
                           const ft_terrain *t, ft_arena *a, ft_error *err);

/* Camera for a pose over this terrain (depth range picked from the terrain). */
ft_status ft_renderer_camera(const ft_renderer *r, const ft_pose *pose, ft_camera *cam,
                             ft_error *err);
ft_status ft_camera_for_pose(const ft_terrain *t, const ft_pose *pose, double fovy_deg,
                             uint32_t width_px, uint32_t height_px, ft_camera *cam,
                             ft_error *err);

/* The method's per-frame LOD selection for cam (CPU only; ft_renderer_draw
 * runs it too when it has not run for this view). Separate so the frame
 * loop can time it as its own stage. */
void ft_renderer_select(ft_renderer *r, const ft_camera *cam);
/* After the selection: the depth range of what the method draws when that
 * is not the scene's grid (the clipmap over a database); else unchanged. */
void ft_renderer_fit_depth(const ft_renderer *r, ft_camera *cam);

/* Test and debugging aid, init time only: relinks the colour program so a
 * transform feedback draw captures gl_Position (4 floats) and v_morph (1
 * float) per vertex (GLES 3 only). Rendering is unchanged. */
#define FT_CAPTURE_FLOATS_PER_VERTEX 5u
ft_status ft_renderer_enable_capture(ft_renderer *r, ft_error *err);
/* The same with the named vertex outputs (1..FT_CAPTURE_VARYINGS_MAX,
 * interleaved in this order: a vec3 takes 3 floats, a float 1). */
#define FT_CAPTURE_VARYINGS_MAX 8u
ft_status ft_renderer_enable_capture_of(ft_renderer *r, const char *const *varyings,
                                        uint32_t count, ft_error *err);

/* Binds target fbo, sets the viewport and the depth state every terrain
 * pass draws with, and clears colour (to clear_rgba) and depth. The bench's
 * oracle draws its own mesh after it, like the renderer's passes. */
void ft_renderer_begin_pass(const ft_renderer *r, GLuint fbo, const float clear_rgba[4]);
/* The colour state of a frame seen from cam: the renderer's palette and
 * bands at the pose's altitude, the void map relative to the eye. */
void ft_renderer_frame_shade(const ft_renderer *r, const ft_camera *cam, ft_shade_state *out);

/* Draws one colour frame into the RGBA8 target. */
ft_status ft_renderer_draw(ft_renderer *r, const ft_camera *cam, ft_frame_stats *st,
                           ft_error *err);
/* Draws the failure annunciation (red cross, reason text) over the colour
 * target's current frame. */
ft_status ft_renderer_draw_annunciation(ft_renderer *r, const char *reason, ft_error *err);

/* GPU time of the last ft_renderer_draw from the timer query, once the GPU
 * is done (after ft_renderer_read_rgba); -1 when the context has no timer
 * queries or the measurement was disjoint (GL_GPU_DISJOINT_EXT). */
double ft_renderer_gpu_timer_ms(ft_renderer *r);

/* Reads the colour target into r->rgba (row 0 = top). */
ft_status ft_renderer_read_rgba(ft_renderer *r, ft_error *err);
/* Draws the position pass and reads it into r->pos (row 0 = top).
 * FT_ERR_UNSUPPORTED when the context cannot render float (GLES 2). */
ft_status ft_renderer_draw_positions(ft_renderer *r, const ft_camera *cam, ft_error *err);

/* Draws the colour target onto framebuffer 0 (the window surface); the
 * platform then presents it (ft_plat_gpu_present). Display scenes only. */
ft_status ft_renderer_present(ft_renderer *r, ft_error *err);

void ft_renderer_shutdown(ft_renderer *r);

/* Staging bytes the unmeasured-cell texture's upload takes (a terrain that
 * may have void-filled samples: planned by the app). */
size_t ft_renderer_void_staging_bytes(uint32_t width);
/* Palette for the next frame (presentation.palette, or a GPIO discrete). */
void ft_renderer_set_palette(ft_renderer *r, ft_palette p);

#endif
