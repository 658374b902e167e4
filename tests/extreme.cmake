# Stiff and extreme cases through every method built in (tests/test_extreme.c).
if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_EGL)
  add_executable(test_extreme test_extreme.c)
  target_compile_options(test_extreme PRIVATE ${FT_WARNINGS})
  target_include_directories(test_extreme PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_extreme PRIVATE ft_app m)
  add_test(NAME extreme_cases COMMAND test_extreme ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(extreme_cases PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 900)
endif()
