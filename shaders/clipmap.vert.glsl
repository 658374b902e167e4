/* clipmap.vert.glsl - geometry clipmaps (method 'clipmap'): one template
 * vertex (block, stitch strip or corner cell) placed on a cached level.
 * The rule, and why, is in src/lod/clipmap.h; src/lod/clipmap.c
 * (ft_cm_vertex) is the same arithmetic on the CPU for the tests.
 *
 * Level l's heights are a side x side texture (u_cm_tex0) holding sample
 * (a, b) at texel (a mod side, b mod side); u_cm_tex1 is level l+1's (the
 * morph target; level l's own when there is no coarser level). */
precision highp float;

#include "curvature.glsl"
#include "decode.glsl"

uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m; /* terrain sample (0,0) minus the eye */
uniform mat4 u_view_proj;

uniform highp sampler2D u_cm_tex0;
uniform highp sampler2D u_cm_tex1;
uniform vec4 u_cm_place;   /* draw origin (level units) */
uniform vec4 u_cm_axes;    /* template x -> xy, template y -> zw */
uniform vec4 u_cm_clamp;   /* the draw's cells: x0, y0, x1, y1 */
uniform vec4 u_cm_data;    /* data extent in level units: lo xy, hi zw */
uniform vec4 u_cm_mbox;    /* transition sides of the drawn box (far away on others) */
uniform vec4 u_cm_level;   /* 2^l, T_l, 1 = a coarser level exists, side */
uniform vec4 u_cm_lattice; /* level-0 lattice sample at terrain sample (0,0); pack min, range */

FT_IN_VS vec2 a_uv;

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;

float ft_cm_texel0(vec2 s)
{
    vec2 t = mod(s, u_cm_level.w);
#if FT_ES3
    vec4 v = texelFetch(u_cm_tex0, ivec2(t), 0);
#else
    vec4 v = texture2DLod(u_cm_tex0, (t + 0.5) / u_cm_level.w, 0.0);
#endif
    return ft_decode(v, u_cm_lattice.zw);
}

float ft_cm_texel1(vec2 s)
{
    vec2 t = mod(s, u_cm_level.w);
#if FT_ES3
    vec4 v = texelFetch(u_cm_tex1, ivec2(t), 0);
#else
    vec4 v = texture2DLod(u_cm_tex1, (t + 0.5) / u_cm_level.w, 0.0);
#endif
    return ft_decode(v, u_cm_lattice.zw);
}

/* bilinear over the four samples around c; written as the CPU mirror's
 * mixf (a * (1 - t) + b * t), which returns a exactly at t = 0 */
float ft_cm_lerp(float a, float b, float t)
{
    return a * (1.0 - t) + b * t;
}

float ft_cm_height0(vec2 c)
{
    vec2 f = floor(c);
    vec2 r = c - f;
    float h00 = ft_cm_texel0(f);
    float h10 = ft_cm_texel0(f + vec2(1.0, 0.0));
    float h01 = ft_cm_texel0(f + vec2(0.0, 1.0));
    float h11 = ft_cm_texel0(f + vec2(1.0, 1.0));
    return ft_cm_lerp(ft_cm_lerp(h00, h10, r.x), ft_cm_lerp(h01, h11, r.x), r.y);
}

float ft_cm_height1(vec2 c)
{
    vec2 f = floor(c);
    vec2 r = c - f;
    float h00 = ft_cm_texel1(f);
    float h10 = ft_cm_texel1(f + vec2(1.0, 0.0));
    float h01 = ft_cm_texel1(f + vec2(0.0, 1.0));
    float h11 = ft_cm_texel1(f + vec2(1.0, 1.0));
    return ft_cm_lerp(ft_cm_lerp(h00, h10, r.x), ft_cm_lerp(h01, h11, r.x), r.y);
}

void main()
{
    vec2 c = u_cm_place.xy + u_cm_axes.xy * a_uv.x + u_cm_axes.zw * a_uv.y;
    c = clamp(clamp(c, u_cm_clamp.xy, u_cm_clamp.zw), u_cm_data.xy, u_cm_data.zw);

    /* morph weight: exactly 1 on a transition side of the drawn box */
    vec2 dlo = c - u_cm_mbox.xy;
    vec2 dhi = u_cm_mbox.zw - c;
    float d = min(min(dlo.x, dhi.x), min(dlo.y, dhi.y));
    float w = 0.0;
    if (u_cm_level.z > 0.0) {
        w = clamp((u_cm_level.y - d) / u_cm_level.y, 0.0, 1.0);
    }
    float h = 0.0;
    if (w < 1.0) {
        h = ft_cm_height0(c);
    }
    if (w > 0.0) {
        float hc = ft_cm_height1(c * 0.5);
        h = (w >= 1.0) ? hc : ft_cm_lerp(h, hc, w);
    }

    /* shading normal from the level's own samples around the nearest one */
    vec2 n = floor(c + 0.5);
    float dhx = ft_cm_texel0(n + vec2(1.0, 0.0)) - ft_cm_texel0(n - vec2(1.0, 0.0));
    float dhy = ft_cm_texel0(n + vec2(0.0, 1.0)) - ft_cm_texel0(n - vec2(0.0, 1.0));
    vec2 span_m = 2.0 * u_cm_level.x * u_cell_m;
    v_normal = normalize(vec3(-dhx / span_m.x, -dhy / span_m.y, 1.0));

    vec2 g = c * u_cm_level.x - u_cm_lattice.xy; /* terrain samples */
    v_height_m = h;
    v_pos_rel_eye_m = ft_earth_curve(u_origin_rel_eye_m + vec3(g * u_cell_m, h));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
