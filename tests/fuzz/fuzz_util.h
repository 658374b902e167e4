/* fuzz_util.h - shared by the libFuzzer harnesses in tests/fuzz/.
 *
 * Each harness defines LLVMFuzzerTestOneInput. It is linked either with
 * libFuzzer (-fsanitize=fuzzer, FIXTERRAIN_FUZZ=ON) or with fuzz_driver.c, a
 * plain main() that runs it over the files of the corpus and regression
 * directories (every normal test run). A failed FUZZ_CHECK aborts, which
 * libFuzzer reports as a crash and the driver as a failed test. */
#ifndef FT_FUZZ_UTIL_H
#define FT_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_CHECK(cond)                                                              \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", __FILE__, __LINE__, \
                    #cond);                                                           \
            abort();                                                                  \
        }                                                                             \
    } while (0)

/* An ft_error's text is a NUL-terminated string within its array. */
#define FUZZ_CHECK_TEXT(arr) FUZZ_CHECK(memchr((arr), '\0', sizeof(arr)) != NULL)

static inline uint16_t fuzz_u16(const uint8_t *p)
{
    return (uint16_t)((unsigned)p[0] | ((unsigned)p[1] << 8));
}

static inline uint32_t fuzz_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

#endif
