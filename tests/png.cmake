if(TARGET ft_app AND FIXTERRAIN_WITH_PNG)
  add_executable(test_png test_png.c)
  target_compile_options(test_png PRIVATE ${FT_WARNINGS})
  target_include_directories(test_png PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_compile_definitions(test_png PRIVATE
    FT_SHARED_DATA_DIR="${FT_SHARED_DATA_DIR}" FT_TEST_OUT_DIR="${CMAKE_BINARY_DIR}/test-out")
  target_link_libraries(test_png PRIVATE ft_app)
  add_test(NAME test_png COMMAND test_png)
endif()
