/* pgrid_vtx.frag.glsl - the vertex pass of method 'pgrid' (src/lod/pgrid.h 6):
 * one fragment per grid vertex (i, j) = the fragment's pixel, placed by the
 * same code as the grid's vertex shader (pgm_grid.glsl), written as
 * (ground point relative to the eye xy, drawn height, level) and the slope
 * into two RGBA32F targets: the quad-bound pass reads the first, and the
 * grid's four draws (mesh, error buffer, two envelopes) read both instead of
 * placing every vertex four times. GLES 3 only; the GLES 2 variant exists so
 * every shader validates in both languages. */
#define FT_PGM_GRID_NO_IO 1
#if !FT_ES3
/* GLSL ES 1.00 has no texture2DLod in a fragment shader (the variant only
 * has to compile: the pass runs on GLES 3 only) */
#define texture2DLod(s, uv, lod) texture2D(s, uv)
#endif
#include "pgm_grid.glsl"
#include "pgrid_rows.glsl"

#if FT_ES3
layout(location = 0) out vec4 o_vertex;  /* (pc.xy relative to the eye, height, level) */
layout(location = 1) out vec4 o_slope;   /* (dh/dgx, dh/dgy, 0, 0): the normal */
#endif

void main()
{
    vec2 ij = floor(gl_FragCoord.xy);
    vec2 pc;
    float morph;
    vec3 s = ft_pgm_vertex(ij, pc, morph);
#if FT_ES3
    o_vertex = vec4(pc, s.x, morph);
    o_slope = vec4(s.yz, 0.0, 0.0);
#else
    gl_FragColor = vec4(pc, s.x, morph);
#endif
}
