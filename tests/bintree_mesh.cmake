# The CPU mirror of the bintree vertex shader (src/lod/bintree_mesh.h) against the
# real shader's outputs (transform feedback), and the bench's oracle frame
# (tools/bench_oracle.h) against the real frame, on N42E001, over the window and
# over the clipmap cache (bintree.heights = clipmap: shaders/bintree_clip.vert.glsl
# against ft_btc_mesh_build) (tests/test_bintree_mesh.c; skipped without
# ../shared/data).
if(TARGET ft_app AND FIXTERRAIN_WITH_METHOD_BINTREE AND FIXTERRAIN_WITH_EGL)
  add_executable(test_bintree_mesh test_bintree_mesh.c ${CMAKE_SOURCE_DIR}/tools/bench_oracle.c)
  target_compile_options(test_bintree_mesh PRIVATE ${FT_WARNINGS})
  target_include_directories(test_bintree_mesh PRIVATE ${CMAKE_SOURCE_DIR}/tests
                             ${CMAKE_SOURCE_DIR}/tools)
  target_link_libraries(test_bintree_mesh PRIVATE ft_app m)
  add_test(NAME bintree_mesh_gl COMMAND test_bintree_mesh ${FT_SHARED_DATA_DIR}/N42E001.hgt)
  set_tests_properties(bintree_mesh_gl PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
endif()
