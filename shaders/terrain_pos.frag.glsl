/* terrain_pos.frag.glsl - the position pass for the error metric: writes the
 * rendered surface point (relative to the eye, metres) into an RGBA32F
 * target; alpha 1 marks terrain (the clear value has alpha 0). */
precision highp float;

#include "frag_out.glsl"

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;

void main()
{
    FT_FRAG_COLOR = vec4(v_pos_rel_eye_m, 1.0);
}
