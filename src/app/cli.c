/* cli.c - option tables and the scene loader (cli.h). */
#include "app/cli.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/platform_api.h"

/* Says "fixterrain[ COMMAND]: [WHAT: ]TEXT" on stderr and in err; returns rc.
 * Printed from the parts, so a long text is never cut on stderr (err holds
 * FT_ERROR_TEXT_MAX bytes of it). */
static int refuse(int rc, ft_error *err, ft_status st, const char *command, const char *what,
                  const char *text)
{
    const char *sp = command != NULL ? " " : "";
    const char *cmd = command != NULL ? command : "";
    const char *sep = what != NULL ? ": " : "";
    const char *w = what != NULL ? what : "";
    (void)fprintf(stderr, "fixterrain%s%s: %s%s%s\n", sp, cmd, w, sep, text);
    (void)ft_fail(err, st, "fixterrain%s%s: %s%s%s", sp, cmd, w, sep, text);
    return rc;
}

/* Decimal digits only: no sign (strtoul would wrap "-1" to a huge number and
 * take "-18446744073709551615" as 1), no leading space. */
static int parse_u32(const char *text, uint32_t lo, uint32_t hi, uint32_t *out)
{
    if (text[0] < '0' || text[0] > '9') {
        return 0;
    }
    char *end = NULL;
    errno = 0;
    const unsigned long v = strtoul(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || v < lo || v > hi) {
        return 0;
    }
    *out = (uint32_t)v;
    return 1;
}

static int parse_double(const char *text, double lo, double hi, double *out)
{
    char *end = NULL;
    const double v = strtod(text, &end);
    /* written so that NaN fails too */
    if (end == text || *end != '\0' || !(v >= lo && v <= hi)) {
        return 0;
    }
    *out = v;
    return 1;
}

static const ft_cli_opt *find_opt(const ft_cli_desc *d, const char *name)
{
    for (size_t r = 0; r < d->opt_count; ++r) {
        if (d->opts[r].name != NULL && strcmp(d->opts[r].name, name) == 0) {
            return &d->opts[r];
        }
    }
    return NULL;
}

/* One option with its value (NULL for a flag): FT_CLI_OK or FT_CLI_USAGE. */
static int take(const ft_cli_desc *d, const ft_cli_opt *o, const char *v, ft_error *err)
{
    ft_error why;
    memset(&why, 0, sizeof why);
    const char *unit_sp = o->unit != NULL ? " " : "";
    const char *unit = o->unit != NULL ? o->unit : "";
    switch (o->kind) {
    case FT_CLI_FLAG:
        *(int *)o->dst = 1;
        return FT_CLI_OK;
    case FT_CLI_STRING:
        *(const char **)o->dst = v;
        return FT_CLI_OK;
    case FT_CLI_U32:
        if (parse_u32(v, o->min_u32, o->max_u32, (uint32_t *)o->dst)) {
            return FT_CLI_OK;
        }
        (void)ft_fail(&why, FT_ERR_ARG, "%s wants %u..%u%s%s", o->name, (unsigned)o->min_u32,
                      (unsigned)o->max_u32, unit_sp, unit);
        break;
    case FT_CLI_DOUBLE:
        if (parse_double(v, o->min, o->max, (double *)o->dst)) {
            return FT_CLI_OK;
        }
        (void)ft_fail(&why, FT_ERR_ARG, "%s wants %g..%g%s%s", o->name, o->min, o->max, unit_sp,
                      unit);
        break;
    case FT_CLI_CUSTOM:
        if (o->parse != NULL && o->parse(v, o->dst, &why) == FT_OK) {
            return FT_CLI_OK;
        }
        if (o->parse == NULL) {
            (void)ft_fail(&why, FT_ERR_ARG, "%s: no parse function (a table fault)", o->name);
        }
        break;
    default:
        (void)ft_fail(&why, FT_ERR_ARG, "%s: unknown option kind %d (a table fault)", o->name,
                      (int)o->kind);
        break;
    }
    return refuse(FT_CLI_USAGE, err, FT_ERR_ARG, d->command, NULL, why.text);
}

int ft_cli_parse(const ft_cli_desc *d, int argc, char **argv, ft_error *err)
{
    ft_error why;
    memset(&why, 0, sizeof why);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            return FT_CLI_HELP;
        }
        const ft_cli_opt *o = find_opt(d, a);
        if (o == NULL) {
            (void)ft_fail(&why, FT_ERR_ARG, "unknown option %s (see --help)", a);
            return refuse(FT_CLI_USAGE, err, FT_ERR_ARG, d->command, NULL, why.text);
        }
        const char *v = NULL;
        if (o->kind != FT_CLI_FLAG) {
            if (i + 1 >= argc) {
                (void)ft_fail(&why, FT_ERR_ARG, "%s needs a value", a);
                return refuse(FT_CLI_USAGE, err, FT_ERR_ARG, d->command, NULL, why.text);
            }
            v = argv[++i];
        }
        const int rc = take(d, o, v, err);
        if (rc != FT_CLI_OK) {
            return rc;
        }
    }
    return FT_CLI_OK;
}

void ft_cli_print_help(const ft_cli_desc *d)
{
    for (size_t r = 0; r < d->opt_count; ++r) {
        if (d->opts[r].help != NULL) {
            printf("  %s\n", d->opts[r].help);
        }
    }
}

int ft_cli_parse_size(const char *text, uint32_t *width_px, uint32_t *height_px)
{
    char *end = NULL;
    const unsigned long w = strtoul(text, &end, 10);
    if (end == text || *end != 'x') {
        return 0;
    }
    const char *p = end + 1;
    const unsigned long h = strtoul(p, &end, 10);
    if (end == p || *end != '\0' || w < 16 || h < 16 || w > 8192 || h > 8192) {
        return 0;
    }
    *width_px = (uint32_t)w;
    *height_px = (uint32_t)h;
    return 1;
}

/* The scene text: the file, or the embedded default. */
static int load_text(const ft_cli_scene_desc *d, ft_scene *scene, ft_error *err)
{
    ft_error why;
    memset(&why, 0, sizeof why);
    if (d->scene_path == NULL) {
        if (ft_scene_parse(scene, ft_default_scene_text, "embedded default scene", &why) !=
            FT_OK) {
            return refuse(FT_CLI_ERROR, err, why.status, NULL, "embedded scene", why.text);
        }
        return FT_CLI_OK;
    }
    size_t len = 0;
    if (d->text == NULL ||
        ft_plat_file_read_text(d->scene_path, d->text, d->text_cap, &len, &why) != FT_OK ||
        ft_scene_parse(scene, d->text, d->scene_path, &why) != FT_OK) {
        if (d->text == NULL) {
            (void)ft_fail(&why, FT_ERR_ARG, "%s: no buffer for the scene text", d->scene_path);
        }
        return refuse(FT_CLI_ERROR, err, why.status, NULL, "scene", why.text);
    }
    /* A relative terrain.dem in a scene file is relative to that file, so a
     * scene works from any working directory. */
    const char *slash = strrchr(d->scene_path, '/');
    if (d->dem == NULL && scene->dem_path[0] != '\0' && scene->dem_path[0] != '/' &&
        slash != NULL) {
        char joined[sizeof scene->dem_path];
        const int n = snprintf(joined, sizeof joined, "%.*s/%s",
                               (int)(slash - d->scene_path), d->scene_path, scene->dem_path);
        if (n < 0 || (size_t)n >= sizeof joined) {
            return refuse(FT_CLI_ERROR, err, FT_ERR_CONFIG, NULL, "scene",
                          "terrain.dem path too long after joining");
        }
        memcpy(scene->dem_path, joined, (size_t)n + 1u);
    }
    return FT_CLI_OK;
}

int ft_cli_scene_load(const ft_cli_scene_desc *d, ft_scene *scene, ft_error *err)
{
    ft_error why;
    memset(&why, 0, sizeof why);
    ft_scene_defaults(scene);
    const int rc = load_text(d, scene, err);
    if (rc != FT_CLI_OK) {
        return rc;
    }
    if (d->dem != NULL) {
        if (strlen(d->dem) >= sizeof scene->dem_path) {
            return refuse(FT_CLI_USAGE, err, FT_ERR_ARG, d->command, NULL,
                          "--dem path too long");
        }
        (void)snprintf(scene->dem_path, sizeof scene->dem_path, "%s", d->dem);
    }
    if (d->method != NULL && !ft_method_from_name(d->method, &scene->method)) {
        (void)ft_fail(&why, FT_ERR_ARG, "unknown method '%s'", d->method);
    } else if (d->backend != NULL && !ft_backend_from_name(d->backend, &scene->backend)) {
        (void)ft_fail(&why, FT_ERR_ARG, "unknown backend '%s' (egl-gles3, egl-gles2, osmesa)",
                      d->backend);
    } else if (d->display != NULL &&
               !ft_display_parse(d->display, &scene->display, scene->display_device,
                                 sizeof scene->display_device)) {
        (void)ft_fail(&why, FT_ERR_ARG, "unknown display '%s' (none, x11, kms, "
                                        "kms:/dev/dri/cardN)", d->display);
    } else if (d->size != NULL &&
               !ft_cli_parse_size(d->size, &scene->width_px, &scene->height_px)) {
        (void)ft_fail(&why, FT_ERR_ARG, "--size wants WxH, each 16..8192");
    } else if (d->pose != NULL && ft_pose_parse(d->pose, &scene->pose, &why) != FT_OK) {
        /* why: ft_pose_parse's own sentence, which names --pose */
    } else {
        return FT_CLI_OK;
    }
    return refuse(FT_CLI_USAGE, err, FT_ERR_ARG, d->command, NULL, why.text);
}
