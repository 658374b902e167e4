/* terrain.frag.glsl - the terrain colour (shade.glsl) of the height and
 * normal the method drew. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#if FT_ES3
out vec4 o_color;
#define FT_FRAG_COLOR o_color
#else
#define FT_FRAG_COLOR gl_FragColor
#endif

#include "shade_relative.glsl"
#include "shade.glsl"

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;

void main()
{
    vec3 rgb = ft_shade(v_height_m, v_normal);
    float alpha = 1.0;
#ifdef FT_SHADE_GRID
    rgb = ft_ground_grid(rgb, v_pos_rel_eye_m.xy, length(v_pos_rel_eye_m));
#endif
#ifdef FT_SHADE_VOID
    if (ft_unmeasured(v_pos_rel_eye_m.xy) > 0.5) {
        rgb = ft_mark_unmeasured(rgb);
        alpha = 0.5;
    }
#endif
#ifdef FT_SHADE_HAZE
    rgb = ft_haze(rgb, length(v_pos_rel_eye_m));
#endif
    FT_FRAG_COLOR = vec4(rgb, alpha);
}
