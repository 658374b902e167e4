#include "method.h"

const char *ft_method_vertex_shader(ft_method_kind m)
{
    switch (m) {
    default:
        return "terrain.vert.glsl";
    }
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
    st->triangles = 0;
    st->draw_calls = 0;
    switch (m->kind) {
    case FT_METHOD_BRUTE:
#if FT_WITH_METHOD_BRUTE
        ft_brute_draw(&m->u.brute, gl, p, t, cam, st);
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

uint64_t ft_method_gpu_bytes(const ft_method *m)
{
    switch (m->kind) {
    case FT_METHOD_BRUTE:
        return m->u.brute.gpu_bytes;
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
    default:
        break;
    }
    (void)gl;
}
