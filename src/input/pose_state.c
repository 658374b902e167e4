/* pose_state.c - pose assembly, attitude and position prediction, position
 * convergence (contract in pose_state.h). Pure arithmetic on caller storage:
 * no heap, no OS. */
#include "input/pose_state.h"

#include "core/ft_ns.h"
#include "core/units.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>

#define FT_NS_PER_MS UINT64_C(1000000)

static const char *const k_qty_name[FT_QTY_COUNT] = {
#define FT_POSE_QTY_NAME(id, name, unit) name,
    FT_POSE_QTY_LIST(FT_POSE_QTY_NAME)
#undef FT_POSE_QTY_NAME
};

static const char *const k_qty_unit[FT_QTY_COUNT] = {
#define FT_POSE_QTY_UNIT(id, name, unit) unit,
    FT_POSE_QTY_LIST(FT_POSE_QTY_UNIT)
#undef FT_POSE_QTY_UNIT
};

const char *ft_pose_qty_name(ft_pose_qty q)
{
    return ((int)q >= 0 && q < FT_QTY_COUNT) ? k_qty_name[q] : "?";
}

const char *ft_pose_qty_unit(ft_pose_qty q)
{
    return ((int)q >= 0 && q < FT_QTY_COUNT) ? k_qty_unit[q] : "?";
}

/* ---- quaternion helpers ---------------------------------------------------- */

ft_quat ft_quat_mul(ft_quat a, ft_quat b)
{
    ft_quat r;
    r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    return r;
}

double ft_quat_norm(ft_quat q)
{
    return sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
}

static int quat_is_finite(ft_quat q)
{
    return isfinite(q.w) && isfinite(q.x) && isfinite(q.y) && isfinite(q.z);
}

/* Unit quaternion or identity: a zero or non-finite quaternion has no
 * direction to keep, and the contract promises no NaN out. */
static ft_quat quat_normalise(ft_quat q)
{
    double n = ft_quat_norm(q);
    if (!quat_is_finite(q) || !(n > 0.0) || !isfinite(n)) {
        ft_quat id = {1.0, 0.0, 0.0, 0.0};
        return id;
    }
    q.w /= n;
    q.x /= n;
    q.y /= n;
    q.z /= n;
    return q;
}

double ft_wrap_deg_0_360(double a_deg)
{
    if (!isfinite(a_deg)) {
        return 0.0;
    }
    double r = fmod(a_deg, 360.0); /* exact, sign of a_deg */
    if (r < 0.0) {
        r += 360.0;
    }
    /* -1e-15 + 360 rounds to 360.0, which is outside [0, 360). */
    if (r >= 360.0) {
        r -= 360.0;
    }
    return r;
}

double ft_wrap_deg_pm180(double a_deg)
{
    if (!isfinite(a_deg)) {
        return 0.0;
    }
    double r = fmod(a_deg, 360.0); /* (-360, 360) */
    if (r > 180.0) {
        r -= 360.0;
    } else if (r <= -180.0) {
        r += 360.0;
    }
    return r;
}

ft_quat ft_quat_from_euler_deg(double heading_deg, double pitch_deg, double roll_deg)
{
    double hh = 0.5 * heading_deg * FT_RAD_PER_DEG;
    double hp = 0.5 * pitch_deg * FT_RAD_PER_DEG;
    double hr = 0.5 * roll_deg * FT_RAD_PER_DEG;
    double cy = cos(hh), sy = sin(hh);
    double cp = cos(hp), sp = sin(hp);
    double cr = cos(hr), sr = sin(hr);
    /* qz(heading) * qy(pitch) * qx(roll), expanded. */
    ft_quat q;
    q.w = cy * cp * cr + sy * sp * sr;
    q.x = cy * cp * sr - sy * sp * cr;
    q.y = cy * sp * cr + sy * cp * sr;
    q.z = sy * cp * cr - cy * sp * sr;
    return quat_normalise(q);
}

void ft_quat_to_euler_deg(ft_quat q, double *heading_deg, double *pitch_deg, double *roll_deg)
{
    q = quat_normalise(q);
    double w = q.w, x = q.x, y = q.y, z = q.z;
    /* Rotation matrix C (body -> NED) elements that are needed. */
    double c11 = 1.0 - 2.0 * (y * y + z * z);
    double c21 = 2.0 * (x * y + w * z);
    double c31 = 2.0 * (x * z - w * y);
    double c32 = 2.0 * (y * z + w * x);
    double c33 = 1.0 - 2.0 * (x * x + y * y);
    double c12 = 2.0 * (x * y - w * z);
    double c22 = 1.0 - 2.0 * (x * x + z * z);

    /* cos(pitch) from the third row, not asin(-c31): asin loses half the
     * digits near +-90 and is NaN if rounding pushes |c31| past 1. */
    double cos_pitch = hypot(c32, c33);
    double pitch = atan2(-c31, cos_pitch);
    double heading, roll;
    if (cos_pitch < FT_POSE_GIMBAL_COS_EPS) {
        /* Gimbal lock: C12 = -sin(h -/+ r), C22 = cos(h -/+ r) for pitch
         * +-90; with roll = 0 both cases give heading = atan2(-C12, C22). */
        roll = 0.0;
        heading = atan2(-c12, c22);
    } else {
        roll = atan2(c32, c33);
        heading = atan2(c21, c11);
    }
    if (heading_deg != NULL) {
        *heading_deg = ft_wrap_deg_0_360(heading * FT_DEG_PER_RAD);
    }
    if (pitch_deg != NULL) {
        *pitch_deg = pitch * FT_DEG_PER_RAD;
    }
    if (roll_deg != NULL) {
        *roll_deg = ft_wrap_deg_pm180(roll * FT_DEG_PER_RAD);
    }
}

/* sin(a)/a without the 0/0: below 1e-4 the series 1 - a^2/6 + a^4/120 is
 * exact to double precision (the next term is a^6/5040 < 2e-28). */
static double sinc(double a)
{
    double aa = fabs(a);
    if (aa < 1e-4) {
        double a2 = a * a;
        return 1.0 - a2 / 6.0 + a2 * a2 / 120.0;
    }
    return sin(a) / a;
}

ft_quat ft_quat_integrate_body_rate(ft_quat q, const double omega_rad_s[3], double dt_s)
{
    if (omega_rad_s == NULL || !isfinite(dt_s) || !isfinite(omega_rad_s[0]) ||
        !isfinite(omega_rad_s[1]) || !isfinite(omega_rad_s[2])) {
        return quat_normalise(q);
    }
    /* exp of the pure quaternion v = 0.5 * omega * dt: (cos|v|, v sinc|v|).
     * Right multiplication because omega is in body axes. */
    double vx = 0.5 * omega_rad_s[0] * dt_s;
    double vy = 0.5 * omega_rad_s[1] * dt_s;
    double vz = 0.5 * omega_rad_s[2] * dt_s;
    double a = sqrt(vx * vx + vy * vy + vz * vz);
    double s = sinc(a);
    ft_quat e = {cos(a), vx * s, vy * s, vz * s};
    return quat_normalise(ft_quat_mul(quat_normalise(q), e));
}

void ft_wgs84_radii_m(double lat_deg, double *meridian_m, double *prime_vertical_m)
{
    /* WGS-84: semi-major axis a and first eccentricity squared e^2 = f (2 - f),
     * f = 1 / 298.257223563 */
    const double a = 6378137.0;
    const double e2 = 6.69437999014e-3;
    const double s = isfinite(lat_deg) ? sin(lat_deg * FT_RAD_PER_DEG) : 0.0;
    const double w = 1.0 - e2 * s * s; /* >= 1 - e^2 > 0 */
    const double n = a / sqrt(w);
    if (meridian_m != NULL) {
        *meridian_m = n * (1.0 - e2) / w;
    }
    if (prime_vertical_m != NULL) {
        *prime_vertical_m = n;
    }
}

/* ---- pose state ------------------------------------------------------------ */

ft_status ft_pose_state_init(ft_pose_state *ps, uint32_t horizon_ms, ft_error *err)
{
    if (ps == NULL) {
        return ft_fail(err, FT_ERR_ARG, "pose state: no storage");
    }
    if (horizon_ms > FT_POSE_HORIZON_MAX_MS) {
        return ft_fail(err, FT_ERR_ARG, "pose state: prediction horizon %" PRIu32
                                        " ms exceeds the maximum %u ms",
                       horizon_ms, FT_POSE_HORIZON_MAX_MS);
    }
    ft_pose_state zero = {0};
    *ps = zero;
    ps->horizon_ms = horizon_ms;
    ps->converge_ms = FT_POSE_CONVERGE_DEFAULT_MS;
    ps->snap_m = FT_POSE_SNAP_DEFAULT_M;
    return FT_OK;
}

ft_status ft_pose_state_set_convergence(ft_pose_state *ps, uint32_t converge_ms, double snap_m,
                                        ft_error *err)
{
    if (ps == NULL) {
        return ft_fail(err, FT_ERR_ARG, "pose state: no storage");
    }
    if (converge_ms > FT_POSE_CONVERGE_MAX_MS ||
        !(snap_m >= FT_POSE_SNAP_MIN_M && snap_m <= FT_POSE_SNAP_MAX_M)) {
        return ft_fail(err, FT_ERR_ARG,
                       "pose state: convergence %" PRIu32 " ms (0..%u) or snap distance %g m "
                       "(%g..%g) out of range",
                       converge_ms, FT_POSE_CONVERGE_MAX_MS, snap_m, FT_POSE_SNAP_MIN_M,
                       FT_POSE_SNAP_MAX_M);
    }
    ps->converge_ms = converge_ms;
    ps->snap_m = snap_m;
    return FT_OK;
}

static uint64_t age_ns(const ft_pose_sample *s, uint64_t t_ns)
{
    return t_ns > s->t_ns ? t_ns - s->t_ns : 0u;
}

static int sample_stale(const ft_pose_sample *s, uint64_t t_ns)
{
    if (!s->valid) {
        return 1;
    }
    return age_ns(s, t_ns) > (uint64_t)s->timeout_ms * FT_NS_PER_MS;
}

/* ---- position prediction and convergence ------------------------------------ */

static int moves_position(ft_pose_qty q)
{
    return q == FT_QTY_LAT || q == FT_QTY_LON || q == FT_QTY_ALT || q == FT_QTY_GROUND_SPEED ||
           q == FT_QTY_TRACK || q == FT_QTY_ALT_RATE;
}

/* The time a sample goes stale; saturates instead of wrapping. */
static uint64_t stop_ns(const ft_pose_sample *s)
{
    const uint64_t life_ns = (uint64_t)s->timeout_ms * FT_NS_PER_MS;
    return s->t_ns > UINT64_MAX - life_ns ? UINT64_MAX : s->t_ns + life_ns;
}

typedef struct pos_pred {
    double lat_deg, lon_deg, alt_m; /* 0 where never received */
    int valid[3];                   /* lat, lon, alt received */
    int axes;                       /* FT_POSE_PRED_*: velocity fresh at t */
    double predict_s;               /* longest extrapolation applied */
    int clamped;                    /* a component reached the horizon */
} pos_pred;

/* Extrapolation time of a component sampled at t_sample_ns when the
 * prediction runs until t_end_ns: none backwards, at most the horizon. */
static double extrap_s(uint64_t t_sample_ns, uint64_t t_end_ns, uint64_t horizon_ns, pos_pred *o)
{
    if (t_end_ns <= t_sample_ns) {
        return 0.0;
    }
    uint64_t dt_ns = t_end_ns - t_sample_ns;
    if (dt_ns > horizon_ns) {
        dt_ns = horizon_ns;
        o->clamped = 1;
    }
    const double dt_s = (double)dt_ns * 1e-9;
    if (dt_s > o->predict_s) {
        o->predict_s = dt_s;
    }
    return dt_s;
}

/* The predicted position at t (contract in pose_state.h), without the
 * convergence offset. */
static void predict_position(const ft_pose_state *ps, uint64_t t_ns, pos_pred *o)
{
    const ft_pose_sample *la = &ps->s[FT_QTY_LAT], *lo = &ps->s[FT_QTY_LON];
    const ft_pose_sample *al = &ps->s[FT_QTY_ALT];
    pos_pred zero = {0};
    *o = zero;
    o->valid[0] = la->valid != 0u;
    o->valid[1] = lo->valid != 0u;
    o->valid[2] = al->valid != 0u;
    o->lat_deg = la->valid ? la->value : 0.0;
    o->lon_deg = lo->valid ? lo->value : 0.0;
    o->alt_m = al->valid ? al->value : 0.0;
    if (ps->horizon_ms == 0u) {
        return;
    }
    const uint64_t horizon_ns = (uint64_t)ps->horizon_ms * FT_NS_PER_MS;
    const ft_pose_sample *gs = &ps->s[FT_QTY_GROUND_SPEED], *tr = &ps->s[FT_QTY_TRACK];
    const ft_pose_sample *vs = &ps->s[FT_QTY_ALT_RATE];
    if (gs->valid && tr->valid && (la->valid || lo->valid)) {
        const uint64_t gs_stop_ns = stop_ns(gs), tr_stop_ns = stop_ns(tr);
        const uint64_t h_stop_ns = gs_stop_ns < tr_stop_ns ? gs_stop_ns : tr_stop_ns;
        const uint64_t t_end_ns = t_ns < h_stop_ns ? t_ns : h_stop_ns;
        if (t_ns <= h_stop_ns) {
            o->axes |= FT_POSE_PRED_HORIZONTAL;
        }
        const double track_rad = tr->value * FT_RAD_PER_DEG;
        const double v_n_mps = gs->value * cos(track_rad), v_e_mps = gs->value * sin(track_rad);
        const double lat_fix_deg = o->lat_deg;
        double meridian_m = 0.0, normal_m = 0.0;
        ft_wgs84_radii_m(lat_fix_deg, &meridian_m, &normal_m);
        if (la->valid) {
            const double dt_s = extrap_s(la->t_ns, t_end_ns, horizon_ns, o);
            const double lat_deg = lat_fix_deg + v_n_mps * dt_s / (meridian_m + o->alt_m) * FT_DEG_PER_RAD;
            o->lat_deg = lat_deg > 90.0 ? 90.0 : (lat_deg < -90.0 ? -90.0 : lat_deg);
        }
        const double cos_lat = cos(lat_fix_deg * FT_RAD_PER_DEG);
        if (lo->valid && cos_lat > FT_POSE_POLE_COS_MIN) {
            const double dt_s = extrap_s(lo->t_ns, t_end_ns, horizon_ns, o);
            o->lon_deg = ft_wrap_deg_pm180(
                o->lon_deg + v_e_mps * dt_s / ((normal_m + o->alt_m) * cos_lat) * FT_DEG_PER_RAD);
        }
    }
    if (vs->valid && al->valid) {
        const uint64_t v_stop_ns = stop_ns(vs);
        const uint64_t t_end_ns = t_ns < v_stop_ns ? t_ns : v_stop_ns;
        if (t_ns <= v_stop_ns) {
            o->axes |= FT_POSE_PRED_VERTICAL;
        }
        o->alt_m += vs->value * extrap_s(al->t_ns, t_end_ns, horizon_ns, o);
    }
}

/* The convergence offset left at t (metres north, east, up). */
static void offset_at(const ft_pose_state *ps, uint64_t t_ns, double off_m[3])
{
    double w = 1.0;
    if (ps->converge_ms == 0u) {
        w = 0.0;
    } else if (t_ns > ps->offset_t_ns) {
        w = exp(-(double)(t_ns - ps->offset_t_ns) / ((double)ps->converge_ms * 1e6));
    }
    for (int k = 0; k < 3; ++k) {
        off_m[k] = ps->offset_m[k] * w;
    }
}

/* Metres north/east to degrees at the position in o (radii at its latitude). */
static void metres_to_deg(const pos_pred *o, double north_m, double east_m, double *dlat_deg,
                          double *dlon_deg)
{
    double meridian_m = 0.0, normal_m = 0.0;
    ft_wgs84_radii_m(o->lat_deg, &meridian_m, &normal_m);
    const double cos_lat = cos(o->lat_deg * FT_RAD_PER_DEG);
    *dlat_deg = north_m / (meridian_m + o->alt_m) * FT_DEG_PER_RAD;
    *dlon_deg = cos_lat > FT_POSE_POLE_COS_MIN
                    ? east_m / ((normal_m + o->alt_m) * cos_lat) * FT_DEG_PER_RAD
                    : 0.0;
}

/* The drawn position at t: prediction + convergence offset. */
static void drawn_position(const ft_pose_state *ps, uint64_t t_ns, pos_pred *o, double *off_norm_m)
{
    predict_position(ps, t_ns, o);
    double off_m[3];
    offset_at(ps, t_ns, off_m);
    double dlat_deg = 0.0, dlon_deg = 0.0;
    metres_to_deg(o, off_m[0], off_m[1], &dlat_deg, &dlon_deg);
    if (o->valid[0]) {
        const double lat_deg = o->lat_deg + dlat_deg;
        o->lat_deg = lat_deg > 90.0 ? 90.0 : (lat_deg < -90.0 ? -90.0 : lat_deg);
    }
    if (o->valid[1]) {
        o->lon_deg = ft_wrap_deg_pm180(o->lon_deg + dlon_deg);
    }
    if (o->valid[2]) {
        o->alt_m += off_m[2];
    }
    if (off_norm_m != NULL) {
        *off_norm_m = sqrt(off_m[0] * off_m[0] + off_m[1] * off_m[1] + off_m[2] * off_m[2]);
    }
}

/* After a value that moves the prediction was stored: the new offset keeps
 * the drawn position where it was at te (drawn_before), on the axes that
 * were predicted; a disagreement over snap_m is snapped to and counted. */
static void position_event(ft_pose_state *ps, const pos_pred *before, uint64_t te)
{
    pos_pred after;
    predict_position(ps, te, &after);
    double meridian_m = 0.0, normal_m = 0.0;
    ft_wgs84_radii_m(after.lat_deg, &meridian_m, &normal_m);
    const double cos_lat = cos(after.lat_deg * FT_RAD_PER_DEG);
    const int horiz = (before->axes & FT_POSE_PRED_HORIZONTAL) != 0;
    const int vert = (before->axes & FT_POSE_PRED_VERTICAL) != 0;
    double d_m[3] = {0.0, 0.0, 0.0};
    if (horiz && before->valid[0] && after.valid[0]) {
        d_m[0] = (before->lat_deg - after.lat_deg) * FT_RAD_PER_DEG * (meridian_m + after.alt_m);
    }
    if (horiz && before->valid[1] && after.valid[1] && cos_lat > FT_POSE_POLE_COS_MIN) {
        d_m[1] = ft_wrap_deg_pm180(before->lon_deg - after.lon_deg) * FT_RAD_PER_DEG *
                 (normal_m + after.alt_m) * cos_lat;
    }
    if (vert && before->valid[2] && after.valid[2]) {
        d_m[2] = before->alt_m - after.alt_m;
    }
    const double norm_m = sqrt(d_m[0] * d_m[0] + d_m[1] * d_m[1] + d_m[2] * d_m[2]);
    if (!(norm_m <= ps->snap_m)) {
        const uint64_t merge_ns = (uint64_t)FT_POSE_SNAP_MERGE_MS * FT_NS_PER_MS;
        /* a difference: a sum near the end of the clock would wrap */
        if (ps->snap_count == 0u || ft_ns_sub_sat(te, ps->last_snap_t_ns) > merge_ns) {
            ++ps->snap_count;
        }
        ps->last_snap_t_ns = te;
        d_m[0] = d_m[1] = d_m[2] = 0.0;
    } else if (norm_m > ps->offset_max_m && ps->converge_ms > 0u) {
        ps->offset_max_m = norm_m;
    }
    for (int k = 0; k < 3; ++k) {
        ps->offset_m[k] = ps->converge_ms > 0u ? d_m[k] : 0.0;
    }
    ps->offset_t_ns = te;
}

ft_status ft_pose_state_apply(ft_pose_state *ps, const ft_pose_input *in, int *applied,
                              ft_error *err)
{
    if (applied != NULL) {
        *applied = 0;
    }
    if (ps == NULL || in == NULL) {
        return ft_fail(err, FT_ERR_ARG, "pose state: no state or input");
    }
    if ((int)in->qty < 0 || in->qty >= FT_QTY_COUNT) {
        return ft_fail(err, FT_ERR_ARG, "pose state: unknown quantity %d", (int)in->qty);
    }
    if (!isfinite(in->value)) {
        return ft_fail(err, FT_ERR_NUMERIC, "pose state: %s is not finite",
                       ft_pose_qty_name(in->qty));
    }
    if (in->timeout_ms == 0u) {
        return ft_fail(err, FT_ERR_ARG, "pose state: %s has timeout 0 ms",
                       ft_pose_qty_name(in->qty));
    }
    ft_pose_sample *s = &ps->s[in->qty];
    if (s->valid) {
        if (in->t_ns < s->t_ns) {
            ++ps->dropped_older_count;
            return FT_OK;
        }
        if (in->priority > s->priority && !sample_stale(s, in->t_ns)) {
            ++ps->dropped_priority_count;
            return FT_OK;
        }
    }
    /* The drawn position just before the value, at the event time (never
     * before the previous event: a value may be older than another
     * quantity's, and the offset must not be moved back). */
    const int moves = moves_position(in->qty);
    const uint64_t te = in->t_ns > ps->offset_t_ns ? in->t_ns : ps->offset_t_ns;
    pos_pred before = {0};
    if (moves) {
        drawn_position(ps, te, &before, NULL);
    }
    s->value = in->value;
    s->t_ns = in->t_ns;
    s->timeout_ms = in->timeout_ms;
    s->source_id = in->source_id;
    s->priority = in->priority;
    s->valid = 1u;
    ++ps->applied_count;
    if (moves) {
        position_event(ps, &before, te);
    }
    if (applied != NULL) {
        *applied = 1;
    }
    return FT_OK;
}

uint32_t ft_pose_state_stale(const ft_pose_state *ps, uint64_t t_ns, char *reason, size_t cap)
{
    return ft_pose_state_stale_in(ps, t_ns, FT_QTY_ALL_MASK, reason, cap);
}

uint32_t ft_pose_state_stale_in(const ft_pose_state *ps, uint64_t t_ns, uint32_t mask_in,
                                char *reason, size_t cap)
{
    mask_in &= FT_QTY_ALL_MASK;
    if (reason != NULL && cap > 0u) {
        reason[0] = '\0';
    }
    if (ps == NULL) {
        if (reason != NULL && cap > 0u) {
            (void)snprintf(reason, cap, "no pose state");
        }
        return mask_in;
    }
    uint32_t mask = 0u;
    int first = -1;
    unsigned more = 0u;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        if ((mask_in & FT_QTY_BIT(q)) != 0u && sample_stale(&ps->s[q], t_ns)) {
            mask |= FT_QTY_BIT(q);
            if (first < 0) {
                first = q;
            } else {
                ++more;
            }
        }
    }
    if (first >= 0 && reason != NULL && cap > 0u) {
        const ft_pose_sample *s = &ps->s[first];
        char extra[24] = "";
        if (more > 0u) {
            (void)snprintf(extra, sizeof extra, " (+%u more)", more);
        }
        if (!s->valid) {
            (void)snprintf(reason, cap, "no %s received%s", k_qty_name[first], extra);
        } else {
            (void)snprintf(reason, cap, "no %s for %" PRIu64 " ms%s", k_qty_name[first],
                           age_ns(s, t_ns) / FT_NS_PER_MS, extra);
        }
    }
    return mask;
}

void ft_pose_state_estimate(const ft_pose_state *ps, uint64_t t_ns, ft_pose_estimate *out)
{
    if (out == NULL) {
        return;
    }
    ft_pose_estimate zero = {0};
    *out = zero;
    out->attitude.w = 1.0;
    if (ps == NULL) {
        out->stale_mask = FT_QTY_ALL_MASK;
        return;
    }
    out->stale_mask = ft_pose_state_stale(ps, t_ns, NULL, 0u);

    const ft_pose_sample *sh = &ps->s[FT_QTY_HEADING];
    const ft_pose_sample *sp = &ps->s[FT_QTY_PITCH];
    const ft_pose_sample *sr = &ps->s[FT_QTY_ROLL];
    /* Never-received angles read 0 (their stale bits tell the caller). */
    double heading = sh->valid ? sh->value : 0.0;
    double pitch = sp->valid ? sp->value : 0.0;
    double roll = sr->valid ? sr->value : 0.0;
    uint64_t epoch = 0u;
    int have_attitude = 0;
    const ft_pose_sample *att[3] = {sh, sp, sr};
    for (int k = 0; k < 3; ++k) {
        if (att[k]->valid) {
            have_attitude = 1;
            if (att[k]->t_ns > epoch) {
                epoch = att[k]->t_ns;
            }
        }
    }
    int rates_ok = (out->stale_mask & FT_QTY_RATE_MASK) == 0u;
    /* The three angles arrive in separate messages a few ms apart. Before
     * they are combined, bring the older ones to the newest one's time with
     * the Euler angle rates of the current body rates; otherwise a heading
     * 2 ms older than the pitch is drawn 2 ms late (0.8 deg at 400 deg/s).
     * Skipped near pitch +-90 deg, where the Euler rates are singular (the
     * stagger error is then left, bounded by rate * stagger). */
    if (have_attitude && rates_ok && ps->horizon_ms > 0u) {
        const double p = ps->s[FT_QTY_ROLL_RATE].value, q_ = ps->s[FT_QTY_PITCH_RATE].value,
                     r = ps->s[FT_QTY_YAW_RATE].value;
        const double sphi = sin(roll * FT_RAD_PER_DEG), cphi = cos(roll * FT_RAD_PER_DEG);
        const double cth = cos(pitch * FT_RAD_PER_DEG), tth = tan(pitch * FT_RAD_PER_DEG);
        if (fabs(cth) > FT_POSE_ALIGN_COS_MIN) {
            const double roll_rate = p + (q_ * sphi + r * cphi) * tth; /* deg/s */
            const double pitch_rate = q_ * cphi - r * sphi;
            const double heading_rate = (q_ * sphi + r * cphi) / cth;
            const uint64_t horizon_ns = (uint64_t)ps->horizon_ms * FT_NS_PER_MS;
            uint64_t lag_ns[3] = {0u, 0u, 0u};
            for (int k = 0; k < 3; ++k) {
                if (att[k]->valid) {
                    lag_ns[k] = epoch - att[k]->t_ns;
                    lag_ns[k] = lag_ns[k] > horizon_ns ? horizon_ns : lag_ns[k];
                }
            }
            heading += heading_rate * (double)lag_ns[0] * 1e-9;
            pitch += pitch_rate * (double)lag_ns[1] * 1e-9;
            roll += roll_rate * (double)lag_ns[2] * 1e-9;
            if (pitch > 90.0) pitch = 90.0;
            if (pitch < -90.0) pitch = -90.0;
        }
    }
    ft_quat q = ft_quat_from_euler_deg(heading, pitch, roll);
    out->epoch_ns = epoch;

    if (have_attitude && rates_ok && ps->horizon_ms > 0u) {
        uint64_t dt_ns = t_ns > epoch ? t_ns - epoch : 0u;
        uint64_t horizon_ns = (uint64_t)ps->horizon_ms * FT_NS_PER_MS;
        if (dt_ns > horizon_ns) {
            dt_ns = horizon_ns;
            out->horizon_clamped = 1;
        }
        double omega[3] = {ps->s[FT_QTY_ROLL_RATE].value * FT_RAD_PER_DEG,
                           ps->s[FT_QTY_PITCH_RATE].value * FT_RAD_PER_DEG,
                           ps->s[FT_QTY_YAW_RATE].value * FT_RAD_PER_DEG};
        out->predict_s = (double)dt_ns * 1e-9;
        q = ft_quat_integrate_body_rate(q, omega, out->predict_s);
        out->predicted = 1;
    }
    out->attitude = q;
    ft_quat_to_euler_deg(q, &out->pose.heading_deg, &out->pose.pitch_deg, &out->pose.roll_deg);
    pos_pred pos;
    drawn_position(ps, t_ns, &pos, &out->offset_m);
    out->pose.lat_deg = pos.lat_deg;
    out->pose.lon_deg = pos.lon_deg;
    out->pose.alt_m = pos.alt_m;
    out->position_predicted = pos.axes;
    out->position_predict_s = pos.predict_s;
    out->position_clamped = pos.clamped;
}
