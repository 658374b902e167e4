# Terrain data: pyramids, void fill, .ftt files, SRTM .hgt, synthetic terrain.
ft_add_test(test_pyramid SOURCES test_pyramid.c)
ft_add_test(test_void_fill SOURCES test_void_fill.c)
ft_add_test(test_terrain_file SOURCES test_terrain_file.c)
ft_add_test(test_hgt SOURCES test_hgt.c)
ft_add_test(test_synth SOURCES test_synth.c)
# The CLI refuses .ftt files with a right crc but impossible content, and no
# --stats JSON gets a non-finite number (files written by test_terrain_file).
if(TARGET fixterrain)
  set_tests_properties(test_terrain_file PROPERTIES FIXTURES_SETUP ftt_corrupt_files)
  add_test(NAME ftt_cli_reject
           COMMAND ${CMAKE_COMMAND} -DFIXTERRAIN=$<TARGET_FILE:fixterrain>
                   -DOUT=${CMAKE_BINARY_DIR}/test-out
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/ftt_cli_reject.cmake)
  set_tests_properties(ftt_cli_reject PROPERTIES FIXTURES_REQUIRED ftt_corrupt_files TIMEOUT 300)
endif()
