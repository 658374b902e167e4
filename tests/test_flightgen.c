/* test_flightgen.c - fixterrain-flightgen's path model and log writer,
 * checked by decoding the logs back through the renderer's own input chain
 * (candump.h -> canaero.h -> pose_state.h):
 *   - every line parses, ids/node/service/DLC are as specified, timestamps
 *     strictly increase and are staggered within a period;
 *   - each decoded value equals the path at its own timestamp (attitude
 *     1e-4 deg, rates 1e-4 deg/s, lat/lon 1e-7 deg, alt 0.01 m);
 *   - message codes step by one per id and wrap 255 -> 0, decoder lost 0;
 *   - values per id arrive at 80 Hz / 10 Hz within 1 %;
 *   - the body rates integrated over 1/80 s from one attitude sample give
 *     the next one within 0.05 deg, and ft_pose_state's prediction at each
 *     new attitude time is within 0.05 deg of the path;
 *   - the built-in paths have their geometry (orbit radius and bank, climb
 *     50 -> 10000 m, dive to -30 deg, turn360 back to its heading, valley);
 *   - the velocity frames (1039/1040/314) equal the path's velocity;
 *   - through the decoder and the pose feed at 60 Hz, orbit and climb at 120
 *     and 250 m/s: the drawn position within 1 m of the flown truth, no
 *     frame step over 1.5 x speed x period (without velocity: both fail);
 *     a 500 m GPS reset snapped and counted, a 5 m one converged, a stopped
 *     velocity stops the prediction at its timeout;
 *   - every fault gives exactly the decoder rejects / lost counts asked for;
 *   - waypoint file errors name their line; the derived-attitude rule;
 *   - determinism, start time and interface options. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/units.h"
#include "input/canaero.h"
#include "input/candump.h"
#include "flight_path.h"
#include "input/pose_feed.h"
#include "input/pose_state.h"
#include "test_util.h"

#define DEG (FT_PI / 180.0)
#define RAD (180.0 / FT_PI)

static flight_path g_path;

/* ---- a log in memory -------------------------------------------------------- */

typedef struct logbuf {
    char *text;
    size_t len, cap;
    uint64_t lines;
} logbuf;

static ft_status mem_sink(void *ctx, const ft_candump_record *rec, const char *line, size_t len,
                          ft_error *err)
{
    (void)rec;
    logbuf *b = ctx;
    if (b->len + len + 1u > b->cap) {
        size_t cap = b->cap == 0u ? (1u << 16) : b->cap;
        while (cap < b->len + len + 1u) {
            cap *= 2u;
        }
        char *t = realloc(b->text, cap);
        if (t == NULL) {
            return ft_fail(err, FT_ERR_BUDGET, "test: out of memory");
        }
        b->text = t;
        b->cap = cap;
    }
    memcpy(b->text + b->len, line, len);
    b->len += len;
    b->text[b->len++] = '\n';
    ++b->lines;
    return FT_OK;
}

static void log_free(logbuf *b)
{
    free(b->text);
    memset(b, 0, sizeof *b);
}

static void generate(const flight_path *p, const flightgen_options *o, logbuf *b,
                     flightgen_stats *st)
{
    memset(b, 0, sizeof *b);
    ft_error err = {0};
    ft_status s = flightgen_run(p, o, mem_sink, b, st, &err);
    if (s != FT_OK) {
        fprintf(stderr, "flightgen_run: %s\n", err.text);
    }
    REQUIRE(s == FT_OK);
    REQUIRE(b->lines == st->lines);
}

static void builtin(flight_builtin_kind k, double duration_s)
{
    flight_builtin_params bp;
    flight_builtin_defaults(&bp, k);
    bp.duration_s = duration_s;
    ft_error err = {0};
    ft_status s = flight_path_builtin(&g_path, &bp, &err);
    if (s != FT_OK) {
        fprintf(stderr, "builtin %s: %s\n", flight_builtin_name(k), err.text);
    }
    REQUIRE(s == FT_OK);
}

/* ---- decoding a log back ---------------------------------------------------- */

typedef struct value {
    ft_pose_qty qty;
    double v;
    uint64_t t_ns;
} value;

typedef struct decoded {
    ft_canaero dec;
    value *vals;
    size_t nvals;
    uint64_t lines, parse_failures, bad_header, non_monotonic;
    uint64_t code_skips; /* codes that did not step by exactly one (own check) */
    uint32_t wraps;      /* 255 -> 0 seen */
    uint64_t per_qty[FT_QTY_COUNT];
    uint64_t first_t_ns, last_t_ns;
    uint64_t rejected_line_t_ns; /* time of the last rejected frame */
    uint32_t rejected_id;
} decoded;

static void decode(const logbuf *b, decoded *d)
{
    memset(d, 0, sizeof *d);
    ft_can_map m;
    ft_canaero_default_map(&m);
    ft_error err = {0};
    REQUIRE(ft_canaero_init(&d->dec, &m, &err) == FT_OK);
    d->vals = malloc((b->lines + 1u) * sizeof *d->vals);
    REQUIRE(d->vals != NULL);
    int has_code[0x800] = {0};
    uint8_t last_code[0x800] = {0};
    size_t i = 0u;
    uint64_t prev_t = 0u;
    while (i < b->len) {
        size_t start = i;
        while (i < b->len && b->text[i] != '\n') {
            ++i;
        }
        size_t n = i - start;
        ++i;
        ++d->lines;
        ft_candump_record rec;
        if (ft_candump_parse_line(b->text + start, n, &rec, &err) != FT_OK) {
            if (d->parse_failures == 0u) {
                fprintf(stderr, "parse: %s: %.*s\n", err.text, (int)n, b->text + start);
            }
            ++d->parse_failures;
            continue;
        }
        const ft_can_frame *f = &rec.frame;
        if (d->lines == 1u) {
            d->first_t_ns = f->t_ns;
        } else if (f->t_ns <= prev_t) {
            ++d->non_monotonic;
        }
        prev_t = f->t_ns;
        d->last_t_ns = f->t_ns;
        if (f->extended || f->data[0] != 1u || f->data[2] != 0u ||
            (f->data[1] != FT_CAN_TYPE_FLOAT && f->data[1] != FT_CAN_TYPE_DOUBLEH &&
             f->data[1] != FT_CAN_TYPE_DOUBLEL)) {
            ++d->bad_header;
        }
        uint32_t id = f->can_id & 0x7FFu;
        uint8_t code = f->data[3];
        if (has_code[id] && code != (uint8_t)(last_code[id] + 1u)) {
            ++d->code_skips;
        }
        if (has_code[id] && last_code[id] == 255u && code == 0u) {
            ++d->wraps;
        }
        has_code[id] = 1;
        last_code[id] = code;
        ft_can_result r;
        ft_can_outcome oc = ft_canaero_decode(&d->dec, f, &r);
        if (oc == FT_CAN_VALUE) {
            value *v = &d->vals[d->nvals++];
            v->qty = r.input.qty;
            v->v = r.input.value;
            v->t_ns = r.input.t_ns;
            ++d->per_qty[r.input.qty];
        } else if (oc == FT_CAN_REJECTED) {
            d->rejected_line_t_ns = f->t_ns;
            d->rejected_id = f->can_id;
        }
    }
}

static void decoded_free(decoded *d)
{
    free(d->vals);
    d->vals = NULL;
}

static uint64_t total_rejects(const decoded *d)
{
    uint64_t n = 0u;
    for (int r = 0; r < (int)FT_CAN_REJECT_COUNT; ++r) {
        n += d->dec.rejects[r];
    }
    return n;
}

static double path_time(const flight_path *p, const flightgen_options *o, uint64_t t_ns)
{
    /* the generator's own mapping: t0 + whole microseconds since the start */
    return flight_path_t0_s(p) + (double)(t_ns / 1000u - o->start_us) * 1e-6;
}

static double quat_angle_deg(ft_quat a, ft_quat b)
{
    double na = ft_quat_norm(a), nb = ft_quat_norm(b);
    double d = fabs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z) / (na * nb);
    return 2.0 * acos(d > 1.0 ? 1.0 : d) * RAD;
}

/* ---- the checks every clean log must pass ----------------------------------- */

typedef struct measured {
    double att_err_deg, rate_err_deg_s, latlon_err_deg, alt_err_m;
    double vel_err_m_s, track_err_deg; /* velocity frames against the path's velocity */
    double predict_err_deg;  /* rates integrated sample to sample */
    double estimate_err_deg; /* ft_pose_state_estimate against the path */
    double hz[FT_QTY_COUNT];
} measured;

static void check_clean(const char *what, const flight_path *p, const flightgen_options *o,
                        const logbuf *b, const flightgen_stats *st, measured *ms)
{
    memset(ms, 0, sizeof *ms);
    decoded d;
    decode(b, &d);
    int fails_before = g_ft_test_failures;
    CHECK(d.lines == st->lines);
    CHECK(d.parse_failures == 0u);
    CHECK(d.bad_header == 0u);
    CHECK(d.non_monotonic == 0u);
    CHECK(d.code_skips == 0u);
    CHECK(total_rejects(&d) == 0u);
    CHECK(d.dec.lost == 0u);
    CHECK(d.first_t_ns == o->start_us * 1000u);
    /* every frame produced a value except the DOUBLEH halves */
    CHECK(d.dec.accepted + d.dec.pending == d.lines);
    CHECK(d.nvals == d.dec.accepted);

    /* values against the path at their own timestamps */
    for (size_t i = 0u; i < d.nvals; ++i) {
        const value *v = &d.vals[i];
        flight_sample s;
        flight_path_sample(p, path_time(p, o, v->t_ns), &s);
        double e = 0.0;
        switch (v->qty) {
        case FT_QTY_PITCH: e = fabs(v->v - s.pitch_deg); break;
        case FT_QTY_ROLL: e = fabs(ft_wrap_deg_pm180(v->v - s.roll_deg)); break;
        case FT_QTY_HEADING: e = fabs(ft_wrap_deg_pm180(v->v - s.heading_deg)); break;
        case FT_QTY_ROLL_RATE: e = fabs(v->v - s.p_deg_s); break;
        case FT_QTY_PITCH_RATE: e = fabs(v->v - s.q_deg_s); break;
        case FT_QTY_YAW_RATE: e = fabs(v->v - s.r_deg_s); break;
        case FT_QTY_LAT: e = fabs(v->v - s.lat_deg); break;
        case FT_QTY_LON: e = fabs(v->v - s.lon_deg); break;
        case FT_QTY_GROUND_SPEED: e = fabs(v->v - hypot(s.v_n_m_s, s.v_e_m_s)); break;
        case FT_QTY_TRACK:
            /* a direction only where there is a horizontal speed */
            e = hypot(s.v_n_m_s, s.v_e_m_s) < 0.5
                    ? 0.0
                    : fabs(ft_wrap_deg_pm180(v->v - atan2(s.v_e_m_s, s.v_n_m_s) * RAD));
            break;
        case FT_QTY_ALT_RATE: e = fabs(v->v - s.v_u_m_s); break;
        case FT_QTY_ALT:
        default: e = fabs(v->v - s.alt_m); break;
        }
        if (v->qty == FT_QTY_TRACK) {
            ms->track_err_deg = fmax(ms->track_err_deg, e);
        } else if (v->qty == FT_QTY_GROUND_SPEED || v->qty == FT_QTY_ALT_RATE) {
            ms->vel_err_m_s = fmax(ms->vel_err_m_s, e);
        } else if (v->qty <= FT_QTY_HEADING) {
            ms->att_err_deg = fmax(ms->att_err_deg, e);
        } else if (v->qty == FT_QTY_LAT || v->qty == FT_QTY_LON) {
            ms->latlon_err_deg = fmax(ms->latlon_err_deg, e);
        } else if (v->qty == FT_QTY_ALT) {
            ms->alt_err_m = fmax(ms->alt_err_m, e);
        } else {
            ms->rate_err_deg_s = fmax(ms->rate_err_deg_s, e);
        }
    }
    CHECK(ms->att_err_deg <= 1e-4);
    CHECK(ms->rate_err_deg_s <= 1e-4);
    CHECK(ms->latlon_err_deg <= 1e-7);
    CHECK(ms->alt_err_m <= 0.01);
    CHECK(ms->vel_err_m_s <= 1e-4); /* FLOAT: 250 m/s to 1.5e-5 m/s */
    CHECK(ms->track_err_deg <= 1e-4);

    /* rates per quantity (values, so a DOUBLEH/L pair counts once) */
    double dur_s = isnan(o->duration_s) ? flight_path_duration_s(p) : o->duration_s;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        ms->hz[q] = (double)d.per_qty[q] / dur_s;
        const int ten_hz = (FT_QTY_BIT(q) & (FT_QTY_POSITION_MASK | FT_QTY_VELOCITY_MASK)) != 0u;
        double want = ten_hz ? 10.0 : 80.0;
        CHECK(fabs(ms->hz[q] - want) <= 0.01 * want);
    }

    /* stagger: the first position period has 11 frames at 11 times */
    CHECK(d.vals[0].t_ns != d.vals[1].t_ns);

    /* attitude sample k + body rates k, integrated 1/80 s -> sample k+1 */
    size_t nper = d.per_qty[FT_QTY_PITCH];
    double *a = malloc(nper * 6u * sizeof *a);
    REQUIRE(a != NULL);
    size_t cnt[6] = {0};
    static const ft_pose_qty k_order[6] = {FT_QTY_HEADING, FT_QTY_PITCH, FT_QTY_ROLL,
                                           FT_QTY_ROLL_RATE, FT_QTY_PITCH_RATE, FT_QTY_YAW_RATE};
    for (size_t i = 0u; i < d.nvals; ++i) {
        for (int j = 0; j < 6; ++j) {
            if (d.vals[i].qty == k_order[j] && cnt[j] < nper) {
                a[cnt[j]++ * 6u + (size_t)j] = d.vals[i].v;
            }
        }
    }
    for (int j = 0; j < 6; ++j) {
        CHECK(cnt[j] == nper);
    }
    for (size_t k = 0u; k + 1u < nper; ++k) {
        const double *x = &a[k * 6u], *y = &a[(k + 1u) * 6u];
        ft_quat qk = ft_quat_from_euler_deg(x[0], x[1], x[2]);
        double w[3] = {x[3] * DEG, x[4] * DEG, x[5] * DEG};
        ft_quat pred = ft_quat_integrate_body_rate(qk, w, 1.0 / 80.0);
        ft_quat next = ft_quat_from_euler_deg(y[0], y[1], y[2]);
        ms->predict_err_deg = fmax(ms->predict_err_deg, quat_angle_deg(pred, next));
    }
    free(a);
    CHECK(ms->predict_err_deg <= 0.05);

    /* the renderer's extrapolator: before each new pitch sample arrives,
     * predict to its time from what was received so far */
    ft_pose_state ps;
    ft_error err = {0};
    REQUIRE(ft_pose_state_init(&ps, FT_POSE_HORIZON_DEFAULT_MS, &err) == FT_OK);
    uint32_t unpredicted = 0u, estimates = 0u;
    for (size_t i = 0u; i < d.nvals; ++i) {
        const value *v = &d.vals[i];
        if (v->qty == FT_QTY_PITCH && i > 0u) {
            uint32_t need = FT_QTY_ATTITUDE_MASK | FT_QTY_RATE_MASK;
            if ((ft_pose_state_stale(&ps, v->t_ns, NULL, 0u) & need) == 0u) {
                ft_pose_estimate est;
                ft_pose_state_estimate(&ps, v->t_ns, &est);
                flight_sample s;
                flight_path_sample(p, path_time(p, o, v->t_ns), &s);
                ms->estimate_err_deg =
                    fmax(ms->estimate_err_deg, quat_angle_deg(est.attitude, s.q));
                unpredicted += est.predicted ? 0u : 1u;
                ++estimates;
            }
        }
        ft_pose_input in = {v->qty, v->v, v->t_ns, 100u, 0u, 0u};
        REQUIRE(ft_pose_state_apply(&ps, &in, NULL, &err) == FT_OK);
    }
    CHECK(unpredicted == 0u);
    CHECK(estimates + 1u == nper); /* every pitch sample but the first */
    CHECK(ms->estimate_err_deg <= 0.05);
    if (g_ft_test_failures != fails_before) {
        fprintf(stderr, "  (in %s)\n", what);
    }
    printf("%-10s %7llu lines %5.1f s: att %.1e deg, rate %.1e deg/s, latlon %.1e deg, alt "
           "%.1e m, velocity %.1e m/s, track %.1e deg, rate-predict %.1e deg, pose_state %.1e "
           "deg, %.2f/%.2f/%.2f Hz\n",
           what, (unsigned long long)d.lines, dur_s, ms->att_err_deg, ms->rate_err_deg_s,
           ms->latlon_err_deg, ms->alt_err_m, ms->vel_err_m_s, ms->track_err_deg,
           ms->predict_err_deg, ms->estimate_err_deg, ms->hz[FT_QTY_PITCH], ms->hz[FT_QTY_LAT],
           ms->hz[FT_QTY_GROUND_SPEED]);
    decoded_free(&d);
}

/* ---- tests ------------------------------------------------------------------ */

static void test_encoder_line(void)
{
    /* the example line of the issue: pitch 5.0 (0x40A00000), code 0 */
    ft_candump_record rec;
    memset(&rec, 0, sizeof rec);
    flightgen_encode(&rec.frame, 311u, FT_CAN_TYPE_FLOAT, 0u, 0x40A00000u,
                     UINT64_C(1700000000012500000));
    memcpy(rec.iface, "vcan0", 6);
    char line[64];
    ft_error err = {0};
    REQUIRE(ft_candump_format(&rec, line, sizeof line, NULL, &err) == FT_OK);
    CHECK(strcmp(line, "(1700000000.012500) vcan0 137#0102000040A00000") == 0);
    /* the schedule carries the CANaerospace default ids (canaero.h's map,
     * not a copy): 1039 ground speed, 1040 true track, 314 altitude rate */
    ft_can_map m;
    ft_canaero_default_map(&m);
    static const ft_pose_qty want[FLIGHTGEN_MSG_COUNT] = {
        FT_QTY_PITCH,     FT_QTY_ROLL,       FT_QTY_HEADING, FT_QTY_ROLL_RATE, FT_QTY_PITCH_RATE,
        FT_QTY_YAW_RATE, FT_QTY_LAT,        FT_QTY_LON,     FT_QTY_ALT,       FT_QTY_GROUND_SPEED,
        FT_QTY_TRACK,    FT_QTY_ALT_RATE};
    static const uint16_t want_id[FLIGHTGEN_MSG_COUNT] = {311u,  312u,  321u,  304u,
                                                          303u,  305u,  1036u, 1037u,
                                                          320u,  1039u, 1040u, 314u};
    uint16_t ids[FLIGHTGEN_MSG_COUNT];
    REQUIRE(flightgen_ids(ids, &err) == FT_OK);
    for (uint32_t i = 0u; i < FLIGHTGEN_MSG_COUNT; ++i) {
        CHECK(flightgen_schedule[i].qty == want[i]);
        CHECK(ids[i] == want_id[i]);
        int found = 0;
        for (uint32_t j = 0u; j < m.count; ++j) {
            if (m.e[j].can_id == ids[i]) {
                found = 1;
                CHECK(m.e[j].qty == want[i]);
                CHECK(m.e[j].priority == 0u);
            }
        }
        CHECK(found);
        /* in time order within the period */
        CHECK(i == 0u || flightgen_schedule[i].offset_us > flightgen_schedule[i - 1u].offset_us);
    }
    double speed, track;
    flightgen_ground_velocity(-3.0, -4.0, &speed, &track);
    CHECK_NEAR(speed, 5.0, 1e-12);
    CHECK_NEAR(track, 180.0 + atan2(4.0, 3.0) * RAD, 1e-9);
    flightgen_ground_velocity(0.0, 0.0, &speed, &track);
    CHECK(speed == 0.0 && track == 0.0);
}

static void test_orbit(void)
{
    builtin(FLIGHT_ORBIT, NAN); /* one revolution */
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf b;
    flightgen_stats st;
    generate(&g_path, &o, &b, &st);
    measured ms;
    check_clean("orbit", &g_path, &o, &b, &st, &ms);

    /* geometry, independent of the path model: radius 2000 m around the
     * centre at 1000 m, bank atan(V^2 / (g R)), level, heading = bearing
     * from the centre + 90, constant yaw/pitch rate from the turn rate */
    decoded d;
    decode(&b, &d);
    CHECK(d.wraps > 0u); /* > 256 frames per id */
    double bank = atan(60.0 * 60.0 / (FLIGHT_G_M_S2 * 2000.0)) * RAD;
    double turn_deg_s = 60.0 / 2000.0 * RAD;
    double lat = 0.0, max_r_err = 0.0, max_roll_err = 0.0, max_rate_err = 0.0;
    double max_hdg_err = 0.0;
    double m_per_deg = FLIGHT_EARTH_RADIUS_M * DEG;
    for (size_t i = 0u; i < d.nvals; ++i) {
        const value *v = &d.vals[i];
        if (v->qty == FT_QTY_LAT) {
            lat = v->v;
        } else if (v->qty == FT_QTY_LON && lat != 0.0) {
            double n = (lat - 46.5) * m_per_deg;
            double e = (v->v - 8.0) * m_per_deg * cos(46.5 * DEG);
            max_r_err = fmax(max_r_err, fabs(hypot(n, e) - 2000.0));
            flight_sample s;
            flight_path_sample(&g_path, path_time(&g_path, &o, v->t_ns), &s);
            double brg = atan2(e, n) * RAD;
            max_hdg_err = fmax(max_hdg_err, fabs(ft_wrap_deg_pm180(s.heading_deg - brg - 90.0)));
        } else if (v->qty == FT_QTY_ALT) {
            CHECK_NEAR(v->v, 1000.0, 1e-3);
        } else if (v->qty == FT_QTY_ROLL) {
            max_roll_err = fmax(max_roll_err, fabs(v->v - bank));
        } else if (v->qty == FT_QTY_PITCH) {
            CHECK_NEAR(v->v, 0.0, 1e-6);
        } else if (v->qty == FT_QTY_YAW_RATE) {
            max_rate_err = fmax(max_rate_err, fabs(v->v - turn_deg_s * cos(bank * DEG)));
        } else if (v->qty == FT_QTY_PITCH_RATE) {
            max_rate_err = fmax(max_rate_err, fabs(v->v - turn_deg_s * sin(bank * DEG)));
        } else if (v->qty == FT_QTY_ROLL_RATE) {
            max_rate_err = fmax(max_rate_err, fabs(v->v));
        }
    }
    printf("orbit geometry: radius err %.3f m, roll err %.1e deg (bank %.3f), rate err %.1e "
           "deg/s, heading err %.4f deg\n",
           max_r_err, max_roll_err, bank, max_rate_err, max_hdg_err);
    CHECK(max_r_err <= 0.1);     /* chord of 0.1 s steps on a 2 km circle: 2 mm */
    CHECK(max_roll_err <= 1e-4);
    CHECK(max_rate_err <= 1e-4);
    CHECK(max_hdg_err <= 0.01);  /* position and heading sampled at different times */
    /* one full revolution: 560 lines per second */
    CHECK(fabs((double)st.lines / flight_path_duration_s(&g_path) - 560.0) < 1.0);
    /* without velocity: 530, the rest identical */
    logbuf nv;
    flightgen_stats stn;
    o.velocity = 0;
    generate(&g_path, &o, &nv, &stn);
    CHECK(stn.lines + st.frames[FLIGHTGEN_GROUND_SPEED] + st.frames[FLIGHTGEN_TRACK] +
              st.frames[FLIGHTGEN_ALT_RATE] ==
          st.lines);
    CHECK(stn.frames[FLIGHTGEN_GROUND_SPEED] == 0u && stn.frames[FLIGHTGEN_TRACK] == 0u);
    CHECK(fabs((double)stn.lines / flight_path_duration_s(&g_path) - 530.0) < 1.0);
    log_free(&nv);
    decoded_free(&d);
    log_free(&b);
}

static void test_other_builtins(void)
{
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf b;
    flightgen_stats st;
    measured ms;
    decoded d;

    /* climb: 50 m -> 10000 m linearly, straight on heading 090 */
    builtin(FLIGHT_CLIMB, 200.0);
    generate(&g_path, &o, &b, &st);
    check_clean("climb", &g_path, &o, &b, &st, &ms);
    decode(&b, &d);
    double gamma = asin(9950.0 / 200.0 / 130.0) * RAD;
    for (size_t i = 0u; i < d.nvals; ++i) {
        const value *v = &d.vals[i];
        double t = path_time(&g_path, &o, v->t_ns);
        if (v->qty == FT_QTY_ALT) {
            CHECK_NEAR(v->v, 50.0 + 9950.0 * t / 200.0, 0.01);
        } else if (v->qty == FT_QTY_PITCH) {
            CHECK_NEAR(v->v, gamma, 1e-4);
        } else if (v->qty == FT_QTY_HEADING) {
            CHECK_NEAR(v->v, 90.0, 1e-4);
        }
    }
    flight_sample s;
    flight_path_sample(&g_path, 200.0, &s);
    CHECK_NEAR(s.alt_m, 10000.0, 1e-6);
    decoded_free(&d);
    log_free(&b);

    /* dive: level, down to -30 deg, level again, never below 50 m */
    builtin(FLIGHT_DIVE, NAN);
    generate(&g_path, &o, &b, &st);
    check_clean("dive", &g_path, &o, &b, &st, &ms);
    decode(&b, &d);
    double min_pitch = 0.0, min_alt = 1e9, last_pitch = 1.0;
    for (size_t i = 0u; i < d.nvals; ++i) {
        if (d.vals[i].qty == FT_QTY_PITCH) {
            min_pitch = fmin(min_pitch, d.vals[i].v);
            last_pitch = d.vals[i].v;
        } else if (d.vals[i].qty == FT_QTY_ALT) {
            min_alt = fmin(min_alt, d.vals[i].v);
        }
    }
    CHECK_NEAR(min_pitch, -30.0, 1e-4);
    CHECK_NEAR(last_pitch, 0.0, 1e-6);
    CHECK(min_alt > 50.0 && min_alt < 3000.0 - 1000.0);
    decoded_free(&d);
    log_free(&b);

    /* turn360: heading goes all the way round and back to 000, banked right */
    builtin(FLIGHT_TURN360, NAN);
    generate(&g_path, &o, &b, &st);
    check_clean("turn360", &g_path, &o, &b, &st, &ms);
    decode(&b, &d);
    double max_roll = 0.0, last_hdg = -1.0, unwrapped = 0.0, prev_hdg = 0.0;
    for (size_t i = 0u; i < d.nvals; ++i) {
        if (d.vals[i].qty == FT_QTY_ROLL) {
            max_roll = fmax(max_roll, d.vals[i].v);
        } else if (d.vals[i].qty == FT_QTY_HEADING) {
            unwrapped += ft_wrap_deg_pm180(d.vals[i].v - prev_hdg);
            prev_hdg = d.vals[i].v;
            last_hdg = d.vals[i].v;
        }
    }
    double want_bank = atan(70.0 * (2.0 * FT_PI / (90.0 - 3.0)) / FLIGHT_G_M_S2) * RAD;
    CHECK_NEAR(max_roll, want_bank, 1e-3);
    CHECK_NEAR(unwrapped, 360.0, 1e-3);
    CHECK(last_hdg >= 0.0 && fabs(ft_wrap_deg_pm180(last_hdg)) < 1e-3);
    decoded_free(&d);
    log_free(&b);

    /* valley: straight and level on 045 at 150 m, no rates */
    builtin(FLIGHT_VALLEY, 30.0);
    generate(&g_path, &o, &b, &st);
    check_clean("valley", &g_path, &o, &b, &st, &ms);
    decode(&b, &d);
    for (size_t i = 0u; i < d.nvals; ++i) {
        const value *v = &d.vals[i];
        if (v->qty == FT_QTY_HEADING) {
            CHECK_NEAR(v->v, 45.0, 1e-4);
        } else if (v->qty == FT_QTY_ALT) {
            CHECK_NEAR(v->v, 150.0, 1e-3);
        } else if (v->qty == FT_QTY_GROUND_SPEED) {
            /* 100 m/s on the sphere the path is built on, as the GPS on the
             * ellipsoid reports it: within 0.7 % */
            CHECK_NEAR(v->v, 100.0, 0.7);
        } else if (v->qty == FT_QTY_TRACK) {
            CHECK_NEAR(v->v, 45.0, 0.2);
        } else if (v->qty != FT_QTY_LAT && v->qty != FT_QTY_LON) {
            CHECK_NEAR(v->v, 0.0, 1e-6);
        }
    }
    decoded_free(&d);
    log_free(&b);

    /* bad built-in parameters */
    flight_builtin_params bp;
    ft_error err = {0};
    flight_builtin_defaults(&bp, FLIGHT_TURN360);
    bp.duration_s = 20.0;
    CHECK(flight_path_builtin(&g_path, &bp, &err) != FT_OK && strstr(err.text, "bank") != NULL);
    flight_builtin_defaults(&bp, FLIGHT_CLIMB);
    bp.alt_m = 500.0;
    CHECK(flight_path_builtin(&g_path, &bp, &err) != FT_OK && strstr(err.text, "--alt") != NULL);
    flight_builtin_defaults(&bp, FLIGHT_DIVE);
    bp.alt_m = 1000.0;
    CHECK(flight_path_builtin(&g_path, &bp, &err) != FT_OK && strstr(err.text, "50 m") != NULL);
    flight_builtin_defaults(&bp, FLIGHT_ORBIT);
    bp.radius_m = 200.0;
    CHECK(flight_path_builtin(&g_path, &bp, &err) != FT_OK && strstr(err.text, "bank") != NULL);
    CHECK(flight_builtin_from_name("loop") == -1);
    CHECK(flight_builtin_from_name("turn360") == FLIGHT_TURN360);
}

static const char k_wp_text[] =
    "# test flight: east, climbing left turn to north, attitude given at 30 s\n"
    "# t_s lat_deg lon_deg alt_m [heading_deg pitch_deg roll_deg]\n"
    "0    46.500000 8.000000 1000   90 0 0\n"
    "\n"
    "10   46.500000 8.010000 1000   # derived\n"
    "20   46.501000 8.019000 1050\n"
    "30   46.505000 8.025000 1100   40 3 -10\n"
    "40   46.511000 8.028000 1100\n"
    "50   46.518000 8.029000 1100\n";

static void test_waypoints(void)
{
    ft_error err = {0};
    ft_status s =
        flight_path_parse_waypoints(&g_path, k_wp_text, strlen(k_wp_text), "test.wp", &err);
    if (s != FT_OK) {
        fprintf(stderr, "%s\n", err.text);
    }
    REQUIRE(s == FT_OK);
    CHECK(g_path.count == 6u);
    CHECK(g_path.wp[1].line == 5u && g_path.wp[5].line == 9u);
    CHECK(g_path.wp[3].has_attitude && !g_path.wp[1].has_attitude);
    CHECK_NEAR(g_path.wp[3].roll_deg, -10.0, 0.0);
    /* derived: turning left (heading decreasing) banks left */
    CHECK(g_path.wp[2].heading_deg > 40.0 && g_path.wp[2].heading_deg < 90.0);
    CHECK(g_path.wp[2].pitch_deg > 0.0);
    CHECK(g_path.wp[4].roll_deg < 0.0);
    CHECK(g_path.wp[5].roll_deg == 0.0); /* end */

    flightgen_options o;
    flightgen_options_default(&o);
    logbuf b;
    flightgen_stats st;
    measured ms;
    generate(&g_path, &o, &b, &st);
    check_clean("waypoints", &g_path, &o, &b, &st, &ms);
    log_free(&b);

    /* the derivation rule on simple cases */
    static const char straight[] = "0 46.5 8.00 1000\n10 46.5 8.01 1100\n20 46.5 8.02 1200\n";
    REQUIRE(flight_path_parse_waypoints(&g_path, straight, strlen(straight), "s", &err) ==
            FT_OK);
    double east_m = 0.01 * DEG * FLIGHT_EARTH_RADIUS_M * cos(46.5 * DEG);
    for (uint32_t i = 0u; i < 3u; ++i) {
        CHECK_NEAR(g_path.wp[i].heading_deg, 90.0, 1e-9);
        CHECK_NEAR(g_path.wp[i].pitch_deg, atan2(100.0, east_m) * RAD, 1e-9);
        CHECK_NEAR(g_path.wp[i].roll_deg, 0.0, 1e-9);
    }
    /* right turn east -> south: coordinated bank atan(V * turn rate / g) */
    static const char right[] = "0 46.5 8.00 1000\n10 46.5 8.01 1000\n20 46.49 8.01 1000\n";
    REQUIRE(flight_path_parse_waypoints(&g_path, right, strlen(right), "r", &err) == FT_OK);
    double north_m = 0.01 * DEG * FLIGHT_EARTH_RADIUS_M;
    double e1 = 0.01 * DEG * FLIGHT_EARTH_RADIUS_M * cos(46.495 * DEG);
    double vh = hypot(north_m, e1) / 20.0;
    double turn = ft_wrap_deg_pm180(atan2(0.0, -north_m) * RAD - 90.0) * DEG / 10.0;
    CHECK_NEAR(g_path.wp[1].roll_deg, atan(vh * turn / FLIGHT_G_M_S2) * RAD, 1e-6);
    CHECK(g_path.wp[1].roll_deg > 0.0);
    CHECK_NEAR(g_path.wp[1].heading_deg, atan2(e1, -north_m) * RAD, 1e-6);
}

static void expect_wp_error(const char *text, const char *want1, const char *want2)
{
    ft_error err = {0};
    ft_status s = flight_path_parse_waypoints(&g_path, text, strlen(text), "bad.wp", &err);
    CHECK(s != FT_OK);
    int ok = strstr(err.text, want1) != NULL && (want2 == NULL || strstr(err.text, want2) != NULL);
    if (!ok || s == FT_OK) {
        fprintf(stderr, "waypoint error: want '%s' '%s', got '%s'\n", want1,
                want2 != NULL ? want2 : "", err.text);
    }
    CHECK(ok);
}

static void test_waypoint_errors(void)
{
    expect_wp_error("0 46.5 8 1000\n1 46.5 8.001 1000\n1 46.5 8.002 1000\n",
                    "bad.wp line 3: time 1 s is not after", "(bad.wp line 2)");
    expect_wp_error("# c\n0 46.5 8 1000\n5 46.5 8.001 1000\n4 46.5 8.002 1000\n", "line 4",
                    "not after");
    expect_wp_error("0 46.5 8 1000\n1 95 8 1000\n", "line 2: lat_deg 95 is outside", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.5 181 1000\n", "line 2: lon_deg", "outside");
    expect_wp_error("0 46.5 8 1000\n1 46.5 8 30000\n", "line 2: alt_m", "outside");
    expect_wp_error("0 46.5 8 1000 0 95 0\n1 46.5 8 1000\n", "line 1: pitch_deg", "outside");
    expect_wp_error("0 46.5 8 1000\n1 46.5 8 nan\n", "line 2: alt_m is NaN", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.5 8 1000 NAN 0 0\n", "line 2: heading_deg is NaN", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.5 inf 1000\n", "line 2: lon_deg is infinite", NULL);
    expect_wp_error("0 46.5 8 1000\n\n\n1 46.5 8 1000 5\n", "line 4: 5 numbers", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.5 8 1000 1 2 3 4\n", "line 2: more than 7", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.5 8x 1000\n", "line 2: lon_deg '8x' is not a number",
                    NULL);
    expect_wp_error("-1 46.5 8 1000\n1 46.5 8 1000\n", "line 1: t_s -1", NULL);
    expect_wp_error("# only one\n0 46.5 8 1000\n", "needs 2..1024 waypoints, has 1", NULL);
    expect_wp_error("", "has 0", NULL);
    expect_wp_error("0 46.5 8 1000\n1 46.6 8 1000\n", "line 2:", "at most 1000 m/s");
    expect_wp_error("0 46.5 8 1000 0 0 0\n0.1 46.5 8.00001 1000 0 0 170\n", "line 2:",
                    "roll rate");
    char longline[400];
    memset(longline, ' ', sizeof longline);
    memcpy(longline, "0 46.5 8 1000\n0", 15);
    longline[sizeof longline - 1u] = '\0';
    expect_wp_error(longline, "line 2: longer than 256", NULL);

    /* capacity: a comment line first, so line = waypoint + 1 */
    size_t cap = 64u * 1100u;
    char *big = malloc(cap);
    REQUIRE(big != NULL);
    size_t len = (size_t)snprintf(big, cap, "# many\n");
    for (uint32_t i = 0u; i < FLIGHT_WAYPOINTS_MAX + 1u; ++i) {
        len += (size_t)snprintf(big + len, cap - len, "%u 46.5 %.6f 1000\n", (unsigned)i,
                                8.0 + 0.0005 * i);
    }
    ft_error err = {0};
    CHECK(flight_path_parse_waypoints(&g_path, big, len, "big.wp", &err) == FT_ERR_BUDGET);
    CHECK(strstr(err.text, "big.wp line 1026: more than 1024 waypoints") != NULL);
    /* exactly the capacity is fine */
    char *last = strstr(big, "\n1024 ");
    REQUIRE(last != NULL);
    CHECK(flight_path_parse_waypoints(&g_path, big, (size_t)(last - big) + 1u, "big.wp", &err) ==
          FT_OK);
    CHECK(g_path.count == FLIGHT_WAYPOINTS_MAX);
    free(big);
}

/* ---- degenerate inputs: refused, never an empty or silently different log -- */

static void expect_run_error(const flightgen_options *o, const char *want)
{
    logbuf b;
    memset(&b, 0, sizeof b);
    flightgen_stats st;
    ft_error err = {0};
    ft_status s = flightgen_run(&g_path, o, mem_sink, &b, &st, &err);
    CHECK(s == FT_ERR_ARG);
    if (s == FT_OK || strstr(err.text, want) == NULL) {
        fprintf(stderr, "flightgen_run: want '%s', got '%s'\n", want, err.text);
        CHECK(0);
    }
    log_free(&b);
}

static void expect_builtin_error(flight_builtin_kind k, double duration_s, double speed_m_s,
                                 const char *want)
{
    flight_builtin_params bp;
    flight_builtin_defaults(&bp, k);
    bp.duration_s = duration_s;
    bp.speed_m_s = speed_m_s;
    ft_error err = {0};
    ft_status s = flight_path_builtin(&g_path, &bp, &err);
    CHECK(s != FT_OK);
    if (s == FT_OK || strstr(err.text, want) == NULL) {
        fprintf(stderr, "builtin: want '%s', got '%s'\n", want, err.text);
        CHECK(0);
    }
}

static void test_degenerate(void)
{
    /* times 0 and 1e-300: used to exit 0 with an empty log */
    expect_wp_error("0 46.5 8 1000\n1e-300 46.5 8 1000\n",
                    "bad.wp: the path lasts 1e-300 s (bad.wp line 1 to bad.wp line 2), shorter "
                    "than one log period of 0.0125 s",
                    NULL);
    /* 5 ms: attitude frames only, no position fix */
    expect_wp_error("0 46.5 8 1000\n0.005 46.5 8 1000\n", "lasts 0.005 s", "one log period");
    expect_wp_error("0 46.5 8 1000\nnan 46.5 8 1000\n", "line 2: t_s is NaN", NULL);
    expect_wp_error("0 46.5 8 1000\ninf 46.5 8 1000\n", "line 2: t_s is infinite", NULL);
    expect_wp_error("0 46.5 8 1000\n-inf 46.5 8 1000\n", "line 2: t_s is infinite", NULL);
    expect_wp_error("-1e-300 46.5 8 1000\n1 46.5 8 1000\n", "line 1: t_s", "outside");
    /* exactly one period: a log with one full set of frames (6 attitude,
     * 2 + 2 position halves, altitude, 3 velocity) */
    static const char one[] = "0 46.5 8 1000\n0.0125 46.5 8 1000\n";
    ft_error err = {0};
    REQUIRE(flight_path_parse_waypoints(&g_path, one, strlen(one), "one.wp", &err) == FT_OK);
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf b;
    flightgen_stats st;
    generate(&g_path, &o, &b, &st);
    CHECK(st.lines == 6u + 4u + 1u + 3u);
    CHECK(st.frames[FLIGHTGEN_LAT] == 2u && st.frames[FLIGHTGEN_ALT_RATE] == 1u);
    log_free(&b);

    /* --duration: at least one period; NaN = the whole path */
    builtin(FLIGHT_VALLEY, 20.0);
    static const double k_bad_dur[] = {1e-300, 0.001, 0.0124, 0.0, -1.0, INFINITY, -INFINITY,
                                       20.5};
    for (size_t i = 0; i < sizeof k_bad_dur / sizeof k_bad_dur[0]; ++i) {
        flightgen_options_default(&o);
        o.duration_s = k_bad_dur[i];
        expect_run_error(&o, "duration");
    }
    flightgen_options_default(&o);
    o.duration_s = 0.0125;
    generate(&g_path, &o, &b, &st);
    CHECK(st.lines == 14u);
    log_free(&b);

    /* fault times: finite and inside the logged path [0, 20) */
    flightgen_options_default(&o);
    o.nan_at_s = -1.0;
    expect_run_error(&o, "--nan-at -1 s is outside the logged path [0, 20) s");
    o.nan_at_s = 1e300;
    expect_run_error(&o, "--nan-at 1e+300 s is outside");
    o.nan_at_s = INFINITY;
    expect_run_error(&o, "--nan-at must be a finite time");
    o.nan_at_s = 19.999; /* inside, but no pitch frame after it */
    expect_run_error(&o, "--nan-at 19.999 s: no pitch frame at or after it");
    flightgen_options_default(&o);
    o.duplicate_at_s = 20.0;
    expect_run_error(&o, "--duplicate-at 20 s is outside");
    flightgen_options_default(&o);
    o.bad_dlc_at_s = -INFINITY;
    expect_run_error(&o, "--bad-dlc-at must be a finite time");
    flightgen_options_default(&o);
    o.velocity_stop_s = 25.0;
    expect_run_error(&o, "--velocity-stop 25 s is outside");
    flightgen_options_default(&o);
    o.gps_jump_at_s = -0.5;
    o.gps_jump_m = 5.0;
    expect_run_error(&o, "--gps-jump -0.5 s is outside");
    flightgen_options_default(&o);
    o.stall_from_s = -5.0;
    o.stall_to_s = -1.0;
    expect_run_error(&o, "--stall FROM -5 s is outside");
    o.stall_from_s = NAN;
    o.stall_to_s = 3.0;
    expect_run_error(&o, "--stall FROM,TO needs finite FROM < TO");
    /* a stall to past the end is a sender that dies: fine */
    flightgen_options_default(&o);
    o.stall_from_s = 15.0;
    o.stall_to_s = 1000.0;
    generate(&g_path, &o, &b, &st);
    CHECK(st.stalled > 0u);
    log_free(&b);

    /* built-in duration and speed */
    expect_builtin_error(FLIGHT_ORBIT, 1e-300, NAN, "duration 1e-300 s outside [0.0125, 36000]");
    expect_builtin_error(FLIGHT_VALLEY, 0.001, NAN, "duration 0.001 s outside");
    expect_builtin_error(FLIGHT_VALLEY, -5.0, NAN, "duration -5 s outside");
    expect_builtin_error(FLIGHT_VALLEY, INFINITY, NAN, "duration inf s outside");
    expect_builtin_error(FLIGHT_ORBIT, NAN, 0.0, "speed 0 m/s outside");
    expect_builtin_error(FLIGHT_ORBIT, NAN, -10.0, "speed -10 m/s outside");
    expect_builtin_error(FLIGHT_ORBIT, NAN, INFINITY, "speed inf m/s outside");
    expect_builtin_error(FLIGHT_ORBIT, NAN, 1e-300, "speed 1e-300 m/s outside");
}

/* ---- faults ----------------------------------------------------------------- */

static void expect_counts(const char *what, const decoded *d, uint64_t nonfinite, uint64_t dlc,
                          uint64_t repeat, uint64_t lost)
{
    int before = g_ft_test_failures;
    CHECK(d->parse_failures == 0u);
    CHECK(d->dec.rejects[FT_CAN_REJECT_NONFINITE] == nonfinite);
    CHECK(d->dec.rejects[FT_CAN_REJECT_DLC] == dlc);
    CHECK(d->dec.rejects[FT_CAN_REJECT_COUNTER_REPEAT] == repeat);
    CHECK(total_rejects(d) == nonfinite + dlc + repeat);
    CHECK(d->dec.lost == lost);
    if (g_ft_test_failures != before) {
        fprintf(stderr, "  (%s: nonfinite %llu dlc %llu repeat %llu lost %llu)\n", what,
                (unsigned long long)d->dec.rejects[FT_CAN_REJECT_NONFINITE],
                (unsigned long long)d->dec.rejects[FT_CAN_REJECT_DLC],
                (unsigned long long)d->dec.rejects[FT_CAN_REJECT_COUNTER_REPEAT],
                (unsigned long long)d->dec.lost);
    }
}

/* Expected losses for --drop-every n over a attitude frames (3 per period,
 * in time order): a drop is seen as a loss once a later frame of its id is
 * written. */
static uint64_t drop_losses(uint64_t a, uint32_t n)
{
    uint64_t lost = 0u;
    for (uint64_t j = 1u; j <= a; ++j) {
        if (j % n != 0u) {
            continue;
        }
        for (uint64_t later = j + 3u; later <= a; later += 3u) {
            if (later % n != 0u) {
                ++lost;
                break;
            }
        }
    }
    return lost;
}

static void test_faults(void)
{
    builtin(FLIGHT_TURN360, NAN);
    flightgen_options o;
    logbuf clean, b;
    flightgen_stats st0, st;
    decoded d;
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    generate(&g_path, &o, &clean, &st0);
    CHECK(st0.lines == 10u * 560u);

    /* drop every 7th attitude frame: 2400 attitude frames, 342 dropped */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.drop_every = 7u;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(st.dropped == 2400u / 7u);
    CHECK(st.lines == st0.lines - st.dropped);
    expect_counts("drop-every 7", &d, 0u, 0u, 0u, drop_losses(2400u, 7u));
    CHECK(d.dec.lost == 342u);
    CHECK(d.per_qty[FT_QTY_PITCH] + d.per_qty[FT_QTY_ROLL] + d.per_qty[FT_QTY_HEADING] ==
          2400u - 342u);
    CHECK(d.per_qty[FT_QTY_ROLL_RATE] == 800u);
    decoded_free(&d);
    log_free(&b);
    /* every 3rd: always the heading, the last one of the log not seen as lost */
    o.drop_every = 3u;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(d.per_qty[FT_QTY_HEADING] == 0u && d.per_qty[FT_QTY_PITCH] == 800u);
    expect_counts("drop-every 3", &d, 0u, 0u, 0u, 0u); /* no heading ever arrives */
    decoded_free(&d);
    log_free(&b);

    /* NaN pitch at 3 s: exactly one NONFINITE reject, at 3.000000 */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.nan_at_s = 3.0;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(st.nan_injected == 1u && st.lines == st0.lines);
    expect_counts("nan-at", &d, 1u, 0u, 0u, 0u);
    CHECK(d.rejected_id == 311u && d.rejected_line_t_ns == (o.start_us + 3000000u) * 1000u);
    /* period 240: message code 0xF0, quiet NaN 0x7FC00000 */
    CHECK(strstr(b.text, "(1700000003.000000) vcan0 137#010200F07FC00000\n") != NULL);
    decoded_free(&d);
    log_free(&b);

    /* bad DLC at 4.0123 s: the first FLOAT frame at or after it, the pitch
     * of period 321 (4.0125 s, code 0x41), has DLC 7; the decoder drops it
     * before it reads the counter, so that id also shows one lost message */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.bad_dlc_at_s = 4.0123;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(st.bad_dlc_injected == 1u && st.lines == st0.lines);
    expect_counts("bad-dlc-at", &d, 0u, 1u, 0u, 1u);
    CHECK(d.rejected_id == 311u && d.rejected_line_t_ns == (o.start_us + 4012500u) * 1000u);
    CHECK(strstr(b.text, "(1700000004.012500) vcan0 137#01020041") != NULL);
    {
        const char *l = strstr(b.text, "(1700000004.012500) vcan0 137#");
        REQUIRE(l != NULL);
        const char *eol = strchr(l, '\n');
        CHECK(eol - strchr(l, '#') - 1 == 14); /* 7 bytes */
    }
    decoded_free(&d);
    log_free(&b);

    /* duplicate at 5.0006 s: the first FLOAT frame at or after it is the
     * roll rate at 5.00075 s, sent again 125 us later */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.duplicate_at_s = 5.0006;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(st.duplicates_injected == 1u && st.lines == st0.lines + 1u);
    expect_counts("duplicate-at", &d, 0u, 0u, 1u, 0u);
    CHECK(d.rejected_id == 304u && d.rejected_line_t_ns == (o.start_us + 5000875u) * 1000u);
    decoded_free(&d);
    log_free(&b);

    /* stall 2 .. 3.5 s: nothing in between, no loss (the sender was silent),
     * attitude stale when it resumes */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.stall_from_s = 2.0;
    o.stall_to_s = 3.5;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    CHECK(st.stalled == 120u * 6u + 15u * 8u);
    CHECK(st.lines + st.stalled == st0.lines);
    expect_counts("stall", &d, 0u, 0u, 0u, 0u);
    uint64_t t_from = (o.start_us + 2000000u) * 1000u, t_to = (o.start_us + 3500000u) * 1000u;
    uint64_t before = 0u, after = UINT64_MAX, inside = 0u;
    ft_pose_state ps;
    ft_error err = {0};
    REQUIRE(ft_pose_state_init(&ps, 100u, &err) == FT_OK);
    uint32_t stale_at_resume = 0u;
    for (size_t i = 0u; i < d.nvals; ++i) {
        uint64_t t = d.vals[i].t_ns;
        if (t < t_from) {
            before = t;
        } else if (t < t_to) {
            ++inside;
        } else if (after == UINT64_MAX) {
            after = t;
            stale_at_resume = ft_pose_state_stale(&ps, t, NULL, 0u);
        }
        ft_pose_input in = {d.vals[i].qty, d.vals[i].v, t, 100u, 0u, 0u};
        REQUIRE(ft_pose_state_apply(&ps, &in, NULL, &err) == FT_OK);
    }
    CHECK(inside == 0u);
    CHECK(after == t_to);                          /* resumes on the period at 3.5 s */
    CHECK(before == t_from - (12500u - 1250u) * 1000u); /* yaw rate of the 1.9875 s period */
    CHECK((stale_at_resume & FT_QTY_ATTITUDE_MASK) == FT_QTY_ATTITUDE_MASK);
    decoded_free(&d);
    log_free(&b);

    /* all at once: each fault still counted exactly once */
    flightgen_options_default(&o);
    o.duration_s = 10.0;
    o.drop_every = 11u;
    o.nan_at_s = 1.0;
    o.bad_dlc_at_s = 2.0;
    o.duplicate_at_s = 3.0;
    o.stall_from_s = 6.0;
    o.stall_to_s = 7.0;
    generate(&g_path, &o, &b, &st);
    decode(&b, &d);
    uint64_t att = 3u * (800u - 80u); /* 80 periods stalled */
    REQUIRE(att % 11u >= 3u);         /* no drop among the last frames of an id */
    CHECK(st.dropped == att / 11u);
    CHECK(st.nan_injected == 1u && st.bad_dlc_injected == 1u && st.duplicates_injected == 1u);
    expect_counts("all faults", &d, 1u, 1u, 1u, att / 11u + 1u);
    decoded_free(&d);
    log_free(&b);

    /* bad option values */
    flightgen_options_default(&o);
    o.stall_from_s = 5.0;
    o.stall_to_s = 4.0;
    CHECK(flightgen_run(&g_path, &o, mem_sink, &b, &st, &err) == FT_ERR_ARG);
    flightgen_options_default(&o);
    o.duration_s = 1000.0;
    CHECK(flightgen_run(&g_path, &o, mem_sink, &b, &st, &err) == FT_ERR_ARG);
    flightgen_options_default(&o);
    o.iface[0] = '\0';
    CHECK(flightgen_run(&g_path, &o, mem_sink, &b, &st, &err) == FT_ERR_ARG);
    log_free(&b);
    log_free(&clean);
}

/* ---- determinism and options ------------------------------------------------- */

static void test_determinism(void)
{
    builtin(FLIGHT_TURN360, NAN);
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf a, b;
    flightgen_stats sa, sb;
    generate(&g_path, &o, &a, &sa);
    builtin(FLIGHT_TURN360, NAN); /* path rebuilt from scratch */
    generate(&g_path, &o, &b, &sb);
    CHECK(a.len == b.len && memcmp(a.text, b.text, a.len) == 0);
    log_free(&b);

    /* another start time and interface: the same lines but for those fields */
    o.start_us = UINT64_C(1700000100500000);
    memcpy(o.iface, "can1", 5);
    generate(&g_path, &o, &b, &sb);
    CHECK(sa.lines == sb.lines);
    size_t ia = 0u, ib = 0u;
    uint64_t mismatches = 0u;
    for (uint64_t n = 0u; n < sa.lines; ++n) {
        ft_candump_record ra, rb;
        size_t ea = ia, eb = ib;
        while (a.text[ea] != '\n') {
            ++ea;
        }
        while (b.text[eb] != '\n') {
            ++eb;
        }
        if (ft_candump_parse_line(a.text + ia, ea - ia, &ra, NULL) != FT_OK ||
            ft_candump_parse_line(b.text + ib, eb - ib, &rb, NULL) != FT_OK ||
            rb.frame.t_ns != ra.frame.t_ns + UINT64_C(100500000000) ||
            strcmp(rb.iface, "can1") != 0 ||
            memcmp(ra.frame.data, rb.frame.data, sizeof ra.frame.data) != 0 ||
            ra.frame.can_id != rb.frame.can_id) {
            ++mismatches;
        }
        ia = ea + 1u;
        ib = eb + 1u;
    }
    CHECK(mismatches == 0u);
    CHECK(strncmp(b.text, "(1700000100.500000) can1 137#", 29) == 0);
    log_free(&a);
    log_free(&b);
}

/* The log goes through a file as the tool writes it, and is read back. */
static void test_file_round_trip(void)
{
    builtin(FLIGHT_VALLEY, 5.0);
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf a;
    flightgen_stats st;
    generate(&g_path, &o, &a, &st);
    char path[512];
    (void)snprintf(path, sizeof path, "%s/flightgen_valley.log", FT_TEST_OUT_DIR);
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    CHECK(fwrite(a.text, 1u, a.len, f) == a.len);
    CHECK(fclose(f) == 0);
    f = fopen(path, "rb");
    REQUIRE(f != NULL);
    char line[FT_CANDUMP_LINE_MAX + 2u];
    uint64_t n = 0u, bad = 0u;
    while (fgets(line, sizeof line, f) != NULL && n < st.lines + 1u) {
        ft_candump_record r;
        if (ft_candump_parse_line(line, strlen(line), &r, NULL) != FT_OK) {
            ++bad;
        }
        ++n;
    }
    fclose(f);
    CHECK(n == st.lines && bad == 0u);
    log_free(&a);
}

/* ---- the drawn position against the flown truth ---------------------------- */

/* What `fixterrain replay` does with a log, without the GL: every frame of
 * the log up to the display time into the decoder and the pose feed, one
 * view per frame period (60 Hz), until the log is done. */
typedef struct drawn {
    uint64_t t_ns;
    double lat, lon, alt;
    int pos_pred, ann;
    char reason[FT_POSE_REASON_MAX];
} drawn;

typedef struct replayed {
    drawn *f;
    size_t n;
    uint64_t snaps, vel_rejects;
    double offset_max_m;
} replayed;

static ft_pose_feed g_feed;

#define FRAME_PERIOD_NS UINT64_C(16667000) /* frame.period_ms 16.667, as replay rounds it */

static void replay_log_tau(const logbuf *b, int velocity_required, uint32_t converge_ms,
                           replayed *out)
{
    memset(out, 0, sizeof *out);
    ft_can_map m;
    ft_canaero_default_map(&m);
    const ft_pose fallback = {46.5, 8.0, 1000.0, 0.0, 0.0, 0.0};
    ft_error err = {0};
    REQUIRE(ft_pose_feed_init(&g_feed, &m, FT_POSE_HORIZON_DEFAULT_MS, &fallback, &err) == FT_OK);
    REQUIRE(ft_pose_feed_set_position(&g_feed, converge_ms, FT_POSE_SNAP_DEFAULT_M,
                                      velocity_required, &err) == FT_OK);
    ft_candump_record *recs = malloc((b->lines + 1u) * sizeof *recs);
    REQUIRE(recs != NULL);
    size_t nrec = 0u, i = 0u;
    while (i < b->len) {
        size_t start = i;
        while (i < b->len && b->text[i] != '\n') {
            ++i;
        }
        REQUIRE(ft_candump_parse_line(b->text + start, i - start, &recs[nrec], &err) == FT_OK);
        ++nrec;
        ++i;
    }
    REQUIRE(nrec > 0u);
    const uint64_t t_last = recs[nrec - 1u].frame.t_ns;
    size_t frames_max = (size_t)((t_last - recs[0].frame.t_ns) / FRAME_PERIOD_NS) + 2u;
    out->f = malloc(frames_max * sizeof *out->f);
    REQUIRE(out->f != NULL);
    size_t next = 0u;
    for (uint64_t t = recs[0].frame.t_ns; out->n < frames_max; t += FRAME_PERIOD_NS) {
        while (next < nrec && recs[next].frame.t_ns <= t) {
            ft_pose_feed_frame(&g_feed, &recs[next].frame);
            ++next;
        }
        ft_pose_view v;
        ft_pose_feed_view(&g_feed, t, &v);
        drawn *d = &out->f[out->n++];
        d->t_ns = t;
        d->lat = v.pose.lat_deg;
        d->lon = v.pose.lon_deg;
        d->alt = v.pose.alt_m;
        d->pos_pred = v.pos_predicted;
        d->ann = v.annunciate;
        memcpy(d->reason, v.reason, sizeof d->reason);
        if (next == nrec && t >= t_last) {
            break;
        }
    }
    out->snaps = g_feed.ps.snap_count;
    out->offset_max_m = g_feed.ps.offset_max_m;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        if ((FT_QTY_VELOCITY_MASK & FT_QTY_BIT(q)) != 0u) {
            out->vel_rejects += g_feed.dec.rejects_by_qty[q];
        }
    }
    free(recs);
}

static void replay_log(const logbuf *b, int velocity_required, replayed *out)
{
    replay_log_tau(b, velocity_required, FT_POSE_CONVERGE_DEFAULT_MS, out);
}

static void replayed_free(replayed *r)
{
    free(r->f);
    memset(r, 0, sizeof *r);
}

/* North, east, up metres from a to b (WGS-84 radii at a). */
static void delta_ned(double lat_a, double lon_a, double alt_a, double lat_b, double lon_b,
                      double alt_b, double d[3])
{
    double m = 0.0, n = 0.0;
    ft_wgs84_radii_m(lat_a, &m, &n);
    d[0] = (lat_b - lat_a) * DEG * (m + alt_a);
    d[1] = ft_wrap_deg_pm180(lon_b - lon_a) * DEG * (n + alt_a) * cos(lat_a * DEG);
    d[2] = alt_b - alt_a;
}

typedef struct accuracy {
    double err_max_m;      /* |drawn - truth| over the checked frames */
    double step_ratio_max; /* frame-to-frame step / (speed x frame period) */
    double step_max_m;
    size_t checked, big_steps; /* frames compared; steps over 1.5 x speed x period */
} accuracy;

/* Compares every frame from 0.2 s of path time (the first fix and velocity
 * are in by then) to the end of the path with the truth at its time, the
 * truth moved jump_m north from the first jumped fix on (jump_m 0: none). */
static void measure(const flight_path *p, const flightgen_options *o, const replayed *r,
                    double jump_m, accuracy *a)
{
    memset(a, 0, sizeof *a);
    const double dur_s = isnan(o->duration_s) ? flight_path_duration_s(p) : o->duration_s;
    double t_jump_s = INFINITY;
    if (jump_m != 0.0) {
        /* the first latitude at or after the jump time (6.25 ms into every
         * 100 ms), used once its DOUBLEL is in (+0.25 ms) */
        double k = ceil((o->gps_jump_at_s - 0.00625) / 0.1 - 1e-9);
        t_jump_s = k * 0.1 + 0.00625 + 0.00025;
    }
    for (size_t i = 1u; i < r->n; ++i) {
        const double t = path_time(p, o, r->f[i].t_ns), t_prev = path_time(p, o, r->f[i - 1u].t_ns);
        if (t < 0.2 || t > dur_s) {
            continue;
        }
        flight_sample s;
        flight_path_sample(p, t, &s);
        double d[3];
        delta_ned(s.lat_deg, s.lon_deg, s.alt_m, r->f[i].lat, r->f[i].lon, r->f[i].alt, d);
        if (t >= t_jump_s) {
            d[0] -= jump_m;
        }
        a->err_max_m = fmax(a->err_max_m, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        delta_ned(r->f[i - 1u].lat, r->f[i - 1u].lon, r->f[i - 1u].alt, r->f[i].lat, r->f[i].lon,
                  r->f[i].alt, d);
        const double step = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double speed = sqrt(s.v_n_m_s * s.v_n_m_s + s.v_e_m_s * s.v_e_m_s +
                                  s.v_u_m_s * s.v_u_m_s);
        const double ratio = step / (speed * (t - t_prev));
        a->step_ratio_max = fmax(a->step_ratio_max, ratio);
        a->step_max_m = fmax(a->step_max_m, step);
        a->big_steps += ratio > 1.5;
        ++a->checked;
    }
}

static void flight_for(flight_builtin_kind kind, double speed_m_s)
{
    flight_builtin_params bp;
    flight_builtin_defaults(&bp, kind);
    bp.speed_m_s = speed_m_s;
    if (kind == FLIGHT_ORBIT) {
        /* one revolution, banked 36 deg at 120 m/s (2 km) and 58 deg at 250
         * m/s (4 km): the built-in paths stay within 60 deg */
        bp.radius_m = speed_m_s > 200.0 ? 4000.0 : 2000.0;
    } else {
        /* 50 m -> 10000 m at 24 deg (120 m/s) and 23 deg (250 m/s) */
        bp.duration_s = speed_m_s > 200.0 ? 100.0 : 200.0;
    }
    ft_error err = {0};
    ft_status s = flight_path_builtin(&g_path, &bp, &err);
    if (s != FT_OK) {
        fprintf(stderr, "%s: %s\n", flight_builtin_name(kind), err.text);
    }
    REQUIRE(s == FT_OK);
}

/* The acceptance test: orbit and climb at 120 and 250 m/s, position
 * at 10 Hz, velocity with it; on every 60 Hz frame the drawn position is
 * within 1 m of the flown truth and no frame-to-frame step exceeds 1.5 x
 * speed x period. The same logs without the velocity frames show today's
 * hold-and-jump for comparison. */
static void test_position_accuracy(void)
{
    static const flight_builtin_kind kinds[2] = {FLIGHT_ORBIT, FLIGHT_CLIMB};
    static const double speeds[2] = {120.0, 250.0};
    for (int ki = 0; ki < 2; ++ki) {
        for (int si = 0; si < 2; ++si) {
            flight_for(kinds[ki], speeds[si]);
            flightgen_options o;
            flightgen_options_default(&o);
            logbuf b;
            flightgen_stats st;
            replayed r;
            accuracy with, without;
            generate(&g_path, &o, &b, &st);
            replay_log(&b, 1, &r);
            measure(&g_path, &o, &r, 0.0, &with);
            size_t unpredicted = 0u, annunciated = 0u;
            for (size_t i = 0u; i < r.n; ++i) {
                const double t = path_time(&g_path, &o, r.f[i].t_ns);
                if (t >= 0.2 && t <= flight_path_duration_s(&g_path)) {
                    unpredicted += r.f[i].pos_pred != 3;
                    annunciated += r.f[i].ann != 0;
                }
            }
            const uint64_t snaps = r.snaps;
            const double offset_max = r.offset_max_m;
            replayed_free(&r);
            log_free(&b);
            o.velocity = 0;
            generate(&g_path, &o, &b, &st);
            replay_log(&b, 0, &r);
            measure(&g_path, &o, &r, 0.0, &without);
            replayed_free(&r);
            log_free(&b);
            printf("%s %3.0f m/s, %zu frames at 60 Hz: drawn position error max %.3f m (without "
                   "velocity %.2f m), largest step %.3f m = %.3f x speed x period (without "
                   "%.2f m = %.2f x), %zu steps over 1.5 x (without %zu), largest offset "
                   "converged %.3f m, %llu snaps\n",
                   flight_builtin_name(kinds[ki]), speeds[si], with.checked, with.err_max_m,
                   without.err_max_m, with.step_max_m, with.step_ratio_max, without.step_max_m,
                   without.step_ratio_max, with.big_steps, without.big_steps, offset_max,
                   (unsigned long long)snaps);
            CHECK(with.checked > 5000u);
            CHECK(with.err_max_m <= 1.0);
            CHECK(with.step_ratio_max <= 1.5 && with.big_steps == 0u);
            CHECK(unpredicted == 0u && annunciated == 0u && snaps == 0u);
            /* today's behaviour, for the record: it fails both */
            CHECK(without.err_max_m > 1.0 && without.big_steps > 0u);
        }
    }
    /* In a turn every fix is off the constant-velocity prediction by about
     * 1/2 a dt^2, always towards the centre; the convergence carries that
     * bias, so the drawn error grows with converge_ms. For the record: */
    flight_for(FLIGHT_ORBIT, 250.0);
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf b;
    flightgen_stats st;
    generate(&g_path, &o, &b, &st);
    static const uint32_t taus[4] = {0u, 100u, 300u, 1000u};
    printf("orbit 250 m/s, 58 deg bank, by converge_ms:");
    for (int k = 0; k < 4; ++k) {
        replayed r;
        accuracy a;
        replay_log_tau(&b, 0, taus[k], &r);
        measure(&g_path, &o, &r, 0.0, &a);
        printf(" %u ms: %.3f m, step %.3f x%s", taus[k], a.err_max_m, a.step_ratio_max,
               k == 3 ? "\n" : ";");
        replayed_free(&r);
    }
    log_free(&b);
}

/* Faults through flightgen, the decoder and the feed: a 500 m GPS reset is
 * snapped to and counted once; a 5 m one is converged without a step; a
 * velocity output that stops mid-flight stops the prediction at its
 * timeout, annunciated only when the velocity is required. */
static void test_position_faults(void)
{
    flight_for(FLIGHT_ORBIT, 250.0);
    flightgen_options o;
    logbuf b;
    flightgen_stats st;
    replayed r;
    accuracy a;

    /* 500 m north at 30 s */
    flightgen_options_default(&o);
    o.duration_s = 40.0;
    o.gps_jump_at_s = 30.0;
    o.gps_jump_m = 500.0;
    generate(&g_path, &o, &b, &st);
    CHECK(st.gps_jumped == 100u);
    replay_log(&b, 0, &r);
    measure(&g_path, &o, &r, 500.0, &a);
    printf("GPS reset 500 m: %llu snaps, error against truth (+500 m after the reset) max %.3f m, "
           "%zu steps over 1.5 x speed x period (largest %.1f m)\n",
           (unsigned long long)r.snaps, a.err_max_m, a.big_steps, a.step_max_m);
    CHECK(r.snaps == 1u);
    CHECK(a.err_max_m <= 1.0);
    CHECK(a.big_steps == 1u && a.step_max_m > 490.0 && a.step_max_m < 510.0);
    replayed_free(&r);
    log_free(&b);

    /* 5 m north at 30 s: no step, converged (within 1 m of truth + 5 m) after
     * 5 time constants */
    o.gps_jump_m = 5.0;
    generate(&g_path, &o, &b, &st);
    replay_log(&b, 0, &r);
    measure(&g_path, &o, &r, 0.0, &a); /* against the truth itself: off by at most 5 m */
    double err_after = 0.0;
    const double tau_s = FT_POSE_CONVERGE_DEFAULT_MS * 1e-3;
    for (size_t i = 0u; i < r.n; ++i) {
        const double t = path_time(&g_path, &o, r.f[i].t_ns);
        if (t >= 30.1 + 5.0 * tau_s && t <= 40.0) {
            flight_sample s;
            flight_path_sample(&g_path, t, &s);
            double d[3];
            delta_ned(s.lat_deg, s.lon_deg, s.alt_m, r.f[i].lat, r.f[i].lon, r.f[i].alt, d);
            d[0] -= 5.0;
            err_after = fmax(err_after, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
    }
    printf("GPS jump 5 m: %llu snaps, largest offset converged %.3f m, largest step %.3f x speed "
           "x period, error against truth max %.3f m, against truth + 5 m after 5 tau %.3f m\n",
           (unsigned long long)r.snaps, r.offset_max_m, a.step_ratio_max, a.err_max_m, err_after);
    CHECK(r.snaps == 0u);
    CHECK(r.offset_max_m > 4.5 && r.offset_max_m < 5.5);
    CHECK(a.big_steps == 0u && a.step_ratio_max <= 1.5);
    CHECK(a.err_max_m <= 5.0 + 1.0);
    CHECK(err_after <= 1.0);
    replayed_free(&r);
    log_free(&b);

    /* the velocity stops at 20 s (last at 19.90875 s, stale after 20.40875) */
    flight_for(FLIGHT_ORBIT, 120.0);
    flightgen_options_default(&o);
    o.duration_s = 25.0;
    o.velocity_stop_s = 20.0;
    generate(&g_path, &o, &b, &st);
    CHECK(st.velocity_stopped == 3u * 50u);
    const double stop_s = 19.9 + 0.008 + 0.5; /* the altitude rate, the last of the three */
    for (int required = 0; required < 2; ++required) {
        replay_log(&b, required, &r);
        size_t first_unpred = SIZE_MAX, ann = 0u, after = 0u, pred_after = 0u;
        double held_err_max = 0.0;
        for (size_t i = 0u; i < r.n; ++i) {
            const double t = path_time(&g_path, &o, r.f[i].t_ns);
            if (t < 0.2 || t > 25.0) {
                continue;
            }
            if (r.f[i].pos_pred != 3 && first_unpred == SIZE_MAX) {
                first_unpred = i;
            }
            if (t > stop_s) {
                ++after;
                pred_after += r.f[i].pos_pred != 0;
                ann += r.f[i].ann != 0;
                if (required) {
                    CHECK(strstr(r.f[i].reason, "no ground speed for") != NULL);
                }
                flight_sample s;
                flight_path_sample(&g_path, t, &s);
                double d[3];
                delta_ned(s.lat_deg, s.lon_deg, s.alt_m, r.f[i].lat, r.f[i].lon, r.f[i].alt, d);
                held_err_max = fmax(held_err_max, hypot(d[0], d[1]));
            } else {
                CHECK(r.f[i].ann == 0);
            }
        }
        REQUIRE(first_unpred != SIZE_MAX);
        const double t_first = path_time(&g_path, &o, r.f[first_unpred].t_ns);
        printf("velocity stops at 20 s (required %d): prediction stops on the frame at %.4f s "
               "(stale after %.5f s), %zu of %zu later frames predicted, %zu annunciated, "
               "held position error up to %.2f m\n",
               required, t_first, stop_s, pred_after, after, ann, held_err_max);
        /* the first frame past the timeout, not one later */
        CHECK(t_first > stop_s && t_first - FRAME_PERIOD_NS * 1e-9 <= stop_s);
        CHECK(pred_after == 0u);
        CHECK(ann == (required ? after : 0u));
        CHECK(held_err_max > 1.0); /* held between fixes again, as without velocity */
        replayed_free(&r);
    }
    log_free(&b);
}

static void test_speed(void)
{
    /* not a pass/fail check: lines per second of generation, for the record */
    builtin(FLIGHT_ORBIT, NAN);
    flightgen_options o;
    flightgen_options_default(&o);
    logbuf a;
    flightgen_stats st;
    clock_t c0 = clock();
    generate(&g_path, &o, &a, &st);
    double cpu_s = (double)(clock() - c0) / CLOCKS_PER_SEC;
    printf("generation: %llu lines (%.1f s of flight) in %.3f s CPU = %.2f M lines/s, %.0fx "
           "real time, %zu bytes\n",
           (unsigned long long)st.lines, flight_path_duration_s(&g_path), cpu_s,
           cpu_s > 0.0 ? (double)st.lines / cpu_s * 1e-6 : 0.0,
           cpu_s > 0.0 ? flight_path_duration_s(&g_path) / cpu_s : 0.0, a.len);
    log_free(&a);
}

int main(void)
{
    test_encoder_line();
    test_orbit();
    test_other_builtins();
    test_waypoints();
    test_waypoint_errors();
    test_degenerate();
    test_faults();
    test_position_accuracy();
    test_position_faults();
    test_determinism();
    test_file_round_trip();
    test_speed();
    return ft_test_result("test_flightgen");
}
