/* gpu_select.c - one dispatch point from ft_backend to the backend that
 * this build contains. */
#include "gpu_backends.h"
#include "gpu/gpu.h"

ft_status ft_plat_gpu_open(const ft_gpu_desc *desc, ft_gpu_context *ctx, ft_error *err)
{
    const ft_backend backend = desc->backend;
    ctx->open = 0;
    if (desc->display == FT_DISPLAY_KMS) { /* EGL on GBM: platform/display_kms.c */
#if FT_WITH_KMS
        if (backend != FT_BACKEND_EGL_GLES3 && backend != FT_BACKEND_EGL_GLES2) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "display 'kms' needs an EGL backend (egl-gles3, egl-gles2), not '%s'",
                           ft_backend_name(backend));
        }
        return ft_plat_kms_open(desc, ctx, err);
#else
        return ft_fail(err, FT_ERR_UNSUPPORTED,
                       "display 'kms' was left out of this build (FIXTERRAIN_WITH_KMS=OFF)");
#endif
    }
    switch (backend) {
    case FT_BACKEND_EGL_GLES3:
    case FT_BACKEND_EGL_GLES2:
#if FT_WITH_EGL
        return ft_plat_egl_open(desc, ctx, err);
#else
        break;
#endif
    case FT_BACKEND_OSMESA:
#if FT_WITH_OSMESA
        if (desc->display != FT_DISPLAY_NONE) {
            return ft_fail(err, FT_ERR_UNSUPPORTED,
                           "OSMesa renders offscreen only: display '%s' needs an EGL backend",
                           ft_display_name(desc->display));
        }
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

ft_status ft_plat_gpu_present(ft_gpu_context *ctx, ft_error *err)
{
    if (ctx->display == FT_DISPLAY_NONE) {
        return FT_OK;
    }
#if FT_WITH_KMS
    if (ctx->display == FT_DISPLAY_KMS) {
        return ft_plat_kms_present(ctx, err);
    }
#endif
#if FT_WITH_EGL
    return ft_plat_egl_present(ctx, err);
#else
    return ft_fail(err, FT_ERR_UNSUPPORTED, "no display support in this build");
#endif
}

void ft_plat_gpu_close(ft_gpu_context *ctx)
{
    if (!ctx->open) {
        return;
    }
#if FT_WITH_KMS
    if (ctx->display == FT_DISPLAY_KMS) {
        ft_plat_kms_close(ctx);
        return;
    }
#endif
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
