if(TARGET fixterrain)
  add_test(NAME cli COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_cli.sh $<TARGET_FILE:fixterrain>
                            ${CMAKE_BINARY_DIR}/test-out ${FT_SHARED_DATA_DIR})
  set_tests_properties(cli PROPERTIES TIMEOUT 300)

  # "Leave out what a scene does not need": a build with every option off
  # must build, and a minimal EGL + brute build must render.
  add_test(NAME lean_build
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_lean_build.sh ${CMAKE_SOURCE_DIR}
                      ${CMAKE_BINARY_DIR}/lean ${CMAKE_C_COMPILER})
  set_tests_properties(lean_build PROPERTIES TIMEOUT 900)
endif()
