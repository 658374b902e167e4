/* pgrid_cache_range.glsl - the finest data's range over a region, read from
 * the clipmap cache's cell and block ranges (src/lod/pgrid.h 2): shared by
 * the grid's vertex shader (the relief bound and the envelopes) and the
 * quad-bound pass over the cache (src/lod/pgrid.h 6). Not a shader by
 * itself: a body includes it after pgm_grid.glsl with FT_PGM_CLIP defined
 * (tools/embed_shaders.cmake expands the include at build time). */
/* Over the clipmap cache (pgrid.heights = clipmap): the cache's cell ranges,
 * laid out as its heights (lod/clip_levels.h, FT_CLIP_BOUNDS_RANGES): per
 * level-L cell (lo, hi), the heights the finest data take over it. */
uniform highp sampler2D u_pgrid_range;
/* and per block of FT_CLIP_BLOCK x FT_CLIP_BLOCK texels (lod/clip_levels.h) */
uniform highp sampler2D u_pgrid_block_range;
uniform vec2 u_pgrid_top_range; /* the coarsest level's, over all its blocks */
#define FT_CLIP_BLOCK 16.0 /* FT_CLIP_BOUND_BLOCK (method_pgrid.c asserts it) */

vec2 ft_range_texel(int level, vec2 c)
{
    vec4 lv = u_pgm_level[level];
    float side = u_pcm_misc.x;
    float l = float(level);
    vec2 block = vec2(mod(l, u_pcm_misc.w), floor(l / u_pcm_misc.w));
    vec2 t = block * side + mod(lv.xy + c, side);
#if FT_ES3
    return texelFetch(u_pgrid_range, ivec2(t), 0).xy;
#else
    return texture2DLod(u_pgrid_range, (t + 0.5) / u_pgm_atlas_size, 0.0).xy;
#endif
}

/* block bt (in the level's texel blocks, wrapping) of level `level` */
vec2 ft_block_range_texel(int level, vec2 bt)
{
    float n = u_pcm_misc.x / FT_CLIP_BLOCK;
    float l = float(level);
    vec2 block = vec2(mod(l, u_pcm_misc.w), floor(l / u_pcm_misc.w));
    vec2 t = block * n + mod(bt, n);
#if FT_ES3
    return texelFetch(u_pgrid_block_range, ivec2(t), 0).xy;
#else
    return texture2DLod(u_pgrid_block_range, (t + 0.5) / (u_pgm_atlas_size / FT_CLIP_BLOCK),
                        0.0).xy;
#endif
}

/* The finest data's range over the box [a, b] of level-0 samples from the
 * eye: from the finest level whose resident cells hold the box within 2 x 2
 * of them, else the finest whose resident cells hold it within 2 x 2 of its
 * blocks (every level's ranges bound the finest data, so any level is
 * sound; the finest such is the tightest, and 2 x 2 cells of a level are
 * tighter than a block of any finer one), else the coarsest level's range
 * (the box is clamped into what is drawn, which that level holds). */
vec2 ft_region_minmax_cache(vec2 a, vec2 b)
{
    float top = u_pcm_misc.z - 1.0;
    float side = u_pcm_misc.x;
    int cells_at = -1, blocks_at = -1;
    vec2 c0 = vec2(0.0), c1 = vec2(0.0), b0 = vec2(0.0), b1 = vec2(0.0);
    for (int k = 0; k < FT_PGM_LEVELS; ++k) {
        if (float(k) > top || cells_at >= 0) {
            break;
        }
        vec4 bx = u_pcm_box[k]; /* resident samples, inclusive, from the level's base */
        float s = exp2(float(k));
        vec2 ua = (a + u_pgm_level[k].zw) / s, ub = (b + u_pgm_level[k].zw) / s;
        vec2 k0 = floor(ua), k1 = max(k0, ceil(ub) - 1.0);
        if (bx.z >= bx.x && bx.w >= bx.y && all(greaterThanEqual(k0, bx.xy)) &&
            all(lessThanEqual(k1, bx.zw - 1.0))) {
            if (all(lessThanEqual(k1 - k0, vec2(1.0)))) {
                cells_at = k;
                c0 = k0;
                c1 = k1;
            } else if (blocks_at < 0) {
                /* the blocks of the cells' south-west corner texels */
                vec2 t0 = mod(u_pgm_level[k].xy + k0, side);
                vec2 q0 = floor(t0 / FT_CLIP_BLOCK), q1 = floor((t0 + (k1 - k0)) / FT_CLIP_BLOCK);
                if (all(lessThanEqual(q1 - q0, vec2(1.0)))) {
                    blocks_at = k;
                    b0 = q0;
                    b1 = q1;
                }
            }
        }
    }
    vec2 r = vec2(1e30, -1e30);
    if (cells_at >= 0) {
        for (int y = 0; y < 2; ++y) {
            for (int x = 0; x < 2; ++x) {
                vec2 v = ft_range_texel(cells_at, min(c0 + vec2(float(x), float(y)), c1));
                r = vec2(min(r.x, v.x), max(r.y, v.y));
            }
        }
    } else if (blocks_at >= 0) {
        for (int y = 0; y < 2; ++y) {
            for (int x = 0; x < 2; ++x) {
                vec2 v = ft_block_range_texel(blocks_at, min(b0 + vec2(float(x), float(y)), b1));
                r = vec2(min(r.x, v.x), max(r.y, v.y));
            }
        }
    } else {
        r = u_pgrid_top_range;
    }
    return r;
}
