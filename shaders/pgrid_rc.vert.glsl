/* pgrid_rc.vert.glsl - full-screen triangle strip for the ray-cast pass of
 * method 'pgrid' (shaders/pgrid_rc.frag.glsl). a_corner in [0, 1]^2. */
precision highp float;

FT_IN_VS vec2 a_corner;

void main()
{
    gl_Position = vec4(a_corner * 2.0 - 1.0, 0.0, 1.0);
}
