/* pgrid_shape.frag.glsl - the vertex-bound pass of method 'pgrid'
 * (src/lod/pgrid.h 6): one fragment per grid vertex (i, j), after the vertex
 * pass and the quad-bound pass. Writes (dh/dgx, dh/dgy, delta, e_Q): the
 * slope the vertex pass found; the vertex's delta, the largest bound of the
 * <= 4 quads around it (every triangle touching the vertex lies in one), by
 * which the envelopes move it and with which their pixels are coded; and
 * the bound of quad (i - 1, j - 1), whose two triangles end at this vertex
 * (its mesh pixels' bound, handed on flat). The grid's draws then read 2
 * texels a vertex (this and the vertex pass's) instead of 6: on a
 * rasteriser whose vertex stage runs on one thread (llvmpipe) the 4 quad
 * fetches of every vertex took about a sixth of a draw (the picture at
 * 1024x512: 93 ms without them against 112).
 * GLES 3 only; the GLES 2 variant exists so every shader validates in both
 * languages. */
precision highp float;

#if FT_ES3
out vec4 o_shape;
#define FT_FRAG_OUT o_shape
#else
#define FT_FRAG_OUT gl_FragColor
#endif

uniform highp sampler2D u_pgrid_slope; /* vertex pass: (dh/dgx, dh/dgy, 0, 0) */
uniform highp sampler2D u_pgrid_quad;  /* quad-bound pass: e_Q (m) in R */
uniform vec2 u_pgrid_cells;            /* the grid's (cols - 1, rows - 1) */

#if FT_ES3
vec4 ft_fetch(highp sampler2D s, vec2 ij) { return texelFetch(s, ivec2(ij), 0); }
#else
vec4 ft_fetch(highp sampler2D s, vec2 ij) { return vec4(0.0); }
#endif

void main()
{
    vec2 ij = floor(gl_FragCoord.xy);
    vec2 last = u_pgrid_cells - 1.0;
    float d = 0.0, ends = 0.0;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            vec2 q = clamp(ij - vec2(float(x), float(y)), vec2(0.0), last);
            float e = ft_fetch(u_pgrid_quad, q).r;
            d = max(d, e);
            if (x == 1 && y == 1) {
                ends = e; /* quad (i - 1, j - 1), whose triangles end here */
            }
        }
    }
    FT_FRAG_OUT = vec4(ft_fetch(u_pgrid_slope, ij).xy, d, ends);
}
