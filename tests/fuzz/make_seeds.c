/* make_seeds.c - writes the binary seed inputs of the fuzz corpora
 * (tests/fuzz/corpus/{canaero,ftd,ftt,hgt}); the text corpora are hand-written.
 * Tiny grids made here (no real data): valid files from the project's own
 * writer and a few slightly broken ones. Re-run after a format change:
 *   cmake --build B --target fuzz_make_seeds && B/tests/fuzz_make_seeds tests/fuzz/corpus
 * (the target is not built by default). */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../ftd_synth.h"
#include "core/io.h"
#include "input/canaero.h"
#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "terrain/terrain_db.h"
#include "terrain/terrain_file.h"

#define SEED_MAX_BYTES 65536u

static const char *g_dir;

static void put(const char *sub, const char *name, const void *data, size_t n)
{
    char path[1024];
    (void)snprintf(path, sizeof path, "%s/%s/%s", g_dir, sub, name);
    FILE *f = fopen(path, "wb");
    if (f == NULL || fwrite(data, 1u, n, f) != n || fclose(f) != 0) {
        fprintf(stderr, "make_seeds: cannot write %s\n", path);
        exit(1);
    }
}

/* ---- .ftt --------------------------------------------------------------- */

/* voids: that many samples (every third from sample 1) recorded as void-filled */
static size_t ftt_bytes(uint8_t *out, uint32_t w, uint32_t h, ft_spacing_unit unit, double sx,
                        double ox, double oy, uint32_t voids)
{
    ft_terrain t;
    memset(&t, 0, sizeof t);
    t.width = w;
    t.height = h;
    t.unit = unit;
    t.spacing_x = sx;
    t.spacing_y = sx;
    t.origin_x = ox;
    t.origin_y = oy;
    t.anchor_lat_deg = unit == FT_UNIT_DEGREE ? oy : 46.5;
    t.anchor_lon_deg = unit == FT_UNIT_DEGREE ? ox : 8.0;
    memcpy(t.crs, unit == FT_UNIT_DEGREE ? "EPSG:4326" : "local", 10u);
    float *hm = (float *)malloc((size_t)w * h * sizeof(float));
    size_t pb = ft_pyramid_bytes(w, h);
    void *pyr = malloc(pb);
    ft_error err;
    if (hm == NULL || pyr == NULL) {
        exit(1);
    }
    for (uint32_t y = 0u; y < h; ++y) {
        for (uint32_t x = 0u; x < w; ++x) {
            hm[y * w + x] = 100.0f + 7.0f * (float)x - 3.0f * (float)y + (float)((x * y) % 5u);
        }
    }
    t.heights_m = hm;
    uint8_t bits[64] = {0};
    for (uint32_t v = 0u; v < voids && 1u + 3u * v < w * h && 1u + 3u * v < 8u * sizeof bits; ++v) {
        const uint32_t i = 1u + 3u * v;
        bits[i >> 3] = (uint8_t)(bits[i >> 3] | (1u << (i & 7u)));
        t.void_count += 1u;
    }
    t.void_bits = t.void_count > 0u ? bits : NULL;
    if (ft_terrain_derive_frame(&t, &err) != FT_OK || ft_pyramid_layout(&t, pyr, pb, &err) != FT_OK) {
        fprintf(stderr, "make_seeds: %s\n", err.text);
        exit(1);
    }
    ft_pyramid_build(&t);
    ft_writer wr;
    ft_mem_writer mw;
    ft_mem_writer_init(&wr, &mw, out, SEED_MAX_BYTES, "seed.ftt");
    if (ft_tfile_write(&t, -32768.0f, &wr, &err) != FT_OK) {
        fprintf(stderr, "make_seeds: %s\n", err.text);
        exit(1);
    }
    free(pyr);
    free(hm);
    return mw.pos;
}

static void make_ftt(void)
{
    static uint8_t b[SEED_MAX_BYTES];
    size_t n = ftt_bytes(b, 2u, 2u, FT_UNIT_METRE, 30.0, 600000.0, 5000000.0, 0u);
    put("ftt", "valid_2x2_m.ftt", b, n);
    n = ftt_bytes(b, 3u, 3u, FT_UNIT_DEGREE, 0.5, 8.0, 46.0, 0u);
    put("ftt", "valid_3x3_deg.ftt", b, n);
    n = ftt_bytes(b, 6u, 5u, FT_UNIT_METRE, 20.0, 0.0, 0.0, 3u);
    put("ftt", "valid_6x5_voids.ftt", b, n);
    n = ftt_bytes(b, 5u, 4u, FT_UNIT_METRE, 10.0, 0.0, 0.0, 0u);
    put("ftt", "valid_5x4_m.ftt", b, n);
    put("ftt", "truncated_payload.ftt", b, n - 4u);
    put("ftt", "header_only.ftt", b, FT_TFILE_HEADER_BYTES);
    b[FT_TFILE_HEADER_BYTES + 3u] ^= 0x40u; /* a height changed: payload crc fails */
    put("ftt", "bad_payload_crc.ftt", b, n);
    b[0] = 'X';
    put("ftt", "bad_magic.ftt", b, n);
}

/* ---- .ftd --------------------------------------------------------------- */
/* tests/ftd_synth.h, with level 1's max raised 5 m (a footprint wider than
 * the tile's own samples) */
static size_t ftd_bytes(uint8_t *out)
{
    ft_tdb_header h;
    ft_error err;
    const size_t n = ft_synth_ftd(out, SEED_MAX_BYTES, 5.0f, &h, &err);
    if (n == 0u) {
        fprintf(stderr, "make_seeds: %s\n", err.text);
        exit(1);
    }
    return n;
}

static void make_ftd(void)
{
    static uint8_t b[SEED_MAX_BYTES];
    size_t n = ftd_bytes(b);
    put("ftd", "valid_2_levels.ftd", b, n);
    put("ftd", "truncated.ftd", b, n - 7u);
    put("ftd", "header_only.ftd", b, FT_TDB_HEADER_BYTES);
    b[FT_TDB_HEADER_BYTES + 2u * FT_TDB_ENTRY_BYTES + 1000u] ^= 0x10u;
    put("ftd", "bad_tile_crc.ftd", b, n);
}

/* ---- .hgt --------------------------------------------------------------- */

static size_t hgt_grid(uint8_t *out, uint32_t side, int16_t base, int void_at)
{
    size_t n = 0u;
    for (uint32_t i = 0u; i < side * side; ++i) {
        int v = ((int)i == void_at) ? -32768 : base + (int)(i * 13u % 97u);
        uint16_t u = (uint16_t)(v & 0xFFFF);
        out[n++] = (uint8_t)(u >> 8);
        out[n++] = (uint8_t)u;
    }
    return n;
}

static void make_hgt(void)
{
    uint8_t b[4096];
    size_t n = hgt_grid(b, 2u, 500, -1);
    put("hgt", "valid_2x2", b, n);
    n = hgt_grid(b, 3u, 1200, 4);
    put("hgt", "void_3x3", b, n);
    n = hgt_grid(b, 5u, -20, 7);
    put("hgt", "valid_5x5_void", b, n);
    put("hgt", "odd_length", b, 9u);
    put("hgt", "not_square", b, 2u * 6u);
    n = hgt_grid(b, 3u, 32000, -1); /* 32000 m: out of range */
    put("hgt", "out_of_range_3x3", b, n);
    for (size_t k = 0u; k < 8u; k += 2u) { /* 0x8000 = -32768 everywhere */
        b[k] = 0x80u;
        b[k + 1u] = 0x00u;
    }
    put("hgt", "all_void_2x2", b, 8u);
    static const char name[] = "@S33W071.hgt\n";
    memcpy(b, name, sizeof name - 1u);
    n = hgt_grid(b + sizeof name - 1u, 3u, 4000, -1);
    put("hgt", "named_S33W071", b, n + sizeof name - 1u);
    static const char bad[] = "@X46E008.hgt\n";
    memcpy(b, bad, sizeof bad - 1u);
    put("hgt", "named_bad", b, n + sizeof bad - 1u);
}

/* ---- CANaerospace records (layout in fuzz_canaero.c) ------------------------ */

typedef struct rec_builder {
    uint8_t b[4096];
    size_t n;
    ft_can_map map;
} rec_builder;

static uint16_t sel_of(const rec_builder *rb, uint16_t can_id)
{
    for (uint32_t i = 0u; i < rb->map.count; ++i) {
        if (rb->map.e[i].can_id == can_id) {
            return (uint16_t)i;
        }
    }
    return (uint16_t)(0x8000u | can_id); /* raw id */
}

static void rec(rec_builder *rb, uint16_t can_id, uint8_t dlc, uint8_t type, uint8_t code,
                uint32_t bits, uint8_t time_mode, uint32_t time_arg)
{
    uint8_t *r = rb->b + rb->n;
    uint16_t sel = sel_of(rb, can_id);
    r[0] = (uint8_t)sel;
    r[1] = (uint8_t)(sel >> 8);
    r[2] = (uint8_t)(dlc | (time_mode << 5));
    r[3] = 1u; /* node */
    r[4] = type;
    r[5] = 0u;
    r[6] = code;
    r[7] = (uint8_t)(bits >> 24);
    r[8] = (uint8_t)(bits >> 16);
    r[9] = (uint8_t)(bits >> 8);
    r[10] = (uint8_t)bits;
    r[11] = (uint8_t)time_arg;
    r[12] = (uint8_t)(time_arg >> 8);
    r[13] = (uint8_t)(time_arg >> 16);
    r[14] = (uint8_t)(time_arg >> 24);
    r[15] = 5u; /* view 5 ms later */
    rb->n += 16u;
}

static uint32_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static void setup(rec_builder *rb, uint16_t horizon_ms)
{
    rb->n = 0u;
    rb->b[rb->n++] = (uint8_t)horizon_ms;
    rb->b[rb->n++] = (uint8_t)(horizon_ms >> 8);
    rb->b[rb->n++] = 5u;  /* converge 200 ms */
    rb->b[rb->n++] = 1u;  /* snap 401 m */
}

/* set-up with bit 1 of byte 1: a scale for every map entry follows */
static void setup_scaled(rec_builder *rb, uint16_t horizon_ms, double scale)
{
    uint64_t bits;
    memcpy(&bits, &scale, sizeof bits);
    setup(rb, (uint16_t)(horizon_ms | 0x0200u));
    for (uint32_t k = 0u; k < 8u; ++k) {
        rb->b[rb->n++] = (uint8_t)(bits >> (8u * k));
    }
}

static void make_canaero(void)
{
    static rec_builder rb;
    ft_canaero_default_map(&rb.map);
    double lat = 46.5, lon = 8.0;
    uint64_t lat_bits, lon_bits;
    memcpy(&lat_bits, &lat, 8u);
    memcpy(&lon_bits, &lon, 8u);

    /* a clean stream: attitude, rates, position, velocity */
    setup(&rb, 100u);
    for (uint8_t k = 0u; k < 4u; ++k) {
        rec(&rb, 311u, 8u, 2u, k, fbits(2.0f + k), 0u, 250u);
        rec(&rb, 312u, 8u, 2u, k, fbits(-5.0f), 0u, 250u);
        rec(&rb, 321u, 8u, 2u, k, fbits(90.0f), 0u, 250u);
        rec(&rb, 303u, 8u, 2u, k, fbits(1.0f), 0u, 250u);
        rec(&rb, 304u, 8u, 2u, k, fbits(0.5f), 0u, 250u);
        rec(&rb, 305u, 8u, 2u, k, fbits(-0.5f), 0u, 250u);
        rec(&rb, 1036u, 8u, 30u, (uint8_t)(2u * k), (uint32_t)(lat_bits >> 32), 0u, 250u);
        rec(&rb, 1036u, 8u, 31u, (uint8_t)(2u * k + 1u), (uint32_t)lat_bits, 0u, 250u);
        rec(&rb, 1037u, 8u, 30u, (uint8_t)(2u * k), (uint32_t)(lon_bits >> 32), 0u, 250u);
        rec(&rb, 1037u, 8u, 31u, (uint8_t)(2u * k + 1u), (uint32_t)lon_bits, 0u, 250u);
        rec(&rb, 320u, 8u, 2u, k, fbits(1500.0f), 0u, 250u);
        rec(&rb, 1039u, 8u, 2u, k, fbits(80.0f), 0u, 250u);
        rec(&rb, 1040u, 8u, 2u, k, fbits(45.0f), 0u, 250u);
        rec(&rb, 314u, 8u, 2u, k, fbits(3.0f), 2u, 12u);
    }
    put("canaero", "clean_stream", rb.b, rb.n);

    /* every reject reason once, and the other data types */
    setup(&rb, 0u);
    rec(&rb, 0x123u, 8u, 2u, 0u, fbits(1.0f), 0u, 100u);      /* unknown id */
    rec(&rb, 311u, 3u, 2u, 0u, fbits(1.0f), 0u, 100u);        /* dlc < 4 */
    rec(&rb, 311u, 8u, 9u, 1u, fbits(1.0f), 0u, 100u);        /* unknown type */
    rec(&rb, 311u, 7u, 2u, 2u, fbits(1.0f), 0u, 100u);        /* FLOAT needs dlc 8 */
    rec(&rb, 311u, 8u, 2u, 3u, fbits(1.0f), 0u, 100u);
    rec(&rb, 311u, 8u, 2u, 3u, fbits(1.0f), 0u, 100u);        /* repeated code */
    rec(&rb, 311u, 8u, 2u, 4u, 0x7FC00000u, 0u, 100u);        /* NaN */
    rec(&rb, 311u, 8u, 2u, 5u, fbits(95.0f), 0u, 100u);       /* out of range */
    rec(&rb, 1036u, 8u, 31u, 0u, 0u, 0u, 100u);               /* DOUBLEL alone */
    rec(&rb, 312u, 8u, 3u, 0u, (uint32_t)-20, 0u, 100u);       /* LONG */
    rec(&rb, 321u, 6u, 6u, 0u, 0x00B40000u, 0u, 100u);        /* SHORT 180, dlc 6 */
    rec(&rb, 311u, 8u, 2u, 200u, fbits(1.0f), 0u, 100u);      /* counter jump */
    rec(&rb, 311u, 8u, 2u, 6u, fbits(1.0f), 1u, 50u);         /* back in time */
    put("canaero", "rejects", rb.b, rb.n);

    /* times at the end of the clock */
    setup(&rb, 1000u);
    rec(&rb, 311u, 8u, 2u, 0u, fbits(1.0f), 3u, 1000000u);
    rec(&rb, 303u, 8u, 2u, 0u, fbits(400.0f), 3u, 999000u);
    rec(&rb, 311u, 8u, 2u, 1u, fbits(2.0f), 3u, 0u);
    rec(&rb, 311u, 8u, 2u, 2u, fbits(3.0f), 1u, 65535u);
    put("canaero", "clock_end", rb.b, rb.n);

    /* every entry scaled: 1e308 overflows a float value to inf (NONFINITE
     * after scale), 0.01 keeps 150 deg of pitch in range */
    setup_scaled(&rb, 100u, 1e308);
    rec(&rb, 311u, 8u, 2u, 0u, fbits(10.0f), 0u, 100u);
    rec(&rb, 311u, 8u, 2u, 1u, fbits(0.0f), 0u, 100u);
    put("canaero", "scale_overflow", rb.b, rb.n);
    setup_scaled(&rb, 100u, 0.01);
    rec(&rb, 311u, 8u, 2u, 0u, fbits(150.0f), 0u, 100u);
    rec(&rb, 1036u, 8u, 30u, 0u, (uint32_t)(lat_bits >> 32), 0u, 250u);
    rec(&rb, 1036u, 8u, 31u, 1u, (uint32_t)lat_bits, 0u, 250u);
    put("canaero", "scale_small", rb.b, rb.n);

    setup(&rb, 0x8000u | 2000u); /* horizon out of range: init refuses */
    rec(&rb, 311u, 8u, 2u, 0u, fbits(1.0f), 0u, 100u);
    put("canaero", "bad_horizon", rb.b, rb.n);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s CORPUS_DIR (tests/fuzz/corpus)\n", argv[0]);
        return 2;
    }
    g_dir = argv[1];
    make_ftt();
    make_ftd();
    make_hgt();
    make_canaero();
    return 0;
}
