/* test_terrain_file.c - .ftt round trip and rejection of corrupt files.
 *
 * Round trip: a synthetic terrain with built pyramids is written to memory,
 * probed and loaded into fresh storage; every header field, every height and
 * every pyramid texel must come back bit-identical. Then each corruption
 * case must fail with the right status AND a message naming the problem. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "core/io.h"
#include "terrain/pyramid.h"
#include "terrain/terrain_file.h"
#include "test_util.h"

#define W 37u
#define H 23u

static uint8_t *g_file;
static size_t g_file_bytes;

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void fix_header_crc(uint8_t *f)
{
    put32(f + 124, 0u);
    put32(f + 124, (uint32_t)crc32(0L, f, 256u));
}

static void fix_payload_crc(uint8_t *f, size_t bytes)
{
    put32(f + 120, (uint32_t)crc32(0L, f + 256, (uInt)(bytes - 256u)));
    fix_header_crc(f);
}

static void put64d(uint8_t *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    put32(p, (uint32_t)u);
    put32(p + 4, (uint32_t)(u >> 32));
}

static void put32f(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put32(p, u);
}

static float get32f(const uint8_t *p)
{
    uint32_t u = get32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* File offset of a pyramid array of `t` (pointers into its pyramid block,
 * which starts right after the heights in the payload). */
static size_t pyr_offset(const ft_terrain *t, const float *array)
{
    const float *block = t->pyr.avg[1].avg_m;
    return 256u + (size_t)W * H * 4u + (size_t)(array - block) * 4u;
}

static void make_terrain(ft_terrain *t)
{
    memset(t, 0, sizeof *t);
    t->width = W;
    t->height = H;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = 30.0;
    t->spacing_y = 25.0;
    t->origin_x = 500000.25;
    t->origin_y = 5100000.5;
    t->anchor_lat_deg = 46.5;
    t->anchor_lon_deg = 8.0;
    strcpy(t->crs, "EPSG:32632");
    t->void_count = 3;
    /* the three void-filled samples: the first row's 6th, one inside, the last */
    static const size_t k_filled[3] = {5u, W * 7u + 11u, W * H - 1u};
    t->void_bits = (uint8_t *)calloc(ft_terrain_void_bits_bytes(W, H), 1);
    REQUIRE(t->void_bits != NULL);
    for (int i = 0; i < 3; ++i) {
        t->void_bits[k_filled[i] >> 3] |= (uint8_t)(1u << (k_filled[i] & 7u));
    }
    t->heights_m = (float *)malloc(W * H * sizeof(float));
    REQUIRE(t->heights_m != NULL);
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x)
            t->heights_m[y * W + x] = 1000.0f + 300.0f * sinf((float)x * 0.37f) *
                                                    cosf((float)y * 0.21f) + 0.125f * (float)x;
    size_t pb = ft_pyramid_bytes(W, H);
    void *pyr = malloc(pb);
    REQUIRE(pyr != NULL);
    ft_error err;
    REQUIRE(ft_pyramid_layout(t, pyr, pb, &err) == FT_OK);
    ft_pyramid_build(t);
    REQUIRE(ft_terrain_derive_frame(t, &err) == FT_OK);
}

/* Probes and loads `bytes` of `data` (declared size `declared`) into fresh
 * storage; returns the first failing status and leaves the message in err. */
static ft_status load_bytes(const uint8_t *data, size_t bytes, uint64_t declared, ft_terrain *out,
                            ft_error *err, int *failed_in_probe)
{
    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, data, bytes, "test.ftt");
    r.size_bytes = declared;
    memset(out, 0, sizeof *out);
    memset(err, 0, sizeof *err);
    *failed_in_probe = 1;
    ft_tfile_header hdr;
    ft_status st = ft_tfile_probe(&r, out, &hdr, err);
    if (st != FT_OK) return st;
    *failed_in_probe = 0;
    out->heights_m = (float *)malloc((size_t)out->width * out->height * sizeof(float));
    out->void_bits = out->void_count > 0u
                         ? (uint8_t *)calloc(ft_terrain_void_bits_bytes(out->width, out->height), 1)
                         : NULL;
    size_t pb = ft_pyramid_bytes(out->width, out->height);
    void *pyr = malloc(pb);
    REQUIRE(out->heights_m != NULL && pyr != NULL);
    st = ft_pyramid_layout(out, pyr, pb, err);
    REQUIRE(st == FT_OK);
    st = ft_tfile_load_payload(&r, out, &hdr, err);
    /* one load per probe */
    if (st == FT_OK) {
        CHECK(!hdr.valid);
        CHECK(ft_tfile_load_payload(&r, out, &hdr, NULL) == FT_ERR_ARG);
    }
    return st;
}

static void free_terrain(ft_terrain *t)
{
    free(t->void_bits);
    t->void_bits = NULL;
    free(t->heights_m);
    if (t->pyr.avg_levels > 1u) free(t->pyr.avg[1].avg_m); /* start of the pyramid block */
    t->heights_m = NULL;
}

/* Runs one corruption case on a copy of the good file. */
static void expect_fail(const char *what, const uint8_t *data, size_t bytes, uint64_t declared,
                        ft_status want, int want_in_probe, const char *want_text)
{
    ft_terrain t;
    ft_error err;
    int in_probe = 0;
    ft_status st = load_bytes(data, bytes, declared, &t, &err, &in_probe);
    int ok = (st == want) && (in_probe == want_in_probe) && strstr(err.text, want_text) != NULL;
    if (!ok) {
        fprintf(stderr, "case '%s': got %s (%s) in %s: \"%s\"; wanted %s with \"%s\"\n", what,
                ft_status_str(st), st == FT_OK ? "-" : "fail", in_probe ? "probe" : "load",
                err.text, ft_status_str(want), want_text);
    } else {
        printf("  %-28s -> %s: %s\n", what, ft_status_str(st), err.text);
    }
    CHECK(ok);
    if (!in_probe) free_terrain(&t);
}

/* Writes `bytes` of `data` to FT_TEST_OUT_DIR/name, for the CLI check in
 * tests/ftt_cli_reject.cmake (fixterrain render must refuse these and never
 * print a non-finite number into --stats). */
static void save_case(const char *name, const uint8_t *data, size_t bytes)
{
    char path[512];
    (void)snprintf(path, sizeof path, "%s/%s", FT_TEST_OUT_DIR, name);
    FILE *fp = fopen(path, "wb");
    REQUIRE(fp != NULL);
    REQUIRE(fwrite(data, 1, bytes, fp) == bytes);
    REQUIRE(fclose(fp) == 0);
}

static uint8_t *copy_file(void)
{
    uint8_t *c = (uint8_t *)malloc(g_file_bytes + 16u);
    REQUIRE(c != NULL);
    memcpy(c, g_file, g_file_bytes);
    return c;
}

int main(void)
{
    ft_terrain src;
    ft_error err;
    make_terrain(&src);

    /* ---- write ---- */
    const size_t bits_bytes = ft_terrain_void_bits_bytes(W, H);
    size_t cap = 256u + W * H * 4u + ft_pyramid_bytes(W, H) + bits_bytes;
    g_file = (uint8_t *)malloc(cap + 64u);
    REQUIRE(g_file != NULL);
    {
        /* too small a sink: the writer's error comes back, named */
        ft_writer w;
        ft_mem_writer mw;
        ft_mem_writer_init(&w, &mw, g_file, cap - 1u, "small.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_ERR_OVERSIZED);
        CHECK(strstr(err.text, "small.ftt") != NULL);
        ft_mem_writer_init(&w, &mw, g_file, cap + 64u, "mem.ftt");
        REQUIRE(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_OK);
        CHECK(mw.pos == cap);
        g_file_bytes = mw.pos;
    }
    CHECK(memcmp(g_file, "FXTERR\r\n", 8) == 0);
    CHECK(get32(g_file + 8) == 2u);
    CHECK(get32(g_file + 16) == W && get32(g_file + 20) == H);

    save_case("ftt_good.ftt", g_file, g_file_bytes);

    /* ---- round trip ---- */
    {
        ft_terrain t;
        int in_probe = 0;
        ft_status st = load_bytes(g_file, g_file_bytes, g_file_bytes, &t, &err, &in_probe);
        if (st != FT_OK) fprintf(stderr, "round trip: %s\n", err.text);
        REQUIRE(st == FT_OK);
        CHECK(t.width == W && t.height == H && t.unit == FT_UNIT_METRE);
        CHECK(t.spacing_x == src.spacing_x && t.spacing_y == src.spacing_y);
        CHECK(t.origin_x == src.origin_x && t.origin_y == src.origin_y);
        CHECK(t.anchor_lat_deg == src.anchor_lat_deg && t.anchor_lon_deg == src.anchor_lon_deg);
        CHECK(strcmp(t.crs, "EPSG:32632") == 0);
        CHECK(t.void_count == 3u);
        CHECK(memcmp(t.void_bits, src.void_bits, bits_bytes) == 0);
        CHECK(t.min_height_m == src.min_height_m && t.max_height_m == src.max_height_m);
        CHECK(t.cell_x_m == src.cell_x_m && t.origin_world_y_m == src.origin_world_y_m);
        CHECK(memcmp(t.heights_m, src.heights_m, W * H * sizeof(float)) == 0);
        CHECK(t.pyr.avg_levels == src.pyr.avg_levels);
        CHECK(t.pyr.minmax_levels == src.pyr.minmax_levels);
        for (uint32_t l = 1; l < t.pyr.avg_levels; ++l)
            CHECK(memcmp(t.pyr.avg[l].avg_m, src.pyr.avg[l].avg_m,
                         (size_t)t.pyr.avg[l].width * t.pyr.avg[l].height * 4u) == 0);
        for (uint32_t l = 0; l < t.pyr.minmax_levels; ++l) {
            size_t n = (size_t)t.pyr.minmax[l].width * t.pyr.minmax[l].height * 4u;
            CHECK(memcmp(t.pyr.minmax[l].min_m, src.pyr.minmax[l].min_m, n) == 0);
            CHECK(memcmp(t.pyr.minmax[l].max_m, src.pyr.minmax[l].max_m, n) == 0);
        }
        /* A second load on the same reader without a new probe is refused. */
        {
            ft_reader r;
            ft_mem_reader m;
            ft_mem_reader_init(&r, &m, g_file, g_file_bytes, "again.ftt");
            ft_tfile_header never_probed;
            memset(&never_probed, 0, sizeof never_probed);
            CHECK(ft_tfile_load_payload(&r, &t, &never_probed, &err) == FT_ERR_ARG);
        }
        /* Writing the loaded terrain again gives the same bytes. */
        uint8_t *again = (uint8_t *)malloc(cap);
        ft_writer w;
        ft_mem_writer mw;
        ft_mem_writer_init(&w, &mw, again, cap, "again.ftt");
        CHECK(ft_tfile_write(&t, -32768.0f, &w, &err) == FT_OK);
        CHECK(mw.pos == g_file_bytes && memcmp(again, g_file, g_file_bytes) == 0);
        free(again);
        free_terrain(&t);
    }

    /* ---- rejections ---- */
    uint8_t *f;
    f = copy_file();
    f[0] = 'X';
    expect_fail("bad magic", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1, "bad magic");
    free(f);

    f = copy_file();
    put32(f + 8, 3u);
    expect_fail("wrong version", f, g_file_bytes, g_file_bytes, FT_ERR_VERSION, 1, "version 3");
    free(f);

    /* version 1 had no void bits: one that filled samples cannot say which */
    f = copy_file();
    put32(f + 8, 1u);
    fix_header_crc(f);
    expect_fail("v1 with voids", f, g_file_bytes, g_file_bytes, FT_ERR_VERSION, 1,
                "3 void-filled samples recorded but not which");
    free(f);

    /* the bits must agree with void_count, crc or not */
    f = copy_file();
    f[g_file_bytes - bits_bytes] ^= 0x01u; /* sample 0 marked too */
    fix_payload_crc(f, g_file_bytes);
    expect_fail("void bits count", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "4 samples marked void-filled, the header says 3");
    free(f);
    f = copy_file();
    f[g_file_bytes - 1u] |= 0x80u; /* past the last of 851 samples */
    fix_payload_crc(f, g_file_bytes);
    expect_fail("void bit past the grid", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "past the last sample");
    free(f);

    /* a writer asked to record voids it cannot place refuses */
    {
        ft_terrain nobits = src;
        nobits.void_bits = NULL;
        uint8_t *spare = (uint8_t *)malloc(cap + 64u);
        REQUIRE(spare != NULL);
        ft_writer w;
        ft_mem_writer mw;
        ft_mem_writer_init(&w, &mw, spare, cap + 64u, "nobits.ftt");
        CHECK(ft_tfile_write(&nobits, -32768.0f, &w, &err) == FT_ERR_ARG);
        CHECK(strstr(err.text, "no void bits") != NULL);
        free(spare);
    }

    f = copy_file();
    f[45] ^= 0x10; /* inside spacing_x */
    expect_fail("header crc bad", f, g_file_bytes, g_file_bytes, FT_ERR_CHECKSUM, 1,
                "header crc32");
    free(f);

    f = copy_file();
    f[256 + 1000] ^= 0x01;
    expect_fail("payload crc bad", f, g_file_bytes, g_file_bytes, FT_ERR_CHECKSUM, 0,
                "payload crc32");
    free(f);
    f = copy_file();
    f[g_file_bytes - 1] ^= 0x80; /* last byte: top max texel */
    expect_fail("payload crc bad (last byte)", f, g_file_bytes, g_file_bytes, FT_ERR_CHECKSUM, 0,
                "payload crc32");
    free(f);

    expect_fail("truncated by 1 byte", g_file, g_file_bytes - 1u, g_file_bytes - 1u,
                FT_ERR_TRUNCATED, 1, "need");
    /* A stream whose promised size is a lie still stops at the end of data. */
    expect_fail("stream 1 byte short", g_file, g_file_bytes - 1u, g_file_bytes, FT_ERR_TRUNCATED,
                0, "truncated");
    expect_fail("truncated inside header", g_file, 100u, 100u, FT_ERR_TRUNCATED, 1,
                "inside the header (100 of 256");
    expect_fail("empty file", g_file, 0u, 0u, FT_ERR_TRUNCATED, 1, "(0 of 256");

    f = copy_file();
    f[g_file_bytes] = 0;
    expect_fail("1 extra byte", f, g_file_bytes + 1u, g_file_bytes + 1u, FT_ERR_OVERSIZED, 1,
                "1 more than");
    expect_fail("stream 1 byte long", f, g_file_bytes + 1u, g_file_bytes, FT_ERR_OVERSIZED, 0,
                "past the declared payload");
    free(f);

    f = copy_file();
    put32(f + 16, 0u);
    fix_header_crc(f);
    expect_fail("width 0", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1, "grid 0x23");
    free(f);

    f = copy_file();
    put32(f + 16, FT_GRID_SIDE_MAX + 1u);
    fix_header_crc(f);
    expect_fail("width > max", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1, "grid 16386x23");
    free(f);

    f = copy_file();
    put32(f + 16, 0xFFFFFFFFu);
    put32(f + 20, 0xFFFFFFFFu);
    fix_header_crc(f);
    expect_fail("huge width*height", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "grid 4294967295x4294967295");
    free(f);

    f = copy_file();
    put32(f + 112, 0xFFFFFFFFu);
    put32(f + 116, 0xFFFFFFFFu);
    fix_header_crc(f);
    expect_fail("huge payload_bytes", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "payload_bytes 18446744073709551615");
    free(f);

    f = copy_file();
    {
        uint32_t nan_bits = 0x7fc00000u;
        put32(f + 256 + 4u * (2u * W + 5u), nan_bits); /* height row 2, col 5 */
        fix_payload_crc(f, g_file_bytes);
    }
    expect_fail("NaN height (crc fixed)", f, g_file_bytes, g_file_bytes, FT_ERR_NUMERIC, 0,
                "height at row 2 col 5 is not finite");
    free(f);

    f = copy_file();
    {
        uint32_t inf_bits = 0x7f800000u;
        put32(f + 256 + 4u * (W * H + 3u), inf_bits); /* avg level 1, texel 3 */
        fix_payload_crc(f, g_file_bytes);
    }
    expect_fail("Inf in avg pyramid", f, g_file_bytes, g_file_bytes, FT_ERR_NUMERIC, 0,
                "avg level 1");
    free(f);

    f = copy_file();
    put32(f + 28, get32(f + 28) + 1u);
    fix_header_crc(f);
    expect_fail("level count mismatch", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "level counts avg 8");
    free(f);

    f = copy_file();
    put32(f + 24, 7u);
    fix_header_crc(f);
    expect_fail("bad spacing unit", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "spacing_unit 7");
    free(f);

    f = copy_file();
    put32(f + 44, 0x7ff80000u); /* spacing_x high word -> NaN */
    fix_header_crc(f);
    expect_fail("NaN spacing", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1, "spacing");
    free(f);

    f = copy_file();
    memset(f + 128, 'A', 64);
    fix_header_crc(f);
    expect_fail("crs not terminated", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "crs text");
    free(f);

    f = copy_file();
    f[200] = 1;
    fix_header_crc(f);
    expect_fail("reserved byte set", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "reserved header byte 200");
    free(f);

    f = copy_file();
    put32(f + 12, 128u);
    fix_header_crc(f);
    expect_fail("header_bytes", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "header_bytes is 128");
    free(f);

    /* ---- content that a recomputed crc does not make true ---- */
    /* min/max pyramids zeroed: every level 0 node must equal its cell's
     * samples; the first node is named. */
    f = copy_file();
    for (uint32_t l = 0; l < src.pyr.minmax_levels; ++l) {
        size_t n = (size_t)src.pyr.minmax[l].width * src.pyr.minmax[l].height * 4u;
        memset(f + pyr_offset(&src, src.pyr.minmax[l].min_m), 0, n);
        memset(f + pyr_offset(&src, src.pyr.minmax[l].max_m), 0, n);
    }
    fix_payload_crc(f, g_file_bytes);
    expect_fail("min/max pyramids zeroed", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "min/max pyramid level 0 node (x 0, y 0)");
    save_case("ftt_minmax_zeroed.ftt", f, g_file_bytes);
    free(f);

    /* min and max swapped at every level: min > max at the first node */
    f = copy_file();
    for (uint32_t l = 0; l < src.pyr.minmax_levels; ++l) {
        size_t n = (size_t)src.pyr.minmax[l].width * src.pyr.minmax[l].height * 4u;
        memcpy(f + pyr_offset(&src, src.pyr.minmax[l].min_m), src.pyr.minmax[l].max_m, n);
        memcpy(f + pyr_offset(&src, src.pyr.minmax[l].max_m), src.pyr.minmax[l].min_m, n);
    }
    fix_payload_crc(f, g_file_bytes);
    expect_fail("min/max pyramids reversed", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "level 0 node (x 0, y 0): min");
    save_case("ftt_minmax_reversed.ftt", f, g_file_bytes);
    free(f);

    /* one node deep in the pyramid no longer bounds its children: named by
     * level, x and y */
    f = copy_file();
    {
        const ft_pyramid_level *lv = &src.pyr.minmax[2];
        REQUIRE(lv->width > 3u && lv->height > 1u);
        size_t at = pyr_offset(&src, lv->max_m) + 4u * (1u * lv->width + 3u);
        put32f(f + at, get32f(f + at) - 5.0f);
    }
    fix_payload_crc(f, g_file_bytes);
    expect_fail("max node below its children", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "min/max pyramid level 2 node (x 3, y 1)");
    free(f);

    /* the top node claims more than the cells hold (a looser bound is still
     * not the documented pyramid) */
    f = copy_file();
    {
        const ft_pyramid_level *lv = &src.pyr.minmax[src.pyr.minmax_levels - 1u];
        put32f(f + pyr_offset(&src, lv->max_m), 8000.0f);
    }
    fix_payload_crc(f, g_file_bytes);
    expect_fail("top max too high", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "children span");
    free(f);

    /* an avg node outside its children's range */
    f = copy_file();
    put32f(f + pyr_offset(&src, src.pyr.avg[1].avg_m) + 4u * 2u, -500.0f);
    fix_payload_crc(f, g_file_bytes);
    expect_fail("avg node off its children", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 0,
                "avg pyramid level 1 node (x 2, y 0)");
    free(f);

    /* heights: finite but outside the range every reader and the importer
     * share */
    f = copy_file();
    put32f(f + 256 + 4u * (4u * W + 6u), 3.0e38f);
    fix_payload_crc(f, g_file_bytes);
    expect_fail("height 3e38", f, g_file_bytes, g_file_bytes, FT_ERR_NUMERIC, 0,
                "height 3e+38 m at row 4 col 6 (row 0 = south) is outside -12000..9000 m");
    free(f);
    f = copy_file();
    put32f(f + 108, 3.0e38f); /* header max_height_m */
    fix_header_crc(f);
    expect_fail("header max 3e38", f, g_file_bytes, g_file_bytes, FT_ERR_NUMERIC, 1,
                "-12000..9000");
    free(f);

    /* spacing_x (offset 40) = 1e305 in a metre file: cell size out of range */
    f = copy_file();
    put64d(f + 40, 1e305);
    fix_header_crc(f);
    expect_fail("spacing_x 1e305", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "test.ftt: terrain cell_x_m 1e+305 m is outside 0.001..200000 m");
    save_case("ftt_spacing_1e305.ftt", f, g_file_bytes);
    free(f);
    f = copy_file();
    put64d(f + 48, 1e308);
    fix_header_crc(f);
    expect_fail("spacing_y 1e308", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "cell_y_m 1e+308 m is outside");
    save_case("ftt_spacing_1e308.ftt", f, g_file_bytes);
    free(f);
    /* cell size fine, but the grid reaches past the coordinate range */
    f = copy_file();
    put64d(f + 40, 1.0e5);
    put64d(f + 56, 9.99e7);
    fix_header_crc(f);
    expect_fail("east edge past 1e8 m", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "east edge x_m");
    free(f);
    f = copy_file();
    put64d(f + 48, 1.9e5); /* 22 * 190 km: extent 4.18e6 m is fine ... */
    put64d(f + 64, -1.5e8); /* ... origin_y is not */
    fix_header_crc(f);
    expect_fail("origin_y -1.5e8 m", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "origin_world_y_m -1.5e+08 m is outside -1e+08..1e+08 m");
    free(f);

    /* degree files: origin_x (offset 56) = 1e15 is range-checked before it
     * becomes the anchor */
    f = copy_file();
    put32(f + 24, 1u); /* unit degree */
    put64d(f + 40, 1.0 / 1200.0);
    put64d(f + 48, 1.0 / 1200.0);
    put64d(f + 56, 8.0);
    put64d(f + 64, 46.0);
    fix_header_crc(f);
    {
        /* first the plausible degree file loads, with a finite frame */
        ft_terrain t;
        int in_probe = 0;
        ft_status st = load_bytes(f, g_file_bytes, g_file_bytes, &t, &err, &in_probe);
        if (st != FT_OK) fprintf(stderr, "degree file: %s\n", err.text);
        CHECK(st == FT_OK);
        CHECK(t.anchor_lon_deg == 8.0 && t.anchor_lat_deg == 46.0);
        CHECK_NEAR(t.cell_y_m, 92.66, 0.01);
        if (!in_probe) free_terrain(&t);
    }
    put64d(f + 56, 1e15);
    fix_header_crc(f);
    expect_fail("degree origin_x 1e15", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "origin_x (longitude) 1e+15 deg is outside -360..360 deg");
    save_case("ftt_deg_origin_1e15.ftt", f, g_file_bytes);
    put64d(f + 56, 8.0);
    put64d(f + 64, 89.99);
    fix_header_crc(f);
    expect_fail("degree grid past the pole", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "northern edge");
    put64d(f + 64, 46.0);
    put64d(f + 40, 20.0); /* 36 * 20 deg of longitude */
    fix_header_crc(f);
    expect_fail("degree lon extent 720", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "longitude extent");
    free(f);

    /* crs with a non-ASCII byte (what a UTF-8 name would leave) */
    f = copy_file();
    memcpy(f + 128, "R\xc3\xa9seau", 8);
    fix_header_crc(f);
    expect_fail("crs non-ASCII", f, g_file_bytes, g_file_bytes, FT_ERR_FORMAT, 1,
                "crs has a non-printable byte 0xc3 at offset 1");
    free(f);

    /* Nothing non-finite reaches a caller (the --stats JSON prints these):
     * every f64 header field set to hostile values, crc fixed; whatever the
     * probe accepts has finite derived quantities inside the ranges. */
    {
        static const double hostile[] = {0.0, -0.0, 1e-320, 1e-9, 1e-3, 1.0, 89.5, 359.0,
                                         1e5, 2e5, 1e7, 9.9e7, 1e8, 1e15, 1e305, 1e308,
                                         -1e308, INFINITY, -INFINITY, NAN, -1.0, -1e5};
        const size_t nh = sizeof hostile / sizeof hostile[0];
        unsigned accepted = 0, tried = 0;
        for (uint32_t unit = 0; unit < 2u; ++unit) {
            for (int field = 0; field < 6; ++field) {
                for (size_t k = 0; k < nh; ++k) {
                    f = copy_file();
                    put32(f + 24, unit);
                    if (unit == 1u) {
                        put64d(f + 40, 1.0 / 1200.0);
                        put64d(f + 48, 1.0 / 1200.0);
                        put64d(f + 56, 8.0);
                        put64d(f + 64, 46.0);
                    }
                    put64d(f + 40 + 8 * field, hostile[k]);
                    fix_header_crc(f);
                    ft_reader r;
                    ft_mem_reader m;
                    ft_terrain t;
                    ft_tfile_header hdr;
                    ft_mem_reader_init(&r, &m, f, g_file_bytes, "hostile.ftt");
                    ++tried;
                    if (ft_tfile_probe(&r, &t, &hdr, &err) == FT_OK) {
                        ++accepted;
                        int fin = isfinite(t.cell_x_m) && isfinite(t.cell_y_m) &&
                                  isfinite(t.origin_world_x_m) && isfinite(t.origin_world_y_m) &&
                                  isfinite(t.anchor_lat_deg) && isfinite(t.anchor_lon_deg) &&
                                  isfinite(t.min_height_m) && isfinite(t.max_height_m);
                        double ex = t.origin_world_x_m + (double)(W - 1u) * t.cell_x_m;
                        double ny = t.origin_world_y_m + (double)(H - 1u) * t.cell_y_m;
                        int in_range = t.cell_x_m >= FT_CELL_MIN_M &&
                                       t.cell_x_m <= FT_CELL_MAX_M &&
                                       t.cell_y_m >= FT_CELL_MIN_M &&
                                       t.cell_y_m <= FT_CELL_MAX_M &&
                                       fabs(ex) <= FT_COORD_MAX_M && fabs(ny) <= FT_COORD_MAX_M;
                        if (!fin || !in_range) {
                            fprintf(stderr, "hostile unit %u field %d value %g accepted: cell %g x "
                                            "%g, origin %g %g\n",
                                    unit, field, hostile[k], t.cell_x_m, t.cell_y_m,
                                    t.origin_world_x_m, t.origin_world_y_m);
                        }
                        CHECK(fin && in_range);
                    } else {
                        CHECK(err.text[0] != '\0');
                    }
                    free(f);
                }
            }
        }
        printf("  hostile header values: %u tried, %u accepted, all finite and in range\n",
               tried, accepted);
        CHECK(accepted > 0u && accepted < tried);
    }

    /* ---- the writer refuses what the reader would refuse ---- */
    {
        ft_writer w;
        ft_mem_writer mw;
        uint8_t *out = (uint8_t *)malloc(cap);
        REQUIRE(out != NULL);
        float keep = src.heights_m[7];
        src.heights_m[7] = 3.0e38f;
        ft_mem_writer_init(&w, &mw, out, cap, "w.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_ERR_NUMERIC);
        CHECK(strstr(err.text, "w.ftt: height 3e+38 m at row 0 col 7") != NULL);
        CHECK(mw.pos == 0u);
        src.heights_m[7] = keep;
        /* heights changed after the pyramids were built */
        float keep11 = src.heights_m[W + 1u];
        src.heights_m[W + 1u] = 5000.0f;
        ft_mem_writer_init(&w, &mw, out, cap, "w.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_ERR_FORMAT);
        CHECK(strstr(err.text, "min/max pyramid level 0 node (x 0, y 0)") != NULL);
        src.heights_m[W + 1u] = keep11;
        char crs_keep[FT_CRS_TEXT_MAX];
        memcpy(crs_keep, src.crs, sizeof crs_keep);
        strcpy(src.crs, "R\xc3\xa9seau");
        ft_mem_writer_init(&w, &mw, out, cap, "w.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_ERR_FORMAT);
        CHECK(strstr(err.text, "non-printable byte 0xc3") != NULL);
        memcpy(src.crs, crs_keep, sizeof crs_keep);
        double sp = src.spacing_x;
        src.spacing_x = 1e305;
        ft_mem_writer_init(&w, &mw, out, cap, "w.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_ERR_FORMAT);
        CHECK(strstr(err.text, "w.ftt: terrain cell_x_m") != NULL);
        src.spacing_x = sp;
        ft_mem_writer_init(&w, &mw, out, cap, "w.ftt");
        CHECK(ft_tfile_write(&src, -32768.0f, &w, &err) == FT_OK);
        free(out);
    }
    /* crs sanitising (what the importer stores for a non-ASCII name) */
    {
        char out[FT_CRS_TEXT_MAX];
        CHECK(ft_terrain_sanitize_crs("R\xc3\xa9seau g\xc3\xa9od\xc3\xa9sique fran\xc3\xa7" "ais",
                                      out) == 4u);
        CHECK(strcmp(out, "R?seau g?od?sique fran?ais") == 0);
        CHECK(ft_terrain_check_crs(out, sizeof out, "x", &err) == FT_OK);
        CHECK(ft_terrain_sanitize_crs("EPSG:4326", out) == 0u && strcmp(out, "EPSG:4326") == 0);
        char longname[200];
        memset(longname, 'a', sizeof longname - 1u);
        longname[sizeof longname - 1u] = '\0';
        CHECK(ft_terrain_sanitize_crs(longname, out) == 0u && strlen(out) == FT_CRS_TEXT_MAX - 1u);
    }

    free(g_file);
    free_terrain(&src);
    return ft_test_result("test_terrain_file");
}
