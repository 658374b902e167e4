/* test_bintree_template.c - the shared tile template: counts, every vertex a
 * lattice point used at least once, triangles tile the unit triangle exactly
 * (areas sum to 1/2, all counter-clockwise, none degenerate), each leg cut
 * into 2^k equal segments, and every interior edge shared by exactly two
 * triangles (a conforming triangulation, no T-junctions inside a tile). */
#include <stdlib.h>
#include <string.h>

#include "lod/bintree_template.h"
#include "test_util.h"

int main(void)
{
    ft_error err;
    for (uint32_t k = FT_BT_TEMPLATE_K_MIN; k <= FT_BT_TEMPLATE_K_MAX; ++k) {
        uint32_t nv = ft_bt_template_vertices(k), nt = ft_bt_template_triangles(k);
        uint32_t s = 1u << k;
        float *uv = malloc(nv * 2u * sizeof(float));
        uint16_t *idx = malloc(nt * 3u * sizeof(uint16_t));
        int16_t *scratch = malloc(ft_bt_template_scratch(k) * sizeof(int16_t));
        uint32_t *use = calloc(nv, sizeof(uint32_t));
        /* edge use counts in a dense (nv x nv) table is too big for k=6; use a
         * sorted list of undirected edges instead */
        uint32_t *edges = malloc(nt * 3u * sizeof(uint32_t));
        REQUIRE(uv && idx && scratch && use && edges);
        REQUIRE(ft_bt_template_build(k, uv, idx, scratch, &err) == FT_OK);
        double area = 0.0;
        uint32_t legs_on_edge = 0;
        for (uint32_t t = 0; t < nt; ++t) {
            const float *p0 = uv + 2u * idx[3u * t], *p1 = uv + 2u * idx[3u * t + 1u],
                        *p2 = uv + 2u * idx[3u * t + 2u];
            double cross = ((double)p1[0] - p0[0]) * ((double)p2[1] - p0[1]) -
                           ((double)p1[1] - p0[1]) * ((double)p2[0] - p0[0]);
            CHECK(cross > 0.0); /* counter-clockwise, not degenerate */
            area += 0.5 * cross;
            for (uint32_t c = 0; c < 3u; ++c) {
                uint32_t a = idx[3u * t + c], b = idx[3u * t + (c + 1u) % 3u];
                use[a]++;
                edges[3u * t + c] = (a < b) ? a * 65536u + b : b * 65536u + a;
                /* an edge lying on the leg a = 0 */
                if (uv[2u * a] == 0.0f && uv[2u * b] == 0.0f) legs_on_edge++;
            }
        }
        CHECK_NEAR(area, 0.5, 1e-9);
        for (uint32_t v = 0; v < nv; ++v) {
            CHECK(use[v] > 0);
            float a = uv[2u * v] * (float)s, b = uv[2u * v + 1u] * (float)s;
            CHECK(a == (float)(int)a && b == (float)(int)b && a + b <= (float)s);
        }
        CHECK(legs_on_edge == s); /* the leg is cut into 2^k segments */
        /* every edge used once (boundary) or twice (interior) */
        for (uint32_t i = 1; i < nt * 3u; ++i) { /* insertion sort: small */
            uint32_t x = edges[i], j = i;
            while (j > 0 && edges[j - 1] > x) { edges[j] = edges[j - 1]; --j; }
            edges[j] = x;
        }
        uint32_t boundary = 0, bad = 0;
        for (uint32_t i = 0; i < nt * 3u;) {
            uint32_t j = i;
            while (j < nt * 3u && edges[j] == edges[i]) ++j;
            if (j - i == 1) boundary++;
            else if (j - i != 2) bad++;
            i = j;
        }
        CHECK(bad == 0);
        CHECK(boundary == 3u * s); /* three sides, 2^k segments each */
        printf("k=%u: %u vertices, %u triangles, %u boundary edges\n", k, nv, nt, boundary);
        free(uv); free(idx); free(scratch); free(use); free(edges);
    }
    CHECK(ft_bt_template_build(0, NULL, NULL, NULL, &err) == FT_ERR_CONFIG);
    CHECK(ft_bt_template_build(7, NULL, NULL, NULL, &err) == FT_ERR_CONFIG);
    return ft_test_result("test_bintree_template");
}
