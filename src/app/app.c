#include "app/app.h"

#include <stdio.h>
#include <string.h>

#include "core/invariant.h"
#include "terrain/dem_hgt.h"
#include "terrain/pyramid.h"
#include "terrain/synth_terrain.h"
#include "terrain/terrain_file.h"

/* Annunciation reasons are shown whole. */
_Static_assert(FT_FAULT_TEXT_MAX <= FT_OVERLAY_TEXT_MAX, "fault text longer than the overlay's");
_Static_assert(FT_POSE_REASON_MAX <= FT_OVERLAY_TEXT_MAX, "pose reason longer than the overlay's");

/* deflate at level 6, windowBits 15, memLevel 8: (1 << 17) + (1 << 17) bytes,
 * plus zlib's state and libpng's row, previous-row and filter buffers (about
 * 6 row copies) and its own structs. Measured in tests/test_png.c. */
size_t ft_png_scratch_bytes(uint32_t width_px)
{
    return 320u * 1024u + 8u * ((size_t)width_px * 4u + 64u);
}

static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    if (n < m) {
        return 0;
    }
    for (size_t i = 0; i < m; ++i) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z') {
            c = (char)(c - 'A' + 'a');
        }
        if (c != suffix[i]) {
            return 0;
        }
    }
    return 1;
}

/* Header only: size, spacing, georeference (and the height range where the
 * header holds it). `file` is left open for the load that follows. */
static ft_status probe_terrain_of(const ft_scene *s, ft_file *file, ft_terrain *t,
                                  ft_dem_kind *kind, ft_tfile_header *hdr, ft_dbw *dbw,
                                  ft_error *err)
{
    memset(t, 0, sizeof *t);
    if (s->dem_path[0] == '\0') {
        *kind = FT_DEM_SYNTH;
        return ft_synth_probe(&s->synth, t, err);
    }
    ft_status st = ft_plat_file_open_read(file, s->dem_path, err);
    if (st != FT_OK) {
        return st;
    }
    if (ends_with(s->dem_path, ".hgt")) {
        *kind = FT_DEM_HGT;
        return ft_hgt_probe(&file->reader, s->dem_path, t, err);
    }
    if (ends_with(s->dem_path, ".ftd")) {
        const ft_dbw_desc d = {s->db_level, s->db_side_samples, s->db_centre_lat_deg,
                               s->db_centre_lon_deg};
        *kind = FT_DEM_FTD;
        return ft_dbw_probe(&file->reader_at, &d, dbw, t, err);
    }
    *kind = FT_DEM_FTT;
    return ft_tfile_probe(&file->reader, t, hdr, err);
}

static ft_status probe_terrain(ft_app *app, ft_file *file, ft_error *err)
{
    return probe_terrain_of(&app->scene, file, &app->terrain, &app->dem_kind,
                            &app->tfile_header, &app->dbw, err);
}

ft_status ft_app_probe_terrain(const ft_scene *scene, ft_terrain *t, ft_error *err)
{
    ft_file file;
    ft_dem_kind kind;
    ft_tfile_header hdr;
    ft_dbw dbw;
    memset(&file, 0, sizeof file);
    file.fd = -1;
    ft_status st = probe_terrain_of(scene, &file, t, &kind, &hdr, &dbw, err);
    ft_plat_file_close(&file);
    if (st == FT_OK) {
        t->curv_drop_per_m2 = ft_terrain_curvature_drop(scene->curvature, t->unit);
    }
    return st;
}

/* A .hgt says how many samples it fills only when read, and so does a .ftd
 * window (its filled and missing samples); a .ftt says it in its header; a
 * synthetic terrain has none. */
static int may_have_voids(const ft_app *app)
{
    return app->dem_kind == FT_DEM_HGT || app->dem_kind == FT_DEM_FTD ||
           (app->dem_kind == FT_DEM_FTT && app->terrain.void_count > 0u);
}

/* A .ftd window's load buffer: the index, then the staging. */
static size_t dbw_io_bytes(const ft_dbw *w)
{
    return ft_dbw_index_bytes(w) + ft_dbw_staging_bytes(w);
}

#if FT_WITH_REFERENCE
/* Samples per side of the truth's database window (measure/ref_window.h). */
static uint32_t truth_side(const ft_app *app)
{
    return app->scene.metric_truth_side != 0u ? app->scene.metric_truth_side : app->dbw.side;
}
#endif

static void plan(ft_app *app)
{
    const ft_scene *s = &app->scene;
    const ft_terrain *t = &app->terrain;
    ft_arena *a = &app->arena;
    ft_arena_plan(a, FT_POOL_HEIGHTS, (size_t)t->width * t->height * sizeof(float));
    if (may_have_voids(app)) {
        ft_arena_plan(a, FT_POOL_HEIGHTS, ft_terrain_void_bits_bytes(t->width, t->height));
        ft_arena_plan(a, FT_POOL_GPU_STAGING, ft_renderer_void_staging_bytes(t->width));
    }
    ft_arena_plan(a, FT_POOL_PYRAMIDS, ft_pyramid_bytes(t->width, t->height));
    if (app->dem_kind == FT_DEM_HGT) {
        ft_arena_plan(a, FT_POOL_DEM_IO, ft_hgt_scratch_bytes(t->width, t->height));
    }
    if (app->dem_kind == FT_DEM_FTD) { /* the index, then one tile's staging */
        ft_arena_plan(a, FT_POOL_DEM_IO, dbw_io_bytes(&app->dbw));
    }
    ft_renderer_plan(s, t, a);
#if FT_WITH_REFERENCE
    if (s->metric_enabled) {
        size_t px = (size_t)s->width_px * s->height_px;
        ft_arena_plan(a, FT_POOL_REFERENCE, px * sizeof(ft_ref_pixel));
        ft_arena_plan(a, FT_POOL_METRIC, ft_metric_scratch_bytes(s->width_px, s->height_px));
        if (app->dem_kind == FT_DEM_FTD) {
            ft_arena_plan(a, FT_POOL_REFERENCE,
                          ft_ref_window_bytes(&app->dbw.hdr, app->dbw.level, truth_side(app)));
        }
    }
#endif
#if FT_WITH_PNG
    ft_arena_plan(a, FT_POOL_PNG, ft_png_scratch_bytes(s->width_px));
#endif
}

/* After a .ftd window's load: the database open for the run (its own file
 * handle, the index read again into the load's buffer and checked), so a
 * method's cache can read past the window. */
static ft_status keep_database_open(ft_app *app, void *index, ft_error *err)
{
    ft_terrain *t = &app->terrain;
    ft_status st = ft_plat_file_open_read(&app->db_file, app->scene.dem_path, err);
    if (st == FT_OK) {
        st = ft_tdb_open(&app->db, &app->db_file.reader_at, index, app->dbw.hdr.entry_count,
                         err);
    }
    if (st == FT_OK && app->db.hdr.index_crc32 != app->dbw.hdr.index_crc32) {
        st = ft_fail(err, FT_ERR_FORMAT, "%s: the database changed during the load",
                     app->scene.dem_path);
    }
    if (st != FT_OK) {
        return st;
    }
    t->db = &app->db;
    t->db_level = app->dbw.level;
    t->db_i0 = app->dbw.i0;
    t->db_j0 = app->dbw.j0;
    t->db_fill_m = app->dbw_counts.fill_m;
    return FT_OK;
}

static ft_status load_terrain(ft_app *app, ft_file *file, ft_error *err)
{
    ft_terrain *t = &app->terrain;
    ft_arena *a = &app->arena;
    size_t n = (size_t)t->width * t->height;
    size_t pyr_bytes = ft_pyramid_bytes(t->width, t->height);
    void *pyr = NULL;
    ft_status st = ft_arena_take(a, FT_POOL_HEIGHTS, n * sizeof(float), (void **)&t->heights_m,
                                 err);
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_PYRAMIDS, pyr_bytes, &pyr, err);
    }
    if (st == FT_OK) {
        st = ft_pyramid_layout(t, pyr, pyr_bytes, err);
    }
    if (st == FT_OK && may_have_voids(app)) {
        const size_t bits_bytes = ft_terrain_void_bits_bytes(t->width, t->height);
        st = ft_arena_take(a, FT_POOL_HEIGHTS, bits_bytes, (void **)&t->void_bits, err);
        if (st == FT_OK) {
            memset(t->void_bits, 0, bits_bytes);
        }
    }
    if (st != FT_OK) {
        return st;
    }
    switch (app->dem_kind) {
    case FT_DEM_SYNTH:
        ft_synth_generate(&app->scene.synth, t);
        ft_pyramid_build(t);
        return FT_OK;
    case FT_DEM_HGT: {
        size_t scratch_bytes = ft_hgt_scratch_bytes(t->width, t->height);
        void *scratch = NULL;
        st = ft_arena_take(a, FT_POOL_DEM_IO, scratch_bytes, &scratch, err);
        if (st == FT_OK) {
            st = ft_hgt_load(&file->reader, t, scratch, scratch_bytes, err);
        }
        if (st == FT_OK) {
            ft_pyramid_build(t);
        }
        return st;
    }
    case FT_DEM_FTT:
        return ft_tfile_load_payload(&file->reader, t, &app->tfile_header, err);
    case FT_DEM_FTD: {
        const size_t io_bytes = dbw_io_bytes(&app->dbw);
        void *io = NULL;
        st = ft_arena_take(a, FT_POOL_DEM_IO, io_bytes, &io, err);
        if (st == FT_OK) {
            st = ft_dbw_load(&file->reader_at, &app->dbw, t, io, io_bytes, &app->dbw_counts, err);
        }
        if (st == FT_OK) {
            st = keep_database_open(app, io, err);
        }
        if (st == FT_OK) {
            ft_pyramid_build(t);
        }
        return st;
    }
    default:
        return ft_fail(err, FT_ERR_ARG, "unknown DEM kind");
    }
}

/* The presentation parts a build may leave out (FIXTERRAIN_WITH_*): a scene
 * that asks for one is refused before anything is loaded, by the key that
 * asks and the option that would bring it. The scene parser itself knows no
 * build options, so the lean-build profile (tools/profile.cmake) reads every
 * scene alike. */
static ft_status check_build_parts(const ft_scene *s, ft_error *err)
{
    char haze_km[32], grid_m[32], night_line[16];
    (void)snprintf(haze_km, sizeof haze_km, "%g", s->present_haze_km);
    (void)snprintf(grid_m, sizeof grid_m, "%g", s->present_grid_m);
    (void)snprintf(night_line, sizeof night_line, "%d", s->gpio_input_line[FT_GPIO_NIGHT]);
    const struct {
        int used, built;
        const char *key, *value, *option;
    } parts[] = {
        {s->present_relative, FT_WITH_RELATIVE_COLOURING, "presentation.colouring", "relative",
         "RELATIVE_COLOURING"},
        {s->present_horizon, FT_WITH_HORIZON, "presentation.horizon", "1", "HORIZON"},
        {s->present_haze_km > 0.0, FT_WITH_HAZE, "presentation.haze_km", haze_km, "HAZE"},
        {s->present_grid_m > 0.0, FT_WITH_GROUND_GRID, "presentation.grid_m", grid_m,
         "GROUND_GRID"},
        {s->present_palette == FT_PALETTE_NIGHT, FT_WITH_NIGHT_PALETTE, "presentation.palette",
         "night", "NIGHT_PALETTE"},
        {s->gpio_input_line[FT_GPIO_NIGHT] >= 0, FT_WITH_NIGHT_PALETTE, "gpio.night_line",
         night_line, "NIGHT_PALETTE"},
    };
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; ++i) {
        if (parts[i].used && !parts[i].built) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "%s = %s was left out of this build (FIXTERRAIN_WITH_%s=OFF)",
                           parts[i].key, parts[i].value, parts[i].option);
        }
    }
    return FT_OK;
}

ft_status ft_app_init(ft_app *app, const ft_scene *scene, ft_error *err)
{
    ft_file file;
    ft_status st;
    uint64_t t0 = ft_plat_monotonic_ns();
    memset(app, 0, sizeof *app);
    memset(&file, 0, sizeof file);
    file.fd = -1;
    app->db_file.fd = -1;
    app->scene = *scene;

    st = ft_scene_validate(&app->scene, err);
    if (st == FT_OK) {
        st = check_build_parts(&app->scene, err);
    }
    if (st != FT_OK) {
        return st;
    }
    st = probe_terrain(app, &file, err);
    if (st != FT_OK) {
        goto fail_file;
    }
    app->terrain.curv_drop_per_m2 =
        ft_terrain_curvature_drop(app->scene.curvature, app->terrain.unit);
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        app->arena.pools[i].budget_bytes = (size_t)app->scene.budget_bytes[i];
    }
    plan(app);
    st = ft_arena_check(&app->arena, err);
    if (st != FT_OK) {
        goto fail_file;
    }
    app->arena_bytes = ft_arena_total_budget(&app->arena);
    st = ft_plat_mem_reserve(app->arena_bytes, &app->arena_memory, err);
    if (st != FT_OK) {
        goto fail_file;
    }
    st = ft_arena_bind(&app->arena, app->arena_memory, app->arena_bytes, err);
    if (st != FT_OK) {
        goto fail_memory;
    }
    st = load_terrain(app, &file, err);
    ft_plat_file_close(&file);
    if (st != FT_OK) {
        goto fail_memory;
    }
    const ft_gpu_desc gd = {app->scene.backend,           app->scene.display,
                            app->scene.width_px,          app->scene.height_px,
                            app->scene.display_device,    app->scene.display_connector,
                            app->scene.display_mode};
    st = ft_plat_gpu_open(&gd, &app->gpu, err);
    if (st != FT_OK) {
        goto fail_memory;
    }
    st = ft_renderer_init(&app->renderer, &app->gpu, &app->scene, &app->terrain, &app->arena,
                          err);
    if (st != FT_OK) {
        goto fail_renderer;
    }
    app->renderer_ready = 1;
#if FT_WITH_REFERENCE
    if (app->scene.metric_enabled) {
        size_t px = (size_t)app->scene.width_px * app->scene.height_px;
        st = ft_arena_take(&app->arena, FT_POOL_REFERENCE, px * sizeof(ft_ref_pixel),
                           (void **)&app->ref, err);
        if (st == FT_OK) {
            st = ft_arena_take(&app->arena, FT_POOL_METRIC,
                               ft_metric_scratch_bytes(app->scene.width_px, app->scene.height_px),
                               &app->metric_scratch, err);
        }
        if (st == FT_OK && app->terrain.db != NULL) {
            const size_t bytes =
                ft_ref_window_bytes(&app->dbw.hdr, app->dbw.level, truth_side(app));
            void *mem = NULL;
            st = ft_arena_take(&app->arena, FT_POOL_REFERENCE, bytes, &mem, err);
            if (st == FT_OK) {
                st = ft_ref_window_init(&app->truth, &app->terrain, truth_side(app), mem, bytes,
                                        err);
            }
            app->truth_ready = (st == FT_OK);
        }
        if (st != FT_OK) {
            goto fail_renderer;
        }
    }
#endif
    ft_arena_lock(&app->arena);
    (void)ft_arena_format_table(&app->arena, app->pool_table, sizeof app->pool_table);
    app->init_ns = ft_plat_monotonic_ns() - t0;
    return FT_OK;

fail_renderer:
    ft_renderer_shutdown(&app->renderer);
    app->renderer_ready = 0;
    ft_plat_gpu_close(&app->gpu);
fail_memory:
    ft_plat_file_close(&app->db_file);
    ft_plat_mem_release(app->arena_memory, app->arena_bytes);
    app->arena_memory = NULL;
fail_file:
    ft_plat_file_close(&file);
    return st;
}

ft_status ft_app_render(ft_app *app, const ft_pose *pose, ft_camera *cam, ft_frame_stats *st,
                        ft_error *err)
{
    return ft_app_render_annunciated(app, pose, NULL, cam, st, err);
}

ft_status ft_app_render_annunciated(ft_app *app, const ft_pose *pose, const char *reason,
                                    ft_camera *cam, ft_frame_stats *st, ft_error *err)
{
    ft_status s = ft_renderer_camera(&app->renderer, pose, cam, err);
    if (s != FT_OK) {
        return s;
    }
    uint64_t ts = ft_plat_monotonic_ns();
    ft_renderer_select(&app->renderer, cam); /* CPU LOD selection, its own stage */
    ft_renderer_fit_depth(&app->renderer, cam); /* a method that draws past the grid */
    uint64_t t0 = ft_plat_monotonic_ns();
    s = ft_renderer_draw(&app->renderer, cam, st, err);
    /* a broken invariant (core/invariant.h), this frame's or an earlier
     * one's, puts the fail-safe annunciation over this and every later frame */
    char fault_text[FT_FAULT_TEXT_MAX];
    st->internal_fault = (ft_fault_latched() != NULL);
    if (st->internal_fault) {
        reason = ft_fault_text(fault_text);
    }
    if (s == FT_OK && reason != NULL) {
        s = ft_renderer_draw_annunciation(&app->renderer, reason, err);
    }
    uint64_t t1 = ft_plat_monotonic_ns();
    if (s != FT_OK) {
        return s;
    }
    s = ft_renderer_read_rgba(&app->renderer, err); /* waits for the GPU */
    st->unmeasured_px = app->renderer.unmeasured_px;
    uint64_t t2 = ft_plat_monotonic_ns();
    st->gpu_timer_ms = (s == FT_OK) ? ft_renderer_gpu_timer_ms(&app->renderer) : -1.0;
    if (st->gpu_timer_ms > (double)(t2 - t0) * 1e-6 + 0.05) {
        /* the query brackets only the draw, which lies inside [t0, t2]: a
         * longer time is not a measurement. (llvmpipe answers a context's
         * first query with a timestamp, ~uptime in ns.) Reported as none. */
        st->gpu_timer_ms = -1.0;
    }
    if (s == FT_OK && app->scene.display != FT_DISPLAY_NONE) {
        s = ft_renderer_present(&app->renderer, err);
        if (s == FT_OK) {
            s = ft_plat_gpu_present(&app->gpu, err);
        }
    }
    st->select_ms = (double)(t0 - ts) * 1e-6;
    st->cpu_ms = (double)(t1 - t0) * 1e-6;
    st->gpu_ms = (double)(t2 - t0) * 1e-6;
    return s;
}

#if FT_WITH_REFERENCE
ft_status ft_app_measure(ft_app *app, const ft_camera *cam, ft_error_stats *out, ft_error *err)
{
    size_t px = (size_t)app->scene.width_px * app->scene.height_px;
    if (!app->scene.metric_enabled || app->ref == NULL) {
        return ft_fail(err, FT_ERR_CONFIG, "error metric needs metric.enabled = 1 in the scene");
    }
    ft_status s = ft_renderer_draw_positions(&app->renderer, cam, err);
    if (s != FT_OK) {
        return s;
    }
    const ft_terrain *truth = NULL;
    s = ft_app_truth(app, cam, &truth, err);
    if (s != FT_OK) {
        return s;
    }
    s = ft_reference_render(truth, cam, app->ref, px, err);
    if (s != FT_OK) {
        return s;
    }
    return ft_metric_compute(truth, cam, app->renderer.pos, app->ref, app->metric_scratch,
                             ft_metric_scratch_bytes(cam->width_px, cam->height_px), out, err);
}

ft_status ft_app_truth(ft_app *app, const ft_camera *cam, const ft_terrain **t, ft_error *err)
{
    *t = &app->terrain;
    if (!app->truth_ready) {
        return FT_OK;
    }
    int moved = 0;
    const ft_status s = ft_ref_window_follow(&app->truth, cam->eye_m, &moved, err);
    if (s != FT_OK) {
        return s;
    }
    *t = &app->truth.t;
    return FT_OK;
}
#endif

void ft_app_shutdown(ft_app *app)
{
    if (app->renderer_ready) {
        ft_renderer_shutdown(&app->renderer);
        app->renderer_ready = 0;
    }
    ft_plat_gpu_close(&app->gpu);
    if (app->terrain.db != NULL) {
        ft_plat_file_close(&app->db_file);
        app->terrain.db = NULL;
    }
    if (app->arena_memory != NULL) {
        ft_plat_mem_release(app->arena_memory, app->arena_bytes);
        app->arena_memory = NULL;
    }
}
