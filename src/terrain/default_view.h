/* The pose a terrain is seen from when nothing names one for it, and the
 * check that a named pose lies over the terrain at all.
 *
 * Without it, a DEM given on the command line keeps the pose of the scene
 * it replaced (the embedded default scene looks at its own synthetic
 * terrain at 46.5 N, 8 E), and the frame shows only sky with no word of why.
 *
 * The default view: the eye above the terrain's south-west corner at
 * max height + half the horizontal distance to the centre, heading for the
 * centre and pitched down so that the centre of the terrain (at the mean of
 * its min and max height) is the centre of the image. On a 1-degree SRTM tile
 * that is about 39 km above the highest ground, about 27 degrees down; a
 * 60-degree view then shows the whole tile below the horizon. */
#ifndef FT_DEFAULT_VIEW_H
#define FT_DEFAULT_VIEW_H

#include "core/camera.h"
#include "terrain/terrain.h"

/* The default view of `t` (the rule above). */
void ft_default_view_pose(const ft_terrain *t, ft_pose *out);

/* 1 if the eye of `p` lies over the extent of `t` (horizontally). */
int ft_pose_over_terrain(const ft_terrain *t, const ft_pose *p);

/* The terrain's extent as geodetic bounds (deg), through the same
 * equirectangular map that places a pose (ft_terrain_geo_to_world). */
void ft_terrain_extent_geo(const ft_terrain *t, double *lat_min_deg, double *lat_max_deg,
                           double *lon_min_deg, double *lon_max_deg);

/* The geodetic position (deg) of the terrain's centre. */
void ft_terrain_centre_geo(const ft_terrain *t, double *lat_deg, double *lon_deg);

#endif
