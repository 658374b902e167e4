/* gpu_select.c - one dispatch point from ft_backend to the backend that
 * this build contains. */
#include "gpu.h"

ft_status ft_plat_egl_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err);
void ft_plat_egl_close(ft_gpu_context *ctx);
ft_status ft_plat_osmesa_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err);
void ft_plat_osmesa_close(ft_gpu_context *ctx);

ft_status ft_plat_gpu_open(ft_backend backend, ft_gpu_context *ctx, ft_error *err)
{
    ctx->open = 0;
    switch (backend) {
    case FT_BACKEND_EGL_GLES3:
    case FT_BACKEND_EGL_GLES2:
#if FT_WITH_EGL
        return ft_plat_egl_open(backend, ctx, err);
#else
        break;
#endif
    case FT_BACKEND_OSMESA:
#if FT_WITH_OSMESA
        return ft_plat_osmesa_open(backend, ctx, err);
#else
        break;
#endif
    default:
        return ft_fail(err, FT_ERR_ARG, "unknown backend %d", (int)backend);
    }
    return ft_fail(err, FT_ERR_UNSUPPORTED,
                   "backend '%s' was left out of this build (see FIXTERRAIN_WITH_* options)",
                   ft_backend_name(backend));
}

void ft_plat_gpu_close(ft_gpu_context *ctx)
{
    if (!ctx->open) {
        return;
    }
#if FT_WITH_EGL
    if (ctx->backend == FT_BACKEND_EGL_GLES3 || ctx->backend == FT_BACKEND_EGL_GLES2) {
        ft_plat_egl_close(ctx);
    }
#endif
#if FT_WITH_OSMESA
    if (ctx->backend == FT_BACKEND_OSMESA) {
        ft_plat_osmesa_close(ctx);
    }
#endif
}
