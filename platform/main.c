/* main.c - the fixterrain command line: one executable, one subcommand per
 * job. Errors go to stderr with the reason; information goes to stdout.
 * Exit status: 0 ok, 1 runtime error, 2 usage error. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "app/cli.h"
#include "app/frame.h"
#include "app/replay.h"
#include "core/platform_api.h"
#include "terrain/default_view.h"
#if FT_WITH_CAN && FT_WITH_GPIO
#include <signal.h>

#include "app/live.h"
#endif
#include "core/scene.h"

#define FT_EXIT_OK FT_CLI_OK
#define FT_EXIT_ERROR FT_CLI_ERROR
#define FT_EXIT_USAGE FT_CLI_USAGE
#define FT_FRAMES_MAX 10000
#define FT_STATS_TEXT_MAX 8192u

/* Static, not stack: the app holds the terrain/pyramid descriptors. */
static ft_app g_app;
static char g_scene_text[FT_SCENE_TEXT_MAX];
static char g_stats_text[FT_STATS_TEXT_MAX];

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static size_t json_pools(const ft_arena *a, char *buf, size_t cap)
{
    size_t n = 0;
    for (int i = 0; i < FT_POOL_COUNT && n < cap; ++i) {
        const ft_pool *p = &a->pools[i];
        size_t used = p->high_water_bytes > p->need_bytes ? p->high_water_bytes : p->need_bytes;
        int w = snprintf(buf + n, cap - n, "%s\n    {\"pool\": \"%s\", \"used_bytes\": %zu, "
                         "\"budget_bytes\": %zu}", i ? "," : "", ft_pool_key((ft_pool_id)i),
                         used, p->budget_bytes);
        n += (w > 0) ? (size_t)w : 0;
    }
    return n;
}

/* Writes the first len bytes of g_stats_text (a snprintf result: len < 0
 * or too long means the JSON did not fit) to path, atomically. */
static ft_status write_stats_text(const char *path, int len, const char *what, ft_error *err)
{
    if (len < 0 || (size_t)len >= sizeof g_stats_text) {
        return ft_fail(err, FT_ERR_OVERSIZED, "%s stats JSON longer than %u bytes", what,
                       FT_STATS_TEXT_MAX);
    }
    ft_file f;
    ft_status s = ft_plat_file_open_write(&f, path, err);
    if (s != FT_OK) {
        return s;
    }
    s = f.writer.write(f.writer.ctx, g_stats_text, (size_t)len);
    if (s != FT_OK) {
        ft_plat_file_close(&f);
        return ft_fail(err, s, "%s: write failed", path);
    }
    return ft_plat_file_finish_write(&f, err);
}

/* The frame's depth buffer as the stats name it: "32f", "24" or "16". */
static const char *depth_format_name(const ft_frame_stats *st)
{
    if (st->depth_float) {
        return "32f";
    }
    return st->depth_bits == 24u ? "24" : (st->depth_bits == 16u ? "16" : "none");
}

static ft_status write_stats(const char *path, const ft_app *app, const ft_camera *cam,
                             const ft_frame_stats *last, double median_ms, unsigned frames,
                             const char *error_json, ft_error *err)
{
    char pools[2048];
    const ft_terrain *t = &app->terrain;
    (void)json_pools(&app->arena, pools, sizeof pools);
    char res_text[32] = "null"; /* JSON has no infinity (no depth buffer) */
    if (isfinite(last->depth_res_far_m)) {
        (void)snprintf(res_text, sizeof res_text, "%.4f", last->depth_res_far_m);
    }
    /* null: no bound (the eye inside a leaf tile's box, or the roots' box) */
    char tau_text[32] = "null";
    char target_text[32] = "null"; /* the roots' fallback: no finite target either */
    if (isfinite(last->tau_target_px)) {
        (void)snprintf(target_text, sizeof target_text, "%.4f", last->tau_target_px);
    }
    if (isfinite(last->tau_achieved_px)) {
        (void)snprintf(tau_text, sizeof tau_text, "%.4f", last->tau_achieved_px);
    }
    int n = snprintf(
        g_stats_text, sizeof g_stats_text,
        "{\n  \"scene\": \"%s\",\n  \"method\": \"%s\",\n  \"backend\": \"%s\",\n"
        "  \"gl_version\": \"%s\",\n  \"gl_renderer\": \"%s\",\n"
        "  \"width_px\": %u,\n  \"height_px\": %u,\n"
        "  \"terrain\": {\"width\": %u, \"height\": %u, \"cell_x_m\": %.6f, \"cell_y_m\": %.6f,"
        " \"min_height_m\": %.3f, \"max_height_m\": %.3f, \"voids_filled\": %u, \"crs\": \"%s\"},\n"
        "  \"eye_m\": [%.3f, %.3f, %.3f],\n"
        "  \"init_ms\": %.3f,\n  \"frames\": %u,\n"
        "  \"frame\": {\"triangles\": %llu, \"draw_calls\": %u, \"tiles\": %u,"
        " \"raycast_px\": %llu, \"raycast_terrain_px\": %llu, \"unmeasured_px\": %llu,"
        " \"internal_fault\": %d, \"cache_levels_behind\": %u,"
        " \"cache_samples_outstanding\": %llu, \"cache_coarser\": %d,"
        " \"cache_forced_updates\": %u,"
        " \"tau_achieved_px\": %s, \"tau_target_px\": %s, \"budget_hit\": %d,"
        " \"back_faces_culled\": %d, \"envelopes\": %u, \"select_ms\": %.3f,"
        " \"cpu_ms\": %.3f, \"gpu_ms\": %.3f, \"gpu_timer_ms\": %.3f, \"median_gpu_ms\": %.3f,"
        " \"near_m\": %.4f, \"far_m\": %.1f, \"depth_format\": \"%s\", \"depth_res_far_m\": %s},\n"
        "  \"gpu_bytes\": %llu,\n  \"gpu_budget_bytes\": %llu,\n"
        "  \"error\": %s,\n  \"pools\": [%s\n  ]\n}\n",
        app->scene.name, ft_method_name(app->scene.method), ft_backend_name(app->scene.backend),
        app->gpu.version, app->gpu.renderer, app->scene.width_px, app->scene.height_px, t->width,
        t->height, t->cell_x_m, t->cell_y_m, (double)t->min_height_m, (double)t->max_height_m,
        t->void_count, t->crs, cam->eye_m[0], cam->eye_m[1], cam->eye_m[2],
        (double)app->init_ns * 1e-6, frames, (unsigned long long)last->triangles,
        last->draw_calls, last->tiles, (unsigned long long)last->raycast_px,
        (unsigned long long)last->terrain_px, (unsigned long long)last->unmeasured_px,
        last->internal_fault, last->cache_levels_behind,
        (unsigned long long)last->cache_samples_outstanding, last->cache_coarser,
        last->cache_forced_updates, tau_text, target_text, last->budget_hit,
        last->back_faces_culled, last->envelopes, last->select_ms,
        last->cpu_ms, last->gpu_ms, last->gpu_timer_ms, median_ms, last->near_m, last->far_m,
        depth_format_name(last), res_text,
        (unsigned long long)app->renderer.gpu_bytes,
        (unsigned long long)app->scene.gpu_texture_bytes, error_json, pools);
    return write_stats_text(path, n, "render", err);
}

/* The pose a command draws from: --pose, else the scene's [pose] when the
 * scene's own terrain is drawn or the pose lies over the terrain given with
 * --dem, else the terrain's default view (a scene's pose belongs to the
 * scene's terrain, not to another DEM named on the command line). A pose
 * that was asked for but lies off the terrain is drawn (the frame is sky)
 * with a warning naming both, or refused under --strict. */
static int settle_pose(const char *cmd, const ft_scene *scene, int pose_from_cli,
                       int dem_from_cli, int strict, const ft_terrain *t, ft_pose *pose)
{
    const char *dem = scene->dem_path[0] != '\0' ? scene->dem_path : "(synthetic terrain)";
    int over = ft_pose_over_terrain(t, &scene->pose);
    int asked = pose_from_cli || (scene->pose_given && (!dem_from_cli || over));
    *pose = scene->pose;
    if (asked && over) {
        return FT_EXIT_OK;
    }
    if (asked) {
        double lat0, lat1, lon0, lon1;
        ft_terrain_extent_geo(t, &lat0, &lat1, &lon0, &lon1);
        fprintf(stderr,
                "fixterrain %s: %s: the pose (lat %.6f, lon %.6f) does not lie over the "
                "terrain %s (lat %.6f..%.6f, lon %.6f..%.6f)%s\n",
                cmd, strict ? "error" : "warning", scene->pose.lat_deg, scene->pose.lon_deg,
                dem, lat0, lat1, lon0, lon1,
                strict ? "" : ": the frame may show no terrain (--strict refuses)");
        return strict ? FT_EXIT_USAGE : FT_EXIT_OK;
    }
    ft_default_view_pose(t, pose);
    fprintf(stderr,
            "fixterrain %s: no pose given for %s: default view from above its south-west "
            "corner: --pose %.6f,%.6f,%.0f,%.1f,%.1f,0\n",
            cmd, dem, pose->lat_deg, pose->lon_deg, pose->alt_m, pose->heading_deg,
            pose->pitch_deg);
    return FT_EXIT_OK;
}

/* Indent of a help line's continuation: the column the text starts in. */
#define FT_HELP_CONT "\n                      "

static int cmd_render(int argc, char **argv)
{
    ft_scene scene;
    ft_error err;
    ft_cli_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.command = "render";
    sd.text = g_scene_text;
    sd.text_cap = sizeof g_scene_text;
    const char *out_path = "fixterrain.png", *stats_path = NULL;
    uint32_t hold_ms = 0, frames = 1;
    int quiet = 0, strict = 0;
    ft_pose pose_drawn;
    memset(&err, 0, sizeof err);

    const ft_cli_opt opts[] = {
        FT_CLI_OPT_STRING("--scene", &sd.scene_path,
                          "--scene FILE        "
                          "scene file (INI; see config/*.ini); default: embedded"),
        FT_CLI_OPT_STRING("--dem", &sd.dem,
                          "--dem FILE          terrain: .ftt (fixterrain import) or SRTM .hgt"),
        FT_CLI_OPT_STRING("--method", &sd.method,
                          "--method NAME       "
                          "terrain method: brute | bintree | pgm | pgrid (as built)"),
        FT_CLI_OPT_STRING("--backend", &sd.backend,
                          "--backend NAME      egl-gles3 | egl-gles2 | osmesa"),
        FT_CLI_OPT_STRING("--display", &sd.display,
                          "--display NAME      none (offscreen) | x11 (a window; EGL backends) |"
                          FT_HELP_CONT "kms[:/dev/dri/cardN] (full screen on DRM/KMS, page flips;"
                          FT_HELP_CONT "the mode's size must be the view size: --size WxH;"
                          FT_HELP_CONT "display.mode and display.connector in the scene)"),
        FT_CLI_OPT_U32("--hold-ms", &hold_ms, 0u, 600000u,
                       "--hold-ms N         with a display: keep the last frame shown N ms"),
        FT_CLI_OPT_STRING("--size", &sd.size,
                          "--size WxH          image size in pixels (16..8192)"),
        FT_CLI_OPT_STRING("--pose", &sd.pose,
                          "--pose LAT,LON,ALT_M,HEADING_DEG,PITCH_DEG,ROLL_DEG"
                          FT_HELP_CONT "default: the scene's [pose] if it lies over the terrain,"
                          FT_HELP_CONT "else the terrain's default view (from above its"
                          FT_HELP_CONT "south-west corner, looking at its centre; said on stderr)"),
        FT_CLI_OPT_FLAG("--strict", &strict,
                        "--strict            a pose that does not lie over the terrain is an error"
                        FT_HELP_CONT "(default: a warning naming both)"),
        FT_CLI_OPT_STRING("--out", &out_path,
                          "--out FILE.png      output image (default fixterrain.png)"),
        FT_CLI_OPT_STRING("--stats", &stats_path,
                          "--stats FILE.json   "
                          "frame, memory and (metric.enabled) error statistics"),
        FT_CLI_OPT_U32("--frames", &frames, 1u, FT_FRAMES_MAX,
                       "--frames N          render N frames (timing: median of all but the first)"),
        FT_CLI_OPT_FLAG("--quiet", &quiet, "--quiet             do not print the memory table"),
    };
    const ft_cli_desc cli = {"render", opts, sizeof opts / sizeof opts[0]};
    int rc0 = ft_cli_parse(&cli, argc, argv, NULL);
    if (rc0 == FT_CLI_HELP) {
        printf("usage: fixterrain render [options]\n"
               "Renders one frame offscreen to a PNG. With no options: the embedded default\n"
               "scene (synthetic terrain, method pgrid, EGL GLES 3) to fixterrain.png.\n\n");
        ft_cli_print_help(&cli);
        return FT_EXIT_OK;
    }
    if (rc0 != FT_EXIT_OK) {
        return rc0;
    }
    rc0 = ft_cli_scene_load(&sd, &scene, NULL);
    if (rc0 != FT_EXIT_OK) {
        return rc0;
    }

    if (ft_app_init(&g_app, &scene, &err) != FT_OK) {
        fprintf(stderr, "fixterrain: init failed: %s: %s\n", ft_status_str(err.status), err.text);
        return FT_EXIT_ERROR;
    }
    rc0 = settle_pose("render", &scene, sd.pose != NULL, sd.dem != NULL, strict, &g_app.terrain,
                      &pose_drawn);
    if (rc0 != FT_EXIT_OK) {
        ft_app_shutdown(&g_app);
        return rc0;
    }
    if (!quiet) {
        printf("fixterrain: %s on %s (%s, %s)\n", ft_method_name(scene.method),
               ft_backend_name(scene.backend), g_app.gpu.version, g_app.gpu.renderer);
        printf("terrain %ux%u, cell %.3f x %.3f m, heights %.1f..%.1f m, %u voids filled\n",
               g_app.terrain.width, g_app.terrain.height, g_app.terrain.cell_x_m,
               g_app.terrain.cell_y_m, (double)g_app.terrain.min_height_m,
               (double)g_app.terrain.max_height_m, g_app.terrain.void_count);
        if (g_app.dem_kind == FT_DEM_FTD) {
            const ft_dbw_counts *c = &g_app.dbw_counts;
            printf("database window: level %u, south-west corner lat %.6f lon %.6f, %u tiles "
                   "read, %u without data; marked unmeasured: %llu samples void-filled by the "
                   "database, %llu drawn from coarser levels, %llu with no data (drawn at %.1f "
                   "m); init %.1f ms\n",
                   g_app.dbw.level, g_app.terrain.origin_y, g_app.terrain.origin_x,
                   c->tiles_read, c->tiles_no_data, (unsigned long long)c->filled_samples,
                   (unsigned long long)c->coarser_samples, (unsigned long long)c->missing_samples,
                   (double)c->fill_m,
                   (double)g_app.init_ns * 1e-6);
        }
        printf("static memory (one arena of %zu bytes, locked after init):\n%s",
               g_app.arena_bytes, g_app.pool_table);
        printf("GPU memory: %llu of %llu bytes budgeted (gpu.texture_bytes)\n",
               (unsigned long long)g_app.renderer.gpu_bytes,
               (unsigned long long)scene.gpu_texture_bytes);
    }

    static double times_ms[FT_FRAMES_MAX];
    /* the same frame N times: the settings as set, no degradation */
    ft_frame_loop loop;
    ft_frame_loop_init(&loop, &g_app, 0);
    ft_frame fr;
    memset(&fr, 0, sizeof fr);
    int rc = FT_EXIT_OK;
    for (unsigned f = 0; f < frames; ++f) {
        if (ft_frame_step(&loop, &g_app, &pose_drawn, NULL, &fr, &err) != FT_OK) {
            fprintf(stderr, "fixterrain: frame %u: %s\n", f, err.text);
            rc = FT_EXIT_ERROR;
            goto done;
        }
        times_ms[f] = fr.stats.gpu_ms;
    }
    const ft_camera cam = fr.cam;
    const ft_frame_stats st = fr.stats;
    /* Frame 0 includes shader compilation in the driver: leave it out. */
    double median = times_ms[0];
    if (frames > 1) {
        qsort(times_ms + 1, frames - 1, sizeof times_ms[0], cmp_double);
        median = times_ms[1 + (frames - 1) / 2];
    }
    char error_json[512] = "null";
#if FT_WITH_REFERENCE
    if (scene.metric_enabled) {
        ft_error_stats es;
        if (ft_app_measure(&g_app, &cam, &es, &err) != FT_OK) {
            fprintf(stderr, "fixterrain: error metric: %s\n", err.text);
            rc = FT_EXIT_ERROR;
            goto done;
        }
        /* JSON has no infinity: a non-finite vertex makes max_px null and
         * is counted in nonfinite_px. */
        char max_text[32];
        if (isfinite(es.max_px)) {
            (void)snprintf(max_text, sizeof max_text, "%.4f", es.max_px);
        } else {
            (void)snprintf(max_text, sizeof max_text, "null");
        }
        (void)snprintf(error_json, sizeof error_json,
                       "{\"max_px\": %s, \"p999_px\": %.4f, \"mean_px\": %.4f, "
                       "\"terrain_px\": %u, \"only_method_px\": %u, \"only_ref_px\": %u, "
                       "\"occlusion_px\": %u, \"occlusion_max_px\": %.4f, "
                       "\"vertical_max_px\": %.4f, "
                       "\"behind_eye_px\": %u, \"nonfinite_px\": %u, \"outside_grid_px\": %u}",
                       max_text, es.p999_px, es.mean_px, es.terrain_px, es.only_method_px,
                       es.only_ref_px, es.occlusion_px, es.occlusion_max_px, es.vertical_max_px,
                       es.behind_eye_px, es.nonfinite_px, es.outside_grid_px);
        if (!quiet) {
            printf("screen-space error vs reference: max %.3f px, p99.9 %.3f px, mean %.4f px; "
                   "coverage mismatch %u + %u px; occlusion mismatch %u px (worst %.2f px)\n",
                   es.max_px, es.p999_px, es.mean_px, es.only_method_px, es.only_ref_px,
                   es.occlusion_px, es.occlusion_max_px);
        }
    }
#endif
#if FT_WITH_PNG
    if (ft_plat_png_write(out_path, g_app.renderer.rgba, scene.width_px, scene.height_px,
                          &g_app.arena, &err) != FT_OK) {
        fprintf(stderr, "fixterrain: %s\n", err.text);
        rc = FT_EXIT_ERROR;
        goto done;
    }
#else
    fprintf(stderr, "fixterrain: built without PNG output (FIXTERRAIN_WITH_PNG=OFF); %s not written\n",
            out_path);
#endif
    if (stats_path != NULL && write_stats(stats_path, &g_app, &cam, &st, median, frames,
                                          error_json, &err) != FT_OK) {
        fprintf(stderr, "fixterrain: stats: %s\n", err.text);
        rc = FT_EXIT_ERROR;
        goto done;
    }
    if (!quiet) {
        printf("frame: %llu triangles in %u draws, %.2f ms (first frame; median of later "
               "frames %.2f ms)\n",
               (unsigned long long)st.triangles, st.draw_calls, times_ms[0], median);
        printf("depth: %s-bit %s buffer, near %.2f m, far %.0f m, one depth step at the far "
               "plane %.3f m\n",
               st.depth_float ? "32" : depth_format_name(&st),
               st.depth_float ? "float" : "fixed-point", st.near_m, st.far_m, st.depth_res_far_m);
        if (st.tiles > 0u && scene.method == FT_METHOD_BINTREE) {
            printf("bintree: %u tiles, error bound %.3f px%s%s, selection %.3f ms\n", st.tiles,
                   st.tau_achieved_px, st.budget_hit ? " (tile budget hit: tau raised)" : "",
                   st.tau_achieved_px > st.tau_target_px
                       ? " (a leaf tile near the eye is over the target: the samples are "
                         "too coarse there)"
                       : "",
                   st.select_ms);
        } else if (scene.method == FT_METHOD_CLIPMAP) {
            if (isfinite(st.tau_achieved_px)) {
                printf("clipmap: error bound of what was drawn %.3f px (reported: the method "
                       "targets none)\n",
                       st.tau_achieved_px);
            } else {
                printf("clipmap: no error bound (a drawn level is finer than the data there, "
                       "or a block's box holds the eye)\n");
            }
        } else if (scene.method == FT_METHOD_PGRID && st.terrain_px == 0u) {
            /* with ray casting the counts are the previous frame's (src/lod/pgrid.h 5) */
            printf("pgrid: error bound %.3f px (ray-cast pixels are counted a frame late: "
                   "render 2 or more frames to see them)\n",
                   st.tau_achieved_px);
        } else if (scene.method == FT_METHOD_PGRID) {
            printf("pgrid: %llu pixels ray cast (of %llu terrain pixels; with ray casting, the "
                   "previous frame's), error bound %.3f px%s\n",
                   (unsigned long long)st.raycast_px, (unsigned long long)st.terrain_px,
                   st.tau_achieved_px, st.budget_hit ? " (ray-casting budget hit)" : "");
        }
        if (g_app.terrain.void_count > 0u) {
            const double frame_px = (double)scene.width_px * (double)scene.height_px;
            printf("unmeasured terrain: %u void-filled samples (%.2f%% of the terrain), shown "
                   "marked on %llu pixels (%.2f%% of the frame)\n",
                   g_app.terrain.void_count,
                   100.0 * g_app.terrain.void_count /
                       ((double)g_app.terrain.width * g_app.terrain.height),
                   (unsigned long long)st.unmeasured_px, 100.0 * (double)st.unmeasured_px / frame_px);
        }
        if (FT_WITH_PNG) {
            printf("wrote %s\n", out_path);
        }
    }
    if (hold_ms > 0 && scene.display != FT_DISPLAY_NONE) {
        printf("showing the frame for %u ms\n", (unsigned)hold_ms);
        (void)fflush(stdout);
        ft_plat_sleep_ms(hold_ms);
    }
done:
    ft_app_shutdown(&g_app);
    return rc;
}

static ft_pose_feed g_feed;
static ft_replay_io g_replay_io; /* the replay's files and line reader */

/* The position prediction's counters and the rejects per quantity, as JSON
 * members (replay and run share them). Returns 0 when cap is too small. */
static size_t json_position(const ft_pose_feed *f, uint32_t frames_predicted,
                            uint32_t frames_velocity_stale, char *buf, size_t cap)
{
    uint64_t vel_rejects = 0u;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        if ((FT_QTY_VELOCITY_MASK & FT_QTY_BIT(q)) != 0u) {
            vel_rejects += f->dec.rejects_by_qty[q];
        }
    }
    int w = snprintf(buf, cap,
                     "  \"position\": {\"frames_predicted\": %u, \"frames_velocity_stale\": %u, "
                     "\"snaps\": %llu, \"offset_max_m\": %.4f, \"velocity_rejects\": %llu, "
                     "\"velocity_required\": %d},\n  \"rejects_by_quantity\": {",
                     frames_predicted, frames_velocity_stale,
                     (unsigned long long)f->ps.snap_count, f->ps.offset_max_m,
                     (unsigned long long)vel_rejects,
                     (f->annunciate_mask & FT_QTY_VELOCITY_MASK) != 0u);
    if (w < 0 || (size_t)w >= cap) {
        return 0u;
    }
    size_t n = (size_t)w;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        w = snprintf(buf + n, cap - n, "%s\"%s\": %llu", q ? ", " : "",
                     ft_pose_qty_name((ft_pose_qty)q),
                     (unsigned long long)f->dec.rejects_by_qty[q]);
        if (w < 0 || (size_t)w >= cap - n) {
            return 0u;
        }
        n += (size_t)w;
    }
    w = snprintf(buf + n, cap - n, "},\n");
    if (w < 0 || (size_t)w >= cap - n) {
        return 0u;
    }
    return n + (size_t)w;
}

static ft_status write_replay_stats(const char *path, const ft_replay_result *r,
                                    const ft_pose_feed *f, ft_error *err)
{
    char rejects[1024];
    size_t n = 0;
    for (int i = 0; i < FT_CAN_REJECT_COUNT; ++i) {
        int w = snprintf(rejects + n, sizeof rejects - n, "%s\"%s\": %llu", i ? ", " : "",
                         ft_can_reject_name((ft_can_reject)i),
                         (unsigned long long)f->dec.rejects[i]);
        if (w < 0 || (size_t)w >= sizeof rejects - n) {
            return ft_fail(err, FT_ERR_OVERSIZED, "replay stats: reject list too long");
        }
        n += (size_t)w;
    }
    char position[1024];
    if (json_position(f, r->frames_pos_predicted, r->frames_velocity_stale, position,
                      sizeof position) == 0u) {
        return ft_fail(err, FT_ERR_OVERSIZED, "replay stats: position counters too long");
    }
    int len = snprintf(
        g_stats_text, sizeof g_stats_text,
        "{\n  \"lines\": %llu,\n  \"lines_bad\": %llu,\n  \"lines_unsupported\": %llu,\n"
        "  \"gaps\": %llu,\n  \"timestamps_backwards\": %llu,\n"
        "  \"timestamps_out_of_range\": %llu,\n"
        "  \"can_frames\": %llu,\n  \"values_applied\": %llu,\n"
        "  \"messages_lost\": %llu,\n  \"messages_out_of_sequence\": %llu,\n"
        "  \"rejects\": {%s},\n%s"
        "  \"frames\": %u,\n  \"frames_annunciated\": %u,\n  \"first_annunciated\": %lld,\n"
        "  \"frames_predicted\": %u,\n  \"log_first_s\": %.6f,\n  \"log_last_s\": %.6f,\n"
        "  \"draw_ms_max\": %.3f,\n  \"budget_ms\": %.3f,\n  \"frames_over_budget\": %u,\n"
        "  \"degrade\": {\"enabled\": %d, \"raises\": %u, \"lowers\": %u, \"scale_max\": %.3f},\n"
        "  \"tau_max_px\": %.4f,\n  \"frames_off_terrain\": %u,\n"
        "  \"frames_cache_behind\": %u,\n  \"frames_cache_coarser\": %u,\n"
        "  \"frames_cache_forced\": %u\n}\n",
        (unsigned long long)r->lines, (unsigned long long)r->lines_bad,
        (unsigned long long)r->lines_unsupported, (unsigned long long)r->gaps,
        (unsigned long long)r->timestamps_backwards,
        (unsigned long long)r->timestamps_out_of_range, (unsigned long long)f->frames_in,
        (unsigned long long)f->values_applied,
        (unsigned long long)f->dec.lost, (unsigned long long)f->dec.out_of_sequence, rejects,
        position, r->frames, r->frames_annunciated,
        r->first_annunciated == UINT32_MAX ? -1LL : (long long)r->first_annunciated,
        r->frames_predicted, r->log_first_s, r->log_last_s, r->frame.timing.render_ms_max,
        r->frame.degrade.budget_ms, r->frame.degrade.over_budget, r->frame.degrade.enabled,
        r->frame.degrade.raises, r->frame.degrade.lowers, r->frame.timing.degrade_scale_max,
        r->frame.timing.tau_max_px, r->frames_off_terrain, r->frames_cache_behind,
        r->frames_cache_coarser, r->frames_cache_forced);
    return write_stats_text(path, len, "replay", err);
}

static int cmd_replay(int argc, char **argv)
{
    ft_cli_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.command = "replay";
    sd.text = g_scene_text;
    sd.text_cap = sizeof g_scene_text;
    ft_replay_desc d;
    memset(&d, 0, sizeof d);
    const char *stats_path = NULL;
    int quiet = 0;
    const ft_cli_opt opts[] = {
        FT_CLI_OPT_STRING("--log", &d.log_path,
                          "--log FILE          "
                          "candump log: (SECONDS.MICROS) IFACE ID#HEXDATA per line"),
        FT_CLI_OPT_STRING("--scene", &sd.scene_path,
                          "--scene FILE        "
                          "scene file (CAN map, frame period, terrain, method)"),
        FT_CLI_OPT_STRING("--dem", &sd.dem,
                          "--dem FILE, --method NAME, --backend NAME, --size WxH   as for render"),
        FT_CLI_OPT_STRING("--method", &sd.method, NULL),
        FT_CLI_OPT_STRING("--backend", &sd.backend, NULL),
        FT_CLI_OPT_STRING("--size", &sd.size, NULL),
        FT_CLI_OPT_STRING("--frames-out", &d.frames_dir,
                          "--frames-out DIR    write every frame as DIR/frame_NNNNNN.png"),
        FT_CLI_OPT_STRING("--poses", &d.poses_path,
                          "--poses FILE.csv    "
                          "one row per frame: time, pose, annunciation, reason"),
        FT_CLI_OPT_STRING("--stats", &stats_path,
                          "--stats FILE.json   "
                          "counters: lines, rejects per reason, annunciated frames"),
        FT_CLI_OPT_U32("--frames", &d.frames_max, 1u, FT_REPLAY_FRAMES_LIMIT - 1u,
                       "--frames N          stop after N frames"),
        FT_CLI_OPT_FLAG("--quiet", &quiet, "--quiet             only errors"),
    };
    const ft_cli_desc cli = {"replay", opts, sizeof opts / sizeof opts[0]};
    int rc = ft_cli_parse(&cli, argc, argv, NULL);
    if (rc == FT_CLI_HELP) {
        printf("usage: fixterrain replay --log FILE [options]\n"
               "Feeds a candump log (as `candump -l` writes it) through the CANaerospace\n"
               "decoder and renders one frame per frame.period_ms of log time. Deterministic.\n\n");
        ft_cli_print_help(&cli);
        return FT_EXIT_OK;
    }
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    if (d.log_path == NULL) {
        fprintf(stderr, "fixterrain replay: --log FILE is required (see --help)\n");
        return FT_EXIT_USAGE;
    }
    static ft_scene scene;
    rc = ft_cli_scene_load(&sd, &scene, NULL);
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    ft_error err;
    memset(&err, 0, sizeof err);
    if (ft_app_init(&g_app, &scene, &err) != FT_OK) {
        fprintf(stderr, "fixterrain: init failed: %s: %s\n", ft_status_str(err.status), err.text);
        return FT_EXIT_ERROR;
    }
    static ft_replay_result r;
    ft_status st = ft_app_replay(&g_app, &d, &g_feed, &g_replay_io, &r, &err);
    for (uint32_t i = 0; i < r.errors_kept; ++i) {
        fprintf(stderr, "fixterrain replay: rejected %s\n", r.errors[i]);
    }
    const uint64_t rejected_lines = r.lines_bad + r.lines_unsupported + r.timestamps_backwards +
                                    r.timestamps_out_of_range;
    if (rejected_lines > r.errors_kept) {
        fprintf(stderr, "fixterrain replay: ... %llu rejected lines in all\n",
                (unsigned long long)rejected_lines);
    }
    if (st != FT_OK) {
        fprintf(stderr, "fixterrain replay: %s\n", err.text);
        rc = FT_EXIT_ERROR;
    }
    if (st == FT_OK && stats_path != NULL && write_replay_stats(stats_path, &r, &g_feed, &err) != FT_OK) {
        fprintf(stderr, "fixterrain replay: stats: %s\n", err.text);
        rc = FT_EXIT_ERROR;
    }
    if (!quiet) {
        printf("replay: %u frames over %.3f s of log (%llu lines, %llu rejected, %llu CAN frames, "
               "%llu decoder rejects, %llu lost, %llu out of sequence); %u frames annunciated",
               r.frames, r.log_last_s - r.log_first_s, (unsigned long long)r.lines,
               (unsigned long long)(r.lines_bad + r.lines_unsupported),
               (unsigned long long)g_feed.frames_in,
               (unsigned long long)ft_pose_feed_rejected(&g_feed),
               (unsigned long long)g_feed.dec.lost,
               (unsigned long long)g_feed.dec.out_of_sequence, r.frames_annunciated);
        if (r.first_annunciated != UINT32_MAX) {
            printf(" (first: frame %u)", r.first_annunciated);
        }
        printf("\n");
        if (r.timestamps_backwards + r.timestamps_out_of_range > 0u) {
            printf("replay: timestamps rejected: %llu backwards, %llu out of range (not fed)\n",
                   (unsigned long long)r.timestamps_backwards,
                   (unsigned long long)r.timestamps_out_of_range);
        }
        if (r.last_view.annunciate) {
            printf("replay: the last frame is annunciated: %s\n", r.last_view.reason);
        }
        if (scene.method == FT_METHOD_CLIPMAP) {
            printf("replay: clipmap cache: %u of %u frames drawn with a level behind, %u with "
                   "the eye's surroundings from a coarser level, %u completed the coarsest "
                   "level before drawing\n",
                   r.frames_cache_behind, r.frames, r.frames_cache_coarser,
                   r.frames_cache_forced);
        }
        if (r.frames_off_terrain > 0u) {
            double lat0, lat1, lon0, lon1;
            ft_terrain_extent_geo(&g_app.terrain, &lat0, &lat1, &lon0, &lon1);
            fprintf(stderr,
                    "fixterrain replay: warning: %u of %u frames were drawn from a position "
                    "that does not lie over the terrain %s (lat %.6f..%.6f, lon %.6f..%.6f); "
                    "the last at lat %.6f, lon %.6f\n",
                    r.frames_off_terrain, r.frames,
                    scene.dem_path[0] != '\0' ? scene.dem_path : "(synthetic terrain)", lat0,
                    lat1, lon0, lon1, r.last_off_lat_deg, r.last_off_lon_deg);
        }
        printf("replay: budget %.3f ms: %u frames over it (slowest %.1f ms); degradation %s "
               "(%u raises, %u lowers, LOD scale up to %.2f, error bound up to %.3f px)\n",
               r.frame.degrade.budget_ms, r.frame.degrade.over_budget,
               r.frame.timing.render_ms_max, r.frame.degrade.enabled ? "on" : "off",
               r.frame.degrade.raises, r.frame.degrade.lowers, r.frame.timing.degrade_scale_max,
               r.frame.timing.tau_max_px);
        printf("replay: position predicted from the velocity on %u frames (velocity stale on "
               "%u), %llu snaps, largest offset converged %.3f m\n",
               r.frames_pos_predicted, r.frames_velocity_stale,
               (unsigned long long)g_feed.ps.snap_count, g_feed.ps.offset_max_m);
    }
    ft_app_shutdown(&g_app);
    return rc;
}

#if FT_WITH_CAN && FT_WITH_GPIO
static volatile sig_atomic_t g_stop;
_Static_assert(sizeof(sig_atomic_t) == sizeof(int), "the stop flag is read as an int");

static void on_stop_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

static ft_live g_live;

static ft_status write_run_stats(const char *path, const ft_live_result *r, const ft_pose_feed *f,
                                 ft_error *err)
{
    char position[1024];
    if (json_position(f, r->frames_pos_predicted, r->frames_velocity_stale, position,
                      sizeof position) == 0u) {
        return ft_fail(err, FT_ERR_OVERSIZED, "run stats: position counters too long");
    }
    const ft_frame_timing *t = &r->frame.timing;
    const ft_degrade *dg = &r->frame.degrade;
    const double frames = r->frames > 0u ? (double)r->frames : 1.0;
    int len = snprintf(
        g_stats_text, sizeof g_stats_text,
        "{\n  \"frames\": %u,\n  \"deadline_misses\": %u,\n  \"frame_ms_max\": %.3f,\n%s"
        "  \"frames_annunciated\": %u,\n  \"frames_frozen\": %u,\n  \"frames_test\": %u,\n"
        "  \"frames_night\": %u,\n"
        "  \"frames_backup\": %u,\n  \"source_switches\": %u,\n"
        "  \"can_frames\": [%llu, %llu],\n  \"can_dropped\": [%llu, %llu],\n"
        "  \"decoder_rejects\": %llu,\n  \"messages_lost\": %llu,\n"
        "  \"messages_out_of_sequence\": %llu,\n"
        "  \"gpio_edges\": %llu,\n  \"gpio_changes\": %llu,\n  \"heartbeat_toggles\": %llu,\n"
        "  \"t_start_ns\": %llu,\n  \"t_first_rx_ns\": %llu,\n"
        "  \"stage_ms_mean\": {\"poll\": %.3f, \"select\": %.3f, \"draw\": %.3f, \"gpu\": %.3f},\n"
        "  \"stage_ms_max\": {\"poll\": %.3f, \"select\": %.3f, \"draw\": %.3f, \"gpu\": %.3f},\n"
        "  \"gpu_timer_ms\": {\"frames\": %u, \"mean\": %.3f, \"max\": %.3f},\n"
        "  \"budget_ms\": %.3f,\n  \"frames_over_budget\": %u,\n"
        "  \"degrade\": {\"enabled\": %d, \"raises\": %u, \"lowers\": %u, \"scale_max\": %.3f},\n"
        "  \"tau_max_px\": %.4f,\n"
        "  \"jobs\": {\"run\": %llu, \"deferred_frames\": %llu, \"refused\": %llu, \"high_water\": %u}\n}\n",
        r->frames, r->deadline_misses, r->frame_ms_max, position, r->frames_annunciated,
        r->frames_frozen,
        r->frames_test, r->frames_night, r->frames_backup, r->source_switches,
        (unsigned long long)r->can_frames[0], (unsigned long long)r->can_frames[1],
        (unsigned long long)r->can_dropped[0], (unsigned long long)r->can_dropped[1],
        (unsigned long long)ft_pose_feed_rejected(f), (unsigned long long)f->dec.lost,
        (unsigned long long)f->dec.out_of_sequence, (unsigned long long)r->gpio_edges,
        (unsigned long long)r->gpio_changes,
        (unsigned long long)r->heartbeat_toggles, (unsigned long long)r->t_start_ns,
        (unsigned long long)r->t_first_rx_ns, r->poll_ms_sum / frames, t->select_ms_sum / frames,
        t->draw_ms_sum / frames, t->gpu_ms_sum / frames, r->poll_ms_max, t->select_ms_max,
        t->draw_ms_max, t->gpu_ms_max, t->gpu_timer_frames,
        t->gpu_timer_ms_sum / (t->gpu_timer_frames ? t->gpu_timer_frames : 1u),
        t->gpu_timer_ms_max, dg->budget_ms, dg->over_budget, dg->enabled, dg->raises,
        dg->lowers, t->degrade_scale_max, t->tau_max_px, (unsigned long long)r->jobs_run,
        (unsigned long long)r->jobs_deferred_frames, (unsigned long long)r->jobs_refused,
        r->jobs_high_water);
    return write_stats_text(path, len, "run", err);
}

static int cmd_run(int argc, char **argv)
{
    ft_cli_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.command = "run";
    sd.text = g_scene_text;
    sd.text_cap = sizeof g_scene_text;
    ft_live_desc d;
    memset(&d, 0, sizeof d);
    const char *stats_path = NULL;
    int quiet = 0;
    const ft_cli_opt opts[] = {
        FT_CLI_OPT_STRING("--scene", &sd.scene_path,
                          "--scene FILE        "
                          "scene file (CAN map, interfaces, GPIO lines, period)"),
        FT_CLI_OPT_STRING("--dem", &sd.dem,
                          "--dem FILE, --method NAME, --backend NAME, --size WxH   as for render"),
        FT_CLI_OPT_STRING("--method", &sd.method, NULL),
        FT_CLI_OPT_STRING("--backend", &sd.backend, NULL),
        FT_CLI_OPT_STRING("--size", &sd.size, NULL),
        FT_CLI_OPT_STRING("--display", &sd.display,
                          "--display NAME      "
                          "none | x11 | kms[:/dev/dri/cardN]: on kms every frame is"
                          FT_HELP_CONT "page-flipped and present waits for the flip, so a late"
                          FT_HELP_CONT "flip is a deadline miss; SIGINT/SIGTERM restore the CRTC"),
        FT_CLI_OPT_STRING("--poses", &d.poses_path,
                          "--poses FILE.csv    "
                          "one row per frame: time, pose, annunciation, freeze, source"),
        FT_CLI_OPT_STRING("--stats", &stats_path,
                          "--stats FILE.json   "
                          "frames, deadline misses, CAN frames, rejects, GPIO, heartbeat"),
        FT_CLI_OPT_U32("--frames", &d.frames_max, 1u, 100000000u,
                       "--frames N          stop after N frames"),
        FT_CLI_OPT_FLAG("--quiet", &quiet, "--quiet             only errors"),
    };
    const ft_cli_desc cli = {"run", opts, sizeof opts / sizeof opts[0]};
    int rc = ft_cli_parse(&cli, argc, argv, NULL);
    if (rc == FT_CLI_HELP) {
        printf("usage: fixterrain run --scene FILE [options]\n"
               "Live: pose from SocketCAN (can.interface, can.backup_interface) and GPIO\n"
               "(gpio.*), one frame per frame.period_ms, until SIGINT/SIGTERM or --frames.\n\n");
        ft_cli_print_help(&cli);
        return FT_EXIT_OK;
    }
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    static ft_scene scene;
    rc = ft_cli_scene_load(&sd, &scene, NULL);
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    if (sigemptyset(&sa.sa_mask) != 0 || sigaction(SIGINT, &sa, NULL) != 0 ||
        sigaction(SIGTERM, &sa, NULL) != 0) {
        fprintf(stderr, "fixterrain run: cannot install the SIGINT/SIGTERM handlers\n");
        return FT_EXIT_ERROR;
    }
    ft_error err;
    memset(&err, 0, sizeof err);
    if (ft_app_init(&g_app, &scene, &err) != FT_OK) {
        fprintf(stderr, "fixterrain: init failed: %s: %s\n", ft_status_str(err.status), err.text);
        return FT_EXIT_ERROR;
    }
    if (!quiet) {
        printf("fixterrain run: %s on %s, CAN %s%s%s, GPIO %s, %.3f ms frames\n",
               ft_method_name(scene.method), ft_backend_name(scene.backend), scene.can_iface,
               scene.can_backup_iface[0] ? " + backup " : "", scene.can_backup_iface,
               scene.gpio_chip[0] ? scene.gpio_chip : "none", scene.frame_period_ms);
        (void)fflush(stdout);
    }
    d.stop = (const volatile int *)&g_stop;
    static ft_live_result r;
    ft_status st = ft_app_run_live(&g_app, &d, &g_live, &g_feed, &r, &err);
    if (st != FT_OK) {
        fprintf(stderr, "fixterrain run: %s\n", err.text);
        rc = FT_EXIT_ERROR;
    }
    if (stats_path != NULL && write_run_stats(stats_path, &r, &g_feed, &err) != FT_OK) {
        fprintf(stderr, "fixterrain run: stats: %s\n", err.text);
        rc = FT_EXIT_ERROR;
    }
    if (!quiet) {
        printf("run: %u frames, %u deadline misses (slowest %.1f ms), %u annunciated, "
               "CAN %llu + %llu frames (%llu rejected, %llu lost), %u source switches, "
               "%llu GPIO edges, %llu heartbeat toggles%s\n",
               r.frames, r.deadline_misses, r.frame_ms_max, r.frames_annunciated,
               (unsigned long long)r.can_frames[0], (unsigned long long)r.can_frames[1],
               (unsigned long long)ft_pose_feed_rejected(&g_feed),
               (unsigned long long)g_feed.dec.lost, r.source_switches,
               (unsigned long long)r.gpio_edges, (unsigned long long)r.heartbeat_toggles,
               g_stop ? " (stopped by a signal)" : "");
    }
    ft_app_shutdown(&g_app);
    return rc;
}
#endif

/* ---- fixterrain budget -------------------------------------------------------- */
/* The binary's own static footprint, from the ELF linker symbols (GNU ld and
 * lld define them for Linux executables). */
extern char __executable_start, etext, __data_start, edata, end;

/* "#define A 1\n#define B 0\n" -> "A=1 B=0" (or "none"). */
static void print_defines(const char *defines)
{
    int any = 0;
    const char *p = defines;
    for (int guard = 0; p != NULL && guard < 32; ++guard) {
        const char *d = strstr(p, "#define ");
        if (d == NULL) {
            break;
        }
        d += 8;
        const char *sp = strchr(d, ' ');
        const char *nl = strchr(d, '\n');
        if (sp == NULL || nl == NULL || sp > nl) {
            break;
        }
        printf("%s%.*s=%.*s", any ? " " : "", (int)(sp - d), d, (int)(nl - sp - 1), sp + 1);
        any = 1;
        p = nl + 1;
    }
    printf("%s", any ? "" : "none");
}

/* The shader variants this scene compiles: only the code it uses. */
static void print_shader_variants(const ft_scene *s, const ft_terrain *t, int es3)
{
    printf("shader variants: %s [", ft_method_vertex_shader(s));
    print_defines(ft_method_vertex_defines(s, es3));
    const char *coarse = ft_method_vertex_defines_coarse(s, es3);
    if (coarse != NULL) {
        printf("] and [");
        print_defines(coarse);
    }
    printf("], colour fragment shaders [");
    char buf[FT_SHADE_DEFINES_MAX];
    print_defines(ft_program_shade_defines(s, t, buf));
    char built[FT_SHADE_PARTS_MAX], left_out[FT_SHADE_PARTS_MAX];
    printf("] (colour parts in this build: %s; left out: %s)\n",
           ft_program_shade_parts(1, built), ft_program_shade_parts(0, left_out));
}

static int cmd_budget(int argc, char **argv)
{
    ft_cli_scene_desc sd;
    memset(&sd, 0, sizeof sd);
    sd.command = "budget";
    sd.text = g_scene_text;
    sd.text_cap = sizeof g_scene_text;
    /* the usage line below lists them */
    const ft_cli_opt opts[] = {
        FT_CLI_OPT_STRING("--scene", &sd.scene_path, NULL),
        FT_CLI_OPT_STRING("--dem", &sd.dem, NULL),
        FT_CLI_OPT_STRING("--method", &sd.method, NULL),
        FT_CLI_OPT_STRING("--backend", &sd.backend, NULL),
        FT_CLI_OPT_STRING("--size", &sd.size, NULL),
    };
    const ft_cli_desc cli = {"budget", opts, sizeof opts / sizeof opts[0]};
    int rc = ft_cli_parse(&cli, argc, argv, NULL);
    if (rc == FT_CLI_HELP) {
        printf("usage: fixterrain budget [--scene FILE] [--dem FILE] [--method NAME] "
               "[--backend NAME]\n"
               "                        [--size WxH]\n"
               "Initialises the scene (terrain, GPU, method) and prints every static memory\n"
               "pool, the binary's static footprint, GPU memory, and the worst-case triangles\n"
               "per frame and ray-cast pixels, each against its budget. Exit status 1 when\n"
               "any budget is exceeded (the message names it), 2 for a usage error.\n");
        return FT_EXIT_OK;
    }
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    static ft_scene scene;
    rc = ft_cli_scene_load(&sd, &scene, NULL);
    if (rc != FT_EXIT_OK) {
        return rc;
    }
    const size_t text_b = (size_t)(&etext - &__executable_start);
    const size_t data_b = (size_t)(&edata - &__data_start);
    const size_t bss_b = (size_t)(&end - &edata);
    printf("scene %s: method %s, %ux%u, backend %s\n", scene.name, ft_method_name(scene.method),
           scene.width_px, scene.height_px, ft_backend_name(scene.backend));
    printf("binary static footprint: text %zu, data %zu, bss %zu bytes (total %zu)\n", text_b,
           data_b, bss_b, text_b + data_b + bss_b);
    ft_error err;
    memset(&err, 0, sizeof err);
    if (ft_app_init(&g_app, &scene, &err) != FT_OK) {
        /* init checks every pool and the GPU budget first: the message names
         * the one exceeded and the numbers */
        fprintf(stderr, "fixterrain budget: OVER BUDGET or init failed: %s: %s\n",
                ft_status_str(err.status), err.text);
        return FT_EXIT_ERROR;
    }
    printf("static memory (one arena of %zu bytes, reserved at init, locked after it):\n%s",
           g_app.arena_bytes, g_app.pool_table);
    printf("GPU memory: %llu of %llu bytes (gpu.texture_bytes)\n",
           (unsigned long long)g_app.renderer.gpu_bytes,
           (unsigned long long)scene.gpu_texture_bytes);
    print_shader_variants(&scene, &g_app.terrain, g_app.gpu.gl.api == FT_GL_API_ES3);
    ft_method_worst worst;
    ft_method_worst_case(&g_app.renderer.method, &g_app.terrain, &worst);
    printf("worst-case triangles per frame: %llu\n", (unsigned long long)worst.triangles);
    printf("worst-case ray-cast pixels per frame: %llu\n", (unsigned long long)worst.raycast_px);
    printf("worst case: %s\n", worst.rule);
    printf("budget: every pool and the GPU memory fit\n");
    ft_app_shutdown(&g_app);
    return FT_EXIT_OK;
}

/* The benchmark and the DEM import are workstation tools with their own
 * binary (fixterrain-tools: GDAL, the plotter, heap use), so the runtime a
 * display computer runs contains none of them. For the user's convenience
 * `fixterrain bench|import` runs that binary from beside this one, then from
 * PATH; only the error path returns. */
#define FT_TOOLS_NAME "fixterrain-tools"
static int forward_to_tools(const char *cmd, char **argv)
{
    char path[4096];
    const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n > 0 && (size_t)n < sizeof path - 1) {
        path[n] = '\0';
        char *slash = strrchr(path, '/');
        if (slash != NULL && (size_t)(slash + 1 - path) + sizeof FT_TOOLS_NAME <= sizeof path) {
            memcpy(slash + 1, FT_TOOLS_NAME, sizeof FT_TOOLS_NAME);
            argv[0] = path;
            (void)execv(path, argv);
        }
    }
    argv[0] = (char *)FT_TOOLS_NAME;
    (void)execvp(FT_TOOLS_NAME, argv);
    fprintf(stderr,
            "fixterrain: '%s' is a workstation tool, not part of the display runtime: "
            "install %s beside fixterrain or on PATH (%s)\n",
            cmd, FT_TOOLS_NAME, strerror(errno));
    return FT_EXIT_ERROR;
}

/* fixterrain keys: every scene key, what it accepts, its default and meaning,
 * printed from the schema the parser uses (src/core/scene.h). */
static int cmd_keys(int argc, char **argv)
{
    if (argc > 1) {
        if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
            printf("usage: fixterrain keys\nLists every scene key: section.key, what it "
                   "accepts, its default and what it means.\n");
            return FT_EXIT_OK;
        }
        fprintf(stderr, "fixterrain keys: takes no options (see --help)\n");
        return FT_EXIT_USAGE;
    }
    size_t n = 0u;
    const ft_scene_key *k = ft_scene_keys(&n);
    for (size_t i = 0; i < n; ++i) {
        char accepts[512];
        printf("%s.%s\n    %s\n", k[i].section, k[i].key,
               k[i].kind == FT_KEY_LIST ? k[i].doc
                                        : ft_scene_key_accepts(&k[i], accepts, sizeof accepts));
        if (k[i].def != NULL) {
            printf("    default: %s\n", k[i].def[0] != '\0' ? k[i].def : "(empty)");
        }
        if (k[i].kind != FT_KEY_LIST) {
            printf("    %s\n", k[i].doc);
        }
    }
    return FT_EXIT_OK;
}

#if FT_WITH_CAN && FT_WITH_GPIO
#define FT_CMD_RUN cmd_run
#else
static int cmd_run_left_out(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "fixterrain: 'run' was left out of this build "
                    "(FIXTERRAIN_WITH_CAN and FIXTERRAIN_WITH_GPIO are needed)\n");
    return FT_EXIT_ERROR;
}
#define FT_CMD_RUN cmd_run_left_out
#endif

typedef struct command {
    const char *name;
    int (*fn)(int argc, char **argv); /* argv[0] is the command's name; NULL: a tool */
    const char *what;
} command;

static const command k_commands[] = {
    {"render", cmd_render, "render one frame of a scene offscreen to PNG"},
    {"replay", cmd_replay, "render a candump log of CANaerospace pose messages"},
    {"run", FT_CMD_RUN, "live: pose from CAN and GPIO, frames at the scene's rate"},
    {"budget", cmd_budget, "static memory, GPU memory and worst-case work against the budgets"},
    {"keys", cmd_keys, "every scene key: what it accepts, its default, what it means"},
    {"bench", NULL, "error against run time: every method and setting over flight paths"},
    {"import", NULL, "convert a DEM (GeoTIFF, .hgt, DTED, ...) to a .ftt terrain file"},
};
#define FT_COMMAND_COUNT (sizeof k_commands / sizeof k_commands[0])

static void print_help(void)
{
    printf("usage: fixterrain COMMAND [options]   (fixterrain COMMAND --help for details)\n\n"
           "commands:\n");
    for (size_t i = 0; i < FT_COMMAND_COUNT; ++i) {
        printf("  %-9s %s\n", k_commands[i].name, k_commands[i].what);
    }
    printf("  help      this text\n\n"
           "bench and import are tools: this runtime runs fixterrain-tools for them.\n"
           "fixterrain %s: fixed-resource terrain renderer (OpenGL ES 2/3 via EGL, OSMesa).\n",
           "0.1.0");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        return cmd_render(1, argv); /* no arguments: the embedded default scene */
    }
    const char *cmd = argv[1];
    for (size_t i = 0; i < FT_COMMAND_COUNT; ++i) {
        if (strcmp(cmd, k_commands[i].name) == 0) {
            return k_commands[i].fn != NULL ? k_commands[i].fn(argc - 1, argv + 1)
                                            : forward_to_tools(cmd, argv);
        }
    }
    if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
        print_help();
        return FT_EXIT_OK;
    }
    fprintf(stderr, "fixterrain: unknown command '%s'\n", cmd);
    print_help();
    return FT_EXIT_USAGE;
}
