# The bintree method on real contexts over real DEM data (tests/test_bintree_gl.c).
if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BINTREE
   AND FIXTERRAIN_WITH_METHOD_BRUTE AND FIXTERRAIN_WITH_EGL)
  add_executable(test_bintree_gl test_bintree_gl.c)
  target_compile_options(test_bintree_gl PRIVATE ${FT_WARNINGS})
  target_include_directories(test_bintree_gl PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_bintree_gl PRIVATE ft_app m)
  set(_dem ${FT_SHARED_DATA_DIR}/N42E001.hgt)
  # watertight (transform feedback), cracks, error bound
  add_test(NAME bintree_gl_es3 COMMAND test_bintree_gl es3 ${_dem})
  # the per-tile GLES 2 path in a strict ES 2.0 context
  add_test(NAME bintree_gl_es2 COMMAND test_bintree_gl es2 ${_dem})
  # the bound with sub-sample levels, on softpipe (see test_bintree_gl.c main)
  add_test(NAME bintree_gl_bound_sub COMMAND test_bintree_gl bound-sub ${_dem})
  set_tests_properties(bintree_gl_bound_sub PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 1800
                       ENVIRONMENT "GALLIUM_DRIVER=softpipe")
  set_tests_properties(bintree_gl_es3 bintree_gl_es2 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
  set_tests_properties(bintree_gl_es2 PROPERTIES ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
endif()

# The bound over the bench's five built-in paths on N42E001 and Rainier
# (imported here) at 640x480, tau 0.5/1/2, subsample_levels 4: max error
# <= tau + 0.05 px on every row, no budget hit, no frame reporting a bound
# over tau (tests/test_bintree_paths.sh). 10 to 11 minutes on 2 cores next to
# other tests (three of its four runs on softpipe, about 200 s each).
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BINTREE
   AND FIXTERRAIN_WITH_GDAL_TOOLS)
  add_test(NAME bintree_paths
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_bintree_paths.sh $<TARGET_FILE:fixterrain>
                      ${CMAKE_SOURCE_DIR} ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(bintree_paths PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 1500)
endif()

# The bound on two more DEMs, Everest (extreme relief) and N52E008 (flat), the
# five paths at 640x480, tau 0.5/1/2, on softpipe: the vertical error within
# each frame's reported bound on every measured frame, and on Everest the
# full error too (tests/test_bintree_dems.sh says why not on flat terrain).
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BINTREE
   AND FIXTERRAIN_WITH_GDAL_TOOLS)
  add_test(NAME bintree_dems
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_bintree_dems.sh $<TARGET_FILE:fixterrain>
                      ${CMAKE_SOURCE_DIR} ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(bintree_dems PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 1500)
endif()
