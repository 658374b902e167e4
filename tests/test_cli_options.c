/* test_cli_options.c - the option table parser and the scene loader
 * (src/app/cli.h): what each kind of row takes, what it refuses and the
 * sentence it says, --help, and the overrides over the embedded scene. The
 * refusals also print to stderr: that output is expected. */
#include <string.h>

#include "app/cli.h"
#include "test_util.h"

#define ARGS_MAX 8

typedef struct opts {
    int quiet;
    const char *out;
    uint32_t frames;
    double clearance_m;
    const char *pick;
} opts;

static ft_status take_pick(const char *value, void *dst, ft_error *err)
{
    if (strcmp(value, "a") != 0 && strcmp(value, "b") != 0) {
        return ft_fail(err, FT_ERR_ARG, "--pick wants a or b");
    }
    *(const char **)dst = value;
    return FT_OK;
}

/* Parses "test" followed by the given arguments (NULL-terminated) into o,
 * which starts from the defaults; the message, if any, in err. */
static int parse(opts *o, ft_error *err, const char *a0, const char *a1, const char *a2,
                 const char *a3)
{
    memset(o, 0, sizeof *o);
    o->out = "default.png";
    o->frames = 1;
    memset(err, 0, sizeof *err);
    const ft_cli_opt table[] = {
        FT_CLI_OPT_FLAG("--quiet", &o->quiet, "--quiet   only errors"),
        FT_CLI_OPT_STRING("--out", &o->out, "--out F   output"),
        FT_CLI_OPT_U32("--frames", &o->frames, 1u, 100u, NULL),
        FT_CLI_OPT_DOUBLE("--clearance", &o->clearance_m, 0.0, 10000.0, "m", NULL),
        FT_CLI_OPT_CUSTOM("--pick", take_pick, &o->pick, NULL),
    };
    const ft_cli_desc desc = {"test", table, sizeof table / sizeof table[0]};
    const char *given[4] = {a0, a1, a2, a3};
    char *argv[ARGS_MAX];
    int argc = 0;
    argv[argc++] = (char *)"test";
    for (int i = 0; i < 4 && given[i] != NULL; ++i) {
        argv[argc++] = (char *)given[i];
    }
    return ft_cli_parse(&desc, argc, argv, err);
}

static void check_parser(void)
{
    opts o;
    ft_error err;

    /* nothing given: the defaults stay */
    CHECK(parse(&o, &err, NULL, NULL, NULL, NULL) == FT_CLI_OK);
    CHECK(o.quiet == 0 && strcmp(o.out, "default.png") == 0 && o.frames == 1u);

    /* a flag, a string, a u32 in range, a double, a custom value */
    CHECK(parse(&o, &err, "--quiet", NULL, NULL, NULL) == FT_CLI_OK);
    CHECK(o.quiet == 1);
    CHECK(parse(&o, &err, "--out", "x.png", "--frames", "100") == FT_CLI_OK);
    CHECK(strcmp(o.out, "x.png") == 0 && o.frames == 100u);
    CHECK(parse(&o, &err, "--frames", "1", NULL, NULL) == FT_CLI_OK && o.frames == 1u);
    CHECK(parse(&o, &err, "--clearance", "12.5", "--pick", "b") == FT_CLI_OK);
    CHECK(o.clearance_m == 12.5 && o.pick != NULL && strcmp(o.pick, "b") == 0);
    /* a value is taken whatever it looks like (a negative latitude, "--help") */
    CHECK(parse(&o, &err, "--out", "-33.9", NULL, NULL) == FT_CLI_OK && strcmp(o.out, "-33.9") == 0);
    CHECK(parse(&o, &err, "--out", "--help", NULL, NULL) == FT_CLI_OK &&
          strcmp(o.out, "--help") == 0);
    /* repeated: the last value wins */
    CHECK(parse(&o, &err, "--out", "a", "--out", "b") == FT_CLI_OK && strcmp(o.out, "b") == 0);

    /* a u32 out of range, or not a number: the message names the option and
     * the range, and the destination keeps its value */
    CHECK(parse(&o, &err, "--frames", "101", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --frames wants 1..100") == 0);
    CHECK(o.frames == 1u);
    CHECK(parse(&o, &err, "--frames", "0", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --frames wants 1..100") == 0);
    CHECK(parse(&o, &err, "--frames", "abc", NULL, NULL) == FT_CLI_USAGE);
    CHECK(parse(&o, &err, "--frames", "5x", NULL, NULL) == FT_CLI_USAGE);
    CHECK(parse(&o, &err, "--frames", "", NULL, NULL) == FT_CLI_USAGE);
    /* a sign is refused: strtoul would take "-18446744073709551615" as 1 */
    CHECK(parse(&o, &err, "--frames", "-18446744073709551615", NULL, NULL) == FT_CLI_USAGE);
    CHECK(parse(&o, &err, "--frames", "99999999999999999999999", NULL, NULL) == FT_CLI_USAGE);
    CHECK(o.frames == 1u);

    /* a double out of range (NaN too), with its unit */
    CHECK(parse(&o, &err, "--clearance", "10000.5", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --clearance wants 0..10000 m") == 0);
    CHECK(parse(&o, &err, "--clearance", "nan", NULL, NULL) == FT_CLI_USAGE);
    CHECK(parse(&o, &err, "--clearance", "0", NULL, NULL) == FT_CLI_OK && o.clearance_m == 0.0);

    /* a custom value refused: its own sentence after the command */
    CHECK(parse(&o, &err, "--pick", "c", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --pick wants a or b") == 0);

    /* a missing value */
    CHECK(parse(&o, &err, "--quiet", "--out", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --out needs a value") == 0);
    CHECK(parse(&o, &err, "--frames", NULL, NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --frames needs a value") == 0);

    /* an unknown option, with or without something after it; a flag given a
     * value leaves the value as an unknown option */
    CHECK(parse(&o, &err, "--bogus", "1", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: unknown option --bogus (see --help)") == 0);
    CHECK(parse(&o, &err, "--bogus", NULL, NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: unknown option --bogus (see --help)") == 0);
    CHECK(parse(&o, &err, "--quiet", "1", NULL, NULL) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: unknown option 1 (see --help)") == 0);
    CHECK(parse(&o, &err, "--Quiet", NULL, NULL, NULL) == FT_CLI_USAGE);

    /* --help and -h, in argv order: before an error it wins, after one not */
    CHECK(parse(&o, &err, "--help", NULL, NULL, NULL) == FT_CLI_HELP);
    CHECK(parse(&o, &err, "-h", NULL, NULL, NULL) == FT_CLI_HELP);
    CHECK(parse(&o, &err, "--quiet", "--help", "--bogus", NULL) == FT_CLI_HELP);
    CHECK(parse(&o, &err, "--frames", "0", "--help", NULL) == FT_CLI_USAGE);
}

static void check_size(void)
{
    uint32_t w = 0, h = 0;
    CHECK(ft_cli_parse_size("64x48", &w, &h) && w == 64u && h == 48u);
    CHECK(ft_cli_parse_size("8192x16", &w, &h) && w == 8192u && h == 16u);
    CHECK(!ft_cli_parse_size("10x10", &w, &h));
    CHECK(!ft_cli_parse_size("8193x16", &w, &h));
    CHECK(!ft_cli_parse_size("64X48", &w, &h));
    CHECK(!ft_cli_parse_size("64x48x", &w, &h));
    CHECK(!ft_cli_parse_size("64x", &w, &h));
    CHECK(w == 8192u && h == 16u); /* untouched when refused */
}

static char g_text[FT_SCENE_TEXT_MAX];

static void check_scene_load(void)
{
    static ft_scene s;
    ft_error err;
    ft_cli_scene_desc d;
    memset(&d, 0, sizeof d);
    d.command = "test";
    d.text = g_text;
    d.text_cap = sizeof g_text;

    /* the embedded default scene, then the overrides */
    memset(&err, 0, sizeof err);
    d.method = "brute";
    d.size = "64x48";
    d.pose = "46.5,8.2,3000,10,-30,0";
    d.dem = "x.ftt";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_OK);
    CHECK(s.method == FT_METHOD_BRUTE && s.width_px == 64u && s.height_px == 48u);
    CHECK(s.pose.lat_deg == 46.5 && s.pose.heading_deg == 10.0);
    CHECK(strcmp(s.dem_path, "x.ftt") == 0);

    /* each override refused: a usage error naming it */
    d.method = "magic";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: unknown method 'magic'") == 0);
    d.method = NULL;
    d.size = "10x10";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_USAGE);
    CHECK(strcmp(err.text, "fixterrain test: --size wants WxH, each 16..8192") == 0);
    d.size = NULL;
    d.pose = "46,8,3000";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_USAGE);
    CHECK(strstr(err.text, "6 comma-separated") != NULL);
    d.pose = NULL;
    d.backend = "vulkan";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_USAGE);
    CHECK(strstr(err.text, "fixterrain test: unknown backend 'vulkan'") == err.text);
    d.backend = NULL;
    d.display = "gbm";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_USAGE);
    CHECK(strstr(err.text, "fixterrain test: unknown display 'gbm'") == err.text);
    d.display = NULL;

    /* a scene file that cannot be read: a runtime error, said as every
     * command says a scene's faults, and reported before the overrides */
    d.scene_path = "/nonexistent/fixterrain-test.ini";
    d.method = "magic";
    CHECK(ft_cli_scene_load(&d, &s, &err) == FT_CLI_ERROR);
    CHECK(strstr(err.text, "fixterrain: scene: /nonexistent/fixterrain-test.ini") == err.text);
}

int main(void)
{
    check_parser();
    check_size();
    check_scene_load();
    return ft_test_result("test_cli_options");
}
