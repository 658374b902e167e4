/* live.c - see live.h. */
#include "app/live.h"

#include <stdio.h>
#include <string.h>

#include "core/ft_ns.h"
#include "input/debounce.h"

/* One debounce slot per GPIO input line. */
_Static_assert(FT_DEBOUNCE_SLOTS_MAX == FT_GPIO_LINES_MAX, "debounce slots vs GPIO lines");

static ft_status write_pose_row(void *ctx, const void *row, size_t bytes)
{
    const ft_writer *w = (const ft_writer *)ctx;
    return w->write(w->ctx, row, bytes);
}

static ft_status open_inputs(ft_live *lv, const ft_scene *s, ft_error *err)
{
    uint16_t ids[FT_CAN_MAP_MAX];
    uint32_t n_ids = 0;
    for (uint32_t i = 0; i < s->can_map.count && i < FT_CAN_MAP_MAX; ++i) {
        ids[n_ids++] = s->can_map.e[i].can_id;
    }
    const char *iface[2] = {s->can_iface, s->can_backup_iface};
    for (int p = 0; p < 2; ++p) {
        if (iface[p][0] == '\0') {
            if (p == 0) {
                return ft_fail(err, FT_ERR_CONFIG, "run: can.interface is empty");
            }
            continue;
        }
        ft_status st = ft_plat_can_open(&lv->can[p], iface[p], ids, n_ids, err);
        if (st != FT_OK) {
            return st;
        }
        lv->can_open[p] = 1;
    }
    if (s->gpio_chip[0] == '\0') {
        return FT_OK;
    }
    int lines[FT_GPIO_LINES_MAX];
    lv->slot_count = 0;
    for (int fn = 0; fn < FT_GPIO_INPUT_COUNT; ++fn) {
        if (s->gpio_input_line[fn] >= 0 && lv->slot_count < FT_GPIO_LINES_MAX) {
            lines[lv->slot_count] = s->gpio_input_line[fn];
            lv->slot_fn[lv->slot_count] = fn;
            lv->slot_count += 1u;
        }
    }
    ft_status st = ft_plat_gpio_open(&lv->gpio, s->gpio_chip, lines, lv->slot_count,
                                     s->gpio_heartbeat_line, err);
    if (st != FT_OK) {
        return st;
    }
    lv->gpio_open = 1;
    if (lv->slot_count > 0u) {
        int levels[FT_GPIO_LINES_MAX];
        st = ft_plat_gpio_levels(&lv->gpio, levels, err);
        if (st == FT_OK) {
            st = ft_debounce_init(&lv->deb, lv->slot_count, s->gpio_debounce_ms,
                                  s->gpio_active_low, levels, ft_plat_monotonic_ns(), err);
        }
    }
    return st;
}

static void close_inputs(ft_live *lv)
{
    for (int p = 0; p < 2; ++p) {
        if (lv->can_open[p]) {
            ft_plat_can_close(&lv->can[p]);
            lv->can_open[p] = 0;
        }
    }
    if (lv->gpio_open) {
        ft_plat_gpio_close(&lv->gpio);
        lv->gpio_open = 0;
    }
}

/* Drains one port; feeds the frames when this port is the active source. */
static ft_status drain_can(ft_live *lv, int port, int active, ft_pose_feed *feed,
                           ft_live_result *r, ft_error *err)
{
    for (uint32_t b = 0; b < FT_LIVE_CAN_BATCHES_MAX; ++b) {
        uint32_t got = 0;
        ft_status st = ft_plat_can_read(&lv->can[port], lv->batch, FT_LIVE_CAN_BATCH, &got, err);
        if (st != FT_OK) {
            return st;
        }
        for (uint32_t i = 0; i < got; ++i) {
            const uint64_t t = lv->batch[i].t_ns;
            if (t > lv->last_rx_ns[port]) lv->last_rx_ns[port] = t;
            if (r->t_first_rx_ns == 0u) r->t_first_rx_ns = t;
            if (active) {
                ft_pose_feed_frame(feed, &lv->batch[i]);
            } else {
                /* keep the standby source's newest frames: a failover
                 * feeds them at once instead of waiting a frame */
                lv->hold[port][lv->hold_next[port]] = lv->batch[i];
                lv->hold_next[port] = (lv->hold_next[port] + 1u) % FT_LIVE_HOLD;
                if (lv->hold_count[port] < FT_LIVE_HOLD) lv->hold_count[port] += 1u;
            }
        }
        r->can_frames[port] += got;
        if (got < FT_LIVE_CAN_BATCH) {
            break;
        }
    }
    r->can_dropped[port] = lv->can[port].rx_dropped;
    return FT_OK;
}

/* Feeds the frames held for a standby port, oldest first, and empties it. */
static void feed_held(ft_live *lv, int port, ft_pose_feed *feed)
{
    const uint32_t n = lv->hold_count[port];
    const uint32_t first = (lv->hold_next[port] + FT_LIVE_HOLD - n) % FT_LIVE_HOLD;
    for (uint32_t i = 0; i < n; ++i) {
        ft_pose_feed_frame(feed, &lv->hold[port][(first + i) % FT_LIVE_HOLD]);
    }
    lv->hold_count[port] = 0u;
}

static ft_status poll_gpio(ft_live *lv, uint64_t now_ns, ft_live_result *r, ft_error *err)
{
    if (!lv->gpio_open || lv->slot_count == 0u) {
        return FT_OK;
    }
    for (uint32_t b = 0; b < FT_LIVE_CAN_BATCHES_MAX; ++b) {
        uint32_t got = 0;
        ft_status st = ft_plat_gpio_read_edges(&lv->gpio, lv->edges, FT_GPIO_EVENTS_MAX, &got, err);
        if (st != FT_OK) {
            return st;
        }
        for (uint32_t i = 0; i < got; ++i) {
            ft_debounce_change ch;
            r->gpio_changes += (uint64_t)ft_debounce_edge(&lv->deb, lv->edges[i].slot,
                                                          lv->edges[i].rising, lv->edges[i].t_ns,
                                                          &ch);
        }
        r->gpio_edges += got;
        if (got < FT_GPIO_EVENTS_MAX) {
            break;
        }
    }
    ft_debounce_change ch[FT_GPIO_LINES_MAX];
    r->gpio_changes += ft_debounce_poll(&lv->deb, now_ns, ch, FT_GPIO_LINES_MAX);
    return FT_OK;
}

static int input_active(const ft_live *lv, ft_gpio_input fn)
{
    for (uint32_t i = 0; i < lv->slot_count; ++i) {
        if (lv->slot_fn[i] == (int)fn) {
            return ft_debounce_active(&lv->deb, i);
        }
    }
    return 0;
}

ft_status ft_app_run_live(ft_app *app, const ft_live_desc *d, ft_live *lv, ft_pose_feed *feed,
                          ft_live_result *r, ft_error *err)
{
    memset(r, 0, sizeof *r);
    memset(lv, 0, sizeof *lv);
    ft_jobs_init(&lv->jobs);
    const ft_scene *s = &app->scene;
    ft_status st = ft_pose_feed_init(feed, &s->can_map, s->pose_horizon_ms, &s->pose, err);
    if (st == FT_OK) {
        st = ft_pose_feed_set_position(feed, s->pose_converge_ms, s->pose_snap_m,
                                       s->pose_velocity_required, err);
    }
    if (st == FT_OK) {
        st = open_inputs(lv, s, err);
    }
    int poses = 0;
    if (st == FT_OK && d->poses_path != NULL) {
        st = ft_plat_file_open_write(&lv->pose_file, d->poses_path, err);
        if (st == FT_OK) {
            poses = 1;
            static const char header[] = FT_POSE_ROW_HEADER;
            st = lv->pose_file.writer.write(lv->pose_file.writer.ctx, header, sizeof header - 1u);
        }
    }
    /* Warm-up frame before the schedule starts: drivers compile shaders at
     * their first draw (seconds on a software rasteriser), which would
     * otherwise be the first deadline miss. It shows the annunciation test
     * (a power-up lamp test), which also compiles the overlay's program. */
    if (st == FT_OK) {
        ft_camera cam;
        ft_frame_stats fs;
        st = ft_app_render_annunciated(app, &s->pose, FT_LIVE_TEST_REASON, &cam, &fs, err);
    }
    uint64_t period_ns = 0u;
    if (st == FT_OK && !ft_ns_from_ms(s->frame_period_ms, 1.0, 1000.0, &period_ns)) {
        st = ft_fail(err, FT_ERR_CONFIG, "run: frame.period_ms %g is not in 1..1000",
                     s->frame_period_ms);
    }
    ft_frame_loop_init(&r->frame, app, 1);
    const uint64_t failover_ns = (uint64_t)s->can_failover_ms * 1000000u;
    int source = 0, frozen = 0, heartbeat = 0;
    ft_pose frozen_pose = s->pose;
    uint64_t t_base = ft_plat_monotonic_ns(), k_base = 0;
    r->t_start_ns = t_base;
    const uint32_t frames_max = d->frames_max ? d->frames_max : UINT32_MAX;
    for (uint32_t k = 0; st == FT_OK && k < frames_max; ++k) {
        if (d->stop != NULL && *d->stop) {
            break;
        }
        /* saturating: a schedule past the end of the clock is simply late */
        uint64_t since_base_ns = 0u;
        (void)ft_ns_mul((uint64_t)k - k_base, period_ns, &since_base_ns);
        const uint64_t t_due = ft_ns_add_sat(t_base, since_base_ns);
        const uint64_t t_next_ns = ft_ns_add_sat(t_due, period_ns);
        uint64_t now = ft_plat_monotonic_ns();
        const uint64_t t_poll0 = now;
        st = poll_gpio(lv, now, r, err);
        for (int p = 0; p < 2 && st == FT_OK; ++p) {
            if (lv->can_open[p]) {
                st = drain_can(lv, p, p == source, feed, r, err);
            }
        }
        if (st != FT_OK) {
            break;
        }
        /* source: the backup on request, or while the primary has been
         * silent for can.failover_ms and the backup has not; on a switch the
         * new source's held frames feed this very frame */
        now = ft_plat_monotonic_ns();
        int want = 0;
        if (lv->can_open[1]) {
            const int primary_silent = now > ft_ns_add_sat(lv->last_rx_ns[0], failover_ns);
            const int backup_alive = now <= ft_ns_add_sat(lv->last_rx_ns[1], failover_ns);
            want = input_active(lv, FT_GPIO_SOURCE) || (primary_silent && backup_alive);
        }
        if (want != source) {
            source = want;
            r->source_switches += 1u;
            feed_held(lv, source, feed);
        }
        ft_pose_view v;
        now = ft_plat_monotonic_ns();
        const double poll_ms = (double)ft_ns_sub_sat(now, t_poll0) * 1e-6;
        ft_pose_feed_view(feed, now, &v);
        const int freeze = input_active(lv, FT_GPIO_FREEZE);
        if (freeze && !frozen) {
            frozen_pose = v.pose;
        }
        frozen = freeze;
        const ft_pose *draw_pose = frozen ? &frozen_pose : &v.pose;
        ft_palette palette = app->scene.present_palette;
#if FT_WITH_NIGHT_PALETTE
        /* the palette switch takes effect on this very frame (a build
         * without the night palette refuses gpio.night_line at init) */
        if (input_active(lv, FT_GPIO_NIGHT)) {
            palette = FT_PALETTE_NIGHT;
        }
        ft_renderer_set_palette(&app->renderer, palette);
#endif
        const int test = input_active(lv, FT_GPIO_TEST);
        const char *reason = test ? FT_LIVE_TEST_REASON : (v.annunciate ? v.reason : NULL);
        ft_frame fr;
        st = ft_frame_step(&r->frame, app, draw_pose, reason, &fr, err);
        if (st != FT_OK) {
            break;
        }
        r->poll_ms_sum += poll_ms;
        if (poll_ms > r->poll_ms_max) r->poll_ms_max = poll_ms;
        if (lv->gpio_open && s->gpio_heartbeat_line >= 0) {
            heartbeat = !heartbeat;
            st = ft_plat_gpio_set_output(&lv->gpio, heartbeat, err);
            r->heartbeat_toggles += 1u;
        }
        r->frames += 1u;
        r->frames_annunciated += (reason != NULL);
        r->frames_frozen += (uint32_t)frozen;
        r->frames_test += (uint32_t)test;
        r->frames_night += (uint32_t)(palette == FT_PALETTE_NIGHT);
        r->frames_backup += (uint32_t)source;
        r->frames_pos_predicted += (uint32_t)(v.pos_predicted != 0);
        r->frames_velocity_stale += (uint32_t)((v.stale_mask & FT_QTY_VELOCITY_MASK) != 0u);
        if (poses && st == FT_OK) {
            char row[FT_POSE_ROW_MAX];
            ft_pose_view shown = v;
            shown.pose = *draw_pose;
            shown.annunciate = reason != NULL;
            if (test) {
                (void)snprintf(shown.reason, sizeof shown.reason, "%s", FT_LIVE_TEST_REASON);
            }
            size_t n = ft_pose_row_format(row, sizeof row, k, now, &shown, frozen, source,
                                          fr.lod_scale, fr.stats.tau_achieved_px);
            if (n == 0u) {
                st = ft_fail(err, FT_ERR_OVERSIZED, "pose row too long");
            } else if (ft_jobs_push(&lv->jobs, write_pose_row, &lv->pose_file.writer,
                                    FT_LIVE_JOB_COST_NS, row, n, NULL) != FT_OK) {
                /* the queue is full: write now rather than lose the row */
                st = lv->pose_file.writer.write(lv->pose_file.writer.ctx, row, n);
            }
        }
        if (st == FT_OK) {
            st = ft_jobs_run(&lv->jobs, ft_plat_monotonic_ns, t_next_ns, 0, err);
        }
        const uint64_t t_end = ft_plat_monotonic_ns();
        const double ms = (double)ft_ns_sub_sat(t_end, t_due) * 1e-6;
        if (ms > r->frame_ms_max) r->frame_ms_max = ms;
        if (t_end > t_next_ns) {
            /* missed: count it and start a new schedule from now rather
             * than drawing the missed frames back to back */
            r->deadline_misses += 1u;
            t_base = t_end;
            k_base = (uint64_t)k + 1u;
        } else {
            const uint64_t wait_ns = t_next_ns - t_end;
            ft_plat_sleep_ns(wait_ns);
        }
    }
    if (st == FT_OK) {
        st = ft_jobs_run(&lv->jobs, ft_plat_monotonic_ns, 0, 1, err); /* the rest, now */
    }
    r->jobs_run = lv->jobs.run;
    r->jobs_deferred_frames = lv->jobs.deferred_frames;
    r->jobs_refused = lv->jobs.refused;
    r->jobs_high_water = lv->jobs.high_water;
    if (poses) {
        if (st == FT_OK) {
            st = ft_plat_file_finish_write(&lv->pose_file, err);
        }
        ft_plat_file_close(&lv->pose_file);
    }
    close_inputs(lv);
    return st;
}
