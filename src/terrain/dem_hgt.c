/* dem_hgt.c - raw SRTM .hgt reader (format in dem_hgt.h). */
#include "terrain/dem_hgt.h"

#include <stdint.h>
#include <string.h>

#include "terrain/void_fill.h"

/* Integer square root of n (n <= 2^40 here); bounded binary search. */
static uint64_t isqrt_u64(uint64_t n)
{
    uint64_t lo = 0u, hi = (n < 0xFFFFFFFFu) ? n + 1u : 0x100000000u; /* answer in [lo, hi) */
    for (int guard = 0; guard < 64 && hi - lo > 1u; ++guard) {
        uint64_t mid = lo + (hi - lo) / 2u;
        if (mid * mid <= n) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

/* Side of a square N*N*2-byte file, or 0 with a message. */
static ft_status side_from_size(uint64_t size_bytes, const char *name, uint32_t *side,
                                ft_error *err)
{
    const uint64_t max_bytes = 2u * (uint64_t)FT_GRID_SIDE_MAX * FT_GRID_SIDE_MAX;
    const uint64_t min_bytes = 2u * (uint64_t)FT_GRID_SIDE_MIN * FT_GRID_SIDE_MIN;
    if (size_bytes < min_bytes) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt file is %llu bytes, smaller than the %llu bytes of a %ux%u grid",
                       name, (unsigned long long)size_bytes, (unsigned long long)min_bytes,
                       FT_GRID_SIDE_MIN, FT_GRID_SIDE_MIN);
    }
    if (size_bytes > max_bytes) {
        return ft_fail(err, FT_ERR_OVERSIZED,
                       "%s: .hgt file is %llu bytes, larger than the %llu bytes of a %ux%u grid",
                       name, (unsigned long long)size_bytes, (unsigned long long)max_bytes,
                       FT_GRID_SIDE_MAX, FT_GRID_SIDE_MAX);
    }
    if ((size_bytes % 2u) != 0u) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt file length %llu bytes is odd (samples are 2-byte int16)", name,
                       (unsigned long long)size_bytes);
    }
    uint64_t samples = size_bytes / 2u;
    uint64_t n = isqrt_u64(samples);
    if (n * n != samples) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt file holds %llu samples, not a square N*N grid (1201^2 or 3601^2)",
                       name, (unsigned long long)samples);
    }
    *side = (uint32_t)n;
    return FT_OK;
}

static int lower(int c)
{
    return (c >= 'A' && c <= 'Z') ? c - 'A' + 'a' : c;
}

static int is_digit(int c)
{
    return c >= '0' && c <= '9';
}

/* Parses "N46W122.hgt" (any directory prefix, any case) into the SW corner. */
static ft_status parse_name(const char *path, double *lat_deg, double *lon_deg, ft_error *err)
{
    const char *base = path;
    size_t len = strlen(path);
    for (size_t i = 0u; i < len; ++i) {
        if (path[i] == '/' || path[i] == '\\') {
            base = path + i + 1u;
        }
    }
    /* 7 characters of position plus ".hgt". */
    if (strlen(base) != 11u) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt name must look like N46W122.hgt (SW corner), got \"%.40s\"", path,
                       base);
    }
    int ns = lower((unsigned char)base[0]);
    int ew = lower((unsigned char)base[3]);
    int ok = (ns == 'n' || ns == 's') && (ew == 'e' || ew == 'w') && is_digit(base[1]) &&
             is_digit(base[2]) && is_digit(base[4]) && is_digit(base[5]) && is_digit(base[6]) &&
             base[7] == '.' && lower((unsigned char)base[8]) == 'h' &&
             lower((unsigned char)base[9]) == 'g' && lower((unsigned char)base[10]) == 't';
    if (!ok) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt name must look like N46W122.hgt (SW corner), got \"%.40s\"", path,
                       base);
    }
    int lat = (base[1] - '0') * 10 + (base[2] - '0');
    int lon = (base[4] - '0') * 100 + (base[5] - '0') * 10 + (base[6] - '0');
    /* The tile spans lat..lat+1, lon..lon+1 from its SW corner. */
    int lat_max = (ns == 'n') ? 89 : 90;
    int lon_max = (ew == 'e') ? 179 : 180;
    if (lat > lat_max || lon > lon_max) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: .hgt SW corner %c%02d %c%03d is outside the globe (lat <= %d, lon <= %d)",
                       path, ns == 'n' ? 'N' : 'S', lat, ew == 'e' ? 'E' : 'W', lon, lat_max,
                       lon_max);
    }
    *lat_deg = (ns == 'n') ? (double)lat : -(double)lat;
    *lon_deg = (ew == 'e') ? (double)lon : -(double)lon;
    return FT_OK;
}

ft_status ft_hgt_probe(const ft_reader *r, const char *path, ft_terrain *t, ft_error *err)
{
    if (r == NULL || t == NULL) {
        return ft_fail(err, FT_ERR_ARG, "hgt probe: reader or terrain is NULL");
    }
    const char *name = (path != NULL) ? path : (r->name != NULL ? r->name : "(unnamed)");
    uint32_t side = 0u;
    double lat = 0.0, lon = 0.0;
    ft_status st = side_from_size(r->size_bytes, name, &side, err);
    if (st != FT_OK) {
        return st;
    }
    st = parse_name(name, &lat, &lon, err);
    if (st != FT_OK) {
        return st;
    }
    t->width = side;
    t->height = side;
    t->unit = FT_UNIT_DEGREE;
    t->spacing_x = 1.0 / (double)(side - 1u);
    t->spacing_y = t->spacing_x;
    t->origin_x = lon;
    t->origin_y = lat;
    t->anchor_lat_deg = lat;
    t->anchor_lon_deg = lon;
    memset(t->crs, 0, sizeof t->crs);
    memcpy(t->crs, "EPSG:4326", sizeof "EPSG:4326");
    t->void_count = 0u;
    t->min_height_m = 0.0f;
    t->max_height_m = 0.0f;
    st = ft_terrain_derive_frame(t, err);
    if (st != FT_OK) {
        return st;
    }
    return FT_OK;
}

/* Offset of the void fill's scratch after the row buffer and the mask. */
static size_t fill_scratch_offset(uint32_t width, uint32_t height)
{
    size_t off = (size_t)width * 2u + (size_t)width * height;
    return (off + 7u) & ~(size_t)7u;
}

int ft_hgt_height_ok(double v_m)
{
    return ft_terrain_height_ok(v_m) && v_m >= (double)FT_HGT_MIN_VALID_M &&
           v_m <= (double)FT_HGT_MAX_VALID_M;
}

size_t ft_hgt_scratch_bytes(uint32_t width, uint32_t height)
{
    if (width < FT_GRID_SIDE_MIN || height < FT_GRID_SIDE_MIN || width > FT_GRID_SIDE_MAX ||
        height > FT_GRID_SIDE_MAX) {
        return 0u;
    }
    /* row of int16 + one mask byte per sample (fits size_t: <= 2.7e8), then
     * the void fill's per-line state, 8-byte aligned. */
    return fill_scratch_offset(width, height) + ft_void_fill_scratch_bytes(width, height);
}

ft_status ft_hgt_load(const ft_reader *r, ft_terrain *t, void *scratch, size_t scratch_bytes,
                      ft_error *err)
{
    if (r == NULL || t == NULL || t->heights_m == NULL) {
        return ft_fail(err, FT_ERR_ARG, "hgt load: reader, terrain or heights is NULL");
    }
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    uint32_t w = t->width, h = t->height;
    size_t need = ft_hgt_scratch_bytes(w, h);
    if (need == 0u || w != h) {
        return ft_fail(err, FT_ERR_ARG, "%s: hgt load: grid %ux%u was not set by ft_hgt_probe",
                       name, w, h);
    }
    if ((uint64_t)w * h * 2u != r->size_bytes) {
        return ft_fail(err, FT_ERR_ARG, "%s: hgt load: %llu-byte file does not hold %ux%u samples",
                       name, (unsigned long long)r->size_bytes, w, h);
    }
    if (scratch == NULL || scratch_bytes < need) {
        return ft_fail(err, FT_ERR_BUDGET, "%s: hgt load needs %zu bytes of scratch, got %zu",
                       name, need, scratch == NULL ? (size_t)0 : scratch_bytes);
    }
    if (((uintptr_t)scratch % 8u) != 0u) {
        return ft_fail(err, FT_ERR_ARG, "%s: hgt load scratch is not 8-byte aligned", name);
    }
    uint8_t *row = (uint8_t *)scratch;
    uint8_t *mask = row + (size_t)w * 2u;
    uint32_t voids = 0u;

    for (uint32_t fr = 0u; fr < h; ++fr) {
        ft_status st = ft_read_exact(r, row, (size_t)w * 2u, err);
        if (st != FT_OK) {
            return st;
        }
        /* File rows run north to south; grid row 0 is south. */
        uint32_t gy = h - 1u - fr;
        float *dst = t->heights_m + (size_t)gy * w;
        uint8_t *mrow = mask + (size_t)gy * w;
        for (uint32_t c = 0u; c < w; ++c) {
            uint16_t u = (uint16_t)(((uint16_t)row[2u * c] << 8) | row[2u * c + 1u]);
            int32_t v = (u >= 0x8000u) ? (int32_t)u - 65536 : (int32_t)u;
            if (v == FT_HGT_VOID) {
                mrow[c] = 1u;
                dst[c] = 0.0f;
                ++voids;
                continue;
            }
            if (!ft_hgt_height_ok((double)v)) {
                return ft_fail(err, FT_ERR_FORMAT,
                               "%s: height %d m at file row %u col %u is outside %d..%d m and "
                               "not the void value %d",
                               name, (int)v, fr, c, FT_HGT_MIN_VALID_M, FT_HGT_MAX_VALID_M,
                               FT_HGT_VOID);
            }
            mrow[c] = 0u;
            dst[c] = (float)v;
        }
    }
    /* The size was promised up front; a stream that keeps going is lying. */
    {
        size_t got = 0u;
        uint8_t extra = 0u;
        ft_status st = r->read(r->ctx, &extra, 1u, &got);
        if (st != FT_OK) {
            return ft_fail(err, st, "%s: read after the last row failed", name);
        }
        if (got != 0u) {
            return ft_fail(err, FT_ERR_OVERSIZED, "%s: more data than the %llu bytes declared",
                           name, (unsigned long long)r->size_bytes);
        }
    }
    int all_void = 0;
    uint32_t filled = 0u;
    if (voids > 0u) {
        uint8_t *fill_scratch = (uint8_t *)scratch + fill_scratch_offset(w, h);
        filled = ft_void_fill(t->heights_m, mask, w, h, fill_scratch,
                              need - fill_scratch_offset(w, h), &all_void);
    }
    if (all_void) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: all %u samples are void (-32768)", name, filled);
    }
    if (filled != voids) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: void fill filled %u of %u voids", name, filled,
                       voids);
    }
    t->void_count = voids;
    if (t->void_bits != NULL) {
        (void)ft_terrain_pack_void_bits(mask, w, h, t->void_bits);
    }
    float lo = t->heights_m[0], hi = t->heights_m[0];
    size_t n = (size_t)w * h;
    for (size_t k = 1u; k < n; ++k) {
        float v = t->heights_m[k];
        lo = (v < lo) ? v : lo;
        hi = (v > hi) ? v : hi;
    }
    t->min_height_m = lo;
    t->max_height_m = hi;
    return FT_OK;
}
