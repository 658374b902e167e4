/* test_render.c - a real context renders a real frame.
 *
 * usage: test_render BACKEND HEIGHT_FORMAT OUT.rgba [EXPECT_VERSION_PREFIX]
 * Renders a small synthetic scene with the brute method, checks the context
 * reports the expected API, the frame has both sky and terrain in plausible
 * proportions and sky where the camera looks above the horizon, and writes
 * the raw RGBA for test_render_compare. */
#include <stdio.h>
#include <string.h>

#include "app/app.h"
#include "gpu/shade.h"
#include "test_util.h"

static const char k_scene[] =
    "[scene]\nname = render-test\nmethod = brute\n"
    "[view]\nwidth_px = 320\nheight_px = 240\nfovy_deg = 60\n"
    "[pose]\nlat_deg = 46.5035\nlon_deg = 8.0501\nalt_m = 2600\n"
    "heading_deg = 30\npitch_deg = -12\nroll_deg = 0\n"
    "[terrain]\ndem =\nsynth_side = 257\nsynth_spacing_m = 30\nsynth_relief_m = 2000\n"
    "synth_seed = 7\nsynth_octaves = 8\nsynth_anchor_lat_deg = 46.5\nsynth_anchor_lon_deg = 8.0\n"
    "[gpu]\ntexture_bytes = 8M\n"
    "[brute]\npatch_cells = 64\nmax_vertices = 100000\n"
    "[budget]\nheights_bytes = 512K\npyramids_bytes = 2M\nframe_rgba_bytes = 512K\n"
    "gpu_staging_bytes = 512K\nmethod_bytes = 128K\npng_bytes = 512K\n";

static ft_app g_app;

int main(int argc, char **argv)
{
    ft_scene s;
    ft_error err;
    REQUIRE(argc >= 4);
    ft_scene_defaults(&s);
    REQUIRE(ft_scene_parse(&s, k_scene, "k_scene", &err) == FT_OK);
    REQUIRE(ft_backend_from_name(argv[1], &s.backend));
    if (strcmp(argv[2], "packed") == 0) {
        s.height_format = FT_HEIGHT_FORMAT_PACKED;
    } else if (strcmp(argv[2], "float") == 0) {
        s.height_format = FT_HEIGHT_FORMAT_FLOAT;
    }
    ft_status st = ft_app_init(&g_app, &s, &err);
    if (st != FT_OK) {
        fprintf(stderr, "init: %s\n", err.text);
    }
    REQUIRE(st == FT_OK);
    printf("%s: GL_VERSION '%s', GL_RENDERER '%s', heights as %s\n", argv[1], g_app.gpu.version,
           g_app.gpu.renderer,
           g_app.renderer.gt.format == FT_HEIGHT_FORMAT_PACKED ? "packed RGBA8" : "float");
    if (argc >= 5) {
        CHECK(strncmp(g_app.gpu.version, argv[4], strlen(argv[4])) == 0);
    }
    if (strcmp(argv[2], "packed") == 0) {
        CHECK(g_app.renderer.gt.format == FT_HEIGHT_FORMAT_PACKED);
    } else {
        CHECK(g_app.renderer.gt.format == FT_HEIGHT_FORMAT_FLOAT);
    }

    ft_camera cam;
    ft_frame_stats fs;
    REQUIRE(ft_app_render(&g_app, &s.pose, &cam, &fs, &err) == FT_OK);
    CHECK(fs.triangles == 2ull * 256u * 256u);
    CHECK(fs.draw_calls == 16u);

    const uint8_t *px = g_app.renderer.rgba;
    const uint8_t sky[3] = {(uint8_t)(FT_SKY_R * 255.0f + 0.5f), (uint8_t)(FT_SKY_G * 255.0f + 0.5f),
                            (uint8_t)(FT_SKY_B * 255.0f + 0.5f)};
    uint32_t n_sky = 0, n_other = 0, n_sky_top = 0;
    for (uint32_t y = 0; y < s.height_px; ++y) {
        for (uint32_t x = 0; x < s.width_px; ++x) {
            const uint8_t *p = px + ((size_t)y * s.width_px + x) * 4u;
            int is_sky = abs(p[0] - sky[0]) <= 1 && abs(p[1] - sky[1]) <= 1 &&
                         abs(p[2] - sky[2]) <= 1;
            n_sky += (uint32_t)is_sky;
            n_other += (uint32_t)!is_sky;
            if (y == 0) {
                n_sky_top += (uint32_t)is_sky;
            }
            CHECK(p[3] == 255);
        }
    }
    double terrain_share = (double)n_other / (double)(n_sky + n_other);
    printf("terrain covers %.1f%% of the frame\n", 100.0 * terrain_share);
    /* Looking 12 deg down from 2600 m over 7.7 km of terrain with peaks to
     * 2000 m: the bottom is terrain, the top row is sky. */
    CHECK(terrain_share > 0.3 && terrain_share < 0.95);
    CHECK(n_sky_top == s.width_px);
    const uint8_t *bottom = px + ((size_t)(s.height_px - 1u) * s.width_px + s.width_px / 2u) * 4u;
    CHECK(!(bottom[0] == sky[0] && bottom[1] == sky[1] && bottom[2] == sky[2]));

    FILE *f = fopen(argv[3], "wb");
    REQUIRE(f != NULL);
    size_t bytes = (size_t)s.width_px * s.height_px * 4u;
    CHECK(fwrite(px, 1, bytes, f) == bytes);
    CHECK(fclose(f) == 0);
    ft_app_shutdown(&g_app);
    return ft_test_result(argv[1]);
}
