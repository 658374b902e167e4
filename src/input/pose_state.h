/* pose_state.h - one aircraft pose assembled from quantities that arrive at
 * different rates (CANaerospace, later other buses), extrapolated to the
 * display time from the body rates.
 *
 * Frames (the aerospace convention, the same attitude convention as ft_pose
 * in camera.h):
 *   world NED: x north, y east, z down;
 *   body:      x nose (forward), y right wing, z down (belly).
 *   Attitude is the unit quaternion q (double) that rotates body vectors into
 *   NED: q = qz(heading) * qy(pitch) * qx(roll) (Z-Y'-X'', i.e. heading about
 *   down, then pitch about the new right wing, then roll about the nose).
 *   Heading clockwise from north, pitch nose-up positive, roll right-wing-
 *   down positive. Body rates p (roll rate, about x), q (pitch rate, about
 *   y), r (yaw rate, about z), each positive by the right-hand rule on these
 *   axes, which is what CANaerospace ids 304/303/305 carry.
 *
 * Euler angles out of a quaternion: heading in [0, 360), pitch in [-90, 90],
 * roll in (-180, 180]. Gimbal lock (cos(pitch) < FT_POSE_GIMBAL_COS_EPS):
 * only heading - roll (pitch +90) or heading + roll (pitch -90) is defined;
 * the convention is roll = 0 and heading carries the whole rotation about
 * the vertical. Never NaN for a finite input.
 *
 * Prediction: the attitude epoch is the NEWEST of the heading, pitch and roll
 * sample times (an AHRS sends the three back to back; the newest sample is
 * exact and the others are at most one transmit period older). The display
 * time t is reached with one exact exponential-map step for a constant body
 * rate, dt = clamp(t - epoch, 0, horizon): before the epoch nothing is
 * predicted backwards, and beyond the horizon the prediction holds the value
 * it had at the horizon (no jump back). Prediction needs all three rates
 * valid (not stale) at t; otherwise the measured attitude is held.
 *
 * Position: dead reckoning in the local tangent plane at the last fix. Each
 * component goes forward from its own sample time (latitude, longitude and
 * altitude arrive in separate messages) with the newest velocity, taken as
 * constant: north v_n = ground speed * cos(track), east v_e = ground speed *
 * sin(track), up = altitude rate, turned into latitude and longitude rates
 * with the WGS-84 radii of curvature at the fix (meridian M, prime vertical
 * N, plus the altitude):
 *   lat(t) = lat_fix + v_n dt / (M + h),  lon(t) = lon_fix + v_e dt / ((N + h) cos lat_fix),
 *   alt(t) = alt_fix + v_up dt,  dt = clamp(min(t, t_stop) - t_fix, 0, horizon),
 * t_stop = the time the velocity goes stale (its sample time + timeout).
 * Horizontal needs ground speed and track, vertical the altitude rate.
 * Error of the model over dt: 1/2 a dt^2 for an acceleration a (a turn at
 * 250 m/s and 60 deg of bank, a = 17 m/s^2: 0.085 m over 100 ms, 8.5 m over
 * the 1 s maximum horizon); the flat step against the WGS-84 geodesic adds
 * about (v dt)^2 tan(lat) / (2 R) (measured at 250 m/s, latitudes 0..70:
 * at most 0.15 mm over 100 ms, 15 mm over 1 s; tests/test_pose_state.c).
 * In a turn every fix disagrees with the prediction by that 1/2 a dt^2,
 * always towards the centre, and the convergence below carries the bias: a
 * longer converge_ms lags more (README: measured). A stale velocity stops the
 * prediction at t_stop: the position is held where the prediction was then
 * (no jump back), and the next fix is drawn as it comes, as without velocity.
 * Beyond the horizon the prediction holds its value at the horizon.
 *
 * Convergence: every value that moves the predicted position (a fix, a
 * velocity) is an event at its sample time te. The drawn position is the
 * prediction plus an offset o (north, east, up metres) that decays as
 * o exp(-(t - te) / converge_ms). At an event, o becomes (drawn just before)
 * - (predicted just after), so the drawn position does not jump: a fix that
 * disagrees with the prediction is reached smoothly (95 % in 3 converge_ms),
 * and the exponential makes a later event's restart cost nothing. Only the
 * axes that were predicted before the event (fresh velocity) converge and
 * count toward a snap; with a stale or missing velocity a fix is drawn at
 * once, as before. When |o|
 * exceeds snap_m (a GPS reset, a switch to another source) the drawn
 * position snaps to the prediction instead, and the snap is counted once per
 * fix (lat, lon and alt of one fix arrive within FT_POSE_SNAP_MERGE_MS).
 * converge_ms 0: every correction at once (snaps are still counted).
 *
 * Storage: everything lives in the caller's ft_pose_state; no heap, no OS. */
#ifndef FT_POSE_STATE_H
#define FT_POSE_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "core/ft_status.h"

/* X(id, name used in annunciations, unit) - in annunciation priority order:
 * attitude first (what the terrain picture depends on most), then position,
 * then the rates that only feed the attitude prediction, then the velocity
 * that only feeds the position prediction. The velocity is what a GPS
 * receiver sends: ground speed (horizontal, >= 0), true track (direction of
 * the ground velocity, clockwise from true north) and the altitude rate
 * (vertical speed, up positive). */
#define FT_POSE_QTY_LIST(X)                        \
    X(FT_QTY_PITCH, "pitch", "deg")                \
    X(FT_QTY_ROLL, "roll", "deg")                  \
    X(FT_QTY_HEADING, "heading", "deg")            \
    X(FT_QTY_LAT, "latitude", "deg")               \
    X(FT_QTY_LON, "longitude", "deg")              \
    X(FT_QTY_ALT, "altitude", "m")                 \
    X(FT_QTY_PITCH_RATE, "pitch rate", "deg/s")    \
    X(FT_QTY_ROLL_RATE, "roll rate", "deg/s")      \
    X(FT_QTY_YAW_RATE, "yaw rate", "deg/s")        \
    X(FT_QTY_GROUND_SPEED, "ground speed", "m/s")  \
    X(FT_QTY_TRACK, "track", "deg")                \
    X(FT_QTY_ALT_RATE, "altitude rate", "m/s")

typedef enum ft_pose_qty {
#define FT_POSE_QTY_ENUM(id, name, unit) id,
    FT_POSE_QTY_LIST(FT_POSE_QTY_ENUM)
#undef FT_POSE_QTY_ENUM
    FT_QTY_COUNT
} ft_pose_qty;

const char *ft_pose_qty_name(ft_pose_qty q); /* "heading"; "?" if out of range */
const char *ft_pose_qty_unit(ft_pose_qty q); /* "deg" */

#define FT_QTY_BIT(q) (1u << (unsigned)(q))
#define FT_QTY_ALL_MASK ((1u << (unsigned)FT_QTY_COUNT) - 1u)
#define FT_QTY_ATTITUDE_MASK \
    (FT_QTY_BIT(FT_QTY_PITCH) | FT_QTY_BIT(FT_QTY_ROLL) | FT_QTY_BIT(FT_QTY_HEADING))
#define FT_QTY_POSITION_MASK \
    (FT_QTY_BIT(FT_QTY_LAT) | FT_QTY_BIT(FT_QTY_LON) | FT_QTY_BIT(FT_QTY_ALT))
#define FT_QTY_RATE_MASK                                                    \
    (FT_QTY_BIT(FT_QTY_PITCH_RATE) | FT_QTY_BIT(FT_QTY_ROLL_RATE) | \
     FT_QTY_BIT(FT_QTY_YAW_RATE))
#define FT_QTY_HVEL_MASK (FT_QTY_BIT(FT_QTY_GROUND_SPEED) | FT_QTY_BIT(FT_QTY_TRACK))
#define FT_QTY_VELOCITY_MASK (FT_QTY_HVEL_MASK | FT_QTY_BIT(FT_QTY_ALT_RATE))

/* Prediction horizon: default and the largest a caller may configure. 100 ms
 * covers a few display frames of input latency; longer predictions from a
 * rate measured once are guesses, so they are capped. */
#define FT_POSE_HORIZON_DEFAULT_MS 100u
#define FT_POSE_HORIZON_MAX_MS 1000u

/* Position convergence (see "Position" above). The default time constant,
 * 300 ms, spreads a 5 m disagreement at 60 Hz over steps of at most
 * 5 m * 16.7 / 300 = 0.28 m on top of the motion; the longest, 10 s, is
 * beyond any useful smoothing. A disagreement over 100 m is a GPS reset or
 * a source switch, not an error to hide: it is snapped to. */
#define FT_POSE_CONVERGE_DEFAULT_MS 300u
#define FT_POSE_CONVERGE_MAX_MS 10000u
#define FT_POSE_SNAP_DEFAULT_M 100.0
#define FT_POSE_SNAP_MIN_M 1.0
#define FT_POSE_SNAP_MAX_M 100000.0

/* Below this cos(pitch) the roll/heading split is numerically meaningless
 * (1e-9 is pitch within 5.7e-8 deg of +-90). */
#define FT_POSE_GIMBAL_COS_EPS 1e-9
/* Staggered angle samples are aligned (Euler rates) only while |cos(pitch)|
 * exceeds this (pitch within about 89.4 deg of level). */
#define FT_POSE_ALIGN_COS_MIN 1e-2

/* Below this cos(latitude) (within 0.2 m of a pole) east motion is not
 * turned into longitude: the longitude is held. */
#define FT_POSE_POLE_COS_MIN 3e-8
/* Snaps closer than this to the previous one are the same fix's. */
#define FT_POSE_SNAP_MERGE_MS 50u

/* ft_pose_estimate.position_predicted bits */
#define FT_POSE_PRED_HORIZONTAL 1
#define FT_POSE_PRED_VERTICAL 2

/* Annunciation text, e.g. "no heading for 250 ms (+2 more)". */
#define FT_POSE_REASON_MAX 64

/* ---- quaternion helpers (public so tests and the renderer can use them) -- */

typedef struct ft_quat {
    double w, x, y, z;
} ft_quat;

/* Body-to-NED attitude from Euler angles (any finite values; no wrapping
 * needed). */
ft_quat ft_quat_from_euler_deg(double heading_deg, double pitch_deg, double roll_deg);

/* Back to Euler angles with the ranges and gimbal-lock convention above. The
 * input need not be exactly unit length (it is normalised first); a zero or
 * non-finite quaternion gives 0, 0, 0. */
void ft_quat_to_euler_deg(ft_quat q, double *heading_deg, double *pitch_deg, double *roll_deg);

/* Constant body rate omega (p, q, r in rad/s) for dt_s seconds (any sign):
 * q <- normalise(q * exp(0.5 * omega * dt)), exact for a constant rate. */
ft_quat ft_quat_integrate_body_rate(ft_quat q, const double omega_rad_s[3], double dt_s);

ft_quat ft_quat_mul(ft_quat a, ft_quat b);
double ft_quat_norm(ft_quat q);

/* Angle wrappers used for the output ranges. */
double ft_wrap_deg_0_360(double a_deg);   /* [0, 360) */
double ft_wrap_deg_pm180(double a_deg);   /* (-180, 180] */

/* WGS-84 radii of curvature at geodetic latitude lat_deg: meridian M =
 * a (1 - e^2) / (1 - e^2 sin^2)^1.5 and prime vertical N = a / sqrt(1 - e^2
 * sin^2). North metres = dlat (rad) * (M + h), east metres = dlon (rad) *
 * (N + h) cos(lat). Either output may be NULL. */
void ft_wgs84_radii_m(double lat_deg, double *meridian_m, double *prime_vertical_m);

/* ---- pose state ------------------------------------------------------------ */

/* One decoded value on its way in (from ft_canaero_decode or any source). */
typedef struct ft_pose_input {
    ft_pose_qty qty;
    double value;        /* in the quantity's unit (deg, m, deg/s) */
    uint64_t t_ns;       /* receive (or measurement) time */
    uint32_t timeout_ms; /* the value is stale this long after t_ns */
    uint8_t priority;    /* 0 = primary source; see ft_pose_state_apply */
    uint32_t source_id;  /* e.g. the CAN id, kept for diagnostics */
} ft_pose_input;

typedef struct ft_pose_sample {
    double value;
    uint64_t t_ns;
    uint32_t timeout_ms;
    uint32_t source_id;
    uint8_t priority;
    uint8_t valid; /* 0 until the first good value */
} ft_pose_sample;

typedef struct ft_pose_state {
    ft_pose_sample s[FT_QTY_COUNT];
    uint32_t horizon_ms;
    uint32_t converge_ms;     /* time constant of the position convergence */
    double snap_m;            /* larger disagreements snap */
    double offset_m[3];       /* drawn minus predicted position (north, east, up) at offset_t_ns */
    uint64_t offset_t_ns;     /* time of the last position event */
    uint64_t last_snap_t_ns;
    uint64_t snap_count;      /* fixes snapped to */
    double offset_max_m;      /* largest offset converged (not snapped) */
    uint64_t applied_count;
    uint64_t dropped_older_count;    /* older than the value already held */
    uint64_t dropped_priority_count; /* a backup source while the primary is fresh */
} ft_pose_state;

/* horizon_ms in [0, FT_POSE_HORIZON_MAX_MS]; 0 disables prediction.
 * Convergence starts at FT_POSE_CONVERGE_DEFAULT_MS and FT_POSE_SNAP_DEFAULT_M. */
ft_status ft_pose_state_init(ft_pose_state *ps, uint32_t horizon_ms, ft_error *err);

/* converge_ms in [0, FT_POSE_CONVERGE_MAX_MS], snap_m in [FT_POSE_SNAP_MIN_M,
 * FT_POSE_SNAP_MAX_M]; out of range fails (FT_ERR_ARG) and changes nothing.
 * Call it before the first value. */
ft_status ft_pose_state_set_convergence(ft_pose_state *ps, uint32_t converge_ms, double snap_m,
                                        ft_error *err);

/* Stores one value as the quantity's last good value. Several sources may
 * feed one quantity (altitude: baro 320, GPS 1038): a sample replaces the
 * held one if its priority number is <= the held one's, or if the held one
 * is stale at the new sample's time, so a backup only takes over while the
 * primary is silent (and the primary takes back over with its next value).
 * A sample older than the held one is dropped, whatever its source:
 * out-of-order delivery must not move the quantity's time back.
 * Non-finite values, timeout 0 or a bad qty fail (FT_ERR_NUMERIC/ARG) and
 * change nothing. *applied (may be NULL) says whether the value was stored. */
ft_status ft_pose_state_apply(ft_pose_state *ps, const ft_pose_input *in, int *applied,
                              ft_error *err);

/* Bit mask (FT_QTY_BIT) of quantities that are stale at t_ns: never received
 * or older than their timeout. A sample time after t_ns counts as age 0.
 * reason (may be NULL, cap bytes) gets the first stale quantity in priority
 * order: "no heading for 250 ms", "no heading received", plus " (+N more)";
 * an empty string when nothing is stale. */
uint32_t ft_pose_state_stale(const ft_pose_state *ps, uint64_t t_ns, char *reason, size_t cap);

/* The same over the quantities in mask only (the reason names only those):
 * what an annunciation that covers some quantities says. */
uint32_t ft_pose_state_stale_in(const ft_pose_state *ps, uint64_t t_ns, uint32_t mask,
                                char *reason, size_t cap);

typedef struct ft_pose_estimate {
    ft_pose pose;           /* attitude and position predicted to t */
    ft_quat attitude;       /* body -> NED, unit */
    uint64_t epoch_ns;      /* attitude sample time the prediction starts at */
    double predict_s;       /* prediction actually applied (0 .. horizon) */
    int horizon_clamped;    /* 1 if t was beyond epoch + horizon */
    int predicted;          /* 0 if the rates were stale (attitude held) */
    uint32_t stale_mask;    /* as ft_pose_state_stale at t */
    int position_predicted; /* FT_POSE_PRED_* of the axes with a fresh velocity at t */
    double position_predict_s; /* longest extrapolation of a position component */
    int position_clamped;   /* a position component reached the horizon */
    double offset_m;        /* |drawn - predicted| position: convergence still to go */
} ft_pose_estimate;

/* Pose at display time t_ns. Quantities never received read 0 (and are in
 * stale_mask): the caller annunciates instead of trusting them. */
void ft_pose_state_estimate(const ft_pose_state *ps, uint64_t t_ns, ft_pose_estimate *out);

#endif
