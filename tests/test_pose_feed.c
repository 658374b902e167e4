/* test_pose_feed.c - the bounded line reader (candump logs, waypoint files)
 * and the pose feed: frames in, pose + annunciation out. */
#include <string.h>

#include "line_reader.h"
#include "pose_feed.h"
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

int main(void)
{
    test_line_reader();
    test_pose_feed();
    return ft_test_result("test_pose_feed");
}
