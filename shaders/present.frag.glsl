/* present.frag.glsl - copies the frame texel for texel (NEAREST, same size). */
precision mediump float;
#include "frag_out.glsl"
#if FT_ES3
#define FT_TEXTURE texture
#else
#define FT_TEXTURE texture2D
#endif
uniform sampler2D u_frame;
FT_IN_FS vec2 v_uv;
void main()
{
    /* opaque: the colour target's alpha marks unmeasured terrain */
    FT_FRAG_COLOR = vec4(FT_TEXTURE(u_frame, v_uv).rgb, 1.0);
}
