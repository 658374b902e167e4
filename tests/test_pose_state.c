/* test_pose_state.c - Euler/quaternion conversions, the exponential-map
 * extrapolator on stiff cases, horizon clamp, staleness and source priority;
 * position prediction from the velocity against closed forms (horizon,
 * stale velocity, convergence of a 5 m fix, snap of a 500 m jump) and the
 * tangent-plane step against the WGS-84 geodesic. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/units.h"
#include "input/pose_state.h"
#include "test_util.h"

#define D2R (FT_PI / 180.0)
#define MS_NS UINT64_C(1000000)

/* Smallest signed difference of two angles in degrees. */
static double ang_diff_deg(double a, double b)
{
    return remainder(a - b, 360.0);
}

static int quat_finite(ft_quat q)
{
    return isfinite(q.w) && isfinite(q.x) && isfinite(q.y) && isfinite(q.z);
}

/* |a - b| up to the sign ambiguity of quaternions. */
static double quat_dist(ft_quat a, ft_quat b)
{
    double dp = fabs(a.w - b.w) + fabs(a.x - b.x) + fabs(a.y - b.y) + fabs(a.z - b.z);
    double dm = fabs(a.w + b.w) + fabs(a.x + b.x) + fabs(a.y + b.y) + fabs(a.z + b.z);
    return dp < dm ? dp : dm;
}

/* Canonical Euler triple for a pitch that may have gone past +-90: going
 * over the top means looking back (heading + 180) and upside down (roll +
 * 180). Returns 0 if the result is too close to gimbal lock to compare. */
static int canonical_euler(double h, double p, double r, double *ho, double *po, double *ro)
{
    p = ft_wrap_deg_pm180(p);
    if (p > 90.0) {
        p = 180.0 - p;
        h += 180.0;
        r += 180.0;
    } else if (p < -90.0) {
        p = -180.0 - p;
        h += 180.0;
        r += 180.0;
    }
    *ho = ft_wrap_deg_0_360(h);
    *po = p;
    *ro = ft_wrap_deg_pm180(r);
    return cos(p * D2R) > 1e-6;
}

static void check_euler(ft_quat q, double h, double p, double r, double tol_deg, int line)
{
    double ho, po, ro, eh, ep, er;
    ft_quat_to_euler_deg(q, &ho, &po, &ro);
    if (!canonical_euler(h, p, r, &eh, &ep, &er)) {
        return;
    }
    if (!(fabs(ang_diff_deg(ho, eh)) <= tol_deg && fabs(po - ep) <= tol_deg &&
          fabs(ang_diff_deg(ro, er)) <= tol_deg)) {
        fprintf(stderr,
                "line %d: euler got (%.12g, %.12g, %.12g) expected (%.12g, %.12g, %.12g)\n", line,
                ho, po, ro, eh, ep, er);
        ++g_ft_test_failures;
    }
    CHECK(ho >= 0.0 && ho < 360.0);
    CHECK(po >= -90.0 && po <= 90.0);
    CHECK(ro > -180.0 && ro <= 180.0);
}

static void test_wrap(void)
{
    CHECK(ft_wrap_deg_0_360(360.0) == 0.0);
    CHECK(ft_wrap_deg_0_360(-1e-15) >= 0.0 && ft_wrap_deg_0_360(-1e-15) < 360.0);
    CHECK_NEAR(ft_wrap_deg_0_360(-90.0), 270.0, 0.0);
    CHECK_NEAR(ft_wrap_deg_0_360(725.0), 5.0, 1e-12);
    CHECK(ft_wrap_deg_pm180(-180.0) == 180.0);
    CHECK(ft_wrap_deg_pm180(180.0) == 180.0);
    CHECK_NEAR(ft_wrap_deg_pm180(190.0), -170.0, 1e-12);
    CHECK_NEAR(ft_wrap_deg_pm180(-190.0), 170.0, 1e-12);
    CHECK(ft_wrap_deg_0_360(NAN) == 0.0);
    CHECK(ft_wrap_deg_pm180(INFINITY) == 0.0);
}

static void test_euler_round_trip(void)
{
    for (int h = -360; h <= 360; h += 30) {
        for (int p = -85; p <= 85; p += 17) {
            for (int r = -180; r <= 180; r += 20) {
                ft_quat q = ft_quat_from_euler_deg(h + 0.25, p + 0.5, r + 0.125);
                CHECK_NEAR(ft_quat_norm(q), 1.0, 1e-15);
                check_euler(q, h + 0.25, p + 0.5, r + 0.125, 1e-9, __LINE__);
            }
        }
    }
    /* Known quaternions: heading 90 is a quarter turn about down (z). */
    ft_quat q = ft_quat_from_euler_deg(90.0, 0.0, 0.0);
    CHECK_NEAR(q.w, sqrt(0.5), 1e-15);
    CHECK_NEAR(q.z, sqrt(0.5), 1e-15);
    q = ft_quat_from_euler_deg(0.0, 90.0, 0.0); /* nose up: about right wing (y) */
    CHECK_NEAR(q.y, sqrt(0.5), 1e-15);
    q = ft_quat_from_euler_deg(0.0, 0.0, 90.0); /* right wing down: about nose (x) */
    CHECK_NEAR(q.x, sqrt(0.5), 1e-15);
}

static void test_gimbal_lock(void)
{
    double h, p, r;
    /* Pitch +90: only heading - roll survives; convention roll = 0. */
    ft_quat_to_euler_deg(ft_quat_from_euler_deg(40.0, 90.0, 10.0), &h, &p, &r);
    CHECK_NEAR(p, 90.0, 1e-9);
    CHECK(r == 0.0);
    CHECK_NEAR(h, 30.0, 1e-9);
    /* Pitch -90: heading + roll survives. */
    ft_quat_to_euler_deg(ft_quat_from_euler_deg(40.0, -90.0, 10.0), &h, &p, &r);
    CHECK_NEAR(p, -90.0, 1e-9);
    CHECK(r == 0.0);
    CHECK_NEAR(h, 50.0, 1e-9);
    /* Lock with a heading that must wrap. */
    ft_quat_to_euler_deg(ft_quat_from_euler_deg(5.0, 90.0, 20.0), &h, &p, &r);
    CHECK_NEAR(h, 345.0, 1e-9);
    CHECK(h >= 0.0 && h < 360.0);
    /* Just off the lock (cos(pitch) = 1.7e-9): finite, pitch close to 90,
     * heading - roll kept; the split itself carries rounding noise of about
     * 1e-16 / cos(pitch) rad, hence the looser tolerance. */
    ft_quat_to_euler_deg(ft_quat_from_euler_deg(40.0, 90.0 - 1e-7, 10.0), &h, &p, &r);
    CHECK(isfinite(h) && isfinite(p) && isfinite(r));
    CHECK_NEAR(p, 90.0 - 1e-7, 1e-9);
    CHECK_NEAR(ang_diff_deg(h - r, 30.0), 0.0, 1e-4);
    /* Degenerate inputs never give NaN. */
    ft_quat zero = {0.0, 0.0, 0.0, 0.0};
    ft_quat_to_euler_deg(zero, &h, &p, &r);
    CHECK(h == 0.0 && p == 0.0 && r == 0.0);
    ft_quat bad = {NAN, 0.0, 1.0, 0.0};
    ft_quat_to_euler_deg(bad, &h, &p, &r);
    CHECK(isfinite(h) && isfinite(p) && isfinite(r));
    /* Slightly non-unit quaternion right at the lock (|C31| rounds past 1). */
    ft_quat big = {sqrt(0.5) * (1.0 + 1e-12), 0.0, sqrt(0.5) * (1.0 + 1e-12), 0.0};
    ft_quat_to_euler_deg(big, &h, &p, &r);
    CHECK(isfinite(h) && isfinite(p) && isfinite(r));
    CHECK_NEAR(p, 90.0, 1e-9);
}

/* Closed form for a constant single-axis body rate: roll rate at any
 * attitude adds to roll; pitch rate with roll 0 adds to pitch; yaw rate
 * with pitch 0 and roll 0 adds to heading. */
static void test_single_axis_closed_form(void)
{
    static const double dts[] = {1e-6, 1e-5, 1e-4, 1e-3, 0.01, 0.1, 0.25, 0.5, 1.0};
    static const double rates[] = {-400.0, -123.4, -1.0, 0.001, 7.5, 90.0, 399.9, 400.0};
    static const double headings[] = {0.0, 10.0, 179.5, 270.0, 359.9};
    for (size_t i = 0; i < sizeof dts / sizeof dts[0]; ++i) {
        for (size_t j = 0; j < sizeof rates / sizeof rates[0]; ++j) {
            for (size_t k = 0; k < sizeof headings / sizeof headings[0]; ++k) {
                double dt = dts[i], rate = rates[j], h0 = headings[k];
                double a = rate * dt;
                /* Roll rate from a pitched, rolled attitude. */
                double w_roll[3] = {rate * D2R, 0.0, 0.0};
                ft_quat q = ft_quat_integrate_body_rate(ft_quat_from_euler_deg(h0, 35.0, -20.0),
                                                        w_roll, dt);
                CHECK(quat_finite(q));
                CHECK_NEAR(ft_quat_norm(q), 1.0, 1e-12);
                check_euler(q, h0, 35.0, -20.0 + a, 1e-9, __LINE__);
                /* Pitch rate with roll 0 (may go over the top). */
                double w_pitch[3] = {0.0, rate * D2R, 0.0};
                q = ft_quat_integrate_body_rate(ft_quat_from_euler_deg(h0, -12.0, 0.0), w_pitch,
                                                dt);
                CHECK(quat_finite(q));
                CHECK_NEAR(ft_quat_norm(q), 1.0, 1e-12);
                check_euler(q, h0, -12.0 + a, 0.0, 1e-9, __LINE__);
                /* Yaw rate, wings level. */
                double w_yaw[3] = {0.0, 0.0, rate * D2R};
                q = ft_quat_integrate_body_rate(ft_quat_from_euler_deg(h0, 0.0, 0.0), w_yaw, dt);
                CHECK(quat_finite(q));
                CHECK_NEAR(ft_quat_norm(q), 1.0, 1e-12);
                check_euler(q, h0 + a, 0.0, 0.0, 1e-9, __LINE__);
                /* The quaternion itself against the closed form too (this is
                 * where a bad small-angle path would show at dt = 1 us). */
                CHECK(quat_dist(q, ft_quat_from_euler_deg(h0 + a, 0.0, 0.0)) < 1e-14);
            }
        }
    }
}

/* Reference: RK4 on qdot = 0.5 q * (0, omega), many small steps. */
static ft_quat rk4_reference(ft_quat q, const double w[3], double dt, int steps)
{
    double h = dt / steps;
    ft_quat om = {0.0, w[0], w[1], w[2]};
    for (int i = 0; i < steps; ++i) {
        ft_quat k[4];
        ft_quat y = q;
        for (int s = 0; s < 4; ++s) {
            ft_quat d = ft_quat_mul(y, om);
            k[s].w = 0.5 * d.w;
            k[s].x = 0.5 * d.x;
            k[s].y = 0.5 * d.y;
            k[s].z = 0.5 * d.z;
            double f = (s < 2) ? 0.5 * h : h;
            if (s < 3) {
                y.w = q.w + f * k[s].w;
                y.x = q.x + f * k[s].x;
                y.y = q.y + f * k[s].y;
                y.z = q.z + f * k[s].z;
            }
        }
        q.w += h / 6.0 * (k[0].w + 2.0 * k[1].w + 2.0 * k[2].w + k[3].w);
        q.x += h / 6.0 * (k[0].x + 2.0 * k[1].x + 2.0 * k[2].x + k[3].x);
        q.y += h / 6.0 * (k[0].y + 2.0 * k[1].y + 2.0 * k[2].y + k[3].y);
        q.z += h / 6.0 * (k[0].z + 2.0 * k[1].z + 2.0 * k[2].z + k[3].z);
    }
    return q;
}

static void test_combined_rates(void)
{
    static const double w_deg[][3] = {
        {400.0, 400.0, 400.0}, {-400.0, 250.0, 33.0}, {1e-3, -400.0, 400.0}, {0.0, 0.0, 0.0}};
    static const double starts[][3] = {
        {0.0, 0.0, 0.0}, {123.0, 45.0, -60.0}, {359.0, -89.0, 179.0}, {10.0, 90.0, 0.0},
        {200.0, -90.0, 30.0}};
    static const double dts[] = {1e-6, 1e-3, 0.1, 1.0};
    for (size_t i = 0; i < sizeof w_deg / sizeof w_deg[0]; ++i) {
        double w[3] = {w_deg[i][0] * D2R, w_deg[i][1] * D2R, w_deg[i][2] * D2R};
        for (size_t s = 0; s < sizeof starts / sizeof starts[0]; ++s) {
            ft_quat q0 = ft_quat_from_euler_deg(starts[s][0], starts[s][1], starts[s][2]);
            for (size_t d = 0; d < sizeof dts / sizeof dts[0]; ++d) {
                double dt = dts[d];
                ft_quat q = ft_quat_integrate_body_rate(q0, w, dt);
                CHECK(quat_finite(q));
                CHECK_NEAR(ft_quat_norm(q), 1.0, 1e-12);
                ft_quat ref = rk4_reference(q0, w, dt, 20000);
                CHECK(quat_dist(q, ref) < 1e-9);
                /* Group property: 1000 equal steps equal one step. */
                ft_quat qs = q0;
                for (int k = 0; k < 1000; ++k) {
                    qs = ft_quat_integrate_body_rate(qs, w, dt / 1000.0);
                }
                CHECK(quat_dist(q, qs) < 1e-12);
                /* Backwards undoes forwards. */
                double wn[3] = {-w[0], -w[1], -w[2]};
                CHECK(quat_dist(ft_quat_integrate_body_rate(q, wn, dt), q0) < 1e-13);
                double h, p, r;
                ft_quat_to_euler_deg(q, &h, &p, &r);
                CHECK(isfinite(h) && isfinite(p) && isfinite(r));
            }
        }
    }
    /* Landing exactly on pitch +90 from level: no NaN, pitch 90. */
    double w_pitch[3] = {90.0 * D2R, 0.0, 0.0};
    w_pitch[0] = 0.0;
    w_pitch[1] = 90.0 * D2R;
    double h, p, r;
    ft_quat_to_euler_deg(ft_quat_integrate_body_rate(ft_quat_from_euler_deg(0.0, 0.0, 0.0),
                                                     w_pitch, 1.0),
                         &h, &p, &r);
    CHECK(isfinite(h) && isfinite(r));
    CHECK_NEAR(p, 90.0, 1e-9);
    CHECK_NEAR(ang_diff_deg(h - r, 0.0), 0.0, 1e-9);
    /* Non-finite rates or dt: attitude unchanged, never NaN. */
    double w_nan[3] = {NAN, 0.0, 0.0};
    ft_quat q0 = ft_quat_from_euler_deg(10.0, 20.0, 30.0);
    CHECK(quat_dist(ft_quat_integrate_body_rate(q0, w_nan, 0.1), q0) < 1e-15);
    CHECK(quat_dist(ft_quat_integrate_body_rate(q0, w_pitch, INFINITY), q0) < 1e-15);
}

static ft_pose_input in_of(ft_pose_qty qty, double v, uint64_t t_ns, uint32_t timeout_ms)
{
    ft_pose_input in;
    memset(&in, 0, sizeof in);
    in.qty = qty;
    in.value = v;
    in.t_ns = t_ns;
    in.timeout_ms = timeout_ms;
    return in;
}

static void apply_ok(ft_pose_state *ps, ft_pose_qty qty, double v, uint64_t t_ns,
                     uint32_t timeout_ms)
{
    ft_pose_input in = in_of(qty, v, t_ns, timeout_ms);
    int applied = 0;
    CHECK(ft_pose_state_apply(ps, &in, &applied, NULL) == FT_OK);
    CHECK(applied == 1);
}

static void feed_attitude(ft_pose_state *ps, double h, double p, double r, double rp, double rq,
                          double rr, uint64_t t_ns)
{
    apply_ok(ps, FT_QTY_HEADING, h, t_ns, 100u);
    apply_ok(ps, FT_QTY_PITCH, p, t_ns, 100u);
    apply_ok(ps, FT_QTY_ROLL, r, t_ns, 100u);
    apply_ok(ps, FT_QTY_ROLL_RATE, rp, t_ns, 100u);
    apply_ok(ps, FT_QTY_PITCH_RATE, rq, t_ns, 100u);
    apply_ok(ps, FT_QTY_YAW_RATE, rr, t_ns, 100u);
}

static void test_estimate_and_horizon(void)
{
    ft_pose_state ps;
    ft_error err = {0};
    CHECK(ft_pose_state_init(&ps, FT_POSE_HORIZON_MAX_MS + 1u, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "horizon") != NULL);
    REQUIRE(ft_pose_state_init(&ps, 1000u, NULL) == FT_OK);
    const uint64_t t0 = UINT64_C(1700000000) * UINT64_C(1000000000);

    /* Heading wrap 359 -> 1 through the yaw rate (200 ms at 10 deg/s). */
    feed_attitude(&ps, 359.0, 0.0, 0.0, 0.0, 0.0, 10.0, t0);
    apply_ok(&ps, FT_QTY_LAT, 46.85, t0, 500u);
    apply_ok(&ps, FT_QTY_LON, -121.76, t0, 500u);
    apply_ok(&ps, FT_QTY_ALT, 3000.0, t0, 500u);
    ft_pose_estimate e;
    ft_pose_state_estimate(&ps, t0 + 90u * MS_NS, &e);
    CHECK(e.predicted == 1 && e.horizon_clamped == 0);
    CHECK_NEAR(e.predict_s, 0.09, 1e-15);
    CHECK_NEAR(e.pose.heading_deg, 359.9, 1e-9);
    CHECK(e.stale_mask == FT_QTY_VELOCITY_MASK); /* never received: position held */
    CHECK(e.position_predicted == 0);
    CHECK_NEAR(e.pose.lat_deg, 46.85, 0.0);
    CHECK_NEAR(e.pose.lon_deg, -121.76, 0.0);
    CHECK_NEAR(e.pose.alt_m, 3000.0, 0.0);
    CHECK_NEAR(ft_quat_norm(e.attitude), 1.0, 1e-12);

    /* Rates stale at 200 ms (timeout 100): attitude held, no prediction. */
    ft_pose_state_estimate(&ps, t0 + 200u * MS_NS, &e);
    CHECK(e.predicted == 0);
    CHECK_NEAR(e.pose.heading_deg, 359.0, 1e-9);
    /* Rates refreshed late (their own time), attitude still from t0. */
    apply_ok(&ps, FT_QTY_ROLL_RATE, 0.0, t0 + 150u * MS_NS, 100u);
    apply_ok(&ps, FT_QTY_PITCH_RATE, 0.0, t0 + 150u * MS_NS, 100u);
    apply_ok(&ps, FT_QTY_YAW_RATE, 10.0, t0 + 150u * MS_NS, 100u);
    ft_pose_state_estimate(&ps, t0 + 200u * MS_NS, &e);
    CHECK(e.predicted == 1);
    CHECK_NEAR(e.pose.heading_deg, 1.0, 1e-9);
    CHECK(e.pose.heading_deg >= 0.0 && e.pose.heading_deg < 360.0);

    /* Roll through 180: 170 + 100 deg/s * 0.2 s = 190 = -170. */
    REQUIRE(ft_pose_state_init(&ps, 1000u, NULL) == FT_OK);
    feed_attitude(&ps, 90.0, 10.0, 170.0, 100.0, 0.0, 0.0, t0);
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    CHECK_NEAR(e.pose.roll_deg, 175.0, 1e-9);
    CHECK_NEAR(e.pose.pitch_deg, 10.0, 1e-9);
    CHECK_NEAR(e.pose.heading_deg, 90.0, 1e-9);
    ft_pose_state_estimate(&ps, t0 + 100u * MS_NS, &e); /* exactly 180 */
    CHECK_NEAR(fabs(e.pose.roll_deg), 180.0, 1e-9);
    CHECK(e.pose.roll_deg > -180.0 && e.pose.roll_deg <= 180.0);
    /* Horizon clamp: default horizon 100 ms; at 400 ms the prediction holds
     * the 100 ms value. */
    REQUIRE(ft_pose_state_init(&ps, FT_POSE_HORIZON_DEFAULT_MS, NULL) == FT_OK);
    feed_attitude(&ps, 90.0, 10.0, 170.0, 100.0, 0.0, 0.0, t0);
    /* Keep rates fresh at the display time so only the horizon limits. */
    apply_ok(&ps, FT_QTY_ROLL_RATE, 100.0, t0 + 380u * MS_NS, 100u);
    apply_ok(&ps, FT_QTY_PITCH_RATE, 0.0, t0 + 380u * MS_NS, 100u);
    apply_ok(&ps, FT_QTY_YAW_RATE, 0.0, t0 + 380u * MS_NS, 100u);
    ft_pose_state_estimate(&ps, t0 + 400u * MS_NS, &e);
    CHECK(e.horizon_clamped == 1);
    CHECK_NEAR(e.predict_s, 0.1, 1e-15);
    CHECK_NEAR(fabs(e.pose.roll_deg), 180.0, 1e-9);
    CHECK(e.epoch_ns == t0);
    /* A display time before the epoch predicts nothing backwards. */
    ft_pose_state_estimate(&ps, t0 - 5u * MS_NS, &e);
    CHECK(e.predict_s == 0.0 && e.horizon_clamped == 0);
    CHECK_NEAR(e.pose.roll_deg, 170.0, 1e-9);
    /* Horizon 0 disables prediction. */
    REQUIRE(ft_pose_state_init(&ps, 0u, NULL) == FT_OK);
    feed_attitude(&ps, 90.0, 10.0, 170.0, 100.0, 0.0, 0.0, t0);
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    CHECK(e.predict_s == 0.0);
    CHECK_NEAR(e.pose.roll_deg, 170.0, 1e-9);

    /* Stiff: 400 deg/s about every axis at once for the whole 1 s horizon,
     * against RK4; and pitch exactly +90 input. */
    REQUIRE(ft_pose_state_init(&ps, 1000u, NULL) == FT_OK);
    feed_attitude(&ps, 0.0, 90.0, 0.0, 400.0, -400.0, 400.0, t0);
    for (uint64_t dt_us = 1u; dt_us <= 1000000u; dt_us *= 10u) {
        apply_ok(&ps, FT_QTY_ROLL_RATE, 400.0, t0 + dt_us * 1000u, 100u);
        apply_ok(&ps, FT_QTY_PITCH_RATE, -400.0, t0 + dt_us * 1000u, 100u);
        apply_ok(&ps, FT_QTY_YAW_RATE, 400.0, t0 + dt_us * 1000u, 100u);
        ft_pose_state_estimate(&ps, t0 + dt_us * 1000u, &e);
        CHECK(e.predicted == 1);
        CHECK(isfinite(e.pose.heading_deg) && isfinite(e.pose.pitch_deg) &&
              isfinite(e.pose.roll_deg));
        CHECK_NEAR(ft_quat_norm(e.attitude), 1.0, 1e-12);
        double w[3] = {400.0 * D2R, -400.0 * D2R, 400.0 * D2R};
        ft_quat ref = rk4_reference(ft_quat_from_euler_deg(0.0, 90.0, 0.0), w,
                                    (double)dt_us * 1e-6, 20000);
        CHECK(quat_dist(e.attitude, ref) < 1e-9);
    }
    /* Epoch is the newest of the three attitude samples. */
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    feed_attitude(&ps, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, t0);
    apply_ok(&ps, FT_QTY_ROLL, 1.0, t0 + 7u * MS_NS, 100u);
    ft_pose_state_estimate(&ps, t0 + 10u * MS_NS, &e);
    CHECK(e.epoch_ns == t0 + 7u * MS_NS);
    CHECK_NEAR(e.predict_s, 0.003, 1e-15);
}

static void test_staleness(void)
{
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    char reason[FT_POSE_REASON_MAX];
    const uint64_t t0 = UINT64_C(5000000000);

    /* Nothing received yet. */
    CHECK(ft_pose_state_stale(&ps, t0, reason, sizeof reason) == FT_QTY_ALL_MASK);
    CHECK(strcmp(reason, "no pitch received (+11 more)") == 0);
    ft_pose_estimate e;
    ft_pose_state_estimate(&ps, t0, &e);
    CHECK(e.stale_mask == FT_QTY_ALL_MASK && e.predicted == 0);
    CHECK(e.pose.heading_deg == 0.0 && e.pose.pitch_deg == 0.0 && e.pose.roll_deg == 0.0);
    CHECK(e.pose.lat_deg == 0.0 && e.pose.alt_m == 0.0);

    feed_attitude(&ps, 10.0, 2.0, 3.0, 0.0, 0.0, 0.0, t0);
    apply_ok(&ps, FT_QTY_LAT, 1.0, t0, 500u);
    apply_ok(&ps, FT_QTY_LON, 2.0, t0, 500u);
    apply_ok(&ps, FT_QTY_ALT, 3.0, t0, 500u);
    CHECK(ft_pose_state_stale(&ps, t0, reason, sizeof reason) == FT_QTY_VELOCITY_MASK);
    CHECK(strcmp(reason, "no ground speed received (+2 more)") == 0);
    apply_ok(&ps, FT_QTY_GROUND_SPEED, 0.0, t0, 500u);
    apply_ok(&ps, FT_QTY_TRACK, 0.0, t0, 500u);
    apply_ok(&ps, FT_QTY_ALT_RATE, 0.0, t0, 500u);
    CHECK(ft_pose_state_stale(&ps, t0, reason, sizeof reason) == 0u);
    CHECK(reason[0] == '\0');
    /* Exactly at the timeout is still fresh; one ns later it is stale. */
    CHECK(ft_pose_state_stale(&ps, t0 + 100u * MS_NS, NULL, 0u) == 0u);
    CHECK(ft_pose_state_stale(&ps, t0 + 100u * MS_NS + 1u, NULL, 0u) ==
          (FT_QTY_ATTITUDE_MASK | FT_QTY_RATE_MASK));
    /* A sample time after the query time counts as age 0. */
    CHECK(ft_pose_state_stale(&ps, t0 - 1000u * MS_NS, NULL, 0u) == 0u);

    /* 250 ms on: attitude and rates stale (100 ms), position fresh (500). */
    CHECK(ft_pose_state_stale(&ps, t0 + 250u * MS_NS, reason, sizeof reason) ==
          (FT_QTY_ATTITUDE_MASK | FT_QTY_RATE_MASK));
    CHECK(strcmp(reason, "no pitch for 250 ms (+5 more)") == 0);
    /* Pitch and roll come back; heading does not. */
    apply_ok(&ps, FT_QTY_PITCH, 2.0, t0 + 240u * MS_NS, 100u);
    apply_ok(&ps, FT_QTY_ROLL, 3.0, t0 + 240u * MS_NS, 100u);
    uint32_t m = ft_pose_state_stale(&ps, t0 + 250u * MS_NS, reason, sizeof reason);
    CHECK(m == (FT_QTY_BIT(FT_QTY_HEADING) | FT_QTY_RATE_MASK));
    CHECK(strcmp(reason, "no heading for 250 ms (+3 more)") == 0);
    /* Small buffer: truncated, terminated. */
    char tiny[8];
    (void)ft_pose_state_stale(&ps, t0 + 250u * MS_NS, tiny, sizeof tiny);
    CHECK(strlen(tiny) == sizeof tiny - 1u);
    /* Recovery. */
    feed_attitude(&ps, 10.0, 2.0, 3.0, 0.0, 0.0, 0.0, t0 + 245u * MS_NS);
    CHECK(ft_pose_state_stale(&ps, t0 + 250u * MS_NS, reason, sizeof reason) == 0u);
    CHECK(reason[0] == '\0');
    /* Position goes stale at its own timeout. */
    m = ft_pose_state_stale(&ps, t0 + 600u * MS_NS, reason, sizeof reason);
    CHECK((m & FT_QTY_POSITION_MASK) == FT_QTY_POSITION_MASK);
    CHECK(ft_pose_state_stale(NULL, t0, reason, sizeof reason) == FT_QTY_ALL_MASK);
}

static void test_apply_rules(void)
{
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    ft_error err = {0};
    int applied = -1;
    const uint64_t t0 = UINT64_C(1000000000);

    /* Bad inputs change nothing. */
    ft_pose_input in = in_of(FT_QTY_ALT, NAN, t0, 500u);
    CHECK(ft_pose_state_apply(&ps, &in, &applied, &err) == FT_ERR_NUMERIC);
    CHECK(applied == 0 && ps.s[FT_QTY_ALT].valid == 0u);
    CHECK(strstr(err.text, "altitude") != NULL);
    in = in_of(FT_QTY_ALT, INFINITY, t0, 500u);
    CHECK(ft_pose_state_apply(&ps, &in, NULL, NULL) == FT_ERR_NUMERIC);
    in = in_of(FT_QTY_ALT, 1.0, t0, 0u);
    CHECK(ft_pose_state_apply(&ps, &in, NULL, NULL) == FT_ERR_ARG);
    in = in_of(FT_QTY_COUNT, 1.0, t0, 100u);
    CHECK(ft_pose_state_apply(&ps, &in, NULL, NULL) == FT_ERR_ARG);
    CHECK(ft_pose_state_apply(&ps, NULL, NULL, NULL) == FT_ERR_ARG);
    CHECK(ps.applied_count == 0u);

    /* Baro (priority 0) and GPS height (priority 1) both feed altitude. */
    ft_pose_input baro = in_of(FT_QTY_ALT, 1000.0, t0, 500u);
    baro.source_id = 320u;
    ft_pose_input gps = in_of(FT_QTY_ALT, 1040.0, t0 + 10u * MS_NS, 500u);
    gps.priority = 1u;
    gps.source_id = 1038u;
    CHECK(ft_pose_state_apply(&ps, &baro, &applied, NULL) == FT_OK && applied == 1);
    CHECK(ft_pose_state_apply(&ps, &gps, &applied, NULL) == FT_OK && applied == 0);
    CHECK(ps.dropped_priority_count == 1u);
    CHECK(ps.s[FT_QTY_ALT].value == 1000.0);
    /* Baro silent past its timeout: GPS takes over. */
    gps.t_ns = t0 + 600u * MS_NS;
    CHECK(ft_pose_state_apply(&ps, &gps, &applied, NULL) == FT_OK && applied == 1);
    CHECK(ps.s[FT_QTY_ALT].value == 1040.0 && ps.s[FT_QTY_ALT].source_id == 1038u);
    /* Baro back: it wins again at once. */
    baro.t_ns = t0 + 610u * MS_NS;
    baro.value = 1001.0;
    CHECK(ft_pose_state_apply(&ps, &baro, &applied, NULL) == FT_OK && applied == 1);
    CHECK(ps.s[FT_QTY_ALT].value == 1001.0 && ps.s[FT_QTY_ALT].priority == 0u);
    /* Out of order: an older sample never replaces a newer one. */
    baro.t_ns = t0 + 605u * MS_NS;
    baro.value = 999.0;
    CHECK(ft_pose_state_apply(&ps, &baro, &applied, NULL) == FT_OK && applied == 0);
    CHECK(ps.dropped_older_count == 1u);
    CHECK(ps.s[FT_QTY_ALT].value == 1001.0);
    CHECK(strcmp(ft_pose_qty_name(FT_QTY_YAW_RATE), "yaw rate") == 0);
    CHECK(strcmp(ft_pose_qty_unit(FT_QTY_ALT), "m") == 0);
    CHECK(strcmp(ft_pose_qty_name(FT_QTY_COUNT), "?") == 0);
}

/* ---- position prediction and convergence ------------------------------------ */

/* North and east metres from (lat0, lon0) to (lat, lon), radii at lat0. */
static void ne_m(double lat0, double lon0, double h, double lat, double lon, double *n_m,
                 double *e_m)
{
    double m = 0.0, nv = 0.0;
    ft_wgs84_radii_m(lat0, &m, &nv);
    *n_m = (lat - lat0) * D2R * (m + h);
    *e_m = remainder(lon - lon0, 360.0) * D2R * (nv + h) * cos(lat0 * D2R);
}

/* A straight flight at constant velocity (north, east, up m/s) from
 * (lat0, lon0, alt0) at t0, in the tangent plane at the start. */
typedef struct straight {
    double lat0, lon0, alt0, v_n, v_e, v_u;
    uint64_t t0;
} straight;

static void straight_at(const straight *f, uint64_t t_ns, double *lat, double *lon, double *alt)
{
    double m = 0.0, nv = 0.0;
    ft_wgs84_radii_m(f->lat0, &m, &nv);
    const double dt = t_ns >= f->t0 ? (double)(t_ns - f->t0) * 1e-9 : -(double)(f->t0 - t_ns) * 1e-9;
    *lat = f->lat0 + f->v_n * dt / (m + f->alt0) / D2R;
    *lon = f->lon0 + f->v_e * dt / ((nv + f->alt0) * cos(f->lat0 * D2R)) / D2R;
    *alt = f->alt0 + f->v_u * dt;
}

/* A fix (lat, lon 1 ms later, alt 2 ms later) of the flight, moved by
 * (dn, de) metres, then its velocity 3 ms later. */
static void send_fix(ft_pose_state *ps, const straight *f, uint64_t t_ns, double dn_m, double de_m,
                     int with_velocity)
{
    double lat, lon, alt, m = 0.0, nv = 0.0;
    ft_wgs84_radii_m(f->lat0, &m, &nv);
    straight_at(f, t_ns, &lat, &lon, &alt);
    apply_ok(ps, FT_QTY_LAT, lat + dn_m / (m + f->alt0) / D2R, t_ns, 500u);
    straight_at(f, t_ns + MS_NS, &lat, &lon, &alt);
    apply_ok(ps, FT_QTY_LON, lon + de_m / ((nv + f->alt0) * cos(f->lat0 * D2R)) / D2R,
             t_ns + MS_NS, 500u);
    straight_at(f, t_ns + 2u * MS_NS, &lat, &lon, &alt);
    apply_ok(ps, FT_QTY_ALT, alt, t_ns + 2u * MS_NS, 500u);
    if (with_velocity) {
        apply_ok(ps, FT_QTY_GROUND_SPEED, hypot(f->v_n, f->v_e), t_ns + 3u * MS_NS, 500u);
        apply_ok(ps, FT_QTY_TRACK, ft_wrap_deg_0_360(atan2(f->v_e, f->v_n) / D2R),
                 t_ns + 3u * MS_NS, 500u);
        apply_ok(ps, FT_QTY_ALT_RATE, f->v_u, t_ns + 3u * MS_NS, 500u);
    }
}

static void test_position_prediction(void)
{
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    const uint64_t t0 = UINT64_C(1700000000) * UINT64_C(1000000000);
    const double lat0 = 46.5, lon0 = 8.0, alt0 = 1000.0;
    double m = 0.0, nv = 0.0;
    ft_wgs84_radii_m(lat0, &m, &nv);
    /* radii against their closed forms at the equator and the pole */
    double m_eq = 0.0, n_eq = 0.0, m_po = 0.0, n_po = 0.0;
    ft_wgs84_radii_m(0.0, &m_eq, &n_eq);
    ft_wgs84_radii_m(90.0, &m_po, &n_po);
    CHECK_NEAR(n_eq, 6378137.0, 1e-6);
    CHECK_NEAR(m_eq, 6335439.327, 1e-3);
    CHECK_NEAR(m_po, n_po, 1e-6);
    CHECK_NEAR(n_po, 6399593.626, 1e-3);

    apply_ok(&ps, FT_QTY_LAT, lat0, t0, 500u);
    apply_ok(&ps, FT_QTY_LON, lon0, t0 + MS_NS, 500u);
    apply_ok(&ps, FT_QTY_ALT, alt0, t0 + 2u * MS_NS, 500u);
    ft_pose_estimate e;
    /* no velocity yet: held, as without prediction */
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    CHECK(e.position_predicted == 0 && e.position_predict_s == 0.0);
    CHECK(e.pose.lat_deg == lat0 && e.pose.lon_deg == lon0 && e.pose.alt_m == alt0);
    /* 250 m/s on track 045, climbing 10 m/s: each component from its own time */
    apply_ok(&ps, FT_QTY_GROUND_SPEED, 250.0, t0 + 3u * MS_NS, 500u);
    apply_ok(&ps, FT_QTY_TRACK, 45.0, t0 + 3u * MS_NS, 500u);
    apply_ok(&ps, FT_QTY_ALT_RATE, 10.0, t0 + 3u * MS_NS, 500u);
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    const double v_n = 250.0 * cos(45.0 * D2R), v_e = 250.0 * sin(45.0 * D2R);
    CHECK(e.position_predicted == (FT_POSE_PRED_HORIZONTAL | FT_POSE_PRED_VERTICAL));
    CHECK_NEAR(e.position_predict_s, 0.050, 1e-12);
    CHECK(e.position_clamped == 0);
    CHECK_NEAR(e.pose.lat_deg, lat0 + v_n * 0.050 / (m + alt0) / D2R, 1e-12);
    CHECK_NEAR(e.pose.lon_deg, lon0 + v_e * 0.049 / ((nv + alt0) * cos(lat0 * D2R)) / D2R, 1e-12);
    CHECK_NEAR(e.pose.alt_m, alt0 + 10.0 * 0.048, 1e-9);
    CHECK(e.offset_m < 1e-9);
    /* beyond the horizon (100 ms) the prediction holds its value there */
    ft_pose_state_estimate(&ps, t0 + 180u * MS_NS, &e);
    CHECK(e.position_clamped == 1);
    CHECK_NEAR(e.position_predict_s, 0.1, 1e-12);
    CHECK_NEAR(e.pose.lat_deg, lat0 + v_n * 0.1 / (m + alt0) / D2R, 1e-12);
    CHECK_NEAR(e.pose.alt_m, alt0 + 1.0, 1e-9);
    /* horizon 0: nothing predicted */
    ps.horizon_ms = 0u;
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    CHECK(e.position_predicted == 0 && e.pose.lat_deg == lat0 && e.pose.alt_m == alt0);
    ps.horizon_ms = 100u;

    /* bad velocity values change nothing */
    ft_pose_input in = in_of(FT_QTY_GROUND_SPEED, NAN, t0 + 10u * MS_NS, 500u);
    CHECK(ft_pose_state_apply(&ps, &in, NULL, NULL) == FT_ERR_NUMERIC);
    in = in_of(FT_QTY_TRACK, INFINITY, t0 + 10u * MS_NS, 500u);
    CHECK(ft_pose_state_apply(&ps, &in, NULL, NULL) == FT_ERR_NUMERIC);
    ft_pose_state_estimate(&ps, t0 + 50u * MS_NS, &e);
    CHECK_NEAR(e.pose.lat_deg, lat0 + v_n * 0.050 / (m + alt0) / D2R, 1e-12);
    CHECK(ps.s[FT_QTY_GROUND_SPEED].value == 250.0);

    /* set_convergence checks its ranges */
    ft_error err = {0};
    CHECK(ft_pose_state_set_convergence(&ps, FT_POSE_CONVERGE_MAX_MS + 1u, 100.0, &err) ==
          FT_ERR_ARG);
    CHECK(ft_pose_state_set_convergence(&ps, 300u, 0.5, &err) == FT_ERR_ARG);
    CHECK(ft_pose_state_set_convergence(&ps, 300u, NAN, &err) == FT_ERR_ARG);
    CHECK(strstr(err.text, "snap") != NULL);
    CHECK(ps.converge_ms == FT_POSE_CONVERGE_DEFAULT_MS && ps.snap_m == FT_POSE_SNAP_DEFAULT_M);
}

/* The velocity goes silent mid-flight: the prediction stops at its timeout
 * (the position held where it was then), the next fix is drawn at once. */
static void test_position_stale_velocity(void)
{
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    const uint64_t t0 = UINT64_C(1700000000) * UINT64_C(1000000000);
    const straight f = {46.5, 8.0, 1000.0, 200.0, -50.0, 5.0, t0};
    send_fix(&ps, &f, t0, 0.0, 0.0, 1); /* velocity at t0 + 3 ms, stale after t0 + 503 ms */
    for (uint64_t k = 1u; k <= 4u; ++k) {
        send_fix(&ps, &f, t0 + k * 100u * MS_NS, 0.0, 0.0, 0);
    }
    ft_pose_estimate e, e2;
    double lat, lon, alt;
    /* still fresh at 450 ms: on the flight */
    ft_pose_state_estimate(&ps, t0 + 450u * MS_NS, &e);
    straight_at(&f, t0 + 450u * MS_NS, &lat, &lon, &alt);
    double dn, de;
    ne_m(lat, lon, alt, e.pose.lat_deg, e.pose.lon_deg, &dn, &de);
    CHECK(e.position_predicted == 3);
    CHECK(fabs(dn) < 1e-3 && fabs(de) < 1e-3 && fabs(e.pose.alt_m - alt) < 1e-6);
    /* stale at 503 ms: from then on the drawn position stays put */
    send_fix(&ps, &f, t0 + 500u * MS_NS, 0.0, 0.0, 0);
    ft_pose_state_estimate(&ps, t0 + 503u * MS_NS, &e);
    CHECK(e.position_predicted == 3);
    straight_at(&f, t0 + 503u * MS_NS, &lat, &lon, &alt);
    ne_m(lat, lon, alt, e.pose.lat_deg, e.pose.lon_deg, &dn, &de);
    if (!(fabs(dn) < 1e-3 && fabs(de) < 1e-3 && fabs(e.pose.alt_m - alt) < 1e-6)) {
        fprintf(stderr, "at the velocity timeout: dn %.3e de %.3e dalt %.3e m\n", dn, de,
                e.pose.alt_m - alt);
        CHECK(0);
    }
    /* (what is left of the convergence of earlier fixes, micrometres here,
     * still decays: equal within 1e-4 m) */
    for (uint64_t t_ms = 504u; t_ms < 600u; t_ms += 16u) {
        ft_pose_state_estimate(&ps, t0 + t_ms * MS_NS, &e2);
        CHECK(e2.position_predicted == 0);
        CHECK((e2.stale_mask & FT_QTY_VELOCITY_MASK) == FT_QTY_VELOCITY_MASK);
        ne_m(e.pose.lat_deg, e.pose.lon_deg, alt, e2.pose.lat_deg, e2.pose.lon_deg, &dn, &de);
        CHECK(fabs(dn) < 1e-4 && fabs(de) < 1e-4 && fabs(e2.pose.alt_m - e.pose.alt_m) < 1e-4);
    }
    /* the next fix: drawn as it is, no convergence, no snap */
    send_fix(&ps, &f, t0 + 600u * MS_NS, 0.0, 0.0, 0);
    ft_pose_state_estimate(&ps, t0 + 610u * MS_NS, &e);
    CHECK(e.position_predicted == 0 && e.offset_m == 0.0);
    CHECK(e.pose.lat_deg == ps.s[FT_QTY_LAT].value && e.pose.lon_deg == ps.s[FT_QTY_LON].value &&
          e.pose.alt_m == ps.s[FT_QTY_ALT].value);
    CHECK(ps.snap_count == 0u);
    /* the velocity returns: prediction again from the held fix */
    send_fix(&ps, &f, t0 + 700u * MS_NS, 0.0, 0.0, 1);
    ft_pose_state_estimate(&ps, t0 + 750u * MS_NS, &e);
    straight_at(&f, t0 + 750u * MS_NS, &lat, &lon, &alt);
    ne_m(lat, lon, alt, e.pose.lat_deg, e.pose.lon_deg, &dn, &de);
    CHECK(e.position_predicted == 3);
    CHECK(fabs(dn) < 1e-3 && fabs(de) < 1e-3 && fabs(e.pose.alt_m - alt) < 1e-6);
}

/* A fix 5 m off (a persistent GPS bias from then on): reached smoothly,
 * drawn = truth + 5 (1 - exp(-(t - te) / tau)); a 500 m jump (GPS reset):
 * snapped to and counted once per fix; converge_ms 0: at once. */
static void test_position_convergence(void)
{
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    REQUIRE(ft_pose_state_set_convergence(&ps, 300u, 100.0, NULL) == FT_OK);
    const uint64_t t0 = UINT64_C(1700000000) * UINT64_C(1000000000);
    const double v = 120.0, tau_s = 0.3;
    const straight f = {46.5, 8.0, 1000.0, v, 0.0, 0.0, t0};
    const uint64_t period_ns = 16666667u, t_bias = t0 + 1000u * MS_NS;
    const double period_s = (double)period_ns * 1e-9;
    double prev_n = 0.0, prev_e = 0.0, max_step = 0.0, max_closed_err = 0.0, max_err_before = 0.0;
    uint64_t next_fix = t0;
    int have_prev = 0;
    for (uint64_t t = t0 + 5u * MS_NS; t < t0 + 3000u * MS_NS; t += period_ns) {
        while (next_fix <= t) {
            send_fix(&ps, &f, next_fix, next_fix >= t_bias ? 5.0 : 0.0, 0.0, 1);
            next_fix += 100u * MS_NS;
        }
        ft_pose_estimate e;
        ft_pose_state_estimate(&ps, t, &e);
        double n, ea;
        ne_m(f.lat0, f.lon0, f.alt0, e.pose.lat_deg, e.pose.lon_deg, &n, &ea);
        double lat, lon, alt, tn, te_m;
        straight_at(&f, t, &lat, &lon, &alt);
        ne_m(f.lat0, f.lon0, f.alt0, lat, lon, &tn, &te_m);
        const double want = t < t_bias ? 0.0
                                       : 5.0 * (1.0 - exp(-(double)(t - t_bias) * 1e-9 / tau_s));
        const double err = fabs(n - tn - want) + fabs(ea - te_m);
        if (t < t_bias) {
            max_err_before = fmax(max_err_before, err);
        } else {
            max_closed_err = fmax(max_closed_err, err);
        }
        if (have_prev) {
            max_step = fmax(max_step, hypot(n - prev_n, ea - prev_e));
        }
        prev_n = n;
        prev_e = ea;
        have_prev = 1;
    }
    printf("convergence of a 5 m fix: closed-form error %.2e m (before %.2e m), largest frame "
           "step %.4f m (speed x period %.4f m, bound %.4f m), offset max %.4f m\n",
           max_closed_err, max_err_before, max_step, v * period_s,
           v * period_s + 5.0 * period_s / tau_s, ps.offset_max_m);
    CHECK(max_err_before < 1e-3);
    CHECK(max_closed_err < 1e-3);
    CHECK(max_step <= v * period_s + 5.0 * period_s / tau_s + 1e-3);
    CHECK(max_step <= 1.5 * v * period_s);
    CHECK(ps.snap_count == 0u);
    CHECK_NEAR(ps.offset_max_m, 5.0, 1e-3);

    /* GPS reset: 500 m north and 300 m east. Latitude and longitude come 1 ms
     * apart: one snap. The drawn position is the new fix's prediction at once. */
    const uint64_t t_reset = next_fix;
    send_fix(&ps, &f, t_reset, 505.0, 300.0, 1);
    CHECK(ps.snap_count == 1u);
    ft_pose_estimate e;
    ft_pose_state_estimate(&ps, t_reset + 10u * MS_NS, &e);
    CHECK(e.offset_m == 0.0);
    double n, ea, lat, lon, alt, tn, te_m;
    ne_m(f.lat0, f.lon0, f.alt0, e.pose.lat_deg, e.pose.lon_deg, &n, &ea);
    straight_at(&f, t_reset + 10u * MS_NS, &lat, &lon, &alt);
    ne_m(f.lat0, f.lon0, f.alt0, lat, lon, &tn, &te_m);
    CHECK_NEAR(n - tn, 505.0, 1e-3);
    CHECK_NEAR(ea - te_m, 300.0, 1e-3);
    CHECK_NEAR(ps.offset_max_m, 5.0, 1e-3); /* a snap is not a convergence */
    /* the next fixes agree with it: nothing more */
    send_fix(&ps, &f, t_reset + 100u * MS_NS, 505.0, 300.0, 1);
    CHECK(ps.snap_count == 1u);
    /* and a reset back 1 s later is a second snap */
    for (uint64_t k = 2u; k <= 10u; ++k) {
        send_fix(&ps, &f, t_reset + k * 100u * MS_NS, 505.0, 300.0, 1);
    }
    CHECK(ps.snap_count == 1u);
    send_fix(&ps, &f, t_reset + 1100u * MS_NS, 0.0, 0.0, 1);
    CHECK(ps.snap_count == 2u);

    /* converge_ms 0: a 5 m fix is drawn at once */
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    REQUIRE(ft_pose_state_set_convergence(&ps, 0u, 100.0, NULL) == FT_OK);
    send_fix(&ps, &f, t0, 0.0, 0.0, 1);
    send_fix(&ps, &f, t0 + 100u * MS_NS, 5.0, 0.0, 1);
    ft_pose_state_estimate(&ps, t0 + 101u * MS_NS, &e);
    ne_m(f.lat0, f.lon0, f.alt0, e.pose.lat_deg, e.pose.lon_deg, &n, &ea);
    straight_at(&f, t0 + 101u * MS_NS, &lat, &lon, &alt);
    ne_m(f.lat0, f.lon0, f.alt0, lat, lon, &tn, &te_m);
    CHECK_NEAR(n - tn, 5.0, 1e-3);
    CHECK(ps.snap_count == 0u && ps.offset_max_m == 0.0 && e.offset_m == 0.0);
    /* without velocity nothing converges either (position held as before) */
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    send_fix(&ps, &f, t0, 0.0, 0.0, 0);
    send_fix(&ps, &f, t0 + 100u * MS_NS, 0.0, 0.0, 0);
    ft_pose_state_estimate(&ps, t0 + 150u * MS_NS, &e);
    CHECK(e.pose.lat_deg == ps.s[FT_QTY_LAT].value && e.offset_m == 0.0);
}

/* The tangent-plane step against the geodesic it approximates (a constant
 * velocity vector, no lateral acceleration), integrated on the WGS-84
 * ellipsoid with RK4: the flat step's own error over the horizon. */
static void geodesic(double lat_deg, double lon_deg, double az_deg, double s_m, double *lat_out,
                     double *lon_out)
{
    double y[3] = {lat_deg * D2R, lon_deg * D2R, az_deg * D2R};
    const int steps = 2000;
    const double h = s_m / steps;
    for (int i = 0; i < steps; ++i) {
        double k[4][3], yt[3];
        for (int st = 0; st < 4; ++st) {
            static const double c[4] = {0.0, 0.5, 0.5, 1.0};
            for (int j = 0; j < 3; ++j) {
                yt[j] = y[j] + (st == 0 ? 0.0 : c[st] * h * k[st - 1][j]);
            }
            double m = 0.0, nv = 0.0;
            ft_wgs84_radii_m(yt[0] / D2R, &m, &nv);
            k[st][0] = cos(yt[2]) / m;
            k[st][1] = sin(yt[2]) / (nv * cos(yt[0]));
            k[st][2] = sin(yt[2]) * tan(yt[0]) / nv;
        }
        for (int j = 0; j < 3; ++j) {
            y[j] += h / 6.0 * (k[0][j] + 2.0 * k[1][j] + 2.0 * k[2][j] + k[3][j]);
        }
    }
    *lat_out = y[0] / D2R;
    *lon_out = y[1] / D2R;
}

static void test_position_horizon_error(void)
{
    const uint64_t t0 = UINT64_C(1700000000) * UINT64_C(1000000000);
    static const double lats[] = {0.0, 45.0, 70.0};
    static const double tracks[] = {0.0, 45.0, 90.0, 270.0};
    static const uint32_t horizons_ms[] = {100u, 1000u};
    const double v = 250.0;
    for (size_t hi = 0; hi < 2u; ++hi) {
        double worst = 0.0;
        for (size_t li = 0; li < 3u; ++li) {
            for (size_t ti = 0; ti < 4u; ++ti) {
                ft_pose_state ps;
                REQUIRE(ft_pose_state_init(&ps, horizons_ms[hi], NULL) == FT_OK);
                apply_ok(&ps, FT_QTY_LAT, lats[li], t0, 2000u);
                apply_ok(&ps, FT_QTY_LON, 8.0, t0, 2000u);
                apply_ok(&ps, FT_QTY_ALT, 0.0, t0, 2000u);
                apply_ok(&ps, FT_QTY_GROUND_SPEED, v, t0, 2000u);
                apply_ok(&ps, FT_QTY_TRACK, tracks[ti], t0, 2000u);
                ft_pose_estimate e;
                const double dt_s = horizons_ms[hi] * 1e-3;
                ft_pose_state_estimate(&ps, t0 + (uint64_t)horizons_ms[hi] * MS_NS, &e);
                double lat, lon, dn, de;
                geodesic(lats[li], 8.0, tracks[ti], v * dt_s, &lat, &lon);
                ne_m(lat, lon, 0.0, e.pose.lat_deg, e.pose.lon_deg, &dn, &de);
                const double err = hypot(dn, de);
                const double bound =
                    (v * dt_s) * (v * dt_s) * (fabs(tan(lats[li] * D2R)) + 0.01) / 6.3e6;
                if (!(err <= bound)) {
                    fprintf(stderr, "lat %g track %g %u ms: error %.3e m > %.3e m\n", lats[li],
                            tracks[ti], horizons_ms[hi], err, bound);
                    CHECK(0);
                }
                worst = fmax(worst, err);
            }
        }
        printf("tangent-plane step against the WGS-84 geodesic, 250 m/s over %u ms, lat 0..70: "
               "worst %.2e m\n",
               horizons_ms[hi], worst);
    }
}

int main(void)
{
    test_wrap();
    test_euler_round_trip();
    test_gimbal_lock();
    test_single_axis_closed_form();
    test_combined_rates();
    test_estimate_and_horizon();
    test_staleness();
    test_apply_rules();
    test_position_prediction();
    test_position_stale_velocity();
    test_position_convergence();
    test_position_horizon_error();
    return ft_test_result("test_pose_state");
}
