/* scene.h - a scene file (INI, parsed with libinih) resolved into one const
 * struct. Zero/absent means "default", resolved once by ft_scene_defaults();
 * shipped files in config/ still set every key. Unknown sections or keys,
 * and values out of range, are errors with the line number: a typo in a
 * budget must never silently fall back to a default.
 *
 * Keys (section.key = meaning [range]):
 *   scene.name            text (<= 63 chars)
 *   scene.method          brute | bintree | pgm | pgrid     (methods built in)
 *   scene.backend         egl-gles3 | egl-gles2 | osmesa
 *   scene.display         none | x11 | kms | kms:/dev/dri/cardN   (where frames are
 *                         shown; none = offscreen; kms = full screen on DRM/KMS)
 *   display.connector     KMS connector: name as the kernel spells it (HDMI-A-1,
 *                         Virtual-1, ...) or its id; empty = the first connected
 *   display.mode          KMS mode: WxH, WxH@HZ or preferred; empty = a mode of the
 *                         view size. Frames are shown 1:1 (never scaled), so the
 *                         mode's size must equal view.width_px x view.height_px
 *   view.width_px, view.height_px   [16, 8192]
 *   view.fovy_deg         [1, 170]
 *   pose.lat_deg [-89,89] pose.lon_deg [-360,360] pose.alt_m [-12000, 1e6]
 *   pose.heading_deg [-1e9,1e9] pose.pitch_deg [-90,90] pose.roll_deg [-1e9,1e9]
 *                         (FT_POSE_FIELD_LIST: the same ranges for --pose, bench
 *                         --centre and the CAN map's position/attitude entries)
 *   terrain.dem           path to .ftt or .hgt, relative to the scene file; empty = synthetic
 *   terrain.synth_side    [3, 16385]   terrain.synth_spacing_m (0, 1e5]
 *   terrain.synth_relief_m [0, 9000]   terrain.synth_seed, terrain.synth_octaves [1,16]
 *   terrain.synth_anchor_lat_deg, terrain.synth_anchor_lon_deg
 *   terrain.curvature     auto | sphere | flat: earth curvature (terrain.h): every
 *                         method, ray caster and the metric's truth lower a point
 *                         d metres from the eye by d^2 / (2 R); auto = sphere for
 *                         a grid in degrees (SRTM, EPSG:4326), flat for one in
 *                         metres (projected or local, e.g. the synthetic terrain)
 *   gpu.height_format     auto | float | packed
 *   gpu.texture_bytes     budget for all GPU textures and buffers
 *   gpu.pyramid_textures  0 | 1: also upload the avg/min/max pyramids as textures
 *   brute.patch_cells     template patch side in cells [1, 180]
 *   brute.max_vertices    most grid vertices brute draws per frame (window)
 *   bintree.template_k    template refinement: 2k bisections, 2^k segments per leg [1, 6]
 *   bintree.tiles_max     tile budget per frame [2, 1048576]
 *   bintree.tau_px        target screen-space error in pixels [0, 1000]
 *   bintree.morph         0 | 1: geomorph split vertices (split at split_fraction x tau)
 *   bintree.split_fraction  [0.5, 0.95]: with morph, a diamond splits at this x tau and
 *                         its vertices morph in before tau (higher: fewer triangles,
 *                         faster morphs)
 *   bintree.subsample_levels  0..4: tiles refine to 2^-S of a cell, their vertices
 *                         on the bilinear surface (the truth), so tau holds near the eye
 *   bintree.vertex_table  0 | 1 (GLES 3): a vertex on a sample reads one RGBA32F texel
 *                         (height, coarse height, diamond error, normal: 16 bytes a
 *                         sample of GPU memory) instead of 8 fetches; 0 saves the memory
 *   pgm.grid_cols         persistent grid columns (vertices across the view) [2, 8192]
 *   pgm.grid_rows         persistent grid rows (vertices from near to far) [2, 8192]
 *                         (pgm uploads its own avg-pyramid atlas: gpu.pyramid_textures
 *                         is not needed; see src/lod/pgm.h)
 *   pgrid.grid_cols, pgrid.grid_rows   the error-bounded projective grid (method pgrid)
 *                         [2, 8192] each (src/lod/pgrid.h)
 *   pgrid.distribution    uniform | view: grid rows evenly on the sampling image plane,
 *                         or evenly in asinh(ground distance / height) (cells close to
 *                         square on the ground)
 *   pgrid.ray_casting     0 | 1: ray cast the pixels whose error exceeds gamma_px
 *                         (GLES 3 only; on GLES 2 pgrid runs without it and says so)
 *   pgrid.gamma_px        screen-space error bound in pixels [0.1, 100]
 *   pgrid.raycast_max_px  most pixels ray cast per frame [0, 67108864]; above it
 *                         gamma is raised for that frame and the error achieved reported
 *   metric.enabled        0 | 1: measure screen-space error against the reference
 *   frame.period_ms       display frame period [1, 1000] (16.667 = 60 Hz); replay
 *                         renders one frame per period of log time
 *   frame.budget_ms       the frame's time budget [0, 1000]; 0 = the period
 *   frame.degrade         0 | 1: coarsen the LOD when frames exceed the budget
 *                         (src/lod/degrade.h; off keeps replay deterministic)
 *   frame.degrade_max_scale  [1, 64]: most the LOD may be coarsened (tau x scale)
 *   pose_input.horizon_ms prediction horizon [0, 1000] (0 = no prediction): attitude
 *                         from the body rates, position from the velocity
 *   pose_input.velocity_required  0 | 1: a stale velocity (ground speed, track,
 *                         altitude rate) raises the annunciation (1) or only stops
 *                         the position prediction (0)
 *   pose_input.converge_ms [0, 10000]: time constant with which the drawn position
 *                         converges to a fix that disagrees with the prediction
 *                         (0 = at once)
 *   pose_input.snap_m     [1, 100000]: a disagreement larger than this is not
 *                         converged but snapped to (and counted)
 *   can.interface, can.backup_interface   SocketCAN interfaces (live input;
 *                         backup empty = none), can.failover_ms [1, 10000]
 *   can_map.defaults      0 | 1: start from the CANaerospace default ids (1) or
 *                         from an empty map (0; put it first in [can_map])
 *   can_map.<quantity>    ID,SCALE,MIN,MAX,TIMEOUT_MS[,PRIORITY]: map CAN id ID
 *                         (11-bit) to quantity pitch|roll|heading|lat|lon|alt|
 *                         pitch_rate|roll_rate|yaw_rate|ground_speed|track|
 *                         alt_rate; value = decoded * SCALE,
 *                         valid in [MIN, MAX], stale after TIMEOUT_MS; replaces
 *                         the quantity's entry with the same id or priority (an
 *                         id mapped to another quantity is an error); at most
 *                         FT_CAN_MAP_MAX (24) entries; for lat, lon, alt, heading,
 *                         pitch and roll, [MIN, MAX] lies within the pose range
 *                         table (the default map's latitude is narrowed to +-89)
 *   gpio.chip             gpiochip name or path (live input; empty = no GPIO)
 *   gpio.freeze_line      input: hold the drawn pose while active [-1 = none, 0..511]
 *   gpio.source_line      input: use can.backup_interface while active
 *   gpio.test_line        input: annunciation test (lamp test) while active
 *   gpio.heartbeat_line   output: toggled once per presented frame
 *   gpio.active_low       0 | 1: inputs are active low
 *   gpio.debounce_ms      [0, 1000]: an input level must hold this long
 *   build.inputs          what the scene's pose comes from, for a lean build
 *                         (cmake -DFIXTERRAIN_PROFILE=SCENE.ini): a comma list of
 *                         replay, can, gpio (replay = candump logs only)
 *   build.png             0 | 1: the build needs PNG output
 *   budget.<pool>_bytes   one per pool in mem_budget.h (heights_bytes, ...) */
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
    X(FT_METHOD_PGRID, "pgrid", "error-bounded projective grid, ray casting over gamma")

typedef enum ft_method_kind {
#define FT_METHOD_ENUM(id, name, what) id,
    FT_METHOD_LIST(FT_METHOD_ENUM)
#undef FT_METHOD_ENUM
    FT_METHOD_COUNT
} ft_method_kind;

const char *ft_method_name(ft_method_kind m);
int ft_method_from_name(const char *name, ft_method_kind *out);

/* bintree.split_fraction: default (and least) and most */
#define FT_BT_SPLIT_FRACTION 0.5
#define FT_BT_SPLIT_FRACTION_MAX 0.95

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
    double bintree_split_fraction; /* bintree.split_fraction */
    uint32_t bintree_subsample_levels; /* bintree.subsample_levels */
    int bintree_vertex_table;          /* bintree.vertex_table (GLES 3 only) */
    uint32_t pgm_grid_cols;      /* pgm.grid_cols */
    uint32_t pgm_grid_rows;      /* pgm.grid_rows */
    uint32_t pgrid_grid_cols;    /* pgrid.grid_cols */
    uint32_t pgrid_grid_rows;    /* pgrid.grid_rows */
    int pgrid_view_distribution; /* pgrid.distribution: 0 uniform, 1 view */
    int pgrid_residual_bound;    /* pgrid.error_bound: 0 relief, 1 residual (src/lod/pgrid.h 6) */
    int pgrid_ray_casting;       /* pgrid.ray_casting */
    double pgrid_gamma_px;       /* pgrid.gamma_px */
    uint32_t pgrid_raycast_max_px; /* pgrid.raycast_max_px */
    int present_relative;   /* presentation.colouring: 0 absolute, 1 relative */
    ft_palette present_palette; /* presentation.palette: day | night */
    ft_bands present_bands; /* presentation.band_edges_ft, band_rgba */
    int present_horizon;    /* presentation.horizon: the conformal zero-pitch line */
    double present_haze_km; /* presentation.haze_km: haze visibility, 0 = none */
    double present_grid_m;  /* presentation.grid_m: ground grid spacing, 0 = none */
    int metric_enabled; /* metric.enabled: position target, reference, error stats */
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

/* The embedded default scene (config/default.ini, compiled in). */
extern const char ft_default_scene_text[];

/* Fills every field with its default (what config/default.ini also says). */
void ft_scene_defaults(ft_scene *s);
/* The default relative-altitude bands (presentation.band_*). */
void ft_scene_default_bands(ft_bands *b);

/* Parses INI text over the current contents of s (start from defaults). */
ft_status ft_scene_parse(ft_scene *s, const char *text, const char *source_name, ft_error *err);

/* Range checks across fields (after parsing and command-line overrides). */
ft_status ft_scene_validate(const ft_scene *s, ft_error *err);

/* The range of every pose field: one table for every way a pose enters (a
 * scene's [pose], --pose, bench --centre, the CAN map's position and attitude
 * entries), so no path can hand the renderer what a scene may not say.
 * X(id, field of ft_pose, min, max, unit); the order is --pose's order. */
#define FT_POSE_FIELD_LIST(X)                              \
    X(FT_POSE_LAT, lat_deg, -89.0, 89.0, "deg")            \
    X(FT_POSE_LON, lon_deg, -360.0, 360.0, "deg")          \
    X(FT_POSE_ALT, alt_m, -12000.0, 1e6, "m")              \
    X(FT_POSE_HEADING, heading_deg, -1e9, 1e9, "deg")      \
    X(FT_POSE_PITCH, pitch_deg, -90.0, 90.0, "deg")        \
    X(FT_POSE_ROLL, roll_deg, -1e9, 1e9, "deg")

typedef enum ft_pose_field {
#define FT_POSE_FIELD_ENUM(id, field, lo, hi, unit) id,
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
