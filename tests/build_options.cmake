# The one table of build options (tools/build_options.cmake) against the code
# that uses them: every FT_WITH_* in the C code has a row and every row is
# used (a script; no build, no GPU).
add_test(NAME build_options_table
         COMMAND ${CMAKE_COMMAND} -DSRC=${CMAKE_SOURCE_DIR}
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_build_options.cmake)
set_tests_properties(build_options_table PROPERTIES TIMEOUT 60)
