/* pose_feed.h - from CAN frames to the pose a frame is drawn with.
 *
 * One feed = one CANaerospace decoder (canaero.h) + one pose assembler
 * (pose_state.h) + counters. Frames come from any source (candump replay,
 * SocketCAN); the feed never sees the OS.
 *
 * The pose drawn at display time t (ft_pose_feed_view):
 *   - attitude predicted to t from the body rates when all rates are fresh
 *     (bounded horizon), else held; position predicted to t from the
 *     velocity (ground speed, track, altitude rate) when it is fresh, and
 *     converged to a fix that disagrees with the prediction (pose_state.h);
 *   - a quantity never received takes the fallback pose's value (the
 *     scene's [pose]);
 *   - annunciate = any attitude or position quantity stale at t (older than
 *     its timeout, or never received), or any velocity quantity when the
 *     velocity is required (ft_pose_feed_set_position): the frame is still
 *     drawn, from the last good values, and the renderer puts the failure
 *     annunciation over it with `reason` (which names only those
 *     quantities). Stale rates alone only switch attitude prediction off (the
 *     drawn attitude is then the last measured one, still within its own
 *     timeout), which is reported (`predicted` = 0) but not annunciated; a
 *     stale velocity that is not required likewise only stops the position
 *     prediction (`pos_predicted` = 0). */
#ifndef FT_POSE_FEED_H
#define FT_POSE_FEED_H

#include <stddef.h>
#include <stdint.h>

#include "input/canaero.h"
#include "input/pose_state.h"

#define FT_POSE_FEED_ANNUNCIATE_MASK (FT_QTY_ATTITUDE_MASK | FT_QTY_POSITION_MASK)

typedef struct ft_pose_feed {
    ft_canaero dec;
    ft_pose_state ps;
    ft_pose fallback;
    uint32_t annunciate_mask; /* FT_POSE_FEED_ANNUNCIATE_MASK, + velocity if required */
    uint64_t frames_in;      /* frames offered */
    uint64_t values_applied; /* decoded values the assembler stored */
    uint64_t values_dropped; /* decoded but not stored (older, or a backup source) */
} ft_pose_feed;

typedef struct ft_pose_view {
    ft_pose pose;
    uint32_t stale_mask; /* FT_QTY_BIT per stale quantity at t */
    int annunciate;      /* attitude or position stale: draw the failure annunciation */
    int predicted;       /* attitude predicted from the rates */
    double predict_s;
    int pos_predicted;   /* FT_POSE_PRED_* axes predicted from a fresh velocity */
    double pos_offset_m; /* convergence still to go (drawn minus predicted position) */
    char reason[FT_POSE_REASON_MAX]; /* empty when nothing is stale */
} ft_pose_view;

/* Velocity not required; convergence at the pose_state defaults. */
ft_status ft_pose_feed_init(ft_pose_feed *f, const ft_can_map *map, uint32_t horizon_ms,
                            const ft_pose *fallback, ft_error *err);

/* The scene's pose_input.converge_ms, snap_m and velocity_required (see
 * ft_pose_state_set_convergence for the ranges). */
ft_status ft_pose_feed_set_position(ft_pose_feed *f, uint32_t converge_ms, double snap_m,
                                    int velocity_required, ft_error *err);

/* Decodes and applies one frame; rejects are counted in f->dec.rejects. */
void ft_pose_feed_frame(ft_pose_feed *f, const ft_can_frame *frame);

void ft_pose_feed_view(const ft_pose_feed *f, uint64_t t_ns, ft_pose_view *out);

/* One row of a pose record (replay and run write the same CSV):
 *   frame,t_s,lat_deg,lon_deg,alt_m,heading_deg,pitch_deg,roll_deg,
 *   annunciate,stale_mask,predicted,frozen,source,lod_scale,tau_px,
 *   pos_predicted,pos_offset_m,reason
 * (lod_scale: the degradation policy's scale; tau_px: the error bound the
 * LOD met, 0 for methods without one; pos_predicted: FT_POSE_PRED_* bits;
 * pos_offset_m: the position convergence still to go)
 * Returns the length, or 0 if it does not fit in cap. */
#define FT_POSE_ROW_HEADER                                                              \
    "frame,t_s,lat_deg,lon_deg,alt_m,heading_deg,pitch_deg,roll_deg,annunciate,stale_mask," \
    "predicted,frozen,source,lod_scale,tau_px,pos_predicted,pos_offset_m,reason\n"
#define FT_POSE_ROW_MAX 512u
size_t ft_pose_row_format(char *buf, size_t cap, uint32_t frame, uint64_t t_ns,
                          const ft_pose_view *v, int frozen, int source, double lod_scale,
                          double tau_px);

/* Frames rejected for any reason (sum of f->dec.rejects). */
uint64_t ft_pose_feed_rejected(const ft_pose_feed *f);

#endif
