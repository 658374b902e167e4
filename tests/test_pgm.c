/* test_pgm.c - the persistent grid mapping's math (src/lod/pgm.h), on the CPU:
 * closed-form cases on flat ground with known cameras (vertex positions,
 * ground distances, lod, parent weight, gamma, sampling-camera angles), the
 * avg-level sampling on a linear ramp, the max-pyramid bound, the atlas
 * layout, and properties over random cameras: every view ray that meets the
 * ground nearer than the terrain's far corner lies inside the sampling
 * rectangle (up to its 88 deg half-angle cap), and no grid vertex (or LOD neighbour) is ever non-finite, at or
 * above the horizon, under the terrain or below the base plane. Last, the
 * LOD does not pop: along a slow climb a vertex's height changes smoothly,
 * where the same vertex with the parent weight dropped jumps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lod/pgm.h"
#include "terrain/pyramid.h"
#include "test_util.h"

#define DEG (FT_PI / 180.0)

static uint32_t g_rng = 12345u;
static double urand(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (double)(g_rng >> 8) / 16777216.0;
}

typedef double (*height_fn)(uint32_t x, uint32_t y);

/* A w x h grid in metres (cell_m spacing, origin at world 0,0) with its
 * pyramids, heights from fn. */
static void make_terrain(ft_terrain *t, uint32_t w, uint32_t h, double cell_m, height_fn fn)
{
    memset(t, 0, sizeof *t);
    t->width = w;
    t->height = h;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = t->spacing_y = cell_m;
    t->cell_x_m = t->cell_y_m = cell_m;
    t->heights_m = malloc((size_t)w * h * sizeof(float));
    REQUIRE(t->heights_m != NULL);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            t->heights_m[(size_t)y * w + x] = (float)fn(x, y);
        }
    }
    const size_t bytes = ft_pyramid_bytes(w, h);
    void *store = aligned_alloc(64, (bytes + 63u) / 64u * 64u);
    REQUIRE(store != NULL);
    ft_error err;
    REQUIRE(ft_pyramid_layout(t, store, bytes, &err) == FT_OK);
    ft_pyramid_build(t);
}

static void free_terrain(ft_terrain *t)
{
    free(t->heights_m);
    /* the pyramid storage starts with avg level 1 (ft_pyramid_layout's order) */
    free(t->pyr.avg_levels > 1u ? (void *)t->pyr.avg[1].avg_m : (void *)t->pyr.minmax[0].min_m);
}

static double flat_500(uint32_t x, uint32_t y)
{
    (void)x;
    (void)y;
    return 500.0;
}

static double ramp(uint32_t x, uint32_t y)
{
    return 100.0 + 3.0 * x - 2.0 * y;
}

static double hills(uint32_t x, uint32_t y)
{
    return 800.0 + 400.0 * sin(0.031 * x) * cos(0.023 * y) + 120.0 * sin(0.17 * x + 0.11 * y) +
           30.0 * sin(0.9 * x) * sin(0.7 * y);
}

static ft_camera camera(double x, double y, double z, double heading_deg, double pitch_deg,
                        double roll_deg, double fovy_deg, uint32_t w, uint32_t h)
{
    ft_camera c;
    ft_error err;
    const double eye[3] = {x, y, z};
    REQUIRE(ft_camera_init(&c, eye, heading_deg * DEG, pitch_deg * DEG, roll_deg * DEG,
                           fovy_deg * DEG, w, h, 1.0, 1e6, &err) == FT_OK);
    return c;
}

/* ---- closed forms ------------------------------------------------------------ */

static void test_rules(void)
{
    const double eps = 0.5 * DEG, a = 30.0 * DEG;
    /* looking down past half the fov: the sampling camera is the view's */
    CHECK_NEAR(ft_pgm_sampling_depression(60.0 * DEG, a, eps), 60.0 * DEG, 1e-15);
    CHECK_NEAR(ft_pgm_sampling_depression(90.0 * DEG, a, eps), 90.0 * DEG, 1e-15);
    /* at, near or above the horizon: FOV/2 + eps */
    CHECK_NEAR(ft_pgm_sampling_depression(10.0 * DEG, a, eps), a + eps, 1e-15);
    CHECK_NEAR(ft_pgm_sampling_depression(0.0, a, eps), a + eps, 1e-15);
    CHECK_NEAR(ft_pgm_sampling_depression(-90.0 * DEG, a, eps), a + eps, 1e-15);
    /* between FOV/2 and FOV/2 + eps the top edge would be within eps of the
     * horizon: also FOV/2 + eps */
    CHECK_NEAR(ft_pgm_sampling_depression(a + 0.5 * eps, a, eps), a + eps, 1e-15);
    /* never past the nadir */
    CHECK_NEAR(ft_pgm_sampling_depression(0.0, 85.0 * DEG, 10.0 * DEG), 90.0 * DEG, 1e-15);

    /* gamma: tan g = r h m / (h^3 + r^2 (h - m)) */
    CHECK_NEAR(ft_pgm_gamma(1000.0, 500.0, 2000.0, 1.0), atan(1.0 / 3.0), 1e-15);
    CHECK_NEAR(ft_pgm_gamma(1000.0, 0.0, 2000.0, 1.0), 0.0, 0.0);
    CHECK_NEAR(ft_pgm_gamma(1000.0, -50.0, 2000.0, 1.0), 0.0, 0.0);
    CHECK_NEAR(ft_pgm_gamma(1000.0, 2000.0, 1000.0, 0.7), 0.7, 0.0); /* den = 0: to the nadir */
    CHECK_NEAR(ft_pgm_gamma(1000.0, 3000.0, 5000.0, 0.7), 0.7, 0.0); /* den < 0 */
    CHECK_NEAR(ft_pgm_gamma(1000.0, 500.0, 2000.0, 0.1), 0.1, 0.0);  /* capped by the room */
    /* what gamma means: with the nearest ray at depression beta (tan beta =
     * h / r), a peak of height m whose top touches that ray has its base at
     * x = (h - m) r / h; the extended edge (beta + gamma) reaches that base. */
    for (int k = 0; k < 200; ++k) {
        const double h = 10.0 + 5000.0 * urand(), m = h * 0.98 * urand();
        const double r = 1.0 + 20000.0 * urand();
        const double g = ft_pgm_gamma(h, m, r, FT_PI);
        const double beta = atan(h / r), x = (h - m) * r / h;
        CHECK_NEAR(tan(beta + g), h / x, 1e-9 * (h / x));
    }

    /* lod = max(0, floor(log2 r)), parent weight r / 2^L - 1 */
    static const struct {
        double r;
        uint32_t levels, level;
        double w;
    } lod[] = {{0.0, 12, 0, 0.0},  {0.5, 12, 0, 0.0},   {1.0, 12, 0, 0.0},  {1.5, 12, 0, 0.5},
               {2.0, 12, 1, 0.0},  {3.0, 12, 1, 0.5},   {4.0, 12, 2, 0.0},  {7.0, 12, 2, 0.75},
               {1000.0, 12, 9, 1000.0 / 512.0 - 1.0},   {3.0, 3, 1, 0.5},   {4.0, 3, 2, 0.0},
               {100.0, 3, 2, 0.0}, {5.0, 1, 0, 0.0}};
    for (size_t k = 0; k < sizeof lod / sizeof lod[0]; ++k) {
        uint32_t l;
        double w;
        ft_pgm_lod(lod[k].r, lod[k].levels, &l, &w);
        CHECK(l == lod[k].level);
        CHECK_NEAR(w, lod[k].w, 1e-15);
    }
    /* L + w is continuous in r (the parent weight reaches 1 where the level
     * steps up): no step larger than the slope allows */
    double prev = 0.0, worst = 0.0;
    for (int k = 0; k <= 200000; ++k) {
        const double r = 0.5 + k * 0.01;
        uint32_t l;
        double w;
        ft_pgm_lod(r, 16, &l, &w);
        const double f = l + w;
        if (k > 0 && fabs(f - prev) > worst) worst = fabs(f - prev);
        prev = f;
    }
    CHECK(worst <= 0.01 + 1e-9); /* dr / 2^L with 2^L >= 1 */
}

/* Flat ground, known cameras: vertex positions in closed form. */
static void test_flat_closed_form(void)
{
    ft_terrain t;
    make_terrain(&t, 1025, 1025, 30.0, flat_500);
    const double h = 1000.0; /* eye above the flat ground = above the base plane */
    const double cx = 512.0 * 30.0, cy = 300.0 * 30.0;
    const uint32_t cols = 101, rows = 201;
    ft_pgm_sampling s;

    /* heading north, 45 deg down, fov 60, square: the sampling camera is the view */
    ft_camera c = camera(cx, cy, 500.0 + h, 0.0, -45.0, 0.0, 60.0, 400, 400);
    ft_pgm_setup(&s, &c, &t);
    CHECK_NEAR(s.base_z_m, 500.0, 0.0);
    CHECK_NEAR(s.height_m, h, 1e-9);
    CHECK_NEAR(s.lift_m, 0.0, 0.0);
    CHECK(!s.pitched_down);
    CHECK_NEAR(s.depression_rad, 45.0 * DEG, 1e-12);
    CHECK_NEAR(s.roll_rad, 0.0, 1e-12);
    CHECK_NEAR(s.missed_max_m, 0.0, 1e-9); /* flat: nothing to miss */
    CHECK_NEAR(s.gamma_rad, 0.0, 0.0);
    CHECK_NEAR(s.rect[1], -tan(30.0 * DEG), 1e-12);
    CHECK_NEAR(s.rect[3], tan(30.0 * DEG), 1e-12);
    CHECK_NEAR(s.rect[2], tan(30.0 * DEG), 1e-12);
    CHECK_NEAR(s.near_ground_m, h / tan(75.0 * DEG), 1e-9);
    ft_pgm_vertex v;
    /* the centre vertex looks along the forward: h ahead */
    ft_pgm_vertex_at(&s, &t, cols, rows, 50, 100, &v);
    CHECK_NEAR(v.ground_rel_m[0], 0.0, 1e-9);
    CHECK_NEAR(v.ground_rel_m[1], h, 1e-9);
    CHECK_NEAR(v.pos_rel_eye_m[0], 0.0, 1e-9);
    CHECK_NEAR(v.pos_rel_eye_m[1], h, 1e-9);
    CHECK_NEAR(v.pos_rel_eye_m[2], -h, 1e-9);
    CHECK_NEAR(v.height_m, 500.0, 1e-9);
    /* bottom and top centre: depressions 75 and 15 deg */
    ft_pgm_vertex_at(&s, &t, cols, rows, 50, 0, &v);
    CHECK_NEAR(v.ground_rel_m[1], h / tan(75.0 * DEG), 1e-9);
    ft_pgm_vertex_at(&s, &t, cols, rows, 50, rows - 1u, &v);
    CHECK_NEAR(v.ground_rel_m[1], h / tan(15.0 * DEG), 1e-9);
    /* top-right corner: d = f + t r + t u, f = (0, c, -c), u = (0, c, c), r = (1, 0, 0) */
    {
        const double tt = tan(30.0 * DEG), q = sqrt(0.5);
        const double d[3] = {tt, q + tt * q, -q + tt * q};
        ft_pgm_vertex_at(&s, &t, cols, rows, cols - 1u, rows - 1u, &v);
        CHECK_NEAR(v.ground_rel_m[0], h * d[0] / -d[2], 1e-8);
        CHECK_NEAR(v.ground_rel_m[1], h * d[1] / -d[2], 1e-8);
        CHECK_NEAR(v.pos_rel_eye_m[2], -h, 1e-9);
    }
    /* every vertex on the flat ground inside the grid sits on its ray's hit */
    double worst = 0.0;
    for (uint32_t j = 0; j < rows; j += 7) {
        for (uint32_t i = 0; i < cols; i += 5) {
            ft_pgm_vertex_at(&s, &t, cols, rows, i, j, &v);
            double d[3];
            ft_pgm_ray(&s, cols, rows, i, j, d);
            const double k = h / -d[2];
            const double e = fabs(v.pos_rel_eye_m[0] - k * d[0]) +
                             fabs(v.pos_rel_eye_m[1] - k * d[1]) +
                             fabs(v.pos_rel_eye_m[2] - k * d[2]);
            worst = (e > worst) ? e : worst;
        }
    }
    CHECK(worst < 1e-6);

    /* nadir, heading east (the image's up points east), fov 90, aspect 2:1:
     * the image plane is parallel to the ground, ground = h (x, y) */
    c = camera(cx, cy, 500.0 + h, 90.0, -90.0, 0.0, 90.0, 800, 400);
    ft_pgm_setup(&s, &c, &t);
    CHECK(!s.pitched_down);
    CHECK_NEAR(s.depression_rad, 90.0 * DEG, 1e-12);
    CHECK_NEAR(s.right[0], 0.0, 1e-12); /* right = south when heading east */
    CHECK_NEAR(s.right[1], -1.0, 1e-12);
    CHECK_NEAR(s.up[0], 1.0, 1e-12);
    CHECK_NEAR(s.rect[2], 2.0, 1e-12); /* tx = aspect * tan 45 */
    CHECK_NEAR(s.rect[3], 1.0, 1e-12);
    CHECK_NEAR(s.near_ground_m, 0.0, 0.0); /* past the nadir: nothing missed */
    ft_pgm_vertex_at(&s, &t, cols, rows, cols - 1u, rows - 1u, &v); /* (x, y) = (2, 1) */
    CHECK_NEAR(v.ground_rel_m[0], h * 1.0, 1e-9);                   /* up (east) 1 */
    CHECK_NEAR(v.ground_rel_m[1], -h * 2.0, 1e-9);                  /* right (south) 2 */
    /* neighbour spacing at nadir: 4 h / (cols - 1) across, 2 h / (rows - 1) along */
    ft_pgm_vertex_at(&s, &t, cols, rows, 50, 100, &v);
    const double rx = 4.0 * h / (cols - 1u) / 30.0, ry = 2.0 * h / (rows - 1u) / 30.0;
    CHECK_NEAR(v.r_cells, rx > ry ? rx : ry, 1e-9);
    CHECK(v.level == 0u); /* 40 m / 30 m = 1.33 cells */
    CHECK_NEAR(v.parent_w, v.r_cells - 1.0, 1e-12);

    /* level view at the horizon: pitched down to FOV/2 + eps, every vertex
     * finite and on the ground */
    c = camera(cx, cy, 500.0 + h, 30.0, 0.0, 0.0, 40.0, 640, 480);
    ft_pgm_setup(&s, &c, &t);
    CHECK(s.pitched_down);
    CHECK_NEAR(s.eps_rad, atan2(h, s.far_m), 1e-15);
    CHECK_NEAR(s.depression_rad, 20.0 * DEG + s.eps_rad, 1e-12);
    CHECK_NEAR(s.rect[3], tan(20.0 * DEG), 1e-12);
    /* the bottom row is the view's bottom edge (depression 20 deg, eps above
     * the sampling axis): nothing on flat ground below it can be seen, and
     * the rows under it would be wasted (half of them, from the sampling
     * camera's own edge 20 deg below its axis) */
    CHECK_NEAR(s.gamma_rad, 0.0, 0.0);
    CHECK_NEAR(s.rect[1], tan(s.eps_rad), 1e-12);
    /* wider than the view (it looks down more), never wider than needed for
     * every view ray below the horizon: tx cos(dep_v) / cos(dep_s) */
    CHECK(s.rect[2] > tan(20.0 * DEG) * 640.0 / 480.0);
    CHECK(s.rect[2] <= tan(20.0 * DEG) * 640.0 / 480.0 / cos(s.depression_rad) + 1e-12);
    for (uint32_t j = 0; j < rows; ++j) {
        for (uint32_t i = 0; i < cols; i += 10) {
            ft_pgm_vertex_at(&s, &t, cols, rows, i, j, &v);
            CHECK(isfinite(v.pos_rel_eye_m[0]) && isfinite(v.pos_rel_eye_m[1]));
            CHECK_NEAR(v.pos_rel_eye_m[2], -h, 1e-9);
        }
    }
    /* pitched 10 deg up: the view's bottom edge looks 10 deg down, 10 deg +
     * eps above the sampling axis; the bottom row's centre ground is where
     * that edge meets the ground. Pitched 75 deg up, its top edge rises
     * past the zenith and the sampling camera's own edge is kept. */
    c = camera(cx, cy, 500.0 + h, 30.0, 10.0, 0.0, 40.0, 640, 480);
    ft_pgm_setup(&s, &c, &t);
    CHECK(s.pitched_down);
    CHECK_NEAR(s.rect[1], tan(10.0 * DEG + s.eps_rad), 1e-12);
    ft_pgm_vertex_at(&s, &t, cols, rows, (cols - 1u) / 2u, 0, &v);
    CHECK_NEAR(hypot(v.ground_rel_m[0], v.ground_rel_m[1]), h / tan(10.0 * DEG), 1e-6);
    c = camera(cx, cy, 500.0 + h, 30.0, 75.0, 0.0, 40.0, 640, 480);
    ft_pgm_setup(&s, &c, &t);
    CHECK_NEAR(s.rect[1], -tan(20.0 * DEG), 1e-12);
    free_terrain(&t);
}

/* Avg levels on a linear ramp are the ramp (means of a linear function at
 * their centres; bilinear keeps it), away from the clamped edge. */
static void test_levels(void)
{
    ft_terrain t;
    make_terrain(&t, 257, 257, 10.0, ramp);
    for (uint32_t l = 0; l < 5; ++l) {
        for (int k = 0; k < 100; ++k) {
            const double gx = 20.0 + 200.0 * urand(), gy = 20.0 + 200.0 * urand();
            double grad[2];
            const double hh = ft_pgm_level_height(&t, l, gx, gy, grad);
            CHECK_NEAR(hh, 100.0 + 3.0 * gx - 2.0 * gy, 1e-3);
            CHECK_NEAR(grad[0], 3.0, 1e-4);
            CHECK_NEAR(grad[1], -2.0, 1e-4);
        }
    }
    /* level 0 at samples: the samples */
    CHECK_NEAR(ft_pgm_level_height(&t, 0, 7.0, 9.0, NULL), 100.0 + 21.0 - 18.0, 1e-4);
    /* the 1 x 1 level is the mean everywhere */
    const uint32_t top = t.pyr.avg_levels - 1u;
    CHECK(t.pyr.avg[top].width == 1u && t.pyr.avg[top].height == 1u);
    CHECK_NEAR(ft_pgm_level_height(&t, top, 3.0, 250.0, NULL), t.pyr.avg[top].avg_m[0], 0.0);

    /* atlas: levels 1.. inside, disjoint */
    uint32_t org[FT_PYRAMID_LEVELS_MAX][2], aw, ah;
    REQUIRE(ft_pgm_atlas_layout(&t, org, &aw, &ah));
    CHECK(aw == 129u + 65u && ah == 65u + 33u + 17u + 9u + 5u + 3u + 2u + 1u);
    for (uint32_t a = 1; a < t.pyr.avg_levels; ++a) {
        CHECK(org[a][0] + t.pyr.avg[a].width <= aw && org[a][1] + t.pyr.avg[a].height <= ah);
        for (uint32_t b = a + 1u; b < t.pyr.avg_levels; ++b) {
            const int apart = org[a][0] + t.pyr.avg[a].width <= org[b][0] ||
                              org[b][0] + t.pyr.avg[b].width <= org[a][0] ||
                              org[a][1] + t.pyr.avg[a].height <= org[b][1] ||
                              org[b][1] + t.pyr.avg[b].height <= org[a][1];
            CHECK(apart);
        }
    }
    free_terrain(&t);

    /* highest terrain in a box: never below the surface anywhere in it (dense
     * samples of the bilinear surface), never above the grid's max; exact
     * (within the dense sampling's reach) for small boxes */
    make_terrain(&t, 301, 233, 25.0, hills);
    int exact = 0;
    for (int k = 0; k < 300; ++k) {
        double x0 = urand() * 7600.0 - 100.0, y0 = urand() * 5900.0 - 100.0;
        double x1 = x0 + urand() * 3000.0, y1 = y0 + urand() * 3000.0;
        if (k % 2 == 0) { /* small boxes too: the exact path */
            x1 = x0 + urand() * 200.0;
            y1 = y0 + urand() * 200.0;
        }
        const double m = ft_pgm_max_height(&t, x0, y0, x1, y1);
        double dense = -INFINITY;
        for (int a = 0; a <= 64; ++a) {
            for (int b = 0; b <= 64; ++b) {
                const double wx = x0 + (x1 - x0) * a / 64.0, wy = y0 + (y1 - y0) * b / 64.0;
                if (wx < 0.0 || wy < 0.0 || wx > 300 * 25.0 || wy > 232 * 25.0) continue;
                const double v = ft_pgm_level_height(&t, 0, wx / 25.0, wy / 25.0, NULL);
                dense = v > dense ? v : dense;
            }
        }
        CHECK(m >= dense - 1e-3);
        CHECK(m <= t.max_height_m);
        if (x1 - x0 <= 200.0 && y1 - y0 <= 200.0 && isfinite(dense)) {
            /* within what 1/64 of the box can miss on these slopes */
            CHECK(m <= dense + 0.02 * (x1 - x0 + y1 - y0) + 1e-3);
            ++exact;
        }
    }
    CHECK(exact > 100);
    {
        /* inside one cell the bilinear surface peaks at a corner of the box */
        const double bx0 = 10 * 25.0 + 3.0, by0 = 20 * 25.0 + 3.0;
        const double bx1 = 10 * 25.0 + 20.0, by1 = 20 * 25.0 + 20.0;
        const double m = ft_pgm_max_height(&t, bx0, by0, bx1, by1);
        double e = -INFINITY;
        for (int k = 0; k < 4; ++k) {
            const double v = ft_pgm_level_height(&t, 0, ((k & 1) ? bx1 : bx0) / 25.0,
                                                 ((k & 2) ? by1 : by0) / 25.0, NULL);
            e = (v > e) ? v : e;
        }
        CHECK_NEAR(m, e, 1e-9);
        /* a big box: the max pyramid's bound, at least the samples' max */
        const double big = ft_pgm_max_height(&t, 0.0, 0.0, 300 * 25.0, 232 * 25.0);
        CHECK_NEAR(big, t.max_height_m, 0.0);
    }
    CHECK(ft_pgm_max_height(&t, -900.0, -900.0, -800.0, -800.0) == -INFINITY);
    free_terrain(&t);
}

/* ---- properties over random cameras ---------------------------------------------- */

static void project(const ft_pgm_sampling *s, const double d[3], double *x, double *y, double *f)
{
    *f = d[0] * s->forward[0] + d[1] * s->forward[1] + d[2] * s->forward[2];
    *x = (d[0] * s->right[0] + d[1] * s->right[1] + d[2] * s->right[2]) / *f;
    *y = (d[0] * s->up[0] + d[1] * s->up[1] + d[2] * s->up[2]) / *f;
}

static void test_random_views(void)
{
    ft_terrain t;
    make_terrain(&t, 401, 401, 30.0, hills);
    static const double fovs[] = {1.0, 10.0, 45.0, 60.0, 90.0, 120.0, 150.0, 170.0};
    static const double heights[] = {1.0, 10.0, 100.0, 1000.0, 10000.0, 100000.0};
    uint64_t rays = 0, vertices = 0, uncovered = 0, nonfinite = 0, bad_dz = 0, beyond_cap = 0;
    uint64_t rising = 0, rising_out = 0;
    double worst_out = 0.0;
    for (int n = 0; n < 4000; ++n) {
        const double fov = fovs[n % 8], hgt = heights[(n / 8) % 6];
        const double pitch = -90.0 + 180.0 * urand(), roll = (urand() < 0.3) ? 0.0 : 360.0 * urand();
        const double heading = 360.0 * urand();
        const double ex = -2000.0 + 16000.0 * urand(), ey = -2000.0 + 16000.0 * urand();
        /* above the local ground, or under it (a few) */
        const double ground = ft_pgm_level_height(&t, 0, fmin(fmax(ex / 30.0, 0.0), 400.0),
                                                  fmin(fmax(ey / 30.0, 0.0), 400.0), NULL);
        const double ez = (n % 17 == 0) ? ground - 300.0 : (n % 23 == 0 ? -50.0 : ground + hgt);
        const uint32_t w = (n % 3 == 0) ? 400u : 640u, h = (n % 3 == 0) ? 400u : 480u;
        ft_camera c = camera(ex, ey, ez, heading, pitch, roll, fov, w, h);
        if (n % 251 == 0) { /* exactly at nadir and zenith too */
            c = camera(ex, ey, ez, heading, (n % 2) ? -90.0 : 90.0, roll, fov, w, h);
        }
        ft_pgm_sampling s;
        ft_pgm_setup(&s, &c, &t);
        CHECK(s.height_m >= FT_PGM_MIN_HEIGHT_M - 1e-9);
        CHECK(s.rect[0] < s.rect[2] && s.rect[1] < s.rect[3]);
        CHECK(s.min_neg_dz > 0.0 && isfinite(s.min_neg_dz));
        /* the rectangle's rays all meet the base plane: corners (the top edge
         * is the worst, d_z is linear and right is horizontal) */
        for (int k = 0; k < 4; ++k) {
            const double x = (k & 1) ? s.rect[2] : s.rect[0], y = (k & 2) ? s.rect[3] : s.rect[1];
            const double dz = s.forward[2] + x * s.right[2] + y * s.up[2];
            bad_dz += !(-dz >= s.min_neg_dz);
        }
        /* view rays with a depression >= eps (they meet the plane within the
         * far corner distance) must fall inside the sampling rectangle, if
         * they are within FT_PGM_HALF_ANGLE_MAX_RAD (88 deg) of its axis: the
         * rectangle stops at tan 88 deg, which only fovs near 170 reach */
        for (int k = 0; k < 64; ++k) {
            double d[3];
            ft_camera_pixel_ray(&c, urand() * w, urand() * h, d);
            if (s.mirrored) {
                d[2] = -d[2]; /* under the plane: the mirrored ray is sampled */
            }
            if (-d[2] < sin(s.eps_rad) * (1.0 + 1e-9)) {
                /* a level or rising ray meets terrain (above the eye) at any
                 * distance out to the far corner: the base-plane point under
                 * it, along its azimuth just inside the top row's
                 * depression eps, must be inside the rectangle's columns */
                const double hz = hypot(d[0], d[1]);
                /* straight up: no ground under it; mirrored (eye under the
                 * base plane): this is a falling ray, it meets no terrain */
                if (hz < 1e-9 || s.mirrored) continue;
                /* it can only meet terrain if it is below the highest point
                 * somewhere out to the far corner; a rising ray only out
                 * to where it climbs past that point */
                const double m = t.max_height_m - s.base_z_m;
                const double drop = s.far_m * fmax(-d[2] / hz, 0.0);
                if (s.height_m - drop > m) continue;
                double reach = s.far_m;
                if (d[2] > 0.0) reach = fmin(reach, (m - s.height_m) * hz / d[2]);
                const double dep = fmax(atan2(s.height_m, reach), s.eps_rad) * (1.0 + 1e-6);
                const double g[3] = {cos(dep) * d[0] / hz, cos(dep) * d[1] / hz, -sin(dep)};
                double x, y, f;
                project(&s, g, &x, &y, &f);
                if (f < cos(FT_PGM_HALF_ANGLE_MAX_RAD)) continue;
                /* the documented limit: columns widen to at most 1.5 tx_b */
                if (fabs(x) > FT_PGM_COLUMNS_WIDEN_MAX * s.half_x_tan) continue;
                ++rising;
                const double out = fmax(s.rect[0] - x, x - s.rect[2]);
                if (out > 1e-9 * (1.0 + fabs(x))) {
                    if (rising_out < 5) {
                        fprintf(stderr, "rising ray's ground outside the columns: pitch %.2f "
                                "roll %.2f fov %.0f h %.1f dep_s %.3f x %.5f rect x %.5f\n",
                                pitch, roll, fov, s.height_m, s.depression_rad / DEG, x,
                                s.rect[2]);
                    }
                    ++rising_out;
                }
                continue;
            }
            double x, y, f;
            project(&s, d, &x, &y, &f);
            if (f < cos(FT_PGM_HALF_ANGLE_MAX_RAD)) {
                ++beyond_cap; /* more than 88 deg off the sampling axis (fov ~170) */
                continue;
            }
            ++rays;
            const double out = fmax(fmax(s.rect[0] - x, x - s.rect[2]),
                                    fmax(s.rect[1] - y, y - s.rect[3]));
            if (!(f > 0.0) || out > 1e-9 * (1.0 + fabs(x) + fabs(y))) {
                if (uncovered < 5) {
                    fprintf(stderr, "uncovered ray: pitch %.2f roll %.2f fov %.0f dep_s %.3f "
                            "(x %.4f y %.4f f %.3g) rect %.4f %.4f %.4f %.4f\n", pitch, roll, fov,
                            s.depression_rad / DEG, x, y, f, s.rect[0], s.rect[1], s.rect[2],
                            s.rect[3]);
                }
                ++uncovered;
                worst_out = (out > worst_out) ? out : worst_out;
            }
        }
        /* vertices and their LOD neighbours (outside the rectangle too) */
        const uint32_t cols = 23, rows = 31;
        for (uint32_t j = 0; j < rows; j += 3) {
            for (uint32_t i = 0; i < cols; i += 2) {
                ft_pgm_vertex v;
                ft_pgm_vertex_at(&s, &t, cols, rows, i, j, &v);
                ++vertices;
                const int ok = isfinite(v.pos_rel_eye_m[0]) && isfinite(v.pos_rel_eye_m[1]) &&
                               isfinite(v.pos_rel_eye_m[2]) && isfinite(v.r_cells) &&
                               isfinite(v.parent_w);
                nonfinite += !ok;
            }
        }
    }
    printf("random views: %llu view rays within the terrain's reach, %llu outside the "
           "sampling rectangle (worst by %.3g), %llu more than 88 deg off its axis; %llu "
           "vertices, %llu non-finite; %llu rays missing the plane\n",
           (unsigned long long)rays, (unsigned long long)uncovered, worst_out,
           (unsigned long long)beyond_cap,
           (unsigned long long)vertices, (unsigned long long)nonfinite,
           (unsigned long long)bad_dz);
    printf("random views: %llu level or rising view rays, %llu whose ground lies outside the "
           "sampling rectangle's columns\n", (unsigned long long)rising,
           (unsigned long long)rising_out);
    CHECK(rising > 1000u);
    CHECK(rising_out == 0u);
    CHECK(rays > 50000u);
    CHECK(uncovered == 0u);
    CHECK(beyond_cap * 500u < rays); /* a handful, all at fov 150..170 */
    CHECK(nonfinite == 0u);
    CHECK(bad_dz == 0u);
    free_terrain(&t);
}

/* Camera under the terrain: nothing special above the base plane; below
 * it the eye and the view are mirrored through the plane (a rising view ray
 * meets the plane where the mirrored falling ray does). */
static void test_below(void)
{
    ft_terrain t;
    make_terrain(&t, 201, 201, 30.0, hills);
    const double base = t.min_height_m;
    ft_pgm_sampling s;
    ft_pgm_vertex v;
    /* inside a hill, above the plane */
    const double ground = ft_pgm_level_height(&t, 0, 100.0, 100.0, NULL);
    ft_camera c = camera(3000.0, 3000.0, ground - 40.0, 20.0, 10.0, 0.0, 60.0, 320, 240);
    REQUIRE(ground - 40.0 > base + 1.0);
    ft_pgm_setup(&s, &c, &t);
    CHECK(!s.mirrored);
    CHECK_NEAR(s.lift_m, 0.0, 1e-9);
    CHECK_NEAR(s.height_m, ground - 40.0 - base, 1e-9);
    /* 250 m under the plane, looking up 60 deg, fov 40: the mirrored view
     * looks down 60 deg (more than 20 + eps), so it is the sampling camera */
    c = camera(3000.0, 3000.0, base - 250.0, 20.0, 60.0, 0.0, 40.0, 320, 240);
    ft_pgm_setup(&s, &c, &t);
    CHECK(s.mirrored);
    CHECK_NEAR(s.height_m, 250.0, 1e-9);
    CHECK_NEAR(s.lift_m, 500.0, 1e-9);
    CHECK(!s.pitched_down);
    CHECK_NEAR(s.depression_rad, 60.0 * DEG, 1e-12);
    CHECK_NEAR(s.gamma_rad, 0.0, 0.0);
    ft_pgm_vertex_at(&s, &t, 51, 51, 25, 25, &v); /* the centre: the view's axis */
    {
        double d[3];
        ft_camera_pixel_ray(&c, 160.0, 120.0, d);
        const double k = 250.0 / d[2]; /* the rising ray meets the plane */
        CHECK_NEAR(v.ground_rel_m[0], k * d[0], 1e-6);
        CHECK_NEAR(v.ground_rel_m[1], k * d[1], 1e-6);
    }
    CHECK(isfinite(v.pos_rel_eye_m[2]) && v.pos_rel_eye_m[2] >= 250.0 - 1e-6); /* terrain above */
    /* far below z = 0, straight down: mirrored, every vertex finite */
    c = camera(3000.0, 3000.0, -1000.0, 20.0, -90.0, 0.0, 60.0, 320, 240);
    ft_pgm_setup(&s, &c, &t);
    CHECK(s.mirrored && s.height_m >= 1000.0);
    for (uint32_t k = 0; k < 50u * 50u; k += 7u) {
        ft_pgm_vertex_at(&s, &t, 50, 50, k % 50u, k / 50u, &v);
        CHECK(isfinite(v.pos_rel_eye_m[0]) && isfinite(v.pos_rel_eye_m[1]) &&
              isfinite(v.pos_rel_eye_m[2]));
    }
    /* just under the plane (0.3 m): at least FT_PGM_MIN_HEIGHT_M */
    c = camera(3000.0, 3000.0, base - 0.3, 20.0, 10.0, 0.0, 60.0, 320, 240);
    ft_pgm_setup(&s, &c, &t);
    CHECK(s.mirrored);
    CHECK_NEAR(s.height_m, FT_PGM_MIN_HEIGHT_M, 1e-9);
    free_terrain(&t);
}

/* No popping: along a slow climb (2 m steps over 2 km) the LOD of a grid
 * vertex changes level; its height, evaluated with the vertex's (L, w) at
 * one fixed ground point (so the grid's swimming with the camera is taken
 * out), moves by little per step. Dropping the parent weight (floor only)
 * makes the same height jump where the level steps. */
static void test_no_pop(void)
{
    ft_terrain t;
    make_terrain(&t, 513, 513, 30.0, hills);
    const uint32_t cols = 200, rows = 800;
    static const uint32_t probe[][2] = {{100, 300}, {40, 500}, {150, 650}, {100, 760},
                                        {20, 700},  {180, 400}, {60, 600}, {120, 720}};
    double worst_blend = 0.0, worst_floor = 0.0;
    uint32_t level_changes = 0;
    for (size_t p = 0; p < sizeof probe / sizeof probe[0]; ++p) {
        double prev_b = 0.0, prev_f = 0.0, g0[2] = {0.0, 0.0};
        uint32_t prev_l = 0;
        for (int k = 0; k <= 1000; ++k) {
            ft_camera c = camera(7000.0, 3000.0, 2200.0 + 2.0 * k, 5.0, -12.0, 0.0, 60.0, 640, 480);
            ft_pgm_sampling s;
            ft_pgm_setup(&s, &c, &t);
            ft_pgm_vertex v;
            ft_pgm_vertex_at(&s, &t, cols, rows, probe[p][0], probe[p][1], &v);
            if (k == 0) {
                g0[0] = v.grid[0];
                g0[1] = v.grid[1];
            }
            const double hl = ft_pgm_level_height(&t, v.level, g0[0], g0[1], NULL);
            const uint32_t up = (v.level + 1u < t.pyr.avg_levels) ? v.level + 1u : v.level;
            const double hp = ft_pgm_level_height(&t, up, g0[0], g0[1], NULL);
            const double b = hl + (hp - hl) * v.parent_w;
            if (k > 0) {
                worst_blend = fmax(worst_blend, fabs(b - prev_b));
                worst_floor = fmax(worst_floor, fabs(hl - prev_f));
                level_changes += (v.level != prev_l);
            }
            prev_b = b;
            prev_f = hl;
            prev_l = v.level;
        }
    }
    printf("no pop: %u level changes along the climbs; largest height step %.3f m with the "
           "parent weight, %.3f m without\n", level_changes, worst_blend, worst_floor);
    CHECK(level_changes >= 4u);
    CHECK(worst_floor > 1.0);
    CHECK(worst_blend < 0.05 * worst_floor);
    free_terrain(&t);
}

int main(void)
{
    test_rules();
    test_flat_closed_form();
    test_levels();
    test_random_views();
    test_below();
    test_no_pop();
    return ft_test_result("test_pgm");
}
