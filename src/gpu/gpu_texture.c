#include "gpu/gpu_texture.h"

static void pack_values(const float *v, size_t n, float min_m, float range_m, uint8_t *out)
{
    for (size_t i = 0; i < n; ++i) {
        double f = ((double)v[i] - min_m) / range_m;
        f = (f > 0.0) ? ((f < 1.0) ? f : 1.0) : 0.0;
        uint32_t q = (uint32_t)(f * 16777215.0 + 0.5);
        out[i * 4u + 0u] = (uint8_t)(q >> 16);
        out[i * 4u + 1u] = (uint8_t)(q >> 8);
        out[i * 4u + 2u] = (uint8_t)q;
        out[i * 4u + 3u] = 255u;
    }
}

ft_status ft_gpu_upload_scalar(const ft_gl *gl, const ft_scalar_format *f, const float *data,
                               uint32_t w_px, uint32_t h_px, GLenum unit, ft_arena *a,
                               GLuint *tex, uint64_t *bytes, ft_error *err)
{
    const GLsizei w = (GLsizei)w_px, h = (GLsizei)h_px;
    gl->GenTextures(1, tex);
    gl->ActiveTexture(unit);
    gl->BindTexture(GL_TEXTURE_2D, *tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    /* NEAREST: texels are fetched exactly (float linear filtering is optional). */
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (f->format == FT_HEIGHT_FORMAT_FLOAT) {
        if (gl->api == FT_GL_API_ES3) {
            gl->TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, w, h, 0, GL_RED, GL_FLOAT, data);
        } else {
            gl->TexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, w, h, 0, GL_LUMINANCE, GL_FLOAT, data);
        }
    } else {
        uint8_t *staging = NULL;
        size_t n = (size_t)w_px * h_px;
        size_t mark = ft_arena_mark(a, FT_POOL_GPU_STAGING);
        ft_status st = ft_arena_take(a, FT_POOL_GPU_STAGING, n * 4u, (void **)&staging, err);
        if (st != FT_OK) {
            return st;
        }
        pack_values(data, n, f->pack_min, f->pack_range, staging);
        gl->TexImage2D(GL_TEXTURE_2D, 0, gl->api == FT_GL_API_ES3 ? GL_RGBA8 : GL_RGBA, w, h, 0,
                       GL_RGBA, GL_UNSIGNED_BYTE, staging);
        ft_arena_reset(a, FT_POOL_GPU_STAGING, mark);
    }
    gl->ActiveTexture(GL_TEXTURE0);
    *bytes += (uint64_t)w_px * (uint64_t)h_px * 4u;
    return ft_gl_check(gl, "scalar texture upload", err);
}
