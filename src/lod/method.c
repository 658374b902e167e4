#include "lod/method.h"

#include <stdio.h>
#include <string.h>

/* One entry per FT_METHOD_LIST name; a method the build leaves out
 * (FIXTERRAIN_WITH_METHOD_*) has none, and a scene naming it fails at init. */
#if FT_WITH_METHOD_BRUTE
#define FT_OPS_BRUTE (&ft_brute_ops)
#else
#define FT_OPS_BRUTE NULL
#endif
#if FT_WITH_METHOD_BINTREE
#define FT_OPS_BINTREE (&ft_bintree_ops)
#else
#define FT_OPS_BINTREE NULL
#endif
#if FT_WITH_METHOD_PGM
#define FT_OPS_PGM (&ft_pgm_ops)
#else
#define FT_OPS_PGM NULL
#endif
#if FT_WITH_METHOD_PGRID
#define FT_OPS_PGRID (&ft_pgrid_ops)
#else
#define FT_OPS_PGRID NULL
#endif
#if FT_WITH_METHOD_CLIPMAP
#define FT_OPS_CLIPMAP (&ft_clipmap_ops)
#else
#define FT_OPS_CLIPMAP NULL
#endif
static const ft_method_ops *const k_ops[FT_METHOD_COUNT] = {
    [FT_METHOD_BRUTE] = FT_OPS_BRUTE,
    [FT_METHOD_BINTREE] = FT_OPS_BINTREE,
    [FT_METHOD_PGM] = FT_OPS_PGM,
    [FT_METHOD_PGRID] = FT_OPS_PGRID,
    [FT_METHOD_CLIPMAP] = FT_OPS_CLIPMAP,
};

const ft_method_ops *ft_method_ops_of(ft_method_kind kind)
{
    return ((unsigned)kind < FT_METHOD_COUNT) ? k_ops[kind] : NULL;
}

const char *ft_method_vertex_shader(const ft_scene *s)
{
    const ft_method_ops *o = ft_method_ops_of(s->method);
    if (o == NULL) {
        return "terrain.vert.glsl";
    }
    return (o->vertex_shader_of != NULL) ? o->vertex_shader_of(s) : o->vertex_shader;
}

const char *ft_method_vertex_defines(const ft_scene *s, int es3)
{
    const ft_method_ops *o = ft_method_ops_of(s->method);
    return (o != NULL && o->vertex_defines != NULL) ? o->vertex_defines(s, es3) : "";
}

const char *ft_method_vertex_defines_coarse(const ft_scene *s, int es3)
{
    const ft_method_ops *o = ft_method_ops_of(s->method);
    return (o != NULL && o->vertex_defines_coarse != NULL) ? o->vertex_defines_coarse(s, es3)
                                                           : NULL;
}

const char *ft_method_colour_defines(const ft_scene *s, int es3)
{
    const ft_method_ops *o = ft_method_ops_of(s->method);
    return (o != NULL && o->colour_defines != NULL) ? o->colour_defines(s, es3) : "";
}

int ft_method_reads_cache(const ft_scene *s)
{
    return s->method == FT_METHOD_CLIPMAP ||
           (s->method == FT_METHOD_PGM && s->pgm_heights_clipmap) ||
           (s->method == FT_METHOD_PGRID && s->pgrid_heights_clipmap) ||
           (s->method == FT_METHOD_BINTREE && s->bintree_heights_clipmap);
}

const ft_clip_cache *ft_method_cache(const ft_method *m)
{
    if (m->kind == FT_METHOD_CLIPMAP) {
        return &m->u.clipmap.cl.cache;
    }
    if (m->kind == FT_METHOD_PGM && m->u.pgm.clip) {
        return &m->u.pgm.cl.cache;
    }
    if (m->kind == FT_METHOD_PGRID && m->u.pgrid.pgm.clip) {
        return &m->u.pgrid.pgm.cl.cache;
    }
    if (m->kind == FT_METHOD_BINTREE && m->u.bintree.clip) {
        return &m->u.bintree.cl.cache;
    }
    return NULL;
}

void ft_method_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    const ft_method_ops *o = ft_method_ops_of(s->method);
    if (o != NULL) {
        o->plan(s, t, a);
    }
}

ft_status ft_method_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                         ft_arena *a, ft_error *err)
{
    m->kind = s->method;
    const ft_method_ops *o = ft_method_ops_of(s->method);
    if (o == NULL) {
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "method '%s' was left out of this build (FIXTERRAIN_WITH_METHOD_* options)",
                       ft_method_name(s->method));
    }
    return o->init(m, gl, s, t, a, err);
}

void ft_method_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                    const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    memset(st, 0, sizeof *st);
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o != NULL) {
        o->draw(m, gl, p, t, cam, st);
    }
}

int ft_method_set_lod_scale(ft_method *m, double scale)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o == NULL || o->set_lod_scale == NULL) {
        return 0;
    }
    o->set_lod_scale(m, scale);
    return 1;
}

int ft_method_fit_depth(const ft_method *m, const ft_terrain *t, ft_camera *cam,
                        double corner_cos)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    return o != NULL && o->fit_depth != NULL && o->fit_depth(m, t, cam, corner_cos);
}

void ft_method_spare(ft_method *m, uint64_t (*now)(void), uint64_t deadline_ns)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o != NULL && o->spare != NULL) {
        o->spare(m, now, deadline_ns);
    }
}

void ft_method_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o != NULL && o->select != NULL) {
        o->select(m, t, cam);
    }
}

uint64_t ft_method_gpu_bytes(const ft_method *m)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    return (o != NULL) ? o->gpu_bytes(m) : 0u;
}

void ft_method_worst_case(const ft_method *m, const ft_terrain *t, ft_method_worst *w)
{
    memset(w, 0, sizeof *w);
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o != NULL) {
        o->worst(m, t, w);
    } else {
        (void)snprintf(w->rule, sizeof w->rule, "method left out of this build");
    }
}

void ft_method_shutdown(ft_method *m, const ft_gl *gl)
{
    const ft_method_ops *o = ft_method_ops_of(m->kind);
    if (o != NULL) {
        o->shutdown(m, gl);
    }
}
