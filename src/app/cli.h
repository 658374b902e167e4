/* cli.h - command lines as tables: one row per option (its name, what its
 * value is, where it goes, its help line), one parse function that walks argv
 * against the table, and the one scene loader every command that draws uses
 * (the scene file or the embedded default, then the command-line overrides).
 *
 * No heap: a table is an array the command declares (its rows point at the
 * command's own variables), values are argv's strings or are written through
 * the row's destination, and the scene text goes to a buffer the caller owns.
 *
 * Messages go to stderr as one line, "fixterrain COMMAND: why", and into err
 * (when err is not NULL) so a test can read them.
 *
 * Results are exit statuses (FT_CLI_OK, FT_CLI_ERROR, FT_CLI_USAGE) except
 * FT_CLI_HELP: --help or -h was given, and the caller prints its help. */
#ifndef FT_APP_CLI_H
#define FT_APP_CLI_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "core/scene.h"

#define FT_CLI_OK 0
#define FT_CLI_ERROR 1 /* a runtime error: a scene the parser refused */
#define FT_CLI_USAGE 2 /* a usage error: the command line */
#define FT_CLI_HELP (-1)

typedef enum ft_cli_kind {
    FT_CLI_FLAG,   /* no value; *(int *)dst = 1 */
    FT_CLI_STRING, /* *(const char **)dst = the value (argv's storage) */
    FT_CLI_U32,    /* *(uint32_t *)dst = decimal digits in [min_u32, max_u32] */
    FT_CLI_DOUBLE, /* *(double *)dst = a number (strtod) in [min, max] */
    FT_CLI_CUSTOM, /* parse(value, dst, err): anything else (a list, a choice) */
} ft_cli_kind;

/* A custom value: FT_OK when taken, else an ft_fail with the reason, which
 * the parser prints after "fixterrain COMMAND: " (so name the option). */
typedef ft_status (*ft_cli_parse_fn)(const char *value, void *dst, ft_error *err);

typedef struct ft_cli_opt {
    const char *name; /* "--frames" (matched exactly) */
    ft_cli_kind kind;
    void *dst;
    uint32_t min_u32, max_u32; /* FT_CLI_U32: the range, both included */
    double min, max;           /* FT_CLI_DOUBLE: the range, both included */
    const char *unit;          /* said after a range ("m"), or NULL */
    ft_cli_parse_fn parse;     /* FT_CLI_CUSTOM */
    /* The option's help as printed after two spaces of indent, continuation
     * lines included; NULL when another row's line covers it. */
    const char *help;
} ft_cli_opt;

/* Rows, one per kind. The conditional with a null pointer of the kind's type
 * makes the compiler refuse a destination of another type. */
#define FT_CLI_OPT_FLAG(name_, dst_, help_)                                             \
    {.name = (name_), .kind = FT_CLI_FLAG, .dst = (1 ? (dst_) : (int *)NULL), .help = (help_)}
#define FT_CLI_OPT_STRING(name_, dst_, help_)                                        \
    {.name = (name_), .kind = FT_CLI_STRING, .dst = (1 ? (dst_) : (const char **)NULL), \
     .help = (help_)}
#define FT_CLI_OPT_U32(name_, dst_, min_, max_, help_)                                  \
    {.name = (name_), .kind = FT_CLI_U32, .dst = (1 ? (dst_) : (uint32_t *)NULL),        \
     .min_u32 = (min_), .max_u32 = (max_), .help = (help_)}
#define FT_CLI_OPT_DOUBLE(name_, dst_, min_, max_, unit_, help_)                        \
    {.name = (name_), .kind = FT_CLI_DOUBLE, .dst = (1 ? (dst_) : (double *)NULL),       \
     .min = (min_), .max = (max_), .unit = (unit_), .help = (help_)}
#define FT_CLI_OPT_CUSTOM(name_, parse_, dst_, help_)                                   \
    {.name = (name_), .kind = FT_CLI_CUSTOM, .dst = (dst_), .parse = (parse_), .help = (help_)}

typedef struct ft_cli_desc {
    const char *command; /* "render": messages say "fixterrain render: ..." */
    const ft_cli_opt *opts;
    size_t opt_count;
} ft_cli_desc;

/* Walks argv[1..argc-1] (argv[0] is the command's name) against the table,
 * in order: --help/-h returns FT_CLI_HELP at once; an option that takes a
 * value takes the next argument whatever it looks like ("--pose -33,...");
 * a repeated option is taken again (the last value wins, or a custom parse
 * collects them). Refused, with FT_CLI_USAGE: an option not in the table,
 * a missing value, a number that is not one or is out of range (the message
 * names the option and the range), a custom value its parse refuses. */
int ft_cli_parse(const ft_cli_desc *desc, int argc, char **argv, ft_error *err);

/* The help lines of the rows that have one, in table order, to stdout. */
void ft_cli_print_help(const ft_cli_desc *desc);

/* "WxH", each 16..8192 pixels: 1 when taken. */
int ft_cli_parse_size(const char *text, uint32_t *width_px, uint32_t *height_px);

/* A scene and its command-line overrides (NULL: not given). The overrides
 * are resolved after the scene text, as a scene key would be, so a scene
 * the parser refuses is reported first. */
typedef struct ft_cli_scene_desc {
    const char *command;    /* "render": a refused override says "fixterrain render: ..." */
    const char *scene_path; /* --scene FILE; NULL: the embedded default scene */
    const char *dem;        /* --dem FILE: replaces terrain.dem */
    const char *method;     /* --method NAME */
    const char *backend;    /* --backend NAME */
    const char *display;    /* --display none | x11 | kms[:/dev/dri/cardN] */
    const char *size;       /* --size WxH */
    const char *pose;       /* --pose LAT,LON,ALT_M,HEADING_DEG,PITCH_DEG,ROLL_DEG */
    char *text;             /* the scene file's text is read into this buffer */
    size_t text_cap;        /* FT_SCENE_TEXT_MAX */
} ft_cli_scene_desc;

/* Defaults, then the scene file (a relative terrain.dem in it made relative
 * to the file, unless --dem replaces it) or the embedded default scene, then
 * the overrides. A scene refused by the parser: FT_CLI_ERROR, said as
 * "fixterrain: scene: ..." (every command, and tools/scene_options.c, say a
 * scene's faults the same way); a refused override: FT_CLI_USAGE. */
int ft_cli_scene_load(const ft_cli_scene_desc *desc, ft_scene *scene, ft_error *err);

#endif
