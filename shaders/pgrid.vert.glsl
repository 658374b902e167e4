/* pgrid.vert.glsl - the error-bounded projective grid (method 'pgrid'): one
 * vertex of the persistent grid, as in pgm.vert.glsl (src/lod/pgm.h), plus
 *  - the row distribution (src/lod/pgrid.h 1): u_pgrid_dist = (mode, s0, s1,
 *    dep_s); mode 1 puts row j at y = tan(dep_s - atan2(1, sinh(mix(s0, s1,
 *    j / (rows - 1))))), mode 0 at mix(y0, y1, j / (rows - 1)) (pgm);
 *  - the object-space error (src/lod/pgrid.h 2): delta = max(hmax - h, h - hmin)
 *    over the box of the ground points of grid points (i +- 1, j +- 1), from
 *    the min/max atlas (levels >= 2) or the heights (levels 0, 1), passed on
 *    as v_delta_m (interpolated: a convex bound of the mesh's error);
 *    with FT_PGRID_TIGHT 1 (error_bound = residual, src/lod/pgrid.h 6) the
 *    vertex is read from the vertex pass and delta from the vertex-bound
 *    pass; a mesh pixel then takes its quad's bound, flat, and an envelope
 *    pixel the vertices' delta, interpolated (src/lod/pgrid.h 6).
 * The bound is a compile-time variant, not a uniform branch: a SIMD shader
 * core runs both sides of a branch under a mask (llvmpipe measured: the
 * tight draws took twice as long while the relief code rode along unused).
 * The placement is shaders/pgm_grid.glsl (shared with 'pgm'). */
#ifndef FT_PGRID_TIGHT
#define FT_PGRID_TIGHT 0 /* the relief bound (src/lod/method_pgrid.c picks) */
#endif
#include "curvature.glsl"
#include "pgm_grid.glsl"
#include "pgrid_rows.glsl"

uniform sampler2D u_pgrid_mm;    /* min (x < half) | max (x >= half) atlas, levels >= 2 */
uniform vec4 u_pgrid_mm_info;    /* (half width, height, pack min, pack range or 0) */
uniform vec4 u_pgrid_mm_level[FT_PGM_LEVELS]; /* origin xy, size zw per min/max level */
uniform float u_pgrid_mm_levels;
uniform float u_pgrid_envelope;  /* 0 the mesh; 1 (-1): the upper (lower) envelope */
uniform highp sampler2D u_pgrid_vtx;  /* the vertex pass: (pc.xy, height, level) */
uniform highp sampler2D u_pgrid_slope; /* vertex-bound pass: (dh/dgx, dh/dgy, delta, e_Q) */

FT_OUT_VS float v_col_t; /* the column's t = i / (cols - 1), for the column warp */

#if FT_PGRID_TIGHT && FT_ES3
/* a mesh pixel's bound: its quad's, from the vertex that ends both its
 * triangles (the fragment shader declares it flat too: FT_PGRID_FLAT_DELTA);
 * an envelope pixel's: the vertices' delta, interpolated */
flat out float v_delta_m;
out float v_env_delta_m;
#else
FT_OUT_VS float v_delta_m;
#endif


float ft_height_at(vec2 ij)
{
#if FT_ES3
    return ft_decode(texelFetch(u_heights, ivec2(ij), 0), u_pack);
#else
    return ft_decode(texture2DLod(u_heights, (ij + 0.5) / u_grid_size, 0.0), u_pack);
#endif
}

float ft_mm_texel(vec2 a)
{
#if FT_ES3
    return ft_decode(texelFetch(u_pgrid_mm, ivec2(a), 0), u_pgrid_mm_info.zw);
#else
    return ft_decode(texture2DLod(u_pgrid_mm, (a + 0.5) / vec2(2.0 * u_pgrid_mm_info.x,
                     u_pgrid_mm_info.y), 0.0), u_pgrid_mm_info.zw);
#endif
}

#ifdef FT_PGM_CLIP
#include "pgrid_cache_range.glsl"
#endif

/* min/max of the surface over grid box [a, b] (clamped), src/lod/pgrid.c rule */
vec2 ft_region_minmax(vec2 a, vec2 b)
{
    vec2 hi_g = u_grid_size - 1.0;
    a = clamp(a, vec2(0.0), hi_g);
    b = clamp(b, vec2(0.0), hi_g);
    float side = max(max(b.x - a.x, b.y - a.y), 1.0);
    float level = max(0.0, ceil(log2(side)));
    if (exp2(level - 1.0) >= side && level > 0.0) {
        level -= 1.0; /* log2 rounding */
    }
    level = min(level, u_pgrid_mm_levels - 1.0);
    float scale = exp2(level);
    vec2 r = vec2(1e30, -1e30);
    if (level < 1.5) {
        /* levels 0, 1: the samples under <= 2 x 2 texels of level 1 */
        vec2 i0 = clamp(floor(a / 2.0), vec2(0.0), floor((hi_g - 1.0) / 2.0));
        i0 = i0 * 2.0;
        for (int y = 0; y < 5; ++y) {
            for (int x = 0; x < 5; ++x) {
                vec2 q = min(i0 + vec2(float(x), float(y)), hi_g);
                float h = ft_height_at(q);
                r = vec2(min(r.x, h), max(r.y, h));
            }
        }
        return r;
    }
    vec4 lv = u_pgrid_mm_level[int(level)];
    vec2 t0 = min(floor(a / scale), lv.zw - 1.0);
    vec2 t1 = min(floor(b / scale), lv.zw - 1.0);
    if (t0.x > 0.0 && a.x == t0.x * scale) t0.x -= 1.0;
    if (t0.y > 0.0 && a.y == t0.y * scale) t0.y -= 1.0;
    t1 = min(t1, t0 + 1.0);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            vec2 q = min(t0 + vec2(float(x), float(y)), t1);
            vec2 o = lv.xy + q;
            r.x = min(r.x, ft_mm_texel(o));
            r.y = max(r.y, ft_mm_texel(o + vec2(u_pgrid_mm_info.x, 0.0)));
        }
    }
    return r;
}

/* Texel ij of a float target of size n (the tight variant runs on GLES 3
 * only; the GLSL ES 1.00 form exists so it validates in both). */
vec4 ft_target_texel(highp sampler2D tex, vec2 ij, vec2 n)
{
#if FT_ES3
    return texelFetch(tex, ivec2(ij), 0);
#else
    return texture2DLod(tex, (ij + 0.5) / n, 0.0);
#endif
}

void main()
{
    vec2 ij = vec2(a_uv.x, a_uv.y + u_pgm_grid.z);
    v_col_t = ij.x / u_pgm_grid.x;
    vec2 pc;
    float morph;
    vec3 s;
#if FT_PGRID_TIGHT
    /* the vertex as the vertex pass placed it (the quad bounds were computed
     * for exactly these positions and heights) */
    vec4 v = ft_target_texel(u_pgrid_vtx, ij, u_pgm_grid.xy + 1.0);
    vec4 g = ft_target_texel(u_pgrid_slope, ij, u_pgm_grid.xy + 1.0);
    pc = v.xy;
    morph = v.w;
    s = vec3(v.z, g.xy);
    v_delta_m = g.w; /* the bound of the quad this vertex ends (src/lod/pgrid.h 6) */
#if FT_ES3
    v_env_delta_m = g.z;
#endif
    /* the envelopes: the mesh moved up (down) by the vertex's bound, the
     * largest of its quads', encloses H */
    s.x += u_pgrid_envelope * g.z;
#else
    s = ft_pgm_vertex(ij, pc, morph);
    vec2 inv_cell = 1.0 / u_cell_m;
    vec2 lo = u_origin_rel_eye_m.xy;
    {
        vec2 c0 = ft_ground(ij + vec2(-1.0, -1.0)), c1 = ft_ground(ij + vec2(1.0, -1.0));
        vec2 c2 = ft_ground(ij + vec2(-1.0, 1.0)), c3 = ft_ground(ij + vec2(1.0, 1.0));
        vec2 bmin = min(min(min(c0, c1), min(c2, c3)), pc);
        vec2 bmax = max(max(max(c0, c1), max(c2, c3)), pc);
#ifdef FT_PGM_CLIP
        /* the triangles' vertices are clamped into what is drawn, and so
         * is the box that holds them */
        bmin = clamp(bmin, u_pcm_clamp.xy, u_pcm_clamp.zw);
        bmax = clamp(bmax, u_pcm_clamp.xy, u_pcm_clamp.zw);
        vec2 mm = ft_region_minmax_cache(bmin * inv_cell, bmax * inv_cell);
#else
        vec2 mm = ft_region_minmax((bmin - lo) * inv_cell, (bmax - lo) * inv_cell);
#endif
        /* the mesh interpolates the curvature drop linearly: over an edge of
         * length L the chord lies up to k L^2 / 4 under the curved surface */
        vec2 ext = bmax - bmin;
        float chord_m = 0.25 * u_earth_drop_per_m2 * dot(ext, ext);
        v_delta_m = max(max(mm.y - s.x, s.x - mm.x), 0.0) + chord_m;
        /* the envelopes (error pass, src/lod/pgrid.h 3): every vertex at the max
         * (u_pgrid_envelope 1) or the min (-1) of its region, which holds all
         * the cells around it, so each triangle lies on or above (below) the
         * surface over its footprint; between them the two hold every pixel
         * the true surface can cover, from above or from under the ground */
        if (u_pgrid_envelope > 0.5) {
            s.x = max(mm.y, s.x) + chord_m;
        } else if (u_pgrid_envelope < -0.5) {
            s.x = min(mm.x, s.x);
        }
    }
#endif
    ft_pgm_emit(pc, s, morph);
}
