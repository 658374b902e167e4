#include "shade.h"

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

void ft_shade_rgba8(float height_m, const float n[3], uint8_t out[4])
{
    float rgb[3];
    int i = 0;
    while (i < FT_RAMP_STOPS - 2 && height_m > ft_ramp_height_m[i + 1]) {
        ++i;
    }
    float t = clamp01((height_m - ft_ramp_height_m[i]) /
                      (ft_ramp_height_m[i + 1] - ft_ramp_height_m[i]));
    for (int c = 0; c < 3; ++c) {
        rgb[c] = ft_ramp_rgb[i][c] + (ft_ramp_rgb[i + 1][c] - ft_ramp_rgb[i][c]) * t;
    }
    float sl = sqrtf(FT_SUN_DIR_X * FT_SUN_DIR_X + FT_SUN_DIR_Y * FT_SUN_DIR_Y +
                     FT_SUN_DIR_Z * FT_SUN_DIR_Z);
    float d = (n[0] * FT_SUN_DIR_X + n[1] * FT_SUN_DIR_Y + n[2] * FT_SUN_DIR_Z) / sl;
    float light = FT_SHADE_AMBIENT + FT_SHADE_DIFFUSE * (d > 0.0f ? d : 0.0f);
    for (int c = 0; c < 3; ++c) {
        out[c] = (uint8_t)(clamp01(rgb[c] * light) * 255.0f + 0.5f);
    }
    out[3] = 255;
}
