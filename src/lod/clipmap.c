#include "lod/clipmap.h"

#include <math.h>
#include <string.h>

#include "lod/worst_pieces.h"

/* floor(a / 2^s) for any sign (an arithmetic shift of a negative value is
 * implementation-defined in C, so divide) */
static int64_t floor_shift(int64_t a, uint32_t s)
{
    const int64_t d = (int64_t)1 << s;
    int64_t q = a / d;
    if (a % d != 0 && a < 0) {
        q -= 1;
    }
    return q;
}

static int64_t ceil_shift(int64_t a, uint32_t s)
{
    return -floor_shift(-a, s);
}

static int64_t even_up(int64_t a)
{
    return floor_shift(a + 1, 1u) * 2;
}

static int64_t even_down(int64_t a)
{
    return floor_shift(a, 1u) * 2;
}

static int rect_drawn(const ft_cm_rect *r)
{
    return r->x1 > r->x0 && r->y1 > r->y0;
}

static int64_t max64(int64_t a, int64_t b)
{
    return a > b ? a : b;
}

static int64_t min64(int64_t a, int64_t b)
{
    return a < b ? a : b;
}

/* One side of D_l: the resident edge r, the data edge o (O_l), and the
 * coarser box's edge p (level-l units) with its kind; sign +1 for a low
 * (west, south) edge, -1 for a high one. Sets *trans (a transition side). */
static int64_t side_of(int64_t r, int64_t o, int has_parent, int64_t p, int p_trans, int sign,
                       int *trans)
{
    int64_t e = (sign > 0) ? max64(r, o) : min64(r, o);
    if (has_parent) {
        const int64_t lim = p + (p_trans ? 2 * sign : 0);
        e = (sign > 0) ? max64(e, lim) : min64(e, lim);
    }
    /* a coarser ring cell lies beyond, inside the data: not at the data
     * edge (beyond it the ring is clamped away) and not on the coarser
     * box's own edge (no ring there: the coarsest level's outer edge) */
    *trans = has_parent && e != o && e != p;
    return e;
}

void ft_cm_layout_make(ft_cm_layout *out, uint32_t levels, const ft_clip_box *valid,
                       const int64_t data_lo[2], const int64_t data_hi[2],
                       double transition_samples)
{
    memset(out, 0, sizeof *out);
    levels = (levels > FT_CLIP_LEVELS_MAX) ? FT_CLIP_LEVELS_MAX : levels;
    out->levels = levels;
    out->data_lo[0] = data_lo[0];
    out->data_lo[1] = data_lo[1];
    out->data_hi[0] = data_hi[0];
    out->data_hi[1] = data_hi[1];
    const double tw = (transition_samples >= 1.0) ? transition_samples : 1.0;
    int parent_drawn = 0;
    /* coarsest first: each box is bounded by the coarser one */
    for (uint32_t k = 0; k < levels; ++k) {
        const uint32_t l = levels - 1u - k;
        ft_cm_level *lv = &out->level[l];
        const ft_clip_box *v = &valid[l];
        const int has_parent = (l + 1u < levels);
        if (has_parent && !parent_drawn) {
            continue; /* a finer level lies inside the coarser one */
        }
        const ft_cm_level *pl = has_parent ? &out->level[l + 1u] : NULL;
        ft_cm_rect rr = {even_up(v->i0), even_up(v->j0), even_down(v->i1 - 1), even_down(v->j1 - 1)};
        const ft_cm_rect o = {floor_shift(data_lo[0], l + 1u) * 2, floor_shift(data_lo[1], l + 1u) * 2,
                              ceil_shift(data_hi[0], l + 1u) * 2, ceil_shift(data_hi[1], l + 1u) * 2};
        ft_cm_rect p = {0, 0, 0, 0};
        if (pl != NULL) {
            p.x0 = 2 * pl->box.x0;
            p.y0 = 2 * pl->box.y0;
            p.x1 = 2 * pl->box.x1;
            p.y1 = 2 * pl->box.y1;
        }
        lv->box.x0 = side_of(rr.x0, o.x0, has_parent, p.x0, pl ? pl->transition[FT_CM_W] : 0, 1,
                             &lv->transition[FT_CM_W]);
        lv->box.y0 = side_of(rr.y0, o.y0, has_parent, p.y0, pl ? pl->transition[FT_CM_S] : 0, 1,
                             &lv->transition[FT_CM_S]);
        lv->box.x1 = side_of(rr.x1, o.x1, has_parent, p.x1, pl ? pl->transition[FT_CM_E] : 0, -1,
                             &lv->transition[FT_CM_E]);
        lv->box.y1 = side_of(rr.y1, o.y1, has_parent, p.y1, pl ? pl->transition[FT_CM_N] : 0, -1,
                             &lv->transition[FT_CM_N]);
        lv->transition_samples = tw;
        lv->drawn = (lv->box.x1 - lv->box.x0 >= 2) && (lv->box.y1 - lv->box.y0 >= 2);
        parent_drawn = lv->drawn;
        if (lv->drawn) {
            if (out->drawn_count == 0u) {
                out->coarsest = l;
            }
            out->finest = l;
            out->drawn_count += 1u;
        }
    }
    /* holes, and T_l capped by the ring's narrowest transition side */
    for (uint32_t l = 1; l < levels; ++l) {
        ft_cm_level *lv = &out->level[l];
        const ft_cm_level *f = &out->level[l - 1u];
        if (!lv->drawn || !f->drawn) {
            continue;
        }
        lv->has_hole = 1;
        lv->hole.x0 = f->box.x0 / 2;
        lv->hole.y0 = f->box.y0 / 2;
        lv->hole.x1 = f->box.x1 / 2;
        lv->hole.y1 = f->box.y1 / 2;
        const int64_t width[4] = {lv->hole.x0 - lv->box.x0, lv->hole.y0 - lv->box.y0,
                                  lv->box.x1 - lv->hole.x1, lv->box.y1 - lv->hole.y1};
        for (int s = 0; s < 4; ++s) {
            if (lv->transition[s] && (double)width[s] < lv->transition_samples) {
                lv->transition_samples = (double)width[s];
            }
        }
    }
}

/* ---- draws ------------------------------------------------------------------ */

static uint64_t emit_blocks(uint32_t l, const ft_cm_rect *r, ft_cm_draw_fn fn, void *ctx)
{
    if (!rect_drawn(r)) {
        return 0u;
    }
    const int64_t b = FT_CM_BLOCK_CELLS;
    uint64_t tris = 0u;
    /* bounded: the rectangle is at most a level's side wide */
    for (int64_t by = r->y0; by < r->y1; by += b) {
        for (int64_t bx = r->x0; bx < r->x1; bx += b) {
            ft_cm_draw d = {l, FT_CM_BLOCK, {bx, by}, {1, 0}, {0, 1}, *r, 0u};
            d.triangles = (uint32_t)(2 * min64(b, r->x1 - bx) * min64(b, r->y1 - by));
            fn(ctx, &d);
            tris += d.triangles;
        }
    }
    return tris;
}

/* The stitch strip along one side of the hole: `len` cells from `start`,
 * going along u, the outer row one cell along v. */
static uint64_t emit_strip(uint32_t l, int64_t sx, int64_t sy, const int32_t u[2],
                           const int32_t v[2], int64_t len, const ft_cm_rect *clamp,
                           ft_cm_draw_fn fn, void *ctx)
{
    const int64_t b = FT_CM_BLOCK_CELLS;
    uint64_t tris = 0u;
    for (int64_t k = 0; k < len; k += b) {
        ft_cm_draw d = {l, FT_CM_STRIP, {sx + u[0] * k, sy + u[1] * k}, {u[0], u[1]}, {v[0], v[1]},
                        *clamp, 0u};
        d.triangles = (uint32_t)(3 * min64(b, len - k));
        fn(ctx, &d);
        tris += d.triangles;
    }
    return tris;
}

static uint64_t emit_corner(uint32_t l, int64_t x, int64_t y, ft_cm_draw_fn fn, void *ctx)
{
    ft_cm_draw d = {l, FT_CM_CORNER, {x, y}, {1, 0}, {0, 1}, {x, y, x + 1, y + 1}, 2u};
    fn(ctx, &d);
    return 2u;
}

uint64_t ft_cm_level_draws(const ft_cm_layout *lay, uint32_t l, ft_cm_draw_fn fn, void *ctx)
{
    if (l >= lay->levels || !lay->level[l].drawn) {
        return 0u;
    }
    const ft_cm_level *lv = &lay->level[l];
    const ft_cm_rect *D = &lv->box;
    if (!lv->has_hole) {
        return emit_blocks(l, D, fn, ctx);
    }
    const ft_cm_rect *H = &lv->hole;
    const int ring[4] = {H->x0 > D->x0, H->y0 > D->y0, D->x1 > H->x1, D->y1 > H->y1};
    const ft_cm_rect E = {H->x0 - ring[FT_CM_W], H->y0 - ring[FT_CM_S], H->x1 + ring[FT_CM_E],
                          H->y1 + ring[FT_CM_N]};
    uint64_t tris = 0u;
    /* regular cells: D minus E, as south, north (full width), west, east */
    const ft_cm_rect south = {D->x0, D->y0, D->x1, E.y0};
    const ft_cm_rect north = {D->x0, E.y1, D->x1, D->y1};
    const ft_cm_rect west = {D->x0, E.y0, E.x0, E.y1};
    const ft_cm_rect east = {E.x1, E.y0, D->x1, E.y1};
    tris += emit_blocks(l, &south, fn, ctx);
    tris += emit_blocks(l, &north, fn, ctx);
    tris += emit_blocks(l, &west, fn, ctx);
    tris += emit_blocks(l, &east, fn, ctx);
    /* stitch strips; the template's orientation is kept (det(u, v) = 1) */
    const int64_t lx = H->x1 - H->x0, ly = H->y1 - H->y0;
    if (ring[FT_CM_N]) {
        const int32_t u[2] = {1, 0}, v[2] = {0, 1};
        const ft_cm_rect c = {H->x0, H->y1, H->x1, H->y1 + 1};
        tris += emit_strip(l, H->x0, H->y1, u, v, lx, &c, fn, ctx);
    }
    if (ring[FT_CM_S]) {
        const int32_t u[2] = {-1, 0}, v[2] = {0, -1};
        const ft_cm_rect c = {H->x0, H->y0 - 1, H->x1, H->y0};
        tris += emit_strip(l, H->x1, H->y0, u, v, lx, &c, fn, ctx);
    }
    if (ring[FT_CM_E]) {
        const int32_t u[2] = {0, -1}, v[2] = {1, 0};
        const ft_cm_rect c = {H->x1, H->y0, H->x1 + 1, H->y1};
        tris += emit_strip(l, H->x1, H->y1, u, v, ly, &c, fn, ctx);
    }
    if (ring[FT_CM_W]) {
        const int32_t u[2] = {0, 1}, v[2] = {-1, 0};
        const ft_cm_rect c = {H->x0 - 1, H->y0, H->x0, H->y1};
        tris += emit_strip(l, H->x0, H->y0, u, v, ly, &c, fn, ctx);
    }
    /* the cells diagonal to H's corners */
    if (ring[FT_CM_W] && ring[FT_CM_S]) tris += emit_corner(l, E.x0, E.y0, fn, ctx);
    if (ring[FT_CM_E] && ring[FT_CM_S]) tris += emit_corner(l, H->x1, E.y0, fn, ctx);
    if (ring[FT_CM_W] && ring[FT_CM_N]) tris += emit_corner(l, E.x0, H->y1, fn, ctx);
    if (ring[FT_CM_E] && ring[FT_CM_N]) tris += emit_corner(l, H->x1, H->y1, fn, ctx);
    return tris;
}

/* ---- templates ------------------------------------------------------------------ */

uint32_t ft_cm_template_vertex_count(ft_cm_kind kind)
{
    return (kind == FT_CM_STRIP) ? FT_CM_STRIP_VERTICES : FT_CM_BLOCK_VERTICES;
}

void ft_cm_template_vertex(ft_cm_kind kind, uint32_t k, float out[2])
{
    const uint32_t b = FT_CM_BLOCK_CELLS;
    if (kind == FT_CM_STRIP) {
        if (k <= 2u * b) { /* inner row, half cells */
            out[0] = 0.5f * (float)k;
            out[1] = 0.0f;
        } else {
            out[0] = (float)(k - (2u * b + 1u));
            out[1] = 1.0f;
        }
        return;
    }
    out[0] = (float)(k % (b + 1u));
    out[1] = (float)(k / (b + 1u));
}

uint32_t ft_cm_template_indices(ft_cm_kind kind, uint16_t *out)
{
    const uint32_t b = FT_CM_BLOCK_CELLS;
    uint32_t n = 0;
    if (kind == FT_CM_STRIP) {
        const uint32_t outer = 2u * b + 1u;
        for (uint32_t k = 0; k < b; ++k) {
            const uint16_t a = (uint16_t)(2u * k), m = (uint16_t)(2u * k + 1u);
            const uint16_t bb = (uint16_t)(2u * k + 2u);
            const uint16_t d = (uint16_t)(outer + k), c = (uint16_t)(outer + k + 1u);
            /* counter-clockwise seen from above, like the blocks */
            out[n++] = a; out[n++] = m; out[n++] = d;
            out[n++] = m; out[n++] = bb; out[n++] = c;
            out[n++] = m; out[n++] = c; out[n++] = d;
        }
        return n;
    }
    /* block (and corner: its first cell, the first 6 indices) */
    for (uint32_t y = 0; y < b; ++y) {
        for (uint32_t x = 0; x < b; ++x) {
            const uint16_t v00 = (uint16_t)(y * (b + 1u) + x), v10 = (uint16_t)(v00 + 1u);
            const uint16_t v01 = (uint16_t)(v00 + b + 1u), v11 = (uint16_t)(v01 + 1u);
            out[n++] = v00; out[n++] = v10; out[n++] = v11;
            out[n++] = v00; out[n++] = v11; out[n++] = v01;
        }
    }
    return n;
}

/* ---- the mirror ------------------------------------------------------------------ */

void ft_cm_uniforms_of(const ft_cm_layout *lay, const ft_cm_draw *d, ft_cm_uniforms *u)
{
    const uint32_t l = d->level;
    const ft_cm_level *lv = &lay->level[l];
    const float scale = ldexpf(1.0f, (int)l);
    memset(u, 0, sizeof *u);
    u->place[0] = (float)d->origin[0];
    u->place[1] = (float)d->origin[1];
    u->axes[0] = (float)d->axis_u[0];
    u->axes[1] = (float)d->axis_u[1];
    u->axes[2] = (float)d->axis_v[0];
    u->axes[3] = (float)d->axis_v[1];
    u->clamp[0] = (float)d->clamp.x0;
    u->clamp[1] = (float)d->clamp.y0;
    u->clamp[2] = (float)d->clamp.x1;
    u->clamp[3] = (float)d->clamp.y1;
    /* exact: the data edges over a power of two */
    u->data[0] = (float)lay->data_lo[0] / scale;
    u->data[1] = (float)lay->data_lo[1] / scale;
    u->data[2] = (float)lay->data_hi[0] / scale;
    u->data[3] = (float)lay->data_hi[1] / scale;
    u->mbox[0] = lv->transition[FT_CM_W] ? (float)lv->box.x0 : -FT_CM_FAR;
    u->mbox[1] = lv->transition[FT_CM_S] ? (float)lv->box.y0 : -FT_CM_FAR;
    u->mbox[2] = lv->transition[FT_CM_E] ? (float)lv->box.x1 : FT_CM_FAR;
    u->mbox[3] = lv->transition[FT_CM_N] ? (float)lv->box.y1 : FT_CM_FAR;
    u->level[0] = scale;
    u->level[1] = (float)lv->transition_samples;
    u->level[2] = (l + 1u < lay->levels && lay->level[l + 1u].drawn) ? 1.0f : 0.0f;
}

static float clampf(float x, float lo, float hi)
{
    return fminf(fmaxf(x, lo), hi);
}

static float mixf(float a, float b, float t)
{
    return a * (1.0f - t) + b * t;
}

static float bilinear(uint32_t level, float cx, float cy, ft_cm_texel_fn texel, void *ctx)
{
    const float fx = floorf(cx), fy = floorf(cy);
    const float rx = cx - fx, ry = cy - fy;
    const int64_t a = (int64_t)fx, b = (int64_t)fy;
    const float h00 = texel(ctx, level, a, b), h10 = texel(ctx, level, a + 1, b);
    const float h01 = texel(ctx, level, a, b + 1), h11 = texel(ctx, level, a + 1, b + 1);
    return mixf(mixf(h00, h10, rx), mixf(h01, h11, rx), ry);
}

void ft_cm_vertex(const ft_cm_uniforms *u, uint32_t level, const float t[2],
                  ft_cm_texel_fn texel, void *ctx, ft_cm_vertex_out *out)
{
    float cx = u->place[0] + u->axes[0] * t[0] + u->axes[2] * t[1];
    float cy = u->place[1] + u->axes[1] * t[0] + u->axes[3] * t[1];
    cx = clampf(clampf(cx, u->clamp[0], u->clamp[2]), u->data[0], u->data[2]);
    cy = clampf(clampf(cy, u->clamp[1], u->clamp[3]), u->data[1], u->data[3]);
    float d = fminf(fminf(cx - u->mbox[0], u->mbox[2] - cx), fminf(cy - u->mbox[1], u->mbox[3] - cy));
    float w = (u->level[2] > 0.0f) ? clampf((u->level[1] - d) / u->level[1], 0.0f, 1.0f) : 0.0f;
    float h = 0.0f;
    if (w < 1.0f) {
        h = bilinear(level, cx, cy, texel, ctx);
    }
    if (w > 0.0f) {
        const float hc = bilinear(level + 1u, cx * 0.5f, cy * 0.5f, texel, ctx);
        h = (w >= 1.0f) ? hc : mixf(h, hc, w);
    }
    out->c[0] = cx;
    out->c[1] = cy;
    out->g[0] = cx * u->level[0];
    out->g[1] = cy * u->level[0];
    out->h_m = h;
    out->w = w;
}

/* ---- the bound of what a frame draws ---------------------------------------------- */

typedef struct cm_bound_ctx {
    const ft_cm_layout *lay;
    const ft_clip_cache *c;
    const ft_clip_world *w;
    const ft_view_bound *v;
    double quantum_m;
    ft_cm_bound *out;
    ft_worst_pieces cand; /* the FT_CM_REFINE_PIECES_MAX largest, and the rest */
} cm_bound_ctx;

/* The drawn cells of level l whose south-west corners lie in p, as that
 * corner range clipped to D_l's cells; 0 when none is drawn (outside D_l,
 * or every one inside the finer box H). */
static int drawn_corners(const ft_cm_level *lv, const ft_clip_box *p, ft_clip_box *out)
{
    const ft_cm_rect *d = &lv->box;
    out->i0 = p->i0 > d->x0 ? p->i0 : d->x0;
    out->j0 = p->j0 > d->y0 ? p->j0 : d->y0;
    out->i1 = p->i1 < d->x1 ? p->i1 : d->x1;
    out->j1 = p->j1 < d->y1 ? p->j1 : d->y1;
    if (out->i1 <= out->i0 || out->j1 <= out->j0) {
        return 0;
    }
    const ft_cm_rect *h = &lv->hole;
    return !(lv->has_hole && out->i0 >= h->x0 && out->i1 <= h->x1 && out->j0 >= h->y0 &&
             out->j1 <= h->y1);
}

/* 1 when a vertex of a cell with south-west corners in r can lie within
 * T_l of a transition side (its height blended towards level l + 1). */
static int morph_reaches(const ft_cm_level *lv, const ft_clip_box *r)
{
    const ft_cm_rect *d = &lv->box;
    const double t = lv->transition_samples;
    const double dist[4] = {(double)(r->i0 - d->x0), (double)(r->j0 - d->y0),
                            (double)(d->x1 - r->i1), (double)(d->y1 - r->j1)};
    for (int s = 0; s < 4; ++s) {
        if (lv->transition[s] && dist[s] < t) {
            return 1;
        }
    }
    return 0;
}

/* The bound of error e_m over the cells with south-west corners in r
 * (level l), z in [lo, hi]: 0 when outside the frustum. */
static double piece_px(const cm_bound_ctx *k, uint32_t l, const ft_clip_box *r, double lo_m,
                       double hi_m, double e_m)
{
    const ft_clip_world *w = k->w;
    const double s = ldexp(1.0, (int)l);
    const double li = (double)k->c->src.lattice_i0, lj = (double)k->c->src.lattice_j0;
    double lo[3] = {((double)r->i0 * s - li) * w->cell_x_m, ((double)r->j0 * s - lj) * w->cell_y_m,
                    lo_m};
    double hi[3] = {((double)r->i1 * s - li) * w->cell_x_m, ((double)r->j1 * s - lj) * w->cell_y_m,
                    hi_m};
    ft_view_bound_drawn_box(k->v, lo, hi);
    if (ft_view_bound_outside(k->v, lo, hi)) {
        return 0.0;
    }
    return ft_view_bound_error_px(k->v, e_m, lo, hi);
}

/* The error a drawn vertex of a piece or cell can carry. */
static double drawn_err_m(const cm_bound_ctx *k, const ft_cm_level *lv, const ft_clip_box *r,
                          const ft_clip_block_bound *b, double *morph_m)
{
    *morph_m = morph_reaches(lv, r) ? (double)b->morph_m : 0.0;
    return (double)b->err_m + *morph_m + k->quantum_m;
}

static void bound_piece(void *ctx, uint32_t l, const ft_clip_block_bound *b)
{
    cm_bound_ctx *k = ctx;
    const ft_cm_level *lv = &k->lay->level[l];
    ft_clip_box r;
    if (!drawn_corners(lv, &b->box, &r)) {
        return;
    }
    double morph_m = 0.0;
    const double e = drawn_err_m(k, lv, &r, b, &morph_m);
    const double px = piece_px(k, l, &r, (double)b->lo_m, (double)b->hi_m, e);
    if (px == 0.0) {
        return; /* outside the frustum, or no error at all */
    }
    k->out->pieces += 1u;
    k->out->unbounded += !(px < INFINITY);
    ft_worst_pieces_note(&k->cand, l, &r, px);
}

/* A candidate piece again, cell by cell (drawn cells only): the largest. */
static double refine_piece(const cm_bound_ctx *k, const ft_worst_piece *p)
{
    const ft_cm_level *lv = &k->lay->level[p->level];
    double best = 0.0;
    for (int64_t b = p->box.j0; b < p->box.j1; ++b) {
        for (int64_t a = p->box.i0; a < p->box.i1; ++a) {
            const ft_clip_box cell = {a, b, a + 1, b + 1};
            ft_clip_box r;
            ft_clip_block_bound cb;
            if (!drawn_corners(lv, &cell, &r) || !ft_clip_cell_bound(k->c, p->level, a, b, &cb)) {
                continue;
            }
            double morph_m = 0.0;
            const double e = drawn_err_m(k, lv, &r, &cb, &morph_m);
            const double px = piece_px(k, p->level, &r, (double)cb.lo_m - morph_m,
                                       (double)cb.hi_m + morph_m, e);
            best = px > best ? px : best;
        }
    }
    return best;
}

#define UNDRAWN_SPLIT 8

/* 1 when data the coarsest drawn box does not reach may be in view: each
 * strip between that box and the data's edge, over the data's height
 * range, tested against the frustum (that terrain is drawn as sky). */
static int undrawn_data_visible(const cm_bound_ctx *k, double zmin_m, double zmax_m)
{
    const ft_cm_layout *lay = k->lay;
    if (lay->drawn_count == 0u) {
        return 1;
    }
    const ft_cm_rect *d = &lay->level[lay->coarsest].box;
    const int64_t s = (int64_t)1 << lay->coarsest;
    const int64_t bx0 = d->x0 * s, bx1 = d->x1 * s, by0 = d->y0 * s, by1 = d->y1 * s;
    const int64_t *lo = lay->data_lo, *hi = lay->data_hi;
    /* x0, x1, y0, y1 of each strip, level-0 lattice */
    const int64_t strip[4][4] = {{lo[0], bx0, lo[1], hi[1]},
                                 {bx1, hi[0], lo[1], hi[1]},
                                 {lo[0], hi[0], lo[1], by0},
                                 {lo[0], hi[0], by1, hi[1]}};
    const ft_clip_world *w = k->w;
    const double li = (double)k->c->src.lattice_i0, lj = (double)k->c->src.lattice_j0;
    /* On a curved earth nothing of the data lies in view past the horizon
     * of its highest point over its lowest, seen from the eye over its
     * lowest: r <= sqrt((z_eye - zmin) / k) + sqrt((zmax - zmin) / k) (the
     * drop k r^2 is a parabola; a sight line past that dips under it, and
     * the data, whose heights are all over zmin, lie under the whole line
     * when the eye is over them). */
    double reach_m = INFINITY;
    const double kd = k->v->curv_drop_per_m2;
    const double ex = k->v->eye_m[0] / w->cell_x_m + li, ey = k->v->eye_m[1] / w->cell_y_m + lj;
    const int eye_over_data = ex >= (double)lo[0] && ex <= (double)hi[0] &&
                              ey >= (double)lo[1] && ey <= (double)hi[1];
    if (kd > 0.0 && eye_over_data) {
        reach_m = sqrt(fmax(k->v->eye_m[2] - zmin_m, 0.0) / kd) +
                  sqrt(fmax(zmax_m - zmin_m, 0.0) / kd);
    }
    for (int q = 0; q < 4; ++q) {
        if (strip[q][1] <= strip[q][0] || strip[q][3] <= strip[q][2]) {
            continue; /* the box reaches the data's edge there */
        }
        double blo[3] = {((double)strip[q][0] - li) * w->cell_x_m,
                         ((double)strip[q][2] - lj) * w->cell_y_m, zmin_m};
        double bhi[3] = {((double)strip[q][1] - li) * w->cell_x_m,
                         ((double)strip[q][3] - lj) * w->cell_y_m, zmax_m};
        int in_reach = 1;
        for (int i = 0; i < 2; ++i) {
            blo[i] = fmax(blo[i], k->v->eye_m[i] - reach_m);
            bhi[i] = fmin(bhi[i], k->v->eye_m[i] + reach_m);
            in_reach &= blo[i] <= bhi[i];
        }
        if (!in_reach) {
            continue;
        }
        /* in UNDRAWN_SPLIT^2 parts: the curvature drop over a part is
         * nearer its own than over the whole strip */
        for (int part = 0; part < UNDRAWN_SPLIT * UNDRAWN_SPLIT; ++part) {
            const double fx = (double)(part % UNDRAWN_SPLIT), fy = (double)(part / UNDRAWN_SPLIT);
            const double dx = (bhi[0] - blo[0]) / UNDRAWN_SPLIT, dy = (bhi[1] - blo[1]) / UNDRAWN_SPLIT;
            double plo[3] = {blo[0] + fx * dx, blo[1] + fy * dy, blo[2]};
            double phi[3] = {blo[0] + (fx + 1.0) * dx, blo[1] + (fy + 1.0) * dy, bhi[2]};
            ft_view_bound_drawn_box(k->v, plo, phi);
            if (!ft_view_bound_outside(k->v, plo, phi)) {
                return 1;
            }
        }
    }
    return 0;
}

void ft_cm_frame_bound(const ft_cm_layout *lay, const ft_clip_cache *c, const ft_clip_world *w,
                       const ft_view_bound *view, double quantum_m, double data_zmin_m,
                       double data_zmax_m, ft_cm_bound *out)
{
    memset(out, 0, sizeof *out);
    cm_bound_ctx k = {.lay = lay, .c = c, .w = w, .v = view, .quantum_m = quantum_m, .out = out};
    ft_worst_pieces_init(&k.cand, FT_CM_REFINE_PIECES_MAX);
    for (uint32_t l = 0u; l < lay->levels; ++l) {
        if (lay->level[l].drawn) {
            (void)ft_clip_blocks_visit(c, l, bound_piece, &k);
        }
    }
    out->undrawn_visible = undrawn_data_visible(&k, data_zmin_m, data_zmax_m);
    if (out->undrawn_visible) {
        out->bound_px = INFINITY;
        return;
    }
    out->bound_px = k.cand.rest_px;
    out->worst_level = k.cand.rest_level;
    for (uint32_t i = 0u; i < k.cand.n; ++i) {
        const ft_worst_piece *p = &k.cand.piece[i];
        double px = p->px;
        if (px > 1.0) { /* both bound the piece: the smaller */
            px = fmin(px, refine_piece(&k, p));
            out->refined += 1u;
        }
        if (px > out->bound_px) {
            out->bound_px = px;
            out->worst_level = p->level;
        }
    }
}
