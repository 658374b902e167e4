/* shade.h - the terrain colour, on the CPU (reference) exactly as the
 * shaders compute it (shaders/terrain.frag.glsl mirrors this code).
 *
 *   colour = ramp(height_m) * (FT_SHADE_AMBIENT + FT_SHADE_DIFFUSE * max(0, dot(n, sun)))
 *   ramp: piecewise linear through the stops below (height in metres).
 *   sun:  normalize(FT_SUN_DIR).
 * Normals: from the bilinear surface (reference) or central differences
 * (meshes); colours differ slightly there, which is why the error metric
 * uses positions, not colours. */
#ifndef FT_SHADE_H
#define FT_SHADE_H

#include <stdint.h>

#define FT_SHADE_AMBIENT 0.35f
#define FT_SHADE_DIFFUSE 0.65f
#define FT_SUN_DIR_X 0.4f
#define FT_SUN_DIR_Y 0.3f
#define FT_SUN_DIR_Z 0.866f

/* Ramp stops: height_m -> RGB in [0,1]. */
#define FT_RAMP_STOPS 6
extern const float ft_ramp_height_m[FT_RAMP_STOPS];
extern const float ft_ramp_rgb[FT_RAMP_STOPS][3];

/* Sky/clear colour: (0.53, 0.70, 0.92) for colour frames; the crack test
 * uses its own clear colour. */
#define FT_SKY_R 0.53f
#define FT_SKY_G 0.70f
#define FT_SKY_B 0.92f

/* n: unit surface normal (world, z up). Writes RGBA8 (alpha 255). */
void ft_shade_rgba8(float height_m, const float n[3], uint8_t out[4]);

#endif
