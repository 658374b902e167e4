#include "core/scene.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const k_method_name[FT_METHOD_COUNT] = {
#define FT_METHOD_NAME(id, name, what) name,
    FT_METHOD_LIST(FT_METHOD_NAME)
#undef FT_METHOD_NAME
};

const char *ft_method_name(ft_method_kind m)
{
    return ((unsigned)m < FT_METHOD_COUNT) ? k_method_name[m] : "?";
}

int ft_method_from_name(const char *name, ft_method_kind *out)
{
    for (int i = 0; i < FT_METHOD_COUNT; ++i) {
        if (strcmp(name, k_method_name[i]) == 0) {
            *out = (ft_method_kind)i;
            return 1;
        }
    }
    return 0;
}

static const char *const k_gpio_input_name[FT_GPIO_INPUT_COUNT] = {
#define FT_GPIO_INPUT_NAME(id, name, what) name,
    FT_GPIO_INPUT_LIST(FT_GPIO_INPUT_NAME)
#undef FT_GPIO_INPUT_NAME
};

const char *ft_gpio_input_name(ft_gpio_input i)
{
    return ((unsigned)i < FT_GPIO_INPUT_COUNT) ? k_gpio_input_name[i] : "?";
}

static const ft_pose_range k_pose_range[FT_POSE_FIELD_COUNT] = {
#define FT_POSE_FIELD_RANGE(id, field, lo, hi, unit) [id] = {#field, lo, hi, unit},
    FT_POSE_FIELD_LIST(FT_POSE_FIELD_RANGE)
#undef FT_POSE_FIELD_RANGE
};

const ft_pose_range *ft_pose_range_of(ft_pose_field f)
{
    return ((unsigned)f < FT_POSE_FIELD_COUNT) ? &k_pose_range[f] : NULL;
}

double *ft_pose_field_ptr(ft_pose *p, ft_pose_field f)
{
    switch (f) {
#define FT_POSE_FIELD_CASE(id, field, lo, hi, unit) \
    case id: return &p->field;
        FT_POSE_FIELD_LIST(FT_POSE_FIELD_CASE)
#undef FT_POSE_FIELD_CASE
    default: return NULL;
    }
}

double ft_pose_get(const ft_pose *p, ft_pose_field f)
{
    switch (f) {
#define FT_POSE_FIELD_GET(id, field, lo, hi, unit) \
    case id: return p->field;
        FT_POSE_FIELD_LIST(FT_POSE_FIELD_GET)
#undef FT_POSE_FIELD_GET
    default: return NAN;
    }
}

int ft_pose_field_ok(ft_pose_field f, double v)
{
    const ft_pose_range *r = ft_pose_range_of(f);
    return r != NULL && isfinite(v) && v >= r->min && v <= r->max;
}

ft_status ft_pose_check(const ft_pose *p, const char *where, ft_error *err)
{
    for (int f = 0; f < FT_POSE_FIELD_COUNT; ++f) {
        const double v = ft_pose_get(p, (ft_pose_field)f);
        if (!ft_pose_field_ok((ft_pose_field)f, v)) {
            const ft_pose_range *r = &k_pose_range[f];
            return ft_fail(err, FT_ERR_ARG, "%s: pose.%s = %g %s (want a finite value in [%g, %g] %s)",
                           where, r->key, v, isfinite(v) ? "is out of range" : "is not finite",
                           r->min, r->max, r->unit);
        }
    }
    return FT_OK;
}

/* The pose field a CAN quantity drives (-1: a rate or velocity, no pose field). */
static int can_qty_pose_field(ft_pose_qty q)
{
    switch (q) {
    case FT_QTY_LAT: return FT_POSE_LAT;
    case FT_QTY_LON: return FT_POSE_LON;
    case FT_QTY_ALT: return FT_POSE_ALT;
    case FT_QTY_HEADING: return FT_POSE_HEADING;
    case FT_QTY_PITCH: return FT_POSE_PITCH;
    case FT_QTY_ROLL: return FT_POSE_ROLL;
    default: return -1;
    }
}

/* The CANaerospace default map accepts latitudes to +-90; the decoder's
 * valid range of a position or attitude entry is kept inside the pose range
 * table, so CAN can deliver no pose a scene could not state. */
static void can_map_to_pose_ranges(ft_can_map *m)
{
    for (uint32_t i = 0; i < m->count && i < FT_CAN_MAP_MAX; ++i) {
        const int f = can_qty_pose_field(m->e[i].qty);
        if (f < 0) continue;
        const ft_pose_range *r = &k_pose_range[f];
        m->e[i].min_value = fmax(m->e[i].min_value, r->min);
        m->e[i].max_value = fmin(m->e[i].max_value, r->max);
    }
}

/* TAWS practice (e.g. the FAA's Advanced Avionics Handbook): terrain more
 * than 1000 ft below the aircraft as it is, 1000 to 100 ft below yellow,
 * within 100 ft below or above red; painted over the terrain colour at 60%
 * and 70% so the relief stays readable (config/default.ini says the same). */
void ft_scene_default_bands(ft_bands *b)
{
    static const float rgba[3][4] = {
        {0.0f, 0.0f, 0.0f, 0.0f},
        {1.0f, 204.0f / 255.0f, 0.0f, 153.0f / 255.0f}, /* FFCC0099 */
        {1.0f, 0.0f, 0.0f, 179.0f / 255.0f}};           /* FF0000B3 */
    memset(b, 0, sizeof *b);
    b->edges = 2u;
    b->edge_ft[0] = -1000.0f;
    b->edge_ft[1] = -100.0f;
    b->colours = 3u;
    memcpy(b->rgba, rgba, sizeof rgba);
}

void ft_scene_defaults(ft_scene *s)
{
    memset(s, 0, sizeof *s);
    (void)snprintf(s->name, sizeof s->name, "%s", "default");
    s->method = FT_METHOD_PGRID;
    s->backend = FT_BACKEND_EGL_GLES3;
    s->display = FT_DISPLAY_NONE;
    s->width_px = 800;
    s->height_px = 600;
    s->fovy_deg = 60.0;
    s->synth.side = 1025;
    s->synth.spacing_m = 30.0;
    s->synth.relief_m = 2400.0;
    s->synth.seed = 1;
    s->synth.octaves = 9;
    s->synth.anchor_lat_deg = 46.5;
    s->synth.anchor_lon_deg = 8.0;
    s->pose.lat_deg = 46.52698;
    s->pose.lon_deg = 8.200674;
    s->pose.alt_m = 4200.0;
    s->pose.heading_deg = 10.0;
    s->pose.pitch_deg = -18.0;
    s->pose.roll_deg = 0.0;
    s->curvature = FT_CURVATURE_AUTO;
    s->height_format = FT_HEIGHT_FORMAT_AUTO;
    s->gpu_texture_bytes = 64ull << 20;
    s->brute_patch_cells = 64;
    s->brute_max_vertices = 4200000;
    s->bintree_template_k = 3;
    s->bintree_tiles_max = 16384;
    s->bintree_tau_px = 1.0;
    s->bintree_morph = 1;
    s->bintree_subsample_levels = 0;
    s->bintree_vertex_table = 1;
    s->bintree_split_fraction = FT_BT_SPLIT_FRACTION;
    s->pgm_grid_cols = 430;
    s->pgm_grid_rows = 430;
    s->pgrid_grid_cols = 200;
    s->pgrid_grid_rows = 800;
    s->pgrid_view_distribution = 1;
    s->pgrid_ray_casting = 1;
    s->pgrid_gamma_px = 1.0;
    s->pgrid_raycast_max_px = 262144;
    s->present_relative = 0;
    s->present_palette = FT_PALETTE_DAY;
    ft_scene_default_bands(&s->present_bands);
    s->present_horizon = 0;
    s->present_haze_km = 0.0;
    s->present_grid_m = 0.0;
    s->metric_enabled = 0;
    s->frame_period_ms = 16.667;
    s->frame_budget_ms = 0.0;
    s->frame_degrade = 0;
    s->frame_degrade_max_scale = 8.0;
    s->pose_horizon_ms = FT_POSE_HORIZON_DEFAULT_MS;
    s->pose_velocity_required = 0;
    s->pose_converge_ms = FT_POSE_CONVERGE_DEFAULT_MS;
    s->pose_snap_m = FT_POSE_SNAP_DEFAULT_M;
    (void)snprintf(s->can_iface, sizeof s->can_iface, "%s", "vcan0");
    s->can_backup_iface[0] = '\0';
    s->can_failover_ms = 200;
    ft_canaero_default_map(&s->can_map);
    can_map_to_pose_ranges(&s->can_map);
    s->gpio_chip[0] = '\0';
    for (int i = 0; i < FT_GPIO_INPUT_COUNT; ++i) {
        s->gpio_input_line[i] = -1;
    }
    s->gpio_heartbeat_line = -1;
    s->gpio_active_low = 0;
    s->gpio_debounce_ms = 10;
    s->build_inputs = FT_BUILD_INPUT_REPLAY | FT_BUILD_INPUT_CAN | FT_BUILD_INPUT_GPIO;
    s->build_png = 1;
    /* Budgets of config/default.ini (tests/test_scene.c checks they agree). */
    s->budget_bytes[FT_POOL_HEIGHTS] = 6ull << 20;
    s->budget_bytes[FT_POOL_PYRAMIDS] = 18ull << 20;
    s->budget_bytes[FT_POOL_DEM_IO] = 2ull << 20;
    s->budget_bytes[FT_POOL_FRAME_RGBA] = 5ull << 20;
    s->budget_bytes[FT_POOL_GPU_STAGING] = 6ull << 20;
    s->budget_bytes[FT_POOL_METHOD] = 4ull << 20;
    s->budget_bytes[FT_POOL_PNG] = 512ull << 10;
}

typedef struct parse_ctx {
    ft_scene *scene;
    ft_error *err;
    ft_status status;
    const char *source;
    char first_error[200];
} parse_ctx;

/* Records the first failure only; libinih goes on parsing and reports the
 * line number of the first failing line, which ft_scene_parse prepends. */
static int fail_key(parse_ctx *c, const char *section, const char *key, const char *value,
                    const char *why)
{
    if (c->status == FT_OK) {
        c->status = FT_ERR_CONFIG;
        (void)snprintf(c->first_error, sizeof c->first_error, "%s.%s = '%.60s': %s", section,
                       key, value, why);
    }
    return 0;
}

static int parse_f64(const char *v, double lo, double hi, double *out)
{
    char *end = NULL;
    errno = 0;
    double d = strtod(v, &end);
    if (end == v || *end != '\0' || errno != 0 || !isfinite(d) || d < lo || d > hi) {
        return 0;
    }
    *out = d;
    return 1;
}

/* 0 (the part is off) or a number in [lo, hi]. */
static int parse_off_or_f64(const char *v, double lo, double hi, double *out)
{
    double d;
    if (!parse_f64(v, 0.0, hi, &d) || (d > 0.0 && d < lo)) {
        return 0;
    }
    *out = d;
    return 1;
}

static int parse_u64(const char *v, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char *end = NULL;
    if (v[0] == '-' || v[0] == '\0') {
        return 0;
    }
    errno = 0;
    unsigned long long u = strtoull(v, &end, 10);
    if (end == v || errno != 0) {
        return 0;
    }
    /* Optional binary suffix for budgets: 64M, 512K, 2G. */
    uint64_t mul = 1;
    if (*end == 'K') mul = 1ull << 10;
    if (*end == 'M') mul = 1ull << 20;
    if (*end == 'G') mul = 1ull << 30;
    if (mul != 1) {
        ++end;
    }
    if (*end != '\0' || (mul != 1 && u > UINT64_MAX / mul)) {
        return 0;
    }
    u *= mul;
    if (u < lo || u > hi) {
        return 0;
    }
    *out = u;
    return 1;
}

static int parse_u32(const char *v, uint32_t lo, uint32_t hi, uint32_t *out)
{
    uint64_t u;
    if (!parse_u64(v, lo, hi, &u)) {
        return 0;
    }
    *out = (uint32_t)u;
    return 1;
}

/* A 0|1 switch into an int. */
/* "E1, E2, ...": 1..FT_BANDS_MAX-1 numbers in ft, strictly increasing. */
static int parse_band_edges(const char *v, ft_bands *b)
{
    uint32_t n = 0u;
    const char *p = v;
    for (uint32_t guard = 0u; guard < FT_BANDS_MAX; ++guard) {
        char *end = NULL;
        errno = 0;
        const double d = strtod(p, &end);
        if (end == p || errno != 0 || !isfinite(d) || d < -FT_BAND_EDGE_LIMIT_FT ||
            d > FT_BAND_EDGE_LIMIT_FT || n >= FT_BANDS_MAX - 1u ||
            (n > 0u && !(d > (double)b->edge_ft[n - 1u]))) {
            return 0;
        }
        b->edge_ft[n++] = (float)d;
        while (*end == ' ' || *end == '\t') ++end;
        if (*end == '\0') {
            b->edges = n;
            return 1;
        }
        if (*end != ',') {
            return 0;
        }
        p = end + 1;
    }
    return 0;
}

/* "RRGGBBAA, ...": 2..FT_BANDS_MAX colours, 8 hex digits each. */
static int parse_band_rgba(const char *v, ft_bands *b)
{
    uint32_t n = 0u;
    const char *p = v;
    for (uint32_t guard = 0u; guard < FT_BANDS_MAX; ++guard) {
        while (*p == ' ' || *p == '\t') ++p;
        uint32_t word = 0u;
        for (int i = 0; i < 8; ++i) {
            const char ch = p[i];
            uint32_t d;
            if (ch >= '0' && ch <= '9') d = (uint32_t)(ch - '0');
            else if (ch >= 'a' && ch <= 'f') d = (uint32_t)(ch - 'a' + 10);
            else if (ch >= 'A' && ch <= 'F') d = (uint32_t)(ch - 'A' + 10);
            else return 0;
            word = (word << 4) | d;
        }
        if (n >= FT_BANDS_MAX) {
            return 0;
        }
        for (int c = 0; c < 4; ++c) {
            b->rgba[n][c] = (float)((word >> (24 - 8 * c)) & 0xffu) / 255.0f;
        }
        ++n;
        p += 8;
        while (*p == ' ' || *p == '\t') ++p;
        if (*p == '\0') {
            if (n < 2u) return 0;
            b->colours = n;
            return 1;
        }
        if (*p != ',') {
            return 0;
        }
        ++p;
    }
    return 0;
}

static int parse_flag(const char *v, int *out)
{
    uint32_t u;
    if (!parse_u32(v, 0, 1, &u)) {
        return 0;
    }
    *out = (int)u;
    return 1;
}

static const char *const k_can_qty_key[FT_QTY_COUNT] = {
    [FT_QTY_PITCH] = "pitch",           [FT_QTY_ROLL] = "roll",
    [FT_QTY_HEADING] = "heading",       [FT_QTY_LAT] = "lat",
    [FT_QTY_LON] = "lon",               [FT_QTY_ALT] = "alt",
    [FT_QTY_PITCH_RATE] = "pitch_rate", [FT_QTY_ROLL_RATE] = "roll_rate",
    [FT_QTY_YAW_RATE] = "yaw_rate",     [FT_QTY_GROUND_SPEED] = "ground_speed",
    [FT_QTY_TRACK] = "track",           [FT_QTY_ALT_RATE] = "alt_rate",
};

/* "ID,SCALE,MIN,MAX,TIMEOUT_MS[,PRIORITY]" into e (qty set by the caller). */
static int parse_can_entry(const char *v, ft_can_map_entry *e)
{
    double f[6];
    int n = 0;
    const char *p = v;
    for (; n < 6; ++n) {
        char *end = NULL;
        errno = 0;
        f[n] = strtod(p, &end);
        if (end == p || errno != 0 || !isfinite(f[n])) {
            return 0;
        }
        p = end;
        while (*p == ' ') ++p;
        if (*p == '\0') {
            ++n;
            break;
        }
        if (*p != ',') {
            return 0;
        }
        ++p;
    }
    if (*p != '\0' || n < 5 || f[0] < 0.0 || f[0] > (double)FT_CAN_STD_ID_MAX ||
        f[0] != floor(f[0]) || f[4] < 1.0 || f[4] > 60000.0 || f[4] != floor(f[4])) {
        return 0;
    }
    if (n == 6 && (f[5] < 0.0 || f[5] > 255.0 || f[5] != floor(f[5]))) {
        return 0;
    }
    e->can_id = (uint16_t)f[0];
    e->scale = f[1];
    e->min_value = f[2];
    e->max_value = f[3];
    e->timeout_ms = (uint32_t)f[4];
    e->priority = (n == 6) ? (uint8_t)f[5] : 0u;
    return 1;
}

/* Replaces an entry for the same quantity with the same id or priority; an id
 * already mapped to another quantity is an error (ft_can_map_add says so). */
static ft_status can_map_upsert(ft_can_map *m, const ft_can_map_entry *e, ft_error *err)
{
    ft_can_map next;
    memset(&next, 0, sizeof next);
    for (uint32_t i = 0; i < m->count && i < FT_CAN_MAP_MAX; ++i) {
        const ft_can_map_entry *o = &m->e[i];
        if ((o->can_id == e->can_id && o->qty == e->qty) ||
            (o->qty == e->qty && o->priority == e->priority)) {
            continue;
        }
        next.e[next.count++] = *o;
    }
    ft_status st = ft_can_map_add(&next, e, err);
    if (st == FT_OK) {
        *m = next;
    }
    return st;
}

#define RANGE(expr, why) ((expr) ? 1 : fail_key(c, section, key, value, why))

static int on_key(void *user, const char *section, const char *key, const char *value)
{
    parse_ctx *c = (parse_ctx *)user;
    ft_scene *s = c->scene;
    if (strcmp(section, "scene") == 0) {
        if (strcmp(key, "name") == 0) {
            if (strlen(value) >= sizeof s->name) {
                return fail_key(c, section, key, value, "longer than 63 characters");
            }
            (void)snprintf(s->name, sizeof s->name, "%s", value);
            return 1;
        }
        if (strcmp(key, "method") == 0) {
            return RANGE(ft_method_from_name(value, &s->method),
                         "unknown method (built in: see 'fixterrain render --help')");
        }
        if (strcmp(key, "display") == 0) {
            return RANGE(ft_display_parse(value, &s->display, s->display_device,
                                          sizeof s->display_device),
                         "unknown display (none, x11, kms, kms:/dev/dri/cardN)");
        }
        if (strcmp(key, "backend") == 0) {
            return RANGE(ft_backend_from_name(value, &s->backend),
                         "unknown backend (egl-gles3, egl-gles2, osmesa)");
        }
    } else if (strcmp(section, "display") == 0) {
        if (strcmp(key, "connector") == 0) {
            if (strlen(value) >= sizeof s->display_connector) {
                return fail_key(c, section, key, value, "longer than 31 characters");
            }
            (void)snprintf(s->display_connector, sizeof s->display_connector, "%s", value);
            return 1;
        }
        if (strcmp(key, "mode") == 0) {
            ft_display_mode m;
            if (strlen(value) >= sizeof s->display_mode) {
                return fail_key(c, section, key, value, "longer than 31 characters");
            }
            if (value[0] != '\0' && !ft_display_mode_parse(value, &m)) {
                return fail_key(c, section, key, value, "expected WxH, WxH@HZ or preferred");
            }
            (void)snprintf(s->display_mode, sizeof s->display_mode, "%s", value);
            return 1;
        }
    } else if (strcmp(section, "view") == 0) {
        if (strcmp(key, "width_px") == 0) {
            return RANGE(parse_u32(value, FT_VIEW_SIDE_MIN_PX, FT_VIEW_SIDE_MAX_PX, &s->width_px), "expected 16..8192");
        }
        if (strcmp(key, "height_px") == 0) {
            return RANGE(parse_u32(value, FT_VIEW_SIDE_MIN_PX, FT_VIEW_SIDE_MAX_PX, &s->height_px), "expected 16..8192");
        }
        if (strcmp(key, "fovy_deg") == 0) {
            return RANGE(parse_f64(value, 1.0, 170.0, &s->fovy_deg), "expected 1..170");
        }
    } else if (strcmp(section, "pose") == 0) {
        s->pose_given = 1;
        for (int f = 0; f < FT_POSE_FIELD_COUNT; ++f) {
            const ft_pose_range *r = &k_pose_range[f];
            if (strcmp(key, r->key) != 0) {
                continue;
            }
            char why[96];
            (void)snprintf(why, sizeof why, "expected %g..%g %s", r->min, r->max, r->unit);
            return RANGE(parse_f64(value, r->min, r->max, ft_pose_field_ptr(&s->pose, (ft_pose_field)f)),
                         why);
        }
    } else if (strcmp(section, "terrain") == 0) {
        if (strcmp(key, "dem") == 0) {
            if (strlen(value) >= sizeof s->dem_path) {
                return fail_key(c, section, key, value, "path too long");
            }
            (void)snprintf(s->dem_path, sizeof s->dem_path, "%s", value);
            return 1;
        }
        if (strcmp(key, "curvature") == 0) {
            if (strcmp(value, "auto") == 0) s->curvature = FT_CURVATURE_AUTO;
            else if (strcmp(value, "sphere") == 0) s->curvature = FT_CURVATURE_SPHERE;
            else if (strcmp(value, "flat") == 0) s->curvature = FT_CURVATURE_FLAT;
            else return fail_key(c, section, key, value, "expected auto, sphere or flat");
            return 1;
        }
        if (strcmp(key, "synth_side") == 0) {
            return RANGE(parse_u32(value, 3, 16385, &s->synth.side), "expected 3..16385");
        }
        if (strcmp(key, "synth_spacing_m") == 0) {
            return RANGE(parse_f64(value, 1e-3, 1e5, &s->synth.spacing_m), "expected 0.001..1e5");
        }
        if (strcmp(key, "synth_relief_m") == 0) {
            return RANGE(parse_f64(value, 0.0, 9000.0, &s->synth.relief_m), "expected 0..9000");
        }
        if (strcmp(key, "synth_seed") == 0) {
            return RANGE(parse_u32(value, 0, UINT32_MAX, &s->synth.seed), "expected a uint32");
        }
        if (strcmp(key, "synth_octaves") == 0) {
            return RANGE(parse_u32(value, 1, 16, &s->synth.octaves), "expected 1..16");
        }
        if (strcmp(key, "synth_anchor_lat_deg") == 0) {
            return RANGE(parse_f64(value, -89.0, 89.0, &s->synth.anchor_lat_deg),
                         "expected -89..89");
        }
        if (strcmp(key, "synth_anchor_lon_deg") == 0) {
            return RANGE(parse_f64(value, -360.0, 360.0, &s->synth.anchor_lon_deg),
                         "expected -360..360");
        }
    } else if (strcmp(section, "gpu") == 0) {
        if (strcmp(key, "height_format") == 0) {
            if (strcmp(value, "auto") == 0) s->height_format = FT_HEIGHT_FORMAT_AUTO;
            else if (strcmp(value, "float") == 0) s->height_format = FT_HEIGHT_FORMAT_FLOAT;
            else if (strcmp(value, "packed") == 0) s->height_format = FT_HEIGHT_FORMAT_PACKED;
            else return fail_key(c, section, key, value, "expected auto, float or packed");
            return 1;
        }
        if (strcmp(key, "pyramid_textures") == 0) {
            return RANGE(parse_flag(value, &s->pyramid_textures), "expected 0 or 1");
        }
        if (strcmp(key, "texture_bytes") == 0) {
            return RANGE(parse_u64(value, 0, 1ull << 40, &s->gpu_texture_bytes),
                         "expected a byte count (suffix K/M/G allowed)");
        }
    } else if (strcmp(section, "brute") == 0) {
        if (strcmp(key, "patch_cells") == 0) {
            return RANGE(parse_u32(value, 1, 180, &s->brute_patch_cells), "expected 1..180");
        }
        if (strcmp(key, "max_vertices") == 0) {
            return RANGE(parse_u32(value, 4, UINT32_MAX, &s->brute_max_vertices),
                         "expected >= 4");
        }
    } else if (strcmp(section, "bintree") == 0) {
        if (strcmp(key, "template_k") == 0) {
            return RANGE(parse_u32(value, 1, 6, &s->bintree_template_k), "expected 1..6");
        }
        if (strcmp(key, "tiles_max") == 0) {
            return RANGE(parse_u32(value, 2, 1048576, &s->bintree_tiles_max),
                         "expected 2..1048576");
        }
        if (strcmp(key, "tau_px") == 0) {
            return RANGE(parse_f64(value, 0.0, 1000.0, &s->bintree_tau_px), "expected 0..1000");
        }
        if (strcmp(key, "morph") == 0) {
            return RANGE(parse_flag(value, &s->bintree_morph), "expected 0 or 1");
        }
        if (strcmp(key, "subsample_levels") == 0) {
            return RANGE(parse_u32(value, 0, 4, &s->bintree_subsample_levels),
                         "expected 0..4");
        }
        if (strcmp(key, "split_fraction") == 0) {
            return RANGE(parse_f64(value, FT_BT_SPLIT_FRACTION, FT_BT_SPLIT_FRACTION_MAX,
                                   &s->bintree_split_fraction),
                         "expected 0.5..0.95");
        }
        if (strcmp(key, "vertex_table") == 0) {
            return RANGE(parse_flag(value, &s->bintree_vertex_table), "expected 0 or 1");
        }
    } else if (strcmp(section, "pgm") == 0) {
        if (strcmp(key, "grid_cols") == 0) {
            return RANGE(parse_u32(value, 2, 8192, &s->pgm_grid_cols), "expected 2..8192");
        }
        if (strcmp(key, "grid_rows") == 0) {
            return RANGE(parse_u32(value, 2, 8192, &s->pgm_grid_rows), "expected 2..8192");
        }
    } else if (strcmp(section, "pgrid") == 0) {
        if (strcmp(key, "grid_cols") == 0) {
            return RANGE(parse_u32(value, 2, 8192, &s->pgrid_grid_cols), "expected 2..8192");
        }
        if (strcmp(key, "grid_rows") == 0) {
            return RANGE(parse_u32(value, 2, 8192, &s->pgrid_grid_rows), "expected 2..8192");
        }
        if (strcmp(key, "distribution") == 0) {
            if (strcmp(value, "uniform") == 0 || strcmp(value, "view") == 0) {
                s->pgrid_view_distribution = (strcmp(value, "view") == 0);
                return 1;
            }
            return fail_key(c, section, key, value, "expected uniform or view");
        }
        if (strcmp(key, "error_bound") == 0) {
            if (strcmp(value, "relief") == 0 || strcmp(value, "residual") == 0) {
                s->pgrid_residual_bound = (strcmp(value, "residual") == 0);
                return 1;
            }
            return fail_key(c, section, key, value, "expected relief or residual");
        }
        if (strcmp(key, "ray_casting") == 0) {
            return RANGE(parse_flag(value, &s->pgrid_ray_casting), "expected 0 or 1");
        }
        if (strcmp(key, "gamma_px") == 0) {
            return RANGE(parse_f64(value, 0.1, 100.0, &s->pgrid_gamma_px), "expected 0.1..100");
        }
        if (strcmp(key, "raycast_max_px") == 0) {
            return RANGE(parse_u32(value, 0, 67108864, &s->pgrid_raycast_max_px),
                         "expected 0..67108864");
        }
    } else if (strcmp(section, "frame") == 0) {
        if (strcmp(key, "period_ms") == 0) {
            return RANGE(parse_f64(value, 1.0, 1000.0, &s->frame_period_ms), "expected 1..1000");
        }
        if (strcmp(key, "budget_ms") == 0) {
            return RANGE(parse_f64(value, 0.0, 1000.0, &s->frame_budget_ms), "expected 0..1000");
        }
        if (strcmp(key, "degrade") == 0) {
            return RANGE(parse_flag(value, &s->frame_degrade), "expected 0 or 1");
        }
        if (strcmp(key, "degrade_max_scale") == 0) {
            return RANGE(parse_f64(value, 1.0, 64.0, &s->frame_degrade_max_scale),
                         "expected 1..64");
        }
    } else if (strcmp(section, "pose_input") == 0) {
        if (strcmp(key, "horizon_ms") == 0) {
            return RANGE(parse_u32(value, 0, FT_POSE_HORIZON_MAX_MS, &s->pose_horizon_ms),
                         "expected 0..1000");
        }
        if (strcmp(key, "velocity_required") == 0) {
            return RANGE(parse_flag(value, &s->pose_velocity_required), "expected 0 or 1");
        }
        if (strcmp(key, "converge_ms") == 0) {
            return RANGE(parse_u32(value, 0, FT_POSE_CONVERGE_MAX_MS, &s->pose_converge_ms),
                         "expected 0..10000");
        }
        if (strcmp(key, "snap_m") == 0) {
            return RANGE(parse_f64(value, FT_POSE_SNAP_MIN_M, FT_POSE_SNAP_MAX_M, &s->pose_snap_m),
                         "expected 1..100000");
        }
    } else if (strcmp(section, "can") == 0) {
        char *dst = NULL;
        if (strcmp(key, "interface") == 0) dst = s->can_iface;
        if (strcmp(key, "backup_interface") == 0) dst = s->can_backup_iface;
        if (dst != NULL) {
            if (strlen(value) >= FT_CAN_IFACE_NAME_MAX) {
                return fail_key(c, section, key, value, "interface name longer than 15");
            }
            (void)snprintf(dst, FT_CAN_IFACE_NAME_MAX, "%s", value);
            return 1;
        }
        if (strcmp(key, "failover_ms") == 0) {
            return RANGE(parse_u32(value, 1, 10000, &s->can_failover_ms), "expected 1..10000");
        }
    } else if (strcmp(section, "gpio") == 0) {
        if (strcmp(key, "chip") == 0) {
            if (strlen(value) >= FT_GPIO_CHIP_NAME_MAX) {
                return fail_key(c, section, key, value, "longer than 63 characters");
            }
            (void)snprintf(s->gpio_chip, sizeof s->gpio_chip, "%s", value);
            return 1;
        }
        int *line = NULL;
        char want[32];
        for (int i = 0; i < FT_GPIO_INPUT_COUNT; ++i) {
            (void)snprintf(want, sizeof want, "%s_line", k_gpio_input_name[i]);
            if (strcmp(key, want) == 0) line = &s->gpio_input_line[i];
        }
        if (strcmp(key, "heartbeat_line") == 0) line = &s->gpio_heartbeat_line;
        if (line != NULL) {
            double d;
            if (!parse_f64(value, -1.0, (double)FT_GPIO_LINE_MAX, &d) || d != floor(d)) {
                return fail_key(c, section, key, value, "expected -1 (none) or a line 0..511");
            }
            *line = (int)d;
            return 1;
        }
        if (strcmp(key, "active_low") == 0) {
            return RANGE(parse_flag(value, &s->gpio_active_low), "expected 0 or 1");
        }
        if (strcmp(key, "debounce_ms") == 0) {
            return RANGE(parse_u32(value, 0, 1000, &s->gpio_debounce_ms), "expected 0..1000");
        }
    } else if (strcmp(section, "build") == 0) {
        if (strcmp(key, "inputs") == 0) {
            /* comma list; bounded by the value's length (< the INI line limit) */
            unsigned bits = 0;
            const char *p = value;
            for (int guard = 0; guard < 16 && *p != '\0'; ++guard) {
                size_t n = strcspn(p, ",");
                if (n == 6 && strncmp(p, "replay", 6) == 0) bits |= FT_BUILD_INPUT_REPLAY;
                else if (n == 3 && strncmp(p, "can", 3) == 0) bits |= FT_BUILD_INPUT_CAN;
                else if (n == 4 && strncmp(p, "gpio", 4) == 0) bits |= FT_BUILD_INPUT_GPIO;
                else return fail_key(c, section, key, value, "expected a comma list of replay, can, gpio");
                p += n;
                if (*p == ',') ++p;
            }
            if (bits == 0u) {
                return fail_key(c, section, key, value, "expected a comma list of replay, can, gpio");
            }
            s->build_inputs = bits;
            return 1;
        }
        if (strcmp(key, "png") == 0) {
            return RANGE(parse_flag(value, &s->build_png), "expected 0 or 1");
        }
    } else if (strcmp(section, "can_map") == 0) {
        if (strcmp(key, "defaults") == 0) {
            uint32_t v;
            if (!parse_u32(value, 0, 1, &v)) {
                return fail_key(c, section, key, value, "expected 0 or 1");
            }
            if (v) {
                /* only the CAN map: [gpio], [build] and the rest keep what
                 * the file said before this line */
                ft_canaero_default_map(&s->can_map);
                can_map_to_pose_ranges(&s->can_map);
            } else {
                memset(&s->can_map, 0, sizeof s->can_map);
            }
            return 1;
        }
        for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
            if (strcmp(key, k_can_qty_key[q]) != 0) {
                continue;
            }
            ft_can_map_entry e;
            memset(&e, 0, sizeof e);
            e.qty = (ft_pose_qty)q;
            if (!parse_can_entry(value, &e)) {
                return fail_key(c, section, key, value,
                                "expected ID,SCALE,MIN,MAX,TIMEOUT_MS[,PRIORITY] "
                                "(id 0..2047, timeout 1..60000 ms, priority 0..255)");
            }
            const int f = can_qty_pose_field(e.qty);
            if (f >= 0 && (e.min_value < k_pose_range[f].min || e.max_value > k_pose_range[f].max)) {
                char why[128];
                (void)snprintf(why, sizeof why, "MIN,MAX must lie within pose.%s [%g, %g] %s",
                               k_pose_range[f].key, k_pose_range[f].min, k_pose_range[f].max,
                               k_pose_range[f].unit);
                return fail_key(c, section, key, value, why);
            }
            ft_error e2;
            if (can_map_upsert(&s->can_map, &e, &e2) != FT_OK) {
                return fail_key(c, section, key, value, e2.text);
            }
            return 1;
        }
    } else if (strcmp(section, "presentation") == 0) {
        if (strcmp(key, "colouring") == 0) {
            if (strcmp(value, "absolute") == 0 || strcmp(value, "relative") == 0) {
                s->present_relative = (value[0] == 'r');
                return 1;
            }
            return fail_key(c, section, key, value, "expected absolute or relative");
        }
        if (strcmp(key, "palette") == 0) {
            if (strcmp(value, "day") == 0 || strcmp(value, "night") == 0) {
                s->present_palette = value[0] == 'n' ? FT_PALETTE_NIGHT : FT_PALETTE_DAY;
                return 1;
            }
            return fail_key(c, section, key, value, "expected day or night");
        }
        if (strcmp(key, "horizon") == 0) {
            return RANGE(parse_flag(value, &s->present_horizon), "expected 0 or 1");
        }
        if (strcmp(key, "haze_km") == 0) {
            return RANGE(parse_off_or_f64(value, FT_HAZE_KM_MIN, FT_HAZE_KM_MAX,
                                          &s->present_haze_km),
                         "expected 0 (no haze) or a visibility of 1 to 1000 km");
        }
        if (strcmp(key, "grid_m") == 0) {
            return RANGE(parse_off_or_f64(value, FT_GRID_M_MIN, FT_GRID_M_MAX,
                                          &s->present_grid_m),
                         "expected 0 (no grid) or a spacing of 10 to 10000 m");
        }
        if (strcmp(key, "band_edges_ft") == 0) {
            return RANGE(parse_band_edges(value, &s->present_bands),
                         "expected 1 to 5 comma-separated heights in ft relative to the "
                         "aircraft, strictly increasing, within +-60000");
        }
        if (strcmp(key, "band_rgba") == 0) {
            return RANGE(parse_band_rgba(value, &s->present_bands),
                         "expected 2 to 6 comma-separated colours RRGGBBAA (hex)");
        }
    } else if (strcmp(section, "metric") == 0) {
        if (strcmp(key, "enabled") == 0) {
            return RANGE(parse_flag(value, &s->metric_enabled), "expected 0 or 1");
        }
    } else if (strcmp(section, "budget") == 0) {
        ft_pool_id id;
        if (ft_pool_from_key(key, &id)) {
            return RANGE(parse_u64(value, 0, 1ull << 40, &s->budget_bytes[id]),
                         "expected a byte count (suffix K/M/G allowed)");
        }
    }
    return fail_key(c, section, key, value, "unknown section or key");
}

ft_status ft_scene_parse(ft_scene *s, const char *text, const char *source_name, ft_error *err)
{
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.scene = s;
    c.err = err;
    c.status = FT_OK;
    c.source = source_name;
    int rc = ini_parse_string(text, on_key, &c);
    if (c.status != FT_OK) {
        return ft_fail(err, c.status, "%s:%d: %s", source_name, rc, c.first_error);
    }
    if (rc < 0) {
        return ft_fail(err, FT_ERR_CONFIG, "%s: scene parser failed (%d)", source_name, rc);
    }
    if (rc > 0) {
        return ft_fail(err, FT_ERR_CONFIG, "%s:%d: malformed line (expected [section] or key = value)",
                       source_name, rc);
    }
    return ft_scene_validate(s, err);
}

ft_status ft_scene_validate(const ft_scene *s, ft_error *err)
{
    if (s->width_px < 16 || s->height_px < 16 || s->width_px > 8192 || s->height_px > 8192) {
        return ft_fail(err, FT_ERR_CONFIG, "view %ux%u outside 16..8192", s->width_px,
                       s->height_px);
    }
    if (!(s->fovy_deg >= 1.0 && s->fovy_deg <= 170.0)) {
        return ft_fail(err, FT_ERR_CONFIG, "view.fovy_deg %g outside 1..170", s->fovy_deg);
    }
    ft_error pose_err;
    if (ft_pose_check(&s->pose, "scene", &pose_err) != FT_OK) {
        return ft_fail(err, FT_ERR_CONFIG, "%s", pose_err.text);
    }
    if (s->brute_patch_cells < 1 || s->brute_patch_cells > 180) {
        return ft_fail(err, FT_ERR_CONFIG, "brute.patch_cells %u outside 1..180",
                       s->brute_patch_cells);
    }
    if (!(s->frame_period_ms >= 1.0 && s->frame_period_ms <= 1000.0) ||
        s->pose_horizon_ms > FT_POSE_HORIZON_MAX_MS) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "frame.period_ms %g (1..1000) or pose_input.horizon_ms %u (0..1000) "
                       "out of range",
                       s->frame_period_ms, s->pose_horizon_ms);
    }
    if (s->pose_converge_ms > FT_POSE_CONVERGE_MAX_MS ||
        !(s->pose_snap_m >= FT_POSE_SNAP_MIN_M && s->pose_snap_m <= FT_POSE_SNAP_MAX_M)) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "pose_input.converge_ms %u (0..10000) or pose_input.snap_m %g "
                       "(1..100000) out of range",
                       s->pose_converge_ms, s->pose_snap_m);
    }
    if (s->present_bands.colours != s->present_bands.edges + 1u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "presentation: %u band colours (band_rgba) for %u band edges "
                       "(band_edges_ft): a colour for each band, edges + 1",
                       s->present_bands.colours, s->present_bands.edges);
    }
    /* GPIO lines: each used at most once */
    int used[FT_GPIO_INPUT_COUNT + 1];
    for (int i = 0; i < FT_GPIO_INPUT_COUNT; ++i) used[i] = s->gpio_input_line[i];
    used[FT_GPIO_INPUT_COUNT] = s->gpio_heartbeat_line;
    for (int i = 0; i <= FT_GPIO_INPUT_COUNT; ++i) {
        for (int j = i + 1; j <= FT_GPIO_INPUT_COUNT; ++j) {
            if (used[i] >= 0 && used[i] == used[j]) {
                return ft_fail(err, FT_ERR_CONFIG, "gpio: line %d is used twice", used[i]);
            }
        }
    }
    if (s->bintree_template_k < 1 || s->bintree_template_k > 6 || s->bintree_tiles_max < 2 ||
        s->bintree_tiles_max > 1048576 || !(s->bintree_tau_px >= 0.0 && s->bintree_tau_px <= 1000.0) ||
        s->bintree_subsample_levels > 4u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "bintree: template_k %u (1..6), tiles_max %u (2..1048576), tau_px %g "
                       "(0..1000) or subsample_levels %u (0..4) out of range",
                       s->bintree_template_k, s->bintree_tiles_max, s->bintree_tau_px,
                       s->bintree_subsample_levels);
    }
    if (s->pgrid_grid_cols < 2 || s->pgrid_grid_cols > 8192 || s->pgrid_grid_rows < 2 ||
        s->pgrid_grid_rows > 8192 || !(s->pgrid_gamma_px >= 0.1 && s->pgrid_gamma_px <= 100.0)) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "pgrid: grid %u x %u outside 2..8192 per side or gamma_px %g outside "
                       "0.1..100",
                       s->pgrid_grid_cols, s->pgrid_grid_rows, s->pgrid_gamma_px);
    }
    if (s->pgm_grid_cols < 2 || s->pgm_grid_cols > 8192 || s->pgm_grid_rows < 2 ||
        s->pgm_grid_rows > 8192) {
        return ft_fail(err, FT_ERR_CONFIG, "pgm: grid %u x %u outside 2..8192 per side",
                       s->pgm_grid_cols, s->pgm_grid_rows);
    }
    return FT_OK;
}

ft_status ft_pose_parse(const char *text, ft_pose *out, ft_error *err)
{
    double v[FT_POSE_FIELD_COUNT];
    const char *p = text;
    for (int i = 0; i < FT_POSE_FIELD_COUNT; ++i) {
        const ft_pose_range *r = &k_pose_range[i];
        char *end = NULL;
        v[i] = strtod(p, &end); /* 1e999 overflows to inf: caught by the range below */
        if (end == p) {
            return ft_fail(err, FT_ERR_ARG,
                           "--pose '%.80s': field %d (%s) is not a number "
                           "(want LAT,LON,ALT_M,HEADING_DEG,PITCH_DEG,ROLL_DEG)",
                           text, i + 1, r->key);
        }
        if (i < FT_POSE_FIELD_COUNT - 1 && *end != ',') {
            return ft_fail(err, FT_ERR_ARG, "--pose '%.80s': expected 6 comma-separated numbers",
                           text);
        }
        if (i == FT_POSE_FIELD_COUNT - 1 && *end != '\0') {
            return ft_fail(err, FT_ERR_ARG, "--pose '%.80s': trailing characters", text);
        }
        if (!ft_pose_field_ok((ft_pose_field)i, v[i])) {
            return ft_fail(err, FT_ERR_ARG,
                           "--pose '%.80s': field %d, %s = %g, %s (want a finite value in "
                           "[%g, %g] %s, as pose.%s in a scene)",
                           text, i + 1, r->key, v[i],
                           isfinite(v[i]) ? "is out of range" : "is not finite", r->min, r->max,
                           r->unit, r->key);
        }
        p = end + 1;
    }
    for (int i = 0; i < FT_POSE_FIELD_COUNT; ++i) {
        *ft_pose_field_ptr(out, (ft_pose_field)i) = v[i];
    }
    return FT_OK;
}
