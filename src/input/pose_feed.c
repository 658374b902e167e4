/* pose_feed.c - see pose_feed.h. */
#include "input/pose_feed.h"

#include <stdio.h>
#include <string.h>

ft_status ft_pose_feed_init(ft_pose_feed *f, const ft_can_map *map, uint32_t horizon_ms,
                            const ft_pose *fallback, ft_error *err)
{
    memset(f, 0, sizeof *f);
    f->fallback = *fallback;
    f->annunciate_mask = FT_POSE_FEED_ANNUNCIATE_MASK;
    ft_status st = ft_canaero_init(&f->dec, map, err);
    if (st == FT_OK) {
        st = ft_pose_state_init(&f->ps, horizon_ms, err);
    }
    return st;
}

ft_status ft_pose_feed_set_position(ft_pose_feed *f, uint32_t converge_ms, double snap_m,
                                    int velocity_required, ft_error *err)
{
    ft_status st = ft_pose_state_set_convergence(&f->ps, converge_ms, snap_m, err);
    if (st == FT_OK) {
        f->annunciate_mask = FT_POSE_FEED_ANNUNCIATE_MASK |
                             (velocity_required ? (uint32_t)FT_QTY_VELOCITY_MASK : 0u);
    }
    return st;
}

void ft_pose_feed_frame(ft_pose_feed *f, const ft_can_frame *frame)
{
    ft_can_result r;
    f->frames_in += 1u;
    if (ft_canaero_decode(&f->dec, frame, &r) != FT_CAN_VALUE) {
        return; /* rejected (counted by the decoder) or half a double */
    }
    int applied = 0;
    /* The decoder only emits finite, in-range values for mapped
     * quantities, so apply cannot fail on data; count a refusal anyway. */
    if (ft_pose_state_apply(&f->ps, &r.input, &applied, NULL) == FT_OK && applied) {
        f->values_applied += 1u;
    } else {
        f->values_dropped += 1u;
    }
}

void ft_pose_feed_view(const ft_pose_feed *f, uint64_t t_ns, ft_pose_view *out)
{
    ft_pose_estimate e;
    memset(out, 0, sizeof *out);
    ft_pose_state_estimate(&f->ps, t_ns, &e);
    out->pose = e.pose;
    /* never received: the fallback value (the annunciation says so) */
    const ft_pose_sample *s = f->ps.s;
    if (!s[FT_QTY_LAT].valid) out->pose.lat_deg = f->fallback.lat_deg;
    if (!s[FT_QTY_LON].valid) out->pose.lon_deg = f->fallback.lon_deg;
    if (!s[FT_QTY_ALT].valid) out->pose.alt_m = f->fallback.alt_m;
    if (!s[FT_QTY_HEADING].valid) out->pose.heading_deg = f->fallback.heading_deg;
    if (!s[FT_QTY_PITCH].valid) out->pose.pitch_deg = f->fallback.pitch_deg;
    if (!s[FT_QTY_ROLL].valid) out->pose.roll_deg = f->fallback.roll_deg;
    out->stale_mask = e.stale_mask;
    out->predicted = e.predicted;
    out->predict_s = e.predict_s;
    out->pos_predicted = e.position_predicted;
    out->pos_offset_m = e.offset_m;
    out->annunciate = (e.stale_mask & f->annunciate_mask) != 0u;
    if (out->annunciate) {
        (void)ft_pose_state_stale_in(&f->ps, t_ns, f->annunciate_mask, out->reason,
                                     sizeof out->reason);
    }
}

uint64_t ft_pose_feed_rejected(const ft_pose_feed *f)
{
    uint64_t n = 0;
    for (int i = 0; i < FT_CAN_REJECT_COUNT; ++i) {
        n += f->dec.rejects[i];
    }
    return n;
}

size_t ft_pose_row_format(char *buf, size_t cap, uint32_t frame, uint64_t t_ns,
                          const ft_pose_view *v, int frozen, int source, double lod_scale,
                          double tau_px)
{
    const ft_pose *p = &v->pose;
    int n = snprintf(buf, cap,
                     "%u,%llu.%09llu,%.9f,%.9f,%.4f,%.6f,%.6f,%.6f,%d,%u,%d,%d,%d,%.4f,%.4f,%d,%.4f,"
                     "\"%s\"\n",
                     frame, (unsigned long long)(t_ns / 1000000000u),
                     (unsigned long long)(t_ns % 1000000000u), p->lat_deg, p->lon_deg, p->alt_m,
                     p->heading_deg, p->pitch_deg, p->roll_deg, v->annunciate, v->stale_mask,
                     v->predicted, frozen, source, lod_scale, tau_px, v->pos_predicted,
                     v->pos_offset_m, v->reason);
    return (n < 0 || (size_t)n >= cap) ? 0u : (size_t)n;
}
