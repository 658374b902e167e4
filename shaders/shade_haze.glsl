/* shade_haze.glsl - distance haze (presentation.haze_km): towards the sky
 * colour, capped so far ridgelines keep a quarter of their contrast
 * (src/gpu/shade.h FT_HAZE_MAX). shade.glsl's ft_colour applies it in the
 * FT_SHADE_HAZE variant. Left out of the shader (and of a lean build) when
 * no scene needs it. */
#ifdef FT_SHADE_HAZE
uniform vec4 u_haze; /* (sky r, g, b, 1 / visibility m) */
vec3 ft_haze(vec3 rgb, float dist_m)
{
    return mix(rgb, u_haze.rgb, 0.75 * (1.0 - exp(-dist_m * u_haze.w)));
}
#endif
