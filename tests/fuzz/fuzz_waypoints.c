/* fuzz_waypoints.c - libFuzzer harness: the waypoint file parser of
 * fixterrain-flightgen --waypoints (tools/flight_path.c:
 * flight_path_parse_waypoints, which also finishes the path: derived
 * attitudes, quaternions, segment rates, whole-path checks).
 *
 * The input is the file's text. For an accepted path the harness samples it
 * (start, middle, end: every value finite) and writes the first 0.1 s of
 * its log through flightgen_run, checking that each line it emits parses
 * back (src/input/candump.c) to the record it was made from. The path lives in a
 * static (it is large) that the parser clears per input. */
#include <math.h>
#include <string.h>

#include "input/candump.h"
#include "flight_path.h"
#include "fuzz_util.h"

#define FUZZ_LOG_S 0.1

static flight_path g_path;

static void check_sample(const flight_sample *s)
{
    FUZZ_CHECK(isfinite(s->lat_deg) && isfinite(s->lon_deg) && isfinite(s->alt_m));
    FUZZ_CHECK(isfinite(s->heading_deg) && isfinite(s->pitch_deg) && isfinite(s->roll_deg));
    FUZZ_CHECK(isfinite(s->p_deg_s) && isfinite(s->q_deg_s) && isfinite(s->r_deg_s));
    FUZZ_CHECK(isfinite(s->v_n_m_s) && isfinite(s->v_e_m_s) && isfinite(s->v_u_m_s));
}

static ft_status sink(void *ctx, const ft_candump_record *rec, const char *line, size_t len,
                      ft_error *err)
{
    uint64_t *lines = (uint64_t *)ctx;
    ft_candump_record back;
    FUZZ_CHECK(ft_candump_parse_line(line, len, &back, err) == FT_OK);
    FUZZ_CHECK(back.frame.can_id == rec->frame.can_id && back.frame.dlc == rec->frame.dlc);
    FUZZ_CHECK(memcmp(back.frame.data, rec->frame.data, 8u) == 0);
    FUZZ_CHECK(back.frame.t_ns == rec->frame.t_ns);
    ++*lines;
    return FT_OK;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ft_error err;
    memset(&err, 0, sizeof err);
    ft_status st = flight_path_parse_waypoints(&g_path, (const char *)data, size, "fuzz.wpt",
                                               &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st != FT_OK) {
        FUZZ_CHECK(err.text[0] != '\0');
        return 0;
    }
    FUZZ_CHECK(g_path.finished && g_path.count >= 2u && g_path.count <= FLIGHT_WAYPOINTS_MAX);
    double t0 = flight_path_t0_s(&g_path), dur = flight_path_duration_s(&g_path);
    FUZZ_CHECK(isfinite(t0) && isfinite(dur) && dur >= FLIGHT_DURATION_MIN_S);
    flight_sample s;
    flight_path_sample(&g_path, t0, &s);
    check_sample(&s);
    flight_path_sample(&g_path, t0 + 0.5 * dur, &s);
    check_sample(&s);
    flight_path_sample(&g_path, t0 + dur, &s);
    check_sample(&s);

    flightgen_options o;
    flightgen_options_default(&o);
    o.duration_s = dur < FUZZ_LOG_S ? dur : FUZZ_LOG_S;
    uint64_t lines = 0u;
    flightgen_stats fs;
    st = flightgen_run(&g_path, &o, sink, &lines, &fs, &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st == FT_OK) {
        FUZZ_CHECK(fs.lines == lines);
    }
    return 0;
}
