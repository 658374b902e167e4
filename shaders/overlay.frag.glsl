/* overlay.frag.glsl - one flat colour per draw (pure red or black). */
precision mediump float;
#if FT_ES3
out vec4 o_color;
#define FT_FRAG_COLOR o_color
#else
#define FT_FRAG_COLOR gl_FragColor
#endif
uniform vec4 u_color;
void main()
{
    FT_FRAG_COLOR = u_color;
}
