/* app.h - one renderer instance from a scene: plan the budgets, reserve the
 * arena once, load the terrain into it, open the GPU, lock the arena.
 *
 * Init order (each step fails with a message naming what and why):
 *   validate the scene, and refuse a presentation part this build left out
 *   (naming the key and the FIXTERRAIN_WITH_* option) -> probe terrain
 *   (header only) -> plan every pool -> check pools against the
 *   scene's budgets -> reserve one arena (platform mmap) -> load heights and
 *   pyramids straight into their pools -> GPU context + renderer -> reference
 *   and metric buffers -> lock. After ft_app_init returns, the renderer takes
 *   no memory (tests/test_no_heap.c proves it with a wrapped allocator). */
#ifndef FT_APP_H
#define FT_APP_H

#include "core/camera.h"
#include "core/mem_budget.h"
#include "core/platform_api.h"
#include "core/scene.h"
#include "gpu/gpu.h"
#include "gpu/renderer.h"
#include "terrain/terrain.h"
#include "terrain/db_window.h"
#include "terrain/terrain_file.h"
#if FT_WITH_REFERENCE
#include "measure/metric.h"
#include "measure/ref_window.h"
#include "measure/reference.h"
#endif

#define FT_POOL_TABLE_TEXT_MAX 2048u

typedef enum ft_dem_kind { FT_DEM_SYNTH = 0, FT_DEM_HGT, FT_DEM_FTT, FT_DEM_FTD } ft_dem_kind;

typedef struct ft_app {
    ft_scene scene;
    ft_arena arena;
    void *arena_memory;
    size_t arena_bytes;
    ft_dem_kind dem_kind;
    ft_tfile_header tfile_header; /* between probe and load of a .ftt */
    ft_dbw dbw;                   /* between probe and load of a .ftd window */
    ft_dbw_counts dbw_counts;     /* what the .ftd window load found */
    /* a .ftd stays open after the window's load (terrain.db points here):
     * its index in FT_POOL_DEM_IO, read again through db_file */
    ft_file db_file;
    ft_tdb db;
    ft_terrain terrain;
    ft_gpu_context gpu;
    ft_renderer renderer;
    int renderer_ready;
#if FT_WITH_REFERENCE
    ft_ref_pixel *ref;     /* FT_POOL_REFERENCE (metric.enabled) */
    void *metric_scratch;  /* FT_POOL_METRIC (metric.enabled): ft_metric_scratch_bytes */
    /* over a database window: the truth read from the database around the
     * eye (FT_POOL_REFERENCE; measure/ref_window.h) */
    ft_ref_window truth;
    int truth_ready;
#endif
    uint64_t init_ns;
    char pool_table[FT_POOL_TABLE_TEXT_MAX];
} ft_app;

/* Scratch libpng+zlib need to encode one width-px-wide RGBA row image. */
size_t ft_png_scratch_bytes(uint32_t width_px);

ft_status ft_app_init(ft_app *app, const ft_scene *scene, ft_error *err);

/* The terrain the scene names, its header only (size, spacing, georeference;
 * no heights, no memory from the arena): for a tool that must know where
 * the terrain lies before it initialises a run. */
ft_status ft_app_probe_terrain(const ft_scene *scene, ft_terrain *t, ft_error *err);

/* One colour frame at `pose`, read back into app->renderer.rgba, and shown
 * on the display when the scene has one. */
ft_status ft_app_render(ft_app *app, const ft_pose *pose, ft_camera *cam, ft_frame_stats *st,
                        ft_error *err);
/* The same, with the failure annunciation (red cross + reason) drawn over
 * the frame when reason is not NULL. */
ft_status ft_app_render_annunciated(ft_app *app, const ft_pose *pose, const char *reason,
                                    ft_camera *cam, ft_frame_stats *st, ft_error *err);

#if FT_WITH_REFERENCE
/* Position pass + reference + metric for the camera (metric.enabled). */
ft_status ft_app_measure(ft_app *app, const ft_camera *cam, ft_error_stats *out, ft_error *err);
/* The terrain the reference casts against for the camera: the scene's, or
 * over a database window the database around the eye (read when the eye
 * moved on; measure/ref_window.h). */
ft_status ft_app_truth(ft_app *app, const ft_camera *cam, const ft_terrain **t, ft_error *err);
#endif

void ft_app_shutdown(ft_app *app);

#endif
