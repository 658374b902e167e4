/* gpu_osmesa.c - OSMesa offscreen context (optional backend: Mesa >= 25.1
 * removed OSMesa).
 *
 * <GL/osmesa.h> pulls in <GL/gl.h>, which clashes with the GLES 3 headers
 * the GL table uses, so the few OSMesa declarations are repeated here (values
 * from Mesa 22.3's osmesa.h). A core-profile 3.3+ context reports 4.5 core and
 * accepts "#version 300 es" shaders unchanged (ARB_ES3_compatibility); core
 * profile needs a bound VAO and sized formats (handled via caps.desktop_core). */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>

#include "gpu_backends.h"
#include "gpu/gpu.h"

typedef struct osmesa_context *OSMesaContext;
typedef void (*OSMESAproc)(void);
extern OSMesaContext OSMesaCreateContextAttribs(const int *attribList, OSMesaContext sharelist);
extern GLboolean OSMesaMakeCurrent(OSMesaContext ctx, void *buffer, GLenum type, GLsizei width,
                                   GLsizei height);
extern void OSMesaDestroyContext(OSMesaContext ctx);
extern OSMESAproc OSMesaGetProcAddress(const char *funcName);

#define FT_OSMESA_FORMAT 0x22
#define FT_OSMESA_DEPTH_BITS 0x30
#define FT_OSMESA_STENCIL_BITS 0x31
#define FT_OSMESA_ACCUM_BITS 0x32
#define FT_OSMESA_PROFILE 0x33
#define FT_OSMESA_CORE_PROFILE 0x34
#define FT_OSMESA_CONTEXT_MAJOR_VERSION 0x36
#define FT_OSMESA_CONTEXT_MINOR_VERSION 0x37

/* MakeCurrent needs a colour buffer; we never draw to it (FBOs only), so a
 * small static one will do. */
#define FT_OSMESA_DUMMY_SIDE 16
static uint32_t g_osmesa_dummy[FT_OSMESA_DUMMY_SIDE * FT_OSMESA_DUMMY_SIDE];
static OSMesaContext g_osmesa;

static ft_gl_proc osmesa_get_proc(const char *name)
{
    return (ft_gl_proc)OSMesaGetProcAddress(name);
}

ft_status ft_plat_osmesa_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err)
{
    static const int attribs[] = {FT_OSMESA_FORMAT, GL_RGBA,
                                  FT_OSMESA_DEPTH_BITS, 24,
                                  FT_OSMESA_STENCIL_BITS, 0,
                                  FT_OSMESA_ACCUM_BITS, 0,
                                  FT_OSMESA_PROFILE, FT_OSMESA_CORE_PROFILE,
                                  FT_OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                  FT_OSMESA_CONTEXT_MINOR_VERSION, 3,
                                  0};
    ft_status s;
    g_osmesa = OSMesaCreateContextAttribs(attribs, NULL);
    if (g_osmesa == NULL) {
        return ft_fail(err, FT_ERR_GPU, "OSMesa: core profile 3.3 context creation failed");
    }
    if (!OSMesaMakeCurrent(g_osmesa, g_osmesa_dummy, GL_UNSIGNED_BYTE, FT_OSMESA_DUMMY_SIDE,
                           FT_OSMESA_DUMMY_SIDE)) {
        s = ft_fail(err, FT_ERR_GPU, "OSMesa: OSMesaMakeCurrent failed");
        goto fail_context;
    }
    s = ft_gl_load(&ctx->gl, FT_GL_API_ES3, 1, osmesa_get_proc, err);
    if (s != FT_OK) {
        goto fail_context;
    }
    const char *version = (const char *)ctx->gl.GetString(GL_VERSION);
    const char *renderer = (const char *)ctx->gl.GetString(GL_RENDERER);
    (void)snprintf(ctx->version, sizeof ctx->version, "%s", version ? version : "?");
    (void)snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "?");
    ctx->backend = backend;
    ctx->open = 1;
    return FT_OK;

fail_context:
    OSMesaDestroyContext(g_osmesa);
    g_osmesa = NULL;
    return s;
}

void ft_plat_osmesa_close(ft_gpu_context *ctx)
{
    if (g_osmesa != NULL) {
        OSMesaDestroyContext(g_osmesa);
        g_osmesa = NULL;
    }
    ctx->open = 0;
}
