# Error-bounded projective grid (method 'pgrid'): the CPU pieces
# (tests/test_pgrid.c).
ft_add_test(test_pgrid SOURCES test_pgrid.c)
# The method on real contexts over a real DEM (tests/test_pgrid_gl.c).
if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_PGRID
   AND FIXTERRAIN_WITH_METHOD_BRUTE AND FIXTERRAIN_WITH_EGL)
  add_executable(test_pgrid_gl test_pgrid_gl.c)
  target_compile_options(test_pgrid_gl PRIVATE ${FT_WARNINGS})
  target_include_directories(test_pgrid_gl PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_pgrid_gl PRIVATE ft_app m)
  set(_dem ${FT_SHARED_DATA_DIR}/N42E001.hgt)
  # error bound with ray casting, distribution, sweep, cracks (GLES 3)
  add_test(NAME pgrid_gl_es3 COMMAND test_pgrid_gl es3 ${_dem})
  # a true ES 2.0 context: no ray casting, the mesh's bound reported, cracks
  add_test(NAME pgrid_gl_es2 COMMAND test_pgrid_gl es2 ${_dem})
  # the sweep again over a second real DEM: the Maritime Alps above Nice
  # (N43E007: mountains down to the sea), around 43.85 N 7.35 E
  add_test(NAME pgrid_gl_sweep_n43e007
           COMMAND test_pgrid_gl sweep ${FT_SHARED_DATA_DIR}/N43E007.hgt 43.85 7.35)
  set_tests_properties(pgrid_gl_es3 pgrid_gl_es2 pgrid_gl_sweep_n43e007 PROPERTIES
                       SKIP_RETURN_CODE 77 TIMEOUT 900)
  set_tests_properties(pgrid_gl_es2 PROPERTIES ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
endif()

# The bound over the bench's valley, climb and orbit paths on N42E001 and
# Rainier (imported here), gamma 0.5/1/2, residual bound, ray-casting budget
# of every pixel: max error <= gamma + 0.1 px on every row, no budget hit
# (tests/test_pgrid_paths.sh); and over the clipmap cache, each frame held
# to the bound it reports. About 200 s on 2 cores.
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_PGRID
   AND FIXTERRAIN_WITH_GDAL_TOOLS)
  add_test(NAME pgrid_paths
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_pgrid_paths.sh $<TARGET_FILE:fixterrain>
                      ${CMAKE_SOURCE_DIR} ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(pgrid_paths PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
endif()

# The bound on two more DEMs, Everest (extreme relief) and N52E008 (flat),
# valley, climb and orbit at 320x240, gamma 0.5/1/2: the vertical error <=
# gamma + 0.1 px on every row, and on Everest the full error too
# (tests/test_pgrid_dems.sh says why not on flat terrain). About 60 s.
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_PGRID
   AND FIXTERRAIN_WITH_GDAL_TOOLS)
  add_test(NAME pgrid_dems
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_pgrid_dems.sh $<TARGET_FILE:fixterrain>
                      ${CMAKE_SOURCE_DIR} ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(pgrid_dems PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
endif()
