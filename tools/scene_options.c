/* scene_options.c - the lean build's view of a scene (tools/profile.cmake).
 *
 * Reads the scene file as `fixterrain --scene` does (ft_plat_file_read_text:
 * the size limit, no NUL byte) and parses it with the runtime's own parser
 * (ft_scene_parse: every key, range and cross-field check), so the build
 * and the runtime can never disagree on a scene. Prints what the build
 * needs, one KEY=VALUE per line:
 *   method=brute|bintree|pgm|pgrid|clipmap   backend=egl-gles3|egl-gles2|osmesa
 *   display=none|x11|kms   inputs_replay=0|1   inputs_can=0|1   inputs_gpio=0|1
 *   png=0|1   metric=0|1   relative=0|1 (presentation.colouring)
 *   horizon=0|1   haze=0|1   ground_grid=0|1 (presentation.horizon, haze_km, grid_m)
 *   night_palette=0|1 (presentation.palette = night, or a gpio.night_line)
 * A scene the runtime refuses: the runtime's message on stderr
 * ("fixterrain: scene: ..."), exit status 1; a usage error: 2.
 * Compiled and run on the build host at configure time; never installed. */
#include <stdio.h>
#include <string.h>

#include "core/platform_api.h"
#include "core/scene.h"

static char g_text[FT_SCENE_TEXT_MAX];

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s SCENE.ini\n", argc > 0 ? argv[0] : "scene_options");
        return 2;
    }
    static ft_scene s;
    ft_error err;
    memset(&err, 0, sizeof err);
    size_t len = 0;
    ft_scene_defaults(&s);
    if (ft_plat_file_read_text(argv[1], g_text, sizeof g_text, &len, &err) != FT_OK ||
        ft_scene_parse(&s, g_text, argv[1], &err) != FT_OK) {
        fprintf(stderr, "fixterrain: scene: %s\n", err.text); /* as src/app/cli.c says it */
        return 1;
    }
    printf("method=%s\nbackend=%s\ndisplay=%s\n", ft_method_name(s.method),
           ft_backend_name(s.backend), ft_display_name(s.display));
    printf("inputs_replay=%d\ninputs_can=%d\ninputs_gpio=%d\n",
           (s.build_inputs & FT_BUILD_INPUT_REPLAY) != 0u, (s.build_inputs & FT_BUILD_INPUT_CAN) != 0u,
           (s.build_inputs & FT_BUILD_INPUT_GPIO) != 0u);
    printf("png=%d\nmetric=%d\nrelative=%d\n", s.build_png != 0, s.metric_enabled != 0,
           s.present_relative != 0);
    printf("horizon=%d\nhaze=%d\nground_grid=%d\nnight_palette=%d\n", s.present_horizon != 0,
           s.present_haze_km > 0.0, s.present_grid_m > 0.0,
           s.present_palette == FT_PALETTE_NIGHT || s.gpio_input_line[FT_GPIO_NIGHT] >= 0);
    return fflush(stdout) == 0 ? 0 : 1;
}
