/* test_clip_cache.c - the clipmap cache's boxes and strip updates
 * (src/terrain/clip_cache.h) against a CPU mirror of the level textures,
 * and its source over the terrain in memory (clip_source.h).
 *
 * The mirror receives exactly what a GPU upload would (each update's texel
 * rectangle); after every step, every sample of every level's valid box must
 * read back its own height from the mirror at its toroidal texel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/view_scale.h"
#include "lod/pgrid.h"
#include "lod/worst_pieces.h"
#include "terrain/clip_cache.h"
#include "terrain/clip_source.h"
#include "test_util.h"

#define SIDE 32u
#define LEVELS 5u

/* A height for every level-0 lattice point, exact in float. */
static float lattice_height(int64_t i, int64_t j)
{
    const uint64_t h = (uint64_t)(i * 73856093) ^ (uint64_t)(j * 19349663);
    return (float)(h % 20000u) * 0.25f - 1000.0f;
}

/* A cell deviation for every level, known to the test: 0 on level 0 (the
 * finest data itself), unknown (-1) on a band of level 2's cells. */
static float synth_dev_m(uint32_t level, int64_t i, int64_t j)
{
    if (level == 0u) {
        return 0.0f;
    }
    if (level == 2u && (i >> 2) % 37 == 5) {
        return -1.0f;
    }
    return (float)((uint64_t)(i * 31 + j * 17) % 8u) * 0.125f * (float)level;
}

static uint64_t g_reads, g_read_samples;

static ft_status read_synth(void *ctx, uint32_t level, int64_t i0, int64_t j0, uint32_t w,
                            uint32_t h, float *heights_m, uint8_t *marks, float *dev_m,
                            ft_error *err)
{
    (void)ctx;
    (void)err;
    g_reads++;
    g_read_samples += (uint64_t)w * h;
    for (uint32_t r = 0u; r < h; ++r) {
        for (uint32_t q = 0u; q < w; ++q) {
            const int64_t s = (int64_t)1 << level;
            heights_m[r * w + q] = lattice_height((i0 + q) * s, (j0 + r) * s);
            marks[r * w + q] = 0u;
            if (dev_m != NULL) {
                dev_m[r * w + q] = synth_dev_m(level, (i0 + q) * s, (j0 + r) * s);
            }
        }
    }
    return FT_OK;
}

static float g_tex[LEVELS][SIDE * SIDE];
static int g_bad_update;

static void upload(const ft_clip_cache *c, const ft_clip_update *u)
{
    if (u->tex_x + u->w > SIDE || u->tex_y + u->h > SIDE ||
        (uint64_t)u->w * u->h > c->desc.update_samples_max || u->w == 0u || u->h == 0u ||
        u->tex_x != ft_clip_texel(c, u->box.i0) || u->tex_y != ft_clip_texel(c, u->box.j0) ||
        (int64_t)u->w != u->box.i1 - u->box.i0 || (int64_t)u->h != u->box.j1 - u->box.j0) {
        g_bad_update++;
        return;
    }
    for (uint32_t r = 0u; r < u->h; ++r) {
        memcpy(&g_tex[u->level][(u->tex_y + r) * SIDE + u->tex_x], &u->heights_m[r * u->w],
               u->w * sizeof(float));
    }
}

/* Every sample of every valid box reads its own height; boxes well formed. */
static int check_mirror(const ft_clip_cache *c)
{
    int bad = 0;
    for (uint32_t l = 0u; l < c->desc.levels; ++l) {
        const ft_clip_box *v = &c->level[l].valid, *w = &c->level[l].want;
        if ((v->i0 & 1) || (v->j0 & 1) || (v->i1 & 1) || (v->j1 & 1) || (w->i0 & 1) ||
            (w->j0 & 1) || w->i1 - w->i0 != SIDE || w->j1 - w->j0 != SIDE) {
            bad++;
        }
        if (v->i1 <= v->i0 || v->j1 <= v->j0) {
            continue;
        }
        if (v->i0 < w->i0 || v->j0 < w->j0 || v->i1 > w->i1 || v->j1 > w->j1) {
            bad++;
        }
        for (int64_t b = v->j0; b < v->j1; ++b) {
            for (int64_t a = v->i0; a < v->i1; ++a) {
                const int64_t s = (int64_t)1 << l;
                const float got =
                    g_tex[l][ft_clip_texel(c, b) * SIDE + ft_clip_texel(c, a)];
                if (got != lattice_height(a * s, b * s)) {
                    bad++;
                }
            }
        }
    }
    return bad;
}

/* Runs at most max_updates updates (all with max_updates = -1). */
static uint32_t drain(ft_clip_cache *c, int max_updates, int *levels_coarse_first)
{
    uint32_t n = 0u, last_level = LEVELS;
    for (int k = 0; k < 100000 && (max_updates < 0 || k < max_updates); ++k) {
        ft_clip_update u;
        int have = 0;
        ft_error err;
        REQUIRE(ft_clip_next_update(c, &u, &have, &err) == FT_OK);
        if (!have) {
            break;
        }
        if (levels_coarse_first != NULL && u.level > last_level) {
            *levels_coarse_first = 0;
        }
        last_level = u.level;
        upload(c, &u);
        ft_clip_commit(c, &u);
        ++n;
    }
    return n;
}

static _Alignas(64) uint8_t g_arena_mem[1u << 20]; /* FT_ARENA_ALIGN */

static void make_cache_kept(ft_clip_cache *c, ft_arena *a, uint32_t update_max, int keep_bounds)
{
    memset(a, 0, sizeof(*a));
    a->pools[FT_POOL_CLIP].budget_bytes = 1u << 19;
    ft_error err;
    REQUIRE(ft_arena_bind(a, g_arena_mem, sizeof(g_arena_mem), &err) == FT_OK);
    ft_clip_source src = {read_synth, NULL, 16u, 0, 0, -100000, 100000, -100000, 100000};
    ft_clip_desc d = {SIDE, LEVELS, update_max, keep_bounds};
    REQUIRE(ft_clip_init(c, &d, &src, a, &err) == FT_OK);
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        for (uint32_t k = 0u; k < SIDE * SIDE; ++k) {
            g_tex[l][k] = NAN;
        }
    }
}

static void make_cache(ft_clip_cache *c, ft_arena *a, uint32_t update_max)
{
    make_cache_kept(c, a, update_max, 0);
}

/* ft_clip_max_height_in bounds every resident sample inside the box, at
 * every level, while the boxes move and lag (partial drains); a box that
 * meets no resident sample, or a NaN box, gets -INFINITY. */
static void test_max_height_in(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache_kept(&c, &a, 256u, 1);
    const ft_clip_world w = {1000.0, -2000.0, 30.0, 20.0};
    uint64_t boxes = 0u, bad = 0u, hit = 0u, lcg = 12345u;
    for (int step = 0; step < 40; ++step) {
        (void)ft_clip_recentre(&c, 37.0 * step - 300.0, 11.0 * step + 5.0);
        (void)drain(&c, step % 3 == 0 ? -1 : 3, NULL);
        for (int q = 0; q < 60; ++q) {
            double r[4];
            for (int k = 0; k < 4; ++k) {
                lcg = lcg * 6364136223846793005u + 1442695040888963407u;
                r[k] = (double)(lcg >> 11) / 9007199254740992.0;
            }
            /* boxes of 1 m .. 40 km around the eye's region */
            const double cx = w.origin_x_m + (37.0 * step - 300.0) * w.cell_x_m +
                              (r[0] - 0.5) * 60000.0;
            const double cy = w.origin_y_m + (11.0 * step + 5.0) * w.cell_y_m +
                              (r[1] - 0.5) * 40000.0;
            const double hx = 0.5 + r[2] * 20000.0, hy = 0.5 + r[3] * 10000.0;
            const double got = ft_clip_max_height_in(&c, &w, cx - hx, cy - hy, cx + hx, cy + hy);
            double ref = -INFINITY;
            for (uint32_t l = 0u; l < LEVELS; ++l) {
                const ft_clip_box *v = &c.level[l].valid;
                const int64_t s = (int64_t)1 << l;
                for (int64_t b = v->j0; b < v->j1; ++b) {
                    const double y = w.origin_y_m + (double)(b * s) * w.cell_y_m;
                    if (y < cy - hy || y > cy + hy) continue;
                    for (int64_t i = v->i0; i < v->i1; ++i) {
                        const double x = w.origin_x_m + (double)(i * s) * w.cell_x_m;
                        if (x < cx - hx || x > cx + hx) continue;
                        const double h = lattice_height(i * s, b * s);
                        ref = h > ref ? h : ref;
                    }
                }
            }
            bad += !(got >= ref);
            hit += ref > -INFINITY;
            ++boxes;
        }
    }
    printf("max_height_in: %llu boxes, %llu holding resident samples, %llu under their "
           "highest sample\n",
           (unsigned long long)boxes, (unsigned long long)hit, (unsigned long long)bad);
    CHECK(bad == 0u);
    CHECK(hit > boxes / 4u && hit < boxes); /* both kinds of box were asked */
    CHECK(ft_clip_max_height_in(&c, &w, 1e9, 1e9, 1e9 + 10.0, 1e9 + 10.0) == -INFINITY);
    CHECK(ft_clip_max_height_in(&c, &w, NAN, 0.0, 10.0, 10.0) == -INFINITY);
}

static void test_fill_and_nesting(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache(&c, &a, 2u * SIDE);
    CHECK(ft_clip_finest_current(&c) == LEVELS);
    CHECK(ft_clip_recentre(&c, 1000.3, -77.8) == 1);
    CHECK(ft_clip_recentre(&c, 1000.3, -77.8) == 0);
    CHECK(c.stats.levels_behind == LEVELS);
    CHECK(c.stats.samples_outstanding == (uint64_t)LEVELS * SIDE * SIDE);
    int coarse_first = 1;
    g_read_samples = 0;
    drain(&c, -1, &coarse_first);
    CHECK(coarse_first);
    CHECK(g_bad_update == 0);
    CHECK(g_read_samples == (uint64_t)LEVELS * SIDE * SIDE); /* nothing read twice */
    CHECK(check_mirror(&c) == 0);
    CHECK(c.stats.levels_behind == 0u && c.stats.samples_outstanding == 0u);
    CHECK(ft_clip_finest_current(&c) == 0u);
    /* the eye near the middle of each level; each level inside the next
     * with side / 4 - 1 coarser samples to spare */
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        const ft_clip_box *w = &c.level[l].want;
        const double e_i = 1000.3 / (double)(1u << l), e_j = -77.8 / (double)(1u << l);
        CHECK(e_i >= (double)w->i0 + SIDE / 2 - 2 && e_i <= (double)w->i0 + SIDE / 2 + 2);
        CHECK(e_j >= (double)w->j0 + SIDE / 2 - 2 && e_j <= (double)w->j0 + SIDE / 2 + 2);
        if (l + 1u < LEVELS) {
            const ft_clip_box *p = &c.level[l + 1u].want;
            const int64_t m = SIDE / 4 - 1;
            CHECK(w->i0 / 2 - p->i0 >= m && p->i1 - w->i1 / 2 >= m);
            CHECK(w->j0 / 2 - p->j0 >= m && p->j1 - w->j1 / 2 >= m);
        }
    }
}

/* A small move reads exactly the samples that enter each box. */
static void test_strips_read_only_new_samples(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache(&c, &a, 3u * SIDE);
    ft_clip_recentre(&c, 0.5, 0.5);
    drain(&c, -1, NULL);
    ft_clip_box before[LEVELS];
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        before[l] = c.level[l].want;
    }
    /* 7 samples east, 3 south at level 0 */
    CHECK(ft_clip_recentre(&c, 7.5, -2.5) == 1);
    uint64_t expect = 0u;
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        const ft_clip_box *w = &c.level[l].want;
        const int64_t ox = SIDE - llabs(w->i0 - before[l].i0);
        const int64_t oy = SIDE - llabs(w->j0 - before[l].j0);
        const uint64_t kept = (ox > 0 && oy > 0) ? (uint64_t)(ox * oy) : 0u;
        expect += (uint64_t)SIDE * SIDE - kept;
        CHECK(c.level[l].samples_outstanding == (uint64_t)SIDE * SIDE - kept);
    }
    CHECK(expect > 0u);
    CHECK(check_mirror(&c) == 0); /* the shrunk valid boxes still read right */
    g_read_samples = 0;
    drain(&c, -1, NULL);
    CHECK(g_read_samples == expect);
    CHECK(check_mirror(&c) == 0);
    CHECK(c.stats.levels_behind == 0u);
}

/* A flight with few updates a frame: the valid boxes lag but never read
 * wrong, and catch up when the eye stops; a jump refills. */
static void test_lagging_flight(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache(&c, &a, 2u * SIDE);
    ft_clip_recentre(&c, -40.0, 13.0);
    drain(&c, -1, NULL);
    int bad = 0;
    uint32_t lagged = 0u;
    for (int f = 0; f < 400; ++f) {
        const double t = f * 0.05;
        ft_clip_recentre(&c, -40.0 + 9.0 * t * cos(t * 0.3), 13.0 - 7.0 * t);
        drain(&c, 1, NULL);
        bad += check_mirror(&c);
        lagged += c.stats.levels_behind > 0u ? 1u : 0u;
        /* a valid box that lags is still a box with samples in it */
        for (uint32_t l = 0u; l < LEVELS; ++l) {
            const ft_clip_box *v = &c.level[l].valid;
            bad += (v->i1 < v->i0 || v->j1 < v->j0) ? 1 : 0;
        }
    }
    CHECK(bad == 0);
    CHECK(g_bad_update == 0);
    CHECK(lagged > 0u); /* one update a frame must fall behind this flight */
    CHECK(c.stats.levels_behind_max > 0u);
    drain(&c, -1, NULL);
    CHECK(c.stats.levels_behind == 0u);
    CHECK(check_mirror(&c) == 0);
    /* a jump far away: every level refilled whole, nothing stale */
    ft_clip_recentre(&c, 5.0e5, -3.0e5);
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        CHECK(c.level[l].samples_outstanding == (uint64_t)SIDE * SIDE);
    }
    g_read_samples = 0;
    drain(&c, -1, NULL);
    CHECK(g_read_samples == (uint64_t)LEVELS * SIDE * SIDE);
    CHECK(check_mirror(&c) == 0);
}

/* An update made stale by a move is not committed. */
static void test_stale_commit(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache(&c, &a, 2u * SIDE);
    ft_clip_recentre(&c, 0.0, 0.0);
    drain(&c, -1, NULL);
    ft_clip_recentre(&c, 40.0, 0.0);
    ft_clip_update u;
    int have = 0;
    ft_error err;
    REQUIRE(ft_clip_next_update(&c, &u, &have, &err) == FT_OK && have);
    const uint64_t updates = c.stats.updates;
    ft_clip_recentre(&c, 200.0, 0.0);
    upload(&c, &u); /* lands in texels outside every valid box */
    ft_clip_commit(&c, &u);
    CHECK(c.stats.updates == updates);
    CHECK(check_mirror(&c) == 0);
    drain(&c, -1, NULL);
    CHECK(check_mirror(&c) == 0);
}

static void test_plan_errors(void)
{
    ft_clip_source src = {read_synth, NULL, 8u, 0, 0, 0, 10, 0, 10};
    ft_error err;
    ft_clip_desc d = {48u, 4u, 96u, 0};
    CHECK(ft_clip_plan(&d, &src, NULL, &err) == FT_ERR_CONFIG && strstr(err.text, "clipmap.side"));
    d.side = 64u;
    d.levels = 9u;
    CHECK(ft_clip_plan(&d, &src, NULL, &err) == FT_ERR_CONFIG &&
          strstr(err.text, "clipmap.levels") && strstr(err.text, "gives 8"));
    d.levels = 0u;
    CHECK(ft_clip_plan(&d, &src, NULL, &err) == FT_ERR_CONFIG);
    d.levels = 8u;
    d.update_samples_max = 127u;
    CHECK(ft_clip_plan(&d, &src, NULL, &err) == FT_ERR_CONFIG &&
          strstr(err.text, "clipmap.update_samples_max"));
    d.update_samples_max = 128u;
    CHECK(ft_clip_plan(&d, &src, NULL, &err) == FT_OK);
    /* the staging comes from the clip pool: too small a budget is refused */
    ft_arena a;
    memset(&a, 0, sizeof(a));
    a.pools[FT_POOL_CLIP].budget_bytes = 128u;
    REQUIRE(ft_arena_bind(&a, g_arena_mem, sizeof(g_arena_mem), &err) == FT_OK);
    ft_clip_cache c;
    CHECK(ft_clip_init(&c, &d, &src, &a, &err) == FT_ERR_BUDGET &&
          strstr(err.text, "clip_bytes"));
}

/* The deviation of level l's cell (a, b) from the terrain, by the rule's
 * definition: the largest |h - H_l| over the terrain samples of the closed
 * cell, H_l the bilinear of the cell's clamped corner reads. */
static double ref_cell_dev(const float *h, int w, int ht, uint32_t l, int64_t a, int64_t b)
{
    const int64_t s = (int64_t)1 << l, x0 = a * s, y0 = b * s;
    double c[4];
    for (int k = 0; k < 4; ++k) {
        int64_t x = x0 + (k & 1) * s, y = y0 + (k >> 1) * s;
        x = x < 0 ? 0 : (x > w - 1 ? w - 1 : x);
        y = y < 0 ? 0 : (y > ht - 1 ? ht - 1 : y);
        c[k] = h[y * w + x];
    }
    double dev = 0.0;
    for (int64_t y = y0; y <= y0 + s; ++y) {
        for (int64_t x = x0; x <= x0 + s; ++x) {
            if (x < 0 || y < 0 || x > w - 1 || y > ht - 1) {
                continue;
            }
            const double u = (double)(x - x0) / (double)s, v = (double)(y - y0) / (double)s;
            const double bl = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + (1 - u) * v * c[2] +
                              u * v * c[3];
            dev = fmax(dev, fabs((double)h[y * w + x] - bl));
        }
    }
    return dev;
}

static void test_terrain_source(void)
{
    enum { W = 9, H = 7 };
    static float heights[W * H];
    static uint8_t voids[(W * H + 7) / 8];
    for (int k = 0; k < W * H; ++k) {
        heights[k] = (float)(k * 3 + 1 + (k * k) % 5); /* not bilinear: cells deviate */
    }
    voids[(2 * W + 4) >> 3] |= (uint8_t)(1u << ((2 * W + 4) & 7));
    ft_terrain t;
    memset(&t, 0, sizeof(t));
    t.width = W;
    t.height = H;
    t.heights_m = heights;
    t.void_bits = voids;
    ft_clip_source src;
    ft_clip_source_terrain(&src, &t);
    CHECK(src.data_i_hi == W - 1 && src.data_j_hi == H - 1 && src.lattice_i0 == 0);
    float out[16];
    uint8_t marks[16];
    ft_error err;
    /* level 1, samples (1..3) x (1..2): terrain (2,2) (4,2) (6,2) / (2,4) .. */
    float dev[16];
    CHECK(src.read(src.ctx, 1u, 1, 1, 3u, 2u, out, marks, dev, &err) == FT_OK);
    /* above level 0 each cell's deviation is exact: the largest |h - the
     * level's bilinear| at the terrain samples of the closed cell */
    for (uint32_t k = 0; k < 6u; ++k) {
        const double want = ref_cell_dev(heights, W, H, 1u, 1 + (int64_t)(k % 3u),
                                         1 + (int64_t)(k / 3u));
        CHECK((double)dev[k] >= want && (double)dev[k] <= want + 1e-3);
    }
    CHECK(dev[0] > 0.0f); /* the synthetic terrain is not bilinear there */
    CHECK(out[0] == heights[2 * W + 2] && out[1] == heights[2 * W + 4] &&
          out[2] == heights[2 * W + 6] && out[3] == heights[4 * W + 2]);
    CHECK(marks[0] == 0u && marks[1] == 1u && marks[2] == 0u); /* (4,2) is void */
    /* off the terrain: the nearest edge sample, marked */
    CHECK(src.read(src.ctx, 2u, -1, 1, 4u, 1u, out, marks, NULL, &err) == FT_OK);
    CHECK(out[0] == heights[4 * W + 0] && marks[0] == 1u);
    CHECK(out[1] == heights[4 * W + 0] && marks[1] == 0u);
    CHECK(out[3] == heights[4 * W + 8] && marks[3] == 0u);
    CHECK(src.read(src.ctx, 2u, 3, 2, 1u, 1u, out, marks, NULL, &err) == FT_OK);
    CHECK(out[0] == heights[6 * W + 8] && marks[0] == 1u); /* (12, 8) -> (8, 6) */
    /* level 0: the terrain is its own finest data; a cell off it is not drawn */
    CHECK(src.read(src.ctx, 0u, -1, 0, 3u, 1u, out, marks, dev, &err) == FT_OK);
    CHECK(dev[0] == 0.0f && dev[1] == 0.0f && dev[2] == 0.0f);
    /* a coarse cell past the terrain's edge: nothing drawn, 0; one across
     * it: over its part on the terrain */
    CHECK(src.read(src.ctx, 2u, (int64_t)W / 4 + 1, 0, 1u, 1u, out, marks, dev, &err) == FT_OK);
    CHECK(dev[0] == 0.0f);
    CHECK(src.read(src.ctx, 2u, 0, 1, 1u, 1u, out, marks, dev, &err) == FT_OK); /* rows 4..8 */
    const double edge = ref_cell_dev(heights, W, H, 2u, 0, 1);
    CHECK((double)dev[0] >= edge && (double)dev[0] <= edge + 1e-3 && edge > 0.0);
}

/* The blocks' errors against the synthetic source's deviations, recomputed
 * cell by cell from the lattice: every resident cell's dev + twist / 4 is
 * within its block's err_m and its dev within dev_m (+INF where a corner's
 * deviation is unknown; dev_m never over err_m),
 * every sample's distance to the next level's bilinear surface within
 * morph_m; and the bounds are tight (the largest cell of a block is its
 * err_m within the float steps) while the boxes move and lag. */
typedef struct block_check {
    const ft_clip_cache *c;
    uint64_t pieces, finite, unbounded, under, loose;
} block_check;

static double synth_h(uint32_t l, int64_t a, int64_t b)
{
    const int64_t s = (int64_t)1 << l;
    return (double)lattice_height(a * s, b * s);
}

static void check_block(void *ctx, uint32_t l, const ft_clip_block_bound *bb)
{
    block_check *k = ctx;
    const ft_clip_box *v = &k->c->level[l].valid;
    const int64_t s = (int64_t)1 << l;
    double worst = 0.0, worst_dev = 0.0;
    int unknown = 0;
    k->under += bb->dev_m > bb->err_m;
    for (int64_t b = bb->box.j0; b < bb->box.j1; ++b) {
        for (int64_t a = bb->box.i0; a < bb->box.i1; ++a) {
            if (l + 1u < LEVELS) {
                const double hc = 0.25 * (synth_h(l + 1u, a >> 1, b >> 1) +
                                          synth_h(l + 1u, (a + 1) >> 1, b >> 1) +
                                          synth_h(l + 1u, a >> 1, (b + 1) >> 1) +
                                          synth_h(l + 1u, (a + 1) >> 1, (b + 1) >> 1));
                k->under += fabs(synth_h(l, a, b) - hc) > (double)bb->morph_m;
            }
            if (a + 1 >= v->i1 || b + 1 >= v->j1) {
                continue;
            }
            int any_unknown = 0;
            for (int q = 0; q < 4; ++q) {
                any_unknown |= synth_dev_m(l, (a + (q & 1)) * s, (b + (q >> 1)) * s) < 0.0f;
            }
            if (any_unknown) {
                unknown = 1;
                continue;
            }
            const double tw = 0.25 * fabs(synth_h(l, a, b) + synth_h(l, a + 1, b + 1) -
                                          synth_h(l, a + 1, b) - synth_h(l, a, b + 1));
            worst = fmax(worst, (double)synth_dev_m(l, a * s, b * s) + tw);
            worst_dev = fmax(worst_dev, (double)synth_dev_m(l, a * s, b * s));
        }
    }
    k->pieces++;
    if (unknown) {
        k->under += !isinf(bb->err_m) || !isinf(bb->dev_m);
        k->unbounded++;
        return;
    }
    k->under += worst > (double)bb->err_m || worst_dev > (double)bb->dev_m;
    if (isfinite(bb->err_m)) {
        k->finite++;
        /* the block's apron holds more cells than the piece: only a block
         * whose piece is the whole block is held to tightness */
        const int whole = bb->box.i1 - bb->box.i0 == 16 && bb->box.j1 - bb->box.j0 == 16;
        k->loose += whole && (double)bb->err_m > 4.0 * worst + 1.0;
    }
}

static void test_block_errors(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache_kept(&c, &a, 256u, 1);
    block_check k = {&c, 0u, 0u, 0u, 0u, 0u};
    for (int step = 0; step < 30; ++step) {
        (void)ft_clip_recentre(&c, 23.0 * step - 200.0, -13.0 * step + 40.0);
        (void)drain(&c, step % 4 == 0 ? -1 : 5, NULL);
        for (uint32_t l = 0u; l < LEVELS; ++l) {
            (void)ft_clip_blocks_visit(&c, l, check_block, &k);
        }
    }
    printf("block errors: %llu pieces, %llu bounded, %llu unbounded, %llu under the cells, "
           "%llu loose\n",
           (unsigned long long)k.pieces, (unsigned long long)k.finite,
           (unsigned long long)k.unbounded, (unsigned long long)k.under,
           (unsigned long long)k.loose);
    CHECK(k.under == 0u);
    CHECK(k.loose == 0u);
    CHECK(k.finite > k.pieces / 2u && k.unbounded > 0u);
}

/* The cells' ranges over a terrain source (its samples are the finest
 * data): while the boxes move and lag, every cell of every level whose
 * four corners are resident holds every terrain sample of its closed
 * footprint (the finest bilinear surface takes its extremes there: the
 * footprint is whole finest cells), and is no wider than its corners'
 * range plus twice its deviation (the rule, not a looser one); a cache over
 * the synthetic source, whose band of unknown deviations gives an unbounded
 * range there and only there. */
static void test_cell_ranges(void)
{
    enum { W = 150, H = 110 };
    static float heights[W * H];
    for (int k = 0; k < W * H; ++k) {
        const int x = k % W, y = k / W;
        heights[k] = (float)(300.0 * sin(0.21 * x) * cos(0.13 * y) + 7.0 * ((k * 7919) % 13));
    }
    ft_terrain t;
    memset(&t, 0, sizeof(t));
    t.width = W;
    t.height = H;
    t.heights_m = heights;
    ft_clip_source src;
    ft_clip_source_terrain(&src, &t);
    ft_arena a;
    memset(&a, 0, sizeof(a));
    a.pools[FT_POOL_CLIP].budget_bytes = 1u << 19;
    ft_error err;
    REQUIRE(ft_arena_bind(&a, g_arena_mem, sizeof(g_arena_mem), &err) == FT_OK);
    ft_clip_cache c;
    const ft_clip_desc d = {16u, 3u, 64u, 1};
    REQUIRE(ft_clip_init(&c, &d, &src, &a, &err) == FT_OK);
    uint64_t cells = 0u, outside = 0u, wide = 0u;
    for (int step = 0; step < 40; ++step) {
        (void)ft_clip_recentre(&c, 20.0 + 2.7 * step, 15.0 + 2.1 * step);
        (void)drain(&c, step % 5 == 0 ? -1 : 3, NULL);
        for (uint32_t l = 0u; l < d.levels; ++l) {
            const ft_clip_box *v = &c.level[l].valid;
            const int64_t s = (int64_t)1 << l;
            for (int64_t b = v->j0; b + 1 < v->j1; ++b) {
                for (int64_t q = v->i0; q + 1 < v->i1; ++q) {
                    if ((q + 1) * s > W - 1 || (b + 1) * s > H - 1 || q < 0 || b < 0) {
                        continue; /* past the terrain: nothing is drawn there */
                    }
                    float lo, hi;
                    ft_clip_cell_range(&c, l, q, b, &lo, &hi);
                    double cmin = INFINITY, cmax = -INFINITY, fmin_ = INFINITY, fmax_ = -INFINITY;
                    for (int k = 0; k < 4; ++k) {
                        const double h = heights[((b + (k >> 1)) * s) * W + (q + (k & 1)) * s];
                        cmin = fmin(cmin, h);
                        cmax = fmax(cmax, h);
                    }
                    for (int64_t y = b * s; y <= (b + 1) * s; ++y) {
                        for (int64_t x = q * s; x <= (q + 1) * s; ++x) {
                            fmin_ = fmin(fmin_, heights[y * W + x]);
                            fmax_ = fmax(fmax_, heights[y * W + x]);
                        }
                    }
                    const double dev = ref_cell_dev(heights, W, H, l, q, b);
                    cells++;
                    outside += (double)lo > fmin_ || (double)hi < fmax_;
                    wide += (double)lo < cmin - dev - 1e-3 || (double)hi > cmax + dev + 1e-3;
                }
            }
        }
    }
    printf("cell ranges: %llu cells, %llu miss the finest data, %llu wider than the rule\n",
           (unsigned long long)cells, (unsigned long long)outside, (unsigned long long)wide);
    CHECK(cells > 10000u && outside == 0u && wide == 0u);
    /* unknown deviations: the synthetic source's band on level 2 */
    ft_clip_cache sc;
    ft_arena sa;
    make_cache_kept(&sc, &sa, 256u, 1);
    (void)ft_clip_recentre(&sc, 0.0, 0.0);
    (void)drain(&sc, -1, NULL);
    uint64_t unbounded = 0u, misplaced = 0u;
    const ft_clip_box *v = &sc.level[2].valid;
    for (int64_t b = v->j0; b + 1 < v->j1; ++b) {
        for (int64_t q = v->i0; q + 1 < v->i1; ++q) {
            float lo, hi;
            ft_clip_cell_range(&sc, 2u, q, b, &lo, &hi);
            int unknown = 0;
            for (int k = 0; k < 4; ++k) {
                unknown |= synth_dev_m(2u, (q + (k & 1)) * 4, (b + (k >> 1)) * 4) < 0.0f;
            }
            unbounded += isinf(lo) && isinf(hi);
            misplaced += unknown != (isinf(lo) && lo < 0.0f && isinf(hi) && hi > 0.0f);
        }
    }
    CHECK(unbounded > 0u && misplaced == 0u);
}

/* pgrid's leaves' bound over the cache (lod/pgrid.h 7) against every cell:
 * while the boxes move and lag and the eye looks around, the frame's bound
 * is at least every cell's own bound (ft_view_bound_error_px of its
 * deviation over its box) among the cells the traversal can end in (levels
 * >= 1, four corners resident, not held by the finer level's box) that meet
 * the view, and +INF when one of them has an unknown deviation (the
 * synthetic band on level 2), finite otherwise. Not vacuous: most frames
 * have leaves in view. */
typedef struct leaf_brute {
    double worst_px;
    int unknown;
} leaf_brute;

/* The synthetic source's heights lie in [-1000, 4000) m (lattice_height). */
#define SYNTH_TOP_M 4000.0

/* Every resident cell of every level by its nearest horizontal distance
 * from the eye, with the lowest of its corners: sorted, then prefix minima,
 * so the lowest drawn height of the cells at most r away is one search. */
typedef struct near_cell {
    double near_m, lo_m;
} near_cell;

static near_cell g_near[LEVELS * SIDE * SIDE];

static int near_cmp(const void *a, const void *b)
{
    const double x = ((const near_cell *)a)->near_m, y = ((const near_cell *)b)->near_m;
    return (x > y) - (x < y);
}

static double horiz_reach(const ft_view_bound *vb, double x0, double x1, double y0, double y1,
                          int farthest)
{
    const double a[2] = {x0 - vb->eye_m[0], y0 - vb->eye_m[1]};
    const double b[2] = {x1 - vb->eye_m[0], y1 - vb->eye_m[1]};
    double d2 = 0.0;
    for (int i = 0; i < 2; ++i) {
        const double n = a[i] > 0.0 ? a[i] : (b[i] < 0.0 ? -b[i] : 0.0);
        const double f = fmax(fabs(a[i]), fabs(b[i]));
        d2 += farthest ? f * f : n * n;
    }
    return sqrt(d2);
}

static size_t near_cells(const ft_clip_cache *c, const ft_view_bound *vb)
{
    size_t n = 0u;
    for (uint32_t l = 0u; l < LEVELS; ++l) {
        const ft_clip_box *r = &c->level[l].valid;
        const int64_t s = (int64_t)1 << l;
        for (int64_t b = r->j0; b + 1 < r->j1; ++b) {
            for (int64_t a = r->i0; a + 1 < r->i1; ++a) {
                double lo = INFINITY;
                for (int q = 0; q < 4; ++q) lo = fmin(lo, synth_h(l, a + (q & 1), b + (q >> 1)));
                g_near[n].near_m = horiz_reach(vb, (double)(a * s) * 90.0,
                                               (double)((a + 1) * s) * 90.0, (double)(b * s) * 90.0,
                                               (double)((b + 1) * s) * 90.0, 0);
                g_near[n].lo_m = lo;
                ++n;
            }
        }
    }
    qsort(g_near, n, sizeof g_near[0], near_cmp);
    for (size_t i = 1u; i < n; ++i) g_near[i].lo_m = fmin(g_near[i].lo_m, g_near[i - 1u].lo_m);
    return n;
}

/* The lowest drawn height of the cells at most r_m away (+INF: none). */
static double lowest_within(size_t n, double r_m)
{
    size_t lo = 0u, hi = n; /* the first cell farther than r_m */
    while (lo < hi) {
        const size_t mid = (lo + hi) / 2u;
        if (g_near[mid].near_m <= r_m) lo = mid + 1u; else hi = mid;
    }
    return lo == 0u ? INFINITY : g_near[lo - 1u].lo_m;
}

static void leaf_brute_force(const ft_clip_cache *c, const ft_pgm_clip_view *v,
                             const ft_view_bound *vb, leaf_brute *out)
{
    out->worst_px = 0.0;
    out->unknown = 0;
    /* the column of an unknown cell a ray can cross starts at the lowest
     * drawn height nearer than the cell's farthest point (the eye is over
     * every height here) */
    const size_t n = near_cells(c, vb);
    for (uint32_t l = 1u; l < LEVELS; ++l) {
        const ft_clip_box *r = &c->level[l].valid;
        const int64_t s = (int64_t)1 << l;
        const double *fb = v->box[l - 1u];
        const double fx0 = (double)v->base[l - 1u][0] + fb[0], fx1 = (double)v->base[l - 1u][0] + fb[2];
        const double fy0 = (double)v->base[l - 1u][1] + fb[1], fy1 = (double)v->base[l - 1u][1] + fb[3];
        for (int64_t b = r->j0; b + 1 < r->j1; ++b) {
            for (int64_t a = r->i0; a + 1 < r->i1; ++a) {
                const int held = fb[2] > fb[0] && fb[3] > fb[1] && 2.0 * (double)a >= fx0 &&
                                 2.0 * (double)(a + 1) <= fx1 && 2.0 * (double)b >= fy0 &&
                                 2.0 * (double)(b + 1) <= fy1;
                if (held) continue;
                double lo = INFINITY, hi = -INFINITY;
                int unknown = 0;
                for (int q = 0; q < 4; ++q) {
                    const double h = synth_h(l, a + (q & 1), b + (q >> 1));
                    lo = fmin(lo, h);
                    hi = fmax(hi, h);
                    unknown |= synth_dev_m(l, (a + (q & 1)) * s, (b + (q >> 1)) * s) < 0.0f;
                }
                const double dev = unknown ? 0.0 : (double)synth_dev_m(l, a * s, b * s);
                const double far_m = horiz_reach(vb, (double)(a * s) * 90.0,
                                                 (double)((a + 1) * s) * 90.0,
                                                 (double)(b * s) * 90.0,
                                                 (double)((b + 1) * s) * 90.0, 1);
                double blo[3] = {(double)(a * s) * 90.0, (double)(b * s) * 90.0,
                                 unknown ? lowest_within(n, far_m) : lo - dev};
                double bhi[3] = {(double)((a + 1) * s) * 90.0, (double)((b + 1) * s) * 90.0,
                                 unknown ? fmax(hi, SYNTH_TOP_M) : hi + dev};
                ft_view_bound_drawn_box(vb, blo, bhi);
                if (ft_view_bound_outside(vb, blo, bhi)) continue;
                if (unknown) {
                    out->unknown = 1;
                    continue;
                }
                out->worst_px = fmax(out->worst_px, ft_view_bound_error_px(vb, dev, blo, bhi));
            }
        }
    }
}

static void test_leaf_bound(void)
{
    ft_clip_cache c;
    ft_arena a;
    make_cache_kept(&c, &a, 256u, 1);
    const ft_clip_world w = {0.0, 0.0, 90.0, 90.0};
    uint32_t frames = 0u, under = 0u, with_leaves = 0u, finite = 0u, unknown = 0u;
    double slack_max = 0.0;
    for (int step = 0; step < 40; ++step) {
        const double ei = 23.0 * step - 200.0 + 0.37, ej = -13.0 * step + 40.0 + 0.61;
        (void)ft_clip_recentre(&c, ei, ej);
        (void)drain(&c, step % 4 == 0 ? -1 : 5, NULL);
        ft_pgm_clip_view v;
        memset(&v, 0, sizeof v);
        v.levels = LEVELS;
        for (uint32_t l = 0u; l < LEVELS; ++l) {
            const double sc = ldexp(1.0, (int)l);
            const ft_clip_box *r = &c.level[l].valid;
            v.base[l][0] = (int64_t)floor(ei / sc);
            v.base[l][1] = (int64_t)floor(ej / sc);
            v.box[l][0] = (double)(r->i0 - v.base[l][0]);
            v.box[l][1] = (double)(r->j0 - v.base[l][1]);
            v.box[l][2] = (double)(r->i1 - 1 - v.base[l][0]);
            v.box[l][3] = (double)(r->j1 - 1 - v.base[l][1]);
        }
        const double eye[3] = {ei * 90.0, ej * 90.0, 6000.0 + 100.0 * (step % 7)};
        ft_camera cam;
        ft_error err;
        REQUIRE(ft_camera_init(&cam, eye, 0.7 * step, -0.05 - 0.02 * (step % 9), 0.0,
                               1.0, 320u, 240u, 1.0, 1e6, &err) == FT_OK);
        const double b = ft_pgrid_cache_leaf_bound_px(&c, &v, &w, &cam, 0.0, SYNTH_TOP_M, 0.5);
        const double origin[2] = {0.0, 0.0};
        ft_view_bound vb;
        ft_view_bound_from_camera(&cam, origin, 0.0, &vb);
        leaf_brute br;
        leaf_brute_force(&c, &v, &vb, &br);
        frames++;
        with_leaves += br.worst_px > 0.0;
        unknown += br.unknown;
        finite += isfinite(b);
        if (br.unknown) {
            under += isfinite(b);
            if (isfinite(b)) printf("  finite %.3f px with an unknown deviation in view\n", b);
            continue;
        }
        under += b < br.worst_px;
        if (b < br.worst_px) printf("  %.4f px under the worst cell's %.4f\n", b, br.worst_px);
        if (isfinite(b)) slack_max = fmax(slack_max, b - br.worst_px);
    }
    printf("leaves' bound: %u frames, %u with leaves in view, %u with an unknown deviation "
           "there, %u finite, %u under the cells; largest excess over the worst cell %.3f px\n",
           frames, with_leaves, unknown, finite, under, slack_max);
    CHECK(under == 0u);
    CHECK(with_leaves * 2u > frames);
    /* every frame without an unknown deviation in view has a bound */
    CHECK(finite + unknown == frames && unknown > 0u && finite > 0u);
}

/* The worst pieces: 200 bounds (ties and +INF among them) into a list of
 * 5: the 5 largest kept, descending, with their levels and boxes; the rest
 * is the 6th largest and its level. */
static void test_worst_pieces(void)
{
    static double px[200];
    ft_worst_pieces w;
    ft_worst_pieces_init(&w, 5u);
    for (uint32_t k = 0u; k < 200u; ++k) {
        px[k] = (k == 77u) ? INFINITY : (double)((k * 7919u) % 101u);
        const ft_clip_box b = {(int64_t)k, 0, (int64_t)k + 1, 1};
        ft_worst_pieces_note(&w, k % 7u, &b, px[k]);
    }
    /* the 6 largest by a plain sort */
    double top[6] = {-1.0, -1.0, -1.0, -1.0, -1.0, -1.0};
    for (uint32_t k = 0u; k < 200u; ++k) {
        double v = px[k];
        for (int i = 0; i < 6; ++i) {
            if (v > top[i]) {
                const double t = top[i];
                top[i] = v;
                v = t;
            }
        }
    }
    int bad = (w.n != 5u);
    for (uint32_t i = 0u; i < w.n; ++i) {
        const ft_worst_piece *p = &w.piece[i];
        const int64_t k = p->box.i0;
        bad |= p->px != top[i] || p->px != px[k] || p->level != (uint32_t)(k % 7) ||
               p->box.i1 != k + 1;
    }
    bad |= w.rest_px != top[5];
    printf("worst pieces: kept %u, largest %g, rest %g\n", w.n, w.piece[0].px, w.rest_px);
    CHECK(!bad);
}

int main(void)
{
    test_fill_and_nesting();
    test_strips_read_only_new_samples();
    test_lagging_flight();
    test_stale_commit();
    test_plan_errors();
    test_terrain_source();
    test_max_height_in();
    test_block_errors();
    test_cell_ranges();
    test_worst_pieces();
    test_leaf_bound();
    return ft_test_result("test_clip_cache");
}
