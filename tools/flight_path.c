/* flight_path.c - flight path model and CANaerospace log writer (contract in
 * flight_path.h). Fixed-size storage, bounded loops, no recursion; the only
 * libc calls are math, strtod and snprintf, so the output depends on nothing
 * but the inputs. */
#include "flight_path.h"

#include <math.h>

#include "core/ft_ns.h"
#include "core/units.h"
#include "input/canaero.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FP_MIN_SPEED_M_S 0.5 /* below this a direction is noise */
#define FP_SUBSTEPS 8u       /* position integration steps per built-in waypoint */

/* ---- small helpers ---------------------------------------------------------- */

/* Where a message points: "NAME line 7" for a file, "NAME at 12.500 s"
 * for a built-in path. */
static void where(const flight_path *p, uint32_t i, char *buf, size_t cap)
{
    if (p->wp[i].line > 0u) {
        (void)snprintf(buf, cap, "%s line %u", p->name, (unsigned)p->wp[i].line);
    } else {
        (void)snprintf(buf, cap, "%s at %.3f s", p->name, p->wp[i].t_s);
    }
}

/* North, east, up metres from a to b on the sphere, flat over one segment
 * (the segments are short enough for the chord to be the arc). */
static void delta_m(const flight_waypoint *a, const flight_waypoint *b, double d[3])
{
    double lat_mid_rad = 0.5 * (a->lat_deg + b->lat_deg) * FT_RAD_PER_DEG;
    d[0] = (b->lat_deg - a->lat_deg) * FT_RAD_PER_DEG * FLIGHT_EARTH_RADIUS_M;
    d[1] = ft_wrap_deg_pm180(b->lon_deg - a->lon_deg) * FT_RAD_PER_DEG * FLIGHT_EARTH_RADIUS_M *
           cos(lat_mid_rad);
    d[2] = b->alt_m - a->alt_m;
}

/* Velocity (north, east, up m/s) of the straight segment a -> b at latitude
 * lat_deg and altitude alt_m, as a GPS receiver reports it: the rates of
 * latitude, longitude and altitude in metres on the WGS-84 ellipsoid. */
static void segment_velocity(const flight_waypoint *a, const flight_waypoint *b, double lat_deg,
                             double alt_m, double v[3])
{
    const double dt = b->t_s - a->t_s;
    double m = 0.0, n = 0.0;
    ft_wgs84_radii_m(lat_deg, &m, &n);
    v[0] = (b->lat_deg - a->lat_deg) / dt * FT_RAD_PER_DEG * (m + alt_m);
    v[1] = ft_wrap_deg_pm180(b->lon_deg - a->lon_deg) / dt * FT_RAD_PER_DEG * (n + alt_m) *
           cos(lat_deg * FT_RAD_PER_DEG);
    v[2] = (b->alt_m - a->alt_m) / dt;
}

static double quat_dot(ft_quat a, ft_quat b)
{
    return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}

/* ---- waypoint checks -------------------------------------------------------- */

typedef struct field_range {
    const char *name;
    double lo, hi;
} field_range;

/* Same ranges as the CANaerospace default map, so every waypoint can be sent. */
static const field_range k_fields[7] = {
    {"t_s", 0.0, FLIGHT_TIME_MAX_S},   {"lat_deg", -90.0, 90.0},
    {"lon_deg", -180.0, 180.0},        {"alt_m", -1000.0, 25000.0},
    {"heading_deg", -360.0, 360.0},    {"pitch_deg", -90.0, 90.0},
    {"roll_deg", -180.0, 180.0},
};

static ft_status check_value(const char *loc, uint32_t field, double v, ft_error *err)
{
    const field_range *r = &k_fields[field];
    if (isnan(v)) {
        return ft_fail(err, FT_ERR_NUMERIC, "%s: %s is NaN", loc, r->name);
    }
    if (!isfinite(v)) {
        return ft_fail(err, FT_ERR_NUMERIC, "%s: %s is infinite", loc, r->name);
    }
    if (v < r->lo || v > r->hi) {
        return ft_fail(err, FT_ERR_NUMERIC, "%s: %s %g is outside [%g, %g]", loc, r->name, v,
                       r->lo, r->hi);
    }
    return FT_OK;
}

ft_status flight_path_add(flight_path *p, const flight_waypoint *w, ft_error *err)
{
    if (p == NULL || w == NULL) {
        return ft_fail(err, FT_ERR_ARG, "flight path: no path or waypoint");
    }
    char loc[96];
    if (w->line > 0u) {
        (void)snprintf(loc, sizeof loc, "%s line %u", p->name, (unsigned)w->line);
    } else {
        (void)snprintf(loc, sizeof loc, "%s waypoint %u", p->name, (unsigned)p->count + 1u);
    }
    if (p->count >= FLIGHT_WAYPOINTS_MAX) {
        return ft_fail(err, FT_ERR_BUDGET, "%s: more than %u waypoints (FLIGHT_WAYPOINTS_MAX)",
                       loc, FLIGHT_WAYPOINTS_MAX);
    }
    const double v[7] = {w->t_s,         w->lat_deg,   w->lon_deg, w->alt_m,
                         w->heading_deg, w->pitch_deg, w->roll_deg};
    uint32_t nfields = w->has_attitude ? 7u : 4u;
    for (uint32_t f = 0u; f < nfields; ++f) {
        ft_status s = check_value(loc, f, v[f], err);
        if (s != FT_OK) {
            return s;
        }
    }
    if (p->count > 0u) {
        const flight_waypoint *prev = &p->wp[p->count - 1u];
        if (!(w->t_s > prev->t_s)) {
            char ploc[96];
            where(p, p->count - 1u, ploc, sizeof ploc);
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s: time %.6g s is not after the previous waypoint's %.6g s (%s)",
                           loc, w->t_s, prev->t_s, ploc);
        }
        if (w->t_s - p->wp[0].t_s > FLIGHT_DURATION_MAX_S) {
            return ft_fail(err, FT_ERR_OVERSIZED,
                           "%s: time %.6g s makes the path longer than %g s", loc, w->t_s,
                           FLIGHT_DURATION_MAX_S);
        }
    }
    flight_waypoint c = *w;
    if (!c.has_attitude) {
        c.heading_deg = c.pitch_deg = c.roll_deg = 0.0;
    }
    p->wp[p->count++] = c;
    p->finished = 0u;
    return FT_OK;
}

/* ---- finishing: derived attitude, quaternions, rates ------------------------ */

static void derive_attitude(flight_path *p)
{
    uint32_t n = p->count;
    double prev_heading_deg = 0.0;
    for (uint32_t i = 0u; i < n; ++i) {
        flight_waypoint *w = &p->wp[i];
        if (w->has_attitude) {
            prev_heading_deg = w->heading_deg;
            continue;
        }
        uint32_t ia = i > 0u ? i - 1u : i;
        uint32_t ib = i + 1u < n ? i + 1u : i;
        double d[3];
        delta_m(&p->wp[ia], &p->wp[ib], d);
        double dt = p->wp[ib].t_s - p->wp[ia].t_s;
        double vn = d[0] / dt, ve = d[1] / dt, vu = d[2] / dt;
        double vh = hypot(vn, ve);
        double heading = prev_heading_deg;
        double pitch = 0.0, roll = 0.0;
        if (vh >= FP_MIN_SPEED_M_S) {
            heading = ft_wrap_deg_0_360(atan2(ve, vn) * FT_DEG_PER_RAD);
        }
        if (hypot(vh, vu) >= FP_MIN_SPEED_M_S) {
            pitch = atan2(vu, vh) * FT_DEG_PER_RAD;
        }
        if (i > 0u && i + 1u < n && vh >= FP_MIN_SPEED_M_S) {
            double din[3], dout[3];
            delta_m(&p->wp[i - 1u], w, din);
            delta_m(w, &p->wp[i + 1u], dout);
            double tin = w->t_s - p->wp[i - 1u].t_s, tout = p->wp[i + 1u].t_s - w->t_s;
            if (hypot(din[0], din[1]) / tin >= FP_MIN_SPEED_M_S &&
                hypot(dout[0], dout[1]) / tout >= FP_MIN_SPEED_M_S) {
                double turn_deg = ft_wrap_deg_pm180((atan2(dout[1], dout[0]) -
                                                     atan2(din[1], din[0])) * FT_DEG_PER_RAD);
                /* the segment headings hold at the segment midpoints */
                double turn_rad_s = turn_deg * FT_RAD_PER_DEG / (0.5 * (tin + tout));
                roll = atan(vh * turn_rad_s / FLIGHT_G_M_S2) * FT_DEG_PER_RAD;
                if (roll > FLIGHT_DERIVED_ROLL_MAX_DEG) {
                    roll = FLIGHT_DERIVED_ROLL_MAX_DEG;
                } else if (roll < -FLIGHT_DERIVED_ROLL_MAX_DEG) {
                    roll = -FLIGHT_DERIVED_ROLL_MAX_DEG;
                }
            }
        }
        w->heading_deg = heading;
        w->pitch_deg = pitch;
        w->roll_deg = roll;
        prev_heading_deg = heading;
    }
}

ft_status flight_path_finish(flight_path *p, ft_error *err)
{
    if (p == NULL) {
        return ft_fail(err, FT_ERR_ARG, "flight path: no path");
    }
    p->finished = 0u;
    uint32_t n = p->count;
    if (n < 2u || n > FLIGHT_WAYPOINTS_MAX) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: needs 2..%u waypoints, has %u", p->name,
                       FLIGHT_WAYPOINTS_MAX, (unsigned)n);
    }
    char loc[96], ploc[96];
    /* The log is sampled every FLIGHTGEN_PERIOD_US: a shorter path gives an
     * empty log (or one without a position fix) that looks like success. */
    const double span_s = p->wp[n - 1u].t_s - p->wp[0].t_s;
    if (!(span_s >= FLIGHT_DURATION_MIN_S)) {
        where(p, n - 1u, loc, sizeof loc);
        where(p, 0u, ploc, sizeof ploc);
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: the path lasts %.6g s (%s to %s), shorter than one log period of "
                       "%g s: the log would not hold one full set of frames",
                       p->name, span_s, ploc, loc, FLIGHT_DURATION_MIN_S);
    }
    for (uint32_t i = 1u; i < n; ++i) {
        double dt = p->wp[i].t_s - p->wp[i - 1u].t_s;
        double d[3];
        delta_m(&p->wp[i - 1u], &p->wp[i], d);
        double speed = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / dt;
        if (!(dt > 0.0) || !(speed <= FLIGHT_SPEED_MAX_M_S)) {
            where(p, i, loc, sizeof loc);
            where(p, i - 1u, ploc, sizeof ploc);
            return ft_fail(err, FT_ERR_NUMERIC,
                           "%s: %.1f m in %.6g s from %s is %.0f m/s, at most %g m/s", loc,
                           sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), dt, ploc, speed,
                           FLIGHT_SPEED_MAX_M_S);
        }
        /* the velocity frames must pass the decoder's ranges too (the
         * ellipsoid's radii differ from the sphere's by up to 0.7 %) */
        double v[3];
        segment_velocity(&p->wp[i - 1u], &p->wp[i], p->wp[i - 1u].lat_deg, p->wp[i - 1u].alt_m, v);
        if (!(hypot(v[0], v[1]) <= FLIGHT_SPEED_MAX_M_S) ||
            !(fabs(v[2]) <= FLIGHT_VSPEED_MAX_M_S)) {
            where(p, i, loc, sizeof loc);
            where(p, i - 1u, ploc, sizeof ploc);
            return ft_fail(err, FT_ERR_NUMERIC,
                           "%s: from %s the ground speed is %.0f m/s and the vertical speed "
                           "%.0f m/s, at most %g and %g m/s",
                           loc, ploc, hypot(v[0], v[1]), v[2], FLIGHT_SPEED_MAX_M_S,
                           FLIGHT_VSPEED_MAX_M_S);
        }
    }
    derive_attitude(p);
    for (uint32_t i = 0u; i < n; ++i) {
        const flight_waypoint *w = &p->wp[i];
        ft_quat q = ft_quat_from_euler_deg(w->heading_deg, w->pitch_deg, w->roll_deg);
        /* q and -q are the same attitude; the sign nearer the previous one
         * makes the slerp take the short way. */
        if (i > 0u && quat_dot(p->q[i - 1u], q) < 0.0) {
            q.w = -q.w;
            q.x = -q.x;
            q.y = -q.y;
            q.z = -q.z;
        }
        p->q[i] = q;
    }
    for (uint32_t i = 0u; i + 1u < n; ++i) {
        ft_quat a = p->q[i], b = p->q[i + 1u];
        ft_quat conj_a = {a.w, -a.x, -a.y, -a.z};
        ft_quat d = ft_quat_mul(conj_a, b); /* body-frame rotation over the segment */
        double nd = ft_quat_norm(d);
        d.w /= nd;
        d.x /= nd;
        d.y /= nd;
        d.z /= nd;
        double s = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        /* rotation angle / s, with its limit 2 / w for tiny angles (w >= 0
         * after the sign alignment) */
        double k = s < 1e-12 ? 2.0 / d.w : 2.0 * atan2(s, d.w) / s;
        double dt = p->wp[i + 1u].t_s - p->wp[i].t_s;
        p->w_rad_s[i][0] = d.x * k / dt;
        p->w_rad_s[i][1] = d.y * k / dt;
        p->w_rad_s[i][2] = d.z * k / dt;
        static const char *const k_axis[3] = {"roll rate", "pitch rate", "yaw rate"};
        for (uint32_t a3 = 0u; a3 < 3u; ++a3) {
            double r_deg_s = p->w_rad_s[i][a3] * FT_DEG_PER_RAD;
            if (!(fabs(r_deg_s) <= FLIGHT_RATE_MAX_DEG_S)) {
                where(p, i + 1u, loc, sizeof loc);
                where(p, i, ploc, sizeof ploc);
                return ft_fail(err, FT_ERR_NUMERIC,
                               "%s: the attitude change from %s needs a %s of %.4g deg/s, "
                               "at most %g deg/s",
                               loc, ploc, k_axis[a3], r_deg_s, FLIGHT_RATE_MAX_DEG_S);
            }
        }
    }
    p->w_rad_s[n - 1u][0] = p->w_rad_s[n - 1u][1] = p->w_rad_s[n - 1u][2] = 0.0;
    p->finished = 1u;
    return FT_OK;
}

/* ---- waypoint file ---------------------------------------------------------- */

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* One line (no '\n'), comment already cut. Returns 0 for an empty line, 1 for
 * a waypoint in *w, or a failure in err. */
static ft_status parse_line(const flight_path *p, char *buf, uint32_t line_no, flight_waypoint *w,
                            int *has, ft_error *err)
{
    static const char *const k_names[7] = {"t_s",         "lat_deg",   "lon_deg", "alt_m",
                                           "heading_deg", "pitch_deg", "roll_deg"};
    double v[7] = {0};
    uint32_t nf = 0u;
    char *c = buf;
    *has = 0;
    /* at most FLIGHT_LINE_MAX characters, so at most that many tokens */
    for (uint32_t guard = 0u; guard <= FLIGHT_LINE_MAX; ++guard) {
        while (*c != '\0' && is_space(*c)) {
            ++c;
        }
        if (*c == '\0') {
            break;
        }
        char *tok = c;
        while (*c != '\0' && !is_space(*c)) {
            ++c;
        }
        char saved = *c;
        *c = '\0';
        if (nf >= 7u) {
            *c = saved;
            return ft_fail(err, FT_ERR_FORMAT,
                           "%s line %u: more than 7 numbers (t_s lat_deg lon_deg alt_m "
                           "[heading_deg pitch_deg roll_deg])",
                           p->name, (unsigned)line_no);
        }
        char *end = NULL;
        double x = strtod(tok, &end);
        if (end == tok || *end != '\0') {
            return ft_fail(err, FT_ERR_FORMAT, "%s line %u: %s '%.40s' is not a number", p->name,
                           (unsigned)line_no, k_names[nf], tok);
        }
        v[nf++] = x;
        *c = saved;
    }
    if (nf == 0u) {
        return FT_OK;
    }
    if (nf != 4u && nf != 7u) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s line %u: %u numbers, expected 4 (t_s lat_deg lon_deg alt_m) or 7 "
                       "(... heading_deg pitch_deg roll_deg)",
                       p->name, (unsigned)line_no, (unsigned)nf);
    }
    memset(w, 0, sizeof *w);
    w->t_s = v[0];
    w->lat_deg = v[1];
    w->lon_deg = v[2];
    w->alt_m = v[3];
    w->has_attitude = nf == 7u;
    if (w->has_attitude) {
        w->heading_deg = v[4];
        w->pitch_deg = v[5];
        w->roll_deg = v[6];
    }
    w->line = line_no;
    *has = 1;
    return FT_OK;
}

ft_status flight_path_parse_waypoints(flight_path *p, const char *text, size_t len,
                                      const char *name, ft_error *err)
{
    if (p == NULL || (text == NULL && len > 0u)) {
        return ft_fail(err, FT_ERR_ARG, "waypoints: no path or text");
    }
    memset(p, 0, sizeof *p);
    (void)snprintf(p->name, sizeof p->name, "%s", name != NULL ? name : "waypoints");
    size_t i = 0u;
    uint32_t line_no = 0u;
    /* each turn consumes at least one byte (the '\n') or ends the text */
    while (i < len) {
        ++line_no;
        size_t start = i;
        while (i < len && text[i] != '\n') {
            ++i;
        }
        size_t n = i - start;
        if (i < len) {
            ++i; /* the '\n' */
        }
        if (n > FLIGHT_LINE_MAX) {
            return ft_fail(err, FT_ERR_OVERSIZED, "%s line %u: longer than %u characters",
                           p->name, (unsigned)line_no, FLIGHT_LINE_MAX);
        }
        char buf[FLIGHT_LINE_MAX + 1u];
        memcpy(buf, text + start, n);
        buf[n] = '\0';
        if (memchr(buf, '\0', n) != NULL) {
            return ft_fail(err, FT_ERR_FORMAT, "%s line %u: contains a NUL byte", p->name,
                           (unsigned)line_no);
        }
        char *hash = strchr(buf, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        flight_waypoint w;
        int has = 0;
        ft_status s = parse_line(p, buf, line_no, &w, &has, err);
        if (s == FT_OK && has) {
            s = flight_path_add(p, &w, err);
        }
        if (s != FT_OK) {
            return s;
        }
    }
    return flight_path_finish(p, err);
}

/* ---- sampling --------------------------------------------------------------- */

double flight_path_t0_s(const flight_path *p)
{
    return (p != NULL && p->count > 0u) ? p->wp[0].t_s : 0.0;
}

double flight_path_duration_s(const flight_path *p)
{
    return (p != NULL && p->count > 1u) ? p->wp[p->count - 1u].t_s - p->wp[0].t_s : 0.0;
}

static void hold(const flight_path *p, uint32_t i, flight_sample *out)
{
    const flight_waypoint *w = &p->wp[i];
    out->lat_deg = w->lat_deg;
    out->lon_deg = w->lon_deg;
    out->alt_m = w->alt_m;
    out->q = p->q[i];
    ft_quat_to_euler_deg(out->q, &out->heading_deg, &out->pitch_deg, &out->roll_deg);
}

void flight_path_sample(const flight_path *p, double t_s, flight_sample *out)
{
    if (out == NULL) {
        return;
    }
    memset(out, 0, sizeof *out);
    out->q.w = 1.0;
    if (p == NULL || !p->finished || p->count < 2u || !isfinite(t_s)) {
        return;
    }
    uint32_t n = p->count;
    if (t_s < p->wp[0].t_s) {
        hold(p, 0u, out);
        return;
    }
    if (t_s > p->wp[n - 1u].t_s) {
        hold(p, n - 1u, out);
        return;
    }
    /* segment i with t_i <= t < t_i+1 (the last segment also takes t_end);
     * binary search: at most 11 halvings of 1024 */
    uint32_t lo = 0u, hi = n - 1u;
    while (hi - lo > 1u) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (p->wp[mid].t_s <= t_s) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const flight_waypoint *a = &p->wp[lo], *b = &p->wp[lo + 1u];
    double dt = t_s - a->t_s;
    double f = dt / (b->t_s - a->t_s);
    out->lat_deg = a->lat_deg + f * (b->lat_deg - a->lat_deg);
    out->lon_deg = ft_wrap_deg_pm180(a->lon_deg + f * ft_wrap_deg_pm180(b->lon_deg - a->lon_deg));
    out->alt_m = a->alt_m + f * (b->alt_m - a->alt_m);
    out->q = ft_quat_integrate_body_rate(p->q[lo], p->w_rad_s[lo], dt);
    ft_quat_to_euler_deg(out->q, &out->heading_deg, &out->pitch_deg, &out->roll_deg);
    out->p_deg_s = p->w_rad_s[lo][0] * FT_DEG_PER_RAD;
    out->q_deg_s = p->w_rad_s[lo][1] * FT_DEG_PER_RAD;
    out->r_deg_s = p->w_rad_s[lo][2] * FT_DEG_PER_RAD;
    double v[3];
    segment_velocity(a, b, out->lat_deg, out->alt_m, v);
    out->v_n_m_s = v[0];
    out->v_e_m_s = v[1];
    out->v_u_m_s = v[2];
}

/* ---- built-in paths --------------------------------------------------------- */

static const char *const k_builtin_names[FLIGHT_BUILTIN_COUNT] = {"orbit", "climb", "dive",
                                                                   "turn360", "valley"};

int flight_builtin_from_name(const char *name)
{
    if (name == NULL) {
        return -1;
    }
    for (int k = 0; k < (int)FLIGHT_BUILTIN_COUNT; ++k) {
        if (strcmp(name, k_builtin_names[k]) == 0) {
            return k;
        }
    }
    return -1;
}

const char *flight_builtin_name(flight_builtin_kind k)
{
    return ((int)k >= 0 && k < FLIGHT_BUILTIN_COUNT) ? k_builtin_names[k] : "?";
}

void flight_builtin_defaults(flight_builtin_params *bp, flight_builtin_kind kind)
{
    if (bp == NULL) {
        return;
    }
    bp->kind = kind;
    bp->centre_lat_deg = FLIGHT_DEFAULT_CENTRE_LAT_DEG;
    bp->centre_lon_deg = FLIGHT_DEFAULT_CENTRE_LON_DEG;
    bp->alt_m = NAN;
    bp->duration_s = NAN;
    bp->radius_m = NAN;
    bp->speed_m_s = NAN;
}

/* Per path: default altitude (m), speed (m/s), duration (s; orbit: NAN = one
 * revolution). Speeds are typical for the manoeuvre: a light aircraft's
 * orbit and turn, an airliner's climb, a jet's dive and low-level run. */
static const struct {
    double alt_m, speed_m_s, duration_s;
} k_builtin_defaults[FLIGHT_BUILTIN_COUNT] = {
    {1000.0, 60.0, NAN},  /* orbit */
    {50.0, 130.0, 900.0}, /* climb: 50 m -> 10000 m */
    {3000.0, 120.0, 60.0}, /* dive */
    {300.0, 70.0, 100.0}, /* turn360 */
    {150.0, 100.0, 120.0}, /* valley */
};

#define ORBIT_RADIUS_DEFAULT_M 2000.0
#define CLIMB_TOP_M 10000.0
#define CLIMB_GAMMA_MAX_DEG 30.0
#define DIVE_GAMMA_DEG 30.0
#define DIVE_MIN_ALT_M 50.0
#define TURN_LEAD_S 5.0   /* straight before and after the turn */
#define TURN_RAMP_S 3.0   /* roll-in / roll-out time, at least */
#define BANK_MAX_DEG 60.0 /* built-in manoeuvres stay within a normal envelope */

typedef struct builtin_ctx {
    flight_builtin_kind kind;
    double lat0_deg, lon0_deg, alt0_m, speed_m_s, duration_s, radius_m;
    double climb_gamma_rad;              /* climb */
    double turn_rate_max_rad_s, ramp_s;  /* turn360 */
} builtin_ctx;

/* Heading (rad) and turn rate (rad/s) of turn360 at t: straight for
 * TURN_LEAD_S, the turn rate rises on a half cosine over ramp_s, holds,
 * falls the same way, straight again; the rates integrate to exactly 2 pi. */
static double turn360_heading(const builtin_ctx *c, double t, double *rate)
{
    double wm = c->turn_rate_max_rad_s, tr = c->ramp_s;
    double tt = c->duration_s - 2.0 * TURN_LEAD_S, th = tt - 2.0 * tr;
    double tau = t - TURN_LEAD_S;
    double a1 = wm * tr * 0.5, a2 = a1 + wm * th;
    if (tau <= 0.0) {
        *rate = 0.0;
        return 0.0;
    }
    if (tau < tr) {
        *rate = wm * 0.5 * (1.0 - cos(FT_PI * tau / tr));
        return wm * (0.5 * tau - tr / (2.0 * FT_PI) * sin(FT_PI * tau / tr));
    }
    if (tau < tr + th) {
        *rate = wm;
        return a1 + wm * (tau - tr);
    }
    if (tau < tt) {
        double u = tau - tr - th;
        *rate = wm * 0.5 * (1.0 + cos(FT_PI * u / tr));
        return a2 + wm * (0.5 * u + tr / (2.0 * FT_PI) * sin(FT_PI * u / tr));
    }
    *rate = 0.0;
    return a2 + a1;
}

/* Flight-path angle of the dive (rad, negative down) at fraction f of the
 * duration: level, half-cosine push-over, hold, half-cosine pull-out, level. */
static double dive_gamma(double f)
{
    double gm = DIVE_GAMMA_DEG * FT_RAD_PER_DEG;
    if (f < 0.1) {
        return 0.0;
    }
    if (f < 0.25) {
        return -gm * 0.5 * (1.0 - cos(FT_PI * (f - 0.1) / 0.15));
    }
    if (f < 0.6) {
        return -gm;
    }
    if (f < 0.8) {
        return -gm * 0.5 * (1.0 + cos(FT_PI * (f - 0.6) / 0.2));
    }
    return 0.0;
}

/* Heading (rad), flight-path angle (rad) and turn rate (rad/s) at t. */
static void builtin_motion(const builtin_ctx *c, double t, double *psi, double *gamma,
                           double *turn)
{
    *gamma = 0.0;
    *turn = 0.0;
    switch (c->kind) {
    case FLIGHT_ORBIT:
        /* bearing from the centre starts at 180 (south); clockwise flight
         * heads 90 deg right of the bearing */
        *turn = c->speed_m_s / c->radius_m;
        *psi = FT_PI + *turn * t + 0.5 * FT_PI;
        break;
    case FLIGHT_CLIMB:
        *psi = 0.5 * FT_PI;
        *gamma = c->climb_gamma_rad;
        break;
    case FLIGHT_DIVE:
        *psi = 0.0;
        *gamma = dive_gamma(t / c->duration_s);
        break;
    case FLIGHT_TURN360:
        *psi = turn360_heading(c, t, turn);
        break;
    case FLIGHT_VALLEY:
    default:
        *psi = 0.25 * FT_PI;
        break;
    }
}

static ft_status builtin_setup(const flight_builtin_params *bp, builtin_ctx *c, double step_s,
                               ft_error *err)
{
    const char *nm = flight_builtin_name(bp->kind);
    memset(c, 0, sizeof *c);
    c->kind = bp->kind;
    c->lat0_deg = bp->centre_lat_deg;
    c->lon0_deg = bp->centre_lon_deg;
    if (!(fabs(c->lat0_deg) <= 85.0) || !(fabs(c->lon0_deg) <= 180.0)) {
        return ft_fail(err, FT_ERR_ARG,
                       "path %s: centre %g,%g must be within +-85 deg latitude and +-180 deg "
                       "longitude",
                       nm, c->lat0_deg, c->lon0_deg);
    }
    c->alt0_m = isnan(bp->alt_m) ? k_builtin_defaults[bp->kind].alt_m : bp->alt_m;
    c->speed_m_s = isnan(bp->speed_m_s) ? k_builtin_defaults[bp->kind].speed_m_s : bp->speed_m_s;
    c->radius_m = isnan(bp->radius_m) ? ORBIT_RADIUS_DEFAULT_M : bp->radius_m;
    if (bp->kind == FLIGHT_CLIMB && !isnan(bp->alt_m)) {
        return ft_fail(err, FT_ERR_ARG, "path climb: --alt does not apply (50 m to %g m)",
                       CLIMB_TOP_M);
    }
    if (bp->kind != FLIGHT_ORBIT && !isnan(bp->radius_m)) {
        return ft_fail(err, FT_ERR_ARG, "path %s: --radius applies to orbit only", nm);
    }
    if (!(c->alt0_m >= -1000.0 && c->alt0_m <= 25000.0)) {
        return ft_fail(err, FT_ERR_ARG, "path %s: altitude %g m outside [-1000, 25000]", nm,
                       c->alt0_m);
    }
    if (!(c->speed_m_s >= 10.0 && c->speed_m_s <= 400.0)) {
        return ft_fail(err, FT_ERR_ARG, "path %s: speed %g m/s outside [10, 400]", nm,
                       c->speed_m_s);
    }
    if (!(c->radius_m >= 100.0 && c->radius_m <= 100000.0)) {
        return ft_fail(err, FT_ERR_ARG, "path %s: radius %g m outside [100, 100000]", nm,
                       c->radius_m);
    }
    double dflt = k_builtin_defaults[bp->kind].duration_s;
    if (bp->kind == FLIGHT_ORBIT) {
        dflt = 2.0 * FT_PI * c->radius_m / c->speed_m_s;
    }
    c->duration_s = isnan(bp->duration_s) ? dflt : bp->duration_s;
    if (!(c->duration_s >= FLIGHT_DURATION_MIN_S && c->duration_s <= FLIGHT_DURATION_MAX_S)) {
        return ft_fail(err, FT_ERR_ARG,
                       "path %s: duration %g s outside [%g, %g] (at least one log period)", nm,
                       c->duration_s, FLIGHT_DURATION_MIN_S, FLIGHT_DURATION_MAX_S);
    }
    double v = c->speed_m_s;
    if (bp->kind == FLIGHT_ORBIT) {
        double bank_deg = atan(v * v / (FLIGHT_G_M_S2 * c->radius_m)) * FT_DEG_PER_RAD;
        if (bank_deg > BANK_MAX_DEG) {
            return ft_fail(err, FT_ERR_ARG,
                           "path orbit: %g m/s on a %g m radius needs %.1f deg of bank, at most "
                           "%g",
                           v, c->radius_m, bank_deg, BANK_MAX_DEG);
        }
    } else if (bp->kind == FLIGHT_CLIMB) {
        double vz = (CLIMB_TOP_M - c->alt0_m) / c->duration_s;
        double s = vz / v;
        if (!(s <= sin(CLIMB_GAMMA_MAX_DEG * FT_RAD_PER_DEG))) {
            return ft_fail(err, FT_ERR_ARG,
                           "path climb: %g m in %g s at %g m/s is steeper than %g deg; use a "
                           "longer --duration",
                           CLIMB_TOP_M - c->alt0_m, c->duration_s, v, CLIMB_GAMMA_MAX_DEG);
        }
        c->climb_gamma_rad = asin(s);
    } else if (bp->kind == FLIGHT_TURN360) {
        /* ramps of at least 30 waypoint steps keep the rate change per
         * segment, and so the extrapolation error, small */
        c->ramp_s = fmax(TURN_RAMP_S, 30.0 * step_s);
        double tt = c->duration_s - 2.0 * TURN_LEAD_S;
        if (!(tt >= 2.0 * c->ramp_s + 1.0)) {
            return ft_fail(err, FT_ERR_ARG, "path turn360: duration %g s is too short (at least "
                                            "%g s)",
                           c->duration_s, 2.0 * TURN_LEAD_S + 2.0 * c->ramp_s + 1.0);
        }
        c->turn_rate_max_rad_s = 2.0 * FT_PI / (tt - c->ramp_s);
        double bank_deg = atan(v * c->turn_rate_max_rad_s / FLIGHT_G_M_S2) * FT_DEG_PER_RAD;
        if (bank_deg > BANK_MAX_DEG) {
            return ft_fail(err, FT_ERR_ARG,
                           "path turn360: a 360 deg turn in %g s at %g m/s needs %.1f deg of "
                           "bank, at most %g; use a longer --duration",
                           c->duration_s, v, bank_deg, BANK_MAX_DEG);
        }
    }
    return FT_OK;
}

ft_status flight_path_builtin(flight_path *p, const flight_builtin_params *bp, ft_error *err)
{
    if (p == NULL || bp == NULL || (int)bp->kind < 0 || bp->kind >= FLIGHT_BUILTIN_COUNT) {
        return ft_fail(err, FT_ERR_ARG, "flight path: no path or unknown built-in path");
    }
    memset(p, 0, sizeof *p);
    (void)snprintf(p->name, sizeof p->name, "path %s", flight_builtin_name(bp->kind));
    /* waypoint count from the duration first: the turn ramps depend on it */
    double dur = bp->duration_s;
    if (isnan(dur)) {
        double r = isnan(bp->radius_m) ? ORBIT_RADIUS_DEFAULT_M : bp->radius_m;
        double v = isnan(bp->speed_m_s) ? k_builtin_defaults[bp->kind].speed_m_s : bp->speed_m_s;
        dur = bp->kind == FLIGHT_ORBIT ? 2.0 * FT_PI * r / v : k_builtin_defaults[bp->kind].duration_s;
    }
    uint32_t n = FLIGHT_WAYPOINTS_MAX;
    if (dur > 0.0 && dur / FLIGHT_BUILTIN_STEP_S < (double)(FLIGHT_WAYPOINTS_MAX - 1u)) {
        n = (uint32_t)ceil(dur / FLIGHT_BUILTIN_STEP_S - 1e-9) + 1u;
    }
    if (n < 2u) {
        n = 2u;
    }
    builtin_ctx c;
    ft_status s = builtin_setup(bp, &c, (isfinite(dur) && dur > 0.0) ? dur / (n - 1u) : 1.0, err);
    if (s != FT_OK) {
        return s;
    }
    double step_s = c.duration_s / (double)(n - 1u);
    double m_per_deg_lat = FLIGHT_EARTH_RADIUS_M * FT_RAD_PER_DEG;
    double m_per_deg_lon = m_per_deg_lat * cos(c.lat0_deg * FT_RAD_PER_DEG);
    double north = 0.0, east = 0.0, up = 0.0, t_prev = 0.0;
    for (uint32_t i = 0u; i < n; ++i) {
        double t = (i + 1u == n) ? c.duration_s : step_s * (double)i;
        if (c.kind == FLIGHT_ORBIT) {
            double b = FT_PI + c.speed_m_s / c.radius_m * t;
            north = c.radius_m * cos(b);
            east = c.radius_m * sin(b);
        } else if (i > 0u) {
            /* midpoint rule on the analytic velocity */
            double h = (t - t_prev) / (double)FP_SUBSTEPS;
            for (uint32_t k = 0u; k < FP_SUBSTEPS; ++k) {
                double psi, gamma, turn;
                builtin_motion(&c, t_prev + ((double)k + 0.5) * h, &psi, &gamma, &turn);
                north += c.speed_m_s * cos(gamma) * cos(psi) * h;
                east += c.speed_m_s * cos(gamma) * sin(psi) * h;
                up += c.speed_m_s * sin(gamma) * h;
            }
        }
        double psi, gamma, turn;
        builtin_motion(&c, t, &psi, &gamma, &turn);
        flight_waypoint w;
        memset(&w, 0, sizeof w);
        w.t_s = t;
        w.lat_deg = c.lat0_deg + north / m_per_deg_lat;
        w.lon_deg = ft_wrap_deg_pm180(c.lon0_deg + east / m_per_deg_lon);
        w.alt_m = c.alt0_m + up;
        w.heading_deg = ft_wrap_deg_0_360(psi * FT_DEG_PER_RAD);
        w.pitch_deg = gamma * FT_DEG_PER_RAD;
        /* coordinated turn: lift tilted so its side part is the centripetal
         * force V * turn rate */
        w.roll_deg = atan(c.speed_m_s * turn / FLIGHT_G_M_S2) * FT_DEG_PER_RAD;
        w.has_attitude = 1u;
        if (c.kind == FLIGHT_DIVE && w.alt_m < DIVE_MIN_ALT_M) {
            return ft_fail(err, FT_ERR_ARG,
                           "path dive: reaches %.0f m at %.1f s (below %g m); raise --alt or "
                           "shorten --duration",
                           w.alt_m, t, DIVE_MIN_ALT_M);
        }
        s = flight_path_add(p, &w, err);
        if (s != FT_OK) {
            return s;
        }
        t_prev = t;
    }
    return flight_path_finish(p, err);
}

/* ---- frames and the log ----------------------------------------------------- */

const flightgen_slot flightgen_schedule[FLIGHTGEN_MSG_COUNT] = {
    {FT_QTY_PITCH, 0u, 1u, 0u},
    {FT_QTY_ROLL, 250u, 1u, 0u},
    {FT_QTY_HEADING, 500u, 1u, 0u},
    {FT_QTY_ROLL_RATE, 750u, 1u, 0u},  /* p */
    {FT_QTY_PITCH_RATE, 1000u, 1u, 0u}, /* q */
    {FT_QTY_YAW_RATE, 1250u, 1u, 0u},  /* r */
    {FT_QTY_LAT, 6250u, FLIGHTGEN_POS_DIVIDER, 1u},
    {FT_QTY_LON, 6750u, FLIGHTGEN_POS_DIVIDER, 1u},
    {FT_QTY_ALT, 7250u, FLIGHTGEN_POS_DIVIDER, 0u},
    {FT_QTY_GROUND_SPEED, 7500u, FLIGHTGEN_POS_DIVIDER, 0u},
    {FT_QTY_TRACK, 7750u, FLIGHTGEN_POS_DIVIDER, 0u},
    {FT_QTY_ALT_RATE, 8000u, FLIGHTGEN_POS_DIVIDER, 0u},
};

ft_status flightgen_ids(uint16_t ids[FLIGHTGEN_MSG_COUNT], ft_error *err)
{
    ft_can_map m;
    ft_canaero_default_map(&m);
    for (uint32_t k = 0u; k < FLIGHTGEN_MSG_COUNT; ++k) {
        int found = 0;
        for (uint32_t i = 0u; i < m.count && i < FT_CAN_MAP_MAX; ++i) {
            if (m.e[i].qty == flightgen_schedule[k].qty && m.e[i].priority == 0u) {
                ids[k] = m.e[i].can_id;
                found = 1;
                break;
            }
        }
        if (!found) {
            return ft_fail(err, FT_ERR_CONFIG, "the default CAN map has no primary id for %s",
                           ft_pose_qty_name(flightgen_schedule[k].qty));
        }
    }
    return FT_OK;
}

void flightgen_ground_velocity(double v_n_m_s, double v_e_m_s, double *speed_m_s,
                               double *track_deg)
{
    *speed_m_s = hypot(v_n_m_s, v_e_m_s);
    /* atan2(0, 0) is 0: a hovering path reports track 000 */
    *track_deg = ft_wrap_deg_0_360(atan2(v_e_m_s, v_n_m_s) * FT_DEG_PER_RAD);
}

void flightgen_encode(ft_can_frame *f, uint16_t can_id, uint8_t data_type, uint8_t code,
                      uint32_t data_bits, uint64_t t_ns)
{
    memset(f, 0, sizeof *f);
    f->can_id = can_id;
    f->dlc = 8u;
    f->data[0] = FLIGHTGEN_NODE_ID;
    f->data[1] = data_type;
    f->data[2] = 0u; /* service code */
    f->data[3] = code;
    f->data[4] = (uint8_t)(data_bits >> 24);
    f->data[5] = (uint8_t)(data_bits >> 16);
    f->data[6] = (uint8_t)(data_bits >> 8);
    f->data[7] = (uint8_t)data_bits;
    f->t_ns = t_ns;
}

void flightgen_options_default(flightgen_options *o)
{
    if (o == NULL) {
        return;
    }
    memset(o, 0, sizeof *o);
    o->start_us = FLIGHTGEN_DEFAULT_START_US;
    (void)snprintf(o->iface, sizeof o->iface, "vcan0");
    o->duration_s = NAN;
    o->velocity = 1;
    o->drop_every = 0u;
    o->nan_at_s = o->bad_dlc_at_s = o->duplicate_at_s = NAN;
    o->stall_from_s = o->stall_to_s = NAN;
    o->velocity_stop_s = NAN;
    o->gps_jump_at_s = o->gps_jump_m = NAN;
}

typedef struct gen_out {
    flightgen_sink_fn sink;
    void *ctx;
    const char *iface;
    flightgen_stats *st;
} gen_out;

static ft_status emit(gen_out *g, const ft_can_frame *f, flightgen_msg m, ft_error *err)
{
    ft_candump_record rec;
    memset(&rec, 0, sizeof rec);
    rec.frame = *f;
    (void)snprintf(rec.iface, sizeof rec.iface, "%s", g->iface);
    char line[64];
    size_t len = 0u;
    ft_status s = ft_candump_format(&rec, line, sizeof line, &len, err);
    if (s != FT_OK) {
        return s;
    }
    s = g->sink(g->ctx, &rec, line, len, err);
    if (s != FT_OK) {
        return s;
    }
    if (g->st->lines == 0u) {
        g->st->first_t_ns = f->t_ns;
    }
    g->st->last_t_ns = f->t_ns;
    ++g->st->lines;
    ++g->st->frames[m];
    return FT_OK;
}

static uint32_t float_bits(double v)
{
    float x = (float)v + 0.0f; /* -0 -> +0: the same value, one spelling in the log */
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

/* A fault time (NAN = off) must be finite and inside the logged path
 * [t0, t_end): one outside would never fire (or fire at once) and the log
 * would silently not be what was asked for. */
static ft_status check_time_opt(const char *what, double v, double t0_s, double t_end_s,
                                ft_error *err)
{
    if (isnan(v)) {
        return FT_OK;
    }
    if (!isfinite(v)) {
        return ft_fail(err, FT_ERR_ARG, "%s must be a finite time", what);
    }
    if (!(v >= t0_s && v < t_end_s)) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s %g s is outside the logged path [%g, %g) s (path times)", what, v,
                       t0_s, t_end_s);
    }
    return FT_OK;
}

ft_status flightgen_run(const flight_path *p, const flightgen_options *o, flightgen_sink_fn sink,
                        void *ctx, flightgen_stats *stats, ft_error *err)
{
    flightgen_stats local;
    flightgen_stats *st = stats != NULL ? stats : &local;
    memset(st, 0, sizeof *st);
    if (p == NULL || o == NULL || sink == NULL || !p->finished) {
        return ft_fail(err, FT_ERR_ARG, "no finished path, options or sink");
    }
    const char *nul = memchr(o->iface, '\0', sizeof o->iface);
    size_t if_len = nul != NULL ? (size_t)(nul - o->iface) : sizeof o->iface;
    if (if_len == 0u || if_len > FT_CANDUMP_IFACE_MAX) {
        return ft_fail(err, FT_ERR_ARG, "interface name must be 1..%u characters",
                       FT_CANDUMP_IFACE_MAX);
    }
    if (o->start_us > FLIGHTGEN_START_MAX_US) {
        return ft_fail(err, FT_ERR_ARG, "start time beyond %llu s",
                       (unsigned long long)(FLIGHTGEN_START_MAX_US / 1000000u));
    }
    double dur_s = flight_path_duration_s(p);
    if (!isnan(o->duration_s)) {
        if (!(o->duration_s >= FLIGHT_DURATION_MIN_S && o->duration_s <= dur_s)) {
            return ft_fail(err, FT_ERR_ARG,
                           "duration %g s must be at least one log period (%g s) and at most "
                           "the path's %g s",
                           o->duration_s, FLIGHT_DURATION_MIN_S, dur_s);
        }
        dur_s = o->duration_s;
    }
    const double t0_s = flight_path_t0_s(p), t_end_s = t0_s + dur_s;
    ft_status s = check_time_opt("--nan-at", o->nan_at_s, t0_s, t_end_s, err);
    if (s == FT_OK) {
        s = check_time_opt("--bad-dlc-at", o->bad_dlc_at_s, t0_s, t_end_s, err);
    }
    if (s == FT_OK) {
        s = check_time_opt("--duplicate-at", o->duplicate_at_s, t0_s, t_end_s, err);
    }
    if (s == FT_OK) {
        s = check_time_opt("--velocity-stop", o->velocity_stop_s, t0_s, t_end_s, err);
    }
    if (s == FT_OK) {
        s = check_time_opt("--gps-jump", o->gps_jump_at_s, t0_s, t_end_s, err);
    }
    if (s == FT_OK && !isnan(o->stall_from_s)) {
        s = check_time_opt("--stall FROM", o->stall_from_s, t0_s, t_end_s, err);
    }
    if (s == FT_OK && !isnan(o->gps_jump_at_s) &&
        !(isfinite(o->gps_jump_m) && fabs(o->gps_jump_m) <= 1e6)) {
        s = ft_fail(err, FT_ERR_ARG, "--gps-jump needs a finite distance of at most 1000 km");
    }
    uint16_t ids[FLIGHTGEN_MSG_COUNT];
    if (s == FT_OK) {
        s = flightgen_ids(ids, err);
    }
    if (s != FT_OK) {
        return s;
    }
    int stall = !isnan(o->stall_from_s) || !isnan(o->stall_to_s);
    if (stall && !(isfinite(o->stall_from_s) && isfinite(o->stall_to_s) &&
                   o->stall_from_s < o->stall_to_s)) {
        return ft_fail(err, FT_ERR_ARG, "--stall FROM,TO needs finite FROM < TO");
    }

    gen_out g = {sink, ctx, o->iface, st};
    const double t0 = t0_s;
    uint64_t dur_us = (uint64_t)llround(dur_s * 1e6);
    uint64_t periods = (dur_us + FLIGHTGEN_PERIOD_US - 1u) / FLIGHTGEN_PERIOD_US;
    uint8_t code[FLIGHTGEN_MSG_COUNT] = {0};
    uint64_t att_seq = 0u;
    int nan_todo = !isnan(o->nan_at_s), dlc_todo = !isnan(o->bad_dlc_at_s);
    int dup_todo = !isnan(o->duplicate_at_s);
    ft_can_frame f;
    for (uint64_t k = 0u; k < periods; ++k) {
        for (uint32_t m = 0u; m < FLIGHTGEN_MSG_COUNT; ++m) {
            const flightgen_slot *sl = &flightgen_schedule[m];
            const int is_velocity = m >= FLIGHTGEN_GROUND_SPEED;
            if (k % sl->divider != 0u || (is_velocity && !o->velocity)) {
                continue;
            }
            uint64_t rel_us = k * FLIGHTGEN_PERIOD_US + sl->offset_us;
            uint64_t last_us = rel_us + (sl->is_double ? FLIGHTGEN_HALF_GAP_US : 0u);
            if (last_us >= dur_us) {
                continue; /* a pair is written whole or not at all */
            }
            double t = t0 + (double)rel_us * 1e-6;
            if (stall && t >= o->stall_from_s && t < o->stall_to_s) {
                st->stalled += sl->is_double ? 2u : 1u;
                continue; /* silent sender: no frame, no code used */
            }
            if (is_velocity && t >= o->velocity_stop_s) {
                ++st->velocity_stopped; /* a failed output: silent, no code used */
                continue;
            }
            /* start <= FLIGHTGEN_START_MAX_US and rel < the path's 36000 s
             * keep this far below 2^64 ns; checked all the same */
            uint64_t t_us = 0u, t_ns = 0u;
            const uint64_t tail_ns = (FLIGHTGEN_HALF_GAP_US + FLIGHTGEN_DUP_DELAY_US) * 1000u;
            if (!ft_ns_add(o->start_us, rel_us, &t_us) || !ft_ns_mul(t_us, 1000u, &t_ns) ||
                t_ns > UINT64_MAX - tail_ns) {
                return ft_fail(err, FT_ERR_ARG, "log time past 64-bit nanoseconds");
            }
            flight_sample smp;
            flight_path_sample(p, t, &smp);
            if (sl->is_double) {
                double v = (m == FLIGHTGEN_LAT) ? smp.lat_deg : smp.lon_deg;
                if (m == FLIGHTGEN_LAT && t >= o->gps_jump_at_s) {
                    double mer = 0.0;
                    ft_wgs84_radii_m(smp.lat_deg, &mer, NULL);
                    v += o->gps_jump_m / (mer + smp.alt_m) * FT_DEG_PER_RAD;
                    v = v > 90.0 ? 90.0 : (v < -90.0 ? -90.0 : v);
                    ++st->gps_jumped;
                }
                uint64_t bits;
                memcpy(&bits, &v, sizeof bits);
                flightgen_encode(&f, ids[m], FT_CAN_TYPE_DOUBLEH, code[m]++,
                                 (uint32_t)(bits >> 32), t_ns);
                s = emit(&g, &f, (flightgen_msg)m, err);
                if (s == FT_OK) {
                    flightgen_encode(&f, ids[m], FT_CAN_TYPE_DOUBLEL, code[m]++,
                                     (uint32_t)bits, t_ns + FLIGHTGEN_HALF_GAP_US * 1000u);
                    s = emit(&g, &f, (flightgen_msg)m, err);
                }
                if (s != FT_OK) {
                    return s;
                }
                continue;
            }
            double v;
            switch ((flightgen_msg)m) {
            case FLIGHTGEN_PITCH: v = smp.pitch_deg; break;
            case FLIGHTGEN_ROLL: v = smp.roll_deg; break;
            case FLIGHTGEN_HEADING:
                /* 359.99999 rounds to 360.0f: send the same direction as 0 to
                 * stay in [0, 360) */
                v = ((float)smp.heading_deg >= 360.0f) ? 0.0 : smp.heading_deg;
                break;
            case FLIGHTGEN_ROLL_RATE: v = smp.p_deg_s; break;
            case FLIGHTGEN_PITCH_RATE: v = smp.q_deg_s; break;
            case FLIGHTGEN_YAW_RATE: v = smp.r_deg_s; break;
            case FLIGHTGEN_GROUND_SPEED:
            case FLIGHTGEN_TRACK: {
                double speed = 0.0, track = 0.0;
                flightgen_ground_velocity(smp.v_n_m_s, smp.v_e_m_s, &speed, &track);
                v = speed;
                if (m == FLIGHTGEN_TRACK) {
                    /* as for the heading: 359.99999 would round to 360.0f */
                    v = ((float)track >= 360.0f) ? 0.0 : track;
                }
                break;
            }
            case FLIGHTGEN_ALT_RATE: v = smp.v_u_m_s; break;
            case FLIGHTGEN_ALT:
            default: v = smp.alt_m; break;
            }
            uint8_t this_code = code[m]++;
            if (m <= FLIGHTGEN_HEADING) {
                ++att_seq;
                if (o->drop_every > 0u && att_seq % o->drop_every == 0u) {
                    ++st->dropped; /* lost on the bus: its code is used up */
                    continue;
                }
            }
            uint32_t bits = float_bits(v);
            int dup = 0;
            uint8_t dlc = 8u;
            /* one fault per frame, so each shows as exactly one reject */
            if (nan_todo && m == FLIGHTGEN_PITCH && t >= o->nan_at_s) {
                bits = 0x7FC00000u; /* quiet NaN */
                nan_todo = 0;
                ++st->nan_injected;
            } else if (dlc_todo && t >= o->bad_dlc_at_s) {
                dlc = 7u;
                dlc_todo = 0;
                ++st->bad_dlc_injected;
            } else if (dup_todo && t >= o->duplicate_at_s) {
                dup = 1;
                dup_todo = 0;
                ++st->duplicates_injected;
            }
            flightgen_encode(&f, ids[m], FT_CAN_TYPE_FLOAT, this_code, bits, t_ns);
            if (dlc != 8u) {
                f.dlc = dlc;
                f.data[7] = 0u; /* bytes past the DLC are 0 in ft_can_frame */
            }
            s = emit(&g, &f, (flightgen_msg)m, err);
            if (s == FT_OK && dup) {
                f.t_ns += FLIGHTGEN_DUP_DELAY_US * 1000u;
                s = emit(&g, &f, (flightgen_msg)m, err);
            }
            if (s != FT_OK) {
                return s;
            }
        }
    }
    /* a single-shot fault near the end may find no frame to go to */
    if (nan_todo || dlc_todo || dup_todo) {
        const char *what = nan_todo ? "--nan-at" : (dlc_todo ? "--bad-dlc-at" : "--duplicate-at");
        const double at_s =
            nan_todo ? o->nan_at_s : (dlc_todo ? o->bad_dlc_at_s : o->duplicate_at_s);
        return ft_fail(err, FT_ERR_ARG, "%s %g s: no %s frame at or after it in the log", what,
                       at_s, nan_todo ? "pitch" : "FLOAT");
    }
    return FT_OK;
}
