/* bintree.vert.glsl - one triangular tile of the bintree, drawn from the one
 * template every tile shares (the unit right triangle bisected 2k times).
 *
 * a_uv are the template vertex's leg coordinates (a, b), multiples of 2^-k:
 *   grid = apex + a * (left - apex) + b * (right - apex)
 * an exact integer grid coordinate for every tile the selection emits, so
 * every tile that holds a grid vertex computes the same coordinate. The CPU
 * sends only the three corner grid coordinates per tile (instanced on GLES 3,
 * as uniforms per draw on GLES 2).
 *
 * Geomorphing is a function of the grid vertex alone (src/bintree.c,
 * ft_bt_vertex_morph, is the same rule on the CPU): the vertex is the
 * midpoint of a coarse edge e0-e1 and enters the mesh when one diamond c
 * splits; its height slides from (h(e0) + h(e1)) / 2 to h(g) as
 *   rho = K * err(c) / (|P - eye| cos^2 theta)  goes from split (the
 * selection's split threshold, f * tau) to tau; theta is P's angle off the
 * view axis (capped at the frustum corner's), the stretch a perspective
 * image gives an angle there, as the selection's box bound does. Every tile that draws the vertex therefore
 * computes the same position from the same inputs: no cracks, even mid-morph.
 *
 * Padding: coordinates are clamped into the real grid; clamped vertices do
 * not morph. All arithmetic on grid coordinates is on integers below 2^24
 * (exact in highp float; divisions are by powers of two). */
precision highp float;

#include "curvature.glsl"

uniform sampler2D u_heights;
uniform vec2 u_grid_size;
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m;
uniform mat4 u_view_proj;
uniform vec2 u_pack;

uniform sampler2D u_bt_err;   /* saturated diamond error (m) on the split-vertex lattice */
uniform vec2 u_bt_err_pack;   /* like u_pack, for u_bt_err */
uniform vec3 u_bt_lattice;    /* (2^k, lattice side, N = 2^n) */
uniform vec4 u_bt_morph;      /* (K px, split px, tau - split px, on) */
uniform vec4 u_bt_axis;       /* (view axis (world, unit), cos of the frustum corner) */

FT_IN_VS vec2 a_uv;
#if FT_ES3
in vec4 i_tile0; /* apex.xy, left.xy */
in vec2 i_tile1; /* right.xy */
#else
uniform vec4 u_tile0;
uniform vec2 u_tile1;
#define i_tile0 u_tile0
#define i_tile1 u_tile1
#endif

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;
FT_OUT_VS float v_morph; /* 1 = at its own height (captured by the crack tests) */

#include "decode.glsl"

float ft_height(vec2 g)
{
    vec2 gc = clamp(g, vec2(0.0), u_grid_size - 1.0);
#if FT_ES3
    vec4 t = texelFetch(u_heights, ivec2(gc), 0);
#else
    vec4 t = texture2DLod(u_heights, (gc + 0.5) / u_grid_size, 0.0);
#endif
    return ft_decode(t, u_pack);
}

/* Error of the diamond that inserts grid vertex g, and the coarse edge it
 * bisects. Negative when g never morphs. */
float ft_morph_error(vec2 g, out vec2 e0, out vec2 e1)
{
    e0 = g;
    e1 = g;
    float s = 0.0; /* lowest power of two that does not divide both coordinates */
    float p = 1.0;
    for (int i = 0; i < 16; ++i) {
        if (mod(g.x, 2.0 * p) != 0.0 || mod(g.y, 2.0 * p) != 0.0) {
            s = p;
            break;
        }
        p *= 2.0;
    }
    float sd = 2.0 * s * u_bt_lattice.x; /* square side of the inserting diamond */
    if (s == 0.0 || sd > u_bt_lattice.z) {
        return -1.0;
    }
    bool odd_x = mod(g.x, 2.0 * s) != 0.0;
    bool odd_y = mod(g.y, 2.0 * s) != 0.0;
    vec2 base = floor(g / sd) * sd;
    vec2 c;
    if (odd_x && odd_y) {
        vec2 q = (g - s) / (2.0 * s);
        float dy = (mod(q.x + q.y, 2.0) == 0.0) ? s : -s;
        e0 = g - vec2(s, dy);
        e1 = g + vec2(s, dy);
        c = base + 0.5 * sd;
    } else {
        vec2 d = odd_x ? vec2(s, 0.0) : vec2(0.0, s);
        e0 = g - d;
        e1 = g + d;
        vec2 r = g - base;
        if (r.y <= r.x && r.y <= sd - r.x) {
            c = base + vec2(0.5 * sd, 0.0);
        } else if (r.y >= r.x && r.y >= sd - r.x) {
            c = base + vec2(0.5 * sd, sd);
        } else if (r.x <= r.y && r.x <= sd - r.y) {
            c = base + vec2(0.0, 0.5 * sd);
        } else {
            c = base + vec2(sd, 0.5 * sd);
        }
    }
    vec2 top = max(g, max(e0, e1));
    if (top.x > u_grid_size.x - 1.0 || top.y > u_grid_size.y - 1.0) {
        e0 = g;
        e1 = g;
        return -1.0;
    }
    vec2 lc = c / u_bt_lattice.x;
#if FT_ES3
    vec4 t = texelFetch(u_bt_err, ivec2(lc), 0);
#else
    vec4 t = texture2DLod(u_bt_err, (lc + 0.5) / u_bt_lattice.y, 0.0);
#endif
    return ft_decode(t, u_bt_err_pack);
}

void main()
{
    vec2 apex = i_tile0.xy;
    vec2 g_raw = apex + a_uv.x * (i_tile0.zw - apex) + a_uv.y * (i_tile1 - apex);
    vec2 g = min(g_raw, u_grid_size - 1.0); /* padding collapses onto the grid edge */
    float h = ft_height(g);

    vec2 lo = max(g - 1.0, vec2(0.0));
    vec2 hi = min(g + 1.0, u_grid_size - 1.0);
    float dhx = (ft_height(vec2(hi.x, g.y)) - ft_height(vec2(lo.x, g.y))) / ((hi.x - lo.x) * u_cell_m.x);
    float dhy = (ft_height(vec2(g.x, hi.y)) - ft_height(vec2(g.x, lo.y))) / ((hi.y - lo.y) * u_cell_m.y);
    v_normal = normalize(vec3(-dhx, -dhy, 1.0));

    float w = 1.0;
    if (u_bt_morph.w > 0.5) {
        vec2 e0, e1;
        float err_m = ft_morph_error(g_raw, e0, e1);
        if (err_m >= 0.0) {
            vec3 p_true = ft_earth_curve(u_origin_rel_eye_m + vec3(g * u_cell_m, h));
            float dist = max(length(p_true), 1e-3);
            float c = max(dot(p_true, u_bt_axis.xyz) / dist, u_bt_axis.w);
            float rho = u_bt_morph.x * err_m / (dist * c * c);
            w = clamp((rho - u_bt_morph.y) / u_bt_morph.z, 0.0, 1.0);
            h = mix(0.5 * (ft_height(e0) + ft_height(e1)), h, w);
        }
    }
    v_morph = w;
    v_height_m = h;
    v_pos_rel_eye_m = ft_earth_curve(u_origin_rel_eye_m + vec3(g * u_cell_m, h));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
