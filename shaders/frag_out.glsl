/* frag_out.glsl - the fragment colour output under one name: FT_FRAG_COLOR
 * is o_color (GLSL ES 3.00) or gl_FragColor (1.00). */
#if FT_ES3
layout(location = 0) out vec4 o_color;
#define FT_FRAG_COLOR o_color
#else
#define FT_FRAG_COLOR gl_FragColor
#endif
