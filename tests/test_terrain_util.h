/* test_terrain_util.h - terrains made in memory for tests: a height
 * function sampled on a grid in metres (local CRS), its pyramids built, and
 * written as a .ftt file the app loads like any imported DEM. Test code
 * (malloc is fine here; the renderer's own memory comes from its arena). */
#ifndef FT_TEST_TERRAIN_UTIL_H
#define FT_TEST_TERRAIN_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "terrain/pyramid.h"
#include "terrain/terrain.h"
#include "terrain/terrain_file.h"
#include "test_util.h"

typedef double (*height_fn)(double x_m, double y_m, uint32_t ix, uint32_t iy);

static void *g_pyr_storage;

static inline void terrain_make(ft_terrain *t, uint32_t w, uint32_t h, double dx_m,
                                double dy_m, double x0, double y0, height_fn fn)
{
    memset(t, 0, sizeof *t);
    t->width = w;
    t->height = h;
    t->unit = FT_UNIT_METRE;
    t->spacing_x = dx_m;
    t->spacing_y = dy_m;
    t->origin_x = x0;
    t->origin_y = y0;
    t->anchor_lat_deg = 45.0;
    t->anchor_lon_deg = 9.0;
    (void)snprintf(t->crs, sizeof t->crs, "local-test");
    REQUIRE(ft_terrain_derive_frame(t, NULL) == FT_OK);
    t->heights_m = malloc((size_t)w * h * sizeof(float));
    size_t pb = ft_pyramid_bytes(w, h);
    g_pyr_storage = aligned_alloc(64, (pb + 63u) & ~(size_t)63u);
    REQUIRE(t->heights_m != NULL && g_pyr_storage != NULL);
    REQUIRE(ft_pyramid_layout(t, g_pyr_storage, pb, NULL) == FT_OK);
    for (uint32_t iy = 0; iy < h; ++iy) {
        for (uint32_t ix = 0; ix < w; ++ix) {
            t->heights_m[(size_t)iy * w + ix] =
                (float)fn(x0 + ix * dx_m, y0 + iy * dy_m, ix, iy);
        }
    }
    ft_pyramid_build(t);
}

static inline void terrain_free(ft_terrain *t)
{
    free(t->heights_m);
    free(g_pyr_storage);
    g_pyr_storage = NULL;
    t->heights_m = NULL;
}

static inline ft_status terrain_stdio_write(void *ctx, const void *src, size_t bytes)
{
    return fwrite(src, 1, bytes, (FILE *)ctx) == bytes ? FT_OK : FT_ERR_IO;
}

/* Writes t to path as a .ftt terrain file (no-data value -32768). */
static inline void terrain_write_ftt(const ft_terrain *t, const char *path)
{
    ft_error err;
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    ft_writer w = {f, terrain_stdio_write, path};
    ft_status st = ft_tfile_write(t, -32768.0f, &w, &err);
    if (st != FT_OK) fprintf(stderr, "write %s: %s\n", path, err.text);
    REQUIRE(st == FT_OK);
    REQUIRE(fclose(f) == 0);
}

#endif
