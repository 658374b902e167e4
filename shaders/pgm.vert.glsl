/* pgm.vert.glsl - persistent grid mapping (method 'pgm'): one vertex of the
 * persistent grid, rows uniform on the sampling image plane. The placement
 * is shaders/pgm_grid.glsl (src/pgm.h). */
#include "pgm_grid.glsl"

float ft_row_y(float t, float y)
{
    return y;
}

void main()
{
    vec2 ij = vec2(a_uv.x, a_uv.y + u_pgm_grid.z);
    vec2 pc;
    float morph;
    vec3 s = ft_pgm_vertex(ij, pc, morph);
    vec2 inv_cell = 1.0 / u_cell_m;
    v_normal = normalize(vec3(-s.y * inv_cell.x, -s.z * inv_cell.y, 1.0));
    v_morph = morph;
    v_height_m = s.x;
    v_pos_rel_eye_m = vec3(pc, s.x + u_origin_rel_eye_m.z);
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}
