/* pgrid_rc_tiles.frag.glsl - method 'pgrid': the ray caster's tile pass
 * (src/lod/pgrid.h 4), GLES 3 only. One fragment a screen tile of
 * u_rc_tile_px^2: the largest error code (G of the error buffer) over the
 * tile and a one-pixel border around it, i.e. over every pixel a pixel of
 * the tile takes its dilated code from. Written to an 8-bit target, so the
 * code k / 255 comes back as k. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#if FT_ES3
out vec4 o_color;

#define FT_RC_TILE_MAX 64 /* pgrid.raycast_tile_px's largest value */

uniform sampler2D u_err;
uniform vec2 u_rc_size;     /* the error buffer's size, px */
uniform float u_rc_tile_px;

void main()
{
    ivec2 lim = ivec2(u_rc_size) - 1;
    int side = int(u_rc_tile_px) + 2;
    ivec2 base = ivec2(gl_FragCoord.xy) * int(u_rc_tile_px) - 1;
    float code = 0.0;
    for (int y = 0; y < FT_RC_TILE_MAX + 2; ++y) {
        if (y >= side) break;
        for (int x = 0; x < FT_RC_TILE_MAX + 2; ++x) {
            if (x >= side) break;
            code = max(code, texelFetch(u_err, clamp(base + ivec2(x, y), ivec2(0), lim), 0).g);
        }
    }
    o_color = vec4(code, 0.0, 0.0, 1.0);
}
#else
/* never built on GLES 2 (no ray casting there); this variant only validates */
void main()
{
    gl_FragColor = vec4(0.0);
}
#endif
