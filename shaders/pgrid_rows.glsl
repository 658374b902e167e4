/* pgrid_rows.glsl - the row distribution of method 'pgrid' (src/lod/pgrid.h 1),
 * shared by the grid's vertex shader and its vertex pass; included after
 * pgm_grid.glsl, whose ft_row_y it defines. */
uniform vec4 u_pgrid_dist; /* (mode, s0, s1, dep_s) */

/* mode 1 (view) spaces rows evenly in s = asinh(ground distance / h); mode 0
 * keeps pgm's uniform y */
float ft_row_y(float t, float y)
{
    if (u_pgrid_dist.x > 0.5) {
        float s = mix(u_pgrid_dist.y, u_pgrid_dist.z, t);
        float sh = 0.5 * (exp(s) - exp(-s));
        return tan(u_pgrid_dist.w - atan(1.0, sh));
    }
    return y;
}
