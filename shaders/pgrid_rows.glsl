/* pgrid_rows.glsl - the row distribution of method 'pgrid' (src/lod/pgrid.h 1),
 * shared by the grid's vertex shader and its vertex pass; included after
 * pgm_grid.glsl, whose ft_row_y it defines. */
uniform vec4 u_pgrid_dist; /* (mode, s0, s1, dep_s) */
#define FT_PGRID_COL_BANDS 16
/* The column warp (src/lod/pgrid.h 1): the rectangle's x is cut in 16 equal
 * bands, and band b's columns are those with t in [T_b, T_b+1], T_b =
 * u_pgrid_cols[b] (T_0 = 0, T_16 = 1, increasing); u_pgrid_cols_on 0:
 * uniform columns. */
uniform float u_pgrid_cols[FT_PGRID_COL_BANDS + 1];
uniform float u_pgrid_cols_on;

float ft_col_x(float t, float x)
{
    if (u_pgrid_cols_on < 0.5) {
        return x;
    }
    float k = 0.0, t0 = u_pgrid_cols[0], t1 = u_pgrid_cols[1];
    for (int n = 1; n < FT_PGRID_COL_BANDS; ++n) {
        if (t >= u_pgrid_cols[n]) {
            k = float(n);
            t0 = u_pgrid_cols[n];
            t1 = u_pgrid_cols[n + 1];
        }
    }
    /* past either end: the end band's slope */
    float u = (k + (t - t0) / (t1 - t0)) / float(FT_PGRID_COL_BANDS);
    return mix(u_pgm_rect.x, u_pgm_rect.z, u);
}

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
