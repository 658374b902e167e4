/* bintree_mesh.h - a CPU mirror of shaders/bintree.vert.glsl: the vertices
 * the bintree method draws for one selection, computed on the CPU.
 *
 * For every selected tile (bt->tiles[0..tiles)) and every template vertex
 * (bintree_template.h) it computes what the vertex shader outputs: the
 * position relative to the eye (geomorph and earth curvature included), the
 * normal (central differences, one-sided at the grid edge) and the drawn
 * height v_height_m, with the same rules, the same clamps and the same
 * morph weight, in double where the shader works in float.
 *
 * Sub-sample levels (bt->sub = S > 0): tile coordinates are in fine units
 * (2^-S of a cell). A vertex on a sample reads it; a vertex between samples
 * takes the bilinear height of its cell (the floor of its coordinate / 2^S,
 * clamped to [0, size - 2]), its normal from that cell's bilinear gradient,
 * its morph endpoints' heights from the same cell's bilinear, and the error
 * of its inserting diamond from the table when the diamond's split vertex
 * is a multiple of 2^(k+S) in both axes, else in closed form from <= 4
 * texels of the twist atlas (the shader's ft_sub_error).
 *
 * Layout: indexed, one vertex per (tile, template vertex): vertex v of tile
 * i is vertex i * tmpl_verts + v, FT_BT_MESH_FLOATS floats each; the
 * triangles are the template's indices offset by i * tmpl_verts
 * (ft_bt_mesh_indices). So the mesh has exactly the method's triangles, in
 * its order, and as many vertices as the method's vertex shader runs.
 *
 * Heights, diamond errors and twists are read from the float tables
 * (bt->heights_m, bt->err_m, bt->twist_atlas): the GPU reads the same values
 * from R32F textures; a context without float vertex textures gets them as
 * 24-bit fixed point (decode.glsl) and differs from this mirror by up to
 * range / 2^24.
 *
 * Used by the bench's oracle and the tests; the runtime never calls it. */
#ifndef FT_BINTREE_MESH_H
#define FT_BINTREE_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "lod/bintree.h"
#include "lod/bintree_cache.h"
#include "terrain/terrain.h"

/* Floats per vertex: position relative to the eye (3, metres), unit normal
 * (3), drawn height (1, metres). */
#define FT_BT_MESH_FLOATS 7u

/* The vertex shader's uniforms for one frame, in double. */
typedef struct ft_bt_mesh_uniforms {
    double origin_rel_eye_m[3]; /* u_origin_rel_eye_m: world(sample 0,0) - eye */
    double cell_m[2];           /* u_cell_m */
    double drop_per_m2;         /* u_earth_drop_per_m2 */
    double k_px;                /* u_bt_morph.x: K = px_per_rad_k */
    double tau_px;              /* u_bt_morph.y: the selection's tau */
    int morph;                  /* u_bt_morph.w > 0.5 */
    ft_bt_view view;            /* the same view as the selection's (Q, bintree.h);
                                   view.gain: u_bt_axis, u_bt_gain_cap */
    int vertex_table;           /* GLES 3: a sample vertex's normal is the vertex
                                   table's 12+12-bit one (ft_bt_sample_texel) */
} ft_bt_mesh_uniforms;

/* The uniforms the method sets for a frame (src/lod/method_bintree.c,
 * ft_bintree_method_draw, and the renderer's draw pass): tau_target_px is
 * the selection's target (tau_used_px), morph the scene's bintree.morph. */
void ft_bt_mesh_uniforms_for(const ft_terrain *t, const ft_camera *cam, double tau_target_px,
                             int morph, ft_bt_mesh_uniforms *u);

/* One vertex as the shader outputs it. */
typedef struct ft_bt_mesh_vertex {
    double pos_rel_eye_m[3]; /* v_pos_rel_eye_m */
    double normal[3];        /* v_normal */
    double height_m;         /* v_height_m */
    double morph_w;          /* v_morph: 1 = at its own height */
    /* how it was computed (for the tests) */
    int on_sample;           /* on a sample (always with S = 0), else between samples */
    double err_m;            /* error of its inserting diamond; -1 when it does not morph */
    double q_m;              /* that diamond's Q (bintree.h; -inf when it does not morph) */
    int32_t e0[2], e1[2];    /* the coarse edge it bisects (fine units) when it morphs */
    double w_m;              /* that diamond's morph width W (m) */
    double q_scale_m;        /* the size of Q's operands (distances over the box, m): the
                                shader's float Q is off by a few ulps of this */
    double morph_span_m;     /* |own height - coarse height| (m): the height a unit of
                                weight moves */
    int err_closed_form;     /* err_m from the closed form (ft_sub_error), not the table */
} ft_bt_mesh_vertex;

/* Template vertex (a, b) (leg coordinates, multiples of 2^-k) of tile
 * (corners in fine units). */
void ft_bt_mesh_vertex_of(const ft_bintree *bt, const ft_bt_mesh_uniforms *u,
                          const ft_bt_tile *tile, double a, double b, ft_bt_mesh_vertex *out);

/* Writes tiles * tmpl_verts vertices (layout above) into out. tmpl_uv is the
 * template's (a, b) per vertex (ft_bt_template_build). Returns the vertices
 * written; 0 when tiles > bt->tiles_max or out_floats is too small (nothing
 * written then). Bounded: tiles * tmpl_verts iterations. */
size_t ft_bt_mesh_build(const ft_bintree *bt, uint32_t tiles, const ft_bt_mesh_uniforms *u,
                        const float *tmpl_uv, uint32_t tmpl_verts, float *out,
                        size_t out_floats);

/* The mesh's triangles: tiles copies of the template's tmpl_indices indices,
 * copy i offset by i * tmpl_verts. Returns the indices written; 0 when
 * out_count is too small or an index would not fit 32 bits. */
size_t ft_bt_mesh_indices(uint32_t tiles, const uint16_t *tmpl_idx, uint32_t tmpl_indices,
                          uint32_t tmpl_verts, uint32_t *out, size_t out_count);

/* The same for the tiles of the bintree over the clipmap cache
 * (bc->tiles[0..tiles), bintree_cache.h), mirroring
 * shaders/bintree_clip.vert.glsl: heights from the cache's CPU copy of the
 * level each tile reads (the texels themselves with float texels; packed ones are up to half a 24-bit step off), normals by its central
 * differences, positions clamped into the data box, relative to the eye at
 * (eye_i, eye_j) on the level-0 lattice and eye_z_m, lowered by the
 * curvature drop. Returns the vertices written (0 when they do not fit). */
size_t ft_btc_mesh_build(const ft_bt_cache *bc, const ft_clip_cache *c, uint32_t tiles,
                         double eye_i, double eye_j, double eye_z_m, double drop_per_m2,
                         const float *tmpl_uv, uint32_t tmpl_verts, float *out,
                         size_t out_floats);

#endif
