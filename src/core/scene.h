/* scene.h - a scene file (INI, parsed with libinih) resolved into one const
 * struct. Every key is one row of one schema (FT_SCENE_KEYS below: section,
 * key, kind, field, range, default, unit, meaning); the defaults, the parser,
 * the validator and `fixterrain keys` are all generated from it, so a key
 * cannot have a range in one place and another elsewhere. The lean-build
 * profile (tools/profile.cmake) reads a scene with this same parser. Unknown
 * sections or keys, and values out of range, are errors with the line
 * number: a typo in a budget must never silently fall back to a default. */
#ifndef FT_SCENE_H
#define FT_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "core/camera.h"
#include "core/ft_status.h"
#include "core/mem_budget.h"
#include "core/output.h"
#include "input/canaero.h"
#include "terrain/synth_terrain.h"
#include "terrain/terrain_db.h"

#define FT_SCENE_TEXT_MAX 65536u /* scene files larger than this are rejected */
#define FT_SCENE_NAME_MAX 64u
#define FT_SCENE_PATH_MAX 512u
#define FT_CAN_IFACE_NAME_MAX 16u /* IFNAMSIZ: 15 characters + NUL */
#define FT_GPIO_CHIP_NAME_MAX 64u
#define FT_VIEW_SIDE_MIN_PX 16u   /* view.width_px, view.height_px */
#define FT_VIEW_SIDE_MAX_PX 8192u
#define FT_GPIO_LINE_MAX 511

#define FT_BUILD_INPUT_REPLAY 1u
#define FT_BUILD_INPUT_CAN 2u
#define FT_BUILD_INPUT_GPIO 4u

/* Discrete inputs (gpio.<name>_line). */
#define FT_GPIO_INPUT_LIST(X)                                             \
    X(FT_GPIO_FREEZE, "freeze", "hold the drawn pose")                     \
    X(FT_GPIO_SOURCE, "source", "use the backup CAN interface")            \
    X(FT_GPIO_TEST, "test", "annunciation test")                          \
    X(FT_GPIO_NIGHT, "night", "night palette (else presentation.palette)")

typedef enum ft_gpio_input {
#define FT_GPIO_INPUT_ENUM(id, name, what) id,
    FT_GPIO_INPUT_LIST(FT_GPIO_INPUT_ENUM)
#undef FT_GPIO_INPUT_ENUM
    FT_GPIO_INPUT_COUNT
} ft_gpio_input;

const char *ft_gpio_input_name(ft_gpio_input i); /* "freeze" */

#define FT_METHOD_LIST(X)                                                                     \
    X(FT_METHOD_BRUTE, "brute", "whole grid as one regular mesh")                             \
    X(FT_METHOD_BINTREE, "bintree", "crack-free bintree of triangular tiles, error-bounded")  \
    X(FT_METHOD_PGM, "pgm", "persistent grid mapping: a view-plane grid laid on the terrain")  \
    X(FT_METHOD_PGRID, "pgrid", "error-bounded projective grid, ray casting over gamma")    \
    X(FT_METHOD_CLIPMAP, "clipmap", "geometry clipmaps: nested rings of cached levels around the eye")

typedef enum ft_method_kind {
#define FT_METHOD_ENUM(id, name, what) id,
    FT_METHOD_LIST(FT_METHOD_ENUM)
#undef FT_METHOD_ENUM
    FT_METHOD_COUNT
} ft_method_kind;

const char *ft_method_name(ft_method_kind m);
int ft_method_from_name(const char *name, ft_method_kind *out);

/* bintree.morph_width: a vertex morphs in over this fraction of its
 * diamond's square side of eye travel (src/lod/bintree.h); default, least,
 * most */
#define FT_BT_MORPH_WIDTH 0.25
#define FT_BT_MORPH_WIDTH_MIN 0.0625
#define FT_BT_MORPH_WIDTH_MAX 1.0

/* [presentation]: how the terrain is coloured (src/gpu/shade.h). Relative
 * colouring paints bands of terrain height relative to the aircraft's
 * altitude over the terrain colour, as a TAWS terrain display does. Band
 * edges are in feet (the unit of altimeters and TAWS), relative to the
 * aircraft (negative: below it), strictly increasing; band i lies between
 * edge i-1 and edge i (band 0 below the first edge, the last band at or
 * above the last edge). Each band's RGBA: the colour and how much of it
 * replaces the terrain colour (alpha 0: the terrain colour shows). */
#define FT_BANDS_MAX 6u
#define FT_BAND_EDGE_LIMIT_FT 60000.0
#define FT_HAZE_KM_MIN 1.0    /* presentation.haze_km: 0 (none) or this .. max */
#define FT_HAZE_KM_MAX 1000.0
#define FT_GRID_M_MIN 10.0   /* presentation.grid_m: 0 (none) or this .. max */
#define FT_GRID_M_MAX 10000.0
typedef enum ft_palette { FT_PALETTE_DAY = 0, FT_PALETTE_NIGHT, FT_PALETTE_COUNT } ft_palette;
typedef struct ft_bands {
    uint32_t edges;                      /* presentation.band_edges_ft: 1..FT_BANDS_MAX-1 */
    float edge_ft[FT_BANDS_MAX - 1u];
    uint32_t colours;                    /* presentation.band_rgba: must be edges + 1 */
    float rgba[FT_BANDS_MAX][4];         /* 0..1 */
} ft_bands;

typedef struct ft_scene {
    char name[FT_SCENE_NAME_MAX];
    ft_method_kind method;
    ft_backend backend;
    ft_display display;
    char display_device[FT_DISPLAY_DEVICE_MAX];       /* kms:PATH; "" = default */
    char display_connector[FT_DISPLAY_CONNECTOR_MAX]; /* display.connector */
    char display_mode[FT_DISPLAY_MODE_MAX];           /* display.mode */
    uint32_t width_px, height_px;
    double fovy_deg;
    ft_pose pose;
    int pose_given; /* 1 when the scene text has a [pose] section */
    char dem_path[FT_SCENE_PATH_MAX];
    uint32_t db_level;        /* terrain.db_level (a .ftd window) */
    uint32_t db_side_samples; /* terrain.db_side_samples */
    double db_centre_lat_deg; /* terrain.db_centre_lat_deg, NaN = the data's middle */
    double db_centre_lon_deg; /* terrain.db_centre_lon_deg, NaN = the data's middle */
    ft_synth_desc synth;
    ft_curvature curvature; /* terrain.curvature */
    ft_height_format height_format;
    uint64_t gpu_texture_bytes;
    int pyramid_textures; /* gpu.pyramid_textures: upload avg/min/max pyramids too */
    uint32_t brute_patch_cells;
    uint32_t brute_max_vertices;
    uint32_t bintree_template_k; /* bintree.template_k */
    uint32_t bintree_tiles_max;  /* bintree.tiles_max */
    double bintree_tau_px;       /* bintree.tau_px */
    int bintree_morph;           /* bintree.morph */
    double bintree_morph_width; /* bintree.morph_width */
    uint32_t bintree_subsample_levels; /* bintree.subsample_levels */
    int bintree_vertex_table;          /* bintree.vertex_table (GLES 3 only) */
    int bintree_cull_back_faces;       /* bintree.cull_back_faces */
    uint32_t bintree_tiles_per_draw;   /* bintree.tiles_per_draw (0: the context's) */
    int bintree_heights_clipmap;       /* bintree.heights: 0 window, 1 clipmap */
    uint32_t pgm_grid_cols;      /* pgm.grid_cols */
    uint32_t pgm_grid_rows;      /* pgm.grid_rows */
    int pgm_heights_clipmap;     /* pgm.heights: 0 pyramid, 1 clipmap */
    uint32_t pgrid_grid_cols;    /* pgrid.grid_cols */
    uint32_t pgrid_grid_rows;    /* pgrid.grid_rows */
    int pgrid_view_distribution; /* pgrid.distribution: 0 uniform, 1 view */
    int pgrid_columns_error;     /* pgrid.columns: 0 uniform, 1 error (src/lod/pgrid.h 1) */
    int pgrid_residual_bound;    /* pgrid.error_bound: 0 relief, 1 residual (src/lod/pgrid.h 6) */
    int pgrid_ray_casting;       /* pgrid.ray_casting */
    double pgrid_gamma_px;       /* pgrid.gamma_px */
    uint32_t pgrid_raycast_max_px; /* pgrid.raycast_max_px */
    uint32_t pgrid_raycast_tile_px; /* pgrid.raycast_tile_px */
    int pgrid_heights_clipmap;   /* pgrid.heights: 0 pyramid, 1 clipmap */
    uint32_t clipmap_side;         /* clipmap.side */
    uint32_t clipmap_levels;       /* clipmap.levels */
    uint32_t clipmap_update_samples_max; /* clipmap.update_samples_max */
    uint32_t clipmap_updates_per_frame;  /* clipmap.updates_per_frame */
    double clipmap_transition_samples;   /* clipmap.transition_samples */
    uint32_t clipmap_tile_slots;         /* clipmap.tile_slots */
    int present_relative;   /* presentation.colouring: 0 absolute, 1 relative */
    ft_palette present_palette; /* presentation.palette: day | night */
    ft_bands present_bands; /* presentation.band_edges_ft, band_rgba */
    int present_horizon;    /* presentation.horizon: the conformal zero-pitch line */
    double present_haze_km; /* presentation.haze_km: haze visibility, 0 = none */
    double present_grid_m;  /* presentation.grid_m: ground grid spacing, 0 = none */
    int metric_enabled; /* metric.enabled: position target, reference, error stats */
    uint32_t metric_truth_side; /* metric.truth_side_samples (0: terrain.db_side_samples) */
    double frame_period_ms;   /* frame.period_ms */
    double frame_budget_ms;   /* frame.budget_ms, 0 = the period */
    int frame_degrade;        /* frame.degrade */
    double frame_degrade_max_scale; /* frame.degrade_max_scale */
    uint32_t pose_horizon_ms; /* pose_input.horizon_ms */
    int pose_velocity_required; /* pose_input.velocity_required */
    uint32_t pose_converge_ms;  /* pose_input.converge_ms */
    double pose_snap_m;         /* pose_input.snap_m */
    char can_iface[FT_CAN_IFACE_NAME_MAX];        /* can.interface */
    char can_backup_iface[FT_CAN_IFACE_NAME_MAX]; /* can.backup_interface */
    uint32_t can_failover_ms;                     /* can.failover_ms */
    ft_can_map can_map;                           /* [can_map] */
    char gpio_chip[FT_GPIO_CHIP_NAME_MAX];        /* gpio.chip; empty = none */
    int gpio_input_line[FT_GPIO_INPUT_COUNT];     /* gpio.<name>_line, -1 = none */
    int gpio_heartbeat_line;                      /* gpio.heartbeat_line, -1 = none */
    int gpio_active_low;                          /* gpio.active_low */
    uint32_t gpio_debounce_ms;                    /* gpio.debounce_ms */
    unsigned build_inputs;                        /* build.inputs: FT_BUILD_INPUT_* bits */
    int build_png;                                /* build.png */
    uint64_t budget_bytes[FT_POOL_COUNT];
} ft_scene;

/* The scene schema: one row per key.
 *   X(section, key, kind, field of ft_scene, min, max, choices, default, unit, meaning)
 * kind: U32, U64 (a count that takes a K/M/G suffix, as budgets do), F64,
 * FLAG (0 | 1), OFF_F64 (0 = the part is off, else min..max), ENUM (one of
 * `choices`, each name followed by '|'; the value is its position), BITS (a
 * comma list of `choices`; bit i = name i; at least one), LINE (a GPIO line:
 * -1 = none, else 0..max), TEXT (at most sizeof field - 1 characters).
 * Ranges are inclusive. Defaults are written as a scene file would say them
 * and are parsed by the same code (config/default.ini repeats them; a test
 * checks the two agree). [pose] keys come from FT_POSE_FIELD_LIST, and a few
 * keys whose values are lists are parsed by their own code
 * (FT_SCENE_LIST_KEYS). */
#define FT_CHOICE(id, name, what) name "|"
#define FT_SCENE_KEYS(X)                                                                         \
    X(scene, name, TEXT, name, 0, 0, NULL, "default", "", "the scene's name")                  \
    X(scene, method, ENUM, method, 0, 0, FT_METHOD_LIST(FT_CHOICE), "pgrid", "",                \
      "terrain method (a lean build has only its own: fixterrain render --help)")                \
    X(scene, backend, ENUM, backend, 0, 0, FT_BACKEND_LIST(FT_CHOICE), "egl-gles3", "",          \
      "GPU backend")                                                                             \
    X(display, connector, TEXT, display_connector, 0, 0, NULL, "", "",                          \
      "KMS connector as the kernel names it (HDMI-A-1, Virtual-1) or its id; empty = the first " \
      "connected one")                                                                           \
    X(view, width_px, U32, width_px, FT_VIEW_SIDE_MIN_PX, FT_VIEW_SIDE_MAX_PX, NULL, "800", "px", \
      "image width")                                                                             \
    X(view, height_px, U32, height_px, FT_VIEW_SIDE_MIN_PX, FT_VIEW_SIDE_MAX_PX, NULL, "600",    \
      "px", "image height")                                                                      \
    X(view, fovy_deg, F64, fovy_deg, 1, 170, NULL, "60", "deg", "vertical field of view")        \
    X(terrain, dem, TEXT, dem_path, 0, 0, NULL, "", "",                                          \
      "path to a .ftt, .hgt or .ftd (a window of it: db_*), relative to the scene file; "       \
      "empty = the synthetic terrain")                                                           \
    X(terrain, db_level, U32, db_level, 0, FT_TDB_LEVELS_MAX - 1u, NULL, "0", "",                \
      ".ftd window: the database level (0 = finest; level k every 2^k level-0 samples)")         \
    X(terrain, db_side_samples, U32, db_side_samples, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX, NULL,  \
      "1201", "samples", ".ftd window: samples per side")                                        \
    X(terrain, curvature, ENUM, curvature, 0, 0, "auto|sphere|flat|", "auto", "",                \
      "earth curvature: every method, ray caster and the metric's truth lower a point d from "   \
      "the eye by d^2 / (2 R); auto = sphere for a grid in degrees, flat for one in metres")     \
    X(terrain, synth_side, U32, synth.side, 3, 16385, NULL, "1025", "samples",                   \
      "synthetic terrain: samples per side")                                                     \
    X(terrain, synth_spacing_m, F64, synth.spacing_m, 1e-3, 1e5, NULL, "30", "m",                \
      "synthetic terrain: sample spacing")                                                       \
    X(terrain, synth_relief_m, F64, synth.relief_m, 0, 9000, NULL, "2400", "m",                  \
      "synthetic terrain: highest peak")                                                         \
    X(terrain, synth_seed, U32, synth.seed, 0, UINT32_MAX, NULL, "1", "",                        \
      "synthetic terrain: noise seed")                                                           \
    X(terrain, synth_octaves, U32, synth.octaves, 1, 16, NULL, "9", "",                          \
      "synthetic terrain: fBm octaves")                                                          \
    X(terrain, synth_anchor_lat_deg, F64, synth.anchor_lat_deg, -89, 89, NULL, "46.5", "deg",    \
      "synthetic terrain: latitude of its south-west corner (where --pose lands)")               \
    X(terrain, synth_anchor_lon_deg, F64, synth.anchor_lon_deg, -360, 360, NULL, "8.0", "deg",   \
      "synthetic terrain: longitude of its south-west corner")                                   \
    X(gpu, height_format, ENUM, height_format, 0, 0, "auto|float|packed|", "auto", "",           \
      "how heights reach the vertex shader: float textures, or RGBA8 24-bit fixed point")        \
    X(gpu, texture_bytes, U64, gpu_texture_bytes, 0, FT_SCENE_BYTES_MAX, NULL, "64M", "bytes",    \
      "budget for all GPU textures, render targets and buffers")                                 \
    X(gpu, pyramid_textures, FLAG, pyramid_textures, 0, 1, NULL, "0", "",                        \
      "also upload the avg/min/max pyramids as textures")                                        \
    X(brute, patch_cells, U32, brute_patch_cells, 1, 180, NULL, "64", "cells",                   \
      "template patch side")                                                                     \
    X(brute, max_vertices, U32, brute_max_vertices, 4, UINT32_MAX, NULL, "4200000", "vertices",  \
      "most grid vertices brute draws per frame (a window around the eye)")                      \
    X(bintree, template_k, U32, bintree_template_k, 1, 6, NULL, "3", "",                         \
      "tile template: 2k bisections, 2^k segments a leg")                                        \
    X(bintree, tiles_max, U32, bintree_tiles_max, 2, 1048576, NULL, "16384", "tiles",            \
      "tile budget per frame")                                                                   \
    X(bintree, tau_px, F64, bintree_tau_px, 0, 1000, NULL, "1.0", "px",                          \
      "target screen-space error")                                                               \
    X(bintree, morph, FLAG, bintree_morph, 0, 1, NULL, "1", "", "geomorph split vertices")       \
    X(bintree, morph_width, F64, bintree_morph_width, FT_BT_MORPH_WIDTH_MIN,                     \
      FT_BT_MORPH_WIDTH_MAX, NULL, "0.25", "",                                                   \
      "with morph, a split's vertices move over this x their diamond's side of eye travel")      \
    X(bintree, subsample_levels, U32, bintree_subsample_levels, 0, 4, NULL, "0", "",             \
      "tiles refine to 2^-S of a cell, their vertices on the bilinear surface")                  \
    X(bintree, vertex_table, FLAG, bintree_vertex_table, 0, 1, NULL, "1", "",                    \
      "GLES 3: a vertex on a sample reads one RGBA32F texel (16 bytes a sample of GPU memory) "  \
      "instead of 8 fetches")                                                                    \
    X(bintree, cull_back_faces, FLAG, bintree_cull_back_faces, 0, 1, NULL, "1", "",              \
      "cull back faces while the eye is over the grid and above the drawn surface under it "     \
      "(they are hidden then)")                                                                  \
    X(bintree, tiles_per_draw, U32, bintree_tiles_per_draw, 0, 1024, NULL, "0", "tiles",         \
      "tiles a draw, a uniform array in the vertex shader (0: 192 on GLES 3, 64 on GLES 2; 1 "  \
      "is fastest on llvmpipe's GLES 2)")                                                        \
    X(bintree, heights, ENUM, bintree_heights_clipmap, 0, 0, "window|clipmap|", "window", "",    \
      "where the tiles read heights: the scene's window, or the clipmap cache around the eye "   \
      "(clipmap.* keys; over a .ftd it reads on past the window; needs morph = 0, "              \
      "subsample_levels = 0 and clipmap.side >= 12 x 2^template_k + 8)")                         \
    X(pgm, grid_cols, U32, pgm_grid_cols, 2, 8192, NULL, "430", "vertices",                      \
      "persistent grid: vertices across the view")                                               \
    X(pgm, grid_rows, U32, pgm_grid_rows, 2, 8192, NULL, "430", "vertices",                      \
      "persistent grid: vertices from near to far")                                              \
    X(pgm, heights, ENUM, pgm_heights_clipmap, 0, 0, "pyramid|clipmap|", "pyramid", "",          \
      "where the grid reads heights: the window's avg pyramid, or the clipmap cache around the " \
      "eye (clipmap.* keys; over a .ftd it reads on past the window)")                           \
    X(pgrid, grid_cols, U32, pgrid_grid_cols, 2, 8192, NULL, "200", "vertices",                  \
      "error-bounded projective grid: vertices across the view")                                 \
    X(pgrid, grid_rows, U32, pgrid_grid_rows, 2, 8192, NULL, "800", "vertices",                  \
      "error-bounded projective grid: vertices from near to far")                                \
    X(pgrid, distribution, ENUM, pgrid_view_distribution, 0, 0, "uniform|view|", "view", "",     \
      "grid rows evenly on the image plane, or evenly in asinh(ground distance / height)")       \
    X(pgrid, columns, ENUM, pgrid_columns_error, 0, 0, "uniform|error|", "uniform", "",          \
      "grid columns evenly across the view, or moved to where the last frame's error was "       \
      "(ray casting only; src/lod/pgrid.h 1)")                                                   \
    X(pgrid, error_bound, ENUM, pgrid_residual_bound, 0, 0, "relief|residual|", "residual", "",  \
      "which bound marks the pixels to ray cast (src/lod/pgrid.h)")                              \
    X(pgrid, ray_casting, FLAG, pgrid_ray_casting, 0, 1, NULL, "1", "",                          \
      "ray cast the pixels whose error bound exceeds gamma_px (GLES 3 only)")                    \
    X(pgrid, gamma_px, F64, pgrid_gamma_px, 0.1, 100, NULL, "1.0", "px",                         \
      "screen-space error bound")                                                                \
    X(pgrid, raycast_max_px, U32, pgrid_raycast_max_px, 0, 67108864, NULL, "262144", "px",       \
      "most pixels ray cast per frame; above it gamma is raised for that frame and reported")    \
    X(pgrid, raycast_tile_px, U32, pgrid_raycast_tile_px, 4, 64, NULL, "16", "px",               \
      "side of the screen tiles the ray caster runs on: only tiles with a pixel to ray cast")    \
    X(pgrid, heights, ENUM, pgrid_heights_clipmap, 0, 0, "pyramid|clipmap|", "pyramid", "",      \
      "where the grid reads heights and bounds its error: the window's pyramids, or the "        \
      "clipmap cache around the eye (rays cast through its levels; the bound achieved is "      \
      "reported)")                                                                              \
    X(clipmap, side, U32, clipmap_side, 16, 4096, NULL, "256", "samples",                         \
      "samples per clipmap level side (a power of two)")                                         \
    X(clipmap, levels, U32, clipmap_levels, 1, 16, NULL, "5", "levels",                          \
      "nested clipmap levels, level l spaced 2^l samples")                                       \
    X(clipmap, update_samples_max, U32, clipmap_update_samples_max, 32, 16777216, NULL, "16384", \
      "samples", "most samples one cache update reads and uploads (at least 2 x side)")          \
    X(clipmap, updates_per_frame, U32, clipmap_updates_per_frame, 0, 4096, NULL, "8", "updates", \
      "cache updates the selection runs each frame; more run in the frame's spare time")         \
    X(clipmap, transition_samples, F64, clipmap_transition_samples, 1, 1024, NULL, "16",         \
      "samples", "width of the band where a level morphs into the next coarser one")             \
    X(clipmap, tile_slots, U32, clipmap_tile_slots, 1, 64, NULL, "16", "tiles",                  \
      "over a .ftd: decoded database tiles kept for the cache's reads (budget.clip_bytes)")      \
    X(presentation, colouring, ENUM, present_relative, 0, 0, "absolute|relative|", "absolute",   \
      "", "a height ramp, or bands of height relative to the aircraft painted over it")          \
    X(presentation, palette, ENUM, present_palette, 0, 0, "day|night|", "day", "",               \
      "colour palette (a GPIO night line overrides it)")                                         \
    X(presentation, horizon, FLAG, present_horizon, 0, 1, NULL, "0", "",                         \
      "draw the conformal zero-pitch line")                                                      \
    X(presentation, haze_km, OFF_F64, present_haze_km, FT_HAZE_KM_MIN, FT_HAZE_KM_MAX, NULL,     \
      "0", "km", "distance haze visibility (0 = no haze)")                                       \
    X(presentation, grid_m, OFF_F64, present_grid_m, FT_GRID_M_MIN, FT_GRID_M_MAX, NULL, "0",    \
      "m", "ground grid spacing (0 = no grid)")                                                  \
    X(metric, enabled, FLAG, metric_enabled, 0, 1, NULL, "0", "",                                \
      "measure the screen-space error against the reference")                                    \
    X(metric, truth_side_samples, U32, metric_truth_side, 0, FT_GRID_SIDE_MAX, NULL, "0",         \
      "samples", ".ftd window: samples per side of the database window the truth reads around "  \
      "the eye (0 = terrain.db_side_samples)")                                                   \
    X(frame, period_ms, F64, frame_period_ms, 1, 1000, NULL, "16.667", "ms",                     \
      "display frame period; replay renders one frame per period of log time")                   \
    X(frame, budget_ms, F64, frame_budget_ms, 0, 1000, NULL, "0", "ms",                          \
      "the frame's time budget (0 = the period)")                                                \
    X(frame, degrade, FLAG, frame_degrade, 0, 1, NULL, "0", "",                                  \
      "coarsen the LOD when frames exceed the budget (off keeps replay deterministic)")          \
    X(frame, degrade_max_scale, F64, frame_degrade_max_scale, 1, 64, NULL, "8", "",              \
      "most the LOD may be coarsened (tau x scale)")                                             \
    X(pose_input, horizon_ms, U32, pose_horizon_ms, 0, FT_POSE_HORIZON_MAX_MS, NULL, "100", "ms", \
      "prediction horizon: attitude from the body rates, position from the velocity")            \
    X(pose_input, velocity_required, FLAG, pose_velocity_required, 0, 1, NULL, "0", "",          \
      "a stale velocity raises the annunciation (1) or only stops position prediction (0)")      \
    X(pose_input, converge_ms, U32, pose_converge_ms, 0, FT_POSE_CONVERGE_MAX_MS, NULL, "300",   \
      "ms", "time constant of the drawn position converging to a disagreeing fix (0 = at once)") \
    X(pose_input, snap_m, F64, pose_snap_m, FT_POSE_SNAP_MIN_M, FT_POSE_SNAP_MAX_M, NULL, "100", \
      "m", "a disagreement larger than this is snapped to, not converged (and counted)")         \
    X(can, interface, TEXT, can_iface, 0, 0, NULL, "vcan0", "", "SocketCAN interface (live input)") \
    X(can, backup_interface, TEXT, can_backup_iface, 0, 0, NULL, "", "",                         \
      "backup SocketCAN interface; empty = none")                                                \
    X(can, failover_ms, U32, can_failover_ms, 1, 10000, NULL, "200", "ms",                       \
      "primary silent this long while the backup is alive: switch to the backup")                \
    X(gpio, chip, TEXT, gpio_chip, 0, 0, NULL, "", "",                                           \
      "gpiochip name or path (live input); empty = no GPIO")                                     \
    X(gpio, freeze_line, LINE, gpio_input_line[FT_GPIO_FREEZE], 0, FT_GPIO_LINE_MAX, NULL, "-1", \
      "", "input: hold the drawn pose while active")                                             \
    X(gpio, source_line, LINE, gpio_input_line[FT_GPIO_SOURCE], 0, FT_GPIO_LINE_MAX, NULL, "-1", \
      "", "input: use can.backup_interface while active")                                        \
    X(gpio, test_line, LINE, gpio_input_line[FT_GPIO_TEST], 0, FT_GPIO_LINE_MAX, NULL, "-1", "", \
      "input: annunciation (lamp) test while active")                                            \
    X(gpio, night_line, LINE, gpio_input_line[FT_GPIO_NIGHT], 0, FT_GPIO_LINE_MAX, NULL, "-1",   \
      "", "input: night palette while active (else presentation.palette)")                       \
    X(gpio, heartbeat_line, LINE, gpio_heartbeat_line, 0, FT_GPIO_LINE_MAX, NULL, "-1", "",      \
      "output: toggled once per presented frame")                                                \
    X(gpio, active_low, FLAG, gpio_active_low, 0, 1, NULL, "0", "", "inputs are active low")     \
    X(gpio, debounce_ms, U32, gpio_debounce_ms, 0, 1000, NULL, "10", "ms",                       \
      "an input level must hold this long")                                                      \
    X(build, inputs, BITS, build_inputs, 0, 0, "replay|can|gpio|", "replay,can,gpio", "",        \
      "what the pose comes from, for a lean build (cmake -DFIXTERRAIN_PROFILE=SCENE.ini)")       \
    X(build, png, FLAG, build_png, 0, 1, NULL, "1", "", "the build needs PNG output")            \
    FT_SCENE_BUDGET_KEYS(X)

/* budget.<pool>_bytes, one per pool of mem_budget.h (a test checks that
 * every pool has its row). */
#define FT_SCENE_BUDGET_KEY(X, pool, key, def)                                                   \
    X(budget, key, U64, budget_bytes[pool], 0, FT_SCENE_BYTES_MAX, NULL, def, "bytes",            \
      "memory pool budget (src/core/mem_budget.h)")
#define FT_SCENE_BUDGET_KEYS(X)                                                                  \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_HEIGHTS, heights_bytes, "6M")                                 \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_PYRAMIDS, pyramids_bytes, "18M")                              \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_DEM_IO, dem_io_bytes, "2M")                                   \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_FRAME_RGBA, frame_rgba_bytes, "5M")                           \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_FRAME_POS, frame_pos_bytes, "0")                              \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_REFERENCE, reference_bytes, "0")                              \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_METRIC, metric_bytes, "0")                                    \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_GPU_STAGING, gpu_staging_bytes, "6M")                         \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_METHOD, method_bytes, "4M")                                   \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_PNG, png_bytes, "512K")                               \
    FT_SCENE_BUDGET_KEY(X, FT_POOL_CLIP, clip_bytes, "0")

/* Keys whose value is a list, names a device or may be left empty, each
 * parsed by its own function in scene.c: X(section, key, parser, default, meaning); key `*`
 * takes every key of the section that has no row of its own. */
#define FT_SCENE_LIST_KEYS(X)                                                                    \
    X(terrain, db_centre_lat_deg, parse_db_centre, "",                                           \
      ".ftd window centre latitude -90..90 deg; empty = the middle of the level's data tiles")    \
    X(terrain, db_centre_lon_deg, parse_db_centre, "",                                           \
      ".ftd window centre longitude -180..180 deg; empty = the middle of the level's data tiles") \
    X(scene, display, parse_display, "none",                                                     \
      "where frames are shown: none (offscreen) | x11 | kms | kms:/dev/dri/cardN")               \
    X(display, mode, parse_display_mode, "",                                                     \
      "KMS mode: WxH, WxH@HZ or preferred; empty = a mode of the view size (shown 1:1, never "   \
      "scaled)")                                                                                 \
    X(presentation, band_edges_ft, parse_band_edges_key, "-1000, -100",                              \
      "1 to 5 band edges in ft relative to the aircraft (negative: below it), strictly "         \
      "increasing, within +-60000")                                                              \
    X(presentation, band_rgba, parse_band_rgba_key, "00000000, FFCC0099, FF0000B3",                  \
      "edges + 1 band colours RRGGBBAA: colour and how much of it covers the terrain colour")   \
    X(can_map, defaults, parse_can_map_defaults, "1",                                            \
      "start from the CANaerospace default ids (1) or an empty map (0); put it first")           \
    X(can_map, *, parse_can_map_entry, NULL,                                                     \
      "<quantity> = ID,SCALE,MIN,MAX,TIMEOUT_MS[,PRIORITY]: map 11-bit CAN id ID to pitch, "     \
      "roll, heading, lat, lon, alt, pitch_rate, roll_rate, yaw_rate, ground_speed, track or "   \
      "alt_rate; value = decoded x SCALE, valid in [MIN, MAX] (for pose quantities within the "  \
      "pose range), stale after TIMEOUT_MS; replaces the entry with the same id or priority; "  \
      "at most FT_CAN_MAP_MAX entries")

#define FT_SCENE_BYTES_MAX (1ull << 40) /* largest byte count a scene may state */

typedef enum ft_scene_key_kind {
    FT_KEY_U32,
    FT_KEY_U64,
    FT_KEY_F64,
    FT_KEY_FLAG,
    FT_KEY_OFF_F64,
    FT_KEY_ENUM,
    FT_KEY_BITS,
    FT_KEY_LINE,
    FT_KEY_TEXT,
    FT_KEY_LIST /* FT_SCENE_LIST_KEYS: parsed by its own function */
} ft_scene_key_kind;

/* One row of the schema, as the parser, validator and key list see it. */
typedef struct ft_scene_key {
    const char *section, *key;
    ft_scene_key_kind kind;
    size_t offset, size; /* the field in ft_scene (FT_KEY_LIST: 0, 0) */
    double min, max;
    const char *choices; /* ENUM, BITS: "a|b|c|" */
    const char *def;     /* the default as a scene file says it; NULL = none */
    const char *unit;
    const char *doc;
} ft_scene_key;

/* Every row, in file order ([pose] after [view]); *count set. */
const ft_scene_key *ft_scene_keys(size_t *count);

/* "16..8192 px", "0 or 1", "auto, sphere or flat": what a key accepts
 * (FT_KEY_LIST: its meaning). Returns text. */
const char *ft_scene_key_accepts(const ft_scene_key *k, char *text, size_t cap);

/* The embedded default scene (config/default.ini, compiled in). */
extern const char ft_default_scene_text[];

/* Fills every field with its default: each row's default text through the
 * parser (config/default.ini says the same). */
void ft_scene_defaults(ft_scene *s);

/* Checks the schema itself: no key twice, every default accepted by its own
 * row (tests; scratch is any ft_scene, overwritten). */
ft_status ft_scene_schema_check(ft_scene *scratch, ft_error *err);

/* Parses INI text over the current contents of s (start from defaults). */
ft_status ft_scene_parse(ft_scene *s, const char *text, const char *source_name, ft_error *err);

/* Range checks across fields (after parsing and command-line overrides). */
ft_status ft_scene_validate(const ft_scene *s, ft_error *err);

/* The range of every pose field: one table for every way a pose enters (a
 * scene's [pose], --pose, bench --centre, the CAN map's position and attitude
 * entries), so no path can hand the renderer what a scene may not say.
 * X(id, field of ft_pose, min, max, unit, the scene's default); the order is
 * --pose's order. A scene's [pose] keys are generated from it. */
#define FT_POSE_FIELD_LIST(X)                                      \
    X(FT_POSE_LAT, lat_deg, -89.0, 89.0, "deg", "46.52698")        \
    X(FT_POSE_LON, lon_deg, -360.0, 360.0, "deg", "8.200674")      \
    X(FT_POSE_ALT, alt_m, -12000.0, 1e6, "m", "4200")              \
    X(FT_POSE_HEADING, heading_deg, -1e9, 1e9, "deg", "10")        \
    X(FT_POSE_PITCH, pitch_deg, -90.0, 90.0, "deg", "-18")         \
    X(FT_POSE_ROLL, roll_deg, -1e9, 1e9, "deg", "0")

typedef enum ft_pose_field {
#define FT_POSE_FIELD_ENUM(id, field, lo, hi, unit, def) id,
    FT_POSE_FIELD_LIST(FT_POSE_FIELD_ENUM)
#undef FT_POSE_FIELD_ENUM
    FT_POSE_FIELD_COUNT
} ft_pose_field;

typedef struct ft_pose_range {
    const char *key; /* "alt_m": the scene key in [pose] */
    double min, max; /* inclusive */
    const char *unit;
} ft_pose_range;

/* The field's range (NULL for an id outside the table). */
const ft_pose_range *ft_pose_range_of(ft_pose_field f);

/* The field's value in p, or a pointer to it. */
double ft_pose_get(const ft_pose *p, ft_pose_field f);
double *ft_pose_field_ptr(ft_pose *p, ft_pose_field f);

/* 1 when v is finite and inside the field's range. */
int ft_pose_field_ok(ft_pose_field f, double v);

/* FT_ERR_ARG naming the first field of p that is not finite or out of its
 * range, and that range: "WHERE: pose.alt_m = 1e+300 outside [-12000, 1e+06] m". */
ft_status ft_pose_check(const ft_pose *p, const char *where, ft_error *err);

/* Parses "LAT,LON,ALT_M,HEADING_DEG,PITCH_DEG,ROLL_DEG"; every field within
 * FT_POSE_FIELD_LIST (an error names the field and its range). */
ft_status ft_pose_parse(const char *text, ft_pose *out, ft_error *err);

#endif
