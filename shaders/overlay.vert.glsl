/* overlay.vert.glsl - annunciation overlay (red cross, reason text): 2D
 * geometry in whole pixels, origin at the top-left corner, y down. */
precision highp float;
uniform vec2 u_px_to_ndc;     /* (2 / width_px, 2 / height_px) */
FT_IN_VS vec2 a_pos;          /* pixels (GL_SHORT attribute) */
void main()
{
    gl_Position = vec4(a_pos.x * u_px_to_ndc.x - 1.0, 1.0 - a_pos.y * u_px_to_ndc.y, 0.0, 1.0);
}
