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

/* Texel t (integer valued) of the atlas u_pgm_atlas. */
float ft_atlas_texel(vec2 t)
{
#if FT_ES3
    return ft_decode(texelFetch(u_pgm_atlas, ivec2(t), 0), u_pgm_atlas_pack);
#else
    return ft_decode(texture2DLod(u_pgm_atlas, (t + 0.5) / u_pgm_atlas_size, 0.0),
                     u_pgm_atlas_pack);
#endif
}

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
    return ft_atlas_texel(u_pgm_level[int(level)].xy + ij);
}

/* Bilinear in the cell whose corner heights are h00 .. h11 at fraction f, of
 * side `scale` level-0 samples: (height, dh/dgx, dh/dgy) per level-0 sample. */
vec3 ft_bilerp(float h00, float h10, float h01, float h11, vec2 f, float scale)
{
    float lo = mix(h00, h10, f.x);
    float up = mix(h01, h11, f.x);
    float dx = mix(h10 - h00, h11 - h01, f.y) / scale;
    float dy = mix(h01 - h00, h11 - h10, f.x) / scale;
    return vec3(mix(lo, up, f.y), dx, dy);
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
    return ft_bilerp(h00, h10, h01, h11, f, scale);
}

#ifdef FT_PGM_CLIP
/* pgm.heights = clipmap (method_pgm.c): the levels are the clipmap cache's,
 * every level a side x side block of the atlas u_pgm_atlas, level L at block
 * (L mod cols, L / cols); level-L sample (a, b) is at texel (a mod side,
 * b mod side) of its block. Coordinates stay near the eye: per level, base
 * is the level-L sample at or below the eye, and
 *   u_pgm_level[L] = (base mod side (xy), eye - base 2^L in level-0 samples (zw))
 *   u_pcm_box[L]   = the resident samples, relative to base, inclusive
 *                    (x0, y0, x1, y1); empty: x1 < x0
 * so a point g0 level-0 samples from the eye is u = (g0 + zw) / 2^L level-L
 * samples from base. */
uniform vec4 u_pcm_box[FT_PGM_LEVELS];
uniform vec4 u_pcm_clamp; /* what is drawn (data and the coarsest level), m from the eye */
uniform vec4 u_pcm_misc;  /* (side, transition samples, levels, atlas columns) */

float ft_pcm_texel(float level, vec2 i)
{
    vec4 lv = u_pgm_level[int(level)];
    float side = u_pcm_misc.x;
    vec2 block = vec2(mod(level, u_pcm_misc.w), floor(level / u_pcm_misc.w));
    return ft_atlas_texel(block * side + mod(lv.xy + i, side));
}

/* Level L bilinear at g0 (level-0 samples from the eye), inside its resident
 * samples: (height, dh/dgx, dh/dgy) per level-0 sample. */
vec3 ft_pcm_sample(float level, vec2 g0)
{
    float scale = exp2(level);
    vec4 b = u_pcm_box[int(level)];
    vec2 u = clamp((g0 + u_pgm_level[int(level)].zw) / scale, b.xy, b.zw);
    vec2 i0 = min(floor(u), b.zw - 1.0);
    vec2 f = u - i0;
    float h00 = ft_pcm_texel(level, i0);
    float h10 = ft_pcm_texel(level, i0 + vec2(1.0, 0.0));
    float h01 = ft_pcm_texel(level, i0 + vec2(0.0, 1.0));
    float h11 = ft_pcm_texel(level, i0 + vec2(1.0, 1.0));
    return ft_bilerp(h00, h10, h01, h11, f, scale);
}

/* The finest level whose resident samples hold g0 one sample in from their
 * edge, and how far into its transition band (the last transition samples
 * before that edge) g0 is: L + t, t in [0, 1], blends to level L + 1 at the
 * edge, so a level ends without a step; the top level when none holds it. */
float ft_pcm_resident(vec2 g0)
{
    float top = u_pcm_misc.z - 1.0;
    for (int k = 0; k < FT_PGM_LEVELS; ++k) {
        float level = float(k);
        if (level >= top) {
            break;
        }
        vec4 b = u_pcm_box[k];
        vec2 u = (g0 + u_pgm_level[k].zw) / exp2(level);
        vec2 d2 = min(u - b.xy, b.zw - u) - 1.0;
        float d = min(d2.x, d2.y);
        if (b.z >= b.x && b.w >= b.y && d >= 0.0) {
            return level + clamp(1.0 - d / u_pcm_misc.y, 0.0, 1.0);
        }
    }
    return top;
}

/* The level sample the vertex reads (g: level-0 samples from the eye). */
vec3 ft_height_sample(float level, vec2 g)
{
    return ft_pcm_sample(level, g);
}
#else
/* The level sample the vertex reads (g: grid coordinates). */
vec3 ft_height_sample(float level, vec2 g)
{
    return ft_level_sample(level, g);
}
#endif

/* Image-plane height of the row at t = j / (rows - 1), whose uniform
 * placement is y: defined by the including body (pgm: y itself). */
float ft_row_y(float t, float y);
/* Image-plane x of the column at t = i / (cols - 1), whose uniform
 * placement is x: defined by the including body (pgm: x itself). */
float ft_col_x(float t, float x);

/* Base-plane point of grid point ij, relative to the viewing eye (xy, m). */
vec2 ft_ground(vec2 ij)
{
    vec2 st = ij / u_pgm_grid.xy;
    vec2 xy = mix(u_pgm_rect.xy, u_pgm_rect.zw, st);
    xy.y = ft_row_y(st.y, xy.y);
    xy.x = ft_col_x(st.x, xy.x);
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
#ifdef FT_PGM_CLIP
    /* the footprint's continuous level, raised to what is resident there */
    pc = clamp(p, u_pcm_clamp.xy, u_pcm_clamp.zw);
    vec2 g = pc * inv_cell;
    float lc = (r > 1.0) ? log2(r) : 0.0;
    lc = max(lc, ft_pcm_resident(g));
    float top = u_pcm_misc.z - 1.0;
    level = min(floor(lc), top);
    w = (level >= top) ? 0.0 : clamp(lc - level, 0.0, 1.0);
#else
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
#endif
    vec3 s = ft_height_sample(level, g);
    if (w > 0.0) {
        s = mix(s, ft_height_sample(level + 1.0, g), w);
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
