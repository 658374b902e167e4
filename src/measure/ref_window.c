/* ref_window.c - the metric's truth over a terrain database (ref_window.h). */
#include "measure/ref_window.h"

#include <math.h>
#include <string.h>

#include "core/mem_budget.h"
#include "terrain/pyramid.h"

/* The block's parts, in order, each rounded to the arena's alignment. */
typedef struct ref_parts {
    size_t heights, pyramid, bits, tiles, coarse;
} ref_parts;

static ref_parts parts_of(const ft_tdb_header *h, uint32_t level, uint32_t side)
{
    const size_t n = (size_t)side * side;
    ref_parts p;
    p.heights = ft_arena_round(n * sizeof(float));
    p.pyramid = ft_arena_round(ft_pyramid_bytes(side, side));
    p.bits = ft_arena_round((n + 7u) / 8u);
    p.tiles = ft_arena_round(ft_tdb_tile_cache_bytes(h, FT_REF_WINDOW_TILE_SLOTS, 0));
    p.coarse = ft_arena_round(ft_dbw_rect_coarse_bytes(h, level, side, side));
    return p;
}

size_t ft_ref_window_bytes(const ft_tdb_header *h, uint32_t level, uint32_t side)
{
    const ref_parts p = parts_of(h, level, side);
    return p.heights + p.pyramid + p.bits + p.tiles + p.coarse;
}

ft_status ft_ref_window_init(ft_ref_window *w, const ft_terrain *scene, uint32_t side, void *mem,
                             size_t bytes, ft_error *err)
{
    memset(w, 0, sizeof *w);
    if (scene->db == NULL) {
        return ft_fail(err, FT_ERR_ARG, "reference window: the terrain is not a database window");
    }
    if (side < FT_GRID_SIDE_MIN || side > FT_GRID_SIDE_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "metric.truth_side_samples = %u: must be %u..%u", side,
                       FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    const size_t need = ft_ref_window_bytes(&scene->db->hdr, scene->db_level, side);
    if (mem == NULL || bytes < need) {
        return ft_fail(err, FT_ERR_ARG, "reference window: %zu bytes given, %zu needed", bytes,
                       need);
    }
    const ref_parts p = parts_of(&scene->db->hdr, scene->db_level, side);
    unsigned char *m = mem; /* the parts in order */
    w->scene = scene;
    w->t = *scene;
    w->t.width = side;
    w->t.height = side;
    w->t.heights_m = (float *)(void *)m;
    m += p.heights;
    memset(&w->t.pyr, 0, sizeof w->t.pyr);
    ft_status st = ft_pyramid_layout(&w->t, m, p.pyramid, err);
    if (st != FT_OK) {
        return st;
    }
    m += p.pyramid;
    w->t.void_bits = m; /* the read's marks (the caster ignores them) */
    w->t.void_count = 0u;
    m += p.bits;
    ft_tdb_tile_cache_init(&w->tiles, &scene->db->hdr, FT_REF_WINDOW_TILE_SLOTS, 0, m);
    m += p.tiles;
    w->coarse_m = (float *)(void *)m;
    w->coarse_bytes = p.coarse;
    return FT_OK;
}

/* The lattice index of the window's sample (0, 0) for eye position x (world
 * metres along one axis): the eye's lattice position rounded to a multiple
 * of the step, less half the side. */
static int64_t corner_for(double eye_m, double origin_world_m, double cell_m, int64_t scene_i0,
                          uint32_t side)
{
    const uint32_t step = (side / FT_REF_WINDOW_STEP_DIV > 0u) ? side / FT_REF_WINDOW_STEP_DIV
                                                               : 1u;
    const double li = (double)scene_i0 + (eye_m - origin_world_m) / cell_m;
    /* far past any lattice: keep the arithmetic in range (nothing is read
     * there but the floor) */
    const double lim = 4.0e15;
    const double c = fmin(fmax(round(li / (double)step) * (double)step, -lim), lim);
    return (int64_t)c - (int64_t)((side - 1u) / 2u);
}

ft_status ft_ref_window_follow(ft_ref_window *w, const double eye_m[3], int *moved,
                               ft_error *err)
{
    *moved = 0;
    const ft_terrain *s = w->scene;
    if (s == NULL || !isfinite(eye_m[0]) || !isfinite(eye_m[1])) {
        return ft_fail(err, FT_ERR_ARG, "reference window: not initialised or a non-finite eye");
    }
    const uint32_t side = w->t.width;
    const int64_t i0 = corner_for(eye_m[0], s->origin_world_x_m, s->cell_x_m, s->db_i0, side);
    const int64_t j0 = corner_for(eye_m[1], s->origin_world_y_m, s->cell_y_m, s->db_j0, side);
    if (w->loaded && i0 == w->i0 && j0 == w->j0) {
        return FT_OK;
    }
    const size_t n = (size_t)side * side;
    memset(w->t.void_bits, 0, (n + 7u) / 8u);
    memset(&w->counts, 0, sizeof w->counts);
    const ft_dbw_rect r = {s->db_level, i0, j0, side, side, w->t.heights_m, w->t.void_bits,
                           NULL};
    uint64_t remaining = 0u;
    w->loaded = 0; /* a failed read leaves no half-moved window behind */
    ft_status st = ft_dbw_read_rect(s->db, &r, &w->tiles, w->coarse_m, w->coarse_bytes,
                                    &w->counts, &remaining, err);
    if (st != FT_OK) {
        return st;
    }
    w->counts.missing_samples += ft_dbw_floor_missing(w->t.heights_m, n, s->db_fill_m,
                                                      w->t.void_bits);
    w->t.db_i0 = i0;
    w->t.db_j0 = j0;
    w->t.origin_world_x_m = s->origin_world_x_m + (double)(i0 - s->db_i0) * s->cell_x_m;
    w->t.origin_world_y_m = s->origin_world_y_m + (double)(j0 - s->db_j0) * s->cell_y_m;
    w->t.origin_x = s->origin_x + (double)(i0 - s->db_i0) * s->spacing_x;
    w->t.origin_y = s->origin_y + (double)(j0 - s->db_j0) * s->spacing_y;
    ft_pyramid_build(&w->t);
    ++w->loads;
    w->i0 = i0;
    w->j0 = j0;
    w->loaded = 1;
    *moved = 1;
    return FT_OK;
}
