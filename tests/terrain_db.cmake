# The tiled terrain database (.ftd): import from real DEMs, read back through
# pread, corrupt copies refused (needs the GDAL import tool).
if(TARGET ft_tools)
  ft_add_test(test_terrain_db SOURCES test_terrain_db.c LIBS ft_tools ft_platform)
endif()

# A scene's window of a .ftd (built in the test from N41E001 + N42E001):
# samples against the .hgt files, missing data marked, errors; and frames
# over the mosaic's edge (hatch and unmeasured_px).
if(TARGET ft_tools AND TARGET ft_app)
  ft_add_test(test_db_window SOURCES test_db_window.c ARGS samples LIBS ft_tools ft_app m)
  if(FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BRUTE)
    add_test(NAME db_window_render_gles3 COMMAND test_db_window render egl-gles3 brute)
    set_tests_properties(db_window_render_gles3 PROPERTIES SKIP_RETURN_CODE 77)
  endif()
endif()

# Terrain across the antimeridian (a database of ETOPO5 alone, built in the
# test): the window, the clipmap cache and frames on both sides of 180 deg E.
if(TARGET ft_tools AND TARGET ft_app AND FIXTERRAIN_WITH_EGL
   AND FIXTERRAIN_WITH_METHOD_BRUTE AND FIXTERRAIN_WITH_METHOD_CLIPMAP)
  ft_add_test(test_antimeridian SOURCES test_antimeridian.c LIBS ft_tools ft_app m)
  set_tests_properties(test_antimeridian PROPERTIES SKIP_RETURN_CODE 77)
endif()

# The deviation bounds a database stores for its coarse levels, measured
# against the finest data read by the runtime's rule (databases built in the
# test from N41E001 + N42E001, and N42E001 over ETOPO5).
if(TARGET ft_tools AND TARGET ft_app)
  ft_add_test(test_tdb_dev SOURCES test_tdb_dev.c LIBS ft_tools ft_app m)
  set_tests_properties(test_tdb_dev PROPERTIES SKIP_RETURN_CODE 77)
endif()
