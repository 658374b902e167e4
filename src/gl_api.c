#include "gl_api.h"

#include <stdio.h>
#include <string.h>

static ft_status load_one(ft_gl_get_proc_fn get_proc, const char *name, ft_gl_proc *out,
                          ft_error *err)
{
    *out = get_proc(name);
    if (*out == NULL) {
        return ft_fail(err, FT_ERR_UNSUPPORTED, "GL entry point %s is missing in this context",
                       name);
    }
    return FT_OK;
}

/* Function pointers of different types are converted through ft_gl_proc,
 * which C11 allows (6.3.2.3p8) as long as the call uses the right type. */
#define FT_GL_LOAD(type, name)                                             \
    {                                                                      \
        ft_gl_proc p_;                                                     \
        ft_status s_ = load_one(get_proc, "gl" #name, &p_, err);           \
        if (s_ != FT_OK) {                                                 \
            return s_;                                                     \
        }                                                                  \
        gl->name = (type)p_;                                               \
    }

int ft_gl_has_extension(const ft_gl *gl, const char *name)
{
    size_t n = strlen(name);
    if (gl->api == FT_GL_API_ES3 && gl->GetStringi != NULL) {
        GLint count = 0;
        gl->GetIntegerv(GL_NUM_EXTENSIONS, &count);
        for (GLint i = 0; i < count && i < 4096; ++i) {
            const char *e = (const char *)gl->GetStringi(GL_EXTENSIONS, (GLuint)i);
            if (e != NULL && strcmp(e, name) == 0) {
                return 1;
            }
        }
        return 0;
    }
    const char *all = (const char *)gl->GetString(GL_EXTENSIONS);
    if (all == NULL) {
        return 0;
    }
    /* Whole-word match in the space-separated list. */
    for (const char *p = strstr(all, name); p != NULL; p = strstr(p + 1, name)) {
        int starts = (p == all) || (p[-1] == ' ');
        int ends = (p[n] == ' ') || (p[n] == '\0');
        if (starts && ends) {
            return 1;
        }
    }
    return 0;
}

ft_status ft_gl_load(ft_gl *gl, ft_gl_api api, int desktop_core, ft_gl_get_proc_fn get_proc,
                     ft_error *err)
{
    memset(gl, 0, sizeof *gl);
    gl->api = api;
    FT_GL_ES2_FUNCS(FT_GL_LOAD)
    if (api == FT_GL_API_ES3) {
        FT_GL_ES3_FUNCS(FT_GL_LOAD)
    }

    ft_gl_caps *c = &gl->caps;
    c->desktop_core = desktop_core;
    gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &c->max_texture_size);
    gl->GetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &c->max_vertex_texture_units);
    if (api == FT_GL_API_ES3) {
        c->has_vao = 1;
        c->has_float_textures = 1; /* R32F with texelFetch is core ES 3.0 */
        c->has_depth24 = 1;
        /* OSMesa's desktop core profile renders to float natively. */
        c->has_float_color_buffer =
            desktop_core || ft_gl_has_extension(gl, "GL_EXT_color_buffer_float");
    } else {
        c->has_vao = 0;
        c->has_float_textures = ft_gl_has_extension(gl, "GL_OES_texture_float");
        c->has_depth24 = ft_gl_has_extension(gl, "GL_OES_depth24");
        c->has_float_color_buffer = 0; /* ES2: no position target; metric unavailable */
    }
    /* Timer queries are optional: load them as a set or not at all. */
    const int core = desktop_core != 0;
    if (core || ft_gl_has_extension(gl, "GL_EXT_disjoint_timer_query")) {
        const char *sfx = core ? "" : "EXT";
        char name[64];
        ft_gl_proc p[6];
        static const char *const base[6] = {"glGenQueries", "glDeleteQueries", "glBeginQuery",
                                            "glEndQuery", "glGetQueryObjectuiv",
                                            "glGetQueryObjectui64v"};
        int all = 1;
        for (int i = 0; i < 6; ++i) {
            (void)snprintf(name, sizeof name, "%s%s", base[i], sfx);
            p[i] = get_proc(name);
            all &= p[i] != NULL;
        }
        if (all) {
            gl->GenQueries = (ft_pfn_gen_queries)p[0];
            gl->DeleteQueries = (ft_pfn_delete_queries)p[1];
            gl->BeginQuery = (ft_pfn_begin_query)p[2];
            gl->EndQuery = (ft_pfn_end_query)p[3];
            gl->GetQueryObjectuiv = (ft_pfn_get_query_object_uiv)p[4];
            gl->GetQueryObjectui64v = (ft_pfn_get_query_object_ui64v)p[5];
            c->has_timer_query = 1;
        }
    }
    return ft_gl_check(gl, "ft_gl_load", err);
}

ft_status ft_gl_check(const ft_gl *gl, const char *where, ft_error *err)
{
    GLenum first = gl->GetError();
    if (first == GL_NO_ERROR) {
        return FT_OK;
    }
    for (int i = 0; i < 16 && gl->GetError() != GL_NO_ERROR; ++i) {
        /* drain: GL keeps one flag per error kind */
    }
    return ft_fail(err, FT_ERR_GPU, "GL error 0x%04x in %s", (unsigned)first, where);
}
