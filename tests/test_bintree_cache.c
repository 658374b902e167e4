/* test_bintree_cache.c - the bintree over the clipmap cache
 * (src/lod/bintree_cache.h) on the CPU, over a rough synthetic terrain
 * read through the cache's terrain source, while the eye moves and levels
 * lag:
 *  - conforming: no tile edge's midpoint is another tile's corner;
 *  - resident: every tile's vertices and their neighbours (the normal's)
 *    lie in the valid box of the level its heights come from;
 *  - bounded: every tile's template surface (its vertices' heights: the
 *    terrain's samples, levels being point samples) departs from the
 *    terrain's bilinear surface by at most its diamond's error, measured
 *    at dense points of every template triangle;
 *  - nested: a tile's diamond has an error and box no larger than either
 *    parent's, so the selection's Q nests;
 *  - while the finest levels lag, tiles are drawn only from what is
 *    resident (the property above) and the achieved bound says so;
 *  - init refuses a cache too small for the template. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/camera.h"
#include "lod/bintree_cache.h"
#include "lod/bintree_template.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "test_util.h"

enum { TW = 700, TH = 640 };
static _Alignas(64) uint8_t g_arena_mem[48u << 20]; /* FT_ARENA_ALIGN */
static float g_heights[TW * TH];

static void make_terrain(ft_terrain *t)
{
    memset(t, 0, sizeof *t);
    t->width = TW;
    t->height = TH;
    t->cell_x_m = 30.0;
    t->cell_y_m = 30.0;
    t->heights_m = g_heights;
    uint32_t rng = 99u;
    float lo = 1e30f, hi = -1e30f;
    for (int y = 0; y < TH; ++y) {
        for (int x = 0; x < TW; ++x) {
            rng = rng * 1664525u + 1013904223u;
            double v = 600.0 * sin(0.013 * x) * cos(0.017 * y) + 120.0 * sin(0.21 * x + 0.11 * y) +
                       15.0 * (double)(rng >> 24) / 256.0;
            if (abs(x - 2 * y + 200) < 3) {
                v += 250.0; /* a sharp ridge */
            }
            const float f = (float)v;
            g_heights[y * TW + x] = f;
            lo = (f < lo) ? f : lo;
            hi = (f > hi) ? f : hi;
        }
    }
    t->min_height_m = lo;
    t->max_height_m = hi;
}

static double height_at(const ft_terrain *t, int64_t x, int64_t y)
{
    x = (x < 0) ? 0 : ((x > (int64_t)t->width - 1) ? (int64_t)t->width - 1 : x);
    y = (y < 0) ? 0 : ((y > (int64_t)t->height - 1) ? (int64_t)t->height - 1 : y);
    return t->heights_m[y * (int64_t)t->width + x];
}

/* the finest data's bilinear surface at level-0 point (x, y) */
static double bilinear(const ft_terrain *t, double x, double y)
{
    const double fx = floor(x), fy = floor(y);
    const int64_t cx = (int64_t)fx, cy = (int64_t)fy;
    const double u = x - fx, v = y - fy;
    const double h00 = height_at(t, cx, cy), h10 = height_at(t, cx + 1, cy);
    const double h01 = height_at(t, cx, cy + 1), h11 = height_at(t, cx + 1, cy + 1);
    return h00 + (h10 - h00) * u + (h01 - h00) * v + (h00 + h11 - h10 - h01) * u * v;
}

static int16_t g_tmpl[6u * 4096u];

typedef struct run_stats {
    uint64_t tiles, checked, across, points, over, nest_bad, t_junctions, not_resident;
    double worst_ratio, sum_ratio;
} run_stats;

static int cmp_pt(const void *a, const void *b)
{
    const int64_t *p = a, *q = b;
    return (p[0] != q[0]) ? ((p[0] < q[0]) ? -1 : 1) : ((p[1] < q[1]) ? -1 : (p[1] > q[1]));
}

static int64_t g_corners[3u * 20000u][2];

static int is_corner(uint32_t n, int64_t x, int64_t y)
{
    const int64_t key[2] = {x, y};
    return bsearch(key, g_corners, n, sizeof g_corners[0], cmp_pt) != NULL;
}

/* Every property of the file's top for one selection. */
static void check_selection(const ft_bt_cache *bc, const ft_clip_cache *c, const ft_terrain *t,
                            const ft_bt_select_stats *st, run_stats *rs)
{
    const uint32_t k = bc->k;
    REQUIRE(st->tiles <= 20000u);
    rs->tiles += st->tiles;
    for (uint32_t i = 0; i < st->tiles; ++i) {
        const ft_bt_tile *tl = &bc->tiles[i];
        g_corners[3u * i][0] = tl->apex[0];
        g_corners[3u * i][1] = tl->apex[1];
        g_corners[3u * i + 1u][0] = tl->left[0];
        g_corners[3u * i + 1u][1] = tl->left[1];
        g_corners[3u * i + 2u][0] = tl->right[0];
        g_corners[3u * i + 2u][1] = tl->right[1];
    }
    qsort(g_corners, 3u * st->tiles, sizeof g_corners[0], cmp_pt);
    for (uint32_t i = 0; i < st->tiles; ++i) {
        const ft_bt_tile *tl = &bc->tiles[i];
        const int32_t *v[3] = {tl->apex, tl->left, tl->right};
        for (int e = 0; e < 3; ++e) {
            const int32_t *p = v[e], *q = v[(e + 1) % 3];
            if (((p[0] + q[0]) & 1) == 0 && ((p[1] + q[1]) & 1) == 0 &&
                is_corner(3u * st->tiles, (p[0] + q[0]) / 2, (p[1] + q[1]) / 2)) {
                rs->t_junctions += 1u;
            }
        }
        /* the level its heights come from holds its vertices and their neighbours */
        const uint32_t m = ft_btc_table_of(bc, tl->level);
        const uint32_t dl = (m < bc->top) ? m : bc->top;
        const int64_t sc = (int64_t)1 << dl;
        const ft_clip_box *vb = &c->level[dl].valid;
        for (int e = 0; e < 3; ++e) {
            const int64_t ax = bc->origin[0] + v[e][0], ay = bc->origin[1] + v[e][1];
            if (ax % sc != 0 || ay % sc != 0 || ax / sc - 1 < vb->i0 || ax / sc + 1 >= vb->i1 ||
                ay / sc - 1 < vb->j0 || ay / sc + 1 >= vb->j1) {
                rs->not_resident += 1u;
            }
        }
        /* nesting: both parents (centres: the apex and its mirror) */
        const int32_t cv[2] = {(tl->left[0] + tl->right[0]) / 2, (tl->left[1] + tl->right[1]) / 2};
        double lo[3], hi[3];
        const double err = ft_btc_diamond(bc, tl->level, cv, lo, hi);
        if (tl->level > 0u) {
            const int32_t par[2][2] = {{tl->apex[0], tl->apex[1]},
                                       {2 * cv[0] - tl->apex[0], 2 * cv[1] - tl->apex[1]}};
            const int32_t dsz = (int32_t)1 << bc->domain_log2;
            for (int pi = 0; pi < 2; ++pi) {
                if (par[pi][0] < 0 || par[pi][1] < 0 || par[pi][0] > dsz || par[pi][1] > dsz) {
                    continue;
                }
                double plo[3], phi[3];
                const double pe = ft_btc_diamond(bc, tl->level - 1u, par[pi], plo, phi);
                if (isinf(pe)) {
                    continue; /* an unknown parent bounds nothing to compare */
                }
                if (!(err <= pe) || plo[0] > lo[0] || plo[1] > lo[1] || plo[2] > lo[2] ||
                    phi[0] < hi[0] || phi[1] < hi[1] || phi[2] < hi[2]) {
                    rs->nest_bad += 1u;
                }
            }
        }
        /* the bound: inside the terrain, the surface as drawn (positions
         * clamped into the terrain, heights those of the lattice points,
         * which the source clamps: the shader's rule) */
        const int64_t x0 = bc->origin[0], y0 = bc->origin[1];
        int inside = 1;
        for (int e = 0; e < 3; ++e) {
            const int64_t ax = x0 + v[e][0], ay = y0 + v[e][1];
            inside &= (ax >= 0 && ay >= 0 && ax <= (int64_t)t->width - 1 &&
                       ay <= (int64_t)t->height - 1);
        }
        if (isinf(err)) {
            continue;
        }
        rs->checked += 1u;
        rs->across += inside ? 0u : 1u;
        const int32_t ux[2] = {tl->left[0] - tl->apex[0], tl->left[1] - tl->apex[1]};
        const int32_t uy[2] = {tl->right[0] - tl->apex[0], tl->right[1] - tl->apex[1]};
        double worst = 0.0;
        for (uint32_t tri = 0; tri < ft_bt_template_triangles(k); ++tri) {
            const int16_t *p = g_tmpl + 6u * tri;
            double px[3], py[3], ph[3];
            for (int q = 0; q < 3; ++q) {
                const int32_t a = p[2 * q], b = p[2 * q + 1];
                const int64_t gx = tl->apex[0] + ((a * ux[0] + b * uy[0]) >> k);
                const int64_t gy = tl->apex[1] + ((a * ux[1] + b * uy[1]) >> k);
                const double wmax = (double)t->width - 1.0, hmax = (double)t->height - 1.0;
                px[q] = fmin(fmax((double)(x0 + gx), 0.0), wmax);
                py[q] = fmin(fmax((double)(y0 + gy), 0.0), hmax);
                ph[q] = height_at(t, x0 + gx, y0 + gy);
            }
            enum { SUB = 12 };
            for (int i0 = 0; i0 <= SUB; ++i0) {
                for (int i1 = 0; i0 + i1 <= SUB; ++i1) {
                    const double w0 = (double)i0 / SUB, w1 = (double)i1 / SUB, w2 = 1.0 - w0 - w1;
                    const double x = w0 * px[0] + w1 * px[1] + w2 * px[2];
                    const double y = w0 * py[0] + w1 * py[1] + w2 * py[2];
                    const double lin = w0 * ph[0] + w1 * ph[1] + w2 * ph[2];
                    const double d = fabs(lin - bilinear(t, x, y));
                    worst = (d > worst) ? d : worst;
                    rs->points += 1u;
                }
            }
        }
        if (worst > err + 1e-9) {
            rs->over += 1u;
            if (rs->over <= 3u) {
                printf("  over: tile level %u table %u err %.4f measured %.4f\n", tl->level, m,
                       err, worst);
            }
        }
        const double ratio = (err > 0.0) ? worst / err : 0.0;
        rs->worst_ratio = (ratio > rs->worst_ratio) ? ratio : rs->worst_ratio;
        rs->sum_ratio += ratio;
    }
}

/* Runs the cache's updates; budget < 0: all of them. */
static void drain(ft_clip_cache *c, int budget)
{
    ft_error err;
    for (int n = 0; n < 200000 && (budget < 0 || n < budget); ++n) {
        ft_clip_update u;
        int have = 0;
        REQUIRE(ft_clip_next_update(c, &u, &have, &err) == FT_OK);
        if (!have) {
            break;
        }
        ft_clip_commit(c, &u);
    }
}

static void run(uint32_t side, uint32_t levels, uint32_t k)
{
    ft_terrain t;
    make_terrain(&t);
    ft_clip_source src;
    ft_clip_source_terrain(&src, &t);
    ft_arena a;
    memset(&a, 0, sizeof a);
    a.pools[FT_POOL_CLIP].budget_bytes = 16u << 20;
    a.pools[FT_POOL_METHOD].budget_bytes = 16u << 20;
    ft_error err;
    REQUIRE(ft_arena_bind(&a, g_arena_mem, sizeof(g_arena_mem), &err) == FT_OK);
    ft_clip_cache c;
    const ft_clip_desc d = {side, levels, 4u * side, 1};
    REQUIRE(ft_clip_init(&c, &d, &src, &a, &err) == FT_OK);
    static ft_bt_cache bc;
    REQUIRE(ft_btc_init(&bc, &c, &t, k, 20000u, &a, &err) == FT_OK);
    ft_bt_template_corners(k, g_tmpl);
    run_stats rs;
    memset(&rs, 0, sizeof rs);
    uint32_t lag_frames = 0u, lag_reported = 0u, squeezed = 0u;
    for (int step = 0; step < 64; ++step) {
        /* the first 24 steps: every 4th lags (only a few updates, the finest
         * levels behind); then a fast flight with 2 updates a step, every
         * level refilled strip by strip while it moves on */
        const int fast = step >= 24;
        /* from near the terrain's south-west corner to its north-east
         * one (the domain reaches past both: tiles across the edge) */
        const double ex = fast ? 560.0 - 9.7 * (step - 24) : 20.0 + 27.0 * step;
        const double ey = fast ? 450.0 - 7.9 * (step - 24) : 30.0 + 25.0 * step;
        (void)ft_clip_recentre(&c, ex, ey);
        drain(&c, fast ? 2 : ((step % 4 == 3) ? 3 : -1));
        /* as the method's select does: the coarsest level is kept whole
         * (updates go coarsest first) */
        for (int n = 0; n < 1000 && !ft_clip_level_current(&c, levels - 1u); ++n) {
            drain(&c, 1);
        }
        CHECK(ft_clip_level_current(&c, levels - 1u));
        ft_btc_update(&bc, &c, ex, ey);
        const double eye[3] = {ex * t.cell_x_m, ey * t.cell_y_m,
                               bilinear(&t, ex, ey) + 40.0 + 30.0 * (step % 5)};
        ft_camera cam;
        REQUIRE(ft_camera_init(&cam, eye, 0.37 * step, -0.15 - 0.05 * (step % 6), 0.0, 1.0, 640,
                               480, 1.0, 1e7, &err) == FT_OK);
        ft_bt_view v;
        ft_bt_view_from_camera(&cam, &t, step % 2, 0, &v);
        ft_bt_select_stats st;
        ft_btc_select(&bc, &v, 1.0, &st);
        CHECK(!st.budget_hit);
        CHECK(st.tau_achieved_px >= 1.0);
        if (!ft_clip_level_current(&c, 0u)) {
            lag_frames += 1u;
            lag_reported += (st.tau_achieved_px > 1.0) ? 1u : 0u;
        }
        check_selection(&bc, &c, &t, &st, &rs);
        /* a coarse target: coarse tiles across the terrain's edge too */
        ft_btc_select(&bc, &v, 24.0, &st);
        check_selection(&bc, &c, &t, &st, &rs);
        if (step % 8 == 0 && levels > 2u) {
            /* a coarser level whose resident box barely holds the finer
             * one's (as if it lagged behind it): the usable boxes' margins
             * must keep the selection conforming. The cache is told its
             * data are not there; they are, so nothing else changes. */
            const ft_clip_box saved = c.level[1].valid;
            const ft_clip_box *v0 = &c.level[0].valid;
            c.level[1].valid = (ft_clip_box){v0->i0 / 2 - 1, v0->j0 / 2 - 1, v0->i1 / 2 + 1,
                                             v0->j1 / 2 + 1};
            ft_btc_update(&bc, &c, ex, ey);
            ft_btc_select(&bc, &v, 0.5, &st);
            check_selection(&bc, &c, &t, &st, &rs);
            c.level[1].valid = saved;
            ft_btc_update(&bc, &c, ex, ey);
            squeezed += 1u;
        }
    }
    printf("side %u levels %u k %u: %llu tiles, %llu checked (%llu across the terrain's edge) at "
           "%llu points: %llu over, "
           "measured / bound worst %.3f mean %.3f; nesting failures %llu, T-junctions %llu, "
           "not resident %llu; lagging frames %u (bound over tau on %u), squeezed %u\n",
           side, levels, k, (unsigned long long)rs.tiles, (unsigned long long)rs.checked,
           (unsigned long long)rs.across,
           (unsigned long long)rs.points, (unsigned long long)rs.over, rs.worst_ratio,
           rs.checked ? rs.sum_ratio / (double)rs.checked : 0.0,
           (unsigned long long)rs.nest_bad, (unsigned long long)rs.t_junctions,
           (unsigned long long)rs.not_resident, lag_frames, lag_reported, squeezed);
    CHECK(rs.checked > 100u);
    CHECK(rs.across > 10u); /* the flights see the terrain's edge */
    CHECK(rs.over == 0u);
    CHECK(rs.nest_bad == 0u);
    CHECK(rs.t_junctions == 0u);
    CHECK(rs.not_resident == 0u);
    CHECK(lag_frames > 0u);
    CHECK(rs.worst_ratio > 0.2); /* the bound is not vacuous */
}

static void test_refusal(void)
{
    ft_terrain t;
    make_terrain(&t);
    ft_clip_source src;
    ft_clip_source_terrain(&src, &t);
    ft_arena a;
    memset(&a, 0, sizeof a);
    a.pools[FT_POOL_CLIP].budget_bytes = 8u << 20;
    a.pools[FT_POOL_METHOD].budget_bytes = 8u << 20;
    ft_error err;
    REQUIRE(ft_arena_bind(&a, g_arena_mem, sizeof(g_arena_mem), &err) == FT_OK);
    ft_clip_cache c;
    const ft_clip_desc d = {64u, 3u, 256u, 1};
    REQUIRE(ft_clip_init(&c, &d, &src, &a, &err) == FT_OK);
    static ft_bt_cache bc;
    CHECK(ft_btc_init(&bc, &c, &t, 3u, 1000u, &a, &err) == FT_ERR_CONFIG &&
          strstr(err.text, "clipmap.side") != NULL && strstr(err.text, "template_k") != NULL);
    CHECK(ft_btc_init(&bc, &c, &t, 2u, 1000u, &a, &err) == FT_OK);
    CHECK(ft_btc_init(&bc, &c, &t, 2u, 1u, &a, &err) == FT_ERR_CONFIG);
}

int main(void)
{
    test_refusal();
    run(64u, 4u, 2u);
    run(128u, 3u, 3u);
    return ft_test_result("test_bintree_cache");
}
