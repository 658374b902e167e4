/* present.vert.glsl - a full-window quad that shows the offscreen frame on a
 * window surface (the frame itself is always drawn into the renderer's FBO). */
precision highp float;
FT_IN_VS vec2 a_corner;       /* (0,0) .. (1,1) */
FT_OUT_VS vec2 v_uv;
void main()
{
    v_uv = a_corner;
    gl_Position = vec4(a_corner * 2.0 - 1.0, 0.0, 1.0);
}
