/* test_clip_util.h - runs a clip cache's updates to the end into a CPU copy
 * of its level textures (levels x side^2 texels, row-major per level), as
 * the method's uploads would place them. */
#ifndef FT_TEST_CLIP_UTIL_H
#define FT_TEST_CLIP_UTIL_H

#include <string.h>

#include "terrain/clip_cache.h"
#include "test_app_util.h"

static inline void ft_test_clip_fill(ft_clip_cache *c, float *tex, uint8_t *mark)
{
    const size_t side = c->desc.side;
    ft_error err;
    for (int k = 0; k < 100000; ++k) {
        ft_clip_update u;
        int have = 0;
        REQUIRE(ft_clip_next_update(c, &u, &have, &err) == FT_OK);
        if (!have) {
            break;
        }
        for (uint32_t r = 0; r < u.h; ++r) {
            const size_t o = (size_t)u.level * side * side + (u.tex_y + r) * side + u.tex_x;
            memcpy(&tex[o], &u.heights_m[r * u.w], u.w * sizeof(float));
            memcpy(&mark[o], &u.marks[r * u.w], u.w);
        }
        ft_clip_commit(c, &u);
    }
}

#endif
