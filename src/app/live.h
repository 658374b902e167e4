/* live.h - `fixterrain run`: live pose input (SocketCAN, GPIO) and a frame
 * loop paced by the monotonic clock.
 *
 * First one warm-up frame showing the annunciation test (power-up lamp
 * test; it makes the driver compile its shaders before the schedule starts).
 * Then every frame k (due at t_start + k * frame.period_ms):
 *   1. drain the CAN sockets (primary and backup; only the active source
 *      feeds the pose), poll the GPIO edges and debounce them;
 *   2. pick the source: the backup while gpio.source_line is active, or
 *      while the primary has been silent for can.failover_ms and the backup
 *      has not (failover and failback are counted);
 *   3. the pose for "now" from the feed (pose_feed.h): predicted, held, or
 *      annunciated; gpio.freeze_line holds the drawn pose (the annunciation
 *      still follows the live data); gpio.test_line forces the annunciation
 *      ("ANNUNCIATION TEST");
 *   4. render and present, then toggle the heartbeat line (once per
 *      presented frame: a monitor that sees it stop knows the display hung);
 *      then deferred jobs (jobs.h: the pose record's file writes) run in
 *      the time left before the next frame is due, at most FT_LIVE_JOB_COST_NS
 *      each, and all of them at the end of the run (none is lost);
 *   5. a frame that ends after its period is a deadline miss; the loop then
 *      re-bases its schedule instead of bursting to catch up;
 *   6. the degradation policy (frame.degrade, src/lod/degrade.h) sees the
 *      frame's render time against frame.budget_ms and coarsens or refines
 *      the LOD for the next frame; the pose record gives the scale and the
 *      error bound each frame met.
 * Per-stage CPU times (input poll, LOD selection, draw submission, GPU
 * finish) are accumulated in the result; the GPU's own time comes from a
 * timer query where the context has them (GL_EXT_disjoint_timer_query),
 * and the finish time (the readback waits for the GPU) is kept too.
 * The loop ends when *stop becomes non-zero (a signal handler sets it) or
 * after frames_max frames. Nothing is allocated: the ports' buffers are in
 * the structs below, sized by FT_CAN_FILTERS_MAX / FT_LIVE_CAN_BATCH. */
#ifndef FT_LIVE_H
#define FT_LIVE_H

#include <stdint.h>

#include "app/app.h"
#include "app/frame.h"
#include "core/jobs.h"
#include "core/platform_api.h"
#include "input/debounce.h"
#include "input/pose_feed.h"

#define FT_LIVE_CAN_BATCH 64u      /* frames read per call */
#define FT_LIVE_CAN_BATCHES_MAX 64u /* calls per frame and port: 4096 frames */
#define FT_LIVE_TEST_REASON "ANNUNCIATION TEST"
#define FT_LIVE_JOB_COST_NS 200000u /* declared cost of one pose-record write */
#define FT_LIVE_HOLD 128u /* newest frames kept per standby port (~0.25 s of CANaerospace) */

typedef struct ft_live_desc {
    const char *poses_path;  /* NULL: no pose record */
    uint32_t frames_max;     /* 0: until *stop */
    const volatile int *stop;
} ft_live_desc;

typedef struct ft_live_result {
    uint32_t frames, frames_annunciated, frames_frozen, frames_test, frames_backup;
    uint32_t frames_night; /* drawn in the night palette */
    uint32_t frames_pos_predicted;  /* position predicted from a velocity */
    uint32_t frames_velocity_stale; /* a velocity quantity stale or never received */
    uint32_t deadline_misses;
    uint32_t source_switches;
    uint64_t can_frames[2];  /* primary, backup */
    uint64_t can_dropped[2]; /* kernel drops */
    uint64_t gpio_edges, gpio_changes, heartbeat_toggles;
    uint64_t t_start_ns, t_first_rx_ns; /* monotonic; first rx 0 if none */
    double frame_ms_max;
    double poll_ms_max, poll_ms_sum; /* inputs: CAN and GPIO reads, worst and sum */
    ft_frame_loop frame; /* the later stages' timing and the LOD degradation */
    uint64_t jobs_run, jobs_deferred_frames, jobs_refused;
    uint32_t jobs_high_water;
} ft_live_result;

typedef struct ft_live {
    ft_can_port can[2];
    int can_open[2];
    uint64_t last_rx_ns[2];
    ft_gpio_port gpio;
    int gpio_open;
    uint32_t slot_count;
    int slot_fn[FT_GPIO_LINES_MAX]; /* ft_gpio_input per slot */
    ft_debounce deb;
    ft_can_frame batch[FT_LIVE_CAN_BATCH];
    ft_jobs jobs;
    ft_can_frame hold[2][FT_LIVE_HOLD]; /* standby port's newest frames */
    uint32_t hold_next[2], hold_count[2];
    ft_gpio_edge edges[FT_GPIO_EVENTS_MAX];
    ft_file pose_file; /* the pose record (live_desc.poses_path) */
} ft_live;

ft_status ft_app_run_live(ft_app *app, const ft_live_desc *d, ft_live *lv, ft_pose_feed *feed,
                          ft_live_result *out, ft_error *err);

#endif
