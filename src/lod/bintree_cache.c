/* bintree_cache.c - the bintree over the clipmap cache (see bintree_cache.h). */
#include "lod/bintree_cache.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/invariant.h"
#include "lod/bintree_template.h"
#include "terrain/clip_source.h"

/* W' of bintree_cache.h: the wanted box shrunk by this many samples (a
 * vertex's normal reads its neighbours, and one more for the cells' edges) */
#define FT_BTC_APRON 2
/* slots of a level whose blocks are 2^shift samples of a side x side box */
/* the deepest tree: leaf level 2 (p - k) with p <= 23 */
#define FT_BTC_STACK_MAX (2u * 23u + 4u)
#define FT_BTC_SLOTS(side, shift) ((((shift) >= 31u) ? 0u : ((side) >> (shift))) + 1u)

static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if ((a % b) != 0 && a < 0) {
        q -= 1;
    }
    return q;
}

static uint32_t wrap_u(int64_t a, uint32_t n)
{
    int64_t r = a % (int64_t)n;
    return (uint32_t)((r < 0) ? r + (int64_t)n : r);
}

static uint32_t log2_u32(uint32_t v)
{
    uint32_t l = 0u;
    while (l < 31u && (1u << (l + 1u)) <= v) {
        ++l;
    }
    return l;
}

/* The data level of table m and its block side in that level's samples. */
static uint32_t data_level(const ft_bt_cache *bc, uint32_t m)
{
    return (m < bc->top) ? m : bc->top;
}

static uint32_t block_shift(const ft_bt_cache *bc, uint32_t m)
{
    return bc->k + ((m > bc->top) ? m - bc->top : 0u);
}

static uint32_t slots_of(uint32_t side, uint32_t k, uint32_t top, uint32_t m)
{
    return FT_BTC_SLOTS(side, k + ((m > top) ? m - top : 0u));
}

static uint32_t root_table(uint32_t side, uint32_t top, uint32_t k)
{
    return log2_u32(side) - 1u + top - k;
}

void ft_btc_plan(ft_arena *a, uint32_t side, uint32_t levels, uint32_t k, uint32_t tiles_max)
{
    if (levels == 0u || levels > FT_CLIP_LEVELS_MAX || side < 4u || k == 0u ||
        log2_u32(side) < k + 1u) {
        return; /* init refuses it */
    }
    const uint32_t top = levels - 1u, root = root_table(side, top, k);
    for (uint32_t m = 0u; m <= root && m < FT_BTC_TABLES_MAX; ++m) {
        const size_t n = slots_of(side, k, top, m);
        ft_arena_plan(a, FT_POOL_METHOD, n * n * 4u * sizeof(int64_t));
        ft_arena_plan(a, FT_POOL_METHOD, n * n * 12u * sizeof(float));
    }
    ft_arena_plan(a, FT_POOL_METHOD, (size_t)tiles_max * sizeof(ft_bt_tile));
}

ft_status ft_btc_init(ft_bt_cache *bc, const ft_clip_cache *c, const ft_terrain *t, uint32_t k,
                      uint32_t tiles_max, ft_arena *a, ft_error *err)
{
    memset(bc, 0, sizeof *bc);
    const uint32_t side = c->desc.side, levels = c->desc.levels;
    if (k < FT_BT_TEMPLATE_K_MIN || k > FT_BT_TEMPLATE_K_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.template_k = %u outside %u..%u", k,
                       FT_BT_TEMPLATE_K_MIN, FT_BT_TEMPLATE_K_MAX);
    }
    if (tiles_max < FT_BT_TILES_MIN || tiles_max > FT_BT_TILES_MAX_LIMIT) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree.tiles_max = %u outside %u..%u", tiles_max,
                       FT_BT_TILES_MIN, FT_BT_TILES_MAX_LIMIT);
    }
    if ((uint64_t)side < 12u * ((uint64_t)1 << k) + 8u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.side = %u is too small for the bintree over the cache with "
                       "bintree.template_k = %u: it needs at least 12 * 2^k + 8 = %u samples "
                       "(a level's wanted box must hold its finer level's with a tile's "
                       "closure to spare)",
                       side, k, 12u * (1u << k) + 8u);
    }
    if (c->mirror_m[0] == NULL) {
        return ft_fail(err, FT_ERR_ARG, "bintree over the cache: the cache keeps no bounds");
    }
    bc->k = k;
    bc->side = side;
    bc->levels = levels;
    bc->top = levels - 1u;
    bc->root_m = root_table(side, bc->top, k);
    bc->domain_log2 = bc->root_m + k;
    if (bc->root_m + 1u > FT_BTC_TABLES_MAX || bc->domain_log2 > 23u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "bintree over the cache: clipmap.side = %u with clipmap.levels = %u "
                       "spans 2^%u level-0 samples, more than the 2^23 a tile coordinate holds",
                       side, levels, bc->domain_log2);
    }
    bc->lattice0[0] = c->src.lattice_i0;
    bc->lattice0[1] = c->src.lattice_j0;
    bc->data[0] = c->src.data_i_lo;
    bc->data[1] = c->src.data_j_lo;
    bc->data[2] = c->src.data_i_hi;
    bc->data[3] = c->src.data_j_hi;
    bc->data_exact_m = bc->root_m;
    for (int e = 0; e < 4; ++e) {
        const int64_t v = bc->data[e];
        if (v <= -FT_CLIP_DATA_UNBOUNDED || v >= FT_CLIP_DATA_UNBOUNDED) {
            continue; /* no edge there */
        }
        uint32_t m = 0u;
        while (m < bc->data_exact_m && (v % ((int64_t)2 << m)) == 0) {
            ++m;
        }
        bc->data_exact_m = m;
    }
    bc->cell_m[0] = t->cell_x_m;
    bc->cell_m[1] = t->cell_y_m;
    for (uint32_t m = 0u; m <= bc->root_m; ++m) {
        ft_btc_blocks *b = &bc->blk[m];
        b->n = slots_of(side, k, bc->top, m);
        const size_t nn = (size_t)b->n * b->n;
        void *tags = NULL, *vals = NULL;
        ft_status st = ft_arena_take(a, FT_POOL_METHOD, nn * 4u * sizeof(int64_t), &tags, err);
        if (st == FT_OK) {
            st = ft_arena_take(a, FT_POOL_METHOD, nn * 12u * sizeof(float), &vals, err);
        }
        if (st != FT_OK) {
            return st;
        }
        b->tag = tags;
        b->ctag = b->tag + 2u * nn;
        float *f = vals;
        b->own_e_m = f;
        b->own_s_m = f + nn;
        b->lo_m = f + 2u * nn;
        b->hi_m = f + 3u * nn;
        b->cum_e_m = f + 4u * nn;
        b->cum_s_m = f + 5u * nn;
        b->cum_lo_m = f + 6u * nn;
        b->cum_hi_m = f + 7u * nn;
        b->tlo_m = f + 8u * nn;
        b->thi_m = f + 9u * nn;
        b->cum_tlo_m = f + 10u * nn;
        b->cum_thi_m = f + 11u * nn;
        for (size_t i = 0; i < 2u * nn; ++i) {
            b->tag[i] = INT64_MIN; /* no block */
            b->ctag[i] = INT64_MIN;
        }
    }
    void *tiles = NULL;
    const ft_status st =
        ft_arena_take(a, FT_POOL_METHOD, (size_t)tiles_max * sizeof(ft_bt_tile), &tiles, err);
    if (st != FT_OK) {
        return st;
    }
    bc->tiles = tiles;
    bc->tiles_max = tiles_max;
    for (uint32_t l = 0u; l < FT_CLIP_LEVELS_MAX; ++l) {
        bc->folded[l] = (ft_clip_box){0, 0, 0, 0};
    }
    bc->origin_set = 0;
    return FT_OK;
}

/* ---- folding the resident cells into their blocks --------------------------------- */

static float round_up_f(double v)
{
    float f = (float)v;
    if ((double)f < v) {
        f = nextafterf(f, INFINITY);
    }
    return f;
}

static float round_down_f(double v)
{
    float f = (float)v;
    if ((double)f > v) {
        f = nextafterf(f, -INFINITY);
    }
    return f;
}

/* The slot of absolute block (bx, by) of table m, reset when it held another. */
static size_t slot_take(ft_btc_blocks *b, int64_t bx, int64_t by)
{
    const size_t s = (size_t)wrap_u(by, b->n) * b->n + wrap_u(bx, b->n);
    if (b->tag[2u * s] != bx || b->tag[2u * s + 1u] != by) {
        b->tag[2u * s] = bx;
        b->tag[2u * s + 1u] = by;
        b->own_e_m[s] = 0.0f;
        b->own_s_m[s] = 0.0f;
        b->lo_m[s] = INFINITY;
        b->hi_m[s] = -INFINITY;
        b->tlo_m[s] = INFINITY;
        b->thi_m[s] = -INFINITY;
    }
    return s;
}

static double mirror_at(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b)
{
    const uint32_t side = c->desc.side;
    return c->mirror_m[l][(size_t)wrap_u(b, side) * side + wrap_u(a, side)];
}

/* 4 float steps of the largest height: what a shader's arithmetic on
 * float heights can add */
static double float_steps(double h_abs_max)
{
    return 4.0 * h_abs_max * ldexp(1.0, -24);
}

/* Cell (a, b) of level l (all four corners resident): |D| / 4 + dev and the
 * finest data's range, into its block. */
static void fold_cell(ft_bt_cache *bc, const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b)
{
    const uint32_t side = c->desc.side;
    double h[4], unknown = 0.0;
    for (int q = 0; q < 4; ++q) {
        const int64_t x = a + (q & 1), y = b + (q >> 1);
        h[q] = mirror_at(c, l, x, y);
        unknown = fmax(unknown, (double)c->dev_mirror_m[l][(size_t)wrap_u(y, side) * side +
                                                           wrap_u(x, side)]);
    }
    ft_btc_blocks *blk = &bc->blk[l];
    const size_t s = slot_take(blk, floor_div(a, (int64_t)1 << bc->k),
                               floor_div(b, (int64_t)1 << bc->k));
    const double lo = fmin(fmin(h[0], h[1]), fmin(h[2], h[3]));
    const double hi = fmax(fmax(h[0], h[1]), fmax(h[2], h[3]));
    const double steps = float_steps(fmax(fabs(lo), fabs(hi)));
    const float tlo = round_down_f(lo - steps), thi = round_up_f(hi + steps);
    blk->tlo_m[s] = (tlo < blk->tlo_m[s]) ? tlo : blk->tlo_m[s];
    blk->thi_m[s] = (thi > blk->thi_m[s]) ? thi : blk->thi_m[s];
    if (isinf(unknown) || isnan(unknown)) {
        blk->own_e_m[s] = INFINITY;
        blk->lo_m[s] = -INFINITY;
        blk->hi_m[s] = INFINITY;
        return;
    }
    const double dev = c->dev_mirror_m[l][(size_t)wrap_u(b, side) * side + wrap_u(a, side)];
    const double e = fabs(h[0] + h[3] - h[1] - h[2]) * 0.25 + dev + steps;
    const float ef = round_up_f(e);
    blk->own_e_m[s] = (ef > blk->own_e_m[s]) ? ef : blk->own_e_m[s];
    const float lof = round_down_f(lo - dev - steps), hif = round_up_f(hi + dev + steps);
    blk->lo_m[s] = (lof < blk->lo_m[s]) ? lof : blk->lo_m[s];
    blk->hi_m[s] = (hif > blk->hi_m[s]) ? hif : blk->hi_m[s];
}

/* Sample (a, b) of level l (its four neighbours resident): the larger
 * second difference along an axis, halved, into its block. */
static void fold_sample(ft_bt_cache *bc, const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b)
{
    const double h = mirror_at(c, l, a, b);
    const double w = mirror_at(c, l, a - 1, b), e = mirror_at(c, l, a + 1, b);
    const double so = mirror_at(c, l, a, b - 1), no = mirror_at(c, l, a, b + 1);
    const double amax = fmax(fmax(fabs(h), fabs(w)), fmax(fmax(fabs(e), fabs(so)), fabs(no)));
    const double d = 0.5 * fmax(fabs(w + e - 2.0 * h), fabs(so + no - 2.0 * h)) + float_steps(amax);
    ft_btc_blocks *blk = &bc->blk[l];
    const size_t s = slot_take(blk, floor_div(a, (int64_t)1 << bc->k),
                               floor_div(b, (int64_t)1 << bc->k));
    const float df = round_up_f(d);
    blk->own_s_m[s] = (df > blk->own_s_m[s]) ? df : blk->own_s_m[s];
}

static int box_is_empty(const ft_clip_box *b)
{
    return b->i1 <= b->i0 || b->j1 <= b->j0;
}

/* Calls fold for every point of box `now` not in box `old` (both half-open,
 * either may be empty): row by row, the row's span minus old's. Returns the
 * points folded. */
typedef void (*fold_fn)(ft_bt_cache *bc, const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b);

static uint64_t fold_difference(ft_bt_cache *bc, const ft_clip_cache *c, uint32_t l,
                                const ft_clip_box *now, const ft_clip_box *old, fold_fn fold)
{
    if (box_is_empty(now)) {
        return 0u;
    }
    const int old_empty = box_is_empty(old);
    uint64_t count = 0u;
    for (int64_t b = now->j0; b < now->j1; ++b) {
        int64_t skip0 = now->i1, skip1 = now->i1; /* [skip0, skip1): already folded */
        if (!old_empty && b >= old->j0 && b < old->j1) {
            skip0 = (old->i0 > now->i0) ? old->i0 : now->i0;
            skip1 = (old->i1 < now->i1) ? old->i1 : now->i1;
            if (skip1 < skip0) {
                skip0 = skip1 = now->i1;
            }
        }
        for (int64_t a = now->i0; a < now->i1; ++a) {
            if (a >= skip0 && a < skip1) {
                a = skip1 - 1; /* bounded: a only grows */
                continue;
            }
            fold(bc, c, l, a, b);
            ++count;
        }
    }
    return count;
}

static ft_clip_box shrink(const ft_clip_box *v, int64_t lo, int64_t hi)
{
    ft_clip_box r = {v->i0 + lo, v->j0 + lo, v->i1 - hi, v->j1 - hi};
    if (box_is_empty(v) || box_is_empty(&r)) {
        r = (ft_clip_box){0, 0, 0, 0};
    }
    return r;
}

/* ---- the pyramid (per frame) -------------------------------------------------------- */

/* Blocks of table m whose cum a lookup may read: those over the data
 * level's wanted box (tables <= Lc), or over the domain (virtual tables). */
static void block_range(const ft_bt_cache *bc, const ft_clip_cache *c, uint32_t m, int64_t r[4])
{
    const uint32_t d = data_level(bc, m), sh = block_shift(bc, m);
    const int64_t bs = (int64_t)1 << sh; /* block side, level-d samples */
    if (m <= bc->top) {
        const ft_clip_box *w = &c->level[d].want;
        r[0] = floor_div(w->i0, bs);
        r[1] = floor_div(w->j0, bs);
        r[2] = floor_div(w->i1 - 2, bs) + 1;
        r[3] = floor_div(w->j1 - 2, bs) + 1;
    } else {
        const int64_t b0 = (int64_t)1 << (m + bc->k); /* level-0 samples */
        const int64_t dsz = (int64_t)1 << bc->domain_log2;
        r[0] = floor_div(bc->origin[0], b0);
        r[1] = floor_div(bc->origin[1], b0);
        r[2] = floor_div(bc->origin[0] + dsz - 1, b0) + 1;
        r[3] = floor_div(bc->origin[1] + dsz - 1, b0) + 1;
    }
    /* never more than the slots hold */
    if (r[2] - r[0] > (int64_t)bc->blk[m].n) {
        r[2] = r[0] + bc->blk[m].n;
    }
    if (r[3] - r[1] > (int64_t)bc->blk[m].n) {
        r[3] = r[1] + bc->blk[m].n;
    }
}

static size_t slot_of(const ft_btc_blocks *b, int64_t bx, int64_t by)
{
    return (size_t)wrap_u(by, b->n) * b->n + wrap_u(bx, b->n);
}

static int cum_known(const ft_btc_blocks *b, int64_t bx, int64_t by, size_t *s)
{
    *s = slot_of(b, bx, by);
    return b->ctag[2u * *s] == bx && b->ctag[2u * *s + 1u] == by;
}

static void build_pyramid(ft_bt_cache *bc, const ft_clip_cache *c)
{
    for (uint32_t m = 0u; m <= bc->root_m; ++m) {
        ft_btc_blocks *b = &bc->blk[m];
        /* a finer level's resident blocks count wherever they are: a tile
         * of it is drawn only inside its resident part (its U) */
        const ft_btc_blocks *fine = (m > 0u) ? &bc->blk[m - 1u] : NULL;
        int64_t r[4];
        block_range(bc, c, m, r);
        for (int64_t by = r[1]; by < r[3]; ++by) {
            for (int64_t bx = r[0]; bx < r[2]; ++bx) {
                const size_t s = slot_of(b, bx, by);
                int known = 0;
                float e = 0.0f, sd = 0.0f, lo = INFINITY, hi = -INFINITY;
                float tlo = INFINITY, thi = -INFINITY;
                if (m <= bc->top && b->tag[2u * s] == bx && b->tag[2u * s + 1u] == by) {
                    known = 1;
                    tlo = b->tlo_m[s];
                    thi = b->thi_m[s];
                    e = b->own_e_m[s];
                    /* sd stays the finer levels' (see ft_btc_diamond) */
                    lo = b->lo_m[s];
                    hi = b->hi_m[s];
                }
                if (m <= bc->top && !known) {
                    /* a level's own cells unknown: no bound from the finer ones alone */
                    b->ctag[2u * s] = INT64_MIN;
                    b->ctag[2u * s + 1u] = INT64_MIN;
                    continue;
                }
                if (fine != NULL) {
                    for (int q = 0; q < 4; ++q) {
                        size_t fs;
                        if (!cum_known(fine, 2 * bx + (q & 1), 2 * by + (q >> 1), &fs)) {
                            continue;
                        }
                        known = 1;
                        e = (fine->cum_e_m[fs] > e) ? fine->cum_e_m[fs] : e;
                        float fsd = fine->cum_s_m[fs];
                        if (m - 1u <= bc->top && fine->tag[2u * fs] == 2 * bx + (q & 1) &&
                            fine->tag[2u * fs + 1u] == 2 * by + (q >> 1)) {
                            fsd = (fine->own_s_m[fs] > fsd) ? fine->own_s_m[fs] : fsd;
                        }
                        sd = (fsd > sd) ? fsd : sd;
                        lo = (fine->cum_lo_m[fs] < lo) ? fine->cum_lo_m[fs] : lo;
                        hi = (fine->cum_hi_m[fs] > hi) ? fine->cum_hi_m[fs] : hi;
                        tlo = (fine->cum_tlo_m[fs] < tlo) ? fine->cum_tlo_m[fs] : tlo;
                        thi = (fine->cum_thi_m[fs] > thi) ? fine->cum_thi_m[fs] : thi;
                    }
                }
                if (!known) {
                    b->ctag[2u * s] = INT64_MIN;
                    b->ctag[2u * s + 1u] = INT64_MIN;
                    continue;
                }
                b->ctag[2u * s] = bx;
                b->ctag[2u * s + 1u] = by;
                b->cum_e_m[s] = e;
                b->cum_s_m[s] = sd;
                b->cum_lo_m[s] = lo;
                b->cum_hi_m[s] = hi;
                b->cum_tlo_m[s] = tlo;
                b->cum_thi_m[s] = thi;
            }
        }
    }
}

/* ---- update (per frame) ------------------------------------------------------------- */

static int64_t floor_to(int64_t v, int64_t step)
{
    return floor_div(v, step) * step;
}

/* The domain: kept while it lies in the coarsest level's usable box, else
 * the multiple of D / 2 nearest the eye that does (the coarsest level is
 * kept whole, clip_levels.h, so one does). */
static void place_domain(ft_bt_cache *bc, double eye_i, double eye_j)
{
    const int64_t *u = bc->usable[bc->top];
    const int64_t dsz = (int64_t)1 << bc->domain_log2, half = dsz / 2;
    const double eye[2] = {eye_i, eye_j};
    for (int ax = 0; ax < 2; ++ax) {
        const int64_t lo = u[ax], hi = u[2 + ax];
        if (bc->origin_set && bc->origin[ax] >= lo && bc->origin[ax] + dsz <= hi) {
            continue;
        }
        const int64_t first = -floor_div(-lo, half) * half; /* ceil to a multiple */
        const int64_t last = floor_to(hi - dsz, half);
        FT_INVARIANT(first <= last, "bintree over the cache: the domain fits the coarsest level");
        if (first > last) {
            continue; /* keep the last domain; may_split checks residency anyway */
        }
        int64_t o = (int64_t)floor((eye[ax] - (double)half) / (double)half + 0.5) * half;
        o = (o < first) ? first : o;
        o = (o > last) ? last : o;
        bc->origin[ax] = o;
    }
    bc->origin_set = 1;
}

/* U of bintree_cache.h, coarsest first. */
static void usable_boxes(ft_bt_cache *bc, const ft_clip_cache *c)
{
    bc->finest_usable = bc->levels;
    for (uint32_t i = 0u; i < bc->levels; ++i) {
        const uint32_t l = bc->levels - 1u - i;
        const ft_clip_box *v = &c->level[l].valid;
        const int64_t sc = (int64_t)1 << l;
        int64_t *u = bc->usable[l];
        u[0] = (v->i0 + FT_BTC_APRON) * sc;
        u[1] = (v->j0 + FT_BTC_APRON) * sc;
        u[2] = (v->i1 - 1 - FT_BTC_APRON) * sc;
        u[3] = (v->j1 - 1 - FT_BTC_APRON) * sc;
        if (l < bc->top) {
            const int64_t *up = bc->usable[l + 1u];
            const int64_t mu = (int64_t)3 << (l + bc->k + 1u);
            u[0] = (up[0] + mu > u[0]) ? up[0] + mu : u[0];
            u[1] = (up[1] + mu > u[1]) ? up[1] + mu : u[1];
            u[2] = (up[2] - mu < u[2]) ? up[2] - mu : u[2];
            u[3] = (up[3] - mu < u[3]) ? up[3] - mu : u[3];
        }
        if (box_is_empty(v) || u[2] < u[0] || u[3] < u[1]) {
            u[0] = u[1] = 0;
            u[2] = u[3] = -1; /* empty */
            continue;
        }
        if (bc->finest_usable == l + 1u) {
            bc->finest_usable = l;
        }
    }
}

void ft_btc_update(ft_bt_cache *bc, const ft_clip_cache *c, double eye_i, double eye_j)
{
    for (uint32_t l = 0u; l < bc->levels; ++l) {
        const ft_clip_box *v = &c->level[l].valid;
        const ft_clip_box cells_now = shrink(v, 0, 1), cells_old = shrink(&bc->folded[l], 0, 1);
        const ft_clip_box samp_now = shrink(v, 1, 1), samp_old = shrink(&bc->folded[l], 1, 1);
        bc->cells_folded += fold_difference(bc, c, l, &cells_now, &cells_old, fold_cell);
        (void)fold_difference(bc, c, l, &samp_now, &samp_old, fold_sample);
        bc->folded[l] = *v;
    }
    usable_boxes(bc, c);
    place_domain(bc, eye_i, eye_j);
    build_pyramid(bc, c);
}

/* ---- diamonds ----------------------------------------------------------------------- */

uint32_t ft_btc_table_of(const ft_bt_cache *bc, uint32_t tree_level)
{
    /* square side s = D >> (t / 2) = 2^(p - t/2); even: m = log2 s - k, odd: one less */
    const uint32_t ls = bc->domain_log2 - tree_level / 2u;
    const uint32_t m = ls - bc->k;
    return ((tree_level & 1u) != 0u) ? m - 1u : m;
}

static uint32_t leaf_level(const ft_bt_cache *bc)
{
    return 2u * (bc->domain_log2 - bc->k);
}

/* The diamond's square side s (level-0 samples) and whether c is the
 * midpoint of a horizontal edge (odd levels). */
static int64_t square_side(const ft_bt_cache *bc, uint32_t tree_level)
{
    return (int64_t)1 << (bc->domain_log2 - tree_level / 2u);
}

/* Region R (error, box): the closure cut to the domain, [x0, x1] x [y0, y1]
 * relative to the origin. */
static void closure_region(const ft_bt_cache *bc, uint32_t t, const int32_t cv[2], int64_t r[4])
{
    const int64_t s = square_side(bc, t);
    const int64_t h = ((t & 1u) != 0u) ? s : s + s / 2;
    const int64_t dsz = (int64_t)1 << bc->domain_log2;
    r[0] = cv[0] - h;
    r[1] = cv[0] + h;
    r[2] = cv[1] - h;
    r[3] = cv[1] + h;
    r[0] = (r[0] < 0) ? 0 : r[0];
    r[2] = (r[2] < 0) ? 0 : r[2];
    r[1] = (r[1] > dsz) ? dsz : r[1];
    r[3] = (r[3] > dsz) ? dsz : r[3];
}

/* lambda of bintree_cache.h: the table of an even diamond, one above an
 * odd one's (the table of its parents) */
static uint32_t lookup_table(const ft_bt_cache *bc, uint32_t t)
{
    const uint32_t m = ft_btc_table_of(bc, t);
    return ((t & 1u) != 0u) ? m + 1u : m;
}

double ft_btc_diamond(const ft_bt_cache *bc, uint32_t tree_level, const int32_t cv[2],
                      double lo[3], double hi[3])
{
    int64_t r[4];
    closure_region(bc, tree_level, cv, r);
    const uint32_t lam = lookup_table(bc, tree_level);
    const ft_btc_blocks *b = &bc->blk[lam];
    const int64_t bs = (int64_t)1 << (lam + bc->k);
    const int64_t bx0 = floor_div(bc->origin[0] + r[0], bs);
    const int64_t bx1 = -floor_div(-(bc->origin[0] + r[1]), bs); /* exclusive */
    const int64_t by0 = floor_div(bc->origin[1] + r[2], bs);
    const int64_t by1 = -floor_div(-(bc->origin[1] + r[3]), bs);
    float e = 0.0f, sd = 0.0f, zlo = INFINITY, zhi = -INFINITY;
    int unknown = 0;
    /* a closure is 3 s (even) or 2 s (odd) wide and blocks are s: at most
     * 4 a side even where the origin is an odd multiple of D / 2 */
    FT_INVARIANT(bx1 - bx0 <= 4 && by1 - by0 <= 4, "bintree over the cache: a closure's blocks");
    for (int64_t by = by0; by < by1; ++by) {
        for (int64_t bx = bx0; bx < bx1; ++bx) {
            size_t s;
            if (!cum_known(b, bx, by, &s)) {
                unknown = 1;
                continue;
            }
            e = (b->cum_e_m[s] > e) ? b->cum_e_m[s] : e;
            sd = (b->cum_s_m[s] > sd) ? b->cum_s_m[s] : sd;
            zlo = (b->cum_lo_m[s] < zlo) ? b->cum_lo_m[s] : zlo;
            zhi = (b->cum_hi_m[s] > zhi) ? b->cum_hi_m[s] : zhi;
        }
    }
    const double ox = (double)(bc->origin[0] - bc->lattice0[0]);
    const double oy = (double)(bc->origin[1] - bc->lattice0[1]);
    lo[0] = (ox + (double)r[0]) * bc->cell_m[0];
    hi[0] = (ox + (double)r[1]) * bc->cell_m[0];
    lo[1] = (oy + (double)r[2]) * bc->cell_m[1];
    hi[1] = (oy + (double)r[3]) * bc->cell_m[1];
    if (unknown || !(zlo <= zhi)) {
        lo[2] = -INFINITY;
        hi[2] = INFINITY;
        return INFINITY;
    }
    lo[2] = zlo;
    hi[2] = zhi;
    double err = (double)e + (double)sd;
    if (lam > bc->top) {
        /* virtual: the relief bounds it too (bintree_cache.h) */
        const double relief = (double)zhi - (double)zlo;
        err = (relief > err) ? relief : err;
    }
    return err;
}

/* A tile's own blocks (those of its table under its bounding box g =
 * x0, x1, y0, y1): what it achieves when it may not split (its own error
 * over its own extent: |D| / 4 + dev, the second differences of its own
 * level and the finer ones, the relief on a virtual table; tighter than
 * its diamond's, which also bounds what a split would draw), and the range
 * of the samples drawn there or below (culling). */
typedef struct btc_tile_bound {
    double err_m;
    double lo[3], hi[3];  /* its box, the finest data's range in z */
    float draw_lo_m, draw_hi_m;
    int known;
} btc_tile_bound;

static void tile_bound(const ft_bt_cache *bc, const int32_t g[4], uint32_t t, btc_tile_bound *o)
{
    const uint32_t m = ft_btc_table_of(bc, t);
    const ft_btc_blocks *b = &bc->blk[m];
    const int64_t bs = (int64_t)1 << (m + bc->k);
    const int64_t bx0 = floor_div(bc->origin[0] + g[0], bs);
    const int64_t bx1 = -floor_div(-(bc->origin[0] + g[1]), bs);
    const int64_t by0 = floor_div(bc->origin[1] + g[2], bs);
    const int64_t by1 = -floor_div(-(bc->origin[1] + g[3]), bs);
    /* a tile is at most 2 s wide, s <= 2 blocks of its table */
    FT_INVARIANT(bx1 - bx0 <= 4 && by1 - by0 <= 4, "bintree over the cache: a tile's blocks");
    float e = 0.0f, sd = 0.0f, zlo = INFINITY, zhi = -INFINITY;
    o->draw_lo_m = INFINITY;
    o->draw_hi_m = -INFINITY;
    int unknown = 0;
    for (int64_t by = by0; by < by1; ++by) {
        for (int64_t bx = bx0; bx < bx1; ++bx) {
            size_t s;
            if (!cum_known(b, bx, by, &s)) {
                unknown = 1;
                continue;
            }
            float own_s = b->cum_s_m[s];
            if (m <= bc->top && b->tag[2u * s] == bx && b->tag[2u * s + 1u] == by) {
                own_s = (b->own_s_m[s] > own_s) ? b->own_s_m[s] : own_s;
            }
            e = (b->cum_e_m[s] > e) ? b->cum_e_m[s] : e;
            sd = (own_s > sd) ? own_s : sd;
            zlo = (b->cum_lo_m[s] < zlo) ? b->cum_lo_m[s] : zlo;
            zhi = (b->cum_hi_m[s] > zhi) ? b->cum_hi_m[s] : zhi;
            o->draw_lo_m = (b->cum_tlo_m[s] < o->draw_lo_m) ? b->cum_tlo_m[s] : o->draw_lo_m;
            o->draw_hi_m = (b->cum_thi_m[s] > o->draw_hi_m) ? b->cum_thi_m[s] : o->draw_hi_m;
        }
    }
    const double ox = (double)(bc->origin[0] - bc->lattice0[0]);
    const double oy = (double)(bc->origin[1] - bc->lattice0[1]);
    o->lo[0] = (ox + (double)g[0]) * bc->cell_m[0];
    o->hi[0] = (ox + (double)g[1]) * bc->cell_m[0];
    o->lo[1] = (oy + (double)g[2]) * bc->cell_m[1];
    o->hi[1] = (oy + (double)g[3]) * bc->cell_m[1];
    o->known = !unknown && o->draw_lo_m <= o->draw_hi_m;
    if (!o->known || !(zlo <= zhi) || isinf(zlo) || isinf(zhi)) {
        o->lo[2] = -INFINITY;
        o->hi[2] = INFINITY;
        o->err_m = INFINITY;
        return;
    }
    o->lo[2] = zlo;
    o->hi[2] = zhi;
    double err = (double)e + (double)sd;
    if (m > bc->top) {
        const double relief = (double)zhi - (double)zlo;
        err = (relief > err) ? relief : err;
    }
    o->err_m = err;
}

int ft_btc_may_split(const ft_bt_cache *bc, uint32_t t, const int32_t cv[2])
{
    if (t >= leaf_level(bc)) {
        return 0;
    }
    const uint32_t m = ft_btc_table_of(bc, t);
    const uint32_t mc = ((t & 1u) != 0u) ? m : m - 1u; /* the children's table */
    /* S: an even diamond's closure; an odd one's, its two parents' closures */
    const int64_t s = square_side(bc, t);
    int64_t hx, hy;
    if ((t & 1u) == 0u) {
        hx = hy = s + s / 2;
    } else if ((cv[0] % s) != 0) { /* a horizontal edge: parents above and below */
        hx = s + s / 2;
        hy = 2 * s;
    } else {
        hx = 2 * s;
        hy = s + s / 2;
    }
    const int64_t dsz = (int64_t)1 << bc->domain_log2;
    int64_t x0 = cv[0] - hx, x1 = cv[0] + hx, y0 = cv[1] - hy, y1 = cv[1] + hy;
    x0 = (x0 < 0) ? 0 : x0;
    y0 = (y0 < 0) ? 0 : y0;
    x1 = (x1 > dsz) ? dsz : x1;
    y1 = (y1 > dsz) ? dsz : y1;
    /* a virtual table's children read the coarsest level */
    const int64_t *u = bc->usable[(mc < bc->top) ? mc : bc->top];
    return bc->origin[0] + x0 >= u[0] && bc->origin[1] + y0 >= u[1] &&
           bc->origin[0] + x1 <= u[2] && bc->origin[1] + y1 <= u[3];
}

int ft_btc_eye_coarser(const ft_bt_cache *bc, double eye_i, double eye_j)
{
    const int64_t *u = bc->usable[0];
    const double r = (double)((int64_t)1 << (bc->k + 2u));
    return !(eye_i - r >= (double)u[0] && eye_j - r >= (double)u[1] &&
             eye_i + r <= (double)u[2] && eye_j + r <= (double)u[3]);
}

/* ---- selection (per frame) ---------------------------------------------------------- */

typedef struct btc_node {
    int32_t apex[2], left[2], right[2];
    uint32_t level;
} btc_node;

static int32_t min3(int32_t a, int32_t b, int32_t c)
{
    const int32_t m = (a < b) ? a : b;
    return (m < c) ? m : c;
}

static int32_t max3(int32_t a, int32_t b, int32_t c)
{
    const int32_t m = (a > b) ? a : b;
    return (m > c) ? m : c;
}

static int select_once(ft_bt_cache *bc, const ft_bt_view *v, double tau_px,
                       ft_bt_select_stats *st)
{
    btc_node stack[FT_BTC_STACK_MAX];
    uint32_t sp = 0u;
    const int32_t n = (int32_t)1 << bc->domain_log2;
    const uint32_t leaf = leaf_level(bc);
    st->tiles = 0u;
    st->tiles_coarse = 0u;
    st->leaf_px_max = 0.0;
    st->nodes_visited = 0u;
    st->culled = 0u;
    st->level_min = UINT32_MAX;
    st->level_max = 0u;
    FT_INVARIANT(leaf + 4u <= FT_BTC_STACK_MAX, "bintree over the cache: the stack holds the tree");
    stack[sp++] = (btc_node){{0, n}, {0, 0}, {n, n}, 0u};
    stack[sp++] = (btc_node){{n, 0}, {n, n}, {0, 0}, 0u};
    /* Bounded: every pop emits, drops or replaces a node by its two children
     * one level down; depth <= leaf, so sp <= leaf + 2. */
    while (sp > 0u) {
        const btc_node t = stack[--sp];
        st->nodes_visited += 1u;
        const int32_t gx0 = min3(t.apex[0], t.left[0], t.right[0]);
        const int32_t gx1 = max3(t.apex[0], t.left[0], t.right[0]);
        const int32_t gy0 = min3(t.apex[1], t.left[1], t.right[1]);
        const int32_t gy1 = max3(t.apex[1], t.left[1], t.right[1]);
        const int64_t ax0 = bc->origin[0] + gx0, ax1 = bc->origin[0] + gx1;
        const int64_t ay0 = bc->origin[1] + gy0, ay1 = bc->origin[1] + gy1;
        if (ax1 <= bc->data[0] || ax0 >= bc->data[2] || ay1 <= bc->data[1] ||
            ay0 >= bc->data[3]) {
            continue; /* off the data, or clamped onto its edge: nothing to draw */
        }
        /* across the data's edge on a lattice that does not hold it: split */
        const int across = (ax0 < bc->data[0] || ax1 > bc->data[2] || ay0 < bc->data[1] ||
                            ay1 > bc->data[3]) &&
                           ft_btc_table_of(bc, t.level) > bc->data_exact_m;
        const int32_t cv[2] = {(t.left[0] + t.right[0]) / 2, (t.left[1] + t.right[1]) / 2};
        const int32_t g[4] = {gx0, gx1, gy0, gy1};
        btc_tile_bound tb;
        tile_bound(bc, g, t.level, &tb);
        if (v->cull && tb.known) {
            /* the tile and everything below it lie in its box, at heights
             * its level's and the finer levels' samples there hold */
            double clo[3] = {tb.lo[0], tb.lo[1], tb.draw_lo_m};
            double chi[3] = {tb.hi[0], tb.hi[1], tb.draw_hi_m};
            ft_view_bound_drawn_box(&v->b, clo, chi);
            if (ft_view_bound_outside(&v->b, clo, chi)) {
                st->culled += 1u;
                continue;
            }
        }
        double lo[3], hi[3];
        const double e = ft_btc_diamond(bc, t.level, cv, lo, hi);
        ft_view_bound_drawn_box(&v->b, lo, hi);
        double q = -INFINITY;
        if (isinf(e) || across) {
            q = INFINITY;
        } else if (tau_px >= 0.0 && isfinite(tau_px)) {
            ft_view_box_terms terms;
            ft_view_bound_terms(&v->b, e, lo, hi, &terms);
            if (terms.err_m > 0.0) {
                q = (!(terms.dist_m > 0.0) || tau_px == 0.0)
                        ? INFINITY
                        : v->b.k_px * terms.err_m * terms.gain / tau_px - terms.dist_m;
            }
        }
        if (q > 0.0) {
            if (ft_btc_may_split(bc, t.level, cv)) {
                stack[sp++] = (btc_node){{cv[0], cv[1]},
                                         {t.right[0], t.right[1]},
                                         {t.apex[0], t.apex[1]},
                                         t.level + 1u};
                stack[sp++] = (btc_node){{cv[0], cv[1]},
                                         {t.apex[0], t.apex[1]},
                                         {t.left[0], t.left[1]},
                                         t.level + 1u};
                continue;
            }
            /* wanted finer but the data are not there (a leaf, or a level
             * behind): what this tile achieves joins the bound */
            double px = INFINITY;
            if (!isinf(tb.err_m) && !across) {
                ft_view_bound_drawn_box(&v->b, tb.lo, tb.hi);
                px = ft_view_bound_error_px(&v->b, tb.err_m, tb.lo, tb.hi);
            }
            st->leaf_px_max = (px > st->leaf_px_max) ? px : st->leaf_px_max;
        }
        if (st->tiles >= bc->tiles_max) {
            return 0;
        }
        ft_bt_tile *out = &bc->tiles[st->tiles++];
        memcpy(out->apex, t.apex, sizeof out->apex);
        memcpy(out->left, t.left, sizeof out->left);
        memcpy(out->right, t.right, sizeof out->right);
        out->level = t.level;
        st->level_min = (t.level < st->level_min) ? t.level : st->level_min;
        st->level_max = (t.level > st->level_max) ? t.level : st->level_max;
    }
    st->tiles_coarse = st->tiles;
    return 1;
}

void ft_btc_select(ft_bt_cache *bc, const ft_bt_view *v, double tau_px, ft_bt_select_stats *st)
{
    double tau = (tau_px > 0.0) ? tau_px : 0.0;
    memset(st, 0, sizeof *st);
    st->tau_target_px = tau;
    for (uint32_t i = 0; i < FT_BT_COARSEN_STEPS_MAX; ++i) {
        st->attempts = i + 1u;
        if (select_once(bc, v, tau, st)) {
            st->budget_hit = (i > 0u);
            st->tau_used_px = tau;
            st->tau_achieved_px = (st->leaf_px_max > tau) ? st->leaf_px_max : tau;
            return;
        }
        tau = (tau > 0.0) ? tau * FT_BT_COARSEN_FACTOR : 1e-3;
    }
    /* last resort (tiles_max >= 2): the two roots, bound = their projected error */
    st->attempts += 1u;
    const int roots_fit = select_once(bc, v, INFINITY, st);
    FT_INVARIANT(roots_fit, "bintree over the cache: the two root tiles over bintree.tiles_max");
    st->budget_hit = 1;
    const int32_t half = (int32_t)1 << (bc->domain_log2 - 1u);
    const int32_t root_c[2] = {half, half};
    double lo[3], hi[3];
    const double e = ft_btc_diamond(bc, 0u, root_c, lo, hi);
    ft_view_bound_drawn_box(&v->b, lo, hi);
    st->tau_used_px = isinf(e) ? INFINITY : ft_view_bound_error_px(&v->b, e, lo, hi);
    st->tau_achieved_px = st->tau_used_px;
}
