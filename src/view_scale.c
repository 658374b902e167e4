/* view_scale.c - the off-axis pixel gain (view_scale.h). */
#include "view_scale.h"

#include <math.h>

double ft_view_corner_cos(const ft_camera *c)
{
    const double ty = tan(0.5 * c->fovy_rad);
    const double tx = ty * (double)c->width_px / (double)(c->height_px > 0u ? c->height_px : 1u);
    return 1.0 / sqrt(1.0 + tx * tx + ty * ty);
}

double ft_view_offaxis_gain(const double fwd[3], double corner_cos, const double lo[3],
                            const double hi[3])
{
    if (!(corner_cos > 0.0) || corner_cos > 1.0) {
        corner_cos = 1e-3; /* a degenerate frustum: the largest gain pgrid allows too */
    }
    const double worst = 1.0 / (corner_cos * corner_cos);
    double c[3], r2 = 0.0, d2 = 0.0, along = 0.0;
    for (int i = 0; i < 3; ++i) {
        c[i] = 0.5 * (lo[i] + hi[i]);
        double h = 0.5 * (hi[i] - lo[i]);
        r2 += h * h;
        d2 += c[i] * c[i];
        along += c[i] * fwd[i];
    }
    if (!(d2 > r2)) {
        return worst;
    }
    const double d = sqrt(d2);
    double cos_c = along / d;
    cos_c = cos_c > 1.0 ? 1.0 : (cos_c < -1.0 ? -1.0 : cos_c);
    /* every point of the box lies within asin(r / d) of its centre's direction */
    const double theta = acos(cos_c) + asin(sqrt(r2) / d);
    const double theta_corner = acos(corner_cos);
    if (theta >= theta_corner) {
        return worst;
    }
    const double ct = cos(theta);
    return 1.0 / (ct * ct);
}
