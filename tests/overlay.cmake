# Failure annunciation overlay (red cross + reason text) and its 5x7 font.
# overlay_cpu: font table and layout rules, core only (no GPU). The GL cases
# draw over a real frame of the embedded default scene on each backend; the
# GLES 2 case forces a strict ES 2.0 context (see render.cmake).
ft_add_test(overlay_cpu SOURCES test_overlay.c ARGS cpu)
target_compile_definitions(overlay_cpu PRIVATE FT_OVERLAY_TEST_GL=0)

if(TARGET ft_app)
  add_executable(test_overlay test_overlay.c)
  target_compile_options(test_overlay PRIVATE ${FT_WARNINGS})
  target_include_directories(test_overlay PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_compile_definitions(test_overlay PRIVATE FT_OVERLAY_TEST_GL=1)
  target_link_libraries(test_overlay PRIVATE ft_app m)
  if(FIXTERRAIN_WITH_EGL)
    add_test(NAME overlay_egl_gles3 COMMAND test_overlay egl-gles3)
    add_test(NAME overlay_egl_gles2_strict COMMAND test_overlay egl-gles2)
    # 640x480: glyph pixel 2, bars 14 px
    add_test(NAME overlay_egl_gles2_strict_640x480 COMMAND test_overlay egl-gles2 640x480)
    set_tests_properties(overlay_egl_gles2_strict overlay_egl_gles2_strict_640x480 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    set_tests_properties(overlay_egl_gles3 overlay_egl_gles2_strict
                         overlay_egl_gles2_strict_640x480 PROPERTIES TIMEOUT 300)
  endif()
  if(FIXTERRAIN_WITH_OSMESA)
    add_test(NAME overlay_osmesa COMMAND test_overlay osmesa)
    set_tests_properties(overlay_osmesa PROPERTIES TIMEOUT 300)
  endif()
endif()
