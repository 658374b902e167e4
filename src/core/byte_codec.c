#include "core/byte_codec.h"

#include <zlib.h>

/* zlib's length is a uInt: feed it in chunks well below that */
#define FT_CRC_CHUNK_BYTES ((size_t)1u << 24)

uint32_t ft_crc32(uint32_t crc, const void *data, size_t bytes)
{
    const Bytef *p = (const Bytef *)data;
    uLong c = crc;
    /* bounded: every pass takes at least one byte */
    for (size_t left = bytes; left > 0u;) {
        const size_t n = left < FT_CRC_CHUNK_BYTES ? left : FT_CRC_CHUNK_BYTES;
        c = crc32(c, p, (uInt)n);
        p += n;
        left -= n;
    }
    return (uint32_t)c;
}
