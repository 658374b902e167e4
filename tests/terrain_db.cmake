# The tiled terrain database (.ftd): import from real DEMs, read back through
# pread, corrupt copies refused (needs the GDAL import tool).
if(TARGET ft_tools)
  ft_add_test(test_terrain_db SOURCES test_terrain_db.c LIBS ft_tools ft_platform)
endif()
