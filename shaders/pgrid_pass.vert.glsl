/* pgrid_pass.vert.glsl - a full-viewport triangle strip for the grid passes
 * of method 'pgrid' (vertex pass, quad-bound pass): a_uv in [0, 1]^2. */
precision highp float;

FT_IN_VS vec2 a_uv;

void main()
{
    gl_Position = vec4(a_uv * 2.0 - 1.0, 0.0, 1.0);
}
