/* method.h - the terrain methods behind one small interface. A method owns
 * its GPU buffers (made at init) and draws with the renderer's terrain
 * program; per frame it only selects and draws. */
#ifndef FT_METHOD_H
#define FT_METHOD_H

#include <stdint.h>

#include "core/camera.h"
#include "core/mem_budget.h"
#include "core/scene.h"
#include "gpu/gl_api.h"
#include "gpu/gpu_texture.h"
#include "gpu/program.h"
#include "lod/bintree.h"
#include "lod/bintree_cache.h"
#include "lod/clip_levels.h"
#include "lod/clipmap.h"
#include "lod/pgm.h"
#include "lod/pgrid.h"
#include "terrain/clip_source.h"
#include "terrain/terrain.h"

typedef struct ft_method_draw_stats {
    uint64_t triangles;
    uint32_t draw_calls;
    uint32_t tiles;          /* bintree: tiles drawn */
    uint64_t raycast_px;     /* pgrid: pixels ray cast */
    uint64_t terrain_px;     /* pgrid: pixels the mesh or an envelope covers */
    double tau_achieved_px;  /* bintree: the screen-space bound the tiles meet;
                                pgrid: the bound met (gamma, or raised by the
                                budget, or the mesh's own without ray casting);
                                clipmap: the bound of what it drew (+INF: none) */
    double tau_target_px;    /* bintree: the selection's target (tau, or raised by the
                                budget); tau_achieved_px is larger where a leaf
                                tile is itself over it. 0 for other methods */
    int budget_hit;          /* bintree: tau was raised to fit the tile budget;
                                pgrid: the ray-casting budget raised gamma */
    int back_faces_culled;   /* bintree: the eye was above the surface, back faces culled */
    uint32_t envelopes;      /* pgrid: envelopes drawn (2 with the lower one: the eye off
                                the grid or not above the terrain's top; src/lod/pgrid.h 3) */
    /* clipmap: how far behind its cache is at this frame's draw */
    uint32_t cache_levels_behind;       /* levels whose valid box is not the wanted one */
    uint64_t cache_samples_outstanding; /* samples still to read and upload */
    int cache_coarser;                  /* the eye's surroundings drawn from a level > 0 */
    uint32_t cache_forced_updates;      /* updates this frame ran to keep the coarsest
                                           level whole (after a jump: all of it) */
} ft_method_draw_stats;

typedef struct ft_brute {
    GLuint vbo, ibo;
    uint32_t patch_cells;   /* template side in cells */
    uint32_t index_count;
    uint32_t window_side;   /* most samples per side drawn (brute.max_vertices) */
    uint64_t gpu_bytes;
} ft_brute;

typedef struct ft_bintree_method {
    ft_bintree bt;
    /* vbo: batch_tiles copies of the template, each vertex (a, b, slot);
     * ibo: their triangles (16-bit) */
    GLuint vbo, ibo;
    GLuint dia_tex;                /* geomorph: per lattice diamond (err, z0, z1, 0), unit 1 */
    GLuint zb_tex;                 /* geomorph below the samples: height blocks, unit 4 */
    GLuint twist_tex;              /* sub-sample levels: the twist atlas (unit 2) */
    GLuint vtx_tex;                /* GLES 3: the one-fetch vertex table (unit 3, RGBA32F) */
    ft_scalar_format twist_fmt;
    uint32_t index_count, triangles_per_tile; /* of one tile */
    uint32_t batch_tiles; /* tiles a draw: the shader's u_bt_tiles, the slots in vbo */
    float *inst; /* tiles_max * (apex, left) grid coordinates (FT_POOL_METHOD) */
    double tau_px;    /* bintree.tau_px */
    double lod_scale; /* degradation: the selection targets tau_px * lod_scale */
    int morph, es3;
    int vertex_table; /* GLES 3 and bintree.vertex_table: vtx_tex is used */
    int cull_back_faces;   /* bintree.cull_back_faces */
    double morph_width;    /* bintree.morph_width */
    uint64_t gpu_bytes;
    /* the last selection and the view it was made for */
    ft_view_key sel_view;
    ft_bt_select_stats sel;
    /* bintree.heights = clipmap: the tiles over the clipmap cache's lattice
     * (lod/bintree_cache.h) instead of bt (whose tables are not built), the
     * cache's levels in one atlas on unit 1 (cl.tex[0]); inst then holds
     * the tiles relative to btc.origin. eye_rel: the eye relative to that
     * origin at the last selection (level-0 samples), which the shader gets
     * split into an integer and a fractional part. */
    int clip;
    ft_clip_levels cl;
    ft_bt_cache btc;
    double eye_rel[2];
} ft_bintree_method;

/* Persistent grid mapping (src/lod/pgm.h, shaders/pgm.vert.glsl). The grid is
 * drawn in bands of band_rows cell rows with one 16-bit template band (vbo:
 * (column, row in band) per vertex; ibo: the band's triangles row by row,
 * so the last, shorter band draws a prefix), the same on every context. */
typedef struct ft_pgm_method {
    GLuint vbo, ibo, atlas_tex;
    uint32_t cols, rows;      /* grid vertices */
    uint32_t band_rows;       /* cell rows per band (vertex rows - 1) */
    uint32_t band_count;
    uint32_t atlas_w, atlas_h;
    uint32_t levels;          /* avg pyramid levels (level 0 = heights texture) */
    float level_px[FT_PYRAMID_LEVELS_MAX][4]; /* atlas origin xy, size zw per level */
    ft_scalar_format atlas_fmt;
    uint64_t gpu_bytes;
    /* the last sampling set-up and the view it was made for */
    ft_view_key sel_view;
    ft_pgm_sampling sampling;
    /* pgm.heights = clipmap: the levels are the clip cache's, all in one
     * atlas on unit 1 (cl.tex[0]); clip_view is what the shader is given
     * for the last selection (pgm.h; u_pgm_level then holds per level base
     * mod side and the eye's offset from base, shaders/pgm_grid.glsl) */
    int clip;
    ft_clip_levels cl;
    ft_clip_world cl_world;   /* the lattice's world frame (clip_max_in) */
    ft_pgm_clip_view clip_view;
    double transition_samples;
} ft_pgm_method;

/* Error-bounded projective grid (src/lod/pgrid.h): the pgm grid (reused: its
 * band buffers and avg atlas, its draw) with the pgrid vertex shader, plus a
 * min/max atlas, the error buffer (RGBA8 texture + depth, drawn with
 * err_prog) and the ray-cast pass (rc_prog, GLES 3). */
typedef struct ft_pgrid_method {
    ft_pgm_method pgm;
    GLuint mm_tex;                 /* min | max atlas (levels >= FT_PGRID_ATLAS_L0) */
    uint32_t mm_half_w, mm_h, mm_levels;
    float mm_level_px[FT_PYRAMID_LEVELS_MAX][4];
    ft_scalar_format mm_fmt;
    GLuint err_tex, err_depth, err_fbo, rc_prog, quad_vbo;
    /* the ray caster (GLES 3, src/lod/pgrid.h 4): the max atlas its traversal
     * reads (levels >= 1; level 0 comes from the heights), and the tile pass
     * that lets it run only on the screen tiles holding a pixel to ray cast
     * (tile_tex: a tile's largest dilated code, tiles_w x tiles_h) */
    GLuint rc_max_tex, tile_tex, tile_fbo, tile_prog;
    float rc_max_level_px[FT_PYRAMID_LEVELS_MAX][4];
    uint32_t tile_px, tiles_w, tiles_h;
    GLint ut_err, ut_size, ut_tile_px;
    ft_terrain_program *err_prog; /* in FT_POOL_METHOD */
    int err_prog_built;
    /* GLES 3: the picture pass writes the error buffer as its second colour
     * attachment and the envelopes (a program of their own, env_prog_built)
     * test against the picture's depth; err_fbo and err_prog then serve a
     * position pass of a view the picture did not see */
    int mrt, env_prog_built;
    /* 0: the lower envelope only when the eye may see the surface from
     * below (src/lod/pgrid.h 3); 1 on every frame, -1 never: for the test
     * that shows the rule changes no decision and leaving it out does */
    int lower_envelope_force;
    /* the tight bound (src/lod/pgrid.h 6; GLES 3 with ray casting): residual
     * atlas (levels >= FT_PGRID_RES_L0), the vertex pass's and quad-bound
     * pass's targets (grid-sized RGBA32F) and programs */
    int tight;
    GLuint res_tex, vtx_tex, slope_tex, vtx_fbo, quad_tex, quad_fbo, quad_prog;
    /* the vertex-bound pass: per grid vertex its slope, delta and the bound
     * of the quad it ends (src/lod/pgrid.h 6) */
    GLuint shape_tex, shape_fbo, shape_prog;
    uint32_t res_levels;
    float res_level_px[FT_PYRAMID_LEVELS_MAX][4];
    ft_terrain_program *vtx_prog; /* in FT_POOL_METHOD */
    int vtx_prog_built;
    /* over the cache the quad-bound pass reads the cache's levels and
     * ranges with pgm's uniforms: a terrain program (FT_POOL_METHOD) in
     * place of quad_prog */
    ft_terrain_program *quad_clip_prog;
    int quad_clip_built;
    GLint uq_vtx, uq_res, uq_heights, uq_grid_size, uq_cell_m, uq_origin, uq_pack, uq_drop;
    GLint uq_res_levels, uq_res_level[FT_PYRAMID_LEVELS_MAX];
    uint64_t terrain_px;            /* the last decision's terrain pixels (undilated code > 0) */
    /* the column warp (src/lod/pgrid.h 1; pgrid.columns = error): T_b per
     * band of the sampling rectangle (FT_PGRID_COL_BANDS + 1 knots), the
     * knots each pack buffer's frame was drawn with, and the band histograms
     * of the last buffer's codes */
    int col_warp;
    float col_t[FT_PGRID_COL_BANDS + 1], col_t_next[FT_PGRID_COL_BANDS + 1];
    float col_t_pbo[2][FT_PGRID_COL_BANDS + 1];
    uint32_t band_hist[FT_PGRID_COL_BANDS][256];
    /* the late decision (GLES 3 with ray casting): the error buffer goes into
     * pixel-pack buffer pack_pbo[pbo_next] without waiting; the next frame
     * maps it (complete by then) and decides from it */
    GLuint pack_pbo[2];
    int pbo_full[2];
    uint32_t pbo_next;
    int late;
    uint32_t w_px, h_px;
    int distribution, ray_casting, es3;
    double gamma_px;
    double lod_scale;               /* degradation: ray cast over gamma_px * lod_scale */
    uint64_t raycast_max_px;
    uint8_t *readback;              /* w * h * 4, FT_POOL_METHOD */
    uint8_t *work;                  /* w * h */
    uint32_t hist[256];
    /* the last frame's decision (colour pass; the position pass reuses it) */
    double dec_eye_m[3], dec_fwd[3], dec_up[3];
    uint32_t thr;                   /* code threshold, 256 = none */
    uint64_t rc_px;                 /* pixels ray cast */
    double achieved_px;
    double leaf_px;                 /* over the cache: the ray caster's leaves' bound (pgrid.h 7) */
    int budget_hit;
    int have_decision;
    uint64_t gpu_bytes;
} ft_pgrid_method;

/* Geometry clipmaps (src/lod/clipmap.h, shaders/clipmap.vert.glsl): the
 * clip cache with one height texture per level (lod/clip_levels.h), the
 * block + stitch-strip template. */
typedef struct ft_clipmap_method {
    ft_clip_levels cl;
    ft_cm_layout layout;           /* the last draw's */
    GLuint vbo, ibo;
    uint32_t block_indices, strip_indices;
    double transition_samples;
    ft_view_key sel_view;
    ft_cm_bound bound;             /* the last draw's (clipmap.h) */
    uint64_t gpu_bytes;            /* the template's (the cache's: cl.gpu_bytes) */
} ft_clipmap_method;

/* clipmap's uniforms (shaders/clipmap.vert.glsl) */
#define FT_CM_UNIFORMS(X)                       \
    X(FT_CM_U_TEX0, "u_cm_tex0", 1u)            \
    X(FT_CM_U_TEX1, "u_cm_tex1", 1u)            \
    X(FT_CM_U_PLACE, "u_cm_place", 1u)          \
    X(FT_CM_U_AXES, "u_cm_axes", 1u)            \
    X(FT_CM_U_CLAMP, "u_cm_clamp", 1u)          \
    X(FT_CM_U_DATA, "u_cm_data", 1u)            \
    X(FT_CM_U_MBOX, "u_cm_mbox", 1u)            \
    X(FT_CM_U_LEVEL, "u_cm_level", 1u)          \
    X(FT_CM_U_LATTICE, "u_cm_lattice", 1u)
enum ft_cm_uniform { FT_CM_UNIFORMS(FT_UNIFORM_ENUM) FT_CM_U_COUNT };

typedef struct ft_method {
    ft_method_kind kind;
    union {
        ft_brute brute;
        ft_bintree_method bintree;
        ft_pgm_method pgm;
        ft_pgrid_method pgrid;
        ft_clipmap_method clipmap;
    } u;
} ft_method;

/* What one frame of a method can cost at most, from its fixed capacities
 * (printed by `fixterrain budget`). */
typedef struct ft_method_worst {
    uint64_t triangles;  /* every triangle submitted in a frame, all passes */
    uint64_t raycast_px; /* pixels ray cast in a frame */
    char rule[256];      /* how the numbers follow from the capacities */
} ft_method_worst;

/* One method's code behind the name the scene selects (FT_METHOD_LIST): a
 * table of entry points each method file defines. NULL entries: select
 * (nothing to select per frame), set_lod_scale (no LOD knob),
 * vertex_defines (one shader variant), vertex_defines_coarse (one program),
 * colour_defines (the colour fragment shader as it is). */
typedef struct ft_method_ops {
    const char *vertex_shader; /* embedded name */
    /* the scene's vertex shader when it is not always vertex_shader (bintree
     * over the clipmap cache), else NULL */
    const char *(*vertex_shader_of)(const ft_scene *s);
    ft_uniform_list uniforms;  /* its own uniforms: ft_terrain_program.method_u */
    const char *(*vertex_defines)(const ft_scene *s, int es3);
    const char *(*vertex_defines_coarse)(const ft_scene *s, int es3);
    const char *(*colour_defines)(const ft_scene *s, int es3);
    void (*plan)(const ft_scene *s, const ft_terrain *t, ft_arena *a);
    ft_status (*init)(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                      ft_arena *a, ft_error *err);
    void (*select)(ft_method *m, const ft_terrain *t, const ft_camera *cam);
    void (*draw)(ft_method *m, const ft_gl *gl, const ft_terrain_program *p,
                 const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st);
    void (*set_lod_scale)(ft_method *m, double scale);
    /* Deferred work (clipmap: the cache's reads and uploads) run after the
     * frame while now() + its declared cost <= deadline_ns; NULL: none. */
    void (*spare)(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns);
    /* After select: sets cam's depth range from what the method will draw
     * when that is not the scene's grid (clipmap over a database); returns 1
     * when it did. NULL or 0: the grid's range stands. */
    int (*fit_depth)(const ft_method *m, const ft_terrain *t, ft_camera *cam, double corner_cos);
    uint64_t (*gpu_bytes)(const ft_method *m);
    void (*worst)(const ft_method *m, const ft_terrain *t, ft_method_worst *w);
    void (*shutdown)(ft_method *m, const ft_gl *gl);
} ft_method_ops;

/* The method's table, NULL when this build left the method out. */
const ft_method_ops *ft_method_ops_of(ft_method_kind kind);

/* The calls below go through the table of the scene's (or m's) method. */

/* The vertex shader (embedded name) the scene's method draws with. */
const char *ft_method_vertex_shader(const ft_scene *s);
/* Lines placed before the vertex shader's body: the compile-time variant
 * the scene needs (bintree: sub-sample levels, vertex table), "" for none. */
const char *ft_method_vertex_defines(const ft_scene *s, int es3);
/* The variant for tiles whose every vertex is on a sample, when the method
 * draws those with a program of their own (bintree, GLES 3, sub-sample
 * levels and the vertex table), else NULL. */
const char *ft_method_vertex_defines_coarse(const ft_scene *s, int es3);
/* Lines placed before the colour pass's fragment shader (after the colour
 * parts): what the method adds to the picture (pgrid: its error buffer as a
 * second output), "" for nothing. */
const char *ft_method_colour_defines(const ft_scene *s, int es3);
#define FT_METHOD_COLOUR_DEFINES_MAX 64u

/* CPU pool needs (FT_POOL_METHOD) of the scene's method. */
void ft_method_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a);
/* FT_ERR_UNSUPPORTED when the build left the scene's method out. */
ft_status ft_method_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                         ft_arena *a, ft_error *err);
/* Binds the method's vertex state and draws; the program is already in use. */
void ft_method_draw(ft_method *m, const ft_gl *gl, const ft_terrain_program *p,
                    const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st);
/* Per-frame LOD selection for the camera (no-op when the view is unchanged
 * or the method selects nothing); ft_method_draw calls it too. */
void ft_method_select(ft_method *m, const ft_terrain *t, const ft_camera *cam);
/* Coarsens the LOD by scale >= 1 (the degradation policy, src/lod/degrade.h):
 * bintree draws to tau_px * scale, pgrid ray casts only the pixels over
 * gamma_px * scale (its achieved bound is reported). Returns 0 when the method has no LOD
 * knob (brute, pgm: the scale is then ignored). */
int ft_method_set_lod_scale(ft_method *m, double scale);
/* Runs the method's deferred work in the frame's spare time: only while
 * now() plus the work's declared cost stays before deadline_ns (the frame
 * loop calls it after the frame, with the next frame's start). */
void ft_method_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns);

/* The method's depth range for cam after select (ft_method_ops.fit_depth);
 * 0 when the scene grid's range stands. */
int ft_method_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                        double corner_cos);
/* 1 when the scene's method reads its heights through the clipmap cache
 * (clipmap; pgm, pgrid and bintree with their heights = clipmap): over a
 * .ftd it draws the database on past the window. */
int ft_method_reads_cache(const ft_scene *s);
/* The clipmap cache m reads its heights through, NULL for none. */
const ft_clip_cache *ft_method_cache(const ft_method *m);
uint64_t ft_method_gpu_bytes(const ft_method *m);
void ft_method_worst_case(const ft_method *m, const ft_terrain *t, ft_method_worst *w);
void ft_method_shutdown(ft_method *m, const ft_gl *gl);

/* The per-method tables (each file defines its own). */
extern const ft_method_ops ft_brute_ops;
extern const ft_method_ops ft_bintree_ops;
extern const ft_method_ops ft_pgm_ops;
extern const ft_method_ops ft_pgrid_ops;
extern const ft_method_ops ft_clipmap_ops;

/* pgrid draws with the pgm grid: pgm's entry points, typed. */
#if FT_WITH_METHOD_PGM || FT_WITH_METHOD_PGRID
/* pgm's uniforms (shaders/pgm.vert.glsl): the first rows of pgrid's list
 * too, which draws with the same grid and these indices. */
#define FT_PGM_UNIFORMS(X)                                        \
    X(FT_PGM_U_ATLAS, "u_pgm_atlas", 1u)                         \
    X(FT_PGM_U_ATLAS_SIZE, "u_pgm_atlas_size", 1u)               \
    X(FT_PGM_U_ATLAS_PACK, "u_pgm_atlas_pack", 1u)               \
    X(FT_PGM_U_GRID, "u_pgm_grid", 1u)                           \
    X(FT_PGM_U_FWD, "u_pgm_fwd", 1u)                             \
    X(FT_PGM_U_RIGHT, "u_pgm_right", 1u)                         \
    X(FT_PGM_U_UP, "u_pgm_up", 1u)                               \
    X(FT_PGM_U_RECT, "u_pgm_rect", 1u)                           \
    X(FT_PGM_U_EYE, "u_pgm_eye", 1u)                             \
    X(FT_PGM_U_LEVEL, "u_pgm_level", FT_PYRAMID_LEVELS_MAX)
enum ft_pgm_uniform { FT_PGM_UNIFORMS(FT_UNIFORM_ENUM) FT_PGM_U_COUNT };
/* pgm.heights = clipmap adds these to pgm's list (pgrid has none of them) */
#define FT_PCM_UNIFORMS(X)                                        \
    X(FT_PCM_U_BOX, "u_pcm_box", FT_CLIP_LEVELS_MAX)             \
    X(FT_PCM_U_CLAMP, "u_pcm_clamp", 1u)                         \
    X(FT_PCM_U_MISC, "u_pcm_misc", 1u)
enum { FT_PCM_U_BEFORE_ = FT_PGM_U_COUNT - 1, FT_PCM_UNIFORMS(FT_UNIFORM_ENUM) FT_PCM_U_COUNT };

/* The grid pgm draws: from pgm's keys, or pgrid's (pgrid.grid). */
typedef struct ft_pgm_grid_desc {
    uint32_t cols, rows;            /* grid vertices */
    ft_height_format height_format; /* gpu.height_format: the avg atlas's too */
    int clip;                       /* heights from the clip cache: no avg atlas */
} ft_pgm_grid_desc;

void ft_pgm_method_plan(const ft_pgm_grid_desc *g, const ft_terrain *t, ft_arena *a);
ft_status ft_pgm_method_init(ft_pgm_method *m, const ft_gl *gl, const ft_pgm_grid_desc *g,
                             const ft_terrain *t, ft_arena *a, ft_error *err);
/* The heights from the clipmap cache (after ft_pgm_method_init with clip):
 * its levels in one atlas on unit 1 (clip_levels.h, with `bounds`). */
ft_status ft_pgm_method_clip_init(ft_pgm_method *pm, const ft_gl *gl, const ft_scene *s,
                                  const ft_terrain *t, ft_clip_bounds_rule bounds, ft_arena *a,
                                  ft_error *err);
/* The frame's selection: over the cache, the cache moved to the eye and
 * this frame's updates run, every frame; then ft_pgm_method_view. */
void ft_pgm_method_select(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam);
/* The sampling camera for cam over what is resident (kept while the view is
 * the same): a draw's, which never moves the cache. */
void ft_pgm_method_view(ft_pgm_method *m, const ft_terrain *t, const ft_camera *cam);
/* Over the cache: its updates in the frame's spare time, and the depth
 * range of what it holds (ft_method_ops.spare, .fit_depth); nothing, 0
 * over the window's pyramid. */
void ft_pgm_method_spare(ft_pgm_method *m, uint64_t (*now)(void), uint64_t deadline_ns);
int ft_pgm_method_fit_depth(const ft_pgm_method *m, const ft_terrain *t, ft_camera *cam,
                            double corner_cos);
/* Cell rows drawn by band b (the last band may be shorter). */
uint32_t ft_pgm_band_cell_rows(const ft_pgm_method *m, uint32_t b);
/* Binds the avg atlas (unit 1) and sets program p's pgm uniforms for the
 * selected sampling (u_pgm_grid with band row 0), without drawing. */
void ft_pgm_method_bind(const ft_pgm_method *m, const ft_gl *gl,
                        const ft_terrain_program *p);
/* Over the cache: what a shader gets for level l (shaders/pgm_grid.glsl):
 * u_pgm_level[l] (base mod side, eye - base 2^l) and u_pcm_box[l] (the
 * resident samples from base, inclusive), from the last view. */
void ft_pgm_method_clip_level(const ft_pgm_method *m, uint32_t l, float level[4], float box[4]);
void ft_pgm_method_draw(ft_pgm_method *m, const ft_gl *gl, const ft_terrain_program *p,
                        const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st);
void ft_pgm_method_shutdown(ft_pgm_method *m, const ft_gl *gl);
#endif

#endif
