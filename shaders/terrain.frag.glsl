/* terrain.frag.glsl - the terrain colour (shade.glsl) of the height and
 * normal the method drew. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#include "frag_out.glsl"

#include "shade_relative.glsl"
#include "shade_grid.glsl"
#include "shade_haze.glsl"
#include "shade.glsl"

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;

void main()
{
    FT_FRAG_COLOR = ft_colour(v_height_m, v_normal, v_pos_rel_eye_m);
}
