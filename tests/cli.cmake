if(TARGET fixterrain)
  add_test(NAME cli COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_cli.sh $<TARGET_FILE:fixterrain>
                            ${CMAKE_BINARY_DIR}/test-out ${FT_SHARED_DATA_DIR})
  set_tests_properties(cli PROPERTIES TIMEOUT 300)

  # The shipped scenes that say so set every key of the schema.
  add_test(NAME scene_keys COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_scene_keys.sh
                                   $<TARGET_FILE:fixterrain> ${CMAKE_SOURCE_DIR})
  set_tests_properties(scene_keys PROPERTIES TIMEOUT 60)

  # The display runtime carries no tool (GDAL, bench, plotter, heap use).
  add_test(NAME runtime_split
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_runtime_split.sh $<TARGET_FILE:fixterrain>
                      $<TARGET_FILE:fixterrain-tools> ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(runtime_split PROPERTIES TIMEOUT 60)

  # "Leave out what a scene does not need": a build with every option off
  # must build, and a minimal EGL + brute build must render.
  add_test(NAME lean_build
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_lean_build.sh ${CMAKE_SOURCE_DIR}
                      ${CMAKE_BINARY_DIR}/lean ${CMAKE_C_COMPILER} $<TARGET_FILE:fixterrain>)
  # the nested builds keep this build's -Werror choice
  set_tests_properties(lean_build PROPERTIES TIMEOUT 900
                       ENVIRONMENT "FT_WERROR=${FIXTERRAIN_WERROR}")

  # The lean build's profile is read by the runtime's scene parser (configures only).
  add_test(NAME lean_profile
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_profile.sh ${CMAKE_SOURCE_DIR}
                      ${CMAKE_BINARY_DIR}/lean-profile ${CMAKE_C_COMPILER} $<TARGET_FILE:fixterrain>)
  set_tests_properties(lean_profile PROPERTIES TIMEOUT 600)
endif()

# Warnings: every build type with gcc and clang is built warning-free by
# tools/build-matrix.sh (a CI step of tools/test-all.sh), not by a test here.

# The option table parser and the scene loader every command uses
# (src/app/cli.h): flags, strings, ranges, missing values, unknown options,
# --help, and the overrides over the embedded scene. No GPU.
if(TARGET ft_app)
  ft_add_test(test_cli_options SOURCES test_cli_options.c LIBS ft_app)
endif()
