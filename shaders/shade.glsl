/* shade.glsl - the terrain colour of a fragment at height h (m) with normal
 * n: the palette's height ramp, the relative-altitude band painted over it
 * (only in the FT_SHADE_RELATIVE variant), times one Lambert light; then the
 * ground grid (FT_SHADE_GRID), the unmeasured-terrain mark (FT_SHADE_VOID)
 * and the haze by the fragment's distance (FT_SHADE_HAZE). The optional
 * parts live in files of their own (shade_relative.glsl, shade_grid.glsl,
 * shade_haze.glsl), included before this one, so a build without a part
 * embeds none of its text; only the calls below name them.
 * src/gpu/shade.c (ft_shade_rgba8_state) is the same rule on the CPU; the
 * uniforms come from the same C tables. */
#define FT_RAMP_STOPS 6
uniform float u_ramp_height_m[FT_RAMP_STOPS];
uniform vec3 u_ramp_rgb[FT_RAMP_STOPS];
uniform vec3 u_sun_dir; /* unit */
uniform vec2 u_light;   /* (ambient, diffuse) */

vec3 ft_shade(float h, vec3 n)
{
    vec3 rgb = u_ramp_rgb[FT_RAMP_STOPS - 1];
    for (int i = 0; i < FT_RAMP_STOPS - 1; ++i) {
        /* first segment whose upper stop is at or above the height */
        if (h <= u_ramp_height_m[i + 1] || i == FT_RAMP_STOPS - 2) {
            float t = clamp((h - u_ramp_height_m[i]) / (u_ramp_height_m[i + 1] - u_ramp_height_m[i]),
                            0.0, 1.0);
            rgb = mix(u_ramp_rgb[i], u_ramp_rgb[i + 1], t);
            break;
        }
    }
#ifdef FT_SHADE_RELATIVE
    rgb = ft_relative_band(h, rgb);
#endif
    float light = u_light.x + u_light.y * max(0.0, dot(normalize(n), u_sun_dir));
    return clamp(rgb * light, 0.0, 1.0);
}

#ifdef FT_SHADE_VOID
/* Unmeasured terrain (src/gpu/shade.h): where the bilinear surface depends on a
 * void-filled sample (a cell with such a corner) the lit colour turns grey
 * and carries a magenta diagonal hatch in screen space, and the fragment's
 * alpha says so (counted at the readback, then set back to opaque). */
uniform sampler2D u_void_cells;  /* one texel per cell: 1 = a corner was filled */
uniform highp vec4 u_void_map;   /* (origin rel. eye x, y m, 1 / cell x, 1 / cell y) */
uniform highp vec2 u_void_size;  /* cells */
float ft_unmeasured(highp vec2 rel_eye_xy_m)
{
    highp vec2 c = floor((rel_eye_xy_m - u_void_map.xy) * u_void_map.zw);
#if FT_ES3
    return texture(u_void_cells, (c + 0.5) / u_void_size).r > 0.5 ? 1.0 : 0.0;
#else
    return texture2D(u_void_cells, (c + 0.5) / u_void_size).r > 0.5 ? 1.0 : 0.0;
#endif
}
vec3 ft_mark_unmeasured(vec3 rgb)
{
    float m = mod(floor(gl_FragCoord.x) + floor(gl_FragCoord.y), 8.0);
    return m < 2.0 ? vec3(0.8, 0.0, 0.8) : vec3(dot(rgb, vec3(0.299, 0.587, 0.114)));
}
#endif

/* The fragment's colour and alpha at height h, normal n, position rel_eye_m
 * (world axes, relative to the eye): shade, then each part the variant has,
 * in the order src/gpu/shade.c applies them (grid, unmeasured, haze). */
vec4 ft_colour(float h, vec3 n, highp vec3 rel_eye_m)
{
    vec3 rgb = ft_shade(h, n);
    float alpha = 1.0;
#ifdef FT_SHADE_GRID
    rgb = ft_ground_grid(rgb, rel_eye_m.xy, length(rel_eye_m));
#endif
#ifdef FT_SHADE_VOID
    if (ft_unmeasured(rel_eye_m.xy) > 0.5) {
        rgb = ft_mark_unmeasured(rgb);
        alpha = 0.5;
    }
#endif
#ifdef FT_SHADE_HAZE
    rgb = ft_haze(rgb, length(rel_eye_m));
#endif
    return vec4(rgb, alpha);
}
