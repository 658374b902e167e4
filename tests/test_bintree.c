/* test_bintree.c - the bintree's tables and selection, checked against
 * independent brute-force computations (no GPU).
 *
 *  - conformity after every selection (culling off): every interior tile
 *    edge is shared by exactly two tiles with the same endpoints, with the
 *    level rule (hypotenuse against leg: levels differ by one, the finer tile
 *    has the hypotenuse; same kind: same level), and the clamped tile areas
 *    sum to the grid's area (no gap, no overlap);
 *  - culling only removes tiles: the culled selection is a subset;
 *  - error tables: for every selected tile, the template error recomputed by
 *    point location (descending the tile's own LEB refinement) is <= the
 *    stored saturated error, 0 for leaf tiles, and the samples lie in the
 *    stored box;
 *  - the bound: K * err * gain / dist(eye, tile) <= tau for every drawn tile
 *    (gain: view_scale.h, over the tile's own box);
 *  - the tile budget: never exceeded, tau raised and reported;
 *  - geomorph rule: a morphing vertex is the midpoint of its coarse edge and
 *    its insertion diamond is an ancestor of every tile that draws it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lod/bintree.h"
#include "lod/bintree_template.h"
#include "terrain/pyramid.h"
#include "test_util.h"

static uint32_t g_rng = 777u;
static double urand(void)
{
    g_rng = g_rng * 1664525u + 1013904223u;
    return (double)(g_rng >> 8) / 16777216.0;
}

static void *g_pyr_storage[16]; /* make_terrain's pyramids, freed at the end */
static int g_pyr_count;

static void make_terrain(ft_terrain *t, uint32_t w, uint32_t h, double spacing_m)
{
    memset(t, 0, sizeof *t);
    t->width = w;
    t->height = h;
    t->cell_x_m = t->cell_y_m = spacing_m;
    t->heights_m = malloc((size_t)w * h * sizeof(float));
    REQUIRE(t->heights_m != NULL);
    float lo = 1e30f, hi = -1e30f;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            double v = 400.0 * sin(0.05 * x) * cos(0.07 * y) + 150.0 * sin(0.3 * x + 0.2 * y) +
                       20.0 * urand();
            if (x == w / 3 && y == h / 2) v += 900.0; /* a needle */
            float f = (float)v;
            t->heights_m[(size_t)y * w + x] = f;
            lo = f < lo ? f : lo;
            hi = f > hi ? f : hi;
        }
    }
    t->min_height_m = lo;
    t->max_height_m = hi;
    /* the min/max pyramid bounds sub-sample boxes */
    const size_t pbytes = (ft_pyramid_bytes(w, h) + 63u) / 64u * 64u;
    void *pyr = aligned_alloc(64, pbytes > 0u ? pbytes : 64u);
    ft_error err;
    REQUIRE(pyr != NULL && ft_pyramid_layout(t, pyr, pbytes, &err) == FT_OK);
    ft_pyramid_build(t);
    t->min_height_m = lo;
    t->max_height_m = hi;
    REQUIRE(g_pyr_count < 16);
    g_pyr_storage[g_pyr_count++] = pyr;
}

static int64_t edge_fn(const int32_t a[2], const int32_t b[2], const int32_t p[2])
{
    return (int64_t)(b[0] - a[0]) * (p[1] - a[1]) - (int64_t)(b[1] - a[1]) * (p[0] - a[0]);
}

static int inside(const int32_t a[2], const int32_t b[2], const int32_t c[2], const int32_t p[2])
{
    return edge_fn(a, b, p) >= 0 && edge_fn(b, c, p) >= 0 && edge_fn(c, a, p) >= 0;
}

static double hgt(const ft_terrain *t, int32_t x, int32_t y)
{
    return t->heights_m[(size_t)y * t->width + (size_t)x];
}

/* The bilinear surface (the truth) at dense point p (units 1/dn cell). */
static double bilinear_dense(const ft_terrain *t, int32_t dn, const int32_t p[2])
{
    int32_t cx = p[0] / dn, cy = p[1] / dn;
    cx = cx > (int32_t)t->width - 2 ? (int32_t)t->width - 2 : cx;
    cy = cy > (int32_t)t->height - 2 ? (int32_t)t->height - 2 : cy;
    const double u = (double)(p[0] - cx * dn) / dn, v = (double)(p[1] - cy * dn) / dn;
    const double h00 = hgt(t, cx, cy), h10 = hgt(t, cx + 1, cy), h01 = hgt(t, cx, cy + 1),
                 h11 = hgt(t, cx + 1, cy + 1);
    return h00 + (h10 - h00) * u + (h01 - h00) * v + (h00 + h11 - h10 - h01) * u * v;
}

/* Template surface of a tile (fine units) at dense point p: the tile scaled
 * by sc = dense points per fine unit; its template vertices take the height
 * the method gives them (ft_bt_height_fine: samples, or bilinear between). */
static double template_height_dense(const ft_bintree *bt, int32_t sc, const ft_bt_tile *tile,
                                    const int32_t p[2])
{
    int32_t a[2] = {tile->apex[0] * sc, tile->apex[1] * sc},
            l[2] = {tile->left[0] * sc, tile->left[1] * sc},
            r[2] = {tile->right[0] * sc, tile->right[1] * sc};
    for (uint32_t i = 0; i < 2u * bt->k; ++i) {
        int32_t m[2] = {(l[0] + r[0]) / 2, (l[1] + r[1]) / 2};
        if (inside(m, a, l, p)) {
            memcpy(r, l, sizeof r); memcpy(l, a, sizeof l); memcpy(a, m, sizeof a);
        } else {
            memcpy(l, r, sizeof l); memcpy(r, a, sizeof r); memcpy(a, m, sizeof a);
        }
    }
    double area2 = (double)edge_fn(a, l, r);
    double w0 = (double)edge_fn(l, r, p), w1 = (double)edge_fn(r, a, p),
           w2 = (double)edge_fn(a, l, p);
    return (w0 * ft_bt_height_fine(bt, a[0] / sc, a[1] / sc) +
            w1 * ft_bt_height_fine(bt, l[0] / sc, l[1] / sc) +
            w2 * ft_bt_height_fine(bt, r[0] / sc, r[1] / sc)) / area2;
}

typedef struct edge_rec {
    int32_t x0, y0, x1, y1;
    uint32_t level;
    int hyp;
} edge_rec;

static int cmp_edge(const void *pa, const void *pb)
{
    const edge_rec *a = pa, *b = pb;
    if (a->x0 != b->x0) return a->x0 < b->x0 ? -1 : 1;
    if (a->y0 != b->y0) return a->y0 < b->y0 ? -1 : 1;
    if (a->x1 != b->x1) return a->x1 < b->x1 ? -1 : 1;
    if (a->y1 != b->y1) return a->y1 < b->y1 ? -1 : 1;
    return 0;
}

static void add_edge(edge_rec *e, const int32_t p[2], const int32_t q[2], uint32_t level, int hyp)
{
    int swap = (p[0] > q[0]) || (p[0] == q[0] && p[1] > q[1]);
    e->x0 = swap ? q[0] : p[0];
    e->y0 = swap ? q[1] : p[1];
    e->x1 = swap ? p[0] : q[0];
    e->y1 = swap ? p[1] : q[1];
    e->level = level;
    e->hyp = hyp;
}

static int on_domain_boundary(const edge_rec *e, int32_t n)
{
    return (e->x0 == e->x1 && (e->x0 == 0 || e->x0 == n)) ||
           (e->y0 == e->y1 && (e->y0 == 0 || e->y0 == n));
}

/* Full conformity check of a culling-free selection. Returns failures. */
static int check_conforming(const ft_bintree *bt, uint32_t count, edge_rec *edges)
{
    int bad = 0;
    const int32_t n = (int32_t)bt->fine_side;
    const int32_t wx = ((int32_t)bt->width - 1) << bt->sub;
    const int32_t hy = ((int32_t)bt->height - 1) << bt->sub;
    double area2 = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        const ft_bt_tile *t = &bt->tiles[i];
        add_edge(&edges[3u * i + 0u], t->left, t->right, t->level, 1);
        add_edge(&edges[3u * i + 1u], t->apex, t->left, t->level, 0);
        add_edge(&edges[3u * i + 2u], t->right, t->apex, t->level, 0);
        int32_t c[3][2];
        const int32_t *v[3] = {t->apex, t->left, t->right};
        for (int j = 0; j < 3; ++j) {
            c[j][0] = v[j][0] > wx ? wx : v[j][0];
            c[j][1] = v[j][1] > hy ? hy : v[j][1];
        }
        area2 += (double)edge_fn(c[0], c[1], c[2]);
    }
    if (fabs(area2 - 2.0 * wx * hy) > 0.5) {
        fprintf(stderr, "clamped area2 %.0f != %.0f\n", area2, 2.0 * wx * hy);
        ++bad;
    }
    qsort(edges, 3u * count, sizeof *edges, cmp_edge);
    for (uint32_t i = 0; i < 3u * count;) {
        uint32_t j = i + 1u;
        while (j < 3u * count && cmp_edge(&edges[i], &edges[j]) == 0) ++j;
        uint32_t m = j - i;
        if (m == 1u) {
            /* unmatched: only allowed on the domain boundary or in the padding */
            int padding = edges[i].x0 >= wx || edges[i].y0 >= hy || edges[i].x1 >= wx ||
                          edges[i].y1 >= hy;
            if (!on_domain_boundary(&edges[i], n) && !padding) {
                if (bad < 5) {
                    fprintf(stderr, "unmatched edge (%d,%d)-(%d,%d) level %u\n", edges[i].x0,
                            edges[i].y0, edges[i].x1, edges[i].y1, edges[i].level);
                }
                ++bad;
            }
        } else if (m == 2u) {
            const edge_rec *a = &edges[i], *b = &edges[i + 1u];
            int ok;
            if (a->hyp == b->hyp) {
                ok = a->level == b->level;
            } else {
                const edge_rec *hyp = a->hyp ? a : b, *leg = a->hyp ? b : a;
                ok = hyp->level == leg->level + 1u;
            }
            if (!ok) {
                ++bad;
            }
        } else {
            ++bad;
        }
        i = j;
    }
    return bad;
}

static int cmp_pt(const void *pa, const void *pb)
{
    const int32_t *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

/* A culled selection is still conforming where it draws: no tile corner lies
 * at the midpoint of another tile's edge (in a bintree that is the only
 * place a T-junction can sit). Returns the T-junctions; pts holds 3 points
 * a tile. */
static int count_t_junctions(const ft_bintree *bt, uint32_t count, int32_t (*pts)[2])
{
    for (uint32_t i = 0; i < count; ++i) {
        const ft_bt_tile *t = &bt->tiles[i];
        memcpy(pts[3u * i], t->apex, sizeof pts[0]);
        memcpy(pts[3u * i + 1u], t->left, sizeof pts[0]);
        memcpy(pts[3u * i + 2u], t->right, sizeof pts[0]);
    }
    qsort(pts, 3u * count, sizeof pts[0], cmp_pt);
    int bad = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const ft_bt_tile *t = &bt->tiles[i];
        const int32_t *v[3] = {t->apex, t->left, t->right};
        for (int e = 0; e < 3; ++e) {
            const int32_t *a = v[e], *b = v[(e + 1) % 3];
            if (((a[0] + b[0]) & 1) || ((a[1] + b[1]) & 1)) continue;
            int32_t m[2] = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
            if (bsearch(m, pts, 3u * count, sizeof pts[0], cmp_pt) != NULL) {
                if (bad < 3) {
                    fprintf(stderr, "T-junction: tile level %u edge (%d,%d)-(%d,%d) has a corner "
                            "at its midpoint\n", t->level, a[0], a[1], b[0], b[1]);
                }
                ++bad;
            }
        }
    }
    return bad;
}

static void random_view(const ft_terrain *t, uint32_t n_cells, ft_camera *cam)
{
    double ext = (double)n_cells * t->cell_x_m;
    double eye[3] = {ext * (urand() * 1.4 - 0.2), ext * (urand() * 1.4 - 0.2),
                     t->max_height_m + (urand() < 0.3 ? 5.0 : 3000.0 * urand())};
    ft_error err;
    REQUIRE(ft_camera_init(cam, eye, urand() * 6.283, -1.4 * urand(), 0.0, 1.0, 640, 480, 1.0,
                           1e6, &err) == FT_OK);
}

static int tile_key_cmp(const void *pa, const void *pb)
{
    return memcmp(pa, pb, sizeof(ft_bt_tile));
}

/* Ancestors' split vertices of a tile (descending from the root holding its
 * centroid). Returns how many (= tile level). */
static uint32_t ancestors(const ft_bintree *bt, const ft_bt_tile *tile, int32_t out[][2])
{
    const int32_t n = (int32_t)bt->fine_side;
    int32_t p2[2] = {tile->apex[0] + tile->left[0] + tile->right[0],
                     tile->apex[1] + tile->left[1] + tile->right[1]}; /* 3x centroid */
    int32_t a[2] = {3 * n, 0}, l[2] = {3 * n, 3 * n}, r[2] = {0, 0};
    if (!inside(a, l, r, p2)) {
        a[0] = 0; a[1] = 3 * n; l[0] = 0; l[1] = 0; r[0] = 3 * n; r[1] = 3 * n;
    }
    for (uint32_t i = 0; i < tile->level; ++i) {
        int32_t m[2] = {(l[0] + r[0]) / 2, (l[1] + r[1]) / 2};
        out[i][0] = m[0] / 3;
        out[i][1] = m[1] / 3;
        if (inside(m, a, l, p2)) {
            memcpy(r, l, sizeof r); memcpy(l, a, sizeof l); memcpy(a, m, sizeof a);
        } else {
            memcpy(l, r, sizeof l); memcpy(r, a, sizeof r); memcpy(a, m, sizeof a);
        }
    }
    return tile->level;
}

/* Tiles [0, tiles_coarse) are coarser than the samples (every template
 * vertex on one), the rest (S > 0 only) finer: the method draws the two
 * kinds with different programs. Returns the misplaced tiles. */
static int check_partition(const ft_bintree *bt, const ft_bt_select_stats *ss)
{
    int bad = 0;
    for (uint32_t i = 0; i < ss->tiles; ++i) {
        const int fine = bt->sub > 0u && bt->tiles[i].level >= bt->sub_level;
        bad += (i < ss->tiles_coarse) ? fine : !fine;
    }
    return bad;
}

/* The method sends a tile as (apex, left) and the shader takes right = apex
 * + (left - apex) turned a quarter counter-clockwise: every tile must be a
 * right isosceles triangle with that turn. Returns the tiles that are not. */
static int check_right_from_left(const ft_bintree *bt, const ft_bt_select_stats *ss)
{
    int bad = 0;
    for (uint32_t i = 0; i < ss->tiles; ++i) {
        const ft_bt_tile *t = &bt->tiles[i];
        const int32_t lx = t->left[0] - t->apex[0], ly = t->left[1] - t->apex[1];
        bad += (t->right[0] != t->apex[0] - ly || t->right[1] != t->apex[1] + lx);
    }
    return bad;
}

/* The vertex table (ft_bt_sample_texel) against the rules it packs: the
 * sample, the morph's coarse height in float, the selection's error of the
 * inserting diamond, and the normal within its 12-bit quantisation. */
static int check_vertex_table(const ft_bintree *bt, const ft_terrain *t)
{
    int bad = 0;
    double normal_err = 0.0;
    uint32_t morphing = 0;
    for (uint32_t gy = 0; gy < bt->height; ++gy) {
        for (uint32_t gx = 0; gx < bt->width; ++gx) {
            float tx[4];
            ft_bt_sample_texel(bt, gx, gy, tx);
            const float h = t->heights_m[(size_t)gy * t->width + gx];
            bad += tx[0] != h;
            int32_t e0[2], e1[2], c[2];
            uint32_t level = 0;
            const int32_t x = (int32_t)gx << bt->sub, y = (int32_t)gy << bt->sub;
            if (!ft_bt_vertex_morph(bt, x, y, e0, e1, c, &level)) {
                bad += tx[1] != h || tx[2] != -1.0f;
            } else {
                const float h0 = ft_bt_height_fine(bt, e0[0], e0[1]);
                const float h1 = ft_bt_height_fine(bt, e1[0], e1[1]);
                const float sum = h0 + h1;
                bad += tx[1] != 0.5f * sum;
                const int32_t s = (x | y) & -(x | y);
                const int even = ((x / s) & 1) != 0 && ((y / s) & 1) != 0;
                const uint32_t sd = 2u * (uint32_t)s * bt->step;
                uint32_t half = 0;
                while ((bt->fine_side >> half) > sd) {
                    ++half;
                }
                float box[FT_BT_BOX_FLOATS];
                const double e = ft_bt_diamond_error(bt, 2u * half + (even ? 0u : 1u), c, box);
                bad += (double)tx[2] != e;
                bad += level != 2u * half + (even ? 0u : 1u);
                morphing += 1u;
            }
            /* the normal: central differences, one-sided at the edge */
            const uint32_t x0 = gx > 0u ? gx - 1u : 0u, x1 = gx + 1u < t->width ? gx + 1u : gx;
            const uint32_t y0 = gy > 0u ? gy - 1u : 0u, y1 = gy + 1u < t->height ? gy + 1u : gy;
            const double dhx = ((double)t->heights_m[(size_t)gy * t->width + x1] -
                                t->heights_m[(size_t)gy * t->width + x0]) /
                               ((double)(x1 - x0) * t->cell_x_m);
            const double dhy = ((double)t->heights_m[(size_t)y1 * t->width + gx] -
                                t->heights_m[(size_t)y0 * t->width + gx]) /
                               ((double)(y1 - y0) * t->cell_y_m);
            const double len = sqrt(dhx * dhx + dhy * dhy + 1.0);
            const double n[3] = {-dhx / len, -dhy / len, 1.0 / len};
            double u[3];
            ft_bt_unpack_normal(tx[3], u);
            for (int i = 0; i < 3; ++i) {
                normal_err = fmax(normal_err, fabs(u[i] - n[i]));
            }
        }
    }
    printf("  vertex table: %u x %u texels (%u morph), normal quantisation error %.2e\n",
           bt->width, bt->height, morphing, normal_err);
    /* 12 bits a hemi-octahedral component: under 5e-4 anywhere on the hemisphere */
    bad += !(normal_err < 1e-3);
    return bad;
}

/* 2x the signed area of (a, b, p), p in fine units. */
static double orient_fine(const int32_t a[2], const int32_t b[2], const double p[2])
{
    return ((double)b[0] - a[0]) * (p[1] - a[1]) - ((double)b[1] - a[1]) * (p[0] - a[0]);
}

/* The back-face rule recomputed from the selection itself: the eye over
 * the grid and above the box top of every selected (unculled) tile that
 * holds its xy. */
static int back_faces_hidden_brute(const ft_bintree *bt, const ft_terrain *t,
                                   const ft_bt_view *v, uint32_t tiles)
{
    const double f = (double)(1u << bt->sub);
    const double ex = v->b.eye_m[0] / t->cell_x_m, ey = v->b.eye_m[1] / t->cell_y_m;
    if (!(ex >= 0.0 && ey >= 0.0 && ex <= (double)t->width - 1.0 &&
          ey <= (double)t->height - 1.0)) {
        return 0;
    }
    const double p[2] = {ex * f, ey * f};
    int found = 0;
    double top = -INFINITY;
    for (uint32_t i = 0; i < tiles; ++i) {
        const ft_bt_tile *tl = &bt->tiles[i];
        const double a = orient_fine(tl->apex, tl->left, p), b = orient_fine(tl->left, tl->right, p),
                     c = orient_fine(tl->right, tl->apex, p);
        if ((a >= 0.0 && b >= 0.0 && c >= 0.0) || (a <= 0.0 && b <= 0.0 && c <= 0.0)) {
            const int32_t cc[2] = {(tl->left[0] + tl->right[0]) / 2,
                                   (tl->left[1] + tl->right[1]) / 2};
            float box[FT_BT_BOX_FLOATS];
            (void)ft_bt_diamond_error(bt, tl->level, cc, box);
            top = fmax(top, (double)box[5]);
            found = 1;
        }
    }
    return found && v->b.eye_m[2] > top + 0.01;
}

static int g_low_hidden, g_low_shown; /* eyes near the ground, over all cases */

static void run_case(uint32_t w, uint32_t h, uint32_t k, uint32_t sub, uint32_t views,
                     int exact_checks)
{
    const int32_t f_per_cell = 1 << sub;
    const int32_t dn = f_per_cell > 2 ? 4 * f_per_cell : 8; /* dense truth points a cell side */
    const int32_t sc = dn / f_per_cell;
    ft_terrain t;
    make_terrain(&t, w, h, 30.0);
    ft_arena a;
    memset(&a, 0, sizeof a);
    const uint32_t tiles_max = 200000u;
    ft_bintree_plan(&a, w, h, k, sub, tiles_max);
    a.pools[FT_POOL_METHOD].budget_bytes = a.pools[FT_POOL_METHOD].need_bytes;
    size_t total = ft_arena_total_budget(&a);
    void *mem = aligned_alloc(FT_ARENA_ALIGN, total);
    ft_error err;
    REQUIRE(mem != NULL && ft_arena_bind(&a, mem, total, &err) == FT_OK);
    ft_bintree bt;
    ft_status st = ft_bintree_init(&bt, &t, k, sub, FT_BT_MORPH_WIDTH, tiles_max, &a, &err);
    if (st != FT_OK) {
        fprintf(stderr, "init %ux%u k=%u: %s\n", w, h, k, err.text);
    }
    REQUIRE(st == FT_OK);
    CHECK(bt.flipped_triangles == 0u);
    printf("grid %ux%u k=%u: N=%u leaf level %u lattice %u max err %.2f m\n", w, h, k,
           bt.side_cells, bt.leaf_level, bt.lattice_side, bt.max_err_m);
    edge_rec *edges = malloc(3u * tiles_max * sizeof *edges);
    ft_bt_tile *nocull = malloc(tiles_max * sizeof *nocull);
    int32_t(*pts)[2] = malloc(3u * tiles_max * sizeof *pts);
    REQUIRE(pts != NULL);
    REQUIRE(edges && nocull);
    static const double taus[] = {0.0, 0.5, 1.0, 2.0, 4.0, 16.0};
    uint32_t total_tiles = 0, morph_vertices = 0, checked_vertices = 0;
    int bad_conf = 0, bad_subset = 0, bad_err = 0, bad_bound = 0, bad_morph = 0;
    int leaf_tiles = 0, leaf_short = 0, bad_tjunctions = 0, bad_pop = 0;
    uint32_t moving_vertices = 0, gap_pairs = 0;
    int bad_gap = 0;
    int bad_back = 0, hidden_views = 0;
    double dense_max_ratio = 0.0; /* largest dense error / stored error: <= 1 */
    int ratio_tiles = 0;
    for (uint32_t vi = 0; vi < views; ++vi) {
        ft_camera cam;
        random_view(&t, bt.side_cells, &cam);
        double tau = taus[vi % (sizeof taus / sizeof taus[0])];
        if (sub > 0u && tau == 0.0) tau = 0.25; /* every leaf of a sub-sample tree is too many */
        int morph = (int)(vi & 1u);
        ft_bt_view v;
        ft_bt_view_from_camera(&cam, &t, 0, morph, &v);
        ft_bt_select_stats ss;
        ft_bintree_select(&bt, &v, tau, &ss);
        CHECK(ss.tiles <= tiles_max);
        CHECK(check_partition(&bt, &ss) == 0);
        CHECK(check_right_from_left(&bt, &ss) == 0);
        CHECK(!ss.budget_hit);
        CHECK(ss.tau_used_px == tau);
        CHECK(ss.tau_achieved_px == fmax(tau, ss.leaf_px_max));
        /* the back-face rule's walk finds the tile the selection draws under the eye */
        const int hidden = back_faces_hidden_brute(&bt, &t, &v, ss.tiles);
        bad_back += (hidden != ss.back_faces_hidden);
        hidden_views += hidden;
        leaf_short += ss.leaf_px_max > tau;
        bad_conf += check_conforming(&bt, ss.tiles, edges);
        total_tiles += ss.tiles;
        uint32_t n_nocull = ss.tiles;
        memcpy(nocull, bt.tiles, n_nocull * sizeof *nocull);
        qsort(nocull, n_nocull, sizeof *nocull, tile_key_cmp);
        /* an unsplit diamond's box projects under tau, with or without the morph */
        const double thr = tau;
        for (uint32_t i = 0; i < n_nocull && exact_checks; ++i) {
            const ft_bt_tile *tile = &nocull[i];
            int32_t x0 = tile->apex[0], x1 = x0, y0 = tile->apex[1], y1 = y0;
            const int32_t *vv[3] = {tile->left, tile->right, tile->apex};
            for (int j = 0; j < 2; ++j) {
                x0 = vv[j][0] < x0 ? vv[j][0] : x0; x1 = vv[j][0] > x1 ? vv[j][0] : x1;
                y0 = vv[j][1] < y0 ? vv[j][1] : y0; y1 = vv[j][1] > y1 ? vv[j][1] : y1;
            }
            /* the drawn heights (template vertices) and the dense truth */
            double dev = 0.0, z0 = 1e30, z1 = -1e30;
            const int32_t ts = 1 << k;
            for (int32_t ib = 0; ib <= ts; ++ib) {
                for (int32_t ia = 0; ia + ib <= ts; ++ia) {
                    const int32_t gx = tile->apex[0] + (ia * (tile->left[0] - tile->apex[0]) +
                                                        ib * (tile->right[0] - tile->apex[0])) / ts;
                    const int32_t gy = tile->apex[1] + (ia * (tile->left[1] - tile->apex[1]) +
                                                        ib * (tile->right[1] - tile->apex[1])) / ts;
                    const double hv = ft_bt_height_fine(&bt, gx, gy);
                    z0 = hv < z0 ? hv : z0;
                    z1 = hv > z1 ? hv : z1;
                }
            }
            const int32_t fa[2] = {tile->apex[0] * sc, tile->apex[1] * sc},
                          fl[2] = {tile->left[0] * sc, tile->left[1] * sc},
                          fr[2] = {tile->right[0] * sc, tile->right[1] * sc};
            for (int32_t y = y0 * sc; y <= y1 * sc; ++y) {
                for (int32_t x = x0 * sc; x <= x1 * sc; ++x) {
                    int32_t p[2] = {x, y};
                    if (!inside(fa, fl, fr, p)) continue;
                    double d = fabs(bilinear_dense(&t, dn, p) - template_height_dense(&bt, sc, tile, p));
                    dev = d > dev ? d : dev;
                }
            }
            int32_t c[2] = {(tile->left[0] + tile->right[0]) / 2,
                            (tile->left[1] + tile->right[1]) / 2};
            const int is_leaf = tile->level == bt.leaf_level;
            float b[FT_BT_BOX_FLOATS];
            const double stored = ft_bt_diamond_error(&bt, tile->level, c, b);
            /* (float vertex heights: a ratio only where the error is not ~ rounding) */
            if (stored > 0.05) {
                dense_max_ratio = fmax(dense_max_ratio, (dev - 1e-4) / stored);
                ++ratio_tiles;
            }
            leaf_tiles += is_leaf;
            const double gx0 = (double)x0 / f_per_cell, gx1 = (double)x1 / f_per_cell;
            const double gy0 = (double)y0 / f_per_cell, gy1 = (double)y1 / f_per_cell;
            if (dev > stored + 1e-3 || z0 < b[4] || z1 > b[5] || gx0 < b[0] || gx1 > b[1] ||
                gy0 < b[2] || gy1 > b[3]) {
                if (bad_err < 3) {
                    fprintf(stderr, "tile level %u dev %.4f stored %.4f z %.2f..%.2f box %.2f..%.2f\n",
                            tile->level, dev, stored, z0, z1, b[4], b[5]);
                }
                ++bad_err;
            }
            if (is_leaf) continue;
            /* bound against the tile's own (tighter) box */
            double lo[3] = {gx0 * t.cell_x_m, gy0 * t.cell_y_m, z0};
            double hi[3] = {gx1 * t.cell_x_m, gy1 * t.cell_y_m, z1};
            double d2 = 0.0, lo_rel[3], hi_rel[3];
            for (int q = 0; q < 3; ++q) {
                double e = v.b.eye_m[q];
                double d = e < lo[q] ? lo[q] - e : (e > hi[q] ? e - hi[q] : 0.0);
                d2 += d * d;
                lo_rel[q] = lo[q] - e;
                hi_rel[q] = hi[q] - e;
            }
            /* pixels a vertical metre covers over the tile's box (view_scale.h) */
            const double gain = ft_view_vertical_gain(&v.b.gain, lo_rel, hi_rel);
            if (dev > 1e-3 && v.b.k_px * dev * gain > thr * sqrt(d2) * (1.0 + 1e-6) + 1e-3) {
                if (bad_bound < 3) {
                    double w_m;
                    const double q = ft_bt_diamond_q(&bt, &v, tile->level, c, tau, &w_m);
                    fprintf(stderr, "bound: level %u dev %.3f stored %.3f d %.1f tau %.2f morph %d "
                            "Q %.2f W %.2f\n", tile->level, dev, stored, sqrt(d2), tau, morph, q, w_m);
                }
                ++bad_bound;
            }
        }
        /* geomorph rule on every template vertex of every tile */
        for (uint32_t i = 0; i < n_nocull && exact_checks; i += 7u) {
            const ft_bt_tile *tile = &nocull[i];
            int32_t anc[FT_BT_LEVELS_MAX][2];
            uint32_t na = ancestors(&bt, tile, anc);
            /* the gap: a parent's Q is at least its child's + the child's W */
            for (uint32_t q = 1; q < na && morph; ++q) {
                double wp, wc;
                const double qp = ft_bt_diamond_q(&bt, &v, q - 1u, anc[q - 1u], tau, &wp);
                const double qc = ft_bt_diamond_q(&bt, &v, q, anc[q], tau, &wc);
                ++gap_pairs;
                if (isfinite(qc) && isfinite(qp) && qp < qc + wc - 1e-9 * fabs(qc) - 1e-6) {
                    if (bad_gap < 3) {
                        fprintf(stderr, "gap: level %u Q %.4f, parent Q %.4f, W %.4f\n", q, qc,
                                qp, wc);
                    }
                    ++bad_gap;
                }
            }
            int32_t s = 1 << k;
            for (int32_t ib = 0; ib <= s; ++ib) {
                for (int32_t ia = 0; ia + ib <= s; ++ia) {
                    int32_t gx = tile->apex[0] + (ia * (tile->left[0] - tile->apex[0]) +
                                                  ib * (tile->right[0] - tile->apex[0])) / s;
                    int32_t gy = tile->apex[1] + (ia * (tile->left[1] - tile->apex[1]) +
                                                  ib * (tile->right[1] - tile->apex[1])) / s;
                    int32_t e0[2], e1[2], c[2];
                    uint32_t level = 0;
                    ++checked_vertices;
                    if (!ft_bt_vertex_morph(&bt, gx, gy, e0, e1, c, &level)) continue;
                    ++morph_vertices;
                    if (morph) {
                        /* a moving vertex's endpoints are at their own heights:
                         * its coarse height is the drawn edge's midpoint */
                        double w_m;
                        const double q = ft_bt_diamond_q(&bt, &v, level, c, tau, &w_m);
                        const double mw = ft_bt_morph_weight(q, w_m);
                        moving_vertices += (mw > 0.0 && mw < 1.0);
                        for (int end = 0; end < 2 && mw > 0.0; ++end) {
                            const int32_t *ep = end ? e1 : e0;
                            int32_t f0[2], f1[2], fc[2];
                            uint32_t fl = 0;
                            if (!ft_bt_vertex_morph(&bt, ep[0], ep[1], f0, f1, fc, &fl)) continue;
                            double fw_m;
                            const double fq = ft_bt_diamond_q(&bt, &v, fl, fc, tau, &fw_m);
                            if (ft_bt_morph_weight(fq, fw_m) != 1.0 || !(fq >= q + w_m * 0.999)) {
                                if (bad_pop < 3) {
                                    fprintf(stderr, "vertex (%d,%d) w %.4f (Q %.3f, W %.3f): "
                                            "endpoint (%d,%d) Q %.3f\n", gx, gy, mw, q, w_m,
                                            ep[0], ep[1], fq);
                                }
                                ++bad_pop;
                            }
                        }
                    }
                    int found = 0;
                    for (uint32_t q = 0; q < na; ++q) found |= (anc[q][0] == c[0] && anc[q][1] == c[1]);
                    if (!found || e0[0] + e1[0] != 2 * gx || e0[1] + e1[1] != 2 * gy) {
                        if (bad_morph < 3) {
                            fprintf(stderr, "vertex (%d,%d) tile level %u: diamond (%d,%d) %s\n",
                                    gx, gy, tile->level, c[0], c[1],
                                    found ? "ok, bad ends" : "not an ancestor");
                        }
                        ++bad_morph;
                    }
                }
            }
        }
        /* culling only removes tiles, and what it keeps is conforming */
        ft_bt_view_from_camera(&cam, &t, 1, morph, &v);
        ft_bintree_select(&bt, &v, tau, &ss);
        CHECK(check_partition(&bt, &ss) == 0);
        CHECK(check_right_from_left(&bt, &ss) == 0);
        bad_tjunctions += count_t_junctions(&bt, ss.tiles, pts);
        for (uint32_t i = 0; i < ss.tiles; ++i) {
            if (bsearch(&bt.tiles[i], nocull, n_nocull, sizeof *nocull, tile_key_cmp) == NULL) {
                ++bad_subset;
            }
        }
        CHECK(ss.tiles <= n_nocull);
    }
    /* the back-face rule near the ground: eyes a little under or over the
     * sample under them, where the diamond the walk ends in decides */
    int low_hidden = 0, low_shown = 0;
    for (uint32_t i = 0; i < 4u * views; ++i) {
        static const double offsets_m[] = {-30.0, 1.0, 5.0, 20.0, 80.0};
        const double gx = urand() * (double)(t.width - 1u), gy = urand() * (double)(t.height - 1u);
        const double ground_m = t.heights_m[(size_t)(gy + 0.5) * t.width + (size_t)(gx + 0.5)];
        const double eye[3] = {gx * t.cell_x_m, gy * t.cell_y_m, ground_m + offsets_m[i % 5u]};
        ft_camera cam;
        ft_error cerr;
        REQUIRE(ft_camera_init(&cam, eye, urand() * 6.283, -0.8 + urand(), 0.0, 1.0, 640, 480,
                               1.0, 1e6, &cerr) == FT_OK);
        ft_bt_view v;
        ft_bt_view_from_camera(&cam, &t, 0, (int)(i & 1u), &v);
        ft_bt_select_stats ss;
        ft_bintree_select(&bt, &v, (i % 3u == 0u) ? 0.5 : 2.0, &ss);
        const int hidden = back_faces_hidden_brute(&bt, &t, &v, ss.tiles);
        bad_back += (hidden != ss.back_faces_hidden);
        low_hidden += hidden;
        low_shown += !hidden;
    }
    printf("  back faces near the ground: hidden for %d eyes, shown for %d\n", low_hidden,
           low_shown);
    g_low_hidden += low_hidden;
    g_low_shown += low_shown;
    CHECK(check_vertex_table(&bt, &t) == 0);
    printf("  %u views: %u tiles, %u/%u template vertices morph; conformity %d, subset %d, "
           "error %d, bound %d, morph %d failures\n",
           views, total_tiles, morph_vertices, checked_vertices, bad_conf, bad_subset, bad_err,
           bad_bound, bad_morph);
    printf("  dense bilinear error / stored error: at most %.4f (%d leaf tiles; %d views with a "
           "leaf over tau)\n", dense_max_ratio, leaf_tiles, leaf_short);
    if (exact_checks) {
        CHECK(dense_max_ratio <= 1.0 + 1e-4);
        /* the stored error is the exact max, not a loose bound */
        CHECK(ratio_tiles == 0 || dense_max_ratio > 0.9);
    }
    printf("  culled selections: %d T-junctions\n", bad_tjunctions);
    CHECK(bad_tjunctions == 0);
    CHECK(bad_conf == 0);
    CHECK(bad_subset == 0);
    CHECK(bad_err == 0);
    CHECK(bad_bound == 0);
    CHECK(bad_morph == 0);
    printf("  back faces hidden in %d of %u views, %d differ from the selection's own tiles\n",
           hidden_views, views, bad_back);
    CHECK(bad_back == 0);
    printf("  geomorph: %u vertices mid-morph, %d with an endpoint not at its own height; "
           "%u parent-child pairs, %d without the gap\n", moving_vertices, bad_pop, gap_pairs,
           bad_gap);
    CHECK(bad_pop == 0);
    CHECK(bad_gap == 0);
    if (exact_checks && bt.leaf_level > 0u) {
        CHECK(morph_vertices > 0u);
    }

    /* The tile budget: a tiny budget is never exceeded, tau is raised and reported. */
    bt.tiles_max = 40u;
    {
        ft_camera cam;
        double eye[3] = {bt.side_cells * 15.0, bt.side_cells * 5.0, t.max_height_m + 50.0};
        REQUIRE(ft_camera_init(&cam, eye, 0.3, -0.3, 0.0, 1.0, 640, 480, 1.0, 1e6, &err) == FT_OK);
        ft_bt_view v;
        ft_bt_view_from_camera(&cam, &t, 0, 1, &v);
        ft_bt_select_stats ss;
        ft_bintree_select(&bt, &v, 0.5, &ss);
        printf("  budget 40 tiles at tau 0.5: %u tiles, %u attempts, achieved tau %.2f px\n",
               ss.tiles, ss.attempts, ss.tau_achieved_px);
        CHECK(ss.tiles <= 40u);
        if (bt.leaf_level >= 6u) {
            CHECK(ss.budget_hit);
            CHECK(ss.tau_achieved_px > 0.5);
        }
        CHECK(check_conforming(&bt, ss.tiles, edges) == 0);
        bt.tiles_max = 2u;
        ft_bintree_select(&bt, &v, 0.5, &ss);
        CHECK(ss.tiles <= 2u);
        CHECK(ss.budget_hit || bt.leaf_level == 0u);
        CHECK(!isnan(ss.tau_achieved_px));
    }
    free(pts);
    free(edges);
    free(nocull);
    free(mem);
    free(t.heights_m);
}

int main(void)
{
    run_case(65, 65, 1, 0, 60, 1);
    run_case(129, 129, 2, 0, 60, 1);
    run_case(257, 257, 3, 0, 40, 1);
    run_case(3, 3, 1, 0, 10, 1);
    /* sub-sample levels: tiles finer than the samples, on the bilinear surface */
    run_case(65, 65, 2, 1, 20, 1);
    run_case(65, 65, 3, 2, 12, 1);
    run_case(33, 33, 2, 4, 6, 1);
    run_case(3, 3, 1, 3, 6, 1);
    /* padded grids: conformity, coverage and budget (the point-location check
     * above assumes no clamp) */
    run_case(100, 70, 2, 0, 40, 0);
    run_case(100, 70, 2, 2, 12, 0);
    run_case(1201, 1201, 3, 0, 12, 0);
    run_case(1201, 1201, 3, 2, 6, 0);

    /* k larger than the grid allows: a clear error */
    {
        ft_terrain t;
        make_terrain(&t, 9, 9, 30.0);
        ft_arena a;
        memset(&a, 0, sizeof a);
        ft_bintree_plan(&a, 9, 9, 4, 0u, 16);
        a.pools[FT_POOL_METHOD].budget_bytes = a.pools[FT_POOL_METHOD].need_bytes;
        size_t total = ft_arena_total_budget(&a);
        void *mem = aligned_alloc(FT_ARENA_ALIGN, total);
        ft_error err;
        REQUIRE(mem && ft_arena_bind(&a, mem, total, &err) == FT_OK);
        ft_bintree bt;
        CHECK(ft_bintree_init(&bt, &t, 4, 0u, FT_BT_MORPH_WIDTH, 16, &a, &err) == FT_ERR_CONFIG);
        CHECK(strstr(err.text, "too large") != NULL);
        CHECK(ft_bintree_init(&bt, &t, 2, 0u, FT_BT_MORPH_WIDTH, 1, &a, &err) == FT_ERR_CONFIG);
        ft_terrain t2;
        make_terrain(&t2, 2, 2, 30.0); /* one cell: no template fits */
        CHECK(ft_bintree_init(&bt, &t2, 1, 0u, FT_BT_MORPH_WIDTH, 16, &a, &err) == FT_ERR_CONFIG);
        free(t2.heights_m);
        free(mem);
        free(t.heights_m);
    }
    /* the near-ground eyes exercised both answers */
    CHECK(g_low_hidden > 20 && g_low_shown > 20);
    for (int i = 0; i < g_pyr_count; ++i) free(g_pyr_storage[i]);
    return g_ft_test_failures ? 1 : 0;
}
