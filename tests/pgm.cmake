# Persistent grid mapping (method 'pgm'): the mapping math on the CPU
# (tests/test_pgm.c), and the method on real contexts over a real DEM
# (tests/test_pgm_gl.c).
ft_add_test(test_pgm SOURCES test_pgm.c)
if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_PGM
   AND FIXTERRAIN_WITH_METHOD_BRUTE AND FIXTERRAIN_WITH_EGL)
  add_executable(test_pgm_gl test_pgm_gl.c)
  target_compile_options(test_pgm_gl PRIVATE ${FT_WARNINGS})
  target_include_directories(test_pgm_gl PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_pgm_gl PRIVATE ft_app m)
  set(_dem ${FT_SHARED_DATA_DIR}/N42E001.hgt)
  # shader = CPU mirror (transform feedback), sweep, cracks, error beside brute
  add_test(NAME pgm_gl_es3 COMMAND test_pgm_gl es3 ${_dem})
  # a true ES 2.0 context: cracks and terrain presence from the colour image
  add_test(NAME pgm_gl_es2 COMMAND test_pgm_gl es2 ${_dem})
  set_tests_properties(pgm_gl_es3 pgm_gl_es2 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  set_tests_properties(pgm_gl_es2 PROPERTIES ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
endif()
