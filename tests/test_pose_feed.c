/* test_pose_feed.c - the bounded line reader (candump logs, waypoint files)
 * and the pose feed: frames in, pose + annunciation out; velocity frames
 * through the decoder: NaN and out-of-range ones rejected and counted, the
 * prediction stopped at the velocity's timeout, annunciated only when the
 * velocity is required. */
#include <string.h>

#include "core/line_reader.h"
#include "input/pose_feed.h"
#include "test_util.h"

static char g_text[20000];

static void test_line_reader(void)
{
    /* 300 numbered lines across several 4 KiB chunks, one CRLF line, one
     * overlong line, an empty line, and a last line without a newline. */
    size_t n = 0;
    for (int i = 0; i < 300; ++i) {
        n += (size_t)snprintf(g_text + n, sizeof g_text - n, "line %d%s\n", i,
                              i == 7 ? "\r" : "");
    }
    g_text[n++] = '\n'; /* empty line 301 */
    memset(g_text + n, 'x', 1500); /* overlong line 302 */
    n += 1500;
    g_text[n++] = '\n';
    n += (size_t)snprintf(g_text + n, sizeof g_text - n, "tail");
    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, g_text, n, "mem");
    ft_line_reader lr;
    ft_line_reader_init(&lr, &r);
    ft_line_kind k;
    ft_error err;
    for (int i = 0; i < 300; ++i) {
        char want[32];
        (void)snprintf(want, sizeof want, "line %d", i);
        REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
        CHECK(k == FT_LINE_OK && strcmp(lr.line, want) == 0 && lr.len == strlen(want));
        CHECK(lr.line_no == (uint64_t)i + 1u);
    }
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_OK && lr.len == 0u && lr.line_no == 301u);
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_OVERLONG && lr.line_no == 302u);
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_OK && strcmp(lr.line, "tail") == 0 && lr.line_no == 303u);
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_END);
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_END); /* stays at the end */

    /* an empty stream has no lines */
    ft_mem_reader_init(&r, &m, g_text, 0, "empty");
    ft_line_reader_init(&lr, &r);
    REQUIRE(ft_line_reader_next(&lr, &k, &err) == FT_OK);
    CHECK(k == FT_LINE_END && lr.line_no == 0u);
}

static uint8_t g_code[2048];

static ft_can_frame float_frame(uint16_t id, float v, uint64_t t_ns)
{
    ft_can_frame f;
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    memset(&f, 0, sizeof f);
    f.can_id = id;
    f.dlc = 8;
    f.data[0] = 1; /* node */
    f.data[1] = FT_CAN_TYPE_FLOAT;
    f.data[2] = 0;
    f.data[3] = g_code[id]++;
    f.data[4] = (uint8_t)(bits >> 24);
    f.data[5] = (uint8_t)(bits >> 16);
    f.data[6] = (uint8_t)(bits >> 8);
    f.data[7] = (uint8_t)bits;
    f.t_ns = t_ns;
    return f;
}

static void feed_all(ft_pose_feed *pf, uint64_t t_ns, int with_position)
{
    ft_can_frame f;
    f = float_frame(311, -5.0f, t_ns); ft_pose_feed_frame(pf, &f);
    f = float_frame(312, 10.0f, t_ns); ft_pose_feed_frame(pf, &f);
    f = float_frame(321, 90.0f, t_ns); ft_pose_feed_frame(pf, &f);
    f = float_frame(303, 0.0f, t_ns); ft_pose_feed_frame(pf, &f);
    f = float_frame(304, 0.0f, t_ns); ft_pose_feed_frame(pf, &f);
    f = float_frame(305, 20.0f, t_ns); ft_pose_feed_frame(pf, &f); /* yaw 20 deg/s */
    if (with_position) {
        f = float_frame(320, 3000.0f, t_ns); ft_pose_feed_frame(pf, &f);
        f = float_frame(1036, 46.5f, t_ns); ft_pose_feed_frame(pf, &f);
        f = float_frame(1037, 8.25f, t_ns); ft_pose_feed_frame(pf, &f);
    }
}

static void test_pose_feed(void)
{
    ft_can_map map;
    ft_canaero_default_map(&map);
    const ft_pose fallback = {10.0, 20.0, 500.0, 1.0, 2.0, 3.0};
    ft_pose_feed pf;
    ft_pose_view v;
    ft_error err;
    REQUIRE(ft_pose_feed_init(&pf, &map, 100, &fallback, &err) == FT_OK);
    const uint64_t ms = 1000000u, t0 = 1000u * ms;

    /* nothing received: fallback pose, annunciated, says what is missing */
    ft_pose_feed_view(&pf, t0, &v);
    CHECK(v.annunciate && v.stale_mask == FT_QTY_ALL_MASK);
    CHECK(memcmp(&v.pose, &fallback, sizeof v.pose) == 0);
    CHECK(strstr(v.reason, "received") != NULL);

    /* attitude only: position from the fallback, still annunciated */
    feed_all(&pf, t0, 0);
    ft_pose_feed_view(&pf, t0, &v);
    CHECK(v.annunciate && strstr(v.reason, "latitude") != NULL);
    CHECK_NEAR(v.pose.lat_deg, 10.0, 0.0);
    CHECK_NEAR(v.pose.heading_deg, 90.0, 1e-9);

    /* everything: no annunciation; 50 ms later heading predicted +1 deg */
    feed_all(&pf, t0, 1);
    ft_pose_feed_view(&pf, t0 + 50u * ms, &v);
    CHECK(!v.annunciate && v.reason[0] == '\0' && v.predicted);
    CHECK_NEAR(v.pose.lat_deg, 46.5, 1e-6);
    CHECK_NEAR(v.pose.alt_m, 3000.0, 1e-3);
    /* a body yaw rate in a body rolled 10 deg also pitches the nose down:
     * d(pitch)/dt = -r sin(roll) = -3.47 deg/s, d(heading)/dt = r cos(roll) /
     * cos(pitch) = 19.77 deg/s */
    CHECK_NEAR(v.pose.pitch_deg, -5.0 - 0.05 * 3.473, 0.01);
    CHECK_NEAR(v.pose.heading_deg, 90.0 + 0.05 * 19.77, 0.01);

    /* attitude goes silent past its 100 ms timeout: annunciated within the
     * first frame after it, the pose held; position is still good */
    ft_can_frame f = float_frame(320, 3000.0f, t0 + 90u * ms);
    ft_pose_feed_frame(&pf, &f);
    ft_pose_feed_view(&pf, t0 + 100u * ms, &v);
    CHECK(!v.annunciate);
    ft_pose_feed_view(&pf, t0 + 101u * ms, &v);
    CHECK(v.annunciate && strstr(v.reason, "no pitch for 101 ms") != NULL);
    /* the rates are stale too: the last measured attitude is held */
    CHECK(!v.predicted);
    CHECK_NEAR(v.pose.heading_deg, 90.0, 1e-9);

    /* bad frames are rejected and counted, never applied */
    uint64_t rej = ft_pose_feed_rejected(&pf);
    f = float_frame(311, 1e30f, t0 + 102u * ms); /* out of range */
    ft_pose_feed_frame(&pf, &f);
    f = float_frame(311, -5.0f, t0 + 103u * ms);
    f.dlc = 3; /* wrong DLC */
    ft_pose_feed_frame(&pf, &f);
    CHECK(ft_pose_feed_rejected(&pf) == rej + 2u);
    ft_pose_feed_view(&pf, t0 + 104u * ms, &v);
    CHECK(v.annunciate);

    /* recovery on the next good data */
    feed_all(&pf, t0 + 200u * ms, 1);
    ft_pose_feed_view(&pf, t0 + 201u * ms, &v);
    CHECK(!v.annunciate && v.reason[0] == '\0');
    CHECK_NEAR(v.pose.pitch_deg, -5.0, 0.05);
}

/* Velocity through the real decoder: straight flight north at 100 m/s at
 * 46.5 N (attitude and rates every 10 ms, position and velocity every 100
 * ms). From 1 s on the velocity frames carry NaN / out-of-range values: each
 * is rejected and counted (per reason and per quantity), never applied; the
 * last good velocity predicts until its 500 ms timeout, then the position
 * is held; the annunciation comes only where the scene requires velocity. */
static void flight_frames(ft_pose_feed *pf, uint64_t t0, uint64_t t, int bad_velocity)
{
    const uint64_t ms = 1000000u;
    const double m_per_deg = 111132.0; /* near enough: both feeds see the same values */
    ft_can_frame f;
    f = float_frame(311, 0.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(312, 0.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(321, 0.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(303, 0.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(304, 0.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(305, 0.0f, t); ft_pose_feed_frame(pf, &f);
    if ((t - t0) % (100u * ms) != 0u) {
        return;
    }
    const double dt = (double)(t - t0) * 1e-9;
    f = float_frame(320, 2000.0f, t); ft_pose_feed_frame(pf, &f);
    f = float_frame(1036, (float)(46.5 + 100.0 * dt / m_per_deg), t); ft_pose_feed_frame(pf, &f);
    f = float_frame(1037, 8.0f, t); ft_pose_feed_frame(pf, &f);
    if (!bad_velocity) {
        f = float_frame(1039, 100.0f, t + ms); ft_pose_feed_frame(pf, &f);
        f = float_frame(1040, 0.0f, t + ms); ft_pose_feed_frame(pf, &f);
        f = float_frame(314, 0.0f, t + ms); ft_pose_feed_frame(pf, &f);
    } else {
        float nan_f;
        const uint32_t qnan = 0x7FC00000u;
        memcpy(&nan_f, &qnan, sizeof nan_f);
        f = float_frame(1039, nan_f, t + ms); ft_pose_feed_frame(pf, &f);
        f = float_frame(1040, 400.0f, t + ms); ft_pose_feed_frame(pf, &f);
        f = float_frame(314, -900.0f, t + ms); ft_pose_feed_frame(pf, &f);
    }
}

/* Both feeds get the same frames with the same message codes. */
static void feed_both(ft_pose_feed pf[2], uint64_t t0, uint64_t t, int bad)
{
    uint8_t codes[sizeof g_code];
    memcpy(codes, g_code, sizeof codes);
    flight_frames(&pf[0], t0, t, bad);
    memcpy(g_code, codes, sizeof codes);
    flight_frames(&pf[1], t0, t, bad);
}

static void init_both(ft_pose_feed pf[2])
{
    ft_can_map map;
    ft_canaero_default_map(&map);
    const ft_pose fallback = {10.0, 20.0, 500.0, 1.0, 2.0, 3.0};
    ft_error err;
    for (int k = 0; k < 2; ++k) {
        REQUIRE(ft_pose_feed_init(&pf[k], &map, 100, &fallback, &err) == FT_OK);
        REQUIRE(ft_pose_feed_set_position(&pf[k], 300u, 100.0, k, &err) == FT_OK);
    }
}

static void test_velocity_feed(void)
{
    static ft_pose_feed pf[2]; /* [0] velocity not required, [1] required */
    ft_error err;
    init_both(pf);
    CHECK(ft_pose_feed_set_position(&pf[0], 300u, 0.0, 0, &err) == FT_ERR_ARG);
    const uint64_t ms = 1000000u, t0 = 5000u * ms;
    /* no velocity ever received: annunciated only where it is required */
    feed_both(pf, t0, t0, 1);
    ft_pose_view v0, v1;
    ft_pose_feed_view(&pf[0], t0 + 5u * ms, &v0);
    ft_pose_feed_view(&pf[1], t0 + 5u * ms, &v1);
    CHECK(!v0.annunciate && v0.pos_predicted == 0 && v0.reason[0] == '\0');
    CHECK(v1.annunciate && strcmp(v1.reason, "no ground speed received (+2 more)") == 0);

    init_both(pf);
    /* the last good velocity is sent at 0.901 s: stale after 1.401 s */
    const uint64_t stop = t0 + 901u * ms + 500u * ms;
    int stale_frames = 0, ann_frames[2] = {0, 0}, pred_frames = 0;
    double prev_lat = 0.0;
    for (uint64_t t = t0; t <= t0 + 2000u * ms; t += 10u * ms) {
        feed_both(pf, t0, t, t >= t0 + 1000u * ms);
        const uint64_t td = t + 5u * ms; /* display time between two frames */
        ft_pose_feed_view(&pf[0], td, &v0);
        ft_pose_feed_view(&pf[1], td, &v1);
        /* both draw the same position: the requirement only annunciates */
        CHECK(v0.pose.lat_deg == v1.pose.lat_deg && v0.pose.alt_m == v1.pose.alt_m);
        if (td <= stop) {
            CHECK(v0.pos_predicted == 3);
            pred_frames += v0.pos_predicted == 3;
            CHECK(!v0.annunciate && !v1.annunciate);
        } else {
            CHECK(v0.pos_predicted == 0);
            CHECK((v0.stale_mask & FT_QTY_VELOCITY_MASK) == FT_QTY_VELOCITY_MASK);
            ++stale_frames;
            ann_frames[0] += v0.annunciate;
            ann_frames[1] += v1.annunciate;
            CHECK(v1.annunciate && strstr(v1.reason, "no ground speed for") != NULL);
            const ft_pose_sample *lat = &pf[0].ps.s[FT_QTY_LAT];
            if (lat->t_ns > stop) {
                /* a fix after the velocity went stale: drawn as it is */
                CHECK(v0.pose.lat_deg == lat->value);
            } else if (stale_frames > 1) {
                /* held where the prediction stopped: what moves is what is
                 * left of the convergence of earlier fixes (FLOAT latitudes
                 * are rounded to 0.4 m here), at most 2 cm a frame */
                CHECK_NEAR(v0.pose.lat_deg, prev_lat, 2e-7);
            }
        }
        prev_lat = v0.pose.lat_deg;
    }
    printf("velocity feed: %d predicted frames, %d frames with a stale velocity: annunciated %d "
           "(not required) / %d (required); rejects ground speed %llu, track %llu, altitude "
           "rate %llu\n",
           pred_frames, stale_frames, ann_frames[0], ann_frames[1],
           (unsigned long long)pf[0].dec.rejects_by_qty[FT_QTY_GROUND_SPEED],
           (unsigned long long)pf[0].dec.rejects_by_qty[FT_QTY_TRACK],
           (unsigned long long)pf[0].dec.rejects_by_qty[FT_QTY_ALT_RATE]);
    CHECK(stale_frames > 0 && ann_frames[0] == 0 && ann_frames[1] == stale_frames);
    for (int k = 0; k < 2; ++k) {
        /* 11 bad fixes (1.0 .. 2.0 s), each with 3 bad velocity frames */
        CHECK(pf[k].dec.rejects_by_qty[FT_QTY_GROUND_SPEED] == 11u);
        CHECK(pf[k].dec.rejects_by_qty[FT_QTY_TRACK] == 11u);
        CHECK(pf[k].dec.rejects_by_qty[FT_QTY_ALT_RATE] == 11u);
        CHECK(pf[k].dec.rejects[FT_CAN_REJECT_NONFINITE] == 11u);
        CHECK(pf[k].dec.rejects[FT_CAN_REJECT_RANGE] == 22u);
        CHECK(ft_pose_feed_rejected(&pf[k]) == 33u);
        CHECK(pf[k].ps.s[FT_QTY_GROUND_SPEED].value == 100.0);
        CHECK(pf[k].ps.snap_count == 0u);
    }
}

int main(void)
{
    test_line_reader();
    test_pose_feed();
    test_velocity_feed();
    return ft_test_result("test_pose_feed");
}
