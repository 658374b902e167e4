/* pgrid_err.frag.glsl - the error buffer of method 'pgrid' (src/lod/pgrid.h 3):
 * rho = K * delta / (|P - eye| cos^2 theta) per fragment, theta the angle
 * off the view axis (a perspective image stretches an angle by 1 / cos^2
 * theta radially: 15x at 75 degrees, so at FOV 150 the edges need it); R = normalised error
 * (0 where rho <= gamma, else 1 - gamma / rho), G = 8-bit log code of rho
 * rounded up (>= 1/255 on terrain; the clear value 0 is sky). */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#include "frag_out.glsl"

uniform vec2 u_pgrid_err;  /* (K px, gamma px) */
uniform vec3 u_pgrid_fwd;  /* viewing camera's forward axis (world, unit) */

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;
FT_IN_FS float v_delta_m;

void main()
{
    float dist = max(length(v_pos_rel_eye_m), 1e-6);
    float c = max(dot(v_pos_rel_eye_m, u_pgrid_fwd) / dist, 1e-3);
    float rho = u_pgrid_err.x * max(v_delta_m, 0.0) / (dist * c * c);
    float e = rho > u_pgrid_err.y ? 1.0 - u_pgrid_err.y / rho : 0.0;
    /* code = ceil((log2 rho + 8) * 255 / 16) in [1, 255]; a little more so
     * the 8-bit store never rounds it down */
    float code = clamp(ceil((log2(max(rho, 1e-30)) + 8.0) * (255.0 / 16.0)), 1.0, 255.0);
    FT_FRAG_COLOR = vec4(e, (code + 0.25) / 255.0, 0.0, 1.0);
}
