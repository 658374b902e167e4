/* pgrid_quad.frag.glsl - the quad-bound pass of method 'pgrid' (src/pgrid.h
 * 6; src/pgrid.c ft_pgrid_quad_bound is the same rule in double): one
 * fragment per grid quad (i, j), corners (i..i+1, j..j+1) read from the vertex
 * pass; writes e_Q + the curvature chord (metres) into R. GLES 3 only; the
 * GLES 2 variant exists so every shader validates in both languages. */
precision highp float;

#if FT_ES3
out vec4 o_bound;
#define FT_FRAG_OUT o_bound
#else
#define FT_FRAG_OUT gl_FragColor
#endif

#define FT_RES_LEVELS 16

uniform highp sampler2D u_heights;
uniform highp sampler2D u_pgrid_vtx;  /* vertex pass: (pc.xy rel. eye, h, level) */
uniform highp sampler2D u_pgrid_res;  /* residual atlas, levels >= 1 */
uniform vec2 u_grid_size;             /* samples */
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m;
uniform vec2 u_pack;                  /* heights: packed (min, range); range 0 = float */
uniform float u_earth_drop_per_m2;
uniform vec4 u_pgrid_res_level[FT_RES_LEVELS]; /* atlas origin xy, size zw */
uniform float u_pgrid_res_levels;

float ft_decode(vec4 t, vec2 pack)
{
    if (pack.y > 0.0) {
        float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));
        return pack.x + pack.y * (q / 16777215.0);
    }
    return t.r;
}

#if FT_ES3
float ft_h(vec2 ij) { return ft_decode(texelFetch(u_heights, ivec2(ij), 0), u_pack); }
vec4 ft_vtx(vec2 ij) { return texelFetch(u_pgrid_vtx, ivec2(ij), 0); }
float ft_res(vec2 a) { return texelFetch(u_pgrid_res, ivec2(a), 0).r; }
#else
float ft_h(vec2 ij) { return 0.0; }
vec4 ft_vtx(vec2 ij) { return vec4(0.0); }
float ft_res(vec2 a) { return 0.0; }
#endif

void main()
{
    vec2 q = floor(gl_FragCoord.xy);
    vec4 c0 = ft_vtx(q), c1 = ft_vtx(q + vec2(1.0, 0.0));
    vec4 c2 = ft_vtx(q + vec2(0.0, 1.0)), c3 = ft_vtx(q + vec2(1.0, 1.0));
    vec2 lo = u_origin_rel_eye_m.xy;
    vec2 inv_cell = 1.0 / u_cell_m;
    vec2 g0 = (c0.xy - lo) * inv_cell, g1 = (c1.xy - lo) * inv_cell;
    vec2 g2 = (c2.xy - lo) * inv_cell, g3 = (c3.xy - lo) * inv_cell;
    vec2 hi_g = u_grid_size - 1.0;
    vec2 a = clamp(min(min(g0, g1), min(g2, g3)), vec2(0.0), hi_g);
    vec2 b = clamp(max(max(g0, g1), max(g2, g3)), vec2(0.0), hi_g);
    float side = max(max(b.x - a.x, b.y - a.y), 1.0);
    float level = max(0.0, ceil(log2(side)));
    if (level > 0.0 && exp2(level - 1.0) >= side) {
        level -= 1.0; /* log2 rounding */
    }
    if (exp2(level) < side) {
        level += 1.0;
    }
    level = min(level, u_pgrid_res_levels - 1.0);
    float scale = exp2(level);
    vec2 nodes = floor((hi_g - 1.0) / scale) + 1.0; /* nodes at this level */
    vec2 n0 = min(floor(a / scale), nodes - 1.0);
    vec2 n1 = min(min(floor(b / scale), nodes - 1.0), n0 + 1.0);
    float e = 0.0;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            vec2 n = min(n0 + vec2(float(x), float(y)), n1);
            vec2 p0 = n * scale;
            vec2 p1 = min(p0 + scale, hi_g);
            float h00 = ft_h(p0), h10 = ft_h(vec2(p1.x, p0.y));
            float h01 = ft_h(vec2(p0.x, p1.y)), h11 = ft_h(p1);
            float m = 0.25 * (h00 + h10 + h01 + h11);
            float bx = 0.5 * (h10 + h11 - h00 - h01);
            float by = 0.5 * (h01 + h11 - h00 - h10);
            float r = level < 0.5 ? 0.25 * abs(h00 - h10 - h01 + h11)
                                  : ft_res(u_pgrid_res_level[int(level)].xy + n);
            vec2 inv = 1.0 / (p1 - p0);
            vec2 u0 = (g0 - p0) * inv - 0.5, u1 = (g1 - p0) * inv - 0.5;
            vec2 u2 = (g2 - p0) * inv - 0.5, u3 = (g3 - p0) * inv - 0.5;
            float off = max(max(abs(m + bx * u0.x + by * u0.y - c0.z),
                                abs(m + bx * u1.x + by * u1.y - c1.z)),
                            max(abs(m + bx * u2.x + by * u2.y - c2.z),
                                abs(m + bx * u3.x + by * u3.y - c3.z)));
            e = max(e, r + off);
        }
    }
    /* the mesh interpolates the curvature drop linearly: over a span of
     * length L the chord lies up to k L^2 / 4 under the curved surface */
    vec2 ext = max(max(c0.xy, c1.xy), max(c2.xy, c3.xy)) - min(min(c0.xy, c1.xy), min(c2.xy, c3.xy));
    FT_FRAG_OUT = vec4(e + 0.25 * u_earth_drop_per_m2 * dot(ext, ext), 0.0, 0.0, 1.0);
}
