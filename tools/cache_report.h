/* cache_report.h - `fixterrain-tools cache-report` (cache_report.c). */
#ifndef FT_CACHE_REPORT_H
#define FT_CACHE_REPORT_H

/* argv[0] is "cache-report". Exit status 0 ok, 1 error, 2 usage. */
int ft_cmd_cache_report(int argc, char **argv);

#endif
