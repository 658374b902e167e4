/* pgrid.vert.glsl - the error-bounded projective grid (method 'pgrid'): one
 * vertex of the persistent grid, as in pgm.vert.glsl (src/pgm.h), plus
 *  - the row distribution (src/pgrid.h 1): u_pgrid_dist = (mode, s0, s1,
 *    dep_s); mode 1 puts row j at y = tan(dep_s - atan2(1, sinh(mix(s0, s1,
 *    j / (rows - 1))))), mode 0 at mix(y0, y1, j / (rows - 1)) (pgm);
 *  - the object-space error (src/pgrid.h 2): delta = max(hmax - h, h - hmin)
 *    over the box of the ground points of grid points (i +- 1, j +- 1), from
 *    the min/max atlas (levels >= 2) or the heights (levels 0, 1), passed on
 *    as v_delta_m (interpolated: a convex bound of the mesh's error).
 * Kept in step with pgm.vert.glsl by hand (that file belongs to 'pgm'). */
precision highp float;

#define FT_PGM_LEVELS 16

uniform sampler2D u_heights;
uniform vec2 u_grid_size;        /* samples (width, height) */
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m; /* grid sample (0,0) minus the viewing eye */
uniform mat4 u_view_proj;
uniform vec2 u_pack;             /* heights: packed (min, range); range 0 = float */

uniform sampler2D u_pgm_atlas;
uniform vec2 u_pgm_atlas_size;
uniform vec2 u_pgm_atlas_pack;   /* like u_pack, for the atlas */
uniform vec4 u_pgm_level[FT_PGM_LEVELS]; /* atlas origin (xy) and size (zw) per avg level */
uniform vec4 u_pgm_grid;         /* (cols - 1, rows - 1, band's first row, avg levels) */
uniform vec3 u_pgm_fwd;          /* sampling frame (world, unit) */
uniform vec3 u_pgm_right;
uniform vec3 u_pgm_up;
uniform vec4 u_pgm_rect;         /* (x0, y0, x1, y1): image plane at distance 1 */
uniform vec2 u_pgm_eye;          /* (h: sampling eye above the base plane, floor of -d_z) */

uniform vec4 u_pgrid_dist;       /* (mode, s0, s1, dep_s) */
uniform sampler2D u_pgrid_mm;    /* min (x < half) | max (x >= half) atlas, levels >= 2 */
uniform vec4 u_pgrid_mm_info;    /* (half width, height, pack min, pack range or 0) */
uniform vec4 u_pgrid_mm_level[FT_PGM_LEVELS]; /* origin xy, size zw per min/max level */
uniform float u_pgrid_mm_levels;
uniform float u_pgrid_envelope;  /* 0 the mesh; 1 (-1): the vertex at its region's max (min) */

FT_IN_VS vec2 a_uv;
FT_OUT_VS float v_delta_m;

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;
FT_OUT_VS float v_morph; /* the continuous level L + w (captured by the tests) */

float ft_decode(vec4 t, vec2 pack)
{
    if (pack.y > 0.0) {
        float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));
        return pack.x + pack.y * (q / 16777215.0);
    }
    return t.r;
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

/* Base-plane point of grid point ij, relative to the viewing eye (xy, m). */
vec2 ft_ground(vec2 ij)
{
    vec2 st = ij / u_pgm_grid.xy;
    vec2 xy = mix(u_pgm_rect.xy, u_pgm_rect.zw, st);
    if (u_pgrid_dist.x > 0.5) {
        float s = mix(u_pgrid_dist.y, u_pgrid_dist.z, st.y);
        float sh = 0.5 * (exp(s) - exp(-s));
        xy.y = tan(u_pgrid_dist.w - atan(1.0, sh));
    }
    vec3 d = u_pgm_fwd + xy.x * u_pgm_right + xy.y * u_pgm_up;
    return (u_pgm_eye.x / max(-d.z, u_pgm_eye.y)) * d.xy;
}

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

/* min/max of the surface over grid box [a, b] (clamped), src/pgrid.c rule */
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

void main()
{
    vec2 ij = vec2(a_uv.x, a_uv.y + u_pgm_grid.z);
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
    vec2 pc = clamp(p, lo, lo + (u_grid_size - 1.0) * u_cell_m);
    vec2 g = (pc - lo) * inv_cell;
    vec3 s = ft_level_sample(level, g);
    if (w > 0.0) {
        s = mix(s, ft_level_sample(level + 1.0, g), w);
    }
    {
        vec2 c0 = ft_ground(ij + vec2(-1.0, -1.0)), c1 = ft_ground(ij + vec2(1.0, -1.0));
        vec2 c2 = ft_ground(ij + vec2(-1.0, 1.0)), c3 = ft_ground(ij + vec2(1.0, 1.0));
        vec2 bmin = min(min(min(c0, c1), min(c2, c3)), pc);
        vec2 bmax = max(max(max(c0, c1), max(c2, c3)), pc);
        vec2 mm = ft_region_minmax((bmin - lo) * inv_cell, (bmax - lo) * inv_cell);
        v_delta_m = max(max(mm.y - s.x, s.x - mm.x), 0.0);
        /* the envelopes (error pass, src/pgrid.h 3): every vertex at the max
         * (u_pgrid_envelope 1) or the min (-1) of its region, which holds all
         * the cells around it, so each triangle lies on or above (below) the
         * surface over its footprint; between them the two hold every pixel
         * the true surface can cover, from above or from under the ground */
        if (u_pgrid_envelope > 0.5) {
            s.x = max(mm.y, s.x);
        } else if (u_pgrid_envelope < -0.5) {
            s.x = min(mm.x, s.x);
        }
    }
    v_normal = normalize(vec3(-s.y * inv_cell.x, -s.z * inv_cell.y, 1.0));
    v_morph = level + w;
    v_height_m = s.x;
    v_pos_rel_eye_m = vec3(pc, s.x + u_origin_rel_eye_m.z);
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
