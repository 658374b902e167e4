/* clip_cache.c - the clipmap levels' boxes and their strip updates
 * (clip_cache.h). Per level the state is two boxes and one strip in
 * progress; every step is O(levels) with no allocation and no loop that
 * depends on how far the eye moved. */
#include <math.h>
#include <string.h>

#include "terrain/clip_cache.h"

#include "core/camera.h"

static int box_empty(const ft_clip_box *b)
{
    return b->i1 <= b->i0 || b->j1 <= b->j0;
}

static int box_equal(const ft_clip_box *a, const ft_clip_box *b)
{
    return a->i0 == b->i0 && a->j0 == b->j0 && a->i1 == b->i1 && a->j1 == b->j1;
}

static uint64_t box_area(const ft_clip_box *b)
{
    return box_empty(b) ? 0u : (uint64_t)(b->i1 - b->i0) * (uint64_t)(b->j1 - b->j0);
}

static int64_t max_i64(int64_t a, int64_t b) { return a > b ? a : b; }
static int64_t min_i64(int64_t a, int64_t b) { return a < b ? a : b; }

/* a mod m in [0, m) for m a power of two (two's complement: exact for
 * negative a too). */
static uint32_t wrap_index(int64_t a, uint32_t m)
{
    return (uint32_t)((uint64_t)a & (uint64_t)(m - 1u));
}

static int is_pow2(uint32_t v) { return v != 0u && (v & (v - 1u)) == 0u; }

static int64_t floor_div_i64(int64_t a, int64_t b)
{
    const int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static size_t mirror_bytes(const ft_clip_desc *d)
{
    return (size_t)d->side * d->side * sizeof(float);
}

/* per level and block: lo, hi, err, morph, dev (ft_clip_block_bound) */
#define BLOCK_ARRAYS 5

static size_t block_bytes(const ft_clip_desc *d)
{
    const size_t n = d->side / FT_CLIP_BOUND_BLOCK;
    return n * n * sizeof(float);
}

ft_status ft_clip_plan(const ft_clip_desc *d, const ft_clip_source *src, ft_arena *a,
                       ft_error *err)
{
    if (!is_pow2(d->side) || d->side < FT_CLIP_SIDE_MIN || d->side > FT_CLIP_SIDE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.side = %u: must be a power of two in %u..%u", d->side,
                       FT_CLIP_SIDE_MIN, FT_CLIP_SIDE_MAX);
    }
    const uint32_t levels_max =
        (src->levels < FT_CLIP_LEVELS_MAX) ? src->levels : FT_CLIP_LEVELS_MAX;
    if (d->levels < 1u || d->levels > levels_max) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.levels = %u: must be 1..%u (the cache holds at most %u, the "
                       "height source gives %u)",
                       d->levels, levels_max, FT_CLIP_LEVELS_MAX, src->levels);
    }
    const uint64_t max_samples = (uint64_t)d->side * d->side;
    if (d->update_samples_max < 2u * d->side || d->update_samples_max > max_samples) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.update_samples_max = %u: must be %u..%llu (two rows of clipmap.side "
                       "= %u up to a whole level)",
                       d->update_samples_max, 2u * d->side, (unsigned long long)max_samples,
                       d->side);
    }
    if (src->read == NULL) {
        return ft_fail(err, FT_ERR_ARG, "clip cache: the height source has no reader");
    }
    if (a != NULL) {
        ft_arena_plan(a, FT_POOL_CLIP, (size_t)d->update_samples_max * sizeof(float));
        ft_arena_plan(a, FT_POOL_CLIP, (size_t)d->update_samples_max);
        if (d->keep_bounds) {
            ft_arena_plan(a, FT_POOL_CLIP, (size_t)d->update_samples_max * sizeof(float));
        }
        for (uint32_t l = 0u; d->keep_bounds && l < d->levels; ++l) {
            ft_arena_plan(a, FT_POOL_CLIP, mirror_bytes(d));
            ft_arena_plan(a, FT_POOL_CLIP, mirror_bytes(d));
            for (int k = 0; k < BLOCK_ARRAYS; ++k) {
                ft_arena_plan(a, FT_POOL_CLIP, block_bytes(d));
            }
        }
    }
    return FT_OK;
}

ft_status ft_clip_init(ft_clip_cache *c, const ft_clip_desc *d, const ft_clip_source *src,
                       ft_arena *a, ft_error *err)
{
    memset(c, 0, sizeof(*c));
    ft_status st = ft_clip_plan(d, src, NULL, err);
    if (st != FT_OK) {
        return st;
    }
    void *heights = NULL, *marks = NULL;
    st = ft_arena_take(a, FT_POOL_CLIP, (size_t)d->update_samples_max * sizeof(float), &heights,
                       err);
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_CLIP, (size_t)d->update_samples_max, &marks, err);
    }
    if (st != FT_OK) {
        return st;
    }
    if (d->keep_bounds) {
        void *dev = NULL;
        st = ft_arena_take(a, FT_POOL_CLIP, (size_t)d->update_samples_max * sizeof(float), &dev,
                           err);
        if (st != FT_OK) {
            return st;
        }
        c->dev_staging_m = dev;
    }
    const size_t texels = (size_t)d->side * d->side;
    const size_t blocks = block_bytes(d) / sizeof(float);
    for (uint32_t l = 0u; d->keep_bounds && l < d->levels; ++l) {
        void *m = NULL, *dm = NULL, *b[BLOCK_ARRAYS] = {NULL, NULL, NULL, NULL, NULL};
        st = ft_arena_take(a, FT_POOL_CLIP, mirror_bytes(d), &m, err);
        if (st == FT_OK) st = ft_arena_take(a, FT_POOL_CLIP, mirror_bytes(d), &dm, err);
        for (int k = 0; k < BLOCK_ARRAYS && st == FT_OK; ++k) {
            st = ft_arena_take(a, FT_POOL_CLIP, block_bytes(d), &b[k], err);
        }
        if (st != FT_OK) {
            return st;
        }
        c->mirror_m[l] = m;
        c->dev_mirror_m[l] = dm;
        c->block_lo_m[l] = b[0];
        c->block_hi_m[l] = b[1];
        c->block_err_m[l] = b[2];
        c->block_morph_m[l] = b[3];
        c->block_dev_m[l] = b[4];
        /* nothing uploaded yet: texels read 0, nothing is bounded */
        memset(m, 0, mirror_bytes(d));
        memset(b[0], 0, block_bytes(d));
        memset(b[1], 0, block_bytes(d));
        for (size_t k = 0u; k < texels; ++k) {
            c->dev_mirror_m[l][k] = INFINITY;
        }
        for (size_t k = 0u; k < blocks; ++k) {
            c->block_err_m[l][k] = INFINITY;
            c->block_morph_m[l][k] = INFINITY;
            c->block_dev_m[l][k] = INFINITY;
        }
    }
    c->desc = *d;
    c->src = *src;
    c->staging_m = heights;
    c->marks = marks;
    return FT_OK;
}

uint32_t ft_clip_texel(const ft_clip_cache *c, int64_t a)
{
    return wrap_index(a, c->desc.side);
}

/* The wanted box of a level for the eye at e (level-l samples): side
 * samples, its first one even, the eye within two samples of its middle. */
static int64_t want_origin(double e, uint32_t side)
{
    return 2 * (int64_t)floor((e - 0.5 * (double)side) * 0.5);
}

static void update_behind(ft_clip_cache *c)
{
    uint32_t behind = 0u;
    uint64_t outstanding = 0u;
    for (uint32_t l = 0u; l < c->desc.levels; ++l) {
        ft_clip_level *lv = &c->level[l];
        lv->samples_outstanding = box_area(&lv->want) - box_area(&lv->valid);
        outstanding += lv->samples_outstanding;
        behind += box_equal(&lv->valid, &lv->want) ? 0u : 1u;
    }
    c->stats.levels_behind = behind;
    c->stats.samples_outstanding = outstanding;
    if (behind > c->stats.levels_behind_max) {
        c->stats.levels_behind_max = behind;
    }
    if (outstanding > c->stats.samples_outstanding_max) {
        c->stats.samples_outstanding_max = outstanding;
    }
}

int ft_clip_recentre(ft_clip_cache *c, double eye_i, double eye_j)
{
    int moved = 0;
    const int64_t side = (int64_t)c->desc.side;
    for (uint32_t l = 0u; l < c->desc.levels; ++l) {
        ft_clip_level *lv = &c->level[l];
        const double scale = ldexp(1.0, -(int)l);
        ft_clip_box want;
        want.i0 = want_origin(eye_i * scale, c->desc.side);
        want.j0 = want_origin(eye_j * scale, c->desc.side);
        want.i1 = want.i0 + side;
        want.j1 = want.j0 + side;
        if (box_equal(&want, &lv->want) && !box_empty(&lv->want)) {
            continue;
        }
        moved = 1;
        lv->want = want;
        /* The texels of the valid part inside the new box are untouched by
         * the strips to come (they fill only samples outside it). */
        ft_clip_box v = lv->valid;
        v.i0 = max_i64(v.i0, want.i0);
        v.j0 = max_i64(v.j0, want.j0);
        v.i1 = min_i64(v.i1, want.i1);
        v.j1 = min_i64(v.j1, want.j1);
        if (box_empty(&v)) {
            v.i0 = want.i0;
            v.i1 = want.i1;
            v.j0 = v.j1 = want.j0;
        }
        lv->valid = v;
        memset(&c->strip[l], 0, sizeof(c->strip[l]));
    }
    if (moved) {
        c->stats.recentres_moved++;
        c->pending = 0;
        update_behind(c);
    }
    return moved;
}

/* The next strip of a level that is behind: the samples that join the
 * valid box next, in the order of clip_cache.h. */
static ft_clip_box next_strip(const ft_clip_level *lv)
{
    const ft_clip_box *v = &lv->valid, *w = &lv->want;
    ft_clip_box s = *v;
    if (v->i0 > w->i0) {
        s.i0 = w->i0;
        s.i1 = v->i0;
    } else if (v->i1 < w->i1) {
        s.i0 = v->i1;
        s.i1 = w->i1;
    } else if (v->j0 > w->j0) {
        s.j0 = w->j0;
        s.j1 = v->j0;
    } else {
        s.j0 = v->j1;
        s.j1 = w->j1;
    }
    return s;
}

/* The chunk of the level's strip at its cursor: up to the strip's end, the
 * next texel wrap (a multiple of side) and update_samples_max samples. */
static ft_clip_box chunk_at(const ft_clip_cache *c, uint32_t l)
{
    const ft_clip_box *s = &c->strip[l];
    const int64_t side = (int64_t)c->desc.side;
    ft_clip_box k;
    k.i0 = c->cursor_i[l];
    k.j0 = c->cursor_j[l];
    /* the next multiples of side above the cursor (exact for negatives) */
    const int64_t next_i = k.i0 - (int64_t)wrap_index(k.i0, c->desc.side) + side;
    const int64_t next_j = k.j0 - (int64_t)wrap_index(k.j0, c->desc.side) + side;
    k.i1 = min_i64(s->i1, next_i);
    /* every chunk of a row band has the band's rows, from the strip's width
     * (<= side, so at least two rows) */
    const int64_t rows = (int64_t)c->desc.update_samples_max / (s->i1 - s->i0);
    k.j1 = min_i64(min_i64(s->j1, next_j), k.j0 + rows);
    return k;
}

ft_status ft_clip_next_update(ft_clip_cache *c, ft_clip_update *u, int *have, ft_error *err)
{
    *have = 0;
    c->pending = 0;
    for (uint32_t n = 0u; n < c->desc.levels; ++n) {
        const uint32_t l = c->desc.levels - 1u - n; /* coarsest first */
        ft_clip_level *lv = &c->level[l];
        if (box_empty(&lv->want) || box_equal(&lv->valid, &lv->want)) {
            continue;
        }
        if (box_empty(&c->strip[l])) {
            c->strip[l] = next_strip(lv);
            c->cursor_i[l] = c->strip[l].i0;
            c->cursor_j[l] = c->strip[l].j0;
        }
        const ft_clip_box k = chunk_at(c, l);
        const uint32_t w = (uint32_t)(k.i1 - k.i0), h = (uint32_t)(k.j1 - k.j0);
        const ft_status st = c->src.read(c->src.ctx, l, k.i0, k.j0, w, h, c->staging_m,
                                         c->marks, c->dev_staging_m, err);
        if (st != FT_OK) {
            return st;
        }
        u->level = l;
        u->box = k;
        u->tex_x = ft_clip_texel(c, k.i0);
        u->tex_y = ft_clip_texel(c, k.j0);
        u->w = w;
        u->h = h;
        u->heights_m = c->staging_m;
        u->marks = c->marks;
        u->dev_m = c->dev_staging_m;
        c->last = *u;
        c->pending = 1;
        *have = 1;
        return FT_OK;
    }
    return FT_OK;
}

/* A bound rounded up to float (err: the texels' float steps too). */
static float round_up_f(double v)
{
    float f = (float)v;
    if ((double)f < v) {
        f = nextafterf(f, INFINITY);
    }
    return f;
}

/* Level l+1's bilinear surface at level-l sample (a, b), from its mirror:
 * the sample itself, or the mean of the 2 or 4 around a half-integer. */
static double coarser_at(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b)
{
    const uint32_t side = c->desc.side;
    const float *m = c->mirror_m[l + 1u];
    const int64_t a0 = floor_div_i64(a, 2), b0 = floor_div_i64(b, 2);
    const int64_t a1 = a0 + (a & 1), b1 = b0 + (b & 1);
    const double h00 = m[(size_t)wrap_index(b0, side) * side + wrap_index(a0, side)];
    const double h10 = m[(size_t)wrap_index(b0, side) * side + wrap_index(a1, side)];
    const double h01 = m[(size_t)wrap_index(b1, side) * side + wrap_index(a0, side)];
    const double h11 = m[(size_t)wrap_index(b1, side) * side + wrap_index(a1, side)];
    return 0.25 * (h00 + h10 + h01 + h11);
}

/* Block (bx, by) of level l over its texels and the apron around them
 * (texel indices wrap): its height range, and its errors
 * (ft_clip_block_bound). A cell is the texels (x, y) .. (x + 1, y + 1)
 * unless x or y is the wanted box's seam (the texel before its first
 * sample: the next texel holds a sample side away), and its samples are
 * the wanted box's. Texels the valid box does not hold are counted too:
 * they can only widen the bounds, and every texel a drawn cell uses was
 * resident when its block was last refreshed (an update refreshes the
 * blocks its apron meets; a coarser level is current whenever a finer one
 * takes an update, and keeps the samples under the finer valid box). */
static void block_range(const ft_clip_cache *c, uint32_t l, uint32_t bx, uint32_t by)
{
    const uint32_t side = c->desc.side, n = side / FT_CLIP_BOUND_BLOCK;
    const float *m = c->mirror_m[l], *dev = c->dev_mirror_m[l];
    const ft_clip_box *want = &c->level[l].want;
    const int64_t span = (int64_t)FT_CLIP_BOUND_BLOCK + 2 * (int64_t)FT_CLIP_BOUND_APRON;
    const int64_t x0 = (int64_t)bx * FT_CLIP_BOUND_BLOCK - FT_CLIP_BOUND_APRON;
    const int64_t y0 = (int64_t)by * FT_CLIP_BOUND_BLOCK - FT_CLIP_BOUND_APRON;
    const uint32_t seam_x = wrap_index(want->i0 - 1, side), seam_y = wrap_index(want->j0 - 1, side);
    const int morph = (l + 1u < c->desc.levels);
    float lo = m[(size_t)wrap_index(y0, side) * side + wrap_index(x0, side)], hi = lo;
    double err = 0.0, dmorph = 0.0, dev_max = 0.0;
    for (int64_t y = y0; y < y0 + span; ++y) {
        const uint32_t ty = wrap_index(y, side), ty1 = wrap_index(y + 1, side);
        const float *row = m + (size_t)ty * side, *row1 = m + (size_t)ty1 * side;
        const float *drow = dev + (size_t)ty * side, *drow1 = dev + (size_t)ty1 * side;
        const int64_t b = want->j0 + (int64_t)wrap_index((int64_t)ty - want->j0, side);
        for (int64_t x = x0; x < x0 + span; ++x) {
            const uint32_t tx = wrap_index(x, side), tx1 = wrap_index(x + 1, side);
            const float v = row[tx];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
            if (morph) {
                const int64_t a = want->i0 + (int64_t)wrap_index((int64_t)tx - want->i0, side);
                dmorph = fmax(dmorph, fabs((double)v - coarser_at(c, l, a, b)));
            }
            if (x + 1 >= x0 + span || y + 1 >= y0 + span || tx == seam_x || ty == seam_y) {
                continue; /* not a cell of the block's span */
            }
            /* the south-west corner's deviation is the cell's; a corner
             * without one (+INF) leaves the cell unbounded */
            const float d = fmaxf(fmaxf(drow[tx], drow[tx1]), fmaxf(drow1[tx], drow1[tx1]));
            const double twist =
                0.25 * fabs((double)v + (double)row1[tx1] - (double)row[tx1] - (double)row1[tx]);
            err = isinf(d) ? INFINITY : fmax(err, (double)drow[tx] + twist);
            dev_max = isinf(d) ? INFINITY : fmax(dev_max, (double)drow[tx]);
        }
    }
    const double steps = 4.0 * fmax(fabs((double)lo), fabs((double)hi)) * ldexp(1.0, -24);
    const size_t k = (size_t)by * n + bx;
    c->block_lo_m[l][k] = lo;
    c->block_hi_m[l][k] = hi;
    c->block_err_m[l][k] = round_up_f(err + steps);
    c->block_morph_m[l][k] = morph ? round_up_f(dmorph + steps) : 0.0f;
    c->block_dev_m[l][k] = round_up_f(dev_max + steps);
}

static int box_holds(const ft_clip_box *b, int64_t a, int64_t c)
{
    return a >= b->i0 && a < b->i1 && c >= b->j0 && c < b->j1;
}

int ft_clip_cell_bound(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b,
                       ft_clip_block_bound *out)
{
    if (!c->desc.keep_bounds || l >= c->desc.levels) {
        return 0;
    }
    const ft_clip_box *v = &c->level[l].valid;
    if (!box_holds(v, a, b) || !box_holds(v, a + 1, b + 1)) {
        return 0;
    }
    const uint32_t side = c->desc.side;
    const float *m = c->mirror_m[l], *dev = c->dev_mirror_m[l];
    const int morph = (l + 1u < c->desc.levels);
    double h[4], d = 0.0, dmorph = 0.0;
    for (int k = 0; k < 4; ++k) {
        const int64_t x = a + (k & 1), y = b + (k >> 1);
        const size_t t = (size_t)wrap_index(y, side) * side + wrap_index(x, side);
        h[k] = m[t];
        d = fmax(d, (double)dev[t]); /* a corner without a deviation (+INF): unknown */
        if (morph) {
            dmorph = fmax(dmorph, fabs(h[k] - coarser_at(c, l, x, y)));
        }
    }
    const double lo = fmin(fmin(h[0], h[1]), fmin(h[2], h[3]));
    const double hi = fmax(fmax(h[0], h[1]), fmax(h[2], h[3]));
    const double steps = 4.0 * fmax(fabs(lo), fabs(hi)) * ldexp(1.0, -24);
    const double sw = dev[(size_t)wrap_index(b, side) * side + wrap_index(a, side)];
    const double err = isinf(d) ? INFINITY : sw + 0.25 * fabs(h[0] + h[3] - h[1] - h[2]);
    out->box.i0 = a;
    out->box.j0 = b;
    out->box.i1 = a + 1;
    out->box.j1 = b + 1;
    out->lo_m = (float)lo;
    out->hi_m = (float)hi;
    out->err_m = isinf(err) ? INFINITY : round_up_f(err + steps);
    out->morph_m = morph ? round_up_f(dmorph + steps) : 0.0f;
    out->dev_m = isinf(d) ? INFINITY : round_up_f(sw + steps);
    return 1;
}

static float round_down_f(double v)
{
    float f = (float)v;
    if ((double)f > v) {
        f = nextafterf(f, -INFINITY);
    }
    return f;
}

void ft_clip_cell_range(const ft_clip_cache *c, uint32_t l, int64_t a, int64_t b, float *lo_m,
                        float *hi_m)
{
    const uint32_t side = c->desc.side;
    const float *m = c->mirror_m[l], *dev = c->dev_mirror_m[l];
    double h[4], unknown = 0.0;
    for (int k = 0; k < 4; ++k) {
        const size_t t = (size_t)wrap_index(b + (k >> 1), side) * side +
                         wrap_index(a + (k & 1), side);
        h[k] = m[t];
        unknown = fmax(unknown, (double)dev[t]); /* +INF: not known */
    }
    if (isinf(unknown)) {
        *lo_m = -INFINITY;
        *hi_m = INFINITY;
        return;
    }
    const double d = dev[(size_t)wrap_index(b, side) * side + wrap_index(a, side)];
    const double lo = fmin(fmin(h[0], h[1]), fmin(h[2], h[3]));
    const double hi = fmax(fmax(h[0], h[1]), fmax(h[2], h[3]));
    const double steps = 4.0 * fmax(fabs(lo), fabs(hi)) * ldexp(1.0, -24);
    *lo_m = round_down_f(lo - d - steps);
    *hi_m = round_up_f(hi + d + steps);
}

/* Copies a committed update into the level's mirror and refreshes the
 * blocks whose texels or apron it touched. */
static void keep_bounds_of(ft_clip_cache *c, const ft_clip_update *u)
{
    const uint32_t side = c->desc.side, n = side / FT_CLIP_BOUND_BLOCK;
    float *m = c->mirror_m[u->level], *dm = c->dev_mirror_m[u->level];
    for (uint32_t r = 0u; r < u->h; ++r) {
        memcpy(m + (size_t)(u->tex_y + r) * side + u->tex_x, u->heights_m + (size_t)r * u->w,
               (size_t)u->w * sizeof(float));
        float *drow = dm + (size_t)(u->tex_y + r) * side + u->tex_x;
        for (uint32_t q = 0u; q < u->w; ++q) {
            const float d = (u->dev_m != NULL) ? u->dev_m[(size_t)r * u->w + q] : -1.0f;
            drow[q] = (d >= 0.0f) ? d : INFINITY; /* negative: not known */
        }
    }
    /* blocks within the apron of the rect, as block indices that may wrap;
     * at most n per axis */
    const int64_t a = FT_CLIP_BOUND_APRON, b = FT_CLIP_BOUND_BLOCK;
    const int64_t bx0 = floor_div_i64((int64_t)u->tex_x - a, b);
    const int64_t bx1 = floor_div_i64((int64_t)u->tex_x + u->w - 1 + a, b);
    const int64_t by0 = floor_div_i64((int64_t)u->tex_y - a, b);
    const int64_t by1 = floor_div_i64((int64_t)u->tex_y + u->h - 1 + a, b);
    const int64_t nx = min_i64(bx1 - bx0 + 1, (int64_t)n), ny = min_i64(by1 - by0 + 1, (int64_t)n);
    for (int64_t y = 0; y < ny; ++y) {
        for (int64_t x = 0; x < nx; ++x) {
            block_range(c, u->level, wrap_index(bx0 + x, n), wrap_index(by0 + y, n));
        }
    }
}

void ft_clip_commit(ft_clip_cache *c, const ft_clip_update *u)
{
    /* Only the update produced last, and only while its level has not moved
     * since: a stale one went to texels outside the valid box (harmless). */
    if (!c->pending || u->level != c->last.level || !box_equal(&u->box, &c->last.box)) {
        return;
    }
    c->pending = 0;
    const uint32_t l = u->level;
    if (c->desc.keep_bounds) {
        keep_bounds_of(c, u);
    }
    ft_clip_box *s = &c->strip[l];
    c->stats.updates++;
    c->stats.samples_uploaded += (uint64_t)u->w * u->h;
    /* advance the cursor: along the row band, then to the next band */
    if (u->box.i1 < s->i1) {
        c->cursor_i[l] = u->box.i1;
    } else {
        c->cursor_i[l] = s->i0;
        c->cursor_j[l] = u->box.j1;
    }
    if (c->cursor_j[l] >= s->j1) {
        ft_clip_box *v = &c->level[l].valid;
        v->i0 = min_i64(v->i0, s->i0);
        v->i1 = max_i64(v->i1, s->i1);
        v->j0 = min_i64(v->j0, s->j0);
        v->j1 = max_i64(v->j1, s->j1);
        memset(s, 0, sizeof(*s));
        update_behind(c);
    }
}

int ft_clip_level_current(const ft_clip_cache *c, uint32_t l)
{
    return l < c->desc.levels && !box_empty(&c->level[l].want) &&
           box_equal(&c->level[l].valid, &c->level[l].want);
}

uint32_t ft_clip_finest_current(const ft_clip_cache *c)
{
    for (uint32_t l = 0u; l < c->desc.levels; ++l) {
        if (ft_clip_level_current(c, l)) {
            return l;
        }
    }
    return c->desc.levels;
}

/* The lattice pieces of one block's texels along one axis: texels
 * [t0, t0 + BLOCK) hold the wanted box's samples w0 + ((t - w0) mod side),
 * one run or two where the box's texels wrap; each cut to the valid
 * [v0, v1). Returns the number of pieces (0..2). */
static int block_pieces(int64_t t0, int64_t w0, int64_t v0, int64_t v1, uint32_t side,
                        int64_t p[2][2])
{
    const int64_t b = FT_CLIP_BOUND_BLOCK, end = w0 + (int64_t)side;
    const int64_t a0 = w0 + (int64_t)wrap_index(t0 - w0, side);
    const int64_t run[2][2] = {{a0, min_i64(a0 + b, end)}, {w0, w0 + (a0 + b - end)}};
    const int runs = a0 + b > end ? 2 : 1;
    int k = 0;
    for (int r = 0; r < runs; ++r) {
        const int64_t lo = max_i64(run[r][0], v0), hi = min_i64(run[r][1], v1);
        if (hi > lo) {
            p[k][0] = lo;
            p[k][1] = hi;
            ++k;
        }
    }
    return k;
}

uint64_t ft_clip_blocks_visit(const ft_clip_cache *c, uint32_t l, ft_clip_block_fn fn,
                              void *ctx)
{
    const uint32_t side = c->desc.side, n = side / FT_CLIP_BOUND_BLOCK;
    if (!c->desc.keep_bounds || l >= c->desc.levels || box_empty(&c->level[l].valid)) {
        return 0u;
    }
    const ft_clip_box *v = &c->level[l].valid, *wb = &c->level[l].want;
    uint64_t count = 0u;
    for (uint32_t by = 0u; by < n; ++by) {
        int64_t py[2][2];
        const int ky =
            block_pieces((int64_t)by * FT_CLIP_BOUND_BLOCK, wb->j0, v->j0, v->j1, side, py);
        for (uint32_t bx = 0u; bx < n && ky > 0; ++bx) {
            int64_t px[2][2];
            const int kx =
                block_pieces((int64_t)bx * FT_CLIP_BOUND_BLOCK, wb->i0, v->i0, v->i1, side, px);
            const size_t k = (size_t)by * n + bx;
            ft_clip_block_bound b = {{0, 0, 0, 0},         c->block_lo_m[l][k],
                                     c->block_hi_m[l][k],  c->block_err_m[l][k],
                                     c->block_morph_m[l][k], c->block_dev_m[l][k]};
            for (int qy = 0; qy < ky; ++qy) {
                for (int qx = 0; qx < kx; ++qx) {
                    b.box.i0 = px[qx][0];
                    b.box.i1 = px[qx][1];
                    b.box.j0 = py[qy][0];
                    b.box.j1 = py[qy][1];
                    fn(ctx, l, &b);
                    ++count;
                }
            }
        }
    }
    return count;
}

/* Calls fn for every resident piece of every level's blocks: its world box
 * (one sample past the piece: the triangles reach it) and its block's
 * height range. Returns the pieces visited. */
typedef void (*piece_fn)(void *ctx, double x0, double x1, double y0, double y1, double lo,
                         double hi);

typedef struct piece_world_ctx {
    const ft_clip_cache *c;
    const ft_clip_world *w;
    piece_fn fn;
    void *ctx;
} piece_world_ctx;

static void piece_world(void *ctx, uint32_t l, const ft_clip_block_bound *b)
{
    const piece_world_ctx *k = ctx;
    const ft_clip_world *w = k->w;
    const double s = (double)((int64_t)1 << l);
    const double li = (double)k->c->src.lattice_i0, lj = (double)k->c->src.lattice_j0;
    k->fn(k->ctx, w->origin_x_m + ((double)b->box.i0 * s - li) * w->cell_x_m,
          w->origin_x_m + ((double)b->box.i1 * s - li) * w->cell_x_m,
          w->origin_y_m + ((double)b->box.j0 * s - lj) * w->cell_y_m,
          w->origin_y_m + ((double)b->box.j1 * s - lj) * w->cell_y_m, b->lo_m, b->hi_m);
}

static uint64_t for_each_piece(const ft_clip_cache *c, const ft_clip_world *w, piece_fn fn,
                               void *ctx)
{
    piece_world_ctx k = {c, w, fn, ctx};
    uint64_t count = 0u;
    for (uint32_t l = 0u; l < c->desc.levels; ++l) {
        count += ft_clip_blocks_visit(c, l, piece_world, &k);
    }
    return count;
}

typedef struct clearance_ctx {
    const double *eye_m;
    double curv_k_per_m, best;
    int any;
    double box_min[2], box_max[2], zmin, zmax;
} clearance_ctx;

static void clearance_piece(void *ctx, double x0, double x1, double y0, double y1, double lo,
                            double hi)
{
    clearance_ctx *k = ctx;
    const double d = ft_camera_box_distance_m(k->eye_m, x0, x1, y0, y1, lo, hi, k->curv_k_per_m);
    k->best = d < k->best ? d : k->best;
    if (!k->any) {
        k->box_min[0] = x0;
        k->box_max[0] = x1;
        k->box_min[1] = y0;
        k->box_max[1] = y1;
        k->zmin = lo;
        k->zmax = hi;
        k->any = 1;
    }
    k->box_min[0] = fmin(k->box_min[0], x0);
    k->box_max[0] = fmax(k->box_max[0], x1);
    k->box_min[1] = fmin(k->box_min[1], y0);
    k->box_max[1] = fmax(k->box_max[1], y1);
    k->zmin = fmin(k->zmin, lo);
    k->zmax = fmax(k->zmax, hi);
}

int ft_clip_clearance_m(const ft_clip_cache *c, const ft_clip_world *w, const double eye_m[3],
                        double curv_k_per_m, double *clearance_m, double box_min_m[2],
                        double box_max_m[2], double *zmin_m, double *zmax_m)
{
    clearance_ctx k = {eye_m, curv_k_per_m, INFINITY, 0, {0.0, 0.0}, {0.0, 0.0}, 0.0, 0.0};
    (void)for_each_piece(c, w, clearance_piece, &k);
    *clearance_m = k.best;
    if (k.any) {
        box_min_m[0] = k.box_min[0];
        box_min_m[1] = k.box_min[1];
        box_max_m[0] = k.box_max[0];
        box_max_m[1] = k.box_max[1];
        *zmin_m = k.zmin;
        *zmax_m = k.zmax;
    }
    return k.any;
}

/* Level-l samples [*lo, *hi] (inclusive) whose pieces can meet world
 * [x0, x1] along one axis: the samples inside it and one more on each side
 * (a piece reaches one sample past its end), cut to the valid range
 * [v0, v1). 0 when none. */
static int axis_range(double x0_m, double x1_m, double origin_m, double cell_m, int64_t lattice0,
                      double s, int64_t v0, int64_t v1, int64_t *lo, int64_t *hi)
{
    const double a0 = floor(((x0_m - origin_m) / cell_m + (double)lattice0) / s) - 1.0;
    const double a1 = ceil(((x1_m - origin_m) / cell_m + (double)lattice0) / s) + 1.0;
    /* NaN-safe: a NaN box compares false and meets nothing */
    if (!(a1 >= (double)v0 && a0 <= (double)(v1 - 1))) {
        return 0;
    }
    *lo = a0 > (double)v0 ? (int64_t)a0 : v0;
    *hi = a1 < (double)(v1 - 1) ? (int64_t)a1 : v1 - 1;
    return 1;
}

double ft_clip_max_height_in(const ft_clip_cache *c, const ft_clip_world *w, double x0_m,
                             double y0_m, double x1_m, double y1_m)
{
    const uint32_t side = c->desc.side, n = side / FT_CLIP_BOUND_BLOCK;
    const int64_t blk = FT_CLIP_BOUND_BLOCK;
    double best = -INFINITY;
    for (uint32_t l = 0u; c->desc.keep_bounds && l < c->desc.levels; ++l) {
        const ft_clip_box *v = &c->level[l].valid;
        if (box_empty(v)) {
            continue;
        }
        const double s = (double)((int64_t)1 << l);
        int64_t i0, i1, j0, j1;
        if (!axis_range(x0_m, x1_m, w->origin_x_m, w->cell_x_m, c->src.lattice_i0, s, v->i0,
                        v->i1, &i0, &i1) ||
            !axis_range(y0_m, y1_m, w->origin_y_m, w->cell_y_m, c->src.lattice_j0, s, v->j0,
                        v->j1, &j0, &j1)) {
            continue;
        }
        /* block by block: a valid box spans at most side samples, so each
         * axis visits at most n + 1 blocks */
        for (int64_t b = j0; b <= j1;) {
            const uint32_t tb = wrap_index(b, side);
            const uint32_t by = tb / FT_CLIP_BOUND_BLOCK;
            for (int64_t a = i0; a <= i1;) {
                const uint32_t ta = wrap_index(a, side);
                const uint32_t bx = ta / FT_CLIP_BOUND_BLOCK;
                const double hi = c->block_hi_m[l][(size_t)by * n + bx];
                best = hi > best ? hi : best;
                a += blk - (int64_t)(ta % FT_CLIP_BOUND_BLOCK);
            }
            b += blk - (int64_t)(tb % FT_CLIP_BOUND_BLOCK);
        }
    }
    return best;
}
