/* clip_levels.c - the clipmap cache on the GPU (clip_levels.h). */
#include "lod/clip_levels.h"

#include <math.h>
#include <string.h>

/* Over a database the levels reach past the scene's grid, whose bounds no
 * longer hold what is drawn: the cache keeps its own (fit_depth). */
static ft_clip_desc desc_of(const ft_scene *s, const ft_terrain *t, ft_clip_bounds_rule bounds)
{
    const ft_clip_desc d = {s->clipmap_side, s->clipmap_levels, s->clipmap_update_samples_max,
                            t->db != NULL || bounds != FT_CLIP_BOUNDS_OVER_DB};
    return d;
}

static size_t packed_bytes(const ft_scene *s)
{
    return (size_t)s->clipmap_update_samples_max * 4u;
}

/* The ranges' staging: an update's cells (lo, hi), at least 2 rows */
static size_t range_bytes(const ft_scene *s)
{
    return (size_t)s->clipmap_update_samples_max * 2u * sizeof(float);
}

void ft_clip_levels_plan(const ft_scene *s, const ft_terrain *t, ft_clip_bounds_rule bounds,
                         ft_arena *a)
{
    ft_clip_source src;
    ft_error err;
    const ft_clip_desc d = desc_of(s, t, bounds);
    ft_clip_source_terrain(&src, t);
    if (t->db != NULL) { /* the database's levels past the window's */
        src.levels = t->db->hdr.level_count - t->db_level;
        ft_clip_db_source_plan(&t->db->hdr, s->clipmap_tile_slots, &d, a);
    }
    (void)ft_clip_plan(&d, &src, a, &err); /* init reports a bad description */
    ft_arena_plan(a, FT_POOL_METHOD, packed_bytes(s));
    if (bounds == FT_CLIP_BOUNDS_RANGES) {
        ft_arena_plan(a, FT_POOL_METHOD, range_bytes(s));
    }
}

/* Atlas columns: the smallest square grid of levels. */
static uint32_t atlas_cols(uint32_t levels)
{
    uint32_t c = 1u;
    while (c * c < levels) {
        ++c;
    }
    return c;
}

static ft_status check_desc(const ft_scene *s, const ft_gl *gl, ft_clip_tex_layout layout,
                            ft_error *err)
{
    const uint32_t side = s->clipmap_side;
    if (side < FT_CLIP_SIDE_MIN || side > FT_CLIP_SIDE_MAX || (side & (side - 1u)) != 0u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.side = %u: must be a power of two in %u..%u samples", side,
                       FT_CLIP_SIDE_MIN, FT_CLIP_SIDE_MAX);
    }
    if (s->clipmap_levels < 1u || s->clipmap_levels > FT_CLIP_LEVELS_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "clipmap.levels = %u: must be 1..%u",
                       s->clipmap_levels, FT_CLIP_LEVELS_MAX);
    }
    const uint32_t cols = (layout == FT_CLIP_TEX_ATLAS) ? atlas_cols(s->clipmap_levels) : 1u;
    if ((uint64_t)side * cols > (uint64_t)gl->caps.max_texture_size) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "clipmap.side = %u%s exceeds GL_MAX_TEXTURE_SIZE %d of this device", side,
                       cols > 1u ? " (its levels side by side in one atlas)" : "",
                       gl->caps.max_texture_size);
    }
    if (s->clipmap_update_samples_max < 2u * side ||
        (uint64_t)s->clipmap_update_samples_max > (uint64_t)side * side) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "clipmap.update_samples_max = %u: must be %u..%llu (two rows of "
                       "clipmap.side = %u up to a whole level)",
                       s->clipmap_update_samples_max, 2u * side,
                       (unsigned long long)side * side, side);
    }
    return FT_OK;
}


static void make_textures(ft_clip_levels *c, const ft_gl *gl)
{
    const int es3 = (gl->api == FT_GL_API_ES3);
    const uint32_t cols = (c->layout == FT_CLIP_TEX_ATLAS) ? atlas_cols(c->levels) : 1u;
    const uint32_t rows = (c->layout == FT_CLIP_TEX_ATLAS) ? (c->levels + cols - 1u) / cols : 1u;
    c->atlas_cols = cols;
    c->tex_w = c->side * cols;
    c->tex_h = c->side * rows;
    ft_texture_desc d = {c->unit, c->tex_w, c->tex_h, 0, 0, 0, 4u};
    if (c->fmt.format == FT_HEIGHT_FORMAT_FLOAT) {
        d.internal_format = es3 ? GL_R32F : GL_LUMINANCE;
        d.format = es3 ? GL_RED : GL_LUMINANCE;
        d.type = GL_FLOAT;
    } else {
        d.internal_format = es3 ? GL_RGBA8 : GL_RGBA;
        d.format = GL_RGBA;
        d.type = GL_UNSIGNED_BYTE;
    }
    c->tex_format = d.format;
    c->tex_type = d.type;
    for (uint32_t l = 0; l < c->levels; ++l) {
        if (c->layout == FT_CLIP_TEX_ATLAS) {
            if (l == 0u) {
                ft_gpu_texture_create(gl, &d, NULL, &c->tex[0], &c->gpu_bytes);
            }
            c->tex[l] = c->tex[0];
            c->origin_px[l][0] = (l % cols) * c->side;
            c->origin_px[l][1] = (l / cols) * c->side;
        } else {
            ft_gpu_texture_create(gl, &d, NULL, &c->tex[l], &c->gpu_bytes);
            c->origin_px[l][0] = c->origin_px[l][1] = 0u;
        }
    }
}

/* The ranges' texture (FT_CLIP_BOUNDS_RANGES), laid out as the heights'
 * atlas; every cell reads unbounded until refreshed. */
static ft_status make_ranges(ft_clip_levels *c, const ft_gl *gl, const ft_scene *s, ft_arena *a,
                             ft_error *err)
{
    if (gl->api != FT_GL_API_ES3 || c->layout != FT_CLIP_TEX_ATLAS ||
        c->fmt.format != FT_HEIGHT_FORMAT_FLOAT) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "the clipmap cache's cell ranges (a vertex shader that bounds its error "
                       "over the cache) need GLES 3 and float heights (this context: %s, "
                       "heights %s)",
                       gl->api == FT_GL_API_ES3 ? "GLES 3" : "GLES 2",
                       c->fmt.format == FT_HEIGHT_FORMAT_FLOAT ? "float" : "packed");
    }
    ft_status st = ft_arena_take(a, FT_POOL_METHOD, range_bytes(s), (void **)&c->range_staging,
                                 err);
    if (st != FT_OK) {
        return st;
    }
    c->range_cells = (uint32_t)(range_bytes(s) / (2u * sizeof(float)));
    const ft_texture_desc d = {c->unit + 1u, c->tex_w, c->tex_h, GL_RG32F, GL_RG, GL_FLOAT,
                               8u};
    ft_gpu_texture_create(gl, &d, NULL, &c->range_tex, &c->gpu_bytes);
    const ft_texture_desc db = {c->unit + 2u, c->tex_w / FT_CLIP_BOUND_BLOCK,
                                c->tex_h / FT_CLIP_BOUND_BLOCK, GL_RG32F, GL_RG, GL_FLOAT, 8u};
    ft_gpu_texture_create(gl, &db, NULL, &c->block_range_tex, &c->gpu_bytes);
    for (uint32_t l = 0; l < c->levels; ++l) {
        /* unbounded until refreshed: the level's texels, row by row
         * through the staging (range_cells >= 2 side) */
        for (uint32_t k = 0; k < 2u * c->side; k += 2u) {
            c->range_staging[k] = -FT_CLIP_RANGE_UNBOUNDED_M;
            c->range_staging[k + 1u] = FT_CLIP_RANGE_UNBOUNDED_M;
        }
        gl->ActiveTexture(c->unit + 1u);
        gl->BindTexture(GL_TEXTURE_2D, c->range_tex);
        for (uint32_t y = 0; y < c->side; ++y) {
            gl->TexSubImage2D(GL_TEXTURE_2D, 0, (GLint)c->origin_px[l][0],
                              (GLint)(c->origin_px[l][1] + y), (GLsizei)c->side, 1, GL_RG,
                              GL_FLOAT, c->range_staging);
        }
        gl->ActiveTexture(GL_TEXTURE0);
    }
    return FT_OK;
}

/* One update's heights into its level's texels. */
static void upload(ft_clip_levels *c, const ft_gl *gl, const ft_clip_update *u)
{
    const void *data = u->heights_m;
    if (c->fmt.format != FT_HEIGHT_FORMAT_FLOAT) {
        const size_t n = (size_t)u->w * u->h;
        for (size_t i = 0; i < n; ++i) {
            double f = ((double)u->heights_m[i] - c->fmt.pack_min) / c->fmt.pack_range;
            f = (f > 0.0) ? ((f < 1.0) ? f : 1.0) : 0.0;
            const uint32_t q = (uint32_t)(f * 16777215.0 + 0.5);
            c->packed[i * 4u + 0u] = (uint8_t)(q >> 16);
            c->packed[i * 4u + 1u] = (uint8_t)(q >> 8);
            c->packed[i * 4u + 2u] = (uint8_t)q;
            c->packed[i * 4u + 3u] = 255u;
        }
        data = c->packed;
    }
    gl->ActiveTexture(c->unit);
    gl->BindTexture(GL_TEXTURE_2D, c->tex[u->level]);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, (GLint)(c->origin_px[u->level][0] + u->tex_x),
                      (GLint)(c->origin_px[u->level][1] + u->tex_y), (GLsizei)u->w,
                      (GLsizei)u->h, c->tex_format, c->tex_type, data);
    gl->ActiveTexture(GL_TEXTURE0);
}

/* The ranges of level l's cells [a0, a1) x [b0, b1) (south-west corner
 * samples), clipped to the cells of the wanted box (the only ones that can
 * become resident: the clipped box is under side wide, so no two of its
 * cells share a texel), uploaded in pieces that do not wrap in texel space
 * (at most 2 x 2), each in runs of rows that fit the staging (at least 2
 * rows: range_cells >= 2 side). */
static void refresh_ranges(ft_clip_levels *c, uint32_t l, int64_t a0, int64_t a1, int64_t b0,
                           int64_t b1)
{
    const ft_clip_box *w = &c->cache.level[l].want;
    a0 = a0 > w->i0 ? a0 : w->i0;
    b0 = b0 > w->j0 ? b0 : w->j0;
    a1 = a1 < w->i1 - 1 ? a1 : w->i1 - 1;
    b1 = b1 < w->j1 - 1 ? b1 : w->j1 - 1;
    if (a1 <= a0 || b1 <= b0) {
        return;
    }
    const int64_t side = (int64_t)c->side;
    const ft_gl *gl = c->gl;
    gl->ActiveTexture(c->unit + 1u);
    gl->BindTexture(GL_TEXTURE_2D, c->range_tex);
    for (int64_t pa = a0; pa < a1;) {
        const int64_t ta = (int64_t)ft_clip_texel(&c->cache, pa);
        const int64_t qa = (a1 - pa < side - ta) ? a1 : pa + (side - ta); /* to the seam */
        const uint32_t wid = (uint32_t)(qa - pa);
        const uint32_t rows_max = c->range_cells / wid;
        for (int64_t pb = b0; pb < b1;) {
            const int64_t tb = (int64_t)ft_clip_texel(&c->cache, pb);
            int64_t qb = (b1 - pb < side - tb) ? b1 : pb + (side - tb);
            qb = (qb - pb > (int64_t)rows_max) ? pb + (int64_t)rows_max : qb;
            float *out = c->range_staging;
            for (int64_t b = pb; b < qb; ++b) {
                for (int64_t a = pa; a < qa; ++a, out += 2) {
                    ft_clip_cell_range(&c->cache, l, a, b, &out[0], &out[1]);
                    /* unknown: a large finite value (an infinite varying
                     * turns to NaN where a weight is 0) */
                    out[0] = fmaxf(out[0], -FT_CLIP_RANGE_UNBOUNDED_M);
                    out[1] = fminf(out[1], FT_CLIP_RANGE_UNBOUNDED_M);
                }
            }
            gl->TexSubImage2D(GL_TEXTURE_2D, 0, (GLint)(c->origin_px[l][0] + (uint32_t)ta),
                              (GLint)(c->origin_px[l][1] + (uint32_t)tb), (GLsizei)wid,
                              (GLsizei)(qb - pb), GL_RG, GL_FLOAT, c->range_staging);
            c->range_uploads += 1u;
            pb = qb;
        }
        pa = qa;
    }
    gl->ActiveTexture(GL_TEXTURE0);
}

/* Level l's blocks' ranges (clip_cache.h, ft_clip_block_bound: the block's
 * texels and apron widened by its error, which is at least every cell's
 * deviation), each block a texel of the block-range texture, uploaded
 * whole, rows at a time through the staging; on the coarsest level their
 * union too (top_range_m: what a box too wide for any level's blocks takes). */
static void refresh_block_ranges(ft_clip_levels *c, uint32_t l)
{
    const uint32_t n = c->side / FT_CLIP_BOUND_BLOCK;
    const uint32_t rows_max = c->range_cells / n;
    const ft_gl *gl = c->gl;
    float lo_all = FT_CLIP_RANGE_UNBOUNDED_M, hi_all = -FT_CLIP_RANGE_UNBOUNDED_M;
    gl->ActiveTexture(c->unit + 2u);
    gl->BindTexture(GL_TEXTURE_2D, c->block_range_tex);
    for (uint32_t y0 = 0; y0 < n; y0 += rows_max) {
        const uint32_t rows = (n - y0 < rows_max) ? n - y0 : rows_max;
        float *out = c->range_staging;
        for (uint32_t k = y0 * n; k < (y0 + rows) * n; ++k, out += 2) {
            const double err = c->cache.block_err_m[l][k];
            const double lo = (double)c->cache.block_lo_m[l][k] - err;
            const double hi = (double)c->cache.block_hi_m[l][k] + err;
            /* rounded outward (err is rounded up already; the sum too) */
            out[0] = isinf(err) ? -FT_CLIP_RANGE_UNBOUNDED_M
                                : nextafterf((float)lo, -FT_CLIP_RANGE_UNBOUNDED_M);
            out[1] = isinf(err) ? FT_CLIP_RANGE_UNBOUNDED_M
                                : nextafterf((float)hi, FT_CLIP_RANGE_UNBOUNDED_M);
            lo_all = fminf(lo_all, out[0]);
            hi_all = fmaxf(hi_all, out[1]);
        }
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, (GLint)(c->origin_px[l][0] / FT_CLIP_BOUND_BLOCK),
                          (GLint)(c->origin_px[l][1] / FT_CLIP_BOUND_BLOCK + y0), (GLsizei)n,
                          (GLsizei)rows, GL_RG, GL_FLOAT, c->range_staging);
        c->range_uploads += 1u;
    }
    gl->ActiveTexture(GL_TEXTURE0);
    if (l + 1u == c->levels) {
        c->top_range_m[0] = lo_all;
        c->top_range_m[1] = hi_all;
    }
}

/* One update (read, upload, commit): 1 when one ran. Timed with now (when
 * not NULL), its time raises the declared cost of an update when it is the
 * slowest yet. */
static int run_one(ft_clip_levels *c, uint64_t (*now)(void), ft_error *err, ft_status *st)
{
    const uint64_t t0 = now != NULL ? now() : 0u;
    ft_clip_update u;
    int have = 0;
    *st = ft_clip_next_update(&c->cache, &u, &have, err);
    if (*st != FT_OK || !have) {
        return 0;
    }
    upload(c, c->gl, &u);
    ft_clip_commit(&c->cache, &u);
    if (c->range_tex != 0u) {
        /* the update's cells and those west and south of it (their east
         * and north corners are its samples) */
        refresh_ranges(c, u.level, u.box.i0 - 1, u.box.i1, u.box.j0 - 1, u.box.j1);
        refresh_block_ranges(c, u.level);
    }
    if (now != NULL) {
        const uint64_t dt = now() - t0;
        uint64_t *slot = &c->cost_ns[c->cost_at];
        *slot = dt > *slot ? dt : *slot;
        c->update_ns_max = dt > c->update_ns_max ? dt : c->update_ns_max;
    }
    return 1;
}

/* Updates (coarsest level first) until the coarsest level is whole. Bound:
 * a whole level is side / rows bands of rows >= 2 rows (a band is split
 * where the texel rows wrap, adding one, and where the columns wrap, doubling
 * them), so at most side + 2 updates; a partial level's strips take fewer
 * samples and at most 4 more splits. */
static uint32_t complete_coarsest(ft_clip_levels *c, ft_error *err, ft_status *st)
{
    const uint32_t most = c->side + 8u;
    uint32_t n = 0u;
    *st = FT_OK;
    while (n < most && !ft_clip_level_current(&c->cache, c->levels - 1u) &&
           run_one(c, NULL, err, st)) {
        ++n;
    }
    return n;
}

/* Runs at most max_updates updates; returns how many ran. */
static uint32_t run_updates(ft_clip_levels *c, uint32_t max_updates, ft_error *err,
                            ft_status *st)
{
    uint32_t n = 0;
    *st = FT_OK;
    while (n < max_updates && run_one(c, NULL, err, st)) {
        ++n;
    }
    return n;
}

void ft_clip_levels_eye(const ft_clip_levels *c, const ft_terrain *t, const double eye_m[3],
                        double *eye_i, double *eye_j)
{
    *eye_i = (eye_m[0] - t->origin_world_x_m) / t->cell_x_m + (double)c->src.lattice_i0;
    *eye_j = (eye_m[1] - t->origin_world_y_m) / t->cell_y_m + (double)c->src.lattice_j0;
}

ft_status ft_clip_levels_init(ft_clip_levels *c, const ft_gl *gl, const ft_scene *s,
                              const ft_terrain *t, ft_clip_tex_layout layout,
                              ft_clip_bounds_rule bounds, GLenum unit, ft_arena *a,
                              ft_error *err)
{
    memset(c, 0, sizeof *c);
    ft_status st = check_desc(s, gl, layout, err);
    if (st != FT_OK) {
        return st;
    }
    const ft_clip_desc d = desc_of(s, t, bounds);
    /* over a .ftd window, the cache reads the database itself: the terrain
     * goes on past the window, from the finest level that has data */
    if (t->db != NULL) {
        st = ft_clip_source_db(&c->src, &c->db_src, t->db, t->db_level, t->db_i0, t->db_j0,
                               t->db_fill_m, s->clipmap_tile_slots, &d, a, err);
    } else {
        ft_clip_source_terrain(&c->src, t);
    }
    if (st == FT_OK) {
        st = ft_clip_init(&c->cache, &d, &c->src, a, err);
    }
    if (st == FT_OK) {
        st = ft_arena_take(a, FT_POOL_METHOD, packed_bytes(s), (void **)&c->packed, err);
    }
    if (st != FT_OK) {
        return st;
    }
    c->gl = gl;
    c->layout = layout;
    c->unit = unit;
    c->side = d.side;
    c->levels = c->cache.desc.levels;
    c->updates_per_frame = s->clipmap_updates_per_frame;
    /* packed texels hold the range of everything the cache can read: over
     * a database its whole range (the window's would clamp the terrain
     * past it), widened by the window's (its floor fill) */
    float lo_m = t->min_height_m, hi_m = t->max_height_m;
    if (t->db != NULL) {
        lo_m = fminf(lo_m, t->db->hdr.min_height_m);
        hi_m = fmaxf(hi_m, t->db->hdr.max_height_m);
    }
    c->fmt = ft_gpu_height_format(gl, s->height_format, lo_m, hi_m);
    make_textures(c, gl);
    if (bounds == FT_CLIP_BOUNDS_RANGES) {
        st = make_ranges(c, gl, s, a, err);
        if (st != FT_OK) {
            return st;
        }
    }
    /* the first frame is complete: every level filled around the terrain's
     * middle now, and again around the first eye by the first select */
    (void)ft_clip_recentre(&c->cache, (double)c->src.lattice_i0 + 0.5 * (t->width - 1u),
                           (double)c->src.lattice_j0 + 0.5 * (t->height - 1u));
    (void)run_updates(c, UINT32_MAX, err, &st);
    if (st != FT_OK) {
        return st;
    }
    c->fill_whole = 1;
    return ft_gl_check(gl, "clipmap cache init (level textures, first fill)", err);
}

void ft_clip_levels_select(ft_clip_levels *c, const ft_terrain *t, const ft_camera *cam)
{
    double ei, ej;
    ft_error err;
    ft_status st;
    ft_clip_levels_eye(c, t, cam->eye_m, &ei, &ej);
    (void)ft_clip_recentre(&c->cache, ei, ej);
    /* the first view is filled whole (init's promise); then the budget */
    const uint32_t n = c->fill_whole ? UINT32_MAX : c->updates_per_frame;
    c->fill_whole = 0;
    c->updates_last = run_updates(c, n, &err, &st);
    if (st != FT_OK) {
        c->read_errors += 1u; /* the cache is unchanged: retried next frame */
    }
    /* What no level holds would be drawn as sky, which hides terrain: the
     * coarsest level is completed now, whatever the frame's budget. In
     * flight that is a strip of 2 x side samples when its box moves; after
     * a jump, the whole level. */
    c->forced_last = complete_coarsest(c, &err, &st);
    if (st != FT_OK) {
        c->read_errors += 1u;
    }
    c->updates_last += c->forced_last;
    c->forced_updates += c->forced_last;
    c->forced_frames += c->forced_last > 0u;
}

/* Bounded by the updates a level set can need (every level whole, in the
 * smallest pieces). Updates run while the declared cost (clip_levels.h,
 * FT_CLIP_COST_CALLS) fits before the deadline; the first call, with nothing
 * measured yet, runs one update and so learns the cost. */
void ft_clip_levels_spare(ft_clip_levels *c, uint64_t (*now)(void), uint64_t deadline_ns)
{
    const uint64_t most = (uint64_t)c->levels * c->side * c->side / (2u * c->side) +
                          (uint64_t)c->levels * 4u;
    ft_error err;
    ft_status st = FT_OK;
    uint64_t n = 0u;
    while (n < most && now() + c->update_ns_max <= deadline_ns) {
        if (!run_one(c, now, &err, &st)) {
            break;
        }
        ++n;
    }
    if (st != FT_OK) {
        c->read_errors += 1u; /* the cache is unchanged: retried later */
    }
    const int deferred = c->cache.stats.levels_behind > 0u;
    c->spare_updates += n;
    c->spare_deferred += deferred;
    /* A call that ran updates or left some for later moves the window on
     * (a call with nothing to do keeps what was learnt); the declared cost
     * is the slowest update still in it. */
    if (n > 0u || deferred) {
        c->cost_at = (c->cost_at + 1u) % FT_CLIP_COST_CALLS;
        c->cost_ns[c->cost_at] = 0u;
        uint64_t m = 0u;
        for (uint32_t i = 0; i < FT_CLIP_COST_CALLS; ++i) {
            m = c->cost_ns[i] > m ? c->cost_ns[i] : m;
        }
        c->update_ns_max = m;
    }
}

ft_clip_world ft_clip_levels_world(const ft_terrain *t)
{
    const ft_clip_world w = {t->origin_world_x_m, t->origin_world_y_m, t->cell_x_m, t->cell_y_m};
    return w;
}

/* Called after select, so it bounds what this frame draws (the grid's range
 * put the near plane 5 km out once the eye left the window, and cut away
 * the terrain below it). */
int ft_clip_levels_fit_depth(const ft_clip_levels *c, const ft_terrain *t, ft_camera *cam,
                             double corner_cos)
{
    if (!c->cache.desc.keep_bounds) {
        return 0;
    }
    const ft_clip_world w = ft_clip_levels_world(t);
    double closest = 0.0, zmin = 0.0, zmax = 0.0, box_min[2], box_max[2];
    if (!ft_clip_clearance_m(&c->cache, &w, cam->eye_m, t->curv_drop_per_m2, &closest, box_min,
                             box_max, &zmin, &zmax)) {
        return 0;
    }
    double near_m = 0.0, far_m = 0.0;
    ft_camera_depth_range_from(cam->eye_m, closest, zmin, zmax, box_min, box_max, corner_cos,
                               t->curv_drop_per_m2, &near_m, &far_m);
    ft_error err;
    return ft_camera_set_depth_range(cam, near_m, far_m, &err) == FT_OK;
}

void ft_clip_levels_shutdown(ft_clip_levels *c, const ft_gl *gl)
{
    const uint32_t n = (c->layout == FT_CLIP_TEX_ATLAS) ? 1u : c->levels;
    for (uint32_t l = 0; l < n; ++l) {
        if (c->tex[l]) gl->DeleteTextures(1, &c->tex[l]);
    }
    memset(c->tex, 0, sizeof c->tex);
    if (c->range_tex) gl->DeleteTextures(1, &c->range_tex);
    if (c->block_range_tex) gl->DeleteTextures(1, &c->block_range_tex);
    c->range_tex = c->block_range_tex = 0u;
}
