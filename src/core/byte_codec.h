/* byte_codec.h - the project's file formats are little-endian and written
 * field by field (no struct is ever written whole, so padding and host byte
 * order never reach a file); these put and get one field, and ft_crc32 is
 * zlib's crc32 over any length (zlib takes at most 4 GiB a call). */
#ifndef FT_BYTE_CODEC_H
#define FT_BYTE_CODEC_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

static inline void ft_le_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static inline void ft_le_put_u64(uint8_t *p, uint64_t v)
{
    ft_le_put_u32(p, (uint32_t)v);
    ft_le_put_u32(p + 4, (uint32_t)(v >> 32));
}

static inline void ft_le_put_f32(uint8_t *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    ft_le_put_u32(p, u);
}

static inline void ft_le_put_f64(uint8_t *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    ft_le_put_u64(p, u);
}

static inline uint32_t ft_le_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

static inline uint64_t ft_le_get_u64(const uint8_t *p)
{
    return (uint64_t)ft_le_get_u32(p) | ((uint64_t)ft_le_get_u32(p + 4) << 32);
}

static inline float ft_le_get_f32(const uint8_t *p)
{
    const uint32_t u = ft_le_get_u32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static inline double ft_le_get_f64(const uint8_t *p)
{
    const uint64_t u = ft_le_get_u64(p);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* zlib crc32 of `bytes` bytes continuing from crc (0 to start). */
uint32_t ft_crc32(uint32_t crc, const void *data, size_t bytes);

#endif
