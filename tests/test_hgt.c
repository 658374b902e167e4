#define _POSIX_C_SOURCE 200809L
/* test_hgt.c - SRTM .hgt reader on in-memory images and the real tiles.
 *
 * In memory: a 5x5 tile with known values and voids checks the row flip
 * (file row 0 = north = grid row 4), big-endian decoding incl. negatives,
 * void fill and count, min/max, the SW corner from the name; bad sizes and
 * names and out-of-range heights are rejected with a clear message.
 * Real data (FT_SHARED_DATA_DIR): N42E001 (7652 voids, 349..3100 m) and
 * N52E008 (3 voids, not the 0 its README says), loaded through a small stdio-backed reader; the load
 * time is printed. Exits 77 if the data directory is missing. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "terrain/dem_hgt.h"
#include "test_util.h"
#include "terrain/void_fill.h"

static void be16(uint8_t *p, int v)
{
    uint16_t u = (uint16_t)(int16_t)v;
    p[0] = (uint8_t)(u >> 8);
    p[1] = (uint8_t)u;
}

/* Loads `img` as file `name`; t receives heights (malloc'd). */
static ft_status load_mem(const uint8_t *img, size_t bytes, const char *name, ft_terrain *t,
                          ft_error *err)
{
    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, img, bytes, name);
    memset(t, 0, sizeof *t);
    memset(err, 0, sizeof *err);
    ft_status st = ft_hgt_probe(&r, name, t, err);
    if (st != FT_OK) return st;
    t->heights_m = (float *)malloc((size_t)t->width * t->height * sizeof(float));
    size_t sb = ft_hgt_scratch_bytes(t->width, t->height);
    void *scratch = malloc(sb);
    REQUIRE(t->heights_m != NULL && scratch != NULL);
    CHECK(ft_hgt_load(&r, t, scratch, sb - 1u, err) == FT_ERR_BUDGET); /* too little scratch */
    st = ft_hgt_load(&r, t, scratch, sb, err);
    free(scratch);
    return st;
}

static void expect_probe_fail(const uint8_t *img, size_t bytes, const char *name, ft_status want,
                              const char *text)
{
    ft_reader r;
    ft_mem_reader m;
    ft_terrain t;
    ft_error err;
    memset(&t, 0, sizeof t);
    memset(&err, 0, sizeof err);
    ft_mem_reader_init(&r, &m, img, bytes, name);
    ft_status st = ft_hgt_probe(&r, name, &t, &err);
    int ok = st == want && strstr(err.text, text) != NULL;
    if (!ok) {
        fprintf(stderr, "probe %s (%zu bytes): got %s \"%s\", wanted %s with \"%s\"\n", name,
                bytes, ft_status_str(st), err.text, ft_status_str(want), text);
    } else {
        printf("  rejected %-22s %zu bytes: %s\n", name, bytes, err.text);
    }
    CHECK(ok);
}

/* ---- stdio-backed reader for the real files ---- */
static ft_status file_read(void *ctx, void *dst, size_t bytes, size_t *got)
{
    FILE *fp = (FILE *)ctx;
    *got = fread(dst, 1, bytes, fp);
    return ferror(fp) ? FT_ERR_IO : FT_OK;
}

static int open_reader(const char *path, ft_reader *r, FILE **fp_out)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL) return 0;
    if (fseek(fp, 0, SEEK_END) != 0) { fclose(fp); return 0; }
    long size = ftell(fp);
    if (size < 0 || fseek(fp, 0, SEEK_SET) != 0) { fclose(fp); return 0; }
    r->ctx = fp;
    r->read = file_read;
    r->size_bytes = (uint64_t)size;
    r->name = path;
    *fp_out = fp;
    return 1;
}

static double now_s(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int load_real(const char *file, uint32_t want_voids, float lo, float hi, int16_t *raw_min,
                     int16_t *raw_max)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", FT_SHARED_DATA_DIR, file);
    ft_reader r;
    FILE *fp = NULL;
    if (!open_reader(path, &r, &fp)) {
        return 0;
    }
    ft_terrain t;
    ft_error err;
    memset(&t, 0, sizeof t);
    memset(&err, 0, sizeof err);
    ft_status st = ft_hgt_probe(&r, path, &t, &err);
    if (st != FT_OK) fprintf(stderr, "%s\n", err.text);
    REQUIRE(st == FT_OK);
    CHECK(t.width == 1201u && t.height == 1201u);
    CHECK(t.unit == FT_UNIT_DEGREE);
    CHECK_NEAR(t.spacing_x, 1.0 / 1200.0, 1e-15);
    CHECK(strcmp(t.crs, "EPSG:4326") == 0);
    t.heights_m = (float *)malloc(1201u * 1201u * sizeof(float));
    t.void_bits = (uint8_t *)calloc(ft_terrain_void_bits_bytes(1201u, 1201u), 1);
    size_t sb = ft_hgt_scratch_bytes(1201u, 1201u);
    void *scratch = malloc(sb);
    REQUIRE(t.heights_m && t.void_bits && scratch);
    double t0 = now_s();
    st = ft_hgt_load(&r, &t, scratch, sb, &err);
    double t1 = now_s();
    if (st != FT_OK) fprintf(stderr, "%s\n", err.text);
    REQUIRE(st == FT_OK);
    printf("  %s: 1201x1201, %u voids, %.1f..%.1f m, load+fill %.1f ms\n", file, t.void_count,
           (double)t.min_height_m, (double)t.max_height_m, (t1 - t0) * 1e3);
    CHECK(t.void_count == want_voids);
    CHECK(t.min_height_m >= lo && t.max_height_m <= hi);
    /* raw extremes (valid samples only, read independently) must survive exactly */
    {
        rewind(fp);
        uint8_t b[2];
        int16_t mn = INT16_MAX, mx = INT16_MIN;
        uint32_t marked_wrong = 0u;
        for (size_t k = 0; k < 1201u * 1201u; ++k) {
            REQUIRE(fread(b, 1, 2, fp) == 2);
            int16_t v = (int16_t)(uint16_t)((b[0] << 8) | b[1]);
            /* file rows run north to south, grid rows south to north */
            const size_t gi = (1200u - k / 1201u) * 1201u + k % 1201u;
            marked_wrong += (uint32_t)(ft_terrain_sample_filled(&t, gi) != (v == -32768));
            if (v == -32768) continue;
            mn = v < mn ? v : mn;
            mx = v > mx ? v : mx;
        }
        *raw_min = mn;
        *raw_max = mx;
        CHECK(marked_wrong == 0u); /* exactly the voids are recorded as filled */
        CHECK(t.min_height_m == (float)mn && t.max_height_m == (float)mx);
        /* north-west corner of the file = grid (0, 1200) */
        rewind(fp);
        REQUIRE(fread(b, 1, 2, fp) == 2);
        int16_t nw = (int16_t)(uint16_t)((b[0] << 8) | b[1]);
        if (nw != -32768) CHECK(t.heights_m[1200u * 1201u] == (float)nw);
    }
    for (size_t k = 0; k < 1201u * 1201u; ++k) {
        if (!(t.heights_m[k] >= lo && t.heights_m[k] <= hi)) {
            CHECK(0 && "filled height outside the tile range");
            break;
        }
    }
    fclose(fp);
    free(scratch);
    free(t.void_bits);
    free(t.heights_m);
    return 1;
}

int main(void)
{
    /* ---- 5x5 in memory ---- file rows north first */
    static const int file_vals[5][5] = {
        {100, 110, 120, 130, 140},     /* north edge, file row 0 */
        {200, -32768, 220, 230, 240},
        {300, 310, -32768, -32768, 340},
        {-5, 410, 420, 430, 440},
        {500, 510, 520, 530, -32768}, /* south edge, file row 4 */
    };
    uint8_t img[50];
    for (int fr = 0; fr < 5; ++fr)
        for (int c = 0; c < 5; ++c) be16(img + 2 * (fr * 5 + c), file_vals[fr][c]);

    ft_terrain t;
    ft_error err;
    ft_status st = load_mem(img, sizeof img, "/some/dir/N46W122.hgt", &t, &err);
    if (st != FT_OK) fprintf(stderr, "%s\n", err.text);
    REQUIRE(st == FT_OK);
    CHECK(t.width == 5u && t.height == 5u);
    CHECK(t.origin_x == -122.0 && t.origin_y == 46.0);
    CHECK(t.spacing_x == 0.25 && t.spacing_y == 0.25);
    CHECK(t.unit == FT_UNIT_DEGREE);
    CHECK(t.void_count == 4u);
    /* flip: grid row iy = file row 4 - iy */
    int void_ok = 1;
    for (int iy = 0; iy < 5; ++iy) {
        for (int ix = 0; ix < 5; ++ix) {
            int v = file_vals[4 - iy][ix];
            if (v != -32768) CHECK(t.heights_m[iy * 5 + ix] == (float)v);
            else void_ok &= (t.heights_m[iy * 5 + ix] > 0.0f);
        }
    }
    CHECK(void_ok);
    CHECK(t.heights_m[1 * 5 + 0] == -5.0f); /* negative big-endian decode */
    /* void fill is the IDW8 rule: recompute with ft_void_fill on the flipped grid */
    {
        float g[25];
        uint8_t m[25];
        for (int iy = 0; iy < 5; ++iy)
            for (int ix = 0; ix < 5; ++ix) {
                int v = file_vals[4 - iy][ix];
                m[iy * 5 + ix] = (v == -32768);
                g[iy * 5 + ix] = (v == -32768) ? 0.0f : (float)v;
            }
        int av = 0;
        uint32_t fs[64];
        REQUIRE(ft_void_fill_scratch_bytes(5, 5) <= sizeof fs);
        CHECK(ft_void_fill(g, m, 5, 5, fs, sizeof fs, &av) == 4u);
        CHECK(memcmp(g, t.heights_m, sizeof g) == 0);
        /* south-east corner void (grid 4,0): W=530 (d1), N=440 (d1), NW=430 (d sqrt2) */
        double s2 = sqrt(2.0);
        double want = (530.0 + 440.0 + 430.0 / s2) / (2.0 + 1.0 / s2);
        CHECK_NEAR(t.heights_m[4], want, 1e-3);
    }
    CHECK(t.min_height_m == -5.0f);
    CHECK(t.max_height_m == 530.0f);
    free(t.heights_m);

    /* names: case, southern/eastern, directory prefixes */
    st = load_mem(img, sizeof img, "s12e034.HGT", &t, &err);
    CHECK(st == FT_OK && t.origin_y == -12.0 && t.origin_x == 34.0);
    free(t.heights_m);
    st = load_mem(img, sizeof img, "C:\\data\\S01W001.hgt", &t, &err);
    CHECK(st == FT_OK && t.origin_y == -1.0 && t.origin_x == -1.0);
    free(t.heights_m);

    /* bad names */
    expect_probe_fail(img, sizeof img, "dir/N46W122.tif", FT_ERR_FORMAT, "N46W122.hgt");
    expect_probe_fail(img, sizeof img, "N4W122.hgt", FT_ERR_FORMAT, "\"N4W122.hgt\"");
    expect_probe_fail(img, sizeof img, "X46W122.hgt", FT_ERR_FORMAT, "X46W122");
    expect_probe_fail(img, sizeof img, "N46Q122.hgt", FT_ERR_FORMAT, "N46Q122");
    expect_probe_fail(img, sizeof img, "N46W12a.hgt", FT_ERR_FORMAT, "N46W12a");
    expect_probe_fail(img, sizeof img, "N95E000.hgt", FT_ERR_FORMAT, "outside the globe");
    expect_probe_fail(img, sizeof img, "N10E180.hgt", FT_ERR_FORMAT, "outside the globe");
    expect_probe_fail(img, sizeof img, "N46W122.hgt.zip", FT_ERR_FORMAT, "N46W122.hgt");
    expect_probe_fail(img, sizeof img, "/a/b/", FT_ERR_FORMAT, "N46W122.hgt");
    /* pole tile: name fine, frame refuses the latitude */
    expect_probe_fail(img, sizeof img, "N89E000.hgt", FT_ERR_FORMAT, "pole");

    /* bad sizes */
    expect_probe_fail(img, 49, "N46W122.hgt", FT_ERR_FORMAT, "odd");
    expect_probe_fail(img, 48, "N46W122.hgt", FT_ERR_FORMAT, "not a square");
    expect_probe_fail(img, 2, "N46W122.hgt", FT_ERR_FORMAT, "smaller");
    expect_probe_fail(img, 0, "N46W122.hgt", FT_ERR_FORMAT, "smaller");
    {
        ft_reader r;
        ft_mem_reader m;
        ft_terrain tt;
        memset(&tt, 0, sizeof tt);
        ft_mem_reader_init(&r, &m, img, 10, "N46W122.hgt");
        r.size_bytes = 2ull * 16386ull * 16386ull; /* bigger than any allowed grid */
        CHECK(ft_hgt_probe(&r, "N46W122.hgt", &tt, &err) == FT_ERR_OVERSIZED);
    }

    /* out-of-range height: error names file row and col */
    {
        uint8_t bad[50];
        memcpy(bad, img, sizeof bad);
        be16(bad + 2 * (3 * 5 + 2), 9500);
        st = load_mem(bad, sizeof bad, "N46W122.hgt", &t, &err);
        CHECK(st == FT_ERR_FORMAT && strstr(err.text, "row 3 col 2") != NULL &&
              strstr(err.text, "9500") != NULL);
        printf("  rejected out-of-range: %s\n", err.text);
        free(t.heights_m);
        be16(bad + 2 * (3 * 5 + 2), -1001);
        st = load_mem(bad, sizeof bad, "N46W122.hgt", &t, &err);
        CHECK(st == FT_ERR_FORMAT && strstr(err.text, "-1001") != NULL);
        free(t.heights_m);
    }
    /* all-void tile */
    {
        uint8_t voids[8];
        for (int k = 0; k < 4; ++k) be16(voids + 2 * k, -32768);
        st = load_mem(voids, sizeof voids, "N46W122.hgt", &t, &err);
        CHECK(st == FT_ERR_FORMAT && strstr(err.text, "all 4 samples are void") != NULL);
        free(t.heights_m);
    }
    /* all 32767: outside -1000..9000 m, refused (the importer refuses the
     * same file through GDAL, tests/test_import.c) */
    {
        uint8_t high[8];
        for (int k = 0; k < 4; ++k) be16(high + 2 * k, 32767);
        st = load_mem(high, sizeof high, "N46W122.hgt", &t, &err);
        CHECK(st == FT_ERR_FORMAT && strstr(err.text, "32767") != NULL &&
              strstr(err.text, "-1000..9000") != NULL);
        free(t.heights_m);
    }
    /* 1201 x 1201 with one valid sample: the void fill is linear in the grid
     * (the ray walk it replaced took about 5 s here). */
    {
        enum { S = 1201 };
        uint8_t *one = malloc((size_t)S * S * 2u);
        REQUIRE(one != NULL);
        for (size_t k = 0; k < (size_t)S * S; ++k) be16(one + 2u * k, -32768);
        be16(one + 2u * ((size_t)600 * S + 17u), 812);
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        st = load_mem(one, (size_t)S * S * 2u, "N46W122.hgt", &t, &err);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double dt = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        printf("  1201x1201 with one valid sample loaded in %.3f s\n", dt);
        CHECK(st == FT_OK);
        CHECK(dt < 1.0);
        if (st == FT_OK) {
            CHECK(t.void_count == (uint32_t)(S * S - 1));
            CHECK(t.min_height_m == 812.0f && t.max_height_m == 812.0f);
        }
        free(t.heights_m);
        free(one);
    }
    /* stream shorter than its declared size */
    {
        ft_reader r;
        ft_mem_reader m;
        ft_terrain tt;
        memset(&tt, 0, sizeof tt);
        ft_mem_reader_init(&r, &m, img, sizeof img, "N46W122.hgt");
        REQUIRE(ft_hgt_probe(&r, "N46W122.hgt", &tt, &err) == FT_OK);
        m.size_bytes = 40; /* data ends early */
        float h[25];
        uint64_t scratch[64]; /* row + mask + void-fill line state, 8-byte aligned */
        tt.heights_m = h;
        CHECK(ft_hgt_load(&r, &tt, scratch, sizeof scratch, &err) == FT_ERR_TRUNCATED);
        CHECK(strstr(err.text, "N46W122.hgt") != NULL);
    }

    /* ---- real tiles ---- */
    int16_t mn = 0, mx = 0;
    if (!load_real("N42E001.hgt", 7652u, 349.0f, 3100.0f, &mn, &mx)) {
        printf("%s/N42E001.hgt missing: skipping the real-data part\n", FT_SHARED_DATA_DIR);
        int r = ft_test_result("test_hgt");
        return r != 0 ? r : FT_TEST_SKIP;
    }
    CHECK(mn == 349 && mx == 3100);
    /* The shared README says 0 voids for N52E008; the file has 3 (file rows
     * 767 and 825, cols 1161..1183), checked independently with a script. */
    if (load_real("N52E008.hgt", 3u, -1.0f, 357.0f, &mn, &mx)) {
        CHECK(mn == -1 && mx == 357);
    }
    return ft_test_result("test_hgt");
}
