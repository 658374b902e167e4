# fixterrain replay end to end (tests/test_replay.c) on a real context.
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BRUTE)
  add_executable(test_replay test_replay.c ${CMAKE_SOURCE_DIR}/tools/flight_path.c)
  target_compile_options(test_replay PRIVATE ${FT_WARNINGS})
  target_include_directories(test_replay PRIVATE ${CMAKE_SOURCE_DIR}/tests ${CMAKE_SOURCE_DIR}/tools)
  target_compile_definitions(test_replay PRIVATE FT_TEST_OUT_DIR="${CMAKE_BINARY_DIR}/test-out")
  target_link_libraries(test_replay PRIVATE ft_app m)
  add_test(NAME replay_faults COMMAND test_replay)
endif()
