/* gl_api.h - the GL subset the renderer uses, as one table of entry points.
 *
 * GL is never linked: platform/ loads every entry point at init through the
 * backend's GetProcAddress (libOSMesa exports gl* too, so linking libGLESv2
 * next to it would silently route calls to the wrong library). The lists
 * below ARE the documented GL subset: GLES 2.0 core, plus the GLES 3.0 entry
 * points used only when the context is GLES 3 (or OSMesa's desktop core). */
#ifndef FT_GL_API_H
#define FT_GL_API_H

#define GL_GLES_PROTOTYPES 0
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>
#include <stdint.h>

#include "core/ft_status.h"

/* X(type, Name): called as gl->Name(...), loaded from "gl" #Name. */
#define FT_GL_ES2_FUNCS(X)                                         \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                       \
    X(PFNGLATTACHSHADERPROC, AttachShader)                         \
    X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)             \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                             \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                   \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                           \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)                       \
    X(PFNGLBUFFERDATAPROC, BufferData)                             \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                       \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)     \
    X(PFNGLCLEARPROC, Clear)                                       \
    X(PFNGLCLEARCOLORPROC, ClearColor)                             \
    X(PFNGLCLEARDEPTHFPROC, ClearDepthf)                           \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                       \
    X(PFNGLCREATESHADERPROC, CreateShader)                         \
    X(PFNGLCULLFACEPROC, CullFace)                                 \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                       \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)             \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                       \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)           \
    X(PFNGLDELETESHADERPROC, DeleteShader)                         \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                     \
    X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, DisableVertexAttribArray) \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                               \
    X(PFNGLDEPTHMASKPROC, DepthMask)                               \
    X(PFNGLDISABLEPROC, Disable)                                   \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                             \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                         \
    X(PFNGLENABLEPROC, Enable)                                     \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)   \
    X(PFNGLFINISHPROC, Finish)                                     \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)   \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)         \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                             \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                   \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                 \
    X(PFNGLGENTEXTURESPROC, GenTextures)                           \
    X(PFNGLGETERRORPROC, GetError)                                 \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                           \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)               \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                         \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                 \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                           \
    X(PFNGLGETSTRINGPROC, GetString)                               \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)             \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                           \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                           \
    X(PFNGLREADPIXELSPROC, ReadPixels)                             \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)           \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                         \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                             \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                       \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                       \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                               \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                               \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv)                             \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                             \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                             \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                               \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                               \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                               \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                 \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                             \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)           \
    X(PFNGLVIEWPORTPROC, Viewport)

#define FT_GL_ES3_FUNCS(X)                                   \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)             \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced) \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)     \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)       \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)             \
    X(PFNGLGETSTRINGIPROC, GetStringi)                       \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)     \
    X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, TransformFeedbackVaryings) \
    X(PFNGLBEGINTRANSFORMFEEDBACKPROC, BeginTransformFeedback) \
    X(PFNGLENDTRANSFORMFEEDBACKPROC, EndTransformFeedback)   \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)               \
    X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)             \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                     \
    X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)               \
    X(PFNGLUNMAPBUFFERPROC, UnmapBuffer)

typedef enum ft_gl_api {
    FT_GL_API_ES2 = 2, /* GLSL ES 1.00 shaders, GLES 2.0 calls only */
    FT_GL_API_ES3 = 3  /* GLSL ES 3.00 shaders, GLES 3.0 calls */
} ft_gl_api;

typedef struct ft_gl_caps {
    int max_texture_size;
    int max_vertex_texture_units;
    int has_float_textures;      /* sampleable float textures in the vertex stage */
    int has_float_color_buffer;  /* RGBA32F render targets (position pass) */
    int has_vao;                 /* BindVertexArray is usable (ES3/core) */
    int has_depth24;
    int desktop_core;            /* OSMesa core profile: a VAO must be bound */
    int has_timer_query;         /* GPU time per frame (see the timer entry points) */
} ft_gl_caps;

/* GPU timer queries: GL_EXT_disjoint_timer_query on GLES (2 or 3), core
 * glBeginQuery(GL_TIME_ELAPSED) on OSMesa's desktop profile. Optional: all
 * NULL (caps.has_timer_query = 0) where the context has neither. */
#ifndef GL_TIME_ELAPSED_EXT
#define GL_TIME_ELAPSED_EXT 0x88BF
#endif
#ifndef GL_QUERY_RESULT_EXT
#define GL_QUERY_RESULT_EXT 0x8866
#endif
#ifndef GL_QUERY_RESULT_AVAILABLE_EXT
#define GL_QUERY_RESULT_AVAILABLE_EXT 0x8867
#endif
#ifndef GL_GPU_DISJOINT_EXT
#define GL_GPU_DISJOINT_EXT 0x8FBB
#endif
typedef void (*ft_pfn_gen_queries)(GLsizei n, GLuint *ids);
typedef void (*ft_pfn_delete_queries)(GLsizei n, const GLuint *ids);
typedef void (*ft_pfn_begin_query)(GLenum target, GLuint id);
typedef void (*ft_pfn_end_query)(GLenum target);
typedef void (*ft_pfn_get_query_object_uiv)(GLuint id, GLenum pname, GLuint *params);
typedef void (*ft_pfn_get_query_object_ui64v)(GLuint id, GLenum pname, uint64_t *params);

typedef void (*ft_gl_proc)(void);
typedef ft_gl_proc (*ft_gl_get_proc_fn)(const char *name);

/* The optional timer-query entry points, as a list like the two above (the
 * recording layer below wraps them too). */
#define FT_GL_OPT_FUNCS(X)                                   \
    X(ft_pfn_gen_queries, GenQueries)                        \
    X(ft_pfn_delete_queries, DeleteQueries)                  \
    X(ft_pfn_begin_query, BeginQuery)                        \
    X(ft_pfn_end_query, EndQuery)                            \
    X(ft_pfn_get_query_object_uiv, GetQueryObjectuiv)        \
    X(ft_pfn_get_query_object_ui64v, GetQueryObjectui64v)

typedef struct ft_gl {
#define FT_GL_MEMBER(type, name) type name;
    FT_GL_ES2_FUNCS(FT_GL_MEMBER)
    FT_GL_ES3_FUNCS(FT_GL_MEMBER)
#undef FT_GL_MEMBER
    ft_gl_api api;
    ft_gl_caps caps;
    /* optional: GPU timer queries (all NULL when caps.has_timer_query = 0) */
#define FT_GL_MEMBER(type, name) type name;
    FT_GL_OPT_FUNCS(FT_GL_MEMBER)
#undef FT_GL_MEMBER
} ft_gl;

/* Loads the table for `api` (ES3 entry points only when api is ES3) and
 * queries the caps. Fails naming the first missing entry point. The context
 * must be current. desktop_core: set for OSMesa's core profile. */
ft_status ft_gl_load(ft_gl *gl, ft_gl_api api, int desktop_core, ft_gl_get_proc_fn get_proc,
                     ft_error *err);

int ft_gl_has_extension(const ft_gl *gl, const char *name);

/* Drains glGetError; returns FT_ERR_GPU naming `where` and the first code. */
ft_status ft_gl_check(const ft_gl *gl, const char *where, ft_error *err);

/* ---- call recording (tests: the safety-critical subset after init) ----------
 *
 * ft_gl_trace_start swaps every loaded entry point of the table for a wrapper
 * that counts the call (per entry point: calls, first and last frame) and
 * forwards it; ft_gl_trace_stop puts the loaded pointers back. Nothing is
 * wrapped unless a test starts a trace, so the runtime pays nothing; the
 * trace is caller storage (no heap). One trace at a time per process (the
 * wrappers forward through one saved copy of the table); GL is used from one
 * thread. glReadPixels is also measured: bytes per frame (format x type x
 * width x height), the largest frame and which frame it was. */
typedef enum ft_gl_entry {
#define FT_GL_ENTRY_ENUM(type, name) FT_GLE_##name,
    FT_GL_ES2_FUNCS(FT_GL_ENTRY_ENUM)
    FT_GL_ES3_FUNCS(FT_GL_ENTRY_ENUM)
    FT_GL_OPT_FUNCS(FT_GL_ENTRY_ENUM)
#undef FT_GL_ENTRY_ENUM
    FT_GL_ENTRY_COUNT
} ft_gl_entry;

#define FT_GL_TRACE_NO_FRAME UINT32_MAX

typedef struct ft_gl_trace_count {
    uint64_t calls;
    uint32_t first_frame, last_frame; /* FT_GL_TRACE_NO_FRAME: before the first frame mark */
} ft_gl_trace_count;

typedef struct ft_gl_trace {
    uint32_t frame;  /* the frame calls are charged to (ft_gl_trace_frame) */
    uint32_t frames; /* frame marks seen */
    ft_gl_trace_count count[FT_GL_ENTRY_COUNT];
    uint64_t read_bytes_frame;     /* glReadPixels bytes in the current frame */
    uint64_t read_bytes_max;       /* largest frame so far (closed frames) */
    uint32_t read_bytes_max_frame;
    uint64_t read_bytes_total;
    uint64_t calls_total;
} ft_gl_trace;

/* "gl" + the entry point's name, e.g. "glBufferData". */
const char *ft_gl_entry_name(ft_gl_entry e);
/* Clears t and starts recording the table's calls into it (calls before the
 * first ft_gl_trace_frame are charged to FT_GL_TRACE_NO_FRAME). Returns 0
 * when another trace is active. */
int ft_gl_trace_start(ft_gl *gl, ft_gl_trace *t);
/* Closes the current frame's readback count and charges what follows to
 * frame. */
void ft_gl_trace_frame(ft_gl_trace *t, uint32_t frame);
/* Closes the last frame and restores the table's loaded entry points. */
void ft_gl_trace_stop(ft_gl *gl, ft_gl_trace *t);

#endif
