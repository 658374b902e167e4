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

#include "core/scene.h"
#include "core/units.h"

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

/* n: unit surface normal (world, z up). Writes RGBA8 (alpha 255): the day
 * palette, absolute colouring. */
void ft_shade_rgba8(float height_m, const float n[3], uint8_t out[4]);

/* Palettes (presentation.palette; a GPIO discrete may switch it per frame):
 * the same ramp scaled to a lower luminance at night, a dark sky, and the
 * relative-altitude bands dimmed less than the terrain so alerts stay the
 * brightest thing on the display. Not a certified palette: the data a
 * display engineer tunes. */
#define FT_NIGHT_TERRAIN_GAIN 0.3f
#define FT_NIGHT_BAND_GAIN 0.6f
#define FT_NIGHT_SKY_R 0.02f
#define FT_NIGHT_SKY_G 0.03f
#define FT_NIGHT_SKY_B 0.08f
/* Haze (presentation.haze_km = V): the lit colour goes towards the sky
 * colour by FT_HAZE_MAX (1 - exp(-d / V)) at distance d. The cap keeps a
 * quarter of the contrast at any distance, so far ridgelines stay readable
 * against the sky; at d = V the haze is 0.47. */
#define FT_HAZE_MAX 0.75f
/* The conformal horizon line (presentation.horizon): thickness and colour
 * (white by day, grey at night). */
#define FT_HORIZON_LINE_PX 2.0
#define FT_HORIZON_DAY_GREY 1.0f
#define FT_HORIZON_NIGHT_GREY 0.55f

/* What a palette sets. A build without the night palette
 * (FIXTERRAIN_WITH_NIGHT_PALETTE=OFF) has the day palette's only, and its
 * scenes cannot ask for the night one (src/app/app.c). */
typedef struct ft_palette_colours {
    float terrain_gain; /* times the ramp's colours */
    float band_gain;    /* times the relative-altitude bands' colours */
    float sky_rgb[3];   /* the clear colour, which the haze fades towards */
    float horizon_grey; /* the horizon line's grey */
} ft_palette_colours;
const ft_palette_colours *ft_palette_colours_of(ft_palette p);

/* Everything the colour depends on besides the fragment: what the scene
 * chose, the palette in force and the aircraft's altitude this frame. */
typedef struct ft_shade_state {
    ft_palette palette;
    int relative;         /* presentation.colouring = relative */
    ft_bands bands;       /* edges in ft, colours before the palette's gain */
    float aircraft_alt_m; /* the pose's altitude, same datum as the heights */
    float haze_per_m;     /* 1 / visibility, 0 = no haze */
    /* unmeasured-terrain lookup for this frame (FT_SHADE_VOID variant):
     * the grid's origin relative to the eye and 1 / cell size, and cells */
    float void_map[4];
    float void_size[2];
    float grid_m;         /* presentation.grid_m, 0 = no ground grid */
    float px_per_rad;     /* the camera's K (pixels per radian), for the grid's width */
} ft_shade_state;

void ft_shade_state_from_scene(ft_shade_state *st, const ft_scene *s);
/* The palette's ramp colours, sky colour and band colours (after its gain);
 * edge_m: the band edges in metres relative to the aircraft, unused edges
 * FT_BAND_EDGE_NONE_M (above any height). */
#define FT_BAND_EDGE_NONE_M 1e30f
void ft_shade_palette_ramp(ft_palette p, float rgb[FT_RAMP_STOPS][3]);
void ft_shade_palette_sky(ft_palette p, float rgb[3]);
void ft_shade_bands_gpu(const ft_shade_state *st, float edge_m[FT_BANDS_MAX - 1u],
                        float rgba[FT_BANDS_MAX][4]);
/* The band a height falls in (0 .. bands.edges), as the shader picks it. */
uint32_t ft_shade_band_of(const ft_shade_state *st, float height_m);
/* The colour the fragment shader computes for this state at distance dist_m
 * from the eye (the CPU mirror). rel_xy_m: the point relative to the eye
 * (world axes; NULL: no ground grid there). frag_xy: NULL over measured
 * terrain; over unmeasured terrain the fragment's window coordinates
 * (gl_FragCoord.xy: pixel centres, origin bottom-left), for the hatch. */
void ft_shade_rgba8_state(const ft_shade_state *st, float height_m, const float n[3],
                          float dist_m, const float *rel_xy_m, const float *frag_xy,
                          uint8_t out[4]);

/* Unmeasured terrain (a cell with a void-filled corner): the lit colour
 * becomes its grey (Rec. 601 luma), crossed by a magenta hatch: window
 * pixels whose (x + y) mod FT_HATCH_PERIOD_PX < FT_HATCH_WIDTH_PX. */
#define FT_HATCH_PERIOD_PX 8.0f
#define FT_HATCH_WIDTH_PX 2.0f
#define FT_HATCH_R 0.8f
#define FT_HATCH_G 0.0f
#define FT_HATCH_B 0.8f

/* Ground grid (presentation.grid_m = s), a motion cue at low level: lines
 * every s metres along the terrain's x and y, about a pixel wide at any
 * distance d (half-width 0.5 max(s FT_GRID_WIDTH_FRAC, d / K) m), darkening
 * the lit colour by FT_GRID_DARKEN, fading out linearly by FT_GRID_FADE_SPACINGS
 * spacings from the eye. */
#define FT_GRID_WIDTH_FRAC 0.02f
#define FT_GRID_DARKEN 0.45f
#define FT_GRID_FADE_SPACINGS 40.0f
#if FT_WITH_GROUND_GRID
/* The grid's line weight (0..1, before the darkening) at a point rel_xy_m
 * (metres from the eye, world axes) at distance dist_m. */
float ft_shade_grid_weight(const ft_shade_state *st, const float rel_xy_m[2], float dist_m);
#endif

#endif
