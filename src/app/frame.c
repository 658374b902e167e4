#include "app/frame.h"

#include <string.h>

#include "lod/method.h"

void ft_frame_loop_init(ft_frame_loop *fl, ft_app *app, int allow_degrade)
{
    const ft_scene *s = &app->scene;
    memset(fl, 0, sizeof *fl);
    ft_degrade_init(&fl->degrade, allow_degrade && s->frame_degrade,
                    s->frame_budget_ms > 0.0 ? s->frame_budget_ms : s->frame_period_ms,
                    s->frame_degrade_max_scale);
    (void)ft_method_set_lod_scale(&app->renderer.method, 1.0);
    fl->timing.degrade_scale_max = fl->degrade.scale;
}

static void add_max(double *sum, double *max, double v)
{
    *sum += v;
    if (v > *max) *max = v;
}

ft_status ft_frame_step(ft_frame_loop *fl, ft_app *app, const ft_pose *pose,
                        const char *annunciation, ft_frame *out, ft_error *err)
{
    out->lod_scale = fl->degrade.scale;
    const uint64_t t_start_ns = ft_plat_monotonic_ns();
    ft_status st = ft_app_render_annunciated(app, pose, annunciation, &out->cam, &out->stats, err);
    if (st != FT_OK) {
        return st;
    }
    /* the method's deferred work (the clipmap cache's reads and uploads) in
     * what is left of this frame's period */
    const uint64_t period_ns = (uint64_t)(app->scene.frame_period_ms * 1e6);
    ft_method_spare(&app->renderer.method, ft_plat_monotonic_ns, t_start_ns + period_ns);
    const ft_frame_stats *fs = &out->stats;
    ft_frame_timing *t = &fl->timing;
    out->render_ms = fs->select_ms + fs->gpu_ms;
    if (ft_degrade_frame(&fl->degrade, out->render_ms)) {
        (void)ft_method_set_lod_scale(&app->renderer.method, fl->degrade.scale);
    }
    t->frames += 1u;
    if (out->render_ms > t->render_ms_max) t->render_ms_max = out->render_ms;
    add_max(&t->select_ms_sum, &t->select_ms_max, fs->select_ms);
    add_max(&t->draw_ms_sum, &t->draw_ms_max, fs->cpu_ms);
    add_max(&t->gpu_ms_sum, &t->gpu_ms_max, fs->gpu_ms);
    if (fs->gpu_timer_ms >= 0.0) {
        t->gpu_timer_frames += 1u;
        add_max(&t->gpu_timer_ms_sum, &t->gpu_timer_ms_max, fs->gpu_timer_ms);
    }
    if (fs->tau_achieved_px > t->tau_max_px) t->tau_max_px = fs->tau_achieved_px;
    if (fl->degrade.scale > t->degrade_scale_max) t->degrade_scale_max = fl->degrade.scale;
    return FT_OK;
}
