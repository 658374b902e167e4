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
 * Timestamps (a log is external input; the rule keeps every clock value
 * representable, so the display clock can never wrap past 2^64 ns):
 *   - the first parsed frame whose timestamp is at most FT_REPLAY_T_MAX_NS
 *     anchors the timeline;
 *   - a frame earlier than the previous accepted frame is rejected and
 *     counted in timestamps_backwards (equal times are accepted: several
 *     frames share a microsecond on a busy bus);
 *   - a frame later than FT_REPLAY_T_MAX_NS (the end of the timeline, 10 s
 *     before 2^64 ns, which leaves room for one display period of at most
 *     1 s after the last frame), or more than FT_REPLAY_SPAN_MAX_S after
 *     the anchor, is rejected and counted in timestamps_out_of_range;
 *   - a rejected frame is not fed to the decoder; its line number and why
 *     are kept with the other rejected lines.
 * The rule needs no look-ahead, so one corrupt timestamp far in the future
 * (but within the span) is taken as a gap and the frames after it that are
 * earlier are then rejected as backwards; the counters show it.
 *
 * Bad input never stops the replay: an unparseable or overlong line is
 * counted (the first FT_REPLAY_ERRORS_KEPT messages are kept with their line
 * numbers), a frame the decoder rejects is counted per reason, and the pose
 * stays on the last good values with the annunciation drawn once a quantity
 * is past its timeout. */
#ifndef FT_REPLAY_H
#define FT_REPLAY_H

#include <stdint.h>

#include "app/app.h"
#include "app/frame.h"
#include "core/line_reader.h"
#include "core/platform_api.h"
#include "input/pose_feed.h"

#define FT_REPLAY_ERRORS_KEPT 8u
#define FT_REPLAY_ERROR_TEXT_MAX 200u
#define FT_REPLAY_GAP_MAX_S 60.0
#define FT_REPLAY_FRAMES_LIMIT 10000000u /* hard bound on one run's frames */
#define FT_REPLAY_SPAN_MAX_S 2592000u     /* 30 days after the anchor */
#define FT_REPLAY_T_HEADROOM_NS UINT64_C(10000000000) /* 10 s */
#define FT_REPLAY_T_MAX_NS (UINT64_MAX - FT_REPLAY_T_HEADROOM_NS) /* 18446744063.709551615 s */

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
    uint64_t timestamps_backwards;    /* frames earlier than the previous accepted one */
    uint64_t timestamps_out_of_range; /* past FT_REPLAY_T_MAX_NS or the span */
    uint32_t errors_kept;
    char errors[FT_REPLAY_ERRORS_KEPT][FT_REPLAY_ERROR_TEXT_MAX];
    uint32_t frames;          /* frames rendered */
    uint32_t frames_annunciated;
    uint32_t first_annunciated; /* frame index; UINT32_MAX if none */
    uint32_t frames_predicted;  /* frames whose attitude was predicted from the rates */
    uint32_t frames_pos_predicted;  /* frames whose position was predicted from a velocity */
    uint32_t frames_velocity_stale; /* frames with a velocity quantity stale (or never received) */
    uint32_t frames_off_terrain;    /* frames drawn from a fresh position that does not lie
                                     * over the terrain (the frame shows no terrain there) */
    double last_off_lat_deg, last_off_lon_deg; /* the last such position */
    uint32_t frames_cache_behind;   /* clipmap: frames drawn with a cache level behind */
    uint32_t frames_cache_coarser;  /* clipmap: frames that drew the eye's surroundings
                                     * from a level coarser than level 0 */
    uint32_t frames_cache_forced;   /* clipmap: frames that completed the coarsest level
                                     * before drawing (its box moved, or a jump) */
    double log_first_s, log_last_s;
    ft_frame_loop frame;     /* the frames' timing (information only) and the LOD
                              * degradation (frame.budget_ms, frame.degrade) */
    ft_pose_view last_view;
} ft_replay_result;

/* The timestamp rule above, on its own (the replay runs every parsed frame
 * through it). Zero-initialise, then call once per frame in log order. */
typedef enum ft_replay_ts {
    FT_REPLAY_TS_OK,
    FT_REPLAY_TS_BACKWARDS,
    FT_REPLAY_TS_OUT_OF_RANGE
} ft_replay_ts;

typedef struct ft_replay_timeline {
    int anchored;
    uint64_t anchor_ns; /* the first accepted timestamp */
    uint64_t last_ns;   /* the latest accepted timestamp */
    uint64_t backwards, out_of_range;
} ft_replay_timeline;

ft_replay_ts ft_replay_timeline_accept(ft_replay_timeline *tl, uint64_t t_ns);

/* The replay's files and line reader (about 5 KiB of buffers): caller
 * storage, like the feed. */
typedef struct ft_replay_io {
    ft_file log_file, pose_file;
    ft_line_reader lr;
} ft_replay_io;

/* Runs the replay on an initialised app. feed and io are caller storage
 * (feed holds the decoder counters afterwards). */
ft_status ft_app_replay(ft_app *app, const ft_replay_desc *d, ft_pose_feed *feed,
                        ft_replay_io *io, ft_replay_result *out, ft_error *err);

#endif
