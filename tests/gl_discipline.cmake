# GL SC 2.0 call discipline after init (tests/test_gl_discipline.c): every
# GL call of 240 frames (120 plain, 120 with the annunciation overlay) of each
# method is recorded through the GL table and checked against the frame
# loop's subset. GLES 3 and a true GLES 2.0 context (MESA_GLES_VERSION_OVERRIDE,
# see render.cmake); OSMesa for one method.
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL)
  add_executable(test_gl_discipline test_gl_discipline.c)
  target_compile_options(test_gl_discipline PRIVATE ${FT_WARNINGS})
  target_include_directories(test_gl_discipline PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_gl_discipline PRIVATE ft_app)
  foreach(_m brute bintree pgm pgrid clipmap)
    string(TOUPPER ${_m} _M)
    if(FIXTERRAIN_WITH_METHOD_${_M})
      add_test(NAME gl_discipline_${_m}_es3 COMMAND test_gl_discipline egl-gles3 ${_m})
      add_test(NAME gl_discipline_${_m}_es2 COMMAND test_gl_discipline egl-gles2 ${_m})
      set_tests_properties(gl_discipline_${_m}_es2 PROPERTIES
                           ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
      set_tests_properties(gl_discipline_${_m}_es3 gl_discipline_${_m}_es2 PROPERTIES
                           TIMEOUT 300 LABELS "gl;gl_discipline")
    endif()
  endforeach()
  # pgrid over the clipmap cache, ray casting through its levels (GLES 3 only)
  if(FIXTERRAIN_WITH_METHOD_PGRID)
    add_test(NAME gl_discipline_pgrid_cache_es3 COMMAND test_gl_discipline egl-gles3 pgrid-cache)
    set_tests_properties(gl_discipline_pgrid_cache_es3 PROPERTIES TIMEOUT 300
                         LABELS "gl;gl_discipline")
  endif()
  # the bintree's tiles over the clipmap cache (bintree.heights = clipmap),
  # GLES 3 and 2
  if(FIXTERRAIN_WITH_METHOD_BINTREE)
    add_test(NAME gl_discipline_bintree_cache_es3 COMMAND test_gl_discipline egl-gles3
             bintree-cache)
    add_test(NAME gl_discipline_bintree_cache_es2 COMMAND test_gl_discipline egl-gles2
             bintree-cache)
    set_tests_properties(gl_discipline_bintree_cache_es2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    set_tests_properties(gl_discipline_bintree_cache_es3 gl_discipline_bintree_cache_es2
                         PROPERTIES TIMEOUT 300 LABELS "gl;gl_discipline")
  endif()
  if(FIXTERRAIN_WITH_OSMESA AND FIXTERRAIN_WITH_METHOD_BINTREE)
    add_test(NAME gl_discipline_bintree_osmesa COMMAND test_gl_discipline osmesa bintree)
    set_tests_properties(gl_discipline_bintree_osmesa PROPERTIES TIMEOUT 300
                         LABELS "gl;gl_discipline")
  endif()
endif()
