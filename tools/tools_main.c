/* tools_main.c - fixterrain-tools: the programs a workstation runs and a
 * display computer does not need (benchmark, DEM import). Kept out of the
 * runtime binary so that `fixterrain` links neither GDAL, the bench nor the
 * plotter, and none of their heap use. `fixterrain bench|import` hands over
 * to this binary when it is installed beside the runtime.
 * Exit status: 0 ok, 1 runtime error, 2 usage error (as fixterrain). */
#include <stdio.h>
#include <string.h>

#include "cache_report.h"
#if FT_WITH_GDAL_TOOLS
#include "import_gdal.h"
#endif
#if FT_WITH_REFERENCE
#include "bench.h"
#endif

#define FT_EXIT_ERROR 1
#define FT_EXIT_USAGE 2

static void print_help(void)
{
    printf("usage: fixterrain-tools COMMAND [options]   (COMMAND --help for details)\n\n"
           "commands:\n"
           "  bench     error against run time: every method and setting over flight paths%s\n"
           "  import    convert a DEM (GeoTIFF, .hgt, DTED, ...) to a .ftt terrain file, or\n"
           "            many DEMs to a tiled .ftd database (--database)%s\n"
           "  cache-report  what the clipmap cache reads from a .ftd database on a flight\n"
           "            at several speeds, in a fixed share of each frame\n"
           "  help      this text\n\n"
           "The display runtime is the separate binary 'fixterrain'; it forwards its\n"
           "'bench' and 'import' commands here.\n",
#if FT_WITH_REFERENCE
           "",
#else
           " (not in this build)",
#endif
#if FT_WITH_GDAL_TOOLS
           ""
#else
           " (not in this build)"
#endif
    );
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_help();
        return FT_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "bench") == 0) {
#if FT_WITH_REFERENCE
        return ft_cmd_bench(argc - 1, argv + 1);
#else
        fprintf(stderr, "fixterrain-tools: 'bench' was left out of this build "
                        "(FIXTERRAIN_WITH_REFERENCE=OFF)\n");
        return FT_EXIT_ERROR;
#endif
    }
    if (strcmp(cmd, "import") == 0) {
#if FT_WITH_GDAL_TOOLS
        return ft_cmd_import(argc - 1, argv + 1);
#else
        fprintf(stderr, "fixterrain-tools: 'import' was left out of this build "
                        "(FIXTERRAIN_WITH_GDAL_TOOLS=OFF)\n");
        return FT_EXIT_ERROR;
#endif
    }
    if (strcmp(cmd, "cache-report") == 0) {
        return ft_cmd_cache_report(argc - 1, argv + 1);
    }
    if (strcmp(cmd, "help") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
        print_help();
        return 0;
    }
    fprintf(stderr, "fixterrain-tools: unknown command '%s'\n", cmd);
    print_help();
    return FT_EXIT_USAGE;
}
