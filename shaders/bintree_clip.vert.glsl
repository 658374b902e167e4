/* bintree_clip.vert.glsl - one triangular tile of the bintree over the
 * clipmap cache (bintree.heights = clipmap; src/lod/bintree_cache.h, drawn
 * by src/lod/method_bintree.c): the template and batches of bintree.vert.glsl,
 * the heights from the cache's levels instead of the window's grid.
 *
 * a_uv = (a, b, slot); u_bt_tiles[slot] = (apex, left) in level-0 lattice
 * samples relative to the domain's origin o (integers below 2^24, exact in
 * highp float). The vertex is
 *   g = apex + a (left - apex) + b (right - apex)
 * with right - apex the leg turned a quarter counter-clockwise: an exact
 * integer, the same in every tile that holds it.
 *
 * Level: the tile's template puts its vertices every 2^m level-0 samples, m
 * its table level: 2^(m + k) is the larger component of its leg. It reads
 * cache level d = min(m, Lc) (tables above the coarsest level take every
 * 2^(m - Lc)-th sample of it), where g is a multiple of 2^d. The cache's
 * levels are point samples of each other, so a vertex shared by tiles of
 * different levels gets one height: no cracks.
 *
 * Texel: level d's sample s = g / 2^d (relative to o / 2^d) lives at atlas
 * texel origin_px[d] + ((o / 2^d + s) mod side); the CPU sends (o / 2^d) mod
 * side, and the sum is reduced in two steps so every value stays below
 * 2 side. Normal: central differences of level d at s +- 1 (2^d samples
 * apart). Position: the eye's offset from o split on the CPU into an integer
 * and a fraction, so g minus the integer part is exact and small near the
 * eye wherever o lies; lowered by the curvature drop as every method is.
 *
 * The data's edge (a single grid): the position is clamped into the data
 * box u_btc_data, the height stays the one the cache holds for the vertex's
 * lattice point (the source clamps it the same way), so a triangle past the
 * edge collapses onto it and one across it is cut to its part inside
 * (src/lod/bintree_cache.h: the selection splits a tile across the edge
 * until its lattice holds the edge). */
precision highp float;

#ifndef FT_BT_BATCH
#define FT_BT_BATCH 64 /* tiles a draw */
#endif
#define FT_BTC_LEVELS 16 /* FT_CLIP_LEVELS_MAX */

#include "curvature.glsl"
#include "decode.glsl"

uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m; /* z: 0 minus the eye's height */
uniform mat4 u_view_proj;

uniform highp sampler2D u_btc_atlas;
uniform vec4 u_btc_level[FT_BTC_LEVELS]; /* atlas origin of level d (xy), (o / 2^d) mod side (zw) */
uniform vec4 u_btc_eye;   /* the eye - o in level-0 samples: integer part (xy), fraction (zw) */
uniform vec4 u_btc_misc;  /* (side, Lc, template k, 0) */
uniform vec4 u_btc_pack;  /* (pack like u_pack, atlas width, height) */
uniform vec4 u_btc_data;  /* the data box relative to o: lo (xy), hi (zw), level-0 samples */

FT_IN_VS vec3 a_uv; /* (a, b, slot) */
uniform vec4 u_bt_tiles[FT_BT_BATCH]; /* per slot: apex.xy, left.xy (level-0 samples from o) */

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;
FT_OUT_VS float v_morph; /* always 1: no geomorphing over the cache */

/* The height of sample s (relative to o / 2^d) of the level lv describes. */
float ft_btc_height(vec4 lv, vec2 s)
{
    float side = u_btc_misc.x;
    vec2 t = lv.xy + mod(mod(s, side) + lv.zw, side);
#if FT_ES3
    vec4 v = texelFetch(u_btc_atlas, ivec2(t), 0);
#else
    vec4 v = texture2DLod(u_btc_atlas, (t + 0.5) / u_btc_pack.zw, 0.0);
#endif
    return ft_decode(v, u_btc_pack.xy);
}

void main()
{
    vec4 tile = u_bt_tiles[int(a_uv.z)];
    vec2 apex = tile.xy;
    vec2 leg = tile.zw - apex;
    vec2 g = apex + a_uv.x * leg + a_uv.y * vec2(-leg.y, leg.x);
    /* integers: the rounding takes log2's and exp2's last bits off */
    float m = floor(log2(max(abs(leg.x), abs(leg.y))) + 0.5) - u_btc_misc.z;
    float d = clamp(m, 0.0, u_btc_misc.y);
    float spacing = floor(exp2(d) + 0.5); /* 2^d */
    vec4 lv = u_btc_level[int(d)];
    vec2 s = g / spacing;
    float h = ft_btc_height(lv, s);
    float dhx = ft_btc_height(lv, s + vec2(1.0, 0.0)) - ft_btc_height(lv, s - vec2(1.0, 0.0));
    float dhy = ft_btc_height(lv, s + vec2(0.0, 1.0)) - ft_btc_height(lv, s - vec2(0.0, 1.0));
    vec2 span_m = 2.0 * spacing * u_cell_m;
    v_normal = normalize(vec3(-dhx / span_m.x, -dhy / span_m.y, 1.0));
    v_morph = 1.0;
    v_height_m = h;
    vec2 gp = clamp(g, u_btc_data.xy, u_btc_data.zw);
    vec2 xy = ((gp - u_btc_eye.xy) - u_btc_eye.zw) * u_cell_m;
    v_pos_rel_eye_m = ft_earth_curve(vec3(xy, h + u_origin_rel_eye_m.z));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
