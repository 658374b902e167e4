/* bintree.vert.glsl - one triangular tile of the bintree, drawn from the one
 * template every tile shares (the unit right triangle bisected 2k times).
 *
 * a_uv are the template vertex's leg coordinates (a, b), multiples of 2^-k:
 *   grid = apex + a * (left - apex) + b * (right - apex)
 * which is an exact integer grid coordinate for every tile the selection
 * emits (level <= 2n - 2k), so both tiles along a shared edge compute
 * bit-identical grid coordinates, heights and positions. The CPU sends only
 * the three corner grid coordinates per tile (instanced on GLES 3, as
 * uniforms per draw on GLES 2). */
precision highp float;

uniform sampler2D u_heights;
uniform vec2 u_grid_size;
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m;
uniform mat4 u_view_proj;
uniform vec2 u_pack;

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

float ft_height(vec2 g)
{
    vec2 gc = clamp(g, vec2(0.0), u_grid_size - 1.0);
#if FT_ES3
    vec4 t = texelFetch(u_heights, ivec2(gc), 0);
#else
    vec4 t = texture2DLod(u_heights, (gc + 0.5) / u_grid_size, 0.0);
#endif
    if (u_pack.y > 0.0) {
        float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));
        return u_pack.x + u_pack.y * (q / 16777215.0);
    }
    return t.r;
}

void main()
{
    vec2 apex = i_tile0.xy;
    vec2 g = apex + a_uv.x * (i_tile0.zw - apex) + a_uv.y * (i_tile1 - apex);
    float h = ft_height(g);

    vec2 lo = max(g - 1.0, vec2(0.0));
    vec2 hi = min(g + 1.0, u_grid_size - 1.0);
    float dhx = (ft_height(vec2(hi.x, g.y)) - ft_height(vec2(lo.x, g.y))) / ((hi.x - lo.x) * u_cell_m.x);
    float dhy = (ft_height(vec2(g.x, hi.y)) - ft_height(vec2(g.x, lo.y))) / ((hi.y - lo.y) * u_cell_m.y);
    v_normal = normalize(vec3(-dhx, -dhy, 1.0));

    v_height_m = h;
    v_pos_rel_eye_m = u_origin_rel_eye_m + vec3(g * u_cell_m, h);
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
