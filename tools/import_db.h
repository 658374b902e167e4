/* import_db.h - `fixterrain import --database OUT.ftd [--tile T] IN...`: many
 * DEMs GDAL reads -> one tiled multi-resolution database
 * (src/terrain/terrain_db.h). GDAL lives in tools/ only. */
#ifndef FT_IMPORT_DB_H
#define FT_IMPORT_DB_H

/* argv[0] is "import"; one argument is "--database". Returns the process exit
 * status: 0 ok, 1 error, 2 usage. */
int ft_cmd_import_db(int argc, char **argv);

#endif
