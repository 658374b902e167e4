#include "terrain/default_view.h"

#include <math.h>

#include "core/units.h"

/* World metres back to geodetic degrees. ft_terrain_geo_to_world is affine
 * in (lon, lat) separately, so two evaluations give its exact inverse
 * without repeating its constants here. */
static void world_to_geo(const ft_terrain *t, double x_m, double y_m, double *lat_deg,
                         double *lon_deg)
{
    double x0, y0, x1, y1;
    ft_terrain_geo_to_world(t, t->anchor_lat_deg, t->anchor_lon_deg, &x0, &y0);
    ft_terrain_geo_to_world(t, t->anchor_lat_deg + 1.0, t->anchor_lon_deg + 1.0, &x1, &y1);
    *lon_deg = t->anchor_lon_deg + (x_m - x0) / (x1 - x0);
    *lat_deg = t->anchor_lat_deg + (y_m - y0) / (y1 - y0);
}

static void extent_world(const ft_terrain *t, double *x0, double *y0, double *x1, double *y1)
{
    *x0 = t->origin_world_x_m;
    *y0 = t->origin_world_y_m;
    *x1 = *x0 + t->cell_x_m * (double)(t->width - 1u);
    *y1 = *y0 + t->cell_y_m * (double)(t->height - 1u);
}

void ft_default_view_pose(const ft_terrain *t, ft_pose *out)
{
    double x0, y0, x1, y1;
    extent_world(t, &x0, &y0, &x1, &y1);
    double half_w = 0.5 * (x1 - x0), half_h = 0.5 * (y1 - y0);
    double dist_m = sqrt(half_w * half_w + half_h * half_h);
    double h_top = (double)t->max_height_m;
    double h_mid = 0.5 * ((double)t->min_height_m + h_top);
    /* The centre is seen from the corner: its own drop below the eye's
     * tangent plane (earth curvature) belongs to the depression angle. */
    double drop_m = t->curv_drop_per_m2 * dist_m * dist_m;
    double alt_m = h_top + 0.5 * dist_m;
    double lat, lon;
    world_to_geo(t, x0, y0, &lat, &lon);
    out->lat_deg = lat;
    out->lon_deg = lon;
    out->alt_m = alt_m;
    out->heading_deg = atan2(half_w, half_h) * FT_DEG_PER_RAD; /* clockwise from north */
    out->pitch_deg = -atan2(alt_m - (h_mid - drop_m), dist_m) * FT_DEG_PER_RAD;
    out->roll_deg = 0.0;
}

int ft_pose_over_terrain(const ft_terrain *t, const ft_pose *p)
{
    double x, y;
    ft_terrain_geo_to_world(t, p->lat_deg, p->lon_deg, &x, &y);
    return ft_terrain_contains(t, x, y);
}

void ft_terrain_extent_geo(const ft_terrain *t, double *lat_min_deg, double *lat_max_deg,
                           double *lon_min_deg, double *lon_max_deg)
{
    double x0, y0, x1, y1;
    extent_world(t, &x0, &y0, &x1, &y1);
    world_to_geo(t, x0, y0, lat_min_deg, lon_min_deg);
    world_to_geo(t, x1, y1, lat_max_deg, lon_max_deg);
}

void ft_terrain_centre_geo(const ft_terrain *t, double *lat_deg, double *lon_deg)
{
    double x0, y0, x1, y1;
    extent_world(t, &x0, &y0, &x1, &y1);
    world_to_geo(t, 0.5 * (x0 + x1), 0.5 * (y0 + y1), lat_deg, lon_deg);
}
