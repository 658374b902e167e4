# Geometry clipmaps (method 'clipmap'): the layout, stitch rule and vertex
# mirror on the CPU (tests/test_clipmap.c).
ft_add_test(test_clipmap SOURCES test_clipmap.c)
# The method on real contexts over a real DEM (tests/test_clipmap_gl.c):
# coverage beside brute, no crack while the eye flies and levels lag, no GL
# error; GLES 3, and a true GLES 2.0 context with float and packed texels.
if(TARGET ft_app AND FIXTERRAIN_WITH_METHOD_CLIPMAP AND FIXTERRAIN_WITH_METHOD_BRUTE
   AND FIXTERRAIN_WITH_EGL)
  add_executable(test_clipmap_gl test_clipmap_gl.c)
  target_compile_options(test_clipmap_gl PRIVATE ${FT_WARNINGS})
  target_include_directories(test_clipmap_gl PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_clipmap_gl PRIVATE ft_app m)
  set(_dem ${FT_SHARED_DATA_DIR}/N42E001.hgt)
  add_test(NAME clipmap_gl_es3 COMMAND test_clipmap_gl es3 ${_dem})
  add_test(NAME clipmap_gl_es2 COMMAND test_clipmap_gl es2 ${_dem})
  set_tests_properties(clipmap_gl_es3 clipmap_gl_es2 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
  set_tests_properties(clipmap_gl_es2 PROPERTIES ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
endif()
# A 249 km flight over a database (N41E001 + N42E001 + ETOPO5, built in the
# test) with the cache at 60 Hz of log time and every 1200th tick drawn and
# measured (tests/test_clip_flight.c): no hole, cache work inside the frame's
# spare time, level 0 current on 99% of the ticks, <= 64 MB of cache.
if(TARGET ft_app AND TARGET ft_tools AND FIXTERRAIN_WITH_METHOD_CLIPMAP
   AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_REFERENCE)
  ft_add_test(test_clip_flight SOURCES test_clip_flight.c ARGS 250 1200 LIBS ft_tools ft_app m)
  set_tests_properties(test_clip_flight PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  # the same flight with pgm reading its heights through the cache
  if(FIXTERRAIN_WITH_METHOD_PGM)
    add_test(NAME test_clip_flight_pgm COMMAND test_clip_flight 250 1200 pgm)
    set_tests_properties(test_clip_flight_pgm PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  endif()
  # and with pgrid over the cache (relief bound from the cache's cell ranges)
  if(FIXTERRAIN_WITH_METHOD_PGRID)
    add_test(NAME test_clip_flight_pgrid COMMAND test_clip_flight 250 1200 pgrid)
    set_tests_properties(test_clip_flight_pgrid PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
    # and ray casting the pixels over gamma through the cache's levels
    add_test(NAME test_clip_flight_pgrid_rc COMMAND test_clip_flight 250 1200 pgrid_rc)
    set_tests_properties(test_clip_flight_pgrid_rc PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
    # and with the tight bound deciding which pixels are ray cast
    add_test(NAME test_clip_flight_pgrid_tight COMMAND test_clip_flight 250 1200 pgrid_tight)
    set_tests_properties(test_clip_flight_pgrid_tight PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  endif()
  # and with the bintree's tiles over the cache (bintree.heights = clipmap),
  # its reported bound held on every frame
  if(FIXTERRAIN_WITH_METHOD_BINTREE)
    add_test(NAME test_clip_flight_bintree COMMAND test_clip_flight 250 1200 bintree)
    set_tests_properties(test_clip_flight_bintree PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  endif()
endif()
