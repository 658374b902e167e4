/* import_gdal.h - `fixterrain import IN OUT`: any DEM GDAL reads -> .ftt.
 * GDAL lives here only (tools/); the runtime never links it. */
#ifndef FT_IMPORT_GDAL_H
#define FT_IMPORT_GDAL_H

/* argv[0] is "import". Returns the process exit status: 0 ok, 1 error, 2 usage. */
int ft_cmd_import(int argc, char **argv);

#endif
