#include "core/scene.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/invariant.h"

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
#define FT_POSE_FIELD_RANGE(id, field, lo, hi, unit, def) [id] = {#field, lo, hi, unit},
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
#define FT_POSE_FIELD_CASE(id, field, lo, hi, unit, def) \
    case id: return &p->field;
        FT_POSE_FIELD_LIST(FT_POSE_FIELD_CASE)
#undef FT_POSE_FIELD_CASE
    default: return NULL;
    }
}

double ft_pose_get(const ft_pose *p, ft_pose_field f)
{
    switch (f) {
#define FT_POSE_FIELD_GET(id, field, lo, hi, unit, def) \
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

/* ---- list keys: values with their own syntax (FT_SCENE_LIST_KEYS) ---- */

static int parse_display(ft_scene *s, const char *key, const char *value, char *why, size_t cap)
{
    (void)key;
    if (!ft_display_parse(value, &s->display, s->display_device, sizeof s->display_device)) {
        (void)snprintf(why, cap, "unknown display (none, x11, kms, kms:/dev/dri/cardN)");
        return 0;
    }
    return 1;
}

/* terrain.db_centre_lat_deg / _lon_deg: empty (NaN) = the middle of the
 * database level's data, placed when the database is opened. */
static int parse_db_centre(ft_scene *s, const char *key, const char *value, char *why,
                           size_t cap)
{
    const int lat = strcmp(key, "db_centre_lat_deg") == 0;
    const double lim = lat ? 90.0 : 180.0;
    double d = NAN;
    if (value[0] != '\0' && !parse_f64(value, -lim, lim, &d)) {
        (void)snprintf(why, cap, "expected -%g..%g deg, or empty (the middle of the data)", lim,
                       lim);
        return 0;
    }
    if (lat) {
        s->db_centre_lat_deg = d;
    } else {
        s->db_centre_lon_deg = d;
    }
    return 1;
}

static int parse_display_mode(ft_scene *s, const char *key, const char *value, char *why,
                              size_t cap)
{
    (void)key;
    ft_display_mode m;
    if (strlen(value) >= sizeof s->display_mode) {
        (void)snprintf(why, cap, "longer than %zu characters", sizeof s->display_mode - 1u);
        return 0;
    }
    if (value[0] != '\0' && !ft_display_mode_parse(value, &m)) {
        (void)snprintf(why, cap, "expected WxH, WxH@HZ or preferred");
        return 0;
    }
    (void)snprintf(s->display_mode, sizeof s->display_mode, "%s", value);
    return 1;
}

static int parse_band_edges_key(ft_scene *s, const char *key, const char *value, char *why,
                                size_t cap)
{
    (void)key;
    if (!parse_band_edges(value, &s->present_bands)) {
        (void)snprintf(why, cap, "expected 1 to 5 comma-separated heights in ft relative to the "
                                 "aircraft, strictly increasing, within +-60000");
        return 0;
    }
    return 1;
}

static int parse_band_rgba_key(ft_scene *s, const char *key, const char *value, char *why,
                               size_t cap)
{
    (void)key;
    if (!parse_band_rgba(value, &s->present_bands)) {
        (void)snprintf(why, cap, "expected 2 to 6 comma-separated colours RRGGBBAA (hex)");
        return 0;
    }
    return 1;
}

/* Only the CAN map: the keys a file set before this line keep their values. */
static int parse_can_map_defaults(ft_scene *s, const char *key, const char *value, char *why,
                                  size_t cap)
{
    (void)key;
    uint64_t v;
    if (!parse_u64(value, 0u, 1u, &v)) {
        (void)snprintf(why, cap, "expected 0 or 1");
        return 0;
    }
    if (v != 0u) {
        ft_canaero_default_map(&s->can_map);
        can_map_to_pose_ranges(&s->can_map);
    } else {
        memset(&s->can_map, 0, sizeof s->can_map);
    }
    return 1;
}

static int parse_can_map_entry(ft_scene *s, const char *key, const char *value, char *why,
                               size_t cap)
{
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        if (strcmp(key, k_can_qty_key[q]) != 0) {
            continue;
        }
        ft_can_map_entry e;
        memset(&e, 0, sizeof e);
        e.qty = (ft_pose_qty)q;
        if (!parse_can_entry(value, &e)) {
            (void)snprintf(why, cap, "expected ID,SCALE,MIN,MAX,TIMEOUT_MS[,PRIORITY] "
                                     "(id 0..2047, timeout 1..60000 ms, priority 0..255)");
            return 0;
        }
        const int f = can_qty_pose_field(e.qty);
        if (f >= 0 && (e.min_value < k_pose_range[f].min || e.max_value > k_pose_range[f].max)) {
            (void)snprintf(why, cap, "MIN,MAX must lie within pose.%s [%g, %g] %s",
                           k_pose_range[f].key, k_pose_range[f].min, k_pose_range[f].max,
                           k_pose_range[f].unit);
            return 0;
        }
        ft_error e2;
        if (can_map_upsert(&s->can_map, &e, &e2) != FT_OK) {
            (void)snprintf(why, cap, "%s", e2.text);
            return 0;
        }
        return 1;
    }
    (void)snprintf(why, cap, "unknown section or key");
    return 0;
}

/* ---- the schema ---- */

typedef int (*list_parse_fn)(ft_scene *s, const char *key, const char *value, char *why,
                             size_t cap);

/* The field size each kind writes (0: any size, TEXT). */
#define FT_KEY_SIZE_U32 sizeof(uint32_t)
#define FT_KEY_SIZE_U64 sizeof(uint64_t)
#define FT_KEY_SIZE_F64 sizeof(double)
#define FT_KEY_SIZE_FLAG sizeof(int)
#define FT_KEY_SIZE_OFF_F64 sizeof(double)
#define FT_KEY_SIZE_ENUM sizeof(int)
#define FT_KEY_SIZE_BITS sizeof(unsigned)
#define FT_KEY_SIZE_LINE sizeof(int)
#define FT_KEY_SIZE_TEXT 0u

#define FT_FIELD_SIZE(field) sizeof(((ft_scene *)0)->field)
#define FT_KEY_CHECK(section, key, kind, field, lo, hi, choices, def, unit, doc)               \
    _Static_assert(FT_KEY_SIZE_##kind == 0u || FT_KEY_SIZE_##kind == FT_FIELD_SIZE(field),   \
                   #section "." #key ": the field's size is not what its kind writes");
FT_SCENE_KEYS(FT_KEY_CHECK)
#undef FT_KEY_CHECK
/* ENUM rows write an int into enum-typed fields: same size, and the
 * enumerators are the small non-negative positions in `choices`. */
_Static_assert(sizeof(ft_method_kind) == sizeof(int) && sizeof(ft_backend) == sizeof(int) &&
                   sizeof(ft_curvature) == sizeof(int) && sizeof(ft_height_format) == sizeof(int) &&
                   sizeof(ft_palette) == sizeof(int),
               "ENUM keys write an int");
_Static_assert(FT_GPIO_INPUT_COUNT == 4, "one gpio.<name>_line row per discrete input");

#define FT_KEY_ROW(section, key, kind, field, lo, hi, choices, def, unit, doc)                  \
    {#section, #key, FT_KEY_##kind, offsetof(ft_scene, field), FT_FIELD_SIZE(field),          \
     (double)(lo), (double)(hi), choices, def, unit, doc},
#define FT_POSE_ROW(id, field, lo, hi, unit, def)                                             \
    {"pose", #field, FT_KEY_F64, offsetof(ft_scene, pose.field), sizeof(double), lo, hi,      \
     NULL, def, unit, "the pose drawn until an input gives one (same range as --pose)"},
#define FT_LIST_ROW(section, key, parser, def, doc)                                           \
    {#section, #key, FT_KEY_LIST, 0u, 0u, 0.0, 0.0, NULL, def, "", doc},
#define FT_LIST_FN(section, key, parser, def, doc) parser,

static const ft_scene_key k_keys[] = {
    FT_SCENE_KEYS(FT_KEY_ROW) FT_POSE_FIELD_LIST(FT_POSE_ROW) FT_SCENE_LIST_KEYS(FT_LIST_ROW)};
static const list_parse_fn k_list_parse[] = {FT_SCENE_LIST_KEYS(FT_LIST_FN)};
#define FT_KEY_COUNT (sizeof k_keys / sizeof k_keys[0])
#define FT_LIST_COUNT (sizeof k_list_parse / sizeof k_list_parse[0])
#define FT_LIST_FIRST (FT_KEY_COUNT - FT_LIST_COUNT) /* list rows come last */

const ft_scene_key *ft_scene_keys(size_t *count)
{
    *count = FT_KEY_COUNT;
    return k_keys;
}

/* The row for section.key: its own row, else the section's `*` row. */
static const ft_scene_key *find_key(const char *section, const char *key)
{
    const ft_scene_key *any = NULL;
    for (size_t i = 0; i < FT_KEY_COUNT; ++i) {
        const ft_scene_key *k = &k_keys[i];
        if (strcmp(k->section, section) != 0) {
            continue;
        }
        if (strcmp(k->key, key) == 0) {
            return k;
        }
        if (strcmp(k->key, "*") == 0) {
            any = k;
        }
    }
    return any;
}

/* Name i of "a|b|c|" into out; 0 past the last. */
static int choice_at(const char *choices, uint32_t i, char *out, size_t cap)
{
    const char *p = choices;
    for (uint32_t n = 0u; n < 32u; ++n) {
        const char *bar = strchr(p, '|');
        if (bar == NULL) {
            return 0;
        }
        if (n == i) {
            (void)snprintf(out, cap, "%.*s", (int)(bar - p), p);
            return 1;
        }
        p = bar + 1;
    }
    return 0;
}

/* Position of the name (length n) in choices, or -1. */
static int choice_index(const char *choices, const char *name, size_t n)
{
    char c[64];
    for (uint32_t i = 0u; choice_at(choices, i, c, sizeof c); ++i) {
        if (strlen(c) == n && strncmp(c, name, n) == 0) {
            return (int)i;
        }
    }
    return -1;
}

static uint32_t choice_count(const char *choices)
{
    char c[64];
    uint32_t n = 0u;
    while (n < 32u && choice_at(choices, n, c, sizeof c)) ++n;
    return n;
}

/* A limit as people write it, exactly: 8192, 0.1, 1e+06, 1048576. */
static void put_number(char *out, size_t cap, double v)
{
    (void)snprintf(out, cap, "%g", v);
    if (strtod(out, NULL) != v) {
        (void)snprintf(out, cap, v == floor(v) && fabs(v) < 1e15 ? "%.0f" : "%.17g", v);
    }
}

const char *ft_scene_key_accepts(const ft_scene_key *k, char *text, size_t cap)
{
    char lo[32], hi[32], names[256] = "";
    put_number(lo, sizeof lo, k->min);
    put_number(hi, sizeof hi, k->max);
    const char *sp = k->unit[0] != '\0' ? " " : "";
    if (k->choices != NULL) {
        const uint32_t n = choice_count(k->choices);
        size_t used = 0u;
        for (uint32_t i = 0u; i < n && used < sizeof names; ++i) {
            char c[64];
            (void)choice_at(k->choices, i, c, sizeof c);
            const char *sep = i == 0u ? "" : (i + 1u == n && k->kind == FT_KEY_ENUM) ? " or " : ", ";
            int w = snprintf(names + used, sizeof names - used, "%s%s", sep, c);
            used += w > 0 ? (size_t)w : 0u;
        }
    }
    switch (k->kind) {
    case FT_KEY_U32:
    case FT_KEY_F64: (void)snprintf(text, cap, "%s..%s%s%s", lo, hi, sp, k->unit); break;
    case FT_KEY_U64:
        (void)snprintf(text, cap, "a byte count %s..%s (suffix K, M or G allowed)", lo, hi);
        break;
    case FT_KEY_FLAG: (void)snprintf(text, cap, "0 or 1"); break;
    case FT_KEY_OFF_F64:
        (void)snprintf(text, cap, "0 (off) or %s..%s%s%s", lo, hi, sp, k->unit);
        break;
    case FT_KEY_ENUM: (void)snprintf(text, cap, "%s", names); break;
    case FT_KEY_BITS: (void)snprintf(text, cap, "a comma list of %s", names); break;
    case FT_KEY_LINE: (void)snprintf(text, cap, "-1 (none) or a line 0..%s", hi); break;
    case FT_KEY_TEXT: (void)snprintf(text, cap, "at most %zu characters", k->size - 1u); break;
    case FT_KEY_LIST: (void)snprintf(text, cap, "%s", k->doc); break;
    }
    return text;
}

static int key_why(const ft_scene_key *k, const char *prefix, char *why, size_t cap)
{
    char accepts[256];
    (void)snprintf(why, cap, "%s%s", prefix, ft_scene_key_accepts(k, accepts, sizeof accepts));
    return 0;
}

/* Parses value for row k into s (key: the key as written, for `*` rows).
 * Returns 1, or 0 with the reason in why. */
static int set_key(ft_scene *s, const ft_scene_key *k, const char *key, const char *value,
                   char *why, size_t cap)
{
    unsigned char *field = (unsigned char *)s + k->offset;
    uint64_t u;
    double d;
    int i;
    switch (k->kind) {
    case FT_KEY_U32:
    case FT_KEY_U64:
        if (!parse_u64(value, (uint64_t)k->min, (uint64_t)k->max, &u)) {
            return key_why(k, "expected ", why, cap);
        }
        if (k->kind == FT_KEY_U32) {
            const uint32_t u32 = (uint32_t)u;
            memcpy(field, &u32, sizeof u32);
        } else {
            memcpy(field, &u, sizeof u);
        }
        return 1;
    case FT_KEY_F64:
    case FT_KEY_OFF_F64:
        if (!parse_f64(value, k->kind == FT_KEY_OFF_F64 ? 0.0 : k->min, k->max, &d) ||
            (k->kind == FT_KEY_OFF_F64 && d > 0.0 && d < k->min)) {
            return key_why(k, "expected ", why, cap);
        }
        memcpy(field, &d, sizeof d);
        return 1;
    case FT_KEY_FLAG:
        if (!parse_u64(value, 0u, 1u, &u)) {
            return key_why(k, "expected ", why, cap);
        }
        i = (int)u;
        memcpy(field, &i, sizeof i);
        return 1;
    case FT_KEY_LINE:
        if (!parse_f64(value, -1.0, k->max, &d) || d != floor(d)) {
            return key_why(k, "expected ", why, cap);
        }
        i = (int)d;
        memcpy(field, &i, sizeof i);
        return 1;
    case FT_KEY_ENUM:
        i = choice_index(k->choices, value, strlen(value));
        if (i < 0) {
            char prefix[64];
            (void)snprintf(prefix, sizeof prefix, "unknown %s: expected ", k->key);
            return key_why(k, prefix, why, cap);
        }
        memcpy(field, &i, sizeof i);
        return 1;
    case FT_KEY_BITS: {
        /* bounded by the value's length (< the INI line limit) */
        unsigned bits = 0u;
        const char *p = value;
        for (int guard = 0; guard < 16 && *p != '\0'; ++guard) {
            const size_t n = strcspn(p, ",");
            const int b = choice_index(k->choices, p, n);
            if (b < 0) {
                return key_why(k, "expected ", why, cap);
            }
            bits |= 1u << (unsigned)b;
            p += n;
            if (*p == ',') ++p;
        }
        if (bits == 0u || *p != '\0') {
            return key_why(k, "expected ", why, cap);
        }
        memcpy(field, &bits, sizeof bits);
        return 1;
    }
    case FT_KEY_TEXT:
        if (strlen(value) >= k->size) {
            (void)snprintf(why, cap, "longer than %zu characters", k->size - 1u);
            return 0;
        }
        (void)snprintf((char *)field, k->size, "%s", value);
        return 1;
    case FT_KEY_LIST:
        return k_list_parse[(size_t)(k - k_keys) - FT_LIST_FIRST](s, key, value, why, cap);
    }
    return 0;
}

/* 1 when the field of row k holds a value the row accepts; its text in text. */
static int key_value_ok(const ft_scene *s, const ft_scene_key *k, char *text, size_t cap)
{
    const unsigned char *field = (const unsigned char *)s + k->offset;
    uint32_t u32;
    uint64_t u64;
    double d;
    int i;
    unsigned bits;
    switch (k->kind) {
    case FT_KEY_U32:
        memcpy(&u32, field, sizeof u32);
        (void)snprintf(text, cap, "%u", u32);
        return (double)u32 >= k->min && (double)u32 <= k->max;
    case FT_KEY_U64:
        memcpy(&u64, field, sizeof u64);
        (void)snprintf(text, cap, "%llu", (unsigned long long)u64);
        return (double)u64 >= k->min && (double)u64 <= k->max;
    case FT_KEY_F64:
    case FT_KEY_OFF_F64:
        memcpy(&d, field, sizeof d);
        (void)snprintf(text, cap, "%g", d);
        return isfinite(d) && ((d >= k->min && d <= k->max) || (k->kind == FT_KEY_OFF_F64 && d == 0.0));
    case FT_KEY_FLAG:
    case FT_KEY_LINE:
    case FT_KEY_ENUM:
        memcpy(&i, field, sizeof i);
        (void)snprintf(text, cap, "%d", i);
        if (k->kind == FT_KEY_FLAG) return i == 0 || i == 1;
        if (k->kind == FT_KEY_LINE) return i >= -1 && (double)i <= k->max;
        return i >= 0 && (uint32_t)i < choice_count(k->choices);
    case FT_KEY_BITS:
        memcpy(&bits, field, sizeof bits);
        (void)snprintf(text, cap, "0x%x", bits);
        return bits != 0u && bits < (1u << choice_count(k->choices));
    case FT_KEY_TEXT:
        (void)snprintf(text, cap, "(text)");
        return memchr(field, '\0', k->size) != NULL;
    case FT_KEY_LIST:
        return 1; /* checked where parsed, and across fields in ft_scene_validate */
    }
    return 0;
}

void ft_scene_defaults(ft_scene *s)
{
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < FT_KEY_COUNT; ++i) {
        const ft_scene_key *k = &k_keys[i];
        char why[256];
        if (k->def != NULL) {
            FT_INVARIANT(set_key(s, k, k->key, k->def, why, sizeof why), "a scene default parses");
        }
    }
}

ft_status ft_scene_schema_check(ft_scene *scratch, ft_error *err)
{
    memset(scratch, 0, sizeof *scratch);
    for (size_t i = 0; i < FT_KEY_COUNT; ++i) {
        const ft_scene_key *k = &k_keys[i];
        char why[256], text[64];
        for (size_t j = 0; j < i; ++j) {
            if (strcmp(k_keys[j].section, k->section) == 0 && strcmp(k_keys[j].key, k->key) == 0) {
                return ft_fail(err, FT_ERR_CONFIG, "scene schema: %s.%s has two rows",
                               k->section, k->key);
            }
        }
        if (k->def != NULL && (!set_key(scratch, k, k->key, k->def, why, sizeof why) ||
                               !key_value_ok(scratch, k, text, sizeof text))) {
            return ft_fail(err, FT_ERR_CONFIG, "scene schema: %s.%s default '%s' is refused: %s",
                           k->section, k->key, k->def, why);
        }
        if (k->def == NULL && strcmp(k->key, "*") != 0) {
            return ft_fail(err, FT_ERR_CONFIG, "scene schema: %s.%s has no default", k->section,
                           k->key);
        }
    }
    return FT_OK;
}

typedef struct parse_ctx {
    ft_scene *scene;
    ft_status status;
    char first_error[512];
} parse_ctx;

/* Records the first failure only; libinih goes on parsing and reports the
 * line number of the first failing line, which ft_scene_parse prepends. */
static int on_key(void *user, const char *section, const char *key, const char *value)
{
    parse_ctx *c = (parse_ctx *)user;
    if (strcmp(section, "pose") == 0) {
        c->scene->pose_given = 1;
    }
    const ft_scene_key *k = find_key(section, key);
    char why[256];
    if (k == NULL) {
        (void)snprintf(why, sizeof why, "unknown section or key");
    } else if (set_key(c->scene, k, key, value, why, sizeof why)) {
        return 1;
    }
    if (c->status == FT_OK) {
        c->status = FT_ERR_CONFIG;
        (void)snprintf(c->first_error, sizeof c->first_error, "%.60s.%.60s = '%.60s': %s", section,
                       key, value, why);
    }
    return 0;
}


ft_status ft_scene_parse(ft_scene *s, const char *text, const char *source_name, ft_error *err)
{
    parse_ctx c;
    memset(&c, 0, sizeof c);
    c.scene = s;
    c.status = FT_OK;
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
    /* every key's range, for what a command line or a tool set after parsing */
    for (size_t i = 0; i < FT_KEY_COUNT; ++i) {
        const ft_scene_key *k = &k_keys[i];
        char value[64], accepts[256];
        if (!key_value_ok(s, k, value, sizeof value)) {
            return ft_fail(err, FT_ERR_CONFIG, "%s.%s = %s: expected %s", k->section, k->key,
                           value, ft_scene_key_accepts(k, accepts, sizeof accepts));
        }
    }
    /* across keys */
    if (s->present_bands.edges < 1u || s->present_bands.edges >= FT_BANDS_MAX ||
        s->present_bands.colours != s->present_bands.edges + 1u) {
        return ft_fail(err, FT_ERR_CONFIG,
                       "presentation: %u band colours (band_rgba) for %u band edges "
                       "(band_edges_ft): a colour for each band, edges + 1",
                       s->present_bands.colours, s->present_bands.edges);
    }
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
