/* pgm_grid.glsl - the persistent grid's vertex placement, shared by
 * pgm.vert.glsl (method 'pgm') and pgrid.vert.glsl (method 'pgrid'); not a
 * shader by itself: tools/embed_shaders.cmake puts it in place of the
 * include line of a body that names it, at build time (GLSL ES has no
 * include directive, so a body that was not expanded fails to compile).
 *
 * The math (and why) is in src/lod/pgm.h; src/lod/pgm.c is the same arithmetic in
 * double, and tests/test_pgm_gl.c holds the shader to it. In short:
 *  - grid vertex (i, j) -> point of the sampling camera's image plane
 *    (rectangle u_pgm_rect, rows placed by the body's ft_row_y, frame
 *    u_pgm_fwd/right/up) -> ray d;
 *  - the ray meets the base plane at P = S + h / (-d_z) d (S the sampling
 *    eye, h its height above the plane; -d_z is floored, so P is finite);
 *  - level of detail from the ground distance to the farthest of the 4 grid
 *    neighbours' points, r cells: L = max(0, floor(log2 r)), parent weight
 *    w = r / 2^L - 1, height = mix(avg_L(P), avg_L+1(P), w) (no popping);
 *  - the vertex goes on the terrain at P.xy (clamped into the grid) and is
 *    drawn with the viewing camera (u_view_proj).
 * Avg level 0 is the heights texture (unit 0); levels 1.. are side by side in
 * u_pgm_atlas (unit 1), level L at texel u_pgm_level[L].xy, size .zw.
 *
 * The grid is drawn in bands of rows (16-bit indices): a_uv is (column, row
 * within the band) and u_pgm_grid.z the band's first row. */
precision highp float;

#define FT_PGM_LEVELS 16

/* highp: samplers default to lowp even in the vertex stage, and Mesa then
 * returns float texels at half precision (2059 m reads as 2058 m) */
uniform highp sampler2D u_heights;
uniform vec2 u_grid_size;        /* samples (width, height) */
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m; /* grid sample (0,0) minus the viewing eye */
uniform mat4 u_view_proj;
uniform vec2 u_pack;             /* heights: packed (min, range); range 0 = float */

uniform highp sampler2D u_pgm_atlas;
uniform vec2 u_pgm_atlas_size;
uniform vec2 u_pgm_atlas_pack;   /* like u_pack, for the atlas */
uniform vec4 u_pgm_level[FT_PGM_LEVELS]; /* atlas origin (xy) and size (zw) per avg level */
uniform vec4 u_pgm_grid;         /* (cols - 1, rows - 1, band's first row, avg levels) */
uniform vec3 u_pgm_fwd;          /* sampling frame (world, unit) */
uniform vec3 u_pgm_right;
uniform vec3 u_pgm_up;
uniform vec4 u_pgm_rect;         /* (x0, y0, x1, y1): image plane at distance 1 */
uniform vec2 u_pgm_eye;          /* (h: sampling eye above the base plane, floor of -d_z) */

/* A fragment shader that places grid vertices (pgrid's vertex pass) defines
 * FT_PGM_GRID_NO_IO: it has neither the attribute nor the varyings. */
#ifndef FT_PGM_GRID_NO_IO
FT_IN_VS vec2 a_uv;

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;
FT_OUT_VS float v_morph; /* the continuous level L + w (captured by the tests) */
#endif

#include "decode.glsl"

/* Texel ij (integer valued, inside the level) of avg level `level`. */
float ft_texel(float level, vec2 ij)
{
    if (level < 0.5) {
#if FT_ES3
        return ft_decode(texelFetch(u_heights, ivec2(ij), 0), u_pack);
#else
        return ft_decode(texture2DLod(u_heights, (ij + 0.5) / u_grid_size, 0.0), u_pack);
#endif
    }
    vec2 a = u_pgm_level[int(level)].xy + ij;
#if FT_ES3
    return ft_decode(texelFetch(u_pgm_atlas, ivec2(a), 0), u_pgm_atlas_pack);
#else
    return ft_decode(texture2DLod(u_pgm_atlas, (a + 0.5) / u_pgm_atlas_size, 0.0),
                     u_pgm_atlas_pack);
#endif
}

/* Avg level `level` bilinear at grid coordinate g: (height, dh/dgx, dh/dgy). */
vec3 ft_level_sample(float level, vec2 g)
{
    float scale = exp2(level);
    vec2 u = (g + 0.5) / scale - 0.5;
    vec2 i0 = floor(u);
    vec2 f = u - i0;
    vec2 hi = u_pgm_level[int(level)].zw - 1.0;
    vec2 a = clamp(i0, vec2(0.0), hi);
    vec2 b = clamp(i0 + 1.0, vec2(0.0), hi);
    float h00 = ft_texel(level, a);
    float h10 = ft_texel(level, vec2(b.x, a.y));
    float h01 = ft_texel(level, vec2(a.x, b.y));
    float h11 = ft_texel(level, b);
    float lo = mix(h00, h10, f.x);
    float up = mix(h01, h11, f.x);
    float dx = mix(h10 - h00, h11 - h01, f.y) / scale;
    float dy = mix(h01 - h00, h11 - h10, f.x) / scale;
    return vec3(mix(lo, up, f.y), dx, dy);
}

/* Image-plane height of the row at t = j / (rows - 1), whose uniform
 * placement is y: defined by the including body (pgm: y itself). */
float ft_row_y(float t, float y);

/* Base-plane point of grid point ij, relative to the viewing eye (xy, m). */
vec2 ft_ground(vec2 ij)
{
    vec2 st = ij / u_pgm_grid.xy;
    vec2 xy = mix(u_pgm_rect.xy, u_pgm_rect.zw, st);
    xy.y = ft_row_y(st.y, xy.y);
    vec3 d = u_pgm_fwd + xy.x * u_pgm_right + xy.y * u_pgm_up;
    return (u_pgm_eye.x / max(-d.z, u_pgm_eye.y)) * d.xy;
}

/* The persistent grid's vertex ij: its base-plane point p and that point
 * clamped into the grid (pc, both relative to the viewing eye), the level
 * of detail L + w, and the (avg-pyramid, morphed) sample s = (height,
 * dh/dgx, dh/dgy). */
vec3 ft_pgm_vertex(vec2 ij, out vec2 pc, out float morph)
{
    vec2 p = ft_ground(ij);
    vec2 inv_cell = 1.0 / u_cell_m;
    vec2 q0 = (ft_ground(ij + vec2(1.0, 0.0)) - p) * inv_cell;
    vec2 q1 = (ft_ground(ij - vec2(1.0, 0.0)) - p) * inv_cell;
    vec2 q2 = (ft_ground(ij + vec2(0.0, 1.0)) - p) * inv_cell;
    vec2 q3 = (ft_ground(ij - vec2(0.0, 1.0)) - p) * inv_cell;
    float r = sqrt(max(max(dot(q0, q0), dot(q1, q1)), max(dot(q2, q2), dot(q3, q3))));

    float level = 0.0;
    float w = 0.0;
    if (r > 1.0) {
        level = floor(log2(r));
        float span = exp2(level);
        /* log2 may round across a power of two: settle on the exact level */
        if (r < span) {
            level -= 1.0;
            span *= 0.5;
        } else if (r >= 2.0 * span) {
            level += 1.0;
            span *= 2.0;
        }
        w = clamp(r / span - 1.0, 0.0, 1.0);
    }
    float top = u_pgm_grid.w - 1.0;
    if (level >= top) {
        level = top;
        w = 0.0;
    }

    /* clamped into the grid in eye-relative metres: near the eye the vertex
     * never goes through the (large) grid origin, float keeps millimetres */
    vec2 lo = u_origin_rel_eye_m.xy;
    pc = clamp(p, lo, lo + (u_grid_size - 1.0) * u_cell_m);
    vec2 g = (pc - lo) * inv_cell;
    vec3 s = ft_level_sample(level, g);
    if (w > 0.0) {
        s = mix(s, ft_level_sample(level + 1.0, g), w);
    }
    morph = level + w;
    return s;
}

#ifndef FT_PGM_GRID_NO_IO
/* The vertex's outputs: placed at (pc, height s.x), drawn with the viewing
 * camera; the normal from the sample's gradient. */
void ft_pgm_emit(vec2 pc, vec3 s, float morph)
{
    vec2 inv_cell = 1.0 / u_cell_m;
    v_normal = normalize(vec3(-s.y * inv_cell.x, -s.z * inv_cell.y, 1.0));
    v_morph = morph;
    v_height_m = s.x;
    v_pos_rel_eye_m = ft_earth_curve(vec3(pc, s.x + u_origin_rel_eye_m.z));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
#endif
