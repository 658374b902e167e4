/* gpu_texture.h - the project's 2D textures: every one is NEAREST-filtered
 * and clamped (texels are fetched exactly; float linear filtering is
 * optional in GLES), created from one descriptor, and either given its data
 * at once or filled strip by strip through the FT_POOL_GPU_STAGING scratch
 * so no copy of a whole grid is ever staged. The GPU bytes of each texture
 * are counted where it is made.
 *
 * One single-channel float array goes up in the format the context supports:
 * R32F (GLES 3), LUMINANCE/FLOAT (GLES 2 with OES_texture_float), or RGBA8
 * packed 24-bit fixed point over [pack_min, pack_min + pack_range] that
 * shaders decode exactly (integers below 2^24 are exact in highp float). */
#ifndef FT_GPU_TEXTURE_H
#define FT_GPU_TEXTURE_H

#include <stdint.h>

#include "core/mem_budget.h"
#include "core/scene.h"
#include "gpu/gl_api.h"

/* What a texture is: where it is bound and how its texels are laid out. */
typedef struct ft_texture_desc {
    GLenum unit; /* GL_TEXTUREn it is bound on when made */
    uint32_t width_px, height_px;
    GLint internal_format;
    GLenum format, type; /* of the client data */
    uint32_t texel_bytes; /* client bytes per texel; also what *bytes counts */
} ft_texture_desc;

/* Makes the texture and gives it `data` (NULL: storage only); leaves
 * GL_TEXTURE0 active and adds width * height * texel_bytes to *bytes. */
void ft_gpu_texture_create(const ft_gl *gl, const ft_texture_desc *d, const void *data,
                           GLuint *tex, uint64_t *bytes);

/* Writes `rows` rows of d->width_px texels, starting at row y0, into strip. */
typedef void (*ft_texture_strip_fn)(void *ctx, uint32_t y0, uint32_t rows, void *strip);

/* Staging bytes ft_gpu_texture_create_strips takes (plan them in
 * FT_POOL_GPU_STAGING before init). */
size_t ft_gpu_texture_strip_bytes(const ft_texture_desc *d, uint32_t strip_rows);

/* Makes the texture, then fills it strip_rows rows at a time with `fill`
 * through a staging strip that is released afterwards. `what` names the
 * texture in a GL error. */
ft_status ft_gpu_texture_create_strips(const ft_gl *gl, const ft_texture_desc *d,
                                       uint32_t strip_rows, ft_texture_strip_fn fill, void *ctx,
                                       ft_arena *a, GLuint *tex, uint64_t *bytes,
                                       const char *what, ft_error *err);

typedef struct ft_scalar_format {
    ft_height_format format; /* FLOAT or PACKED (resolved) */
    float pack_min, pack_range;
} ft_scalar_format;

/* The renderer's rule for heights read in a vertex shader: `format` as the
 * scene gives it, auto = float when the context has float textures, else
 * packed, over [min_m, max_m] (a range of 1 for flat terrain: any range
 * decodes it exactly). */
ft_scalar_format ft_gpu_height_format(const ft_gl *gl, ft_height_format format, float min_m,
                                      float max_m);

/* Uploads data (w x h floats) on texture unit `unit`; adds w*h*4 to *bytes. */
ft_status ft_gpu_upload_scalar(const ft_gl *gl, const ft_scalar_format *f, const float *data,
                               uint32_t w, uint32_t h, GLenum unit, ft_arena *a, GLuint *tex,
                               uint64_t *bytes, ft_error *err);

#endif
