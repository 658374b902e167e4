#include "gpu/gpu_texture.h"

void ft_gpu_texture_create(const ft_gl *gl, const ft_texture_desc *d, const void *data,
                           GLuint *tex, uint64_t *bytes)
{
    gl->GenTextures(1, tex);
    gl->ActiveTexture(d->unit);
    gl->BindTexture(GL_TEXTURE_2D, *tex);
    /* rows of 1- or 2-byte texels are not 4-byte aligned */
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, (d->texel_bytes % 4u == 0u) ? 4 : 1);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->TexImage2D(GL_TEXTURE_2D, 0, d->internal_format, (GLsizei)d->width_px,
                   (GLsizei)d->height_px, 0, d->format, d->type, data);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->ActiveTexture(GL_TEXTURE0);
    *bytes += (uint64_t)d->width_px * d->height_px * d->texel_bytes;
}

size_t ft_gpu_texture_strip_bytes(const ft_texture_desc *d, uint32_t strip_rows)
{
    return (size_t)d->width_px * strip_rows * d->texel_bytes;
}

ft_status ft_gpu_texture_create_strips(const ft_gl *gl, const ft_texture_desc *d,
                                       uint32_t strip_rows, ft_texture_strip_fn fill, void *ctx,
                                       ft_arena *a, GLuint *tex, uint64_t *bytes,
                                       const char *what, ft_error *err)
{
    void *strip = NULL;
    const size_t mark = ft_arena_mark(a, FT_POOL_GPU_STAGING);
    ft_status st = ft_arena_take(a, FT_POOL_GPU_STAGING, ft_gpu_texture_strip_bytes(d, strip_rows),
                                 &strip, err);
    if (st != FT_OK) {
        return st;
    }
    ft_gpu_texture_create(gl, d, NULL, tex, bytes);
    gl->ActiveTexture(d->unit);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, (d->texel_bytes % 4u == 0u) ? 4 : 1);
    for (uint32_t y0 = 0; y0 < d->height_px; y0 += strip_rows) {
        const uint32_t left = d->height_px - y0;
        const uint32_t rows = (left < strip_rows) ? left : strip_rows;
        fill(ctx, y0, rows, strip);
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, (GLint)y0, (GLsizei)d->width_px, (GLsizei)rows,
                          d->format, d->type, strip);
    }
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->ActiveTexture(GL_TEXTURE0);
    ft_arena_reset(a, FT_POOL_GPU_STAGING, mark);
    return ft_gl_check(gl, what, err);
}

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

ft_scalar_format ft_gpu_height_format(const ft_gl *gl, ft_height_format format, float min_m,
                                      float max_m)
{
    ft_scalar_format f;
    f.format = format;
    if (f.format == FT_HEIGHT_FORMAT_AUTO) {
        f.format = gl->caps.has_float_textures ? FT_HEIGHT_FORMAT_FLOAT : FT_HEIGHT_FORMAT_PACKED;
    }
    f.pack_min = min_m;
    f.pack_range = max_m - min_m;
    if (!(f.pack_range > 0.0f)) {
        f.pack_range = 1.0f;
    }
    return f;
}

ft_status ft_gpu_upload_scalar(const ft_gl *gl, const ft_scalar_format *f, const float *data,
                               uint32_t w_px, uint32_t h_px, GLenum unit, ft_arena *a,
                               GLuint *tex, uint64_t *bytes, ft_error *err)
{
    const int es3 = (gl->api == FT_GL_API_ES3);
    ft_texture_desc d = {unit, w_px, h_px, 0, 0, 0, 4u};
    if (f->format == FT_HEIGHT_FORMAT_FLOAT) {
        d.internal_format = es3 ? GL_R32F : GL_LUMINANCE;
        d.format = es3 ? GL_RED : GL_LUMINANCE;
        d.type = GL_FLOAT;
        ft_gpu_texture_create(gl, &d, data, tex, bytes);
    } else {
        d.internal_format = es3 ? GL_RGBA8 : GL_RGBA;
        d.format = GL_RGBA;
        d.type = GL_UNSIGNED_BYTE;
        uint8_t *staging = NULL;
        const size_t n = (size_t)w_px * h_px;
        const size_t mark = ft_arena_mark(a, FT_POOL_GPU_STAGING);
        ft_status st = ft_arena_take(a, FT_POOL_GPU_STAGING, n * 4u, (void **)&staging, err);
        if (st != FT_OK) {
            return st;
        }
        pack_values(data, n, f->pack_min, f->pack_range, staging);
        ft_gpu_texture_create(gl, &d, staging, tex, bytes);
        ft_arena_reset(a, FT_POOL_GPU_STAGING, mark);
    }
    return ft_gl_check(gl, "scalar texture upload", err);
}
