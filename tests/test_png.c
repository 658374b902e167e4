/* test_png.c - PNG output through libpng with arena-only allocation:
 * round trip, a too-small png pool fails with the named budget error, the
 * scratch is given back on every path, and the planned scratch
 * (ft_png_scratch_bytes) covers what libpng + zlib really take. */
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/platform_api.h"
#include "test_util.h"

static _Alignas(64) uint8_t g_memory[4u << 20];

static void make_arena(ft_arena *a, size_t png_budget)
{
    ft_error err;
    memset(a, 0, sizeof *a);
    a->pools[FT_POOL_PNG].budget_bytes = png_budget;
    REQUIRE(ft_arena_bind(a, g_memory, sizeof g_memory, &err) == FT_OK);
    ft_arena_lock(a); /* output happens after init: scratch only */
}

int main(void)
{
    ft_arena a;
    ft_error err;
    const uint32_t sizes[][2] = {{640, 480}, {1280, 1024}, {17, 3}};
    const char *path = FT_TEST_OUT_DIR "/png_roundtrip.png";
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        uint32_t w = sizes[k][0], h = sizes[k][1];
        size_t bytes = (size_t)w * h * 4u;
        uint8_t *img = malloc(bytes), *back = malloc(bytes);
        REQUIRE(img != NULL && back != NULL);
        for (size_t i = 0; i < bytes; ++i) {
            img[i] = (uint8_t)((i * 2654435761u) >> 13); /* noise: worst case for zlib */
        }
        make_arena(&a, 2u << 20);
        CHECK(ft_plat_png_write(path, img, w, h, &a, &err) == FT_OK);
        CHECK(ft_arena_mark(&a, FT_POOL_PNG) == 0);
        size_t used = a.pools[FT_POOL_PNG].high_water_bytes;
        printf("%ux%u: libpng + zlib took %zu bytes of scratch; planned %zu\n", w, h, used,
               ft_png_scratch_bytes(w));
        CHECK(used <= ft_png_scratch_bytes(w));
        uint32_t rw = 0, rh = 0;
        CHECK(ft_plat_png_read(path, back, bytes, &rw, &rh, &a, &err) == FT_OK);
        CHECK(rw == w && rh == h);
        CHECK(memcmp(img, back, bytes) == 0);
        CHECK(ft_arena_mark(&a, FT_POOL_PNG) == 0);
        /* A pool that is too small: named error, nothing left half-written. */
        make_arena(&a, 64u << 10);
        const char *small = FT_TEST_OUT_DIR "/png_small.png";
        (void)remove(small);
        CHECK(ft_plat_png_write(small, img, w, h, &a, &err) == FT_ERR_BUDGET);
        CHECK(strstr(err.text, "budget.png_bytes") != NULL);
        CHECK(ft_arena_mark(&a, FT_POOL_PNG) == 0);
        FILE *f = fopen(small, "rb");
        CHECK(f == NULL);
        if (f) fclose(f);
        free(img);
        free(back);
    }
    /* Reading something that is not a PNG is an error, not a crash. */
    make_arena(&a, 2u << 20);
    uint8_t buf[64];
    uint32_t w = 0, h = 0;
    CHECK(ft_plat_png_read(FT_SHARED_DATA_DIR "/README.md", buf, sizeof buf, &w, &h, &a, &err) !=
          FT_OK);
    CHECK(ft_plat_png_read(FT_TEST_OUT_DIR "/no-such.png", buf, sizeof buf, &w, &h, &a, &err) ==
          FT_ERR_IO);
    /* Too small a destination for a real image. */
    CHECK(ft_plat_png_read(path, buf, sizeof buf, &w, &h, &a, &err) == FT_ERR_OVERSIZED);
    CHECK(ft_arena_mark(&a, FT_POOL_PNG) == 0);
    return ft_test_result("test_png");
}
