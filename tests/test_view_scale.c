/* test_view_scale.c - the pixels a vertical metre covers (core/view_scale.h).
 *
 * For random cameras (any heading, pitch -90..90 deg, roll, FOV 10..170 deg)
 * and random boxes in front of them:
 * 1. Bound: at random points of a sub-box that the frustum holds, the image
 *    displacement of a small vertical step, by finite differences of the
 *    projection (camera axes, not the formula), times the point's distance,
 *    is at most the sub-box's gain.
 * 2. Nested: a sub-box never gets a larger gain than its box.
 * 3. Never above the off-axis gain 1 / cos^2 theta bounded over the corners
 *    (what the bound used before), and tighter where a view sees the
 *    vertical across: a level 60 deg 4:3 view's corner gets about 1.39
 *    instead of 1.92, and a view straight down gets about 0 at the nadir. */
#include <math.h>
#include <stdio.h>

#include "core/camera.h"
#include "core/units.h"
#include "core/view_scale.h"
#include "test_util.h"

static unsigned g_rng = 12345u;

static double urand(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (double)(g_rng >> 8) / 16777216.0;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Normalised image position of q (relative to the eye). */
static void image_of(const ft_camera *c, const double q[3], double s[2])
{
    const double z = dot3(q, c->forward);
    s[0] = dot3(q, c->right) / z;
    s[1] = dot3(q, c->up) / z;
}

/* 1 / cos^2 theta bounded over the box's corners (the earlier gain). */
static double offaxis_gain(const ft_camera *c, const double lo[3], const double hi[3])
{
    double cos_min = 1.0;
    for (int corner = 0; corner < 8; ++corner) {
        const double p[3] = {(corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1],
                             (corner & 4) ? hi[2] : lo[2]};
        const double cs = dot3(p, c->forward) / sqrt(dot3(p, p));
        cos_min = (cs < cos_min) ? cs : cos_min;
    }
    const double cc = ft_view_corner_cos(c);
    return (cos_min <= cc) ? 1.0 / (cc * cc) : 1.0 / (cos_min * cos_min);
}

static int make_camera(ft_camera *c, double heading, double pitch, double roll, double fovy,
                       uint32_t w, uint32_t h)
{
    const double eye[3] = {0.0, 0.0, 0.0};
    ft_error err;
    return ft_camera_init(c, eye, heading, pitch, roll, fovy, w, h, 1.0, 1e6, &err) == FT_OK;
}

static void test_random(void)
{
    const double fovs_deg[4] = {10.0, 60.0, 120.0, 170.0};
    long points = 0, bad_bound = 0, bad_nest = 0, above_old = 0;
    double worst_ratio = 0.0;
    for (int cam_i = 0; cam_i < 400; ++cam_i) {
        ft_camera c;
        const double pitch = (cam_i % 10 == 0) ? -0.5 * FT_PI : (urand() - 0.5) * FT_PI;
        REQUIRE(make_camera(&c, urand() * 2.0 * FT_PI, pitch, (urand() - 0.5) * FT_PI,
                            fovs_deg[cam_i % 4] * FT_RAD_PER_DEG, (cam_i & 1) ? 640u : 100u,
                            (cam_i & 1) ? 480u : 700u));
        ft_view_gain_frame g;
        ft_view_gain_frame_from_camera(&c, &g);
        const double ty = tan(0.5 * c.fovy_rad);
        const double tx = ty * (double)c.width_px / (double)c.height_px;
        for (int box_i = 0; box_i < 200; ++box_i) {
            /* a box around a point along a random ray in (or near) the view */
            const double dist = 10.0 + urand() * 20000.0;
            const double x = (urand() * 2.4 - 1.2) * tx, y = (urand() * 2.4 - 1.2) * ty;
            double lo[3], hi[3], slo[3], shi[3];
            for (int a = 0; a < 3; ++a) {
                const double ctr = dist * (c.forward[a] + x * c.right[a] + y * c.up[a]) /
                                   sqrt(1.0 + x * x + y * y);
                const double half = urand() * 0.3 * dist;
                lo[a] = ctr - half;
                hi[a] = ctr + half;
                const double u = urand(), v = urand();
                slo[a] = lo[a] + (hi[a] - lo[a]) * fmin(u, v);
                shi[a] = lo[a] + (hi[a] - lo[a]) * fmax(u, v);
            }
            const double gb = ft_view_vertical_gain(&g, lo, hi);
            const double gs = ft_view_vertical_gain(&g, slo, shi);
            bad_nest += gs > gb * (1.0 + 1e-12);
            above_old += gb > offaxis_gain(&c, lo, hi) * (1.0 + 1e-12);
            for (int p_i = 0; p_i < 8; ++p_i) {
                double q[3], q2[3], s0[2], s1[2];
                for (int a = 0; a < 3; ++a) {
                    q[a] = slo[a] + (shi[a] - slo[a]) * urand();
                }
                const double z = dot3(q, c.forward);
                if (!(z > 0.0)) continue;
                image_of(&c, q, s0);
                if (fabs(s0[0]) > tx || fabs(s0[1]) > ty) continue; /* not drawn */
                const double d = sqrt(dot3(q, q));
                const double step = 1e-6 * d;
                q2[0] = q[0];
                q2[1] = q[1];
                q2[2] = q[2] + step;
                image_of(&c, q2, s1);
                const double moved = hypot(s1[0] - s0[0], s1[1] - s0[1]) / step * d;
                ++points;
                const double ratio = moved / gs;
                worst_ratio = (ratio > worst_ratio) ? ratio : worst_ratio;
                bad_bound += moved > gs * (1.0 + 1e-5) + 1e-9;
            }
        }
    }
    printf("vertical gain: %ld points, %ld above their box's bound (worst ratio %.6f), "
           "%ld sub-boxes above their box, %ld boxes above the off-axis gain\n",
           points, bad_bound, worst_ratio, bad_nest, above_old);
    CHECK(points > 100000);
    CHECK(bad_bound == 0);
    CHECK(bad_nest == 0);
    CHECK(above_old == 0);
    CHECK(worst_ratio > 0.9); /* the bound is reached somewhere: not a loose constant */
}

static void test_tighter(void)
{
    ft_camera c;
    ft_view_gain_frame g;
    const double fovy = 60.0 * FT_RAD_PER_DEG;
    /* level, 4:3: a small box on the top-right corner ray, 1 km out */
    REQUIRE(make_camera(&c, 0.3, 0.0, 0.0, fovy, 640u, 480u));
    ft_view_gain_frame_from_camera(&c, &g);
    const double ty = tan(0.5 * fovy), tx = ty * 640.0 / 480.0;
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        const double p = 1000.0 * (c.forward[a] + 0.999 * tx * c.right[a] + 0.999 * ty * c.up[a]);
        lo[a] = p - 0.01;
        hi[a] = p + 0.01;
    }
    const double gnew = ft_view_vertical_gain(&g, lo, hi), gold = offaxis_gain(&c, lo, hi);
    printf("level view, corner: gain %.4f (off-axis %.4f)\n", gnew, gold);
    CHECK_NEAR(gnew, sqrt(1.0 + tx * tx + ty * ty), 0.01);
    CHECK_NEAR(gold, 1.0 + tx * tx + ty * ty, 0.01);
    /* straight down: a box on the axis 1 km below sees the vertical along its rays */
    REQUIRE(make_camera(&c, 0.0, -0.5 * FT_PI, 0.0, fovy, 640u, 480u));
    ft_view_gain_frame_from_camera(&c, &g);
    const double dlo[3] = {-1.0, -1.0, -1001.0}, dhi[3] = {1.0, 1.0, -999.0};
    const double gdown = ft_view_vertical_gain(&g, dlo, dhi);
    printf("straight down, nadir: gain %.6f (off-axis %.6f)\n", gdown, offaxis_gain(&c, dlo, dhi));
    CHECK(gdown < 0.002);
    /* a corner behind the eye: the caps */
    const double blo[3] = {-10.0, -10.0, -10.0}, bhi[3] = {10.0, 10.0, 10.0};
    CHECK_NEAR(ft_view_vertical_gain(&g, blo, bhi), g.a_cap * g.b_cap, 1e-12);
}

int main(void)
{
    test_random();
    test_tighter();
    return ft_test_result("test_view_scale");
}
