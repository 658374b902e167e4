/* fuzz_canaero.c - libFuzzer harness: CANaerospace decoding and the pose it
 * feeds (src/input/canaero.c through src/input/pose_feed.c, as replay and live input
 * use it).
 *
 * Input: 4 bytes of set-up, then 16-byte frame records.
 *   set-up: u16 prediction horizon (ms; % 1001 unless bit 15 is set, so
 *   out-of-range values reach the init checks too), u8 converge (x 40 ms),
 *   u8 snap (1 + x * 400 m); bit 0 of byte 1 = velocity required; bit 1 of
 *   byte 1: 8 more set-up bytes, a little-endian double that replaces the
 *   scale of every map entry (the decoder's scaled-value checks; the map
 *   checks refuse a scale that is 0 or not finite).
 *   record: u16 id selector (bit 15 clear: the id of default-map entry
 *   sel % count, so most frames reach the decoder's later checks; set: raw
 *   id sel & 0x1FFF), u8 dlc (low 4 bits) | extended (bit 4) | time mode
 *   (bits 5-6), 8 data bytes, u32 time argument, u8 view offset (ms).
 *   time modes: 0 forward by arg us, 1 backward by (arg & 0xFFFF) us,
 *   2 forward by arg ms, 3 to UINT64_MAX - arg us (the end of the clock).
 * State is reset per input (ft_pose_feed_init clears all of it).
 * Invariants after every frame: the pose view is finite (a renderer must
 * never get NaN), the lost counter is the sum of the per-id ones, every
 * frame offered is counted, the CSV row fits its buffer. */
#include <math.h>
#include <string.h>

#include "input/canaero.h"
#include "fuzz_util.h"
#include "input/pose_feed.h"

#define REC_BYTES 16u

static ft_pose_feed g_feed; /* large: static, re-initialised per input */

static uint64_t sat_add(uint64_t a, uint64_t b)
{
    return (a > UINT64_MAX - b) ? UINT64_MAX : a + b;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 4u) {
        return 0;
    }
    ft_can_map map;
    ft_canaero_default_map(&map);
    uint16_t h = fuzz_u16(data);
    uint32_t horizon_ms = (h & 0x8000u) ? (uint32_t)(h & 0x7FFFu) : (uint32_t)h % 1001u;
    size_t first = 4u;
    if ((data[1] & 2u) != 0u) {
        if (size < 12u) {
            return 0;
        }
        uint64_t bits = (uint64_t)fuzz_u32(data + 4) | ((uint64_t)fuzz_u32(data + 8) << 32);
        double scale;
        memcpy(&scale, &bits, sizeof scale);
        for (uint32_t i = 0u; i < map.count; ++i) {
            map.e[i].scale = scale;
        }
        first = 12u;
    }
    ft_pose fallback;
    memset(&fallback, 0, sizeof fallback);
    fallback.lat_deg = 46.5;
    fallback.lon_deg = 8.0;
    fallback.alt_m = 3000.0;
    ft_error err;
    memset(&err, 0, sizeof err);
    if (ft_pose_feed_init(&g_feed, &map, horizon_ms, &fallback, &err) != FT_OK) {
        FUZZ_CHECK_TEXT(err.text);
        return 0;
    }
    uint32_t converge_ms = (uint32_t)data[2] * 40u;
    double snap_m = 1.0 + (double)data[3] * 400.0;
    if (ft_pose_feed_set_position(&g_feed, converge_ms, snap_m, data[1] & 1, &err) != FT_OK) {
        FUZZ_CHECK_TEXT(err.text);
        return 0;
    }
    uint64_t t_ns = UINT64_C(1700000000000000000);
    uint64_t frames = 0u;
    for (size_t off = first; off + REC_BYTES <= size; off += REC_BYTES) {
        const uint8_t *r = data + off;
        uint16_t sel = fuzz_u16(r);
        ft_can_frame f;
        memset(&f, 0, sizeof f);
        f.can_id = (sel & 0x8000u) ? (uint32_t)(sel & 0x1FFFu)
                                   : (uint32_t)map.e[sel % map.count].can_id;
        f.dlc = (uint8_t)(r[2] & 0x0Fu);
        f.extended = (uint8_t)((r[2] >> 4) & 1u);
        /* bytes past the DLC are 0, as every frame source guarantees */
        for (uint32_t k = 0u; k < 8u && k < f.dlc; ++k) {
            f.data[k] = r[3u + k];
        }
        uint32_t arg = fuzz_u32(r + 11);
        switch ((r[2] >> 5) & 3u) {
        case 0u:
            t_ns = sat_add(t_ns, (uint64_t)arg * 1000u);
            break;
        case 1u: {
            uint64_t back = (uint64_t)(arg & 0xFFFFu) * 1000u;
            t_ns = (t_ns > back) ? t_ns - back : 0u;
            break;
        }
        case 2u:
            t_ns = sat_add(t_ns, (uint64_t)arg * 1000000u);
            break;
        default:
            t_ns = UINT64_MAX - (uint64_t)arg * 1000u;
            break;
        }
        f.t_ns = t_ns;
        ft_pose_feed_frame(&g_feed, &f);
        ++frames;

        ft_pose_view v;
        ft_pose_feed_view(&g_feed, sat_add(t_ns, (uint64_t)r[15] * 1000000u), &v);
        FUZZ_CHECK(isfinite(v.pose.lat_deg) && isfinite(v.pose.lon_deg) &&
                   isfinite(v.pose.alt_m));
        FUZZ_CHECK(isfinite(v.pose.heading_deg) && isfinite(v.pose.pitch_deg) &&
                   isfinite(v.pose.roll_deg));
        FUZZ_CHECK(isfinite(v.predict_s) && isfinite(v.pos_offset_m));
        FUZZ_CHECK_TEXT(v.reason);
        char row[FT_POSE_ROW_MAX];
        size_t n = ft_pose_row_format(row, sizeof row, (uint32_t)frames, t_ns, &v, 0, 0, 1.0,
                                      1.0);
        FUZZ_CHECK(n < sizeof row);
    }
    FUZZ_CHECK(g_feed.frames_in == frames);
    uint64_t lost = 0u;
    for (uint32_t i = 0u; i < FT_CAN_MAP_MAX; ++i) {
        lost += g_feed.dec.st[i].lost;
    }
    FUZZ_CHECK(lost == g_feed.dec.lost);
    /* an out-of-sequence frame counts once, and only a frame can be one */
    uint64_t oos = 0u;
    for (uint32_t i = 0u; i < FT_CAN_MAP_MAX; ++i) {
        oos += g_feed.dec.st[i].out_of_sequence;
    }
    FUZZ_CHECK(oos == g_feed.dec.out_of_sequence && oos <= frames);
    uint64_t rej_by_qty = 0u;
    for (uint32_t q = 0u; q < FT_QTY_COUNT; ++q) {
        rej_by_qty += g_feed.dec.rejects_by_qty[q];
    }
    /* every reject of a mapped id is also counted by its quantity */
    FUZZ_CHECK(rej_by_qty + g_feed.dec.rejects[FT_CAN_REJECT_UNKNOWN_ID] ==
               ft_pose_feed_rejected(&g_feed));
    FUZZ_CHECK(g_feed.dec.accepted == g_feed.values_applied + g_feed.values_dropped);
    return 0;
}
