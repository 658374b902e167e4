/* terrain.vert.glsl - one template patch placed on the grid.
 *
 * The CPU sends only integers (template vertex, patch origin, stride); the
 * height comes from a vertex texture. Positions are relative to the eye:
 * u_origin_rel_eye_m = world(sample 0,0) - eye, computed in double on the
 * CPU, so huge world coordinates never reach float. */
precision highp float;

#include "curvature.glsl"

uniform sampler2D u_heights;
uniform vec2 u_grid_size;        /* samples (width, height) */
uniform vec2 u_patch_origin;     /* grid coordinates of template vertex (0,0) */
uniform float u_patch_stride;    /* grid cells per template cell */
uniform vec2 u_cell_m;           /* sample spacing in metres (x, y) */
uniform vec3 u_origin_rel_eye_m;
uniform mat4 u_view_proj;        /* rotation-only view, then projection */
uniform vec4 u_clamp_box;        /* drawn samples: (x0, y0, x1, y1) grid coords */
uniform vec2 u_pack;             /* packed texels: (min_m, range_m); range 0 = float texels */

FT_IN_VS vec2 a_uv;

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;

float ft_height(vec2 g)
{
    vec2 gc = clamp(g, vec2(0.0), u_grid_size - 1.0);
#if FT_ES3
    vec4 t = texelFetch(u_heights, ivec2(gc), 0);
#else
    vec4 t = texture2DLod(u_heights, (gc + 0.5) / u_grid_size, 0.0);
#endif
    if (u_pack.y > 0.0) {
        /* 24-bit fixed point in RGB (see gpu_terrain.c): exact in highp. */
        float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));
        return u_pack.x + u_pack.y * (q / 16777215.0);
    }
    return t.r;
}

void main()
{
    vec2 g = clamp(u_patch_origin + a_uv * u_patch_stride, u_clamp_box.xy, u_clamp_box.zw);
    float h = ft_height(g);

    /* Central differences, one-sided at the grid edge. */
    vec2 lo = max(g - 1.0, vec2(0.0));
    vec2 hi = min(g + 1.0, u_grid_size - 1.0);
    float dhx = (ft_height(vec2(hi.x, g.y)) - ft_height(vec2(lo.x, g.y))) / ((hi.x - lo.x) * u_cell_m.x);
    float dhy = (ft_height(vec2(g.x, hi.y)) - ft_height(vec2(g.x, lo.y))) / ((hi.y - lo.y) * u_cell_m.y);
    v_normal = normalize(vec3(-dhx, -dhy, 1.0));

    v_height_m = h;
    v_pos_rel_eye_m = ft_earth_curve(u_origin_rel_eye_m + vec3(g * u_cell_m, h));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
