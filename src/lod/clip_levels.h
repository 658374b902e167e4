/* clip_levels.h - the clipmap cache (terrain/clip_cache.h) on the GPU: the
 * cache, its height source (the runtime's terrain, or the database behind a
 * .ftd window) and the level textures it fills, shared by the methods that
 * read heights through it (clipmap always; pgm with pgm.heights = clipmap).
 *
 * Textures: one side x side texture per level (FT_CLIP_TEX_PER_LEVEL: a
 * vertex shader binds the two levels it blends), or every level in one
 * atlas texture, level l at texel origin_px[l] (FT_CLIP_TEX_ATLAS: a vertex
 * shader that picks its level per vertex, which cannot index samplers). In
 * both, level-l sample (a, b) is at origin_px[l] + (a mod side, b mod side).
 * Texel format: the renderer's rule (float when the context samples it in
 * the vertex stage, else RGBA8 24-bit fixed point over the window's height
 * range, clamped).
 *
 * Work: init fills every level around the window's middle; select moves the
 * wanted boxes to the eye, runs at most updates_per_frame updates (read,
 * sub-image upload, commit) and then whatever the coarsest level still lacks
 * (terrain is never drawn as sky); spare runs updates while now() + the
 * slowest update seen so far fits before the deadline. Nothing waits or
 * allocates after init. */
#ifndef FT_CLIP_LEVELS_H
#define FT_CLIP_LEVELS_H

#include <stdint.h>

#include "core/camera.h"
#include "core/mem_budget.h"
#include "core/scene.h"
#include "gpu/gl_api.h"
#include "gpu/gpu_texture.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "terrain/terrain.h"

typedef enum ft_clip_tex_layout { FT_CLIP_TEX_PER_LEVEL, FT_CLIP_TEX_ATLAS } ft_clip_tex_layout;

/* When the cache keeps its CPU bounds (heights and cells' deviations per
 * level, clip_cache.h keep_bounds): over a database only (its depth range
 * needs them), or always (a method that bounds its error from them); and
 * with RANGES, every resident cell's range of the finest data
 * (ft_clip_cell_range) on the GPU too, for a vertex shader that bounds its
 * own error: an RG32F texture laid out as the heights (the atlas; GLES 3
 * with float heights only), on the unit after the heights', refreshed for
 * the cells every committed update touches (the cells west and south of it
 * too, whose corners it holds), so a cell whose four corners are resident
 * holds its range; and on the unit after that the ranges of the level's
 * blocks (ft_clip_block_bound: lo - err, hi + err), for a box too wide for
 * a few cells. */
/* A cell range's ends where the finest data are not known there. */
#define FT_CLIP_RANGE_UNBOUNDED_M 1e30f

typedef enum ft_clip_bounds_rule {
    FT_CLIP_BOUNDS_OVER_DB,
    FT_CLIP_BOUNDS_ALWAYS,
    FT_CLIP_BOUNDS_RANGES
} ft_clip_bounds_rule;

/* Spare calls an update's measured cost is remembered for. A slowest-ever
 * declaration stopped the spare time for good after one slow update (a
 * preempted read or upload longer than the spare time); with a window, such
 * an update stops it for at most this many calls (half a second at 60 Hz),
 * during which the methods draw from the resident coarser levels. */
#define FT_CLIP_COST_CALLS 32u

typedef struct ft_clip_levels {
    ft_clip_cache cache;
    ft_clip_source src;
    ft_clip_db_source db_src;      /* the source's state over a .ftd (terrain.db) */
    const ft_gl *gl;               /* select and spare upload the cache's updates */
    ft_clip_tex_layout layout;
    GLuint tex[FT_CLIP_LEVELS_MAX]; /* per level; with the atlas every entry is it */
    uint32_t origin_px[FT_CLIP_LEVELS_MAX][2];
    uint32_t tex_w, tex_h;         /* one level's texture, or the atlas */
    uint32_t atlas_cols;           /* levels a row of the atlas (1 per level: 1) */
    GLenum unit;                   /* the unit the textures were made on */
    GLenum tex_format, tex_type;
    uint32_t side, levels, updates_per_frame;
    ft_scalar_format fmt;
    uint8_t *packed;               /* update_samples_max * 4 (FT_POOL_METHOD) */
    int fill_whole;                /* the first select fills every level */
    uint32_t updates_last;         /* updates run by the last select */
    uint32_t forced_last;          /* of those, run to keep the coarsest level whole */
    uint64_t forced_updates;       /* all such updates since init */
    uint64_t forced_frames;        /* selects that ran some */
    /* spare time: an update's declared cost is the slowest update of the
     * last FT_CLIP_COST_CALLS spare calls that ran updates or had to leave
     * them for later (cost_ns, one slot a call, cost_at the current one).
     * The first call, with nothing measured, runs one update to learn it. */
    uint64_t update_ns_max;
    uint64_t cost_ns[FT_CLIP_COST_CALLS];
    uint32_t cost_at;
    uint64_t spare_updates;        /* updates run in spare time */
    uint64_t spare_deferred;       /* spare calls that left work for later */
    uint64_t read_errors;          /* source reads that failed (retried) */
    uint64_t gpu_bytes;
    /* FT_CLIP_BOUNDS_RANGES: the cells' ranges (lo, hi), the blocks' (one
     * texel a block, the same layout at 1 / FT_CLIP_BOUND_BLOCK) and their
     * staging (range_cells cells, FT_POOL_METHOD) */
    GLuint range_tex, block_range_tex;
    float top_range_m[2];          /* the coarsest level's: over all its blocks' */
    float *range_staging;
    uint32_t range_cells;
    uint64_t range_uploads;        /* sub-image uploads of ranges since init */
} ft_clip_levels;

/* CPU pool needs: the cache's staging and the database source's tiles
 * (FT_POOL_CLIP), the packed-texel staging and, with RANGES, the ranges'
 * staging (FT_POOL_METHOD). */
void ft_clip_levels_plan(const ft_scene *s, const ft_terrain *t, ft_clip_bounds_rule bounds,
                         ft_arena *a);

/* Checks the clipmap.* keys against the device (side a power of two within
 * GL_MAX_TEXTURE_SIZE, the atlas too; levels; update_samples_max), makes the
 * source, the cache and the textures on `unit` (with RANGES the ranges on
 * unit + 1: an error unless GLES 3, the atlas and float heights), and fills
 * every level. */
ft_status ft_clip_levels_init(ft_clip_levels *c, const ft_gl *gl, const ft_scene *s,
                              const ft_terrain *t, ft_clip_tex_layout layout,
                              ft_clip_bounds_rule bounds, GLenum unit, ft_arena *a,
                              ft_error *err);

/* The eye in the cache's level-0 lattice (fractional). */
void ft_clip_levels_eye(const ft_clip_levels *c, const ft_terrain *t, const double eye_m[3],
                        double *eye_i, double *eye_j);

/* Recentres on the camera's eye and runs this frame's updates (above). */
void ft_clip_levels_select(ft_clip_levels *c, const ft_terrain *t, const ft_camera *cam);

/* The frame's spare time (ft_method_ops.spare). */
void ft_clip_levels_spare(ft_clip_levels *c, uint64_t (*now)(void), uint64_t deadline_ns);

/* Over a database: cam's depth range from the resident samples' bounds (the
 * scene grid's range does not hold what is drawn once the eye leaves the
 * window); 0 when bounds are not kept or nothing is resident. */
int ft_clip_levels_fit_depth(const ft_clip_levels *c, const ft_terrain *t, ft_camera *cam,
                             double corner_cos);

/* The world frame of the cache's lattice (the runtime terrain's). */
ft_clip_world ft_clip_levels_world(const ft_terrain *t);

void ft_clip_levels_shutdown(ft_clip_levels *c, const ft_gl *gl);

#endif
