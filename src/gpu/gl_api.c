#include "gpu/gl_api.h"

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

/* ---- call recording ------------------------------------------------------------- */

typedef const GLubyte *ft_gl_cstr;
typedef void *ft_gl_voidp;

/* Every entry point of the table but glReadPixels (wrapped by hand below: it
 * also counts bytes): V(name, params, args) returns nothing, R(ret, name,
 * params, args) returns ret. The installer names each wrapper from the
 * table's own lists, so an entry point added there without a line here does
 * not compile; a wrong signature is an incompatible-pointer error. */
#define FT_GL_TRACE_SIGS(V, R)                                                                     \
    V(ActiveTexture, (GLenum texture), (texture))                                                  \
    V(AttachShader, (GLuint program, GLuint shader), (program, shader))                            \
    V(BindAttribLocation, (GLuint program, GLuint index, const GLchar *name),                      \
      (program, index, name))                                                                      \
    V(BindBuffer, (GLenum target, GLuint buffer), (target, buffer))                                \
    V(BindFramebuffer, (GLenum target, GLuint framebuffer), (target, framebuffer))                 \
    V(BindRenderbuffer, (GLenum target, GLuint renderbuffer), (target, renderbuffer))              \
    V(BindTexture, (GLenum target, GLuint texture), (target, texture))                             \
    V(BlendEquation, (GLenum mode), (mode))                                                        \
    V(BufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage),                \
      (target, size, data, usage))                                                                 \
    V(BufferSubData, (GLenum target, GLintptr offset, GLsizeiptr size, const void *data),          \
      (target, offset, size, data))                                                                \
    R(GLenum, CheckFramebufferStatus, (GLenum target), (target))                                   \
    V(Clear, (GLbitfield mask), (mask))                                                            \
    V(ClearColor, (GLfloat red, GLfloat green, GLfloat blue, GLfloat alpha),                       \
      (red, green, blue, alpha))                                                                   \
    V(ClearDepthf, (GLfloat d), (d))                                                               \
    V(CompileShader, (GLuint shader), (shader))                                                    \
    R(GLuint, CreateProgram, (void), ())                                                           \
    R(GLuint, CreateShader, (GLenum type), (type))                                                 \
    V(CullFace, (GLenum mode), (mode))                                                             \
    V(DeleteBuffers, (GLsizei n, const GLuint *buffers), (n, buffers))                             \
    V(DeleteFramebuffers, (GLsizei n, const GLuint *framebuffers), (n, framebuffers))              \
    V(DeleteProgram, (GLuint program), (program))                                                  \
    V(DeleteRenderbuffers, (GLsizei n, const GLuint *renderbuffers), (n, renderbuffers))           \
    V(DeleteShader, (GLuint shader), (shader))                                                     \
    V(DeleteTextures, (GLsizei n, const GLuint *textures), (n, textures))                          \
    V(DisableVertexAttribArray, (GLuint index), (index))                                           \
    V(DepthFunc, (GLenum func), (func))                                                            \
    V(DepthMask, (GLboolean flag), (flag))                                                         \
    V(Disable, (GLenum cap), (cap))                                                                \
    V(DrawArrays, (GLenum mode, GLint first, GLsizei count), (mode, first, count))                 \
    V(DrawElements, (GLenum mode, GLsizei count, GLenum type, const void *indices),                \
      (mode, count, type, indices))                                                                \
    V(Enable, (GLenum cap), (cap))                                                                 \
    V(EnableVertexAttribArray, (GLuint index), (index))                                            \
    V(Finish, (void), ())                                                                          \
    V(FramebufferRenderbuffer,                                                                     \
      (GLenum target, GLenum attachment, GLenum renderbuffertarget, GLuint renderbuffer),          \
      (target, attachment, renderbuffertarget, renderbuffer))                                      \
    V(FramebufferTexture2D,                                                                        \
      (GLenum target, GLenum attachment, GLenum textarget, GLuint texture, GLint level),           \
      (target, attachment, textarget, texture, level))                                             \
    V(GenBuffers, (GLsizei n, GLuint *buffers), (n, buffers))                                      \
    V(GenFramebuffers, (GLsizei n, GLuint *framebuffers), (n, framebuffers))                       \
    V(GenRenderbuffers, (GLsizei n, GLuint *renderbuffers), (n, renderbuffers))                    \
    V(GenTextures, (GLsizei n, GLuint *textures), (n, textures))                                   \
    R(GLenum, GetError, (void), ())                                                                \
    V(GetIntegerv, (GLenum pname, GLint *data), (pname, data))                                     \
    V(GetProgramInfoLog, (GLuint program, GLsizei bufSize, GLsizei *length, GLchar *infoLog),      \
      (program, bufSize, length, infoLog))                                                         \
    V(GetProgramiv, (GLuint program, GLenum pname, GLint *params), (program, pname, params))       \
    V(GetShaderInfoLog, (GLuint shader, GLsizei bufSize, GLsizei *length, GLchar *infoLog),        \
      (shader, bufSize, length, infoLog))                                                          \
    V(GetShaderiv, (GLuint shader, GLenum pname, GLint *params), (shader, pname, params))          \
    R(ft_gl_cstr, GetString, (GLenum name), (name))                                                \
    R(GLint, GetUniformLocation, (GLuint program, const GLchar *name), (program, name))            \
    V(LinkProgram, (GLuint program), (program))                                                    \
    V(PixelStorei, (GLenum pname, GLint param), (pname, param))                                    \
    V(RenderbufferStorage,                                                                         \
      (GLenum target, GLenum internalformat, GLsizei width, GLsizei height),                       \
      (target, internalformat, width, height))                                                     \
    V(ShaderSource,                                                                                \
      (GLuint shader, GLsizei count, const GLchar *const *string, const GLint *length),            \
      (shader, count, string, length))                                                             \
    V(TexImage2D,                                                                                  \
      (GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height,            \
       GLint border, GLenum format, GLenum type, const void *pixels),                              \
      (target, level, internalformat, width, height, border, format, type, pixels))                \
    V(TexParameteri, (GLenum target, GLenum pname, GLint param), (target, pname, param))           \
    V(TexSubImage2D,                                                                               \
      (GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width, GLsizei height,    \
       GLenum format, GLenum type, const void *pixels),                                            \
      (target, level, xoffset, yoffset, width, height, format, type, pixels))                      \
    V(Uniform1f, (GLint location, GLfloat v0), (location, v0))                                     \
    V(Uniform1i, (GLint location, GLint v0), (location, v0))                                       \
    V(Uniform1fv, (GLint location, GLsizei count, const GLfloat *value), (location, count, value)) \
    V(Uniform3fv, (GLint location, GLsizei count, const GLfloat *value), (location, count, value)) \
    V(Uniform4fv, (GLint location, GLsizei count, const GLfloat *value), (location, count, value)) \
    V(Uniform2f, (GLint location, GLfloat v0, GLfloat v1), (location, v0, v1))                     \
    V(Uniform3f, (GLint location, GLfloat v0, GLfloat v1, GLfloat v2), (location, v0, v1, v2))     \
    V(Uniform4f, (GLint location, GLfloat v0, GLfloat v1, GLfloat v2, GLfloat v3),                 \
      (location, v0, v1, v2, v3))                                                                  \
    V(UniformMatrix4fv,                                                                            \
      (GLint location, GLsizei count, GLboolean transpose, const GLfloat *value),                  \
      (location, count, transpose, value))                                                         \
    V(UseProgram, (GLuint program), (program))                                                     \
    V(VertexAttribPointer,                                                                         \
      (GLuint index, GLint size, GLenum type, GLboolean normalized, GLsizei stride,                \
       const void *pointer),                                                                       \
      (index, size, type, normalized, stride, pointer))                                            \
    V(Viewport, (GLint x, GLint y, GLsizei width, GLsizei height), (x, y, width, height))          \
    V(BindVertexArray, (GLuint array), (array))                                                    \
    V(DrawElementsInstanced,                                                                       \
      (GLenum mode, GLsizei count, GLenum type, const void *indices, GLsizei instancecount),       \
      (mode, count, type, indices, instancecount))                                                 \
    V(VertexAttribDivisor, (GLuint index, GLuint divisor), (index, divisor))                       \
    V(DeleteVertexArrays, (GLsizei n, const GLuint *arrays), (n, arrays))                          \
    V(GenVertexArrays, (GLsizei n, GLuint *arrays), (n, arrays))                                   \
    R(ft_gl_cstr, GetStringi, (GLenum name, GLuint index), (name, index))                          \
    V(DrawArraysInstanced, (GLenum mode, GLint first, GLsizei count, GLsizei instancecount),       \
      (mode, first, count, instancecount))                                                         \
    V(TransformFeedbackVaryings,                                                                   \
      (GLuint program, GLsizei count, const GLchar *const *varyings, GLenum bufferMode),           \
      (program, count, varyings, bufferMode))                                                      \
    V(BeginTransformFeedback, (GLenum primitiveMode), (primitiveMode))                             \
    V(EndTransformFeedback, (void), ())                                                            \
    V(BindBufferBase, (GLenum target, GLuint index, GLuint buffer), (target, index, buffer))       \
    V(BindBufferRange,                                                                             \
      (GLenum target, GLuint index, GLuint buffer, GLintptr offset, GLsizeiptr size),              \
      (target, index, buffer, offset, size))                                                       \
    V(DrawBuffers, (GLsizei n, const GLenum *bufs), (n, bufs))                                     \
    R(ft_gl_voidp, MapBufferRange,                                                                 \
      (GLenum target, GLintptr offset, GLsizeiptr length, GLbitfield access),                      \
      (target, offset, length, access))                                                            \
    R(GLboolean, UnmapBuffer, (GLenum target), (target))                                           \
    V(GenQueries, (GLsizei n, GLuint *ids), (n, ids))                                              \
    V(DeleteQueries, (GLsizei n, const GLuint *ids), (n, ids))                                     \
    V(BeginQuery, (GLenum target, GLuint id), (target, id))                                        \
    V(EndQuery, (GLenum target), (target))                                                         \
    V(GetQueryObjectuiv, (GLuint id, GLenum pname, GLuint *params), (id, pname, params))           \
    V(GetQueryObjectui64v, (GLuint id, GLenum pname, uint64_t *params), (id, pname, params))

static const char *const k_entry_names[FT_GL_ENTRY_COUNT] = {
#define FT_GL_ENTRY_NAME(type, name) "gl" #name,
    FT_GL_ES2_FUNCS(FT_GL_ENTRY_NAME) FT_GL_ES3_FUNCS(FT_GL_ENTRY_NAME)
        FT_GL_OPT_FUNCS(FT_GL_ENTRY_NAME)
#undef FT_GL_ENTRY_NAME
};

const char *ft_gl_entry_name(ft_gl_entry e)
{
    return ((unsigned)e < (unsigned)FT_GL_ENTRY_COUNT) ? k_entry_names[e] : "gl?";
}

static ft_gl s_trace_real;     /* the loaded entry points while a trace runs */
static ft_gl_trace *s_trace;   /* NULL: no trace */

static void trace_call(ft_gl_entry e)
{
    ft_gl_trace *t = s_trace;
    if (t == NULL) {
        return;
    }
    ft_gl_trace_count *c = &t->count[e];
    if (c->calls == 0u) {
        c->first_frame = t->frame;
    }
    c->calls += 1u;
    c->last_frame = t->frame;
    t->calls_total += 1u;
}

#define FT_GL_TRACE_WRAP_V(name, params, args)      \
    static void GL_APIENTRY trace_##name params    \
    {                                               \
        trace_call(FT_GLE_##name);                  \
        s_trace_real.name args;                     \
    }
#define FT_GL_TRACE_WRAP_R(ret, name, params, args) \
    static ret GL_APIENTRY trace_##name params     \
    {                                               \
        trace_call(FT_GLE_##name);                  \
        return s_trace_real.name args;              \
    }
FT_GL_TRACE_SIGS(FT_GL_TRACE_WRAP_V, FT_GL_TRACE_WRAP_R)
#undef FT_GL_TRACE_WRAP_V
#undef FT_GL_TRACE_WRAP_R

/* Bytes glReadPixels writes for one pixel of format x type (0: unknown,
 * counted as 16, the largest the renderer reads). */
static uint64_t read_pixel_bytes(GLenum format, GLenum type)
{
    uint64_t comps = (format == GL_RGBA || format == GL_RGBA_INTEGER) ? 4u
                     : (format == GL_RGB) ? 3u
                     : (format == GL_RG) ? 2u
                     : (format == GL_RED || format == GL_ALPHA || format == GL_LUMINANCE) ? 1u
                                                                                            : 0u;
    uint64_t size = (type == GL_UNSIGNED_BYTE || type == GL_BYTE) ? 1u
                    : (type == GL_HALF_FLOAT || type == GL_UNSIGNED_SHORT) ? 2u
                    : (type == GL_FLOAT || type == GL_UNSIGNED_INT || type == GL_INT) ? 4u
                                                                                      : 0u;
    return (comps == 0u || size == 0u) ? 16u : comps * size;
}

static void GL_APIENTRY trace_ReadPixels(GLint x, GLint y, GLsizei width, GLsizei height,
                                         GLenum format, GLenum type, void *pixels)
{
    trace_call(FT_GLE_ReadPixels);
    if (s_trace != NULL && width > 0 && height > 0) {
        uint64_t bytes = (uint64_t)width * (uint64_t)height * read_pixel_bytes(format, type);
        s_trace->read_bytes_frame += bytes;
        s_trace->read_bytes_total += bytes;
    }
    s_trace_real.ReadPixels(x, y, width, height, format, type, pixels);
}

static void close_frame(ft_gl_trace *t)
{
    if (t->read_bytes_frame > t->read_bytes_max) {
        t->read_bytes_max = t->read_bytes_frame;
        t->read_bytes_max_frame = t->frame;
    }
    t->read_bytes_frame = 0u;
}

int ft_gl_trace_start(ft_gl *gl, ft_gl_trace *t)
{
    if (s_trace != NULL) {
        return 0;
    }
    memset(t, 0, sizeof *t);
    t->frame = FT_GL_TRACE_NO_FRAME;
    t->read_bytes_max_frame = FT_GL_TRACE_NO_FRAME;
    s_trace_real = *gl;
    s_trace = t;
#define FT_GL_TRACE_INSTALL(type, name) \
    if (gl->name != NULL) {             \
        gl->name = trace_##name;        \
    }
    FT_GL_ES2_FUNCS(FT_GL_TRACE_INSTALL)
    FT_GL_ES3_FUNCS(FT_GL_TRACE_INSTALL)
    FT_GL_OPT_FUNCS(FT_GL_TRACE_INSTALL)
#undef FT_GL_TRACE_INSTALL
    return 1;
}

void ft_gl_trace_frame(ft_gl_trace *t, uint32_t frame)
{
    if (t->frame != FT_GL_TRACE_NO_FRAME || t->read_bytes_frame != 0u) {
        close_frame(t);
    }
    t->frame = frame;
    t->frames += 1u;
}

void ft_gl_trace_stop(ft_gl *gl, ft_gl_trace *t)
{
    if (s_trace != t) {
        return;
    }
    close_frame(t);
#define FT_GL_TRACE_RESTORE(type, name) gl->name = s_trace_real.name;
    FT_GL_ES2_FUNCS(FT_GL_TRACE_RESTORE)
    FT_GL_ES3_FUNCS(FT_GL_TRACE_RESTORE)
    FT_GL_OPT_FUNCS(FT_GL_TRACE_RESTORE)
#undef FT_GL_TRACE_RESTORE
    s_trace = NULL;
}
