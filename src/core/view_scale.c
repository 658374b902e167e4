/* view_scale.c - the off-axis pixel gain (view_scale.h). */
#include "core/view_scale.h"

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
    /* The angle off the axis is quasi-convex where it is below 90 degrees
     * (its sublevel sets are convex cones), so over a box in front of the
     * eye it peaks at a corner. A sub-box therefore never gets a larger gain
     * than its box: the selection's nested boxes keep nested errors. */
    double cos_min = 1.0;
    for (int corner = 0; corner < 8; ++corner) {
        const double p[3] = {(corner & 1) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1],
                             (corner & 4) ? hi[2] : lo[2]};
        const double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        const double along = p[0] * fwd[0] + p[1] * fwd[1] + p[2] * fwd[2];
        if (!(len > 0.0) || !(along > 0.0)) {
            return worst; /* a corner at or behind the eye: the box may hold any angle */
        }
        const double c = along / len;
        cos_min = (c < cos_min) ? c : cos_min;
    }
    if (cos_min <= corner_cos) {
        return worst;
    }
    return 1.0 / (cos_min * cos_min);
}
