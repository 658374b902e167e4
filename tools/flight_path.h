/* flight_path.h - a flight path (waypoint file or built-in manoeuvre) and
 * the CANaerospace candump log it produces (fixterrain-flightgen).
 * Used by tools/flightgen.c and by the tests, which decode the log back.
 *
 * ---- path model ------------------------------------------------------------
 * A path is a list of waypoints (t_s, lat, lon, alt, heading, pitch, roll),
 * strictly increasing in time. Between two waypoints:
 *   - position is linear in lat, lon (the shorter way round the
 *     antimeridian) and alt;
 *   - attitude is the quaternion slerp q(t) = q_i * exp(0.5 * w_i * (t - t_i))
 *     with w_i the constant body rate that turns q_i into q_i+1 over the
 *     segment (shortest way). That is exactly the motion the renderer's
 *     extrapolator (ft_quat_integrate_body_rate) assumes, so the body rates
 *     sent are w_i and a prediction inside a segment is exact; across a
 *     waypoint the error is |w_i+1 - w_i| times the part of the step that
 *     falls in the next segment.
 * Attitude convention: pose_state.h (body -> NED, Z-Y'-X'').
 *
 * A waypoint without attitude (4 numbers on its line) gets one when the
 * path is finished, from the positions around it (zero angle of attack,
 * coordinated flight):
 *   - velocity = central difference of the neighbouring waypoints' positions
 *     (one-sided at the ends) in local metres;
 *   - heading = direction of the horizontal velocity, pitch = flight-path
 *     angle atan2(climb, horizontal speed); below 0.5 m/s horizontal speed
 *     the heading of the previous waypoint is kept (0 at the start);
 *   - roll = atan(V * turn_rate / g), turn_rate = change of the segment
 *     headings before and after the waypoint divided by the time between
 *     the segment midpoints, clamped to +-FLIGHT_DERIVED_ROLL_MAX_DEG;
 *     0 at both ends.
 *
 * Checks on every path: at least 2 waypoints, at most FLIGHT_WAYPOINTS_MAX,
 * time strictly increasing, values finite and in range (those of the
 * CANaerospace default map), ground speed of a segment at most
 * FLIGHT_SPEED_MAX_M_S (a typo in a coordinate jumps kilometres), body rates
 * at most FLIGHT_RATE_MAX_DEG_S per axis (the decoder's range), duration at
 * least FLIGHT_DURATION_MIN_S (one log period: a shorter path would give an
 * empty or position-less log) and at most FLIGHT_DURATION_MAX_S. Errors name
 * the waypoint file line.
 *
 * Built-in paths (position in a local tangent plane at the centre, sphere of
 * radius FLIGHT_EARTH_RADIUS_M; attitude from the velocity as above but
 * analytic; sampled into waypoints every FLIGHT_BUILTIN_STEP_S or wider
 * when the duration needs more than FLIGHT_WAYPOINTS_MAX):
 *   orbit    clockwise circle of radius R around the centre at constant
 *            altitude, banked atan(V^2 / (g R)); default one revolution
 *   climb    straight climb on heading 090 from 50 m to 10000 m at a
 *            constant flight-path angle (--alt does not apply)
 *   dive     level, push over to -30 deg, hold, pull out, level (heading 000)
 *   turn360  straight, roll in, a full 360 deg turn, roll out, straight, at
 *            low altitude; bank from the turn rate
 *   valley   straight and level low-level line on heading 045
 *
 * ---- log -------------------------------------------------------------------
 * Every 12.5 ms (80 Hz) "period" k at path time t0 + k * 12.5 ms:
 *   +0     us  311 pitch     FLOAT deg
 *   +250   us  312 roll      FLOAT deg
 *   +500   us  321 heading   FLOAT deg [0, 360)
 *   +750   us  304 roll rate FLOAT deg/s (p)
 *   +1000  us  303 pitch rate FLOAT deg/s (q)
 *   +1250  us  305 yaw rate  FLOAT deg/s (r)
 * and every 8th period (10 Hz):
 *   +6250  us 1036 latitude  DOUBLEH, +6500 us DOUBLEL (consecutive codes)
 *   +6750  us 1037 longitude DOUBLEH, +7000 us DOUBLEL
 *   +7250  us  320 altitude  FLOAT m
 *   +7500  us 1039 GPS ground speed FLOAT m/s   (unless --no-velocity)
 *   +7750  us 1040 GPS true track   FLOAT deg [0, 360)
 *   +8000  us  314 altitude rate    FLOAT m/s, up positive
 * The ids are canaero.h's defaults (ft_canaero_default_map, the primary
 * source of each quantity), not a copy. 250 us is about one 8-byte frame at
 * 500 kbit/s, so the schedule is one a bus could carry; 80 * 6 + 10 * 8 =
 * 560 frames per second of flight (530 without velocity). Each frame
 * carries the path's value at its own timestamp (a double at its
 * DOUBLEH's), and timestamps are whole microseconds, so what the log says
 * is exactly what was sampled. The velocity is what a GPS receiver reports
 * for the path's latitude/longitude/altitude track: its time derivative in
 * north/east/up metres per second on the WGS-84 ellipsoid (radii of
 * curvature M, N at the latitude, plus the altitude; pose_state.h), i.e.
 * exactly the motion the renderer's position prediction inverts. Frames: node-id 1, service code 0, message
 * code a per-id counter from 0 wrapping 255 -> 0, DLC 8. Frames of
 * [t0, t0 + duration) are written, sorted by time; log time =
 * start time + (t - t0).
 *
 * A --duration limit is likewise at least one log period. Fault times must
 * be finite and inside the logged path [t0, t0 + duration) (a --stall's
 * FROM; its TO may lie past the end), else the run is refused: a fault
 * outside would silently never fire, or fire on the first frame.
 *
 * Faults (times are path times, the clock of the waypoint file; each
 * single-shot fault goes to the first frame at or after its time that is
 * written and carries no other fault):
 *   drop_every N  every Nth attitude frame (311/312/321, counted together
 *                 in time order) is not written, but its message code is
 *                 used up: the decoder counts one lost message per drop
 *                 (once a later frame of that id arrives);
 *   nan_at        a pitch frame carries a quiet NaN -> NONFINITE reject;
 *   bad_dlc_at    a FLOAT frame is written with DLC 7 -> DLC reject; the
 *                 decoder drops it before it reads the message code, so the
 *                 next frame of that id also shows one lost message;
 *   duplicate_at  a FLOAT frame is written twice, the copy 125 us later with
 *                 the same code -> COUNTER_REPEAT reject;
 *   stall         no frame at all in [from, to): the sender is silent, its
 *                 counters do not advance (no loss is counted, the data go
 *                 stale); a DOUBLEH/DOUBLEL pair is kept or left out whole;
 *   velocity_stop no velocity frame (1039/1040/314) at or after this time:
 *                 the GPS velocity output fails, the position goes on;
 *   gps_jump      from this time on every latitude is sent gps_jump_m metres
 *                 north of the path (a GPS reset, or a receiver that changes
 *                 its solution), the velocity unchanged.
 *
 * Deterministic: no clock, no randomness, fixed-order arithmetic; the same
 * path and options give the same bytes. */
#ifndef FT_TOOLS_FLIGHT_PATH_H
#define FT_TOOLS_FLIGHT_PATH_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "input/candump.h"
#include "input/pose_state.h"

#define FLIGHT_WAYPOINTS_MAX 1024u
#define FLIGHT_LINE_MAX 256u               /* waypoint file line, characters */
#define FLIGHT_EARTH_RADIUS_M 6371008.8    /* mean radius (IUGG) */
#define FLIGHT_G_M_S2 9.80665
#define FLIGHT_RATE_MAX_DEG_S 500.0        /* decoder range of 303/304/305 */
#define FLIGHT_SPEED_MAX_M_S 1000.0        /* and the decoder range of 1039 */
#define FLIGHT_VSPEED_MAX_M_S 500.0        /* decoder range of 314 */
#define FLIGHT_DURATION_MAX_S 36000.0
#define FLIGHT_DURATION_MIN_S (FLIGHTGEN_PERIOD_US * 1e-6) /* one log period */
#define FLIGHT_TIME_MAX_S 1e7              /* waypoint time stamps */
#define FLIGHT_DERIVED_ROLL_MAX_DEG 80.0
#define FLIGHT_BUILTIN_STEP_S 0.1

typedef struct flight_waypoint {
    double t_s;
    double lat_deg, lon_deg, alt_m;
    double heading_deg, pitch_deg, roll_deg;
    uint32_t line;        /* waypoint file line, 0 for built-in paths */
    uint8_t has_attitude; /* 0: derived when the path is finished */
} flight_waypoint;

typedef struct flight_path {
    char name[64];                            /* file name or built-in name */
    flight_waypoint wp[FLIGHT_WAYPOINTS_MAX];
    ft_quat q[FLIGHT_WAYPOINTS_MAX];          /* attitude, sign-aligned for slerp */
    double w_rad_s[FLIGHT_WAYPOINTS_MAX][3];  /* body rate p, q, r of segment i -> i+1 */
    uint32_t count;
    uint8_t finished;
} flight_path;

/* The path at time t_s. Outside [t0, t_end] the end state is held with zero
 * rates. Euler angles come from q (pose_state.h ranges). The velocity is the
 * segment's (the path is linear in lat, lon, alt between waypoints), in
 * metres per second on the WGS-84 ellipsoid at the sample's latitude and
 * altitude (what a GPS receiver reports; 0 outside the path). */
typedef struct flight_sample {
    double lat_deg, lon_deg, alt_m;
    double heading_deg, pitch_deg, roll_deg;
    ft_quat q;
    double p_deg_s, q_deg_s, r_deg_s; /* body rates: roll, pitch, yaw */
    double v_n_m_s, v_e_m_s, v_u_m_s; /* velocity north, east, up */
} flight_sample;

/* Parses a waypoint file held in text[0..len) (see the top of the file for
 * the rules) and finishes the path. name is used in messages:
 * "NAME line 7: time 3 s is not after the previous waypoint's 3 s (line 6)". */
ft_status flight_path_parse_waypoints(flight_path *p, const char *text, size_t len,
                                      const char *name, ft_error *err);

/* Appends one waypoint (for tests and callers that build paths in code);
 * call flight_path_finish after the last one. */
ft_status flight_path_add(flight_path *p, const flight_waypoint *w, ft_error *err);

/* Derives missing attitudes, aligns quaternions, computes segment rates and
 * runs the whole-path checks. */
ft_status flight_path_finish(flight_path *p, ft_error *err);

typedef enum flight_builtin_kind {
    FLIGHT_ORBIT,
    FLIGHT_CLIMB,
    FLIGHT_DIVE,
    FLIGHT_TURN360,
    FLIGHT_VALLEY,
    FLIGHT_BUILTIN_COUNT
} flight_builtin_kind;

/* "orbit" -> FLIGHT_ORBIT; -1 if unknown. */
int flight_builtin_from_name(const char *name);
const char *flight_builtin_name(flight_builtin_kind k);

typedef struct flight_builtin_params {
    flight_builtin_kind kind;
    double centre_lat_deg, centre_lon_deg; /* orbit centre, else the start */
    double alt_m;      /* NAN: the path's default */
    double duration_s; /* NAN: the path's default */
    double radius_m;   /* orbit only; NAN: default */
    double speed_m_s;  /* NAN: default */
} flight_builtin_params;

#define FLIGHT_DEFAULT_CENTRE_LAT_DEG 46.5
#define FLIGHT_DEFAULT_CENTRE_LON_DEG 8.0

/* Default centre, everything else NAN (= the path's default). */
void flight_builtin_defaults(flight_builtin_params *bp, flight_builtin_kind kind);

/* Builds and finishes a built-in path. */
ft_status flight_path_builtin(flight_path *p, const flight_builtin_params *bp, ft_error *err);

/* Needs a finished path. */
void flight_path_sample(const flight_path *p, double t_s, flight_sample *out);
double flight_path_t0_s(const flight_path *p);
double flight_path_duration_s(const flight_path *p);

/* ---- frame encoder and log writer ----------------------------------------- */

#define FLIGHTGEN_PERIOD_US 12500u   /* 80 Hz */
#define FLIGHTGEN_POS_DIVIDER 8u     /* position every 8th period: 10 Hz */
#define FLIGHTGEN_HALF_GAP_US 250u   /* DOUBLEH -> DOUBLEL */
#define FLIGHTGEN_DUP_DELAY_US 125u
#define FLIGHTGEN_NODE_ID 1u
#define FLIGHTGEN_DEFAULT_START_US UINT64_C(1700000000000000)
/* Log times must fit candump's 64-bit nanoseconds with room for the flight. */
#define FLIGHTGEN_START_MAX_US UINT64_C(18000000000000000)

typedef enum flightgen_msg {
    FLIGHTGEN_PITCH,
    FLIGHTGEN_ROLL,
    FLIGHTGEN_HEADING,
    FLIGHTGEN_ROLL_RATE,
    FLIGHTGEN_PITCH_RATE,
    FLIGHTGEN_YAW_RATE,
    FLIGHTGEN_LAT,
    FLIGHTGEN_LON,
    FLIGHTGEN_ALT,
    FLIGHTGEN_GROUND_SPEED,
    FLIGHTGEN_TRACK,
    FLIGHTGEN_ALT_RATE,
    FLIGHTGEN_MSG_COUNT
} flightgen_msg;

typedef struct flightgen_slot {
    ft_pose_qty qty;    /* sent on the default CANaerospace id of this quantity */
    uint32_t offset_us; /* within the 12.5 ms period */
    uint32_t divider;   /* sent every divider-th period */
    uint8_t is_double;  /* DOUBLEH + DOUBLEL, else FLOAT */
} flightgen_slot;

/* The schedule in the table at the top of the file, indexed by flightgen_msg. */
extern const flightgen_slot flightgen_schedule[FLIGHTGEN_MSG_COUNT];

/* The CAN id of every message: the primary (priority 0) entry of its
 * quantity in ft_canaero_default_map. FT_ERR_CONFIG if one has none. */
ft_status flightgen_ids(uint16_t ids[FLIGHTGEN_MSG_COUNT], ft_error *err);

/* Ground speed (m/s, >= 0) and true track (deg, [0, 360)) of a velocity. */
void flightgen_ground_velocity(double v_n_m_s, double v_e_m_s, double *speed_m_s,
                               double *track_deg);

/* One CANaerospace normal-operation frame: node-id 1, the given type, service
 * code 0, message code, data big-endian in bytes 4..7, DLC 8. */
void flightgen_encode(ft_can_frame *f, uint16_t can_id, uint8_t data_type, uint8_t code,
                      uint32_t data_bits, uint64_t t_ns);

typedef struct flightgen_options {
    uint64_t start_us;                         /* log time of path time t0 */
    char iface[FT_CANDUMP_IFACE_MAX + 1u];     /* "vcan0" */
    double duration_s;                         /* NAN: the whole path, else a limit */
    int velocity;                              /* 1: send 1039/1040/314 (--no-velocity: 0) */
    uint32_t drop_every;                       /* 0: off */
    double nan_at_s, bad_dlc_at_s, duplicate_at_s; /* NAN: off */
    double stall_from_s, stall_to_s;           /* NAN: off */
    double velocity_stop_s;                    /* NAN: off */
    double gps_jump_at_s, gps_jump_m;          /* NAN: off */
} flightgen_options;

/* start 1700000000.000000, vcan0, whole path, velocity sent, no faults. */
void flightgen_options_default(flightgen_options *o);

typedef struct flightgen_stats {
    uint64_t lines;                         /* written, duplicates included */
    uint64_t frames[FLIGHTGEN_MSG_COUNT];   /* written per message */
    uint64_t dropped;                       /* attitude frames left out (--drop-every) */
    uint64_t stalled;                       /* frames not sent during the stall */
    uint64_t velocity_stopped;              /* velocity frames not sent (--velocity-stop) */
    uint64_t gps_jumped;                    /* latitudes sent off the path (--gps-jump) */
    uint32_t nan_injected, bad_dlc_injected, duplicates_injected;
    uint64_t first_t_ns, last_t_ns;         /* log times of the first and last line */
} flightgen_stats;

/* Receives each line (without a line end) and its record, in time order.
 * Returns FT_OK to go on; anything else stops the run with that status. */
typedef ft_status (*flightgen_sink_fn)(void *ctx, const ft_candump_record *rec, const char *line,
                                       size_t len, ft_error *err);

/* Writes the log of a finished path. stats may be NULL. */
ft_status flightgen_run(const flight_path *p, const flightgen_options *o, flightgen_sink_fn sink,
                        void *ctx, flightgen_stats *stats, ft_error *err);

#endif
