/* shade_relative.glsl - relative-altitude colouring (presentation.colouring
 * = relative): the band of the fragment's height relative to the aircraft,
 * painted over the terrain colour by the band's alpha. Edges are metres
 * relative to the aircraft, increasing; unused edges lie above any height,
 * so the band is the count of edges at or below the relative height. Left
 * out of the shader (and of a lean build) when no scene needs it. */
#ifdef FT_SHADE_RELATIVE
#define FT_BANDS_MAX 6
uniform float u_band_edge_m[FT_BANDS_MAX - 1];
uniform vec4 u_band_rgba[FT_BANDS_MAX];
uniform float u_aircraft_alt_m;

vec3 ft_relative_band(float h, vec3 rgb)
{
    float rel = h - u_aircraft_alt_m;
    vec4 band = u_band_rgba[0];
    for (int i = 0; i < FT_BANDS_MAX - 1; ++i) {
        if (rel >= u_band_edge_m[i]) {
            band = u_band_rgba[i + 1];
        }
    }
    return mix(rgb, band.rgb, band.a);
}
#endif
