/* fuzz_scene.c - libFuzzer harness: the scene parser (src/core/scene.c over
 * libinih) on INI text held in memory, as `fixterrain --scene` hands it over.
 *
 * The input is the file's text: like ft_plat_file_read_text, inputs larger
 * than FT_SCENE_TEXT_MAX - 1 bytes or with a NUL byte are refused before
 * the parser, so they are skipped here. Each input starts from
 * ft_scene_defaults. Invariants for an accepted scene: it validates again,
 * every text field is terminated, and its CAN map is one the decoder
 * accepts (ft_canaero_init re-checks every entry). A rejected scene has a
 * message. */
#include <string.h>

#include "input/canaero.h"
#include "fuzz_util.h"
#include "core/scene.h"

static ft_scene g_scene;
static ft_canaero g_dec;
static char g_text[FT_SCENE_TEXT_MAX];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size >= sizeof g_text || (size > 0u && memchr(data, '\0', size) != NULL)) {
        return 0;
    }
    if (size > 0u) {
        memcpy(g_text, data, size);
    }
    g_text[size] = '\0';
    ft_scene_defaults(&g_scene);
    ft_error err;
    memset(&err, 0, sizeof err);
    ft_status st = ft_scene_parse(&g_scene, g_text, "fuzz.ini", &err);
    FUZZ_CHECK_TEXT(err.text);
    if (st != FT_OK) {
        FUZZ_CHECK(err.text[0] != '\0');
        return 0;
    }
    FUZZ_CHECK(ft_scene_validate(&g_scene, &err) == FT_OK);
    FUZZ_CHECK_TEXT(g_scene.name);
    FUZZ_CHECK_TEXT(g_scene.display_device);
    FUZZ_CHECK_TEXT(g_scene.display_connector);
    FUZZ_CHECK_TEXT(g_scene.display_mode);
    FUZZ_CHECK_TEXT(g_scene.dem_path);
    FUZZ_CHECK_TEXT(g_scene.can_iface);
    FUZZ_CHECK_TEXT(g_scene.can_backup_iface);
    FUZZ_CHECK_TEXT(g_scene.gpio_chip);
    FUZZ_CHECK(g_scene.can_map.count <= FT_CAN_MAP_MAX);
    FUZZ_CHECK(ft_canaero_init(&g_dec, &g_scene.can_map, &err) == FT_OK);
    return 0;
}
