/* test_replay.c - `fixterrain replay` end to end on a real GL context: a
 * candump log written here (through the same candump writer the tools use)
 * with a known flight and known faults, replayed twice.
 *
 * Flight: heading 100 + 30 t deg (yaw rate 30 deg/s, level), pitch -12,
 * roll 0, at 46.55 N 8.20 E, 3500 m. Attitude and rates at 80 Hz, position
 * (lat/lon as DOUBLEH/DOUBLEL pairs, altitude FLOAT) at 10 Hz, 3 s of log.
 * Faults, each with a known count:
 *   t = 0.50 s: a NaN pitch, a DLC-3 pitch, a duplicate heading (same
 *               message code), an unknown id 999, a pitch of 120 deg;
 *   1.0 - 1.5 s: every 4th attitude frame dropped (counter gaps: 8 lost
 *               per attitude id, 24 in all, never stale: gaps < timeout);
 *   2.0 - 2.5 s: nothing at all (a stalled bus);
 *   two garbage lines and a remote frame line.
 * Checks: counters per reason; the annunciation starts on exactly the first
 * frame whose display time is past the attitude timeout (100 ms) after the
 * last frame before the stall, and ends on the first frame after data is
 * back; the drawn heading follows the flight (prediction from the rates)
 * within 0.05 deg on every frame that is not annunciated; no frame is
 * missing; the pose records of two runs are byte-identical (determinism);
 * a log with a 2-hour gap resumes after it; a log without a valid frame is
 * an error that says so. Then a fixterrain-flightgen orbit at 250 m/s with
 * velocity, a 500 m GPS reset and the velocity output stopping, replayed at
 * 60 Hz: positions within 1 m of the flown truth, steps within 1.5 x speed
 * x period but the one snap, prediction stopped at the velocity's timeout
 * and annunciated only when the scene requires the velocity. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/units.h"
#include "input/candump.h"
#include "flight_path.h"
#include "app/replay.h"
#include "test_util.h"

static ft_app g_app;
static ft_pose_feed g_feed;
static ft_replay_io g_replay_io; /* the replay's files and line reader */
static ft_replay_result g_res;

static const char k_scene[] =
    "[scene]\nmethod = brute\nbackend = egl-gles3\n"
    "[view]\nwidth_px = 160\nheight_px = 120\nfovy_deg = 60\n"
    "[terrain]\ndem =\nsynth_side = 257\nsynth_spacing_m = 30\nsynth_relief_m = 2000\n"
    "synth_seed = 3\nsynth_octaves = 8\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[frame]\nperiod_ms = 20\n[pose_input]\nhorizon_ms = 100\n"
    "[gpu]\ntexture_bytes = 16M\n"
    "[budget]\nheights_bytes = 512K\npyramids_bytes = 2M\nframe_rgba_bytes = 128K\n"
    "gpu_staging_bytes = 0\nmethod_bytes = 128K\npng_bytes = 512K\n";

#define T0_NS 1700000000000000000ull
#define MS 1000000ull

static FILE *g_log;
static uint8_t g_code[2048];

static void put(uint16_t id, uint8_t type, uint32_t bits, uint64_t t_ns, int dlc, int repeat)
{
    ft_candump_record rec;
    memset(&rec, 0, sizeof rec);
    (void)snprintf(rec.iface, sizeof rec.iface, "vcan0");
    rec.frame.can_id = id;
    rec.frame.dlc = (uint8_t)dlc;
    rec.frame.t_ns = t_ns;
    uint8_t *d = rec.frame.data;
    d[0] = 1;
    d[1] = type;
    d[2] = 0;
    d[3] = repeat ? (uint8_t)(g_code[id] - 1u) : g_code[id]++;
    d[4] = (uint8_t)(bits >> 24);
    d[5] = (uint8_t)(bits >> 16);
    d[6] = (uint8_t)(bits >> 8);
    d[7] = (uint8_t)bits;
    char line[64];
    ft_error err;
    REQUIRE(ft_candump_format(&rec, line, sizeof line, NULL, &err) == FT_OK);
    fprintf(g_log, "%s\n", line);
}

static void put_float(uint16_t id, float v, uint64_t t_ns)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    put(id, FT_CAN_TYPE_FLOAT, bits, t_ns, 8, 0);
}

static void put_double(uint16_t id, double v, uint64_t t_ns)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    put(id, FT_CAN_TYPE_DOUBLEH, (uint32_t)(bits >> 32), t_ns, 8, 0);
    put(id, FT_CAN_TYPE_DOUBLEL, (uint32_t)bits, t_ns + 100000u, 8, 0);
}

static double heading_at(double t_s)
{
    return fmod(100.0 + 30.0 * t_s, 360.0);
}

static const double k_stall_from_s = 2.0, k_stall_to_s = 2.5, k_log_s = 3.0;
/* Body rates of a level-pitched (-12 deg), wings-level turn at 30 deg/s of
 * heading: r = 30 cos(pitch), and p = -r tan(pitch) keeps the roll at 0. */
static double k_yaw_rate, k_roll_rate;

/* Writes the log; returns the time (ns) of the last attitude frame before
 * the stall (all three angles are sent within 2 ms of each other). */
static void write_log(const char *path)
{
    g_log = fopen(path, "w");
    REQUIRE(g_log != NULL);
    memset(g_code, 0, sizeof g_code);
    fprintf(g_log, "this is not a candump line\n");
    for (int i = 0; i < (int)(k_log_s * 80.0); ++i) {
        const double t_s = i / 80.0;
        const uint64_t t = T0_NS + (uint64_t)i * 12500000ull;
        if (t_s >= k_stall_from_s && t_s < k_stall_to_s) {
            continue;
        }
        const int drop = (t_s >= 1.0 && t_s < 1.5 && i % 4 == 0);
        if (drop) { /* lost on the bus: their message codes are skipped */
            g_code[311]++;
            g_code[312]++;
            g_code[321]++;
        } else {
            put_float(311, -12.0f, t);
            put_float(312, 0.0f, t + 1 * MS);
            put_float(321, (float)heading_at(t_s + 0.002), t + 2 * MS);
        }
        put_float(303, 0.0f, t + 3 * MS);
        put_float(304, (float)k_roll_rate, t + 3 * MS + 200000u);
        put_float(305, (float)k_yaw_rate, t + 3 * MS + 400000u);
        if (i % 8 == 0) {
            put_float(320, 3500.0f, t + 4 * MS);
            put_double(1036, 46.55, t + 5 * MS);
            put_double(1037, 8.20, t + 6 * MS);
        }
        if (i == 40) { /* t = 0.5 s: the bad frames */
            put(311, FT_CAN_TYPE_FLOAT, 0x7fc00000u, t + 7 * MS, 8, 0); /* NaN */
            put(311, FT_CAN_TYPE_FLOAT, 0xc1400000u, t + 7 * MS + 100000u, 3, 0); /* DLC 3 */
            put(321, FT_CAN_TYPE_FLOAT, 0x42c80000u, t + 7 * MS + 200000u, 8, 1); /* repeat */
            put(999, FT_CAN_TYPE_FLOAT, 0u, t + 7 * MS + 300000u, 8, 0);           /* unknown */
            put(311, FT_CAN_TYPE_FLOAT, 0x42f00000u, t + 7 * MS + 400000u, 8, 0); /* 120 deg */
            fprintf(g_log, "(1700000000.507500) vcan0 137#ZZ\n");
            fprintf(g_log, "(1700000000.507600) vcan0 137#R\n");
        }
    }
    REQUIRE(fclose(g_log) == 0);
}

static int run_replay(const char *log, const char *poses, ft_status *st_out, ft_error *err)
{
    ft_replay_desc d;
    memset(&d, 0, sizeof d);
    d.log_path = log;
    d.poses_path = poses;
    *st_out = ft_app_replay(&g_app, &d, &g_feed, &g_replay_io, &g_res, err);
    return *st_out == FT_OK;
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    REQUIRE(f != NULL);
    REQUIRE(fseek(f, 0, SEEK_END) == 0);
    long len = ftell(f);
    REQUIRE(len > 0);
    rewind(f);
    char *b = malloc((size_t)len + 1u);
    REQUIRE(b != NULL);
    REQUIRE(fread(b, 1, (size_t)len, f) == (size_t)len);
    b[len] = '\0';
    fclose(f);
    *n = (size_t)len;
    return b;
}

/* ---- smooth position: a flightgen orbit at 250 m/s through replay ---------- */

static FILE *g_fg_out;

/* North, east, up metres from 46.5 N 8.0 E, 0 m (WGS-84 radii there: the
 * orbit stays within 4 km, where that is exact to 1e-3). */
static void local_m(double lat, double lon, double alt, double out[3])
{
    const double deg = FT_RAD_PER_DEG;
    double m = 0.0, n = 0.0;
    ft_wgs84_radii_m(46.5, &m, &n);
    out[0] = (lat - 46.5) * deg * m;
    out[1] = (lon - 8.0) * deg * n * cos(46.5 * deg);
    out[2] = alt;
}

static ft_status fg_sink(void *ctx, const ft_candump_record *rec, const char *line, size_t len,
                         ft_error *err)
{
    (void)ctx;
    (void)rec;
    if (fwrite(line, 1u, len, g_fg_out) != len || fputc('\n', g_fg_out) == EOF) {
        return ft_fail(err, FT_ERR_IO, "test: log write failed");
    }
    return FT_OK;
}

/* A 4 km orbit at 250 m/s (58 deg of bank) around the synthetic terrain's
 * anchor, with a 500 m GPS reset at 5 s, replayed at 60 Hz by the real
 * `fixterrain replay` loop: the pose record's positions within 1 m of the
 * flown truth (plus the reset after it), one snap counted, no other step
 * over 1.5 x speed x period; then the same log with the velocity required
 * and its output stopped at 7 s. */
static void test_smooth_position(void)
{
    static flight_path path;
    flight_builtin_params bp;
    flight_builtin_defaults(&bp, FLIGHT_ORBIT);
    bp.centre_lat_deg = 46.5;
    bp.centre_lon_deg = 8.0;
    bp.alt_m = 3000.0;
    bp.radius_m = 4000.0;
    bp.speed_m_s = 250.0;
    ft_error err;
    REQUIRE(flight_path_builtin(&path, &bp, &err) == FT_OK);
    flightgen_options o;
    flightgen_options_default(&o);
    o.duration_s = 8.0;
    o.gps_jump_at_s = 5.0;
    o.gps_jump_m = 500.0;
    o.velocity_stop_s = 7.0;
    const char *log = FT_TEST_OUT_DIR "/replay_orbit250.log";
    const char *poses = FT_TEST_OUT_DIR "/replay_orbit250.csv";
    g_fg_out = fopen(log, "w");
    REQUIRE(g_fg_out != NULL);
    flightgen_stats fst;
    REQUIRE(flightgen_run(&path, &o, fg_sink, NULL, &fst, &err) == FT_OK);
    REQUIRE(fclose(g_fg_out) == 0);

    const double period_saved = g_app.scene.frame_period_ms;
    g_app.scene.frame_period_ms = 16.667; /* 60 Hz */
    for (int required = 0; required < 2; ++required) {
        g_app.scene.pose_velocity_required = required;
        ft_status st;
        if (!run_replay(log, poses, &st, &err)) fprintf(stderr, "replay orbit: %s\n", err.text);
        REQUIRE(st == FT_OK);
        size_t n = 0;
        char *text = slurp(poses, &n);
        const char *line = strchr(text, '\n');
        double prev[3] = {0.0, 0.0, 0.0}, prev_t = 0.0, err_max = 0.0, step_ratio_max = 0.0;
        int have_prev = 0, rows = 0, big_steps = 0, ann_rows = 0, pred_after_stop = 0;
        const double stop_s = 6.9 + 0.008 + 0.5; /* last altitude rate + its timeout */
        const double t_jump = 5.00650;           /* the first jumped latitude is in */
        while (line != NULL && line[1] != '\0') {
            ++line;
            unsigned k, mask;
            double t_s, lat, lon, alt, hdg, pitch, roll, scale, tau, off;
            int ann, pred, frozen, source, pos_pred;
            if (sscanf(line, "%u,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%d,%u,%d,%d,%d,%lf,%lf,%d,%lf", &k,
                       &t_s, &lat, &lon, &alt, &hdg, &pitch, &roll, &ann, &mask, &pred, &frozen,
                       &source, &scale, &tau, &pos_pred, &off) != 17) {
                fprintf(stderr, "bad pose row: %.100s\n", line);
                CHECK(0);
                break;
            }
            line = strchr(line, '\n');
            ++rows;
            const double t = t_s - 1700000000.0; /* path time */
            if (t < 0.2 || t > 8.0) {
                continue;
            }
            flight_sample s;
            flight_path_sample(&path, t, &s);
            double p[3], q[3];
            local_m(lat, lon, alt, p);
            local_m(s.lat_deg, s.lon_deg, s.alt_m, q);
            if (t >= t_jump) {
                q[0] += 500.0;
            }
            const double e = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                  (p[2] - q[2]) * (p[2] - q[2]));
            if (t <= stop_s) {
                /* the accuracy while the velocity is current (the last one
                 * at 6.9 s still predicts, from an older direction, until
                 * its timeout) */
                if (t < 7.0) {
                    err_max = fmax(err_max, e);
                }
                CHECK(pos_pred == 3 && ann == 0);
            } else {
                pred_after_stop += pos_pred != 0;
                ann_rows += ann;
            }
            if (have_prev && t <= stop_s) {
                const double step = sqrt((p[0] - prev[0]) * (p[0] - prev[0]) +
                                         (p[1] - prev[1]) * (p[1] - prev[1]) +
                                         (p[2] - prev[2]) * (p[2] - prev[2]));
                const double ratio = step / (250.0 * (t - prev_t));
                big_steps += ratio > 1.5;
                if (!(prev_t < t_jump && t >= t_jump)) {
                    step_ratio_max = fmax(step_ratio_max, ratio);
                }
            }
            memcpy(prev, p, sizeof prev);
            prev_t = t;
            have_prev = 1;
        }
        free(text);
        printf("replay orbit 250 m/s at 60 Hz (velocity required %d): %d rows, position error "
               "max %.3f m, largest step %.3f x speed x period outside the reset, %d steps over "
               "1.5 x, %llu snaps, velocity stale after %.3f s: %d rows predicted, %d "
               "annunciated, %u frames with a stale velocity\n",
               required, rows, err_max, step_ratio_max, big_steps,
               (unsigned long long)g_feed.ps.snap_count, stop_s, pred_after_stop, ann_rows,
               g_res.frames_velocity_stale);
        CHECK(err_max <= 1.0);
        CHECK(step_ratio_max <= 1.5);
        CHECK(big_steps == 1); /* the 500 m reset */
        CHECK(g_feed.ps.snap_count == 1u);
        CHECK(pred_after_stop == 0);
        CHECK(required ? ann_rows > 0 : ann_rows == 0);
        CHECK(g_res.frames_velocity_stale > 0u && g_res.frames_pos_predicted > 400u);
    }
    g_app.scene.frame_period_ms = period_saved;
    g_app.scene.pose_velocity_required = 0;
}

/* ---- timestamps the timeline cannot take ---------------------------------- */

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    REQUIRE(f != NULL);
    REQUIRE(fputs(text, f) >= 0);
    REQUIRE(fclose(f) == 0);
}

static void test_timeline_rule(void)
{
    const uint64_t s_ns = 1000000000ull;
    ft_replay_timeline tl;
    memset(&tl, 0, sizeof tl);
    /* past the end of the timeline: never an anchor */
    CHECK(ft_replay_timeline_accept(&tl, UINT64_MAX) == FT_REPLAY_TS_OUT_OF_RANGE);
    CHECK(ft_replay_timeline_accept(&tl, FT_REPLAY_T_MAX_NS + 1u) == FT_REPLAY_TS_OUT_OF_RANGE);
    CHECK(!tl.anchored && tl.out_of_range == 2u);
    CHECK(ft_replay_timeline_accept(&tl, 100u * s_ns) == FT_REPLAY_TS_OK);
    CHECK(tl.anchored && tl.anchor_ns == 100u * s_ns);
    CHECK(ft_replay_timeline_accept(&tl, 100u * s_ns) == FT_REPLAY_TS_OK); /* equal: fine */
    CHECK(ft_replay_timeline_accept(&tl, 100u * s_ns - 1u) == FT_REPLAY_TS_BACKWARDS);
    CHECK(ft_replay_timeline_accept(&tl, 0u) == FT_REPLAY_TS_BACKWARDS);
    CHECK(tl.backwards == 2u && tl.last_ns == 100u * s_ns);
    /* the span: exactly FT_REPLAY_SPAN_MAX_S after the anchor is in, 1 ns more is out */
    const uint64_t span_end = 100u * s_ns + (uint64_t)FT_REPLAY_SPAN_MAX_S * s_ns;
    CHECK(ft_replay_timeline_accept(&tl, span_end + 1u) == FT_REPLAY_TS_OUT_OF_RANGE);
    CHECK(ft_replay_timeline_accept(&tl, span_end) == FT_REPLAY_TS_OK);
    CHECK(tl.out_of_range == 3u && tl.last_ns == span_end);
    /* an anchor near the end of the clock: the end of the timeline bounds it */
    memset(&tl, 0, sizeof tl);
    CHECK(ft_replay_timeline_accept(&tl, FT_REPLAY_T_MAX_NS) == FT_REPLAY_TS_OK);
    CHECK(ft_replay_timeline_accept(&tl, FT_REPLAY_T_MAX_NS + 1u) == FT_REPLAY_TS_OUT_OF_RANGE);
    CHECK(ft_replay_timeline_accept(&tl, FT_REPLAY_T_MAX_NS) == FT_REPLAY_TS_OK);
}

static void test_timestamps(void)
{
    ft_status st;
    ft_error err;
    test_timeline_rule();

    /* A timestamp going backwards after a huge one: the display clock used
     * to restart at the small one (t_last + gap wrapped) and then step
     * towards the huge one for FT_REPLAY_FRAMES_LIMIT frames. */
    const char *back = FT_TEST_OUT_DIR "/replay_ts_backwards.log";
    write_text(back, "(18446744014.000000) vcan0 137#01020000A6652EE1\n"
                     "(1.000000) vcan0 137#01020001A6652EE1\n");
    CHECK(run_replay(back, NULL, &st, &err));
    printf("backwards log: %u frames, %llu backwards, %llu out of range, %llu CAN frames fed\n",
           g_res.frames, (unsigned long long)g_res.timestamps_backwards,
           (unsigned long long)g_res.timestamps_out_of_range,
           (unsigned long long)g_feed.frames_in);
    CHECK(g_res.frames == 1u);
    CHECK(g_res.timestamps_backwards == 1u && g_res.timestamps_out_of_range == 0u);
    CHECK(g_feed.frames_in == 1u); /* the rejected frame is not fed */
    CHECK(g_res.errors_kept == 1u &&
          strstr(g_res.errors[0], "replay_ts_backwards.log:2: timestamp 1.000000 s is "
                                  "earlier than the previous accepted frame's "
                                  "18446744014.000000 s") != NULL);

    /* A path longer than the kept text keeps its end: the file's name. */
    const char *back_long = FT_TEST_OUT_DIR "/replay_ts_backwards_in_a_file_whose_name_alone_is_"
                                            "longer_than_sixty_characters.log";
    write_text(back_long, "(18446744014.000000) vcan0 137#01020000A6652EE1\n"
                          "(1.000000) vcan0 137#01020001A6652EE1\n");
    CHECK(run_replay(back_long, NULL, &st, &err));
    printf("long path: kept \"%s\"\n", g_res.errors_kept == 1u ? g_res.errors[0] : "");
    CHECK(g_res.errors_kept == 1u && strncmp(g_res.errors[0], "...", 3) == 0 &&
          strstr(g_res.errors[0], "_sixty_characters.log:2: timestamp 1.000000 s is earlier") != NULL);

    /* The display clock wrapping past 2^64 ns: the second frame is 615 ns
     * before the end of the clock, so no display time can reach it. */
    const char *wrap = FT_TEST_OUT_DIR "/replay_ts_wrap.log";
    write_text(wrap, "(18446744013.709551) vcan0 137#0102000040400000\n"
                     "(18446744073.709551) vcan0 137#0102000140400000\n");
    CHECK(run_replay(wrap, NULL, &st, &err));
    printf("wrapping log: %u frames, %llu backwards, %llu out of range\n", g_res.frames,
           (unsigned long long)g_res.timestamps_backwards,
           (unsigned long long)g_res.timestamps_out_of_range);
    CHECK(g_res.frames == 1u);
    CHECK(g_res.timestamps_backwards == 0u && g_res.timestamps_out_of_range == 1u);
    CHECK(g_feed.frames_in == 1u);
    CHECK(g_res.errors_kept == 1u &&
          strstr(g_res.errors[0], "replay_ts_wrap.log:2: timestamp 18446744073.709551 s is past "
                                  "the end of the replay timeline") != NULL);
    CHECK(g_res.log_last_s >= 18446744013.0 && g_res.log_last_s <= 18446744014.0);

    /* Only timestamps past the end: nothing to anchor on, an error that
     * counts them. */
    const char *end_only = FT_TEST_OUT_DIR "/replay_ts_end.log";
    write_text(end_only, "(18446744073.709551) vcan0 137#0102000040400000\n"
                         "(18446744070.000000) vcan0 137#0102000140400000\n");
    CHECK(!run_replay(end_only, NULL, &st, &err));
    CHECK(st == FT_ERR_FORMAT && strstr(err.text, "no valid CAN frame in 2 lines (2 timestamps "
                                                  "out of range)") != NULL);
    CHECK(g_res.timestamps_out_of_range == 2u && g_res.frames == 0u);

    /* In a normal log: a frame from the past in the middle and one more
     * than the span after the first are rejected and counted; the rest
     * plays on, the timeline untouched (20 ms frames over 0.2 s). */
    const char *mixed = FT_TEST_OUT_DIR "/replay_ts_mixed.log";
    g_log = fopen(mixed, "w");
    REQUIRE(g_log != NULL);
    memset(g_code, 0, sizeof g_code);
    for (int i = 0; i <= 16; ++i) {
        uint64_t t = T0_NS + (uint64_t)i * 12500000ull;
        if (i == 5) {
            t = T0_NS - 3600ull * 1000000000ull; /* an hour before the first */
        } else if (i == 9) {
            t = T0_NS + ((uint64_t)FT_REPLAY_SPAN_MAX_S + 1u) * 1000000000ull;
        }
        put_float(311, -12.0f, t);
    }
    REQUIRE(fclose(g_log) == 0);
    CHECK(run_replay(mixed, NULL, &st, &err));
    printf("mixed log: %u frames, %llu backwards, %llu out of range, %llu gaps, %llu fed\n",
           g_res.frames, (unsigned long long)g_res.timestamps_backwards,
           (unsigned long long)g_res.timestamps_out_of_range, (unsigned long long)g_res.gaps,
           (unsigned long long)g_feed.frames_in);
    CHECK(g_res.timestamps_backwards == 1u && g_res.timestamps_out_of_range == 1u);
    CHECK(g_res.gaps == 0u && g_feed.frames_in == 15u);
    CHECK(g_res.frames == 11u); /* 0 .. 200 ms in 20 ms steps */
    CHECK_NEAR(g_res.log_last_s - g_res.log_first_s, 0.2, 1e-6);
    /* the message codes of the two rejected frames read as lost */
    CHECK(g_feed.dec.lost == 2u);
}

int main(void)
{
    const double pitch_rad = -12.0 * FT_RAD_PER_DEG;
    k_yaw_rate = 30.0 * cos(pitch_rad);
    k_roll_rate = -k_yaw_rate * tan(pitch_rad);
    ft_scene s;
    ft_error err;
    ft_status st;
    ft_scene_defaults(&s);
    REQUIRE(ft_scene_parse(&s, k_scene, "k_scene", &err) == FT_OK);
    st = ft_app_init(&g_app, &s, &err);
    if (st != FT_OK) fprintf(stderr, "init: %s\n", err.text);
    REQUIRE(st == FT_OK);

    const char *log = FT_TEST_OUT_DIR "/replay_faults.log";
    const char *poses_a = FT_TEST_OUT_DIR "/replay_a.csv", *poses_b = FT_TEST_OUT_DIR "/replay_b.csv";
    write_log(log);
    if (!run_replay(log, poses_a, &st, &err)) fprintf(stderr, "replay: %s\n", err.text);
    REQUIRE(st == FT_OK);
    const uint64_t *rej = g_feed.dec.rejects;
    printf("replay: %u frames, %llu lines (%llu bad, %llu unsupported), %llu CAN frames, "
           "rejects nonfinite %llu dlc %llu repeat %llu unknown %llu range %llu, lost %llu; "
           "%u annunciated (first %u), %u predicted\n",
           g_res.frames, (unsigned long long)g_res.lines, (unsigned long long)g_res.lines_bad,
           (unsigned long long)g_res.lines_unsupported, (unsigned long long)g_feed.frames_in,
           (unsigned long long)rej[FT_CAN_REJECT_NONFINITE],
           (unsigned long long)rej[FT_CAN_REJECT_DLC],
           (unsigned long long)rej[FT_CAN_REJECT_COUNTER_REPEAT],
           (unsigned long long)rej[FT_CAN_REJECT_UNKNOWN_ID],
           (unsigned long long)rej[FT_CAN_REJECT_RANGE], (unsigned long long)g_feed.dec.lost,
           g_res.frames_annunciated, g_res.first_annunciated, g_res.frames_predicted);
    CHECK(g_res.lines_bad == 2u && g_res.lines_unsupported == 1u);
    CHECK(rej[FT_CAN_REJECT_NONFINITE] == 1u && rej[FT_CAN_REJECT_DLC] == 1u);
    CHECK(rej[FT_CAN_REJECT_COUNTER_REPEAT] == 1u && rej[FT_CAN_REJECT_UNKNOWN_ID] == 1u);
    CHECK(rej[FT_CAN_REJECT_RANGE] == 1u && rej[FT_CAN_REJECT_TYPE] == 0u);
    CHECK(ft_pose_feed_rejected(&g_feed) == 5u);
    /* 10 dropped frames on each attitude id, plus the code the DLC-3 frame
     * used (rejected before its counter is read, so it reads as lost) */
    CHECK(g_feed.dec.lost == 31u);
    /* frames 0 .. ceil(last log time / 20 ms): the last frame at 2.9875 s +
     * 3.4 ms needs k = 150 */
    CHECK(g_res.frames == 151u);
    /* frame 0 has only the first pitch; the stall: last attitude at 1.9875 s,
     * pitch stale after 2.0875 s: frames 105 (2.10 s) .. 125 (2.50 s, roll and
     * heading of 2.501/2.502 s not yet in); 126 recovers */
    CHECK(g_res.first_annunciated == 0u);
    CHECK(g_res.frames_annunciated == 22u);

    size_t na = 0, nb = 0;
    char *a = slurp(poses_a, &na);
    int rows = 0, bad_heading = 0, window_ok = 1;
    double worst = 0.0;
    const char *line = strchr(a, '\n');
    while (line != NULL && line[1] != '\0') {
        ++line;
        unsigned k, mask;
        double t_s, lat, lon, alt, hdg, pitch, roll;
        int ann, pred;
        if (sscanf(line, "%u,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%d,%u,%d", &k, &t_s, &lat, &lon, &alt,
                   &hdg, &pitch, &roll, &ann, &mask, &pred) != 11) {
            fprintf(stderr, "bad pose row: %.80s\n", line);
            CHECK(0);
            break;
        }
        CHECK((int)k == rows);
        CHECK(isfinite(lat) && isfinite(lon) && isfinite(alt) && isfinite(hdg) &&
              isfinite(pitch) && isfinite(roll));
        const int expect_ann = (k == 0u) || (k >= 105u && k <= 125u);
        if (ann != expect_ann) {
            fprintf(stderr, "frame %u: annunciate %d, expected %d\n", k, ann, expect_ann);
            window_ok = 0;
        }
        if (!ann && pred) {
            double dt = t_s - 1700000000.0;
            double e = fabs(fmod(hdg - heading_at(dt) + 540.0, 360.0) - 180.0);
            if (e > worst) worst = e;
            bad_heading += (e > 0.05);
            CHECK_NEAR(pitch, -12.0, 0.01);
            CHECK_NEAR(roll, 0.0, 0.01);
            CHECK_NEAR(lat, 46.55, 1e-9);
            CHECK_NEAR(alt, 3500.0, 1e-3);
        }
        ++rows;
        line = strchr(line, '\n');
    }
    printf("pose rows %d, worst heading error against the flight %.5f deg\n", rows, worst);
    CHECK(rows == 151);
    CHECK(window_ok);
    CHECK(bad_heading == 0);

    /* determinism: the same log again gives the same bytes */
    if (!run_replay(log, poses_b, &st, &err)) fprintf(stderr, "replay 2: %s\n", err.text);
    CHECK(st == FT_OK);
    char *b = slurp(poses_b, &nb);
    CHECK(na == nb && memcmp(a, b, na) == 0);
    free(a);
    free(b);

    /* a spliced log with a 2-hour gap resumes after it */
    const char *gap_log = FT_TEST_OUT_DIR "/replay_gap.log";
    g_log = fopen(gap_log, "w");
    REQUIRE(g_log != NULL);
    memset(g_code, 0, sizeof g_code);
    for (int i = 0; i < 20; ++i) {
        uint64_t t = T0_NS + (uint64_t)i * 12500000ull + (i >= 10 ? 7200ull * 1000000000ull : 0u);
        put_float(311, -12.0f, t);
    }
    REQUIRE(fclose(g_log) == 0);
    CHECK(run_replay(gap_log, NULL, &st, &err));
    printf("gap log: %u frames, %llu gaps\n", g_res.frames, (unsigned long long)g_res.gaps);
    CHECK(g_res.gaps == 1u && g_res.frames < 30u);

    /* nothing valid at all: an error that says so */
    const char *junk = FT_TEST_OUT_DIR "/replay_junk.log";
    g_log = fopen(junk, "w");
    REQUIRE(g_log != NULL);
    fprintf(g_log, "hello\n(17.5) vcan0 1#00\n");
    REQUIRE(fclose(g_log) == 0);
    CHECK(!run_replay(junk, NULL, &st, &err));
    CHECK(st == FT_ERR_FORMAT && strstr(err.text, "no valid CAN frame") != NULL);
    CHECK(g_res.lines_bad == 2u && g_res.errors_kept == 2u);
    CHECK(strstr(g_res.errors[0], "replay_junk.log:1:") != NULL);

    test_timestamps();

    /* a missing log */
    CHECK(!run_replay(FT_TEST_OUT_DIR "/no_such.log", NULL, &st, &err));
    CHECK(st == FT_ERR_IO);

    test_smooth_position();

    ft_app_shutdown(&g_app);
    return ft_test_result("test_replay");
}
