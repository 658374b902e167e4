/* fuzz_ftt.c - libFuzzer harness: the .ftt terrain reader
 * (src/terrain/terrain_file.c: ft_tfile_probe, then ft_tfile_load_payload into
 * pyramids laid out by ft_pyramid_layout), over a memory reader.
 *
 * Built twice: as given (FUZZ_FTT_FIX_CRC 0: almost every mutation stops at
 * the header crc), and with FUZZ_FTT_FIX_CRC 1, which rewrites both crc
 * fields of the input to match its bytes before reading, so the checks
 * behind the crc (dimensions, levels, spacing, origin, heights, pyramids)
 * see the mutations. The probe ties the file size to the grid, so the
 * buffers allocated per input are never larger than the input. Invariants
 * of an accepted file: finite heights inside the range it reports, and one
 * load per probe. */
#include <math.h>
#include <string.h>
#include <zlib.h>

#include "fuzz_util.h"
#include "core/io.h"
#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "terrain/terrain_file.h"

#ifndef FUZZ_FTT_FIX_CRC
#define FUZZ_FTT_FIX_CRC 0
#endif

#define HDR FT_TFILE_HEADER_BYTES
#define OFF_PAYLOAD_CRC 120u
#define OFF_HEADER_CRC 124u

static void put_u32le(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *in = data;
    uint8_t *copy = NULL;
    if (FUZZ_FTT_FIX_CRC && size >= HDR) {
        copy = (uint8_t *)malloc(size);
        FUZZ_CHECK(copy != NULL);
        memcpy(copy, data, size);
        uLong pc = crc32(0L, Z_NULL, 0);
        pc = crc32(pc, copy + HDR, (uInt)(size - HDR));
        put_u32le(copy + OFF_PAYLOAD_CRC, (uint32_t)pc);
        put_u32le(copy + OFF_HEADER_CRC, 0u);
        uLong hc = crc32(crc32(0L, Z_NULL, 0), copy, HDR);
        put_u32le(copy + OFF_HEADER_CRC, (uint32_t)hc);
        in = copy;
    }
    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, in, size, "fuzz.ftt");
    ft_terrain t;
    ft_tfile_header hdr;
    ft_error err;
    memset(&t, 0, sizeof t);
    memset(&hdr, 0, sizeof hdr);
    memset(&err, 0, sizeof err);
    ft_status st = ft_tfile_probe(&r, &t, &hdr, &err);
    FUZZ_CHECK_TEXT(err.text);
    float *heights = NULL;
    void *pyr = NULL;
    uint8_t *bits = NULL;
    if (st == FT_OK) {
        FUZZ_CHECK(hdr.valid);
        /* every derived quantity of an accepted header is finite and in range */
        FUZZ_CHECK(isfinite(t.cell_x_m) && isfinite(t.cell_y_m) && t.cell_x_m > 0.0 &&
                   t.cell_y_m > 0.0);
        FUZZ_CHECK(isfinite(t.origin_world_x_m) && isfinite(t.origin_world_y_m));
        FUZZ_CHECK(isfinite(t.cell_x_m * (double)(t.width - 1u)) &&
                   isfinite(t.cell_y_m * (double)(t.height - 1u)));
        FUZZ_CHECK(isfinite(t.anchor_lat_deg) && isfinite(t.anchor_lon_deg));
        FUZZ_CHECK(t.width >= FT_GRID_SIDE_MIN && t.width <= FT_GRID_SIDE_MAX);
        FUZZ_CHECK(t.height >= FT_GRID_SIDE_MIN && t.height <= FT_GRID_SIDE_MAX);
        size_t hb = (size_t)t.width * t.height * sizeof(float);
        size_t pb = ft_pyramid_bytes(t.width, t.height);
        /* the probe matched the size to the grid (and the void bits) */
        FUZZ_CHECK(hb + pb + hdr.void_bits_bytes + HDR == size);
        FUZZ_CHECK((hdr.void_bits_bytes > 0u) == (t.void_count > 0u));
        heights = (float *)malloc(hb);
        pyr = malloc(pb);
        FUZZ_CHECK(heights != NULL && pyr != NULL);
        t.heights_m = heights;
        if (hdr.void_bits_bytes > 0u) {
            bits = (uint8_t *)malloc(hdr.void_bits_bytes);
            FUZZ_CHECK(bits != NULL);
            t.void_bits = bits;
        }
        FUZZ_CHECK(ft_pyramid_layout(&t, pyr, pb, &err) == FT_OK);
        st = ft_tfile_load_payload(&r, &t, &hdr, &err);
        FUZZ_CHECK_TEXT(err.text);
        FUZZ_CHECK(!hdr.valid); /* one load per probe */
        if (st == FT_OK) {
            size_t n = (size_t)t.width * t.height;
            FUZZ_CHECK(t.min_height_m <= t.max_height_m);
            for (size_t k = 0u; k < n; ++k) {
                FUZZ_CHECK(isfinite(heights[k]));
                FUZZ_CHECK(heights[k] >= t.min_height_m && heights[k] <= t.max_height_m);
            }
            /* exactly void_count samples are marked void-filled */
            uint64_t marked = 0u;
            for (size_t k = 0u; k < n; ++k) {
                marked += (uint64_t)ft_terrain_sample_filled(&t, k);
            }
            FUZZ_CHECK(marked == t.void_count);
            /* a second load without a probe is refused */
            FUZZ_CHECK(ft_tfile_load_payload(&r, &t, &hdr, &err) == FT_ERR_ARG);
        }
    }
    if (st != FT_OK) {
        FUZZ_CHECK(err.text[0] != '\0');
    }
    free(bits);
    free(pyr);
    free(heights);
    free(copy);
    return 0;
}
