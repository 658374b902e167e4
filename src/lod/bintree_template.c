#include "lod/bintree_template.h"

uint32_t ft_bt_template_vertices(uint32_t k)
{
    uint32_t s = 1u << k;
    return (s + 1u) * (s + 2u) / 2u;
}

uint32_t ft_bt_template_triangles(uint32_t k)
{
    return 1u << (2u * k);
}

uint32_t ft_bt_template_scratch(uint32_t k)
{
    return 6u * ft_bt_template_triangles(k);
}

/* Vertex (i, j), i + j <= s, numbered row by row (j), i along the row. */
static uint16_t vertex_index(int32_t i, int32_t j, int32_t s)
{
    return (uint16_t)(j * (s + 1) - (j * (j - 1)) / 2 + i);
}

void ft_bt_template_corners(uint32_t k, int16_t *scratch)
{
    const int32_t s = (int32_t)1 << k; /* leg length in template units */
    /* Triangles as 3 integer points (apex, left, right) in units of 2^-k. */
    int16_t *tri = scratch;
    uint32_t count = 1u;
    tri[0] = 0; tri[1] = 0;                    /* apex */
    tri[2] = (int16_t)s; tri[3] = 0;           /* left */
    tri[4] = 0; tri[5] = (int16_t)s;           /* right */
    for (uint32_t level = 0; level < 2u * k; ++level) {
        /* Back to front so each parent is read before its slots are reused. */
        for (uint32_t t = count; t-- > 0u;) {
            const int16_t *p = tri + 6u * t;
            int16_t ax = p[0], ay = p[1], lx = p[2], ly = p[3], rx = p[4], ry = p[5];
            int16_t mx = (int16_t)((lx + rx) / 2), my = (int16_t)((ly + ry) / 2);
            int16_t *c0 = tri + 6u * (2u * t);
            int16_t *c1 = tri + 6u * (2u * t + 1u);
            /* child 0 = (m, apex, left), child 1 = (m, right, apex) */
            c0[0] = mx; c0[1] = my; c0[2] = ax; c0[3] = ay; c0[4] = lx; c0[5] = ly;
            c1[0] = mx; c1[1] = my; c1[2] = rx; c1[3] = ry; c1[4] = ax; c1[5] = ay;
        }
        count *= 2u;
    }
}

ft_status ft_bt_template_build(uint32_t k, float *uv, uint16_t *idx, int16_t *scratch,
                               ft_error *err)
{
    if (k < FT_BT_TEMPLATE_K_MIN || k > FT_BT_TEMPLATE_K_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "bintree template k = %u outside %u..%u", k,
                       FT_BT_TEMPLATE_K_MIN, FT_BT_TEMPLATE_K_MAX);
    }
    const int32_t s = (int32_t)1 << k;
    const int16_t *tri = scratch;
    const uint32_t count = ft_bt_template_triangles(k);
    ft_bt_template_corners(k, scratch);
    for (int32_t j = 0; j <= s; ++j) {
        for (int32_t i = 0; i + j <= s; ++i) {
            uint16_t v = vertex_index(i, j, s);
            uv[2u * v] = (float)i / (float)s;
            uv[2u * v + 1u] = (float)j / (float)s;
        }
    }
    for (uint32_t t = 0; t < count; ++t) {
        for (uint32_t c = 0; c < 3u; ++c) {
            idx[3u * t + c] = vertex_index(tri[6u * t + 2u * c], tri[6u * t + 2u * c + 1u], s);
        }
    }
    return FT_OK;
}
