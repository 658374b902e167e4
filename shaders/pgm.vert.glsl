/* pgm.vert.glsl - persistent grid mapping (method 'pgm'): one vertex of the
 * persistent grid, rows uniform on the sampling image plane. The placement
 * is shaders/pgm_grid.glsl (src/lod/pgm.h). */
#include "curvature.glsl"
#include "pgm_grid.glsl"

float ft_row_y(float t, float y)
{
    return y;
}

float ft_col_x(float t, float x)
{
    return x;
}

void main()
{
    vec2 ij = vec2(a_uv.x, a_uv.y + u_pgm_grid.z);
    vec2 pc;
    float morph;
    vec3 s = ft_pgm_vertex(ij, pc, morph);
    ft_pgm_emit(pc, s, morph);
}
