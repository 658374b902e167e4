/* fuzz_hgt.c - libFuzzer harness: the SRTM .hgt reader (src/terrain/dem_hgt.c:
 * ft_hgt_probe, ft_hgt_load with its void fill) over a memory reader.
 *
 * The reader takes the SW corner from the file name: an input starting
 * with '@' carries its own name up to the first '\n' (at most 64 bytes;
 * the rest is the file), any other input is the file "N46E008.hgt".
 * Buffers are allocated per input from the probed side, which the probe
 * ties to the input size. Invariants of an accepted file: every height
 * (filled voids too) finite and inside the reader's valid range, the range
 * it reports spans them, no more voids than samples. */
#include <math.h>
#include <string.h>

#include "terrain/dem_hgt.h"
#include "fuzz_util.h"
#include "core/io.h"
#include "terrain/terrain.h"

#define NAME_MAX_BYTES 64u

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char name[NAME_MAX_BYTES + 1u] = "N46E008.hgt";
    if (size > 0u && data[0] == '@') {
        const uint8_t *nl = (const uint8_t *)memchr(data, '\n', size);
        size_t n = (nl != NULL) ? (size_t)(nl - data) - 1u : NAME_MAX_BYTES + 1u;
        if (n > NAME_MAX_BYTES || memchr(data + 1, '\0', n) != NULL) {
            return 0;
        }
        memcpy(name, data + 1, n);
        name[n] = '\0';
        size -= n + 2u;
        data += n + 2u;
    }
    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, data, size, name);
    ft_terrain t;
    ft_error err;
    memset(&t, 0, sizeof t);
    memset(&err, 0, sizeof err);
    ft_status st = ft_hgt_probe(&r, name, &t, &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st != FT_OK) {
        FUZZ_CHECK(err.text[0] != '\0');
        return 0;
    }
    FUZZ_CHECK(t.width == t.height && t.width >= FT_GRID_SIDE_MIN);
    FUZZ_CHECK((uint64_t)t.width * t.height * 2u == size);
    size_t n = (size_t)t.width * t.height;
    size_t sb = ft_hgt_scratch_bytes(t.width, t.height);
    FUZZ_CHECK(sb > 0u);
    float *heights = (float *)malloc(n * sizeof(float));
    void *scratch = malloc(sb);
    FUZZ_CHECK(heights != NULL && scratch != NULL);
    t.heights_m = heights;
    st = ft_hgt_load(&r, &t, scratch, sb, &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st == FT_OK) {
        FUZZ_CHECK(t.void_count <= n);
        FUZZ_CHECK(t.min_height_m <= t.max_height_m);
        for (size_t k = 0u; k < n; ++k) {
            FUZZ_CHECK(isfinite(heights[k]));
            FUZZ_CHECK(heights[k] >= -1000.0f && heights[k] <= 9000.0f);
            FUZZ_CHECK(heights[k] >= t.min_height_m && heights[k] <= t.max_height_m);
        }
    } else {
        FUZZ_CHECK(err.text[0] != '\0');
    }
    free(scratch);
    free(heights);
    return 0;
}
