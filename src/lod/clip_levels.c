/* clip_levels.c - the clipmap cache on the GPU (clip_levels.h). */
#include "lod/clip_levels.h"

#include <math.h>
#include <string.h>

/* Over a database the levels reach past the scene's grid, whose bounds no
 * longer hold what is drawn: the cache keeps its own (fit_depth). */
static ft_clip_desc desc_of(const ft_scene *s, const ft_terrain *t, ft_clip_bounds_rule bounds)
{
    const ft_clip_desc d = {s->clipmap_side, s->clipmap_levels, s->clipmap_update_samples_max,
                            t->db != NULL || bounds == FT_CLIP_BOUNDS_ALWAYS};
    return d;
}

static size_t packed_bytes(const ft_scene *s)
{
    return (size_t)s->clipmap_update_samples_max * 4u;
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
}
