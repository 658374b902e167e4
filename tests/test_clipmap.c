/* test_clipmap.c - the clipmap geometry on the CPU (src/lod/clipmap.h):
 * 1. Layout: for many valid-box configurations (current caches, lagging
 *    levels with valid smaller than wanted or empty, data extents cutting
 *    through the boxes), the triangles of every drawn level, placed by the
 *    shader's mirror (ft_cm_vertex), cover the coarsest drawn box within the
 *    data exactly once, each point by the level whose ring holds it, and
 *    nothing outside the data.
 * 2. Stitch: every vertex one level puts on the boundary with the next has
 *    the same position and height, to the bit, as the other level's vertex
 *    there; every fine boundary vertex on a transition side has a coarse
 *    partner (no T-junction), and the fine level's weight is 1 there.
 * 3. The template triangles are counter-clockwise and none is zero-area. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lod/clipmap.h"
#include "test_util.h"

#define SIDE 64
#define LEVELS 5
#define GRID_MAX (SIDE * 16 + 8) /* level-0 extent of the coarsest box */

static uint32_t g_rng = 2024u;
static uint32_t rnd(uint32_t n)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (g_rng >> 8) % n;
}

static float texel(void *ctx, uint32_t level, int64_t a, int64_t b)
{
    (void)ctx;
    uint32_t h = (uint32_t)(a * 73856093) ^ (uint32_t)(b * 19349663) ^ (level * 83492791u);
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (float)(h % 300000u) * 0.01f;
}

static int64_t even_floor(double x)
{
    return (int64_t)floor(x / 2.0) * 2;
}

/* A cache state: wanted boxes around the eye, valid sub-boxes (some lag). */
static void make_valid(ft_clip_box *valid, int lag)
{
    const double ex = 300.0 + rnd(400), ey = 300.0 + rnd(400);
    for (int k = LEVELS - 1; k >= 0; --k) {
        const double s = ldexp(1.0, k);
        ft_clip_box w;
        w.i0 = even_floor(ex / s - SIDE / 2);
        w.j0 = even_floor(ey / s - SIDE / 2);
        w.i1 = w.i0 + SIDE;
        w.j1 = w.j0 + SIDE;
        ft_clip_box v = w;
        if (lag && rnd(3) != 0u) {
            v.i0 += 2 * (int64_t)rnd(SIDE / 4);
            v.j0 += 2 * (int64_t)rnd(SIDE / 4);
            v.i1 -= 2 * (int64_t)rnd(SIDE / 4);
            v.j1 -= 2 * (int64_t)rnd(SIDE / 4);
            if (rnd(12) == 0u) v.j1 = v.j0; /* empty */
        }
        if (k + 1 < LEVELS) { /* a finer valid box stays inside the coarser one */
            const ft_clip_box *c = &valid[k + 1];
            if (v.i0 < 2 * c->i0) v.i0 = 2 * c->i0;
            if (v.j0 < 2 * c->j0) v.j0 = 2 * c->j0;
            if (v.i1 > 2 * c->i1) v.i1 = 2 * c->i1;
            if (v.j1 > 2 * c->j1) v.j1 = 2 * c->j1;
            if (c->i1 <= c->i0 || c->j1 <= c->j0) v.i1 = v.i0;
        }
        valid[k] = v;
    }
}

/* ---- triangles of a layout ---------------------------------------------------- */

typedef struct vert {
    float g[2], h;
    float w;
    uint32_t level;
    int inner; /* a strip's inner-row vertex */
} vert;

typedef struct collect {
    const ft_cm_layout *lay;
    vert *v;        /* 3 per triangle */
    size_t n, cap;
    uint32_t bad_template;
} collect;

static void collect_draw(void *ctx, const ft_cm_draw *d)
{
    collect *c = ctx;
    static uint16_t idx[FT_CM_BLOCK_INDICES];
    const uint32_t ni = ft_cm_template_indices(d->kind, idx);
    const uint32_t use = (d->kind == FT_CM_CORNER) ? 6u : ni;
    ft_cm_uniforms u;
    ft_cm_uniforms_of(c->lay, d, &u);
    for (uint32_t k = 0; k + 3u <= use; k += 3u) {
        vert tri[3];
        for (int q = 0; q < 3; ++q) {
            float t[2];
            ft_cm_template_vertex(d->kind, idx[k + (uint32_t)q], t);
            ft_cm_vertex_out o;
            ft_cm_vertex(&u, d->level, t, texel, NULL, &o);
            tri[q].g[0] = o.g[0];
            tri[q].g[1] = o.g[1];
            tri[q].h = o.h_m;
            tri[q].w = o.w;
            tri[q].level = d->level;
            tri[q].inner = (d->kind == FT_CM_STRIP && t[1] == 0.0f);
        }
        REQUIRE(c->n + 3u <= c->cap);
        memcpy(c->v + c->n, tri, sizeof tri);
        c->n += 3u;
    }
}

static double area2(const vert *t)
{
    return ((double)t[1].g[0] - t[0].g[0]) * ((double)t[2].g[1] - t[0].g[1]) -
           ((double)t[2].g[0] - t[0].g[0]) * ((double)t[1].g[1] - t[0].g[1]);
}

static uint8_t g_count[GRID_MAX][GRID_MAX];
static uint8_t g_level[GRID_MAX][GRID_MAX];

static int inside_rect_l0(const ft_cm_rect *r, uint32_t l, double x, double y)
{
    const double s = ldexp(1.0, (int)l);
    return x > r->x0 * s && x < r->x1 * s && y > r->y0 * s && y < r->y1 * s;
}

/* the level whose drawn part holds point (x, y), or -1 */
static int expected_level(const ft_cm_layout *lay, double x, double y)
{
    if (x < lay->data_lo[0] || x > lay->data_hi[0] || y < lay->data_lo[1] || y > lay->data_hi[1]) {
        return -1;
    }
    if (lay->drawn_count == 0u) return -1;
    for (uint32_t l = lay->finest; l <= lay->coarsest; ++l) {
        if (inside_rect_l0(&lay->level[l].box, l, x, y)) return (int)l;
    }
    return -1;
}

static void check_coverage(const ft_cm_layout *lay, const vert *v, size_t n, int64_t ox,
                           int64_t oy, uint32_t *bad)
{
    memset(g_count, 0, sizeof g_count);
    memset(g_level, 0xff, sizeof g_level);
    for (size_t k = 0; k < n; k += 3u) {
        const vert *t = v + k;
        const double a = area2(t);
        if (a == 0.0) continue; /* clamped away: draws nothing */
        double x0 = fmin(fmin(t[0].g[0], t[1].g[0]), t[2].g[0]);
        double x1 = fmax(fmax(t[0].g[0], t[1].g[0]), t[2].g[0]);
        double y0 = fmin(fmin(t[0].g[1], t[1].g[1]), t[2].g[1]);
        double y1 = fmax(fmax(t[0].g[1], t[1].g[1]), t[2].g[1]);
        for (int64_t py = (int64_t)floor(y0) - 1; py <= (int64_t)ceil(y1); ++py) {
            for (int64_t px = (int64_t)floor(x0) - 1; px <= (int64_t)ceil(x1); ++px) {
                const double x = (double)px + 0.37, y = (double)py + 0.21;
                int in = 1;
                for (int e = 0; e < 3; ++e) {
                    const vert *p = t + e, *q = t + (e + 1) % 3;
                    const double c = ((double)q->g[0] - p->g[0]) * (y - p->g[1]) -
                                     ((double)q->g[1] - p->g[1]) * (x - p->g[0]);
                    if ((a > 0.0) ? c < 0.0 : c > 0.0) in = 0;
                }
                if (!in) continue;
                const int64_t gx = px - ox, gy = py - oy;
                if (gx < 0 || gy < 0 || gx >= GRID_MAX || gy >= GRID_MAX) {
                    ++*bad;
                    continue;
                }
                g_count[gy][gx] = (uint8_t)(g_count[gy][gx] + 1u);
                g_level[gy][gx] = (uint8_t)t[0].level;
            }
        }
    }
    for (int64_t gy = 0; gy < GRID_MAX; ++gy) {
        for (int64_t gx = 0; gx < GRID_MAX; ++gx) {
            const double x = (double)(gx + ox) + 0.37, y = (double)(gy + oy) + 0.21;
            const int want = expected_level(lay, x, y);
            const int ok = (want < 0) ? g_count[gy][gx] == 0u
                                      : (g_count[gy][gx] == 1u && g_level[gy][gx] == want);
            if (!ok) {
                if (*bad < 5u) {
                    fprintf(stderr, "point (%.2f, %.2f): covered %u times (level %d), want level %d\n",
                            x, y, g_count[gy][gx], g_level[gy][gx] == 0xff ? -1 : g_level[gy][gx], want);
                }
                ++*bad;
            }
        }
    }
}

/* ---- stitch ------------------------------------------------------------------------ */

static int cmp_vert(const void *pa, const void *pb)
{
    const vert *a = pa, *b = pb;
    if (a->g[0] != b->g[0]) return a->g[0] < b->g[0] ? -1 : 1;
    if (a->g[1] != b->g[1]) return a->g[1] < b->g[1] ? -1 : 1;
    return 0;
}

static int on_rect_edge_l0(const ft_cm_rect *r, uint32_t l, const float g[2], int side)
{
    const float s = ldexpf(1.0f, (int)l);
    const float x0 = (float)r->x0 * s, x1 = (float)r->x1 * s, y0 = (float)r->y0 * s,
                y1 = (float)r->y1 * s;
    const int inx = g[0] >= x0 && g[0] <= x1, iny = g[1] >= y0 && g[1] <= y1;
    switch (side) {
    case FT_CM_W: return g[0] == x0 && iny;
    case FT_CM_E: return g[0] == x1 && iny;
    case FT_CM_S: return g[1] == y0 && inx;
    default: return g[1] == y1 && inx;
    }
}

/* The fine level (l - 1) against the coarse one (l) on the fine box's
 * transition sides. */
static void check_stitch(const ft_cm_layout *lay, uint32_t l, vert *v, size_t n, uint32_t *bad,
                         uint32_t *pairs)
{
    const ft_cm_level *f = &lay->level[l - 1u];
    /* sorted copies per level, of the vertices of non-degenerate triangles */
    static vert fine[1u << 20], coarse[1u << 20];
    size_t nf = 0, nc = 0;
    for (size_t k = 0; k < n; k += 3u) {
        if (area2(v + k) == 0.0) continue;
        for (int q = 0; q < 3; ++q) {
            const vert *p = v + k + q;
            if (p->level == l - 1u && nf < (1u << 20)) fine[nf++] = *p;
            if (p->level == l && nc < (1u << 20)) coarse[nc++] = *p;
        }
    }
    qsort(fine, nf, sizeof *fine, cmp_vert);
    qsort(coarse, nc, sizeof *coarse, cmp_vert);
    for (size_t k = 0; k < nf; ++k) {
        const vert *p = fine + k;
        int side_hit = -1;
        for (int s = 0; s < 4; ++s) {
            if (f->transition[s] && on_rect_edge_l0(&f->box, l - 1u, p->g, s)) side_hit = s;
        }
        if (side_hit < 0) continue;
        if (p->w != 1.0f) {
            if (*bad < 5u) fprintf(stderr, "fine boundary vertex weight %g\n", (double)p->w);
            ++*bad;
        }
        const vert *q = bsearch(p, coarse, nc, sizeof *coarse, cmp_vert);
        if (q == NULL) {
            if (*bad < 5u) {
                const ft_cm_level *cl = &lay->level[l];
                fprintf(stderr, "level %u boundary vertex (%g, %g) side %d has no level-%u partner "
                        "(fine box %lld %lld %lld %lld, coarse box %lld %lld %lld %lld hole %lld %lld %lld %lld, data %lld %lld %lld %lld)\n",
                        l - 1u, (double)p->g[0], (double)p->g[1], side_hit, l,
                        (long long)f->box.x0, (long long)f->box.y0, (long long)f->box.x1, (long long)f->box.y1,
                        (long long)cl->box.x0, (long long)cl->box.y0, (long long)cl->box.x1, (long long)cl->box.y1,
                        (long long)cl->hole.x0, (long long)cl->hole.y0, (long long)cl->hole.x1, (long long)cl->hole.y1,
                        (long long)lay->data_lo[0], (long long)lay->data_lo[1], (long long)lay->data_hi[0], (long long)lay->data_hi[1]);
            }
            ++*bad;
            continue;
        }
        ++*pairs;
        if (memcmp(&q->h, &p->h, sizeof p->h) != 0) {
            if (*bad < 5u) {
                fprintf(stderr, "stitch (%g, %g): fine h %.9g, coarse h %.9g (coarse w %g)\n",
                        (double)p->g[0], (double)p->g[1], (double)p->h, (double)q->h,
                        (double)q->w);
            }
            ++*bad;
        }
    }
    /* the other way: every coarse inner strip vertex meets a fine vertex */
    for (size_t k = 0; k < nc; ++k) {
        const vert *q = coarse + k;
        if (!q->inner) continue;
        const vert *p = bsearch(q, fine, nf, sizeof *fine, cmp_vert);
        if (p == NULL || memcmp(&q->h, &p->h, sizeof p->h) != 0) {
            if (*bad < 5u) {
                fprintf(stderr, "level %u stitch vertex (%g, %g) unmatched by level %u\n", l,
                        (double)q->g[0], (double)q->g[1], l - 1u);
            }
            ++*bad;
        }
    }
}

static void check_templates(void)
{
    static uint16_t idx[FT_CM_BLOCK_INDICES];
    const ft_cm_kind kinds[2] = {FT_CM_BLOCK, FT_CM_STRIP};
    for (int k = 0; k < 2; ++k) {
        const uint32_t n = ft_cm_template_indices(kinds[k], idx);
        CHECK(n == (k == 0 ? FT_CM_BLOCK_INDICES : FT_CM_STRIP_INDICES));
        for (uint32_t i = 0; i + 2u < n; i += 3u) {
            vert t[3];
            for (int q = 0; q < 3; ++q) {
                CHECK(idx[i + (uint32_t)q] < ft_cm_template_vertex_count(kinds[k]));
                ft_cm_template_vertex(kinds[k], idx[i + (uint32_t)q], t[q].g);
            }
            CHECK(area2(t) > 0.0);
        }
    }
}

int main(void)
{
    static vert buf[1u << 21];
    check_templates();
    uint32_t bad_cover = 0, bad_stitch = 0, pairs = 0, configs = 0, lagging = 0, narrow = 0;
    for (int it = 0; it < 160; ++it) {
        ft_clip_box valid[LEVELS];
        const int lag = (it % 2) == 1;
        make_valid(valid, lag);
        int64_t lo[2] = {0, 0}, hi[2] = {1200, 1200};
        if (it % 4 >= 2) { /* data edges through the boxes */
            lo[0] = 200 + rnd(500);
            lo[1] = 200 + rnd(500);
            hi[0] = lo[0] + 1 + rnd(600);
            hi[1] = lo[1] + 1 + rnd(600);
        }
        ft_cm_layout lay;
        ft_cm_layout_make(&lay, LEVELS, valid, lo, hi, 6.0);
        collect c = {&lay, buf, 0, sizeof buf / sizeof buf[0], 0};
        uint64_t tris = 0;
        for (uint32_t l = 0; l < LEVELS; ++l) {
            tris += ft_cm_level_draws(&lay, l, collect_draw, &c);
        }
        (void)tris;
        /* the count grid's origin: the coarsest box's corner */
        const uint32_t lc = lay.drawn_count ? lay.coarsest : 0u;
        const int64_t ox = lay.drawn_count ? (lay.level[lc].box.x0 << lc) - 2 : 0;
        const int64_t oy = lay.drawn_count ? (lay.level[lc].box.y0 << lc) - 2 : 0;
        check_coverage(&lay, buf, c.n, ox, oy, &bad_cover);
        for (uint32_t l = 1; l < LEVELS; ++l) {
            if (lay.level[l].drawn && lay.level[l].has_hole) {
                check_stitch(&lay, l, buf, c.n, &bad_stitch, &pairs);
                if (lay.level[l].transition_samples < 6.0) ++narrow;
            }
        }
        ++configs;
        lagging += (uint32_t)lag;
    }
    printf("%u configurations (%u lagging, %u narrow rings): coverage failures %u, stitch "
           "failures %u over %u boundary vertex pairs\n",
           configs, lagging, narrow, bad_cover, bad_stitch, pairs);
    CHECK(bad_cover == 0u);
    CHECK(bad_stitch == 0u);
    CHECK(pairs > 1000u);
    CHECK(narrow > 0u); /* the cap on T_l was exercised */
    return ft_test_result("test_clipmap");
}
