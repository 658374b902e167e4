# Presentation: the [presentation] keys and band rule (no GPU), and a
# staircase terrain coloured by relative altitude on real contexts. The
# program exercises every optional part (relative colouring and the night
# palette in the staircase, haze, horizon, ground grid): a build that leaves
# one out does not build it (tests/test_lean_build.sh checks those builds).
if(NOT (FIXTERRAIN_WITH_RELATIVE_COLOURING AND FIXTERRAIN_WITH_HORIZON AND FIXTERRAIN_WITH_HAZE
        AND FIXTERRAIN_WITH_GROUND_GRID AND FIXTERRAIN_WITH_NIGHT_PALETTE))
  return()
endif()
ft_add_test(test_presentation SOURCES test_presentation.c ARGS parse LIBS m)
if(NOT (TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE))
  target_compile_definitions(test_presentation PRIVATE FT_PRESENTATION_GL=0)
else()
  target_compile_definitions(test_presentation PRIVATE FT_PRESENTATION_GL=1)
  target_link_libraries(test_presentation PRIVATE ft_app)
  if(FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BRUTE)
    add_test(NAME presentation_stairs_gles3 COMMAND test_presentation stairs egl-gles3 brute)
    # a true ES 2.0 context (without the override Mesa returns ES 3.2)
    add_test(NAME presentation_stairs_gles2 COMMAND test_presentation stairs egl-gles2 brute)
    set_tests_properties(presentation_stairs_gles2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    # the conformal horizon over a flat sea on a spherical earth
    add_test(NAME presentation_horizon_gles3 COMMAND test_presentation horizon egl-gles3)
    add_test(NAME presentation_horizon_gles2 COMMAND test_presentation horizon egl-gles2)
    set_tests_properties(presentation_horizon_gles2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    # void-filled terrain is marked exactly over its cells (half-void tile, N52E008)
    add_test(NAME presentation_voids_gles3 COMMAND test_presentation voids egl-gles3 brute)
    add_test(NAME presentation_grid_gles3 COMMAND test_presentation grid egl-gles3 brute)
    add_test(NAME presentation_grid_gles2 COMMAND test_presentation grid egl-gles2 brute)
    set_tests_properties(presentation_grid_gles2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    add_test(NAME presentation_voids_gles2 COMMAND test_presentation voids egl-gles2 brute)
    set_tests_properties(presentation_voids_gles2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
  endif()
  if(FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_PGRID)
    # the ray-cast pixels colour through their own shader (pgrid_rc.frag.glsl)
    add_test(NAME presentation_stairs_pgrid COMMAND test_presentation stairs egl-gles3 pgrid)
    add_test(NAME presentation_voids_pgrid COMMAND test_presentation voids egl-gles3 pgrid)
    add_test(NAME presentation_grid_pgrid COMMAND test_presentation grid egl-gles3 pgrid)
  endif()
endif()
