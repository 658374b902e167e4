/* shade_grid.glsl - the ground grid (presentation.grid_m; src/gpu/shade.h
 * FT_GRID_*): lines every spacing metres along the terrain's x and y, about
 * a pixel wide at any distance, darkening the lit colour, fading out by 40
 * spacings. shade.glsl's ft_colour applies it in the FT_SHADE_GRID variant.
 * Left out of the shader (and of a lean build) when no scene needs it. */
#ifdef FT_SHADE_GRID
uniform highp vec4 u_ground_grid; /* (terrain origin rel. eye x, y m, spacing m, K px per rad) */
vec3 ft_ground_grid(vec3 rgb, highp vec2 rel_eye_xy_m, float dist_m)
{
    highp vec2 g = (rel_eye_xy_m - u_ground_grid.xy) / u_ground_grid.z;
    highp vec2 d = abs(g - floor(g + 0.5)) * u_ground_grid.z;
    float half_w = 0.5 * max(u_ground_grid.z * 0.02, dist_m / u_ground_grid.w);
    float fade = clamp(1.0 - dist_m / (40.0 * u_ground_grid.z), 0.0, 1.0);
    float on = min(d.x, d.y) < half_w ? fade : 0.0;
    return rgb * (1.0 - 0.45 * on);
}
#endif
