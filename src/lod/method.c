#include "lod/method.h"

#include <string.h>

const char *ft_method_vertex_shader(ft_method_kind m)
{
    switch (m) {
    case FT_METHOD_BINTREE:
        return "bintree.vert.glsl";
    case FT_METHOD_PGM:
        return "pgm.vert.glsl";
    case FT_METHOD_PGRID:
        return "pgrid.vert.glsl";
    default:
        return "terrain.vert.glsl";
    }
}

const char *ft_method_vertex_defines(const ft_scene *s, int es3)
{
    if (s->method != FT_METHOD_BINTREE) {
        return "";
    }
    const int sub = s->bintree_subsample_levels > 0u;
    const int vtx = es3 && s->bintree_vertex_table;
    static const char *const k_bintree[2][2] = {
        {"#define FT_BT_SUB 0\n#define FT_BT_VTX 0\n", "#define FT_BT_SUB 0\n#define FT_BT_VTX 1\n"},
        {"#define FT_BT_SUB 1\n#define FT_BT_VTX 0\n", "#define FT_BT_SUB 1\n#define FT_BT_VTX 1\n"},
    };
    return k_bintree[sub][vtx];
}

const char *ft_method_vertex_defines_coarse(const ft_scene *s, int es3)
{
    if (s->method != FT_METHOD_BINTREE || s->bintree_subsample_levels == 0u || !es3 ||
        !s->bintree_vertex_table) {
        return NULL;
    }
    return "#define FT_BT_SUB 0\n#define FT_BT_VTX 1\n";
}

void ft_method_plan(const ft_scene *s, const ft_terrain *t, ft_arena *a)
{
    (void)t;
    switch (s->method) {
    case FT_METHOD_BRUTE:
#if FT_WITH_METHOD_BRUTE
        ft_brute_plan(s, a);
#endif
        break;
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        ft_bintree_method_plan(s, t, a);
#endif
        break;
    case FT_METHOD_PGM:
#if FT_WITH_METHOD_PGM
        ft_pgm_method_plan(s, t, a);
#endif
        break;
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        ft_pgrid_method_plan(s, t, a);
#endif
        break;
    default:
        break;
    }
    (void)a;
}

ft_status ft_method_init(ft_method *m, const ft_gl *gl, const ft_scene *s, const ft_terrain *t,
                         ft_arena *a, ft_error *err)
{
    m->kind = s->method;
    switch (s->method) {
    case FT_METHOD_BRUTE:
#if FT_WITH_METHOD_BRUTE
        return ft_brute_init(&m->u.brute, gl, s, t, a, err);
#else
        break;
#endif
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        return ft_bintree_method_init(&m->u.bintree, gl, s, t, a, err);
#else
        break;
#endif
    case FT_METHOD_PGM:
#if FT_WITH_METHOD_PGM
        return ft_pgm_method_init(&m->u.pgm, gl, s, t, a, err);
#else
        break;
#endif
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        return ft_pgrid_method_init(&m->u.pgrid, gl, s, t, a, err);
#else
        break;
#endif
    default:
        break;
    }
    (void)gl;
    (void)t;
    (void)a;
    return ft_fail(err, FT_ERR_UNSUPPORTED,
                   "method '%s' was left out of this build (FIXTERRAIN_WITH_METHOD_* options)",
                   ft_method_name(s->method));
}

void ft_method_draw(ft_method *m, const ft_gl *gl, const struct ft_terrain_program *p,
                    const ft_terrain *t, const ft_camera *cam, ft_method_draw_stats *st)
{
    memset(st, 0, sizeof *st);
    switch (m->kind) {
    case FT_METHOD_BRUTE:
#if FT_WITH_METHOD_BRUTE
        ft_brute_draw(&m->u.brute, gl, p, t, cam, st);
#endif
        break;
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        ft_bintree_method_draw(&m->u.bintree, gl, p, t, cam, st);
#endif
        break;
    case FT_METHOD_PGM:
#if FT_WITH_METHOD_PGM
        ft_pgm_method_draw(&m->u.pgm, gl, p, t, cam, st);
#endif
        break;
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        ft_pgrid_method_draw(&m->u.pgrid, gl, p, t, cam, st);
#endif
        break;
    default:
        break;
    }
    (void)gl;
    (void)p;
    (void)t;
    (void)cam;
}

int ft_method_set_lod_scale(ft_method *m, double scale)
{
    switch (m->kind) {
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        ft_bintree_method_set_lod_scale(&m->u.bintree, scale);
        return 1;
#else
        break;
#endif
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        ft_pgrid_method_set_lod_scale(&m->u.pgrid, scale);
        return 1;
#else
        break;
#endif
    default:
        break;
    }
    (void)scale;
    return 0;
}

void ft_method_select(ft_method *m, const ft_terrain *t, const ft_camera *cam)
{
    switch (m->kind) {
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        ft_bintree_method_select(&m->u.bintree, t, cam);
#endif
        break;
    case FT_METHOD_PGM:
#if FT_WITH_METHOD_PGM
        ft_pgm_method_select(&m->u.pgm, t, cam);
#endif
        break;
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        ft_pgrid_method_select(&m->u.pgrid, t, cam);
#endif
        break;
    default:
        break;
    }
    (void)t;
    (void)cam;
}

uint64_t ft_method_gpu_bytes(const ft_method *m)
{
    switch (m->kind) {
    case FT_METHOD_BRUTE:
        return m->u.brute.gpu_bytes;
    case FT_METHOD_BINTREE:
        return m->u.bintree.gpu_bytes;
    case FT_METHOD_PGM:
        return m->u.pgm.gpu_bytes;
    case FT_METHOD_PGRID:
        return m->u.pgrid.gpu_bytes + m->u.pgrid.pgm.gpu_bytes;
    default:
        return 0;
    }
}

void ft_method_shutdown(ft_method *m, const ft_gl *gl)
{
    switch (m->kind) {
    case FT_METHOD_BRUTE:
#if FT_WITH_METHOD_BRUTE
        ft_brute_shutdown(&m->u.brute, gl);
#endif
        break;
    case FT_METHOD_BINTREE:
#if FT_WITH_METHOD_BINTREE
        ft_bintree_method_shutdown(&m->u.bintree, gl);
#endif
        break;
    case FT_METHOD_PGM:
#if FT_WITH_METHOD_PGM
        ft_pgm_method_shutdown(&m->u.pgm, gl);
#endif
        break;
    case FT_METHOD_PGRID:
#if FT_WITH_METHOD_PGRID
        ft_pgrid_method_shutdown(&m->u.pgrid, gl);
#endif
        break;
    default:
        break;
    }
    (void)gl;
}
