/* overlay.frag.glsl - one flat colour per draw (pure red or black). */
precision mediump float;
#include "frag_out.glsl"
uniform vec4 u_color;
void main()
{
    FT_FRAG_COLOR = u_color;
}
