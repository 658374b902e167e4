/* pgrid_rc.vert.glsl - the ray-cast pass of method 'pgrid'
 * (shaders/pgrid_rc.frag.glsl): one instance a screen tile of u_rc_tile_px^2
 * (row-major, u_rc_tiles_w across), a_corner in [0, 1]^2 its corners. A tile
 * whose largest code (the tile pass, shaders/pgrid_rc_tiles.frag.glsl) is
 * under the threshold holds no pixel to ray cast: it is placed outside the
 * clip volume and never reaches the fragment shader. */
precision highp float;

FT_IN_VS vec2 a_corner;

#if FT_ES3
uniform sampler2D u_rc_tiles;
uniform float u_rc_thr;
uniform vec2 u_rc_size;      /* viewport px */
uniform float u_rc_tile_px;
uniform float u_rc_tiles_w;

void main()
{
    int across = int(u_rc_tiles_w + 0.5);
    ivec2 tile = ivec2(gl_InstanceID % across, gl_InstanceID / across);
    float code = floor(texelFetch(u_rc_tiles, tile, 0).r * 255.0 + 0.5);
    vec2 lo = vec2(tile) * u_rc_tile_px;
    vec2 hi = min(lo + u_rc_tile_px, u_rc_size);
    vec2 ndc = mix(lo, hi, a_corner) / u_rc_size * 2.0 - 1.0;
    gl_Position = (code >= u_rc_thr) ? vec4(ndc, 0.0, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
#else
void main()
{
    gl_Position = vec4(a_corner * 2.0 - 1.0, 0.0, 1.0);
}
#endif
