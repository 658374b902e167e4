/* pgrid_err_code.glsl - the error buffer's texel of method 'pgrid'
 * (src/lod/pgrid.h 3), for the error pass (pgrid_err.frag.glsl) and for the
 * picture pass writing it as its second output (terrain.frag.glsl):
 * rho = K * delta / (|P - eye| cos^2 theta), theta the angle off the view
 * axis (a perspective image stretches an angle by 1 / cos^2 theta radially:
 * 15x at 75 degrees, so at FOV 150 the edges need it); R = normalised error
 * (0 where rho <= gamma, else 1 - gamma / rho), G = 8-bit log code of rho
 * rounded up (>= 1/255 on terrain; the clear value 0 is sky), B = the grid
 * column's t = i / (cols - 1) (the column warp reads it back). */
uniform vec2 u_pgrid_err;  /* (K px, gamma px) */
uniform vec3 u_pgrid_fwd;  /* viewing camera's forward axis (world, unit) */

vec4 ft_pgrid_err_texel(vec3 pos_rel_eye_m, float delta_m, float col_t)
{
    float dist = max(length(pos_rel_eye_m), 1e-6);
    float c = max(dot(pos_rel_eye_m, u_pgrid_fwd) / dist, 1e-3);
    float rho = u_pgrid_err.x * max(delta_m, 0.0) / (dist * c * c);
    float e = rho > u_pgrid_err.y ? 1.0 - u_pgrid_err.y / rho : 0.0;
    /* code = ceil((log2 rho + 8) * 255 / 16) in [1, 255]; a little more so
     * the 8-bit store never rounds it down */
    float code = clamp(ceil((log2(max(rho, 1e-30)) + 8.0) * (255.0 / 16.0)), 1.0, 255.0);
    return vec4(e, (code + 0.25) / 255.0, col_t, 1.0);
}
