/* replay.c - see replay.h. */
#include "app/replay.h"

#include "terrain/default_view.h"

#include <stdio.h>
#include <string.h>

#include "core/ft_ns.h"
#include "core/line_reader.h"
#include "input/candump.h"

#define NS_PER_S UINT64_C(1000000000)

ft_replay_ts ft_replay_timeline_accept(ft_replay_timeline *tl, uint64_t t_ns)
{
    if (t_ns > FT_REPLAY_T_MAX_NS ||
        (tl->anchored && t_ns > tl->anchor_ns &&
         t_ns - tl->anchor_ns > (uint64_t)FT_REPLAY_SPAN_MAX_S * NS_PER_S)) {
        tl->out_of_range += 1u;
        return FT_REPLAY_TS_OUT_OF_RANGE;
    }
    if (tl->anchored && t_ns < tl->last_ns) {
        tl->backwards += 1u;
        return FT_REPLAY_TS_BACKWARDS;
    }
    if (!tl->anchored) {
        tl->anchored = 1;
        tl->anchor_ns = t_ns;
    }
    tl->last_ns = t_ns;
    return FT_REPLAY_TS_OK;
}

/* "1700000000.123456" (the candump spelling; whole microseconds) */
static void ts_text(uint64_t t_ns, char out[32])
{
    (void)snprintf(out, 32, "%llu.%06llu", (unsigned long long)(t_ns / NS_PER_S),
                   (unsigned long long)((t_ns % NS_PER_S) / 1000u));
}


/* A long path keeps its end (the file's name says which log), not its start. */
#define LOG_NAME_KEPT 60u

static void keep_error(ft_replay_result *r, const char *log, uint64_t line_no, const char *text)
{
    if (r->errors_kept < FT_REPLAY_ERRORS_KEPT) {
        const size_t len = strlen(log);
        const char *lead = len > LOG_NAME_KEPT ? "..." : "";
        const char *tail = len > LOG_NAME_KEPT ? log + (len - (LOG_NAME_KEPT - 3u)) : log;
        (void)snprintf(r->errors[r->errors_kept], FT_REPLAY_ERROR_TEXT_MAX, "%s%s:%llu: %.120s", lead,
                       tail, (unsigned long long)line_no, text);
        r->errors_kept += 1u;
    }
}

/* Next valid record from the log; *have = 0 at the end. Bad lines are
 * counted and skipped (bounded by the file: every pass consumes a line). */
static ft_status next_record(ft_line_reader *lr, const char *log, ft_replay_result *r,
                             ft_replay_timeline *tl, ft_candump_record *rec, int *have,
                             ft_error *err)
{
    *have = 0;
    for (;;) {
        ft_line_kind kind;
        ft_status st = ft_line_reader_next(lr, &kind, err);
        if (st != FT_OK) {
            return st;
        }
        if (kind == FT_LINE_END) {
            return FT_OK;
        }
        r->lines += 1u;
        if (kind == FT_LINE_OVERLONG) {
            r->lines_bad += 1u;
            keep_error(r, log, lr->line_no, "line longer than the reader's limit");
            continue;
        }
        if (lr->len == 0u) {
            continue; /* blank lines are allowed (candump never writes them) */
        }
        ft_error e;
        st = ft_candump_parse_line(lr->line, lr->len, rec, &e);
        if (st == FT_OK) {
            const ft_replay_ts ts = ft_replay_timeline_accept(tl, rec->frame.t_ns);
            if (ts == FT_REPLAY_TS_OK) {
                *have = 1;
                return FT_OK;
            }
            char t_txt[32], ref_txt[32], why[FT_REPLAY_ERROR_TEXT_MAX];
            ts_text(rec->frame.t_ns, t_txt);
            if (ts == FT_REPLAY_TS_BACKWARDS) {
                r->timestamps_backwards += 1u;
                ts_text(tl->last_ns, ref_txt);
                (void)snprintf(why, sizeof why,
                               "timestamp %s s is earlier than the previous accepted frame's "
                               "%s s",
                               t_txt, ref_txt);
            } else {
                r->timestamps_out_of_range += 1u;
                if (tl->anchored && rec->frame.t_ns <= FT_REPLAY_T_MAX_NS) {
                    ts_text(tl->anchor_ns, ref_txt);
                    (void)snprintf(why, sizeof why,
                                   "timestamp %s s is more than %u s after the first frame's "
                                   "%s s",
                                   t_txt, FT_REPLAY_SPAN_MAX_S, ref_txt);
                } else {
                    ts_text(FT_REPLAY_T_MAX_NS, ref_txt);
                    (void)snprintf(why, sizeof why,
                                   "timestamp %s s is past the end of the replay timeline "
                                   "(%s s)",
                                   t_txt, ref_txt);
                }
            }
            keep_error(r, log, lr->line_no, why);
            continue;
        }
        if (st == FT_ERR_UNSUPPORTED) {
            r->lines_unsupported += 1u;
        } else {
            r->lines_bad += 1u;
        }
        keep_error(r, log, lr->line_no, e.text);
    }
}

static ft_status write_row(ft_writer *w, uint32_t frame, uint64_t t_ns, const ft_pose_view *v,
                           double lod_scale, double tau_px, ft_error *err)
{
    char row[FT_POSE_ROW_MAX];
    size_t n = ft_pose_row_format(row, sizeof row, frame, t_ns, v, 0, 0, lod_scale, tau_px);
    if (n == 0u) {
        return ft_fail(err, FT_ERR_OVERSIZED, "pose record row longer than %u bytes",
                       FT_POSE_ROW_MAX);
    }
    return w->write(w->ctx, row, n);
}

ft_status ft_app_replay(ft_app *app, const ft_replay_desc *d, ft_pose_feed *feed,
                        ft_replay_io *io, ft_replay_result *r, ft_error *err)
{
    memset(r, 0, sizeof *r);
    r->first_annunciated = UINT32_MAX;
    const ft_scene *s = &app->scene;
    if (d->frames_dir != NULL && !FT_WITH_PNG) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "--frames-out: PNG output was left out of this build (FIXTERRAIN_WITH_PNG)");
    }
    ft_status st = ft_pose_feed_init(feed, &s->can_map, s->pose_horizon_ms, &s->pose, err);
    if (st == FT_OK) {
        st = ft_pose_feed_set_position(feed, s->pose_converge_ms, s->pose_snap_m,
                                       s->pose_velocity_required, err);
    }
    if (st != FT_OK) {
        return st;
    }
    uint64_t period_ns = 0u;
    if (!ft_ns_from_ms(s->frame_period_ms, 1.0, 1000.0, &period_ns)) {
        return ft_fail(err, FT_ERR_CONFIG, "replay: frame.period_ms %g is not in 1..1000",
                       s->frame_period_ms);
    }
    _Static_assert(FT_REPLAY_T_HEADROOM_NS >= UINT64_C(1000000000),
                   "one display period (at most 1 s) fits after the last accepted frame");
    ft_frame_loop_init(&r->frame, app, 1);
    const uint64_t gap_ns = (uint64_t)(FT_REPLAY_GAP_MAX_S * 1e9);
    ft_file *const log_file = &io->log_file, *const pose_file = &io->pose_file;
    ft_line_reader *const lr = &io->lr;
    st = ft_plat_file_open_read(log_file, d->log_path, err);
    if (st != FT_OK) {
        return st;
    }
    ft_line_reader_init(lr, &log_file->reader);
    int poses = 0;
    if (d->poses_path != NULL) {
        st = ft_plat_file_open_write(pose_file, d->poses_path, err);
        if (st != FT_OK) {
            ft_plat_file_close(log_file);
            return st;
        }
        poses = 1;
        static const char header[] = FT_POSE_ROW_HEADER;
        st = pose_file->writer.write(pose_file->writer.ctx, header, sizeof header - 1u);
    }

    ft_candump_record rec;
    ft_replay_timeline tl;
    memset(&tl, 0, sizeof tl);
    int have = 0;
    if (st == FT_OK) {
        st = next_record(lr, d->log_path, r, &tl, &rec, &have, err);
    }
    if (st == FT_OK && !have) {
        st = ft_fail(err, FT_ERR_FORMAT,
                     "%s: no valid CAN frame in %llu lines (%llu timestamps out of range)",
                     d->log_path, (unsigned long long)r->lines,
                     (unsigned long long)r->timestamps_out_of_range);
    }
    uint64_t t_display = have ? rec.frame.t_ns : 0u;
    uint64_t t_last = t_display;
    r->log_first_s = (double)t_display * 1e-9;
    const uint32_t frames_max =
        (d->frames_max > 0u && d->frames_max < FT_REPLAY_FRAMES_LIMIT) ? d->frames_max
                                                                       : FT_REPLAY_FRAMES_LIMIT;
    for (uint32_t k = 0; st == FT_OK && k < frames_max; ++k) {
        /* feed everything up to this frame's display time */
        while (have && rec.frame.t_ns <= t_display) {
            ft_pose_feed_frame(feed, &rec.frame);
            t_last = rec.frame.t_ns > t_last ? rec.frame.t_ns : t_last;
            st = next_record(lr, d->log_path, r, &tl, &rec, &have, err);
            if (st != FT_OK) {
                break;
            }
            /* accepted frames never go backwards: rec.frame.t_ns >= t_last */
            if (have && ft_ns_sub_sat(rec.frame.t_ns, t_last) > gap_ns) {
                r->gaps += 1u; /* resume the timeline at the later frame */
                t_display = rec.frame.t_ns;
            }
        }
        if (st != FT_OK) {
            break;
        }
        ft_pose_view v;
        ft_pose_feed_view(feed, t_display, &v);
        ft_frame fr;
        st = ft_frame_step(&r->frame, app, &v.pose, v.annunciate ? v.reason : NULL, &fr, err);
        if (st != FT_OK) {
            break;
        }
        r->frames += 1u;
        r->frames_predicted += (uint32_t)v.predicted;
        r->frames_cache_behind += (uint32_t)(fr.stats.cache_levels_behind > 0u);
        r->frames_cache_coarser += (uint32_t)(fr.stats.cache_coarser != 0);
        r->frames_cache_forced += (uint32_t)(fr.stats.cache_forced_updates > 0u);
        r->frames_pos_predicted += (uint32_t)(v.pos_predicted != 0);
        r->frames_velocity_stale += (uint32_t)((v.stale_mask & FT_QTY_VELOCITY_MASK) != 0u);
        /* a method reading the clip cache over a .ftd draws the database
         * past the window: no position over the database is off its terrain */
        const int terrain_goes_on = app->terrain.db != NULL && ft_method_reads_cache(&app->scene);
        if ((v.stale_mask & FT_QTY_POSITION_MASK) == 0u && !terrain_goes_on &&
            !ft_pose_over_terrain(&app->terrain, &v.pose)) {
            r->frames_off_terrain += 1u;
            r->last_off_lat_deg = v.pose.lat_deg;
            r->last_off_lon_deg = v.pose.lon_deg;
        }
        if (v.annunciate) {
            r->frames_annunciated += 1u;
            if (r->first_annunciated == UINT32_MAX) r->first_annunciated = k;
        }
        r->last_view = v;
        if (poses) {
            st = write_row(&pose_file->writer, k, t_display, &v, fr.lod_scale,
                           fr.stats.tau_achieved_px, err);
        }
        if (st == FT_OK && d->frames_dir != NULL) {
            char path[FT_PATH_MAX];
            int n = snprintf(path, sizeof path, "%s/frame_%06u.png", d->frames_dir, k);
            if (n < 0 || (size_t)n >= sizeof path) {
                st = ft_fail(err, FT_ERR_ARG, "--frames-out path too long");
            } else {
#if FT_WITH_PNG
                st = ft_plat_png_write(path, app->renderer.rgba, s->width_px, s->height_px,
                                       &app->arena, err);
#endif
            }
        }
        if (!have && t_display >= t_last) {
            break; /* the log is done and this frame showed its end */
        }
        /* Cannot fail: t_display <= the last accepted timestamp <=
         * FT_REPLAY_T_MAX_NS, 10 s below the end of the clock. Ending the
         * run is still the answer if it ever did. */
        if (!ft_ns_add(t_display, period_ns, &t_display)) {
            break;
        }
    }
    r->log_last_s = (double)t_last * 1e-9;
    if (poses) {
        if (st == FT_OK) {
            st = ft_plat_file_finish_write(pose_file, err);
        }
        ft_plat_file_close(pose_file);
    }
    ft_plat_file_close(log_file);
    return st;
}
