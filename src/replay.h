/* replay.h - `fixterrain replay`: a candump log through the same decoder and
 * pose feed the live input uses, rendered at the scene's frame rate in log
 * time. Deterministic: no wall clock takes part in any decision, so the same
 * log and scene give the same poses, annunciations and images every run.
 *
 * Timeline: display time t_k = t_first + k * frame.period_ms, where t_first
 * is the first valid frame's timestamp. Before frame k is drawn, every log
 * frame with timestamp <= t_k has been fed. The run ends after the frame at
 * or past the last log timestamp (or after frames_max frames). A forward jump
 * of more than FT_REPLAY_GAP_MAX_S between consecutive log frames is a
 * discontinuity (a log spliced from two sessions): counted, and the timeline
 * restarts at the later frame instead of rendering hours of stale frames.
 *
 * Bad input never stops the replay: an unparseable or overlong line is
 * counted (the first FT_REPLAY_ERRORS_KEPT messages are kept with their line
 * numbers), a frame the decoder rejects is counted per reason, and the pose
 * stays on the last good values with the annunciation drawn once a quantity
 * is past its timeout. */
#ifndef FT_REPLAY_H
#define FT_REPLAY_H

#include <stdint.h>

#include "app.h"
#include "degrade.h"
#include "pose_feed.h"

#define FT_REPLAY_ERRORS_KEPT 8u
#define FT_REPLAY_ERROR_TEXT_MAX 200u
#define FT_REPLAY_GAP_MAX_S 60.0
#define FT_REPLAY_FRAMES_LIMIT 10000000u /* hard bound on one run's frames */

typedef struct ft_replay_desc {
    const char *log_path;
    const char *frames_dir; /* NULL: no images; else DIR/frame_NNNNNN.png */
    const char *poses_path; /* NULL: no pose record; else a CSV, one row per frame */
    uint32_t frames_max;    /* 0: until the log ends */
} ft_replay_desc;

typedef struct ft_replay_result {
    uint64_t lines;          /* lines read */
    uint64_t lines_bad;      /* unparseable (candump syntax) or overlong */
    uint64_t lines_unsupported; /* remote, FD or error frames: valid syntax, not ours */
    uint64_t gaps;           /* discontinuities (see above) */
    uint32_t errors_kept;
    char errors[FT_REPLAY_ERRORS_KEPT][FT_REPLAY_ERROR_TEXT_MAX];
    uint32_t frames;          /* frames rendered */
    uint32_t frames_annunciated;
    uint32_t first_annunciated; /* frame index; UINT32_MAX if none */
    uint32_t frames_predicted;  /* frames whose attitude was predicted from the rates */
    uint32_t frames_pos_predicted;  /* frames whose position was predicted from a velocity */
    uint32_t frames_velocity_stale; /* frames with a velocity quantity stale (or never received) */
    double log_first_s, log_last_s;
    double draw_ms_max;      /* slowest frame (select + draw + readback), information only */
    ft_degrade degrade;      /* frame.budget_ms: frames over it, LOD scale steps */
    double degrade_scale_max;
    double tau_max_px;       /* worst error bound a frame's LOD met (bintree) */
    ft_pose_view last_view;
} ft_replay_result;

/* Runs the replay on an initialised app. feed is caller storage (it holds
 * the decoder counters afterwards). */
ft_status ft_app_replay(ft_app *app, const ft_replay_desc *d, ft_pose_feed *feed,
                        ft_replay_result *out, ft_error *err);

#endif
