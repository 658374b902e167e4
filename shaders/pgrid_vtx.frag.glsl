/* pgrid_vtx.frag.glsl - the vertex pass of method 'pgrid' (src/pgrid.h 6):
 * one fragment per grid vertex (i, j) = the fragment's pixel, placed by the
 * same code as the grid's vertex shader (pgm_grid.glsl), written as
 * (ground point relative to the eye xy, drawn height, level) into an RGBA32F
 * target the quad-bound pass reads. GLES 3 only; the GLES 2 variant exists so
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
out vec4 o_vertex;
#define FT_FRAG_OUT o_vertex
#else
#define FT_FRAG_OUT gl_FragColor
#endif

void main()
{
    vec2 ij = floor(gl_FragCoord.xy);
    vec2 pc;
    float morph;
    vec3 s = ft_pgm_vertex(ij, pc, morph);
    FT_FRAG_OUT = vec4(pc, s.x, morph);
}
