# A DEM without a pose gets its default view; a pose off the terrain is said.
if(TARGET fixterrain AND FIXTERRAIN_WITH_METHOD_BINTREE AND FIXTERRAIN_WITH_REFERENCE)
  add_test(NAME default_view
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_default_view.sh $<TARGET_FILE:fixterrain>
                      ${CMAKE_BINARY_DIR}/test-out ${FT_SHARED_DATA_DIR})
  set_tests_properties(default_view PROPERTIES TIMEOUT 600)
endif()
