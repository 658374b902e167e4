/* degrade.c - see degrade.h. */
#include "lod/degrade.h"

#include <string.h>

void ft_degrade_init(ft_degrade *d, int enabled, double budget_ms, double max_scale)
{
    memset(d, 0, sizeof *d);
    d->enabled = enabled;
    d->budget_ms = budget_ms;
    d->max_scale = max_scale < 1.0 ? 1.0 : max_scale;
    d->scale = 1.0;
}

int ft_degrade_frame(ft_degrade *d, double frame_ms)
{
    if (frame_ms > d->budget_ms) {
        d->over_budget += 1u;
    }
    if (!d->enabled) {
        return 0;
    }
    if (frame_ms > FT_DEGRADE_HIGH * d->budget_ms) {
        d->calm = 0;
        if (d->scale < d->max_scale) {
            double s = d->scale * FT_DEGRADE_STEP;
            d->scale = s > d->max_scale ? d->max_scale : s;
            d->raises += 1u;
            return 1;
        }
        return 0;
    }
    if (frame_ms < FT_DEGRADE_LOW * d->budget_ms) {
        d->calm += 1u;
        if (d->calm >= FT_DEGRADE_CALM_FRAMES && d->scale > 1.0) {
            double s = d->scale / FT_DEGRADE_STEP;
            d->scale = s < 1.0 ? 1.0 : s;
            d->calm = 0;
            d->lowers += 1u;
            return 1;
        }
        return 0;
    }
    d->calm = 0; /* between the bands: hold */
    return 0;
}
