/* bench_oracle.h - the floor of a bintree frame on this rasteriser.
 *
 * The oracle draws the frame's selected triangles (the same tiles, the same
 * template, the same order) as a static, pre-transformed mesh: positions
 * relative to the eye, normals and drawn heights computed on the CPU by the
 * mirror of the bintree vertex shader (src/lod/bintree_mesh.h), uploaded outside
 * the timed region, drawn with a trivial vertex shader (shaders/
 * oracle.vert.glsl) and the same fragment shader, uniforms, target and
 * readback as the method's frame. Its time is what that triangle set costs
 * with no vertex-stage work beyond the projection: the bench reports the
 * method's time over it.
 *
 * Mesh: indexed (32-bit indices; GLES 2 needs OES_element_index_uint), one
 * vertex per (tile, template vertex) like the method's instanced draw, 7
 * floats per vertex. The CPU arrays and GL buffers grow to the largest frame
 * seen (the bench is a tool and may allocate; nothing here runs in the
 * runtime's frame loop).
 *
 * Use, per bintree frame, after ft_app_render drew it: bench_oracle_prepare
 * (mirror + upload + glFinish: not timed), then bench_oracle_frame (clear,
 * draw, read back like ft_app_render: timed). */
#ifndef FT_BENCH_ORACLE_H
#define FT_BENCH_ORACLE_H

#include <stddef.h>
#include <stdint.h>

#include "gpu/renderer.h"

typedef struct bench_oracle {
    int ready;
    const ft_gl *gl;
    ft_terrain_program prog; /* oracle.vert.glsl + terrain.frag.glsl */
    GLuint vao, vbo, ibo;
    size_t vbo_bytes;        /* GL buffer sizes */
    uint32_t ibo_tiles;      /* tiles whose indices the index buffer holds */
    uint32_t tmpl_verts, tmpl_indices;
    float *tmpl_uv;          /* template (a, b) per vertex */
    uint16_t *tmpl_idx;
    float *verts;            /* the mirror's vertices (FT_BT_MESH_FLOATS each) */
    size_t verts_cap;        /* floats */
    uint32_t *idx;
    size_t idx_cap;          /* indices */
    uint32_t tiles;          /* prepared: tiles, indices to draw */
    size_t index_count;
    double prepare_ms;       /* the last prepare (mirror + upload), for information */
} bench_oracle;

/* Builds the oracle program and buffers for the renderer's bintree method.
 * FT_ERR_UNSUPPORTED when the method is not bintree or the context has no
 * 32-bit indices. */
ft_status bench_oracle_init(bench_oracle *o, ft_renderer *r, ft_error *err);

/* The mirror of the frame's selection (the method's last one, made for cam),
 * uploaded; returns once the GPU has the data. Not part of the timing. */
ft_status bench_oracle_prepare(bench_oracle *o, ft_renderer *r, const ft_camera *cam,
                               ft_error *err);

/* One timed oracle frame: target, clear, draw, colour readback (waits for
 * the GPU), as ft_app_render times a frame. *ms = wall time of all that. */
ft_status bench_oracle_frame(bench_oracle *o, ft_renderer *r, const ft_camera *cam, double *ms,
                             ft_error *err);

/* Frees the arrays and GL objects (the context must still be current). */
void bench_oracle_shutdown(bench_oracle *o);

#endif
