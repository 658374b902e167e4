/* gpu_texture.h - one single-channel float array as a NEAREST texture, in the
 * format the context supports: R32F (GLES 3), LUMINANCE/FLOAT (GLES 2 with
 * OES_texture_float), or RGBA8 packed 24-bit fixed point over
 * [pack_min, pack_min + pack_range] that shaders decode exactly (integers
 * below 2^24 are exact in highp float). Packed texels go through the
 * FT_POOL_GPU_STAGING scratch (reset afterwards). */
#ifndef FT_GPU_TEXTURE_H
#define FT_GPU_TEXTURE_H

#include <stdint.h>

#include "core/mem_budget.h"
#include "core/scene.h"
#include "gpu/gl_api.h"

typedef struct ft_scalar_format {
    ft_height_format format; /* FLOAT or PACKED (resolved) */
    float pack_min, pack_range;
} ft_scalar_format;

/* Uploads data (w x h floats) on texture unit `unit`; adds w*h*4 to *bytes. */
ft_status ft_gpu_upload_scalar(const ft_gl *gl, const ft_scalar_format *f, const float *data,
                               uint32_t w, uint32_t h, GLenum unit, ft_arena *a, GLuint *tex,
                               uint64_t *bytes, ft_error *err);

#endif
