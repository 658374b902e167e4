/* frame.h - one frame through the middle of the pipeline: the pose a loop
 * settled on -> LOD selection -> draw (with the annunciation, if any) ->
 * readback and present -> the degradation policy, into one timing record.
 *
 * Every command's loop calls it: render and bench (degradation off: they
 * measure the settings as set), replay (one frame per period of log time)
 * and run (live inputs on a schedule, jobs in the time left). What differs
 * stays with the loop: where the pose comes from (inputs -> pose) before the
 * step, and after it the metric on the frame just drawn (ft_app_measure) and
 * the jobs. */
#ifndef FT_FRAME_H
#define FT_FRAME_H

#include <stdint.h>

#include "app/app.h"
#include "lod/degrade.h"

/* What the frames of one loop cost, stage by stage. */
typedef struct ft_frame_timing {
    uint32_t frames;
    double render_ms_max; /* selection + draw to finish: what the degrade policy sees */
    double select_ms_sum, select_ms_max; /* LOD selection (CPU) */
    double draw_ms_sum, draw_ms_max;     /* frame submission (CPU) */
    double gpu_ms_sum, gpu_ms_max;       /* submission + finish */
    uint32_t gpu_timer_frames;           /* frames with a timer query result */
    double gpu_timer_ms_sum, gpu_timer_ms_max;
    double tau_max_px;        /* worst error bound a frame's LOD met (bintree) */
    double degrade_scale_max; /* coarsest LOD scale drawn */
} ft_frame_timing;

typedef struct ft_frame_loop {
    ft_degrade degrade; /* frame.budget_ms: frames over it, LOD scale steps */
    ft_frame_timing timing;
} ft_frame_loop;

/* One frame's result. */
typedef struct ft_frame {
    ft_camera cam;
    ft_frame_stats stats;
    double render_ms; /* selection + draw to finish */
    double lod_scale; /* the LOD scale the frame was drawn with (1 = the scene's) */
} ft_frame;

/* Starts a loop on app: the LOD at the scene's own setting, and the
 * degradation policy on when the scene asks for it and allow_degrade is 1. */
void ft_frame_loop_init(ft_frame_loop *fl, ft_app *app, int allow_degrade);

/* Draws one frame at pose (annunciation: NULL, or the reason shown with the
 * failure cross), then feeds its time to the degradation policy, which may
 * change the LOD scale for the next frame. */
ft_status ft_frame_step(ft_frame_loop *fl, ft_app *app, const ft_pose *pose,
                        const char *annunciation, ft_frame *out, ft_error *err);

#endif
