/* test_util.h - minimal assertions for CTest executables. A failed CHECK
 * prints file:line and the expression, counts, and makes main return 1. */
#ifndef FT_TEST_UTIL_H
#define FT_TEST_UTIL_H

#include <math.h>
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

#endif
