/* test_util.h - minimal assertions for CTest executables. A failed CHECK
 * prints file:line and the expression, counts, and makes main return 1. */
#ifndef FT_TEST_UTIL_H
#define FT_TEST_UTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static int g_ft_test_failures;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
            ++g_ft_test_failures;                                                     \
        }                                                                             \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                              \
    do {                                                                                   \
        double ft_a_ = (double)(a), ft_b_ = (double)(b);                                   \
        if (!(fabs(ft_a_ - ft_b_) <= (double)(tol))) {                                     \
            fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.9g, %s = %.9g, tol %.3g\n", \
                    __FILE__, __LINE__, #a, ft_a_, #b, ft_b_, (double)(tol));              \
            ++g_ft_test_failures;                                                          \
        }                                                                                  \
    } while (0)

/* Fatal: stop this test now (the rest would only crash). */
#define REQUIRE(cond)                                                                   \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "%s:%d: REQUIRE failed: %s\n", __FILE__, __LINE__, #cond); \
            exit(1);                                                                    \
        }                                                                               \
    } while (0)

#define FT_TEST_SKIP 77

static inline int ft_test_result(const char *name)
{
    if (g_ft_test_failures != 0) {
        fprintf(stderr, "%s: %d check(s) failed\n", name, g_ft_test_failures);
        return 1;
    }
    printf("%s: all checks passed\n", name);
    return 0;
}

/* An SRTM3 tile (1201 x 1201 big-endian int16, row 0 = north) read as it
 * is, for tests that compare against the file itself. */
#define FT_TEST_SRTM3_SIDE 1201u
static inline void ft_test_read_srtm3(const char *path,
                                      int16_t out[FT_TEST_SRTM3_SIDE * FT_TEST_SRTM3_SIDE])
{
    FILE *f = fopen(path, "rb");
    REQUIRE(f != NULL);
    static uint8_t raw[FT_TEST_SRTM3_SIDE * FT_TEST_SRTM3_SIDE * 2u];
    REQUIRE(fread(raw, 1, sizeof raw, f) == sizeof raw);
    fclose(f);
    for (size_t i = 0; i < (size_t)FT_TEST_SRTM3_SIDE * FT_TEST_SRTM3_SIDE; ++i) {
        out[i] = (int16_t)(uint16_t)(((uint16_t)raw[2 * i] << 8) | raw[2 * i + 1]);
    }
}

#endif
