if(TARGET fixterrain)
  add_test(NAME cli COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_cli.sh $<TARGET_FILE:fixterrain>
                            ${CMAKE_BINARY_DIR}/test-out ${FT_SHARED_DATA_DIR})
  set_tests_properties(cli PROPERTIES TIMEOUT 300)

  # "Leave out what a scene does not need": a build with every option off
  # must build, and a minimal EGL + brute build must render.
  add_test(NAME lean_build
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_lean_build.sh ${CMAKE_SOURCE_DIR}
                      ${CMAKE_BINARY_DIR}/lean ${CMAKE_C_COMPILER} $<TARGET_FILE:fixterrain>)
  # the nested builds keep this build's -Werror choice
  set_tests_properties(lean_build PROPERTIES TIMEOUT 900
                       ENVIRONMENT "FT_WERROR=${FIXTERRAIN_WERROR}")
endif()

# The whole tree (every option on, tests included) must also build warning-free
# with clang; the main build uses whatever CC is (gcc on Debian).
find_program(FT_CLANG clang)
if(FT_CLANG AND NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
  add_test(NAME clang_build
           COMMAND sh -c "cmake -S '${CMAKE_SOURCE_DIR}' -B '${CMAKE_BINARY_DIR}/clang' -DCMAKE_C_COMPILER='${FT_CLANG}' -DFIXTERRAIN_WITH_GDAL_TOOLS=${FIXTERRAIN_WITH_GDAL_TOOLS} -DFIXTERRAIN_WERROR=${FIXTERRAIN_WERROR} > '${CMAKE_BINARY_DIR}/clang-configure.log' && cmake --build '${CMAKE_BINARY_DIR}/clang' -j2")
  set_tests_properties(clang_build PROPERTIES TIMEOUT 900)
endif()
