/* terrain_file.c - the ".ftt" terrain file (layout in terrain_file.h).
 *
 * Everything is serialised field by field in little-endian, so the file is
 * the same on every host. The payload is read straight into the pools; on a
 * big-endian host it is byte-swapped in place after the crc check. */
#include "terrain/terrain_file.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/byte_codec.h"
#include "terrain/pyramid.h"
#include "terrain/void_fill.h"

/* Header field offsets (terrain_file.h). */
enum {
    OFF_MAGIC = 0,
    OFF_VERSION = 8,
    OFF_HEADER_BYTES = 12,
    OFF_WIDTH = 16,
    OFF_HEIGHT = 20,
    OFF_UNIT = 24,
    OFF_AVG_LEVELS = 28,
    OFF_MINMAX_LEVELS = 32,
    OFF_VOID_COUNT = 36,
    OFF_SPACING_X = 40,
    OFF_SPACING_Y = 48,
    OFF_ORIGIN_X = 56,
    OFF_ORIGIN_Y = 64,
    OFF_ANCHOR_LAT = 72,
    OFF_ANCHOR_LON = 80,
    OFF_VSCALE = 88,
    OFF_VOFFSET = 92,
    OFF_NODATA = 96,
    OFF_FILL_RULE = 100,
    OFF_MIN_H = 104,
    OFF_MAX_H = 108,
    OFF_PAYLOAD_BYTES = 112,
    OFF_PAYLOAD_CRC = 120,
    OFF_HEADER_CRC = 124,
    OFF_CRS = 128,
    OFF_RESERVED = 192
};

/* Largest block handed to one read or write call: a short block keeps the
 * per-call cost bounded. */
#define FT_TFILE_CHUNK_BYTES ((size_t)1u << 24)
/* Floats converted per step when the host is big-endian. */
#define FT_TFILE_SWAP_FLOATS 1024u

static int host_is_little_endian(void)
{
    const uint16_t probe = 1u;
    uint8_t b = 0u;
    memcpy(&b, &probe, 1u);
    return b == 1u;
}

/* crc32 of the header with its own crc field taken as zero. */
static uint32_t header_crc(const uint8_t hdr[FT_TFILE_HEADER_BYTES])
{
    uint8_t copy[FT_TFILE_HEADER_BYTES];
    memcpy(copy, hdr, sizeof copy);
    ft_le_put_u32(copy + OFF_HEADER_CRC, 0u);
    return ft_crc32(0u, copy, sizeof copy);
}

/* The arrays of the payload in file order (heights, avg 1.., min/max per
 * level). Returns the count; fails if the pyramid is not laid out for t. */
#define FT_TFILE_ARRAYS_MAX (1u + FT_PYRAMID_LEVELS_MAX + 2u * FT_PYRAMID_LEVELS_MAX)
typedef struct tfile_array {
    float *data;
    size_t count;
    uint32_t width; /* for messages */
    const char *what;
    uint32_t level;
} tfile_array;

static int dims_ok(uint32_t w, uint32_t h)
{
    return w >= FT_GRID_SIDE_MIN && h >= FT_GRID_SIDE_MIN && w <= FT_GRID_SIDE_MAX &&
           h <= FT_GRID_SIDE_MAX;
}

static ft_status collect_arrays(const ft_terrain *t, const char *name, tfile_array *arr,
                                uint32_t *count, ft_error *err)
{
    const ft_pyramid *p = &t->pyr;
    uint32_t avg_levels = ft_pyramid_avg_levels(t->width, t->height);
    uint32_t mm_levels = ft_pyramid_minmax_levels(t->width, t->height);
    if (t->heights_m == NULL) {
        return ft_fail(err, FT_ERR_ARG, "%s: terrain heights are not bound", name);
    }
    if (p->avg_levels != avg_levels || p->minmax_levels != mm_levels) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s: pyramid has %u avg / %u min-max levels, a %ux%u grid needs %u / %u "
                       "(call ft_pyramid_layout)",
                       name, p->avg_levels, p->minmax_levels, t->width, t->height, avg_levels,
                       mm_levels);
    }
    uint32_t n = 0u;
    arr[n++] = (tfile_array){t->heights_m, (size_t)t->width * t->height, t->width, "height", 0u};
    uint32_t w = t->width, h = t->height;
    for (uint32_t l = 1u; l < avg_levels; ++l) {
        w = (w + 1u) / 2u;
        h = (h + 1u) / 2u;
        const ft_pyramid_level *lv = &p->avg[l];
        if (lv->avg_m == NULL || lv->width != w || lv->height != h) {
            return ft_fail(err, FT_ERR_ARG, "%s: avg pyramid level %u is not laid out as %ux%u",
                           name, l, w, h);
        }
        arr[n++] = (tfile_array){lv->avg_m, (size_t)w * h, w, "avg", l};
    }
    w = t->width - 1u;
    h = t->height - 1u;
    for (uint32_t l = 0u; l < mm_levels; ++l) {
        const ft_pyramid_level *lv = &p->minmax[l];
        if (lv->min_m == NULL || lv->max_m == NULL || lv->width != w || lv->height != h) {
            return ft_fail(err, FT_ERR_ARG,
                           "%s: min/max pyramid level %u is not laid out as %ux%u", name, l, w,
                           h);
        }
        arr[n++] = (tfile_array){lv->min_m, (size_t)w * h, w, "min", l};
        arr[n++] = (tfile_array){lv->max_m, (size_t)w * h, w, "max", l};
        w = (w + 1u) / 2u;
        h = (h + 1u) / 2u;
    }
    *count = n;
    return FT_OK;
}

/* Payload size from the dimensions and the void count alone (never from
 * the file): version 2 appends the void bits when samples were filled. */
static uint64_t payload_bytes_for(uint32_t w, uint32_t h, uint32_t void_count)
{
    return (uint64_t)w * h * sizeof(float) + (uint64_t)ft_pyramid_bytes(w, h) +
           (void_count > 0u ? (uint64_t)ft_terrain_void_bits_bytes(w, h) : 0u);
}

/* Streams bytes in chunks into the writer and/or the crc. */
static ft_status emit_bytes(const uint8_t *src, size_t left, const ft_writer *w, uint32_t *crc,
                            ft_error *err)
{
    const char *name = (w != NULL && w->name != NULL) ? w->name : "(unnamed)";
    for (size_t guard = 0u; left > 0u && guard < ((size_t)-1 / 2u); ++guard) {
        size_t n = left < FT_TFILE_CHUNK_BYTES ? left : FT_TFILE_CHUNK_BYTES;
        if (crc != NULL) {
            *crc = ft_crc32(*crc, src, n);
        }
        if (w != NULL) {
            ft_status st = w->write(w->ctx, src, n);
            if (st != FT_OK) {
                return ft_fail(err, st, "%s: writing %zu payload bytes failed", name, n);
            }
        }
        src += n;
        left -= n;
    }
    return FT_OK;
}

static void swap_floats(float *f, size_t n)
{
    for (size_t k = 0u; k < n; ++k) {
        uint8_t b[4];
        memcpy(b, &f[k], 4u);
        uint8_t s[4] = {b[3], b[2], b[1], b[0]};
        memcpy(&f[k], s, 4u);
    }
}

/* Puts the file name in front of a message from a function that has none. */
static ft_status prefix_name(ft_error *err, ft_status st, const char *name)
{
    if (err == NULL) {
        return st;
    }
    char text[sizeof err->text];
    memcpy(text, err->text, sizeof text);
    text[sizeof text - 1u] = '\0';
    return ft_fail(err, st, "%s: %s", name, text);
}

/* ---- probe ------------------------------------------------------------------ */

ft_status ft_tfile_probe(const ft_reader *r, ft_terrain *t, ft_tfile_header *hdr_out, ft_error *err)
{
    if (r == NULL || t == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain file probe: reader or terrain is NULL");
    }
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    uint8_t hdr[FT_TFILE_HEADER_BYTES];
    size_t got = 0u;
    if (hdr_out == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain file probe: header record is NULL");
    }
    hdr_out->valid = 0;
    memset(hdr, 0, sizeof hdr);
    ft_status st = r->read(r->ctx, hdr, sizeof hdr, &got);
    if (st != FT_OK) {
        return ft_fail(err, st, "%s: reading the %u-byte header failed", name,
                       FT_TFILE_HEADER_BYTES);
    }
    if (got >= 8u && memcmp(hdr + OFF_MAGIC, FT_TFILE_MAGIC, 8u) != 0) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: bad magic (not a fixterrain .ftt file, or mangled by a text-mode copy)",
                       name);
    }
    if (got < sizeof hdr) {
        return ft_fail(err, FT_ERR_TRUNCATED, "%s: truncated inside the header (%zu of %u bytes)",
                       name, got, FT_TFILE_HEADER_BYTES);
    }
    uint32_t version = ft_le_get_u32(hdr + OFF_VERSION);
    if (version != FT_TFILE_VERSION && version != FT_TFILE_VERSION_NO_VOID_BITS) {
        return ft_fail(err, FT_ERR_VERSION, "%s: file version %u, this build reads versions %u and %u",
                       name, version, FT_TFILE_VERSION_NO_VOID_BITS, FT_TFILE_VERSION);
    }
    uint32_t header_bytes = ft_le_get_u32(hdr + OFF_HEADER_BYTES);
    if (header_bytes != FT_TFILE_HEADER_BYTES) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: header_bytes is %u, expected %u", name,
                       header_bytes, FT_TFILE_HEADER_BYTES);
    }
    uint32_t crc_stored = ft_le_get_u32(hdr + OFF_HEADER_CRC);
    uint32_t crc_calc = header_crc(hdr);
    if (crc_stored != crc_calc) {
        return ft_fail(err, FT_ERR_CHECKSUM,
                       "%s: header crc32 is 0x%08x, the header bytes give 0x%08x", name,
                       crc_stored, crc_calc);
    }
    uint32_t w = ft_le_get_u32(hdr + OFF_WIDTH), h = ft_le_get_u32(hdr + OFF_HEIGHT);
    if (!dims_ok(w, h)) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: grid %ux%u is outside %u..%u samples per side",
                       name, w, h, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    uint32_t unit = ft_le_get_u32(hdr + OFF_UNIT);
    if (unit != (uint32_t)FT_UNIT_METRE && unit != (uint32_t)FT_UNIT_DEGREE) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: spacing_unit %u is neither 0 (m) nor 1 (deg)",
                       name, unit);
    }
    uint32_t avg_levels = ft_le_get_u32(hdr + OFF_AVG_LEVELS);
    uint32_t mm_levels = ft_le_get_u32(hdr + OFF_MINMAX_LEVELS);
    uint32_t avg_want = ft_pyramid_avg_levels(w, h), mm_want = ft_pyramid_minmax_levels(w, h);
    if (avg_levels != avg_want || mm_levels != mm_want) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: level counts avg %u / minmax %u, a %ux%u grid has %u / %u", name,
                       avg_levels, mm_levels, w, h, avg_want, mm_want);
    }
    uint32_t void_count = ft_le_get_u32(hdr + OFF_VOID_COUNT);
    if ((uint64_t)void_count > (uint64_t)w * h) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: void_count %u exceeds the %llu samples", name,
                       void_count, (unsigned long long)((uint64_t)w * h));
    }
    if (version == FT_TFILE_VERSION_NO_VOID_BITS && void_count > 0u) {
        /* the renderer must show invented terrain as such; without the
         * bits it cannot say where */
        return ft_fail(err, FT_ERR_VERSION,
                       "%s: a version 1 file: %u void-filled samples recorded but not which; "
                       "import the DEM again (version 2 records them)",
                       name, void_count);
    }
    double sx = ft_le_get_f64(hdr + OFF_SPACING_X), sy = ft_le_get_f64(hdr + OFF_SPACING_Y);
    double ox = ft_le_get_f64(hdr + OFF_ORIGIN_X), oy = ft_le_get_f64(hdr + OFF_ORIGIN_Y);
    double alat = ft_le_get_f64(hdr + OFF_ANCHOR_LAT), alon = ft_le_get_f64(hdr + OFF_ANCHOR_LON);
    if (!isfinite(sx) || !isfinite(sy) || !(sx > 0.0) || !(sy > 0.0)) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: spacing %g x %g is not positive and finite", name,
                       sx, sy);
    }
    if (!isfinite(ox) || !isfinite(oy) || !isfinite(alat) || !isfinite(alon)) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: origin (%g, %g) or anchor (%g, %g) is not finite", name, ox, oy, alat,
                       alon);
    }
    float vscale = ft_le_get_f32(hdr + OFF_VSCALE), voffset = ft_le_get_f32(hdr + OFF_VOFFSET);
    if (!isfinite(vscale) || !(vscale > 0.0f) || !isfinite(voffset)) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: vertical scale %g must be positive and finite, offset %g finite", name,
                       (double)vscale, (double)voffset);
    }
    uint32_t rule = ft_le_get_u32(hdr + OFF_FILL_RULE);
    if (rule > FT_VOID_FILL_RULE_IDW8 || (rule == 0u && void_count != 0u)) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: void_fill_rule %u unknown (or 0 with %u voids filled)", name, rule,
                       void_count);
    }
    float hmin = ft_le_get_f32(hdr + OFF_MIN_H), hmax = ft_le_get_f32(hdr + OFF_MAX_H);
    if (!ft_terrain_height_ok((double)hmin) || !ft_terrain_height_ok((double)hmax) ||
        hmin > hmax) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "%s: header height range %g..%g m is not ordered within %g..%g m", name,
                       (double)hmin, (double)hmax, FT_HEIGHT_MIN_M, FT_HEIGHT_MAX_M);
    }
    uint64_t payload = ft_le_get_u64(hdr + OFF_PAYLOAD_BYTES);
    uint64_t payload_want = payload_bytes_for(w, h, void_count);
    if (payload != payload_want) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: payload_bytes %llu, a %ux%u grid with pyramids needs %llu", name,
                       (unsigned long long)payload, w, h, (unsigned long long)payload_want);
    }
    const char *crs = (const char *)(hdr + OFF_CRS);
    st = ft_terrain_check_crs(crs, FT_CRS_TEXT_MAX, name, err);
    if (st != FT_OK) {
        return st;
    }
    size_t crs_len = strlen(crs);
    for (uint32_t k = OFF_RESERVED; k < FT_TFILE_HEADER_BYTES; ++k) {
        if (hdr[k] != 0u) {
            return ft_fail(err, FT_ERR_FORMAT, "%s: reserved header byte %u is 0x%02x, not 0",
                           name, k, hdr[k]);
        }
    }
    uint64_t want_size = (uint64_t)FT_TFILE_HEADER_BYTES + payload;
    if (r->size_bytes < want_size) {
        return ft_fail(err, FT_ERR_TRUNCATED,
                       "%s: file is %llu bytes, header + payload of a %ux%u grid need %llu", name,
                       (unsigned long long)r->size_bytes, w, h, (unsigned long long)want_size);
    }
    if (r->size_bytes > want_size) {
        return ft_fail(err, FT_ERR_OVERSIZED,
                       "%s: file is %llu bytes, %llu more than the %llu of header + payload", name,
                       (unsigned long long)r->size_bytes,
                       (unsigned long long)(r->size_bytes - want_size),
                       (unsigned long long)want_size);
    }

    memset(t, 0, sizeof *t);
    t->width = w;
    t->height = h;
    t->unit = (ft_spacing_unit)unit;
    t->spacing_x = sx;
    t->spacing_y = sy;
    t->origin_x = ox;
    t->origin_y = oy;
    t->anchor_lat_deg = alat;
    t->anchor_lon_deg = alon;
    memcpy(t->crs, crs, crs_len);
    t->void_count = void_count;
    t->min_height_m = hmin;
    t->max_height_m = hmax;
    st = ft_terrain_derive_frame(t, err);
    if (st != FT_OK) {
        return prefix_name(err, st, name);
    }
    hdr_out->payload_crc32 = ft_le_get_u32(hdr + OFF_PAYLOAD_CRC);
    hdr_out->vertical_scale = vscale;
    hdr_out->vertical_offset = voffset;
    hdr_out->header_min_m = hmin;
    hdr_out->header_max_m = hmax;
    hdr_out->void_bits_bytes = void_count > 0u ? ft_terrain_void_bits_bytes(w, h) : 0u;
    hdr_out->valid = 1;
    return FT_OK;
}

/* ---- payload ------------------------------------------------------------------ */

ft_status ft_tfile_load_payload(const ft_reader *r, ft_terrain *t, ft_tfile_header *hdr,
                                ft_error *err)
{
    if (r == NULL || t == NULL || hdr == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain file load: reader or terrain is NULL");
    }
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    if (!hdr->valid) {
        return ft_fail(err, FT_ERR_ARG,
                       "%s: ft_tfile_load_payload without a successful ft_tfile_probe "
                       "(or a second load after one probe)",
                       name);
    }
    const ft_tfile_header pend = *hdr;
    hdr->valid = 0; /* one load per probe: the reader has moved on */
    if (!dims_ok(t->width, t->height)) {
        return ft_fail(err, FT_ERR_ARG, "%s: terrain grid %ux%u changed since the probe", name,
                       t->width, t->height);
    }
    tfile_array arr[FT_TFILE_ARRAYS_MAX];
    uint32_t n_arr = 0u;
    ft_status st = collect_arrays(t, name, arr, &n_arr, err);
    if (st != FT_OK) {
        return st;
    }
    if (pend.void_bits_bytes > 0u && t->void_bits == NULL) {
        return ft_fail(err, FT_ERR_ARG, "%s: %u void-filled samples but no void_bits storage",
                       name, t->void_count);
    }
    uint32_t crc = 0u;
    for (uint32_t a = 0u; a <= n_arr; ++a) {
        if (a == n_arr && pend.void_bits_bytes == 0u) {
            break;
        }
        /* the arrays, then (version 2, voids filled) the void bits */
        uint8_t *dst = a < n_arr ? (uint8_t *)arr[a].data : t->void_bits;
        size_t left = a < n_arr ? arr[a].count * sizeof(float) : pend.void_bits_bytes;
        for (size_t guard = 0u; left > 0u && guard < ((size_t)-1 / 2u); ++guard) {
            size_t n = left < FT_TFILE_CHUNK_BYTES ? left : FT_TFILE_CHUNK_BYTES;
            st = ft_read_exact(r, dst, n, err);
            if (st != FT_OK) {
                return st;
            }
            crc = ft_crc32(crc, dst, n);
            dst += n;
            left -= n;
        }
    }
    {
        size_t got = 0u;
        uint8_t extra = 0u;
        st = r->read(r->ctx, &extra, 1u, &got);
        if (st != FT_OK) {
            return ft_fail(err, st, "%s: read after the payload failed", name);
        }
        if (got != 0u) {
            return ft_fail(err, FT_ERR_OVERSIZED, "%s: data continues past the declared payload",
                           name);
        }
    }
    if (crc != pend.payload_crc32) {
        return ft_fail(err, FT_ERR_CHECKSUM,
                       "%s: payload crc32 is 0x%08x, the header says 0x%08x", name, crc,
                       pend.payload_crc32);
    }
    if (pend.void_bits_bytes > 0u) {
        st = ft_terrain_check_void_bits(t->void_bits, t->width, t->height, t->void_count, name,
                                        err);
        if (st != FT_OK) {
            return st;
        }
    }
    const int identity = (pend.vertical_scale == 1.0f && pend.vertical_offset == 0.0f);
    const int swap = !host_is_little_endian();
    float lo = INFINITY, hi = -INFINITY;
    for (uint32_t a = 0u; a < n_arr; ++a) {
        float *d = arr[a].data;
        size_t cnt = arr[a].count;
        if (swap) {
            swap_floats(d, cnt);
        }
        for (size_t k = 0u; k < cnt; ++k) {
            float v = identity ? d[k] : d[k] * pend.vertical_scale + pend.vertical_offset;
            if (!isfinite(v) && a == 0u) {
                return ft_fail(err, FT_ERR_NUMERIC,
                               "%s: height at row %zu col %zu is not finite (%g)", name,
                               k / arr[a].width, k % arr[a].width, (double)v);
            }
            if (!isfinite(v)) {
                return ft_fail(err, FT_ERR_NUMERIC,
                               "%s: %s level %u value at row %zu col %zu is not finite (%g)",
                               name, arr[a].what, arr[a].level, k / arr[a].width,
                               k % arr[a].width, (double)v);
            }
            d[k] = v;
            if (a == 0u) {
                lo = v < lo ? v : lo;
                hi = v > hi ? v : hi;
            }
        }
    }
    /* The same height range the importer and the writer enforce. */
    st = ft_terrain_check_heights(t->heights_m, t->width, t->height, name, err);
    if (st != FT_OK) {
        return st;
    }
    /* The header range is informational for planning; the data decides, but
     * a large disagreement means a broken writer. */
    double tol = 0.01 + 1e-6 * (fabs((double)lo) + fabs((double)hi));
    if (fabs((double)lo - (double)pend.header_min_m) > tol ||
        fabs((double)hi - (double)pend.header_max_m) > tol) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "%s: heights span %g..%g m but the header says %g..%g m", name, (double)lo,
                       (double)hi, (double)pend.header_min_m, (double)pend.header_max_m);
    }
    t->pyr.avg[0].avg_m = t->heights_m;
    /* The pyramids against the heights: every error bound comes from them. */
    st = ft_pyramid_check(t, name, err);
    if (st != FT_OK) {
        return st;
    }
    t->min_height_m = lo;
    t->max_height_m = hi;
    return FT_OK;
}

/* ---- write ------------------------------------------------------------------ */

/* Runs crc and/or write over one array as little-endian bytes. */
static ft_status emit_array(const tfile_array *a, const ft_writer *w, uint32_t *crc,
                            ft_error *err)
{
    const char *name = (w != NULL && w->name != NULL) ? w->name : "(unnamed)";
    if (host_is_little_endian()) {
        return emit_bytes((const uint8_t *)a->data, a->count * sizeof(float), w, crc, err);
    }
    float buf[FT_TFILE_SWAP_FLOATS];
    for (size_t k = 0u; k < a->count; k += FT_TFILE_SWAP_FLOATS) {
        size_t n = a->count - k;
        n = n < FT_TFILE_SWAP_FLOATS ? n : FT_TFILE_SWAP_FLOATS;
        memcpy(buf, a->data + k, n * sizeof(float));
        swap_floats(buf, n);
        if (crc != NULL) {
            *crc = ft_crc32(*crc, buf, n * sizeof(float));
        }
        if (w != NULL) {
            ft_status st = w->write(w->ctx, buf, n * sizeof(float));
            if (st != FT_OK) {
                return ft_fail(err, st, "%s: writing %zu payload bytes failed", name,
                               n * sizeof(float));
            }
        }
    }
    return FT_OK;
}

ft_status ft_tfile_write(const ft_terrain *t, float nodata_value, const ft_writer *w,
                         ft_error *err)
{
    if (t == NULL || w == NULL) {
        return ft_fail(err, FT_ERR_ARG, "terrain file write: terrain or writer is NULL");
    }
    const char *name = (w->name != NULL) ? w->name : "(unnamed)";
    if (!dims_ok(t->width, t->height)) {
        return ft_fail(err, FT_ERR_ARG, "%s: grid %ux%u is outside %u..%u samples per side", name,
                       t->width, t->height, FT_GRID_SIDE_MIN, FT_GRID_SIDE_MAX);
    }
    if (t->unit != FT_UNIT_METRE && t->unit != FT_UNIT_DEGREE) {
        return ft_fail(err, FT_ERR_ARG, "%s: spacing unit %d unknown", name, (int)t->unit);
    }
    /* Everything the reader checks, checked here with the same functions:
     * never write a file the runtime would refuse. */
    {
        ft_terrain frame = *t;
        ft_status fst = ft_terrain_derive_frame(&frame, err);
        if (fst != FT_OK) {
            return prefix_name(err, fst, name);
        }
    }
    ft_status st = ft_terrain_check_crs(t->crs, sizeof t->crs, name, err);
    if (st != FT_OK) {
        return st;
    }
    size_t crs_len = strlen(t->crs);
    tfile_array arr[FT_TFILE_ARRAYS_MAX];
    uint32_t n_arr = 0u;
    st = collect_arrays(t, name, arr, &n_arr, err);
    if (st != FT_OK) {
        return st;
    }
    st = ft_terrain_check_heights(t->heights_m, t->width, t->height, name, err);
    if (st != FT_OK) {
        return st;
    }
    st = ft_pyramid_check(t, name, err);
    if (st != FT_OK) {
        return st;
    }
    float lo = t->heights_m[0], hi = t->heights_m[0];
    for (size_t k = 0u; k < arr[0].count; ++k) {
        float v = t->heights_m[k];
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    const size_t bits_bytes =
        t->void_count > 0u ? ft_terrain_void_bits_bytes(t->width, t->height) : 0u;
    if (t->void_count > 0u) {
        if (t->void_bits == NULL) {
            return ft_fail(err, FT_ERR_ARG,
                           "%s: %u void-filled samples but no void bits to say which", name,
                           t->void_count);
        }
        st = ft_terrain_check_void_bits(t->void_bits, t->width, t->height, t->void_count, name,
                                        err);
        if (st != FT_OK) {
            return st;
        }
    }
    /* First pass: the payload crc, so the header can go out first. */
    uint32_t crc = 0u;
    for (uint32_t a = 0u; a < n_arr; ++a) {
        st = emit_array(&arr[a], NULL, &crc, err);
        if (st != FT_OK) {
            return st;
        }
    }
    st = emit_bytes(t->void_bits, bits_bytes, NULL, &crc, err);
    if (st != FT_OK) {
        return st;
    }
    uint8_t hdr[FT_TFILE_HEADER_BYTES];
    memset(hdr, 0, sizeof hdr);
    memcpy(hdr + OFF_MAGIC, FT_TFILE_MAGIC, 8u);
    ft_le_put_u32(hdr + OFF_VERSION, FT_TFILE_VERSION);
    ft_le_put_u32(hdr + OFF_HEADER_BYTES, FT_TFILE_HEADER_BYTES);
    ft_le_put_u32(hdr + OFF_WIDTH, t->width);
    ft_le_put_u32(hdr + OFF_HEIGHT, t->height);
    ft_le_put_u32(hdr + OFF_UNIT, (uint32_t)t->unit);
    ft_le_put_u32(hdr + OFF_AVG_LEVELS, t->pyr.avg_levels);
    ft_le_put_u32(hdr + OFF_MINMAX_LEVELS, t->pyr.minmax_levels);
    ft_le_put_u32(hdr + OFF_VOID_COUNT, t->void_count);
    ft_le_put_f64(hdr + OFF_SPACING_X, t->spacing_x);
    ft_le_put_f64(hdr + OFF_SPACING_Y, t->spacing_y);
    ft_le_put_f64(hdr + OFF_ORIGIN_X, t->origin_x);
    ft_le_put_f64(hdr + OFF_ORIGIN_Y, t->origin_y);
    ft_le_put_f64(hdr + OFF_ANCHOR_LAT, t->anchor_lat_deg);
    ft_le_put_f64(hdr + OFF_ANCHOR_LON, t->anchor_lon_deg);
    ft_le_put_f32(hdr + OFF_VSCALE, 1.0f);
    ft_le_put_f32(hdr + OFF_VOFFSET, 0.0f);
    ft_le_put_f32(hdr + OFF_NODATA, nodata_value);
    ft_le_put_u32(hdr + OFF_FILL_RULE, FT_VOID_FILL_RULE_IDW8);
    ft_le_put_f32(hdr + OFF_MIN_H, lo);
    ft_le_put_f32(hdr + OFF_MAX_H, hi);
    ft_le_put_u64(hdr + OFF_PAYLOAD_BYTES, payload_bytes_for(t->width, t->height, t->void_count));
    ft_le_put_u32(hdr + OFF_PAYLOAD_CRC, crc);
    memcpy(hdr + OFF_CRS, t->crs, crs_len);
    ft_le_put_u32(hdr + OFF_HEADER_CRC, header_crc(hdr));
    st = w->write(w->ctx, hdr, sizeof hdr);
    if (st != FT_OK) {
        return ft_fail(err, st, "%s: writing the %u-byte header failed", name,
                       FT_TFILE_HEADER_BYTES);
    }
    for (uint32_t a = 0u; a < n_arr; ++a) {
        st = emit_array(&arr[a], w, NULL, err);
        if (st != FT_OK) {
            return st;
        }
    }
    return emit_bytes(t->void_bits, bits_bytes, w, NULL, err);
}
