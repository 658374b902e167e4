#include "gpu/shade.h"

#include <math.h>

const float ft_ramp_height_m[FT_RAMP_STOPS] = {0.0f, 1.0f, 600.0f, 1800.0f, 3200.0f, 4500.0f};
const float ft_ramp_rgb[FT_RAMP_STOPS][3] = {
    {0.16f, 0.35f, 0.62f}, /* water / 0 m */
    {0.30f, 0.52f, 0.27f}, /* lowland */
    {0.46f, 0.60f, 0.30f},
    {0.58f, 0.48f, 0.34f}, /* rock */
    {0.62f, 0.60f, 0.58f},
    {0.96f, 0.96f, 0.98f}, /* snow */
};

static float clamp01(float x)
{
    return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
}

static const ft_palette_colours k_palette_day = {
    1.0f, 1.0f, {FT_SKY_R, FT_SKY_G, FT_SKY_B}, FT_HORIZON_DAY_GREY};
#if FT_WITH_NIGHT_PALETTE
static const ft_palette_colours k_palette_night = {
    FT_NIGHT_TERRAIN_GAIN, FT_NIGHT_BAND_GAIN, {FT_NIGHT_SKY_R, FT_NIGHT_SKY_G, FT_NIGHT_SKY_B},
    FT_HORIZON_NIGHT_GREY};
#endif

const ft_palette_colours *ft_palette_colours_of(ft_palette p)
{
#if FT_WITH_NIGHT_PALETTE
    if (p == FT_PALETTE_NIGHT) {
        return &k_palette_night;
    }
#else
    (void)p; /* the night palette is refused at init in this build */
#endif
    return &k_palette_day;
}

void ft_shade_palette_ramp(ft_palette p, float rgb[FT_RAMP_STOPS][3])
{
    const float gain = ft_palette_colours_of(p)->terrain_gain;
    for (int i = 0; i < FT_RAMP_STOPS; ++i) {
        for (int c = 0; c < 3; ++c) {
            rgb[i][c] = ft_ramp_rgb[i][c] * gain;
        }
    }
}

void ft_shade_palette_sky(ft_palette p, float rgb[3])
{
    const float *sky = ft_palette_colours_of(p)->sky_rgb;
    for (int c = 0; c < 3; ++c) {
        rgb[c] = sky[c];
    }
}

void ft_shade_state_from_scene(ft_shade_state *st, const ft_scene *s)
{
    st->palette = s->present_palette;
    st->relative = s->present_relative;
    st->bands = s->present_bands;
    st->aircraft_alt_m = (float)s->pose.alt_m;
    st->haze_per_m = s->present_haze_km > 0.0 ? (float)(1.0 / (s->present_haze_km * 1000.0)) : 0.0f;
    st->grid_m = (float)s->present_grid_m;
}

#if FT_WITH_RELATIVE_COLOURING
void ft_shade_bands_gpu(const ft_shade_state *st, float edge_m[FT_BANDS_MAX - 1u],
                        float rgba[FT_BANDS_MAX][4])
{
    const float gain = ft_palette_colours_of(st->palette)->band_gain;
    for (uint32_t i = 0; i < FT_BANDS_MAX - 1u; ++i) {
        edge_m[i] = i < st->bands.edges ? (float)((double)st->bands.edge_ft[i] * FT_M_PER_FT)
                                        : FT_BAND_EDGE_NONE_M;
    }
    for (uint32_t i = 0; i < FT_BANDS_MAX; ++i) {
        const uint32_t b = i < st->bands.colours ? i : st->bands.colours - 1u;
        for (int c = 0; c < 3; ++c) {
            rgba[i][c] = st->bands.rgba[b][c] * gain;
        }
        rgba[i][3] = st->bands.rgba[b][3];
    }
}

/* The shader's rule: the count of edges at or below the relative height. */
static uint32_t band_index(const float edge_m[FT_BANDS_MAX - 1u], float rel_m)
{
    uint32_t band = 0u;
    for (uint32_t i = 0; i < FT_BANDS_MAX - 1u; ++i) {
        if (rel_m >= edge_m[i]) {
            band = i + 1u;
        }
    }
    return band;
}

uint32_t ft_shade_band_of(const ft_shade_state *st, float height_m)
{
    float edge_m[FT_BANDS_MAX - 1u], rgba[FT_BANDS_MAX][4];
    ft_shade_bands_gpu(st, edge_m, rgba);
    return band_index(edge_m, height_m - st->aircraft_alt_m);
}
#endif

#if FT_WITH_GROUND_GRID
float ft_shade_grid_weight(const ft_shade_state *st, const float rel_xy_m[2], float dist_m)
{
    if (!(st->grid_m > 0.0f) || !(st->px_per_rad > 0.0f)) {
        return 0.0f;
    }
    float dmin = INFINITY;
    for (int k = 0; k < 2; ++k) {
        const float g = (rel_xy_m[k] - st->void_map[k]) / st->grid_m;
        const float d = fabsf(g - floorf(g + 0.5f)) * st->grid_m;
        dmin = d < dmin ? d : dmin;
    }
    const float w = st->grid_m * FT_GRID_WIDTH_FRAC;
    const float px = dist_m / st->px_per_rad;
    const float half_w = 0.5f * (w > px ? w : px);
    const float fade = clamp01(1.0f - dist_m / (FT_GRID_FADE_SPACINGS * st->grid_m));
    return dmin < half_w ? fade : 0.0f;
}
#endif

/* haze: NULL, or (sky r, g, b, fraction); frag_xy: NULL, or the window
 * coordinates of an unmeasured fragment */
static void shade(const float ramp[FT_RAMP_STOPS][3], const float *band_rgba, const float *haze,
                  float grid_weight, const float *frag_xy, float height_m, const float n[3],
                  uint8_t out[4])
{
    float rgb[3];
    int i = 0;
    while (i < FT_RAMP_STOPS - 2 && height_m > ft_ramp_height_m[i + 1]) {
        ++i;
    }
    float t = clamp01((height_m - ft_ramp_height_m[i]) /
                      (ft_ramp_height_m[i + 1] - ft_ramp_height_m[i]));
    for (int c = 0; c < 3; ++c) {
        rgb[c] = ramp[i][c] + (ramp[i + 1][c] - ramp[i][c]) * t;
        if (band_rgba != NULL) {
            rgb[c] += (band_rgba[c] - rgb[c]) * band_rgba[3];
        }
    }
    float sl = sqrtf(FT_SUN_DIR_X * FT_SUN_DIR_X + FT_SUN_DIR_Y * FT_SUN_DIR_Y +
                     FT_SUN_DIR_Z * FT_SUN_DIR_Z);
    float d = (n[0] * FT_SUN_DIR_X + n[1] * FT_SUN_DIR_Y + n[2] * FT_SUN_DIR_Z) / sl;
    float light = FT_SHADE_AMBIENT + FT_SHADE_DIFFUSE * (d > 0.0f ? d : 0.0f);
    float lit[3];
    for (int c = 0; c < 3; ++c) {
        lit[c] = clamp01(rgb[c] * light) * (1.0f - FT_GRID_DARKEN * grid_weight);
    }
    if (frag_xy != NULL) {
        const float m = fmodf(floorf(frag_xy[0]) + floorf(frag_xy[1]), FT_HATCH_PERIOD_PX);
        const float grey = 0.299f * lit[0] + 0.587f * lit[1] + 0.114f * lit[2];
        const float hatch[3] = {FT_HATCH_R, FT_HATCH_G, FT_HATCH_B};
        for (int c = 0; c < 3; ++c) {
            lit[c] = m < FT_HATCH_WIDTH_PX ? hatch[c] : grey;
        }
    }
    for (int c = 0; c < 3; ++c) {
        float v = lit[c];
        if (haze != NULL) {
            v += (haze[c] - v) * haze[3];
        }
        out[c] = (uint8_t)(v * 255.0f + 0.5f);
    }
    out[3] = 255;
}

void ft_shade_rgba8(float height_m, const float n[3], uint8_t out[4])
{
    shade(ft_ramp_rgb, NULL, NULL, 0.0f, NULL, height_m, n, out);
}

void ft_shade_rgba8_state(const ft_shade_state *st, float height_m, const float n[3],
                          float dist_m, const float *rel_xy_m, const float *frag_xy,
                          uint8_t out[4])
{
    (void)dist_m; /* unused in a build without haze and ground grid */
    (void)rel_xy_m;
    float ramp[FT_RAMP_STOPS][3];
    ft_shade_palette_ramp(st->palette, ramp);
    const float *band = NULL;
#if FT_WITH_RELATIVE_COLOURING
    float edge_m[FT_BANDS_MAX - 1u], rgba[FT_BANDS_MAX][4];
    if (st->relative) {
        ft_shade_bands_gpu(st, edge_m, rgba);
        band = rgba[band_index(edge_m, height_m - st->aircraft_alt_m)];
    }
#endif
    const float *haze = NULL;
#if FT_WITH_HAZE
    float haze_rgba[4];
    if (st->haze_per_m > 0.0f) {
        ft_shade_palette_sky(st->palette, haze_rgba);
        haze_rgba[3] = FT_HAZE_MAX * (1.0f - expf(-dist_m * st->haze_per_m));
        haze = haze_rgba;
    }
#endif
    float grid = 0.0f;
#if FT_WITH_GROUND_GRID
    if (rel_xy_m != NULL) {
        grid = ft_shade_grid_weight(st, rel_xy_m, dist_m);
    }
#endif
    shade((const float(*)[3])ramp, band, haze, grid, frag_xy, height_m, n, out);
}
