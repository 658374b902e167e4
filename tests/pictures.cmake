# The README's pictures (docs/pictures) against what the renderer draws now
# (tools/render-pictures.sh; the Rainier ones need ../shared/data).
if(TARGET fixterrain AND TARGET fixterrain-tools AND FIXTERRAIN_WITH_PNG AND
   FIXTERRAIN_WITH_GDAL_TOOLS AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BINTREE AND
   FIXTERRAIN_WITH_METHOD_PGRID AND FIXTERRAIN_WITH_RELATIVE_COLOURING AND
   FIXTERRAIN_WITH_HORIZON AND FIXTERRAIN_WITH_HAZE AND FIXTERRAIN_WITH_NIGHT_PALETTE)
  add_executable(picture_compare picture_compare.c)
  target_compile_options(picture_compare PRIVATE ${FT_WARNINGS})
  target_link_libraries(picture_compare PRIVATE PkgConfig::PNG)
  add_test(NAME pictures
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_pictures.sh ${CMAKE_SOURCE_DIR}
                      ${CMAKE_BINARY_DIR} ${CMAKE_BINARY_DIR}/test-out ${FT_SHARED_DATA_DIR}
                      $<TARGET_FILE:picture_compare>)
  set_tests_properties(pictures PROPERTIES TIMEOUT 300 SKIP_RETURN_CODE 77)
endif()
