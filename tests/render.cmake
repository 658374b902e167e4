# Real contexts, real frames: EGL GLES 3, EGL GLES 2 (a true ES 2.0 context via
# MESA_GLES_VERSION_OVERRIDE: without it Mesa returns ES 3.2 to an ES 2
# request and would hide ES 3 features in the GLES 2 path), OSMesa, and the
# packed-height fallback; then the images must agree.
if(TARGET ft_app)
  set(_out ${CMAKE_BINARY_DIR}/test-out)
  add_executable(test_render test_render.c)
  target_compile_options(test_render PRIVATE ${FT_WARNINGS})
  target_include_directories(test_render PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_render PRIVATE ft_app)
  set(_images "")
  macro(ft_render_case name backend format expect env)
    add_test(NAME ${name} COMMAND test_render ${backend} ${format} ${_out}/${name}.rgba ${expect})
    set_tests_properties(${name} PROPERTIES FIXTURES_SETUP render_images TIMEOUT 300
                         ENVIRONMENT "${env}")
    list(APPEND _images ${_out}/${name}.rgba)
  endmacro()
  if(FIXTERRAIN_WITH_EGL)
    ft_render_case(render_egl_gles3 egl-gles3 auto "OpenGL ES 3" "")
    ft_render_case(render_egl_gles2_strict egl-gles2 auto "OpenGL ES 2.0" "MESA_GLES_VERSION_OVERRIDE=2.0")
    ft_render_case(render_egl_gles2_packed egl-gles2 packed "OpenGL ES 2.0" "MESA_GLES_VERSION_OVERRIDE=2.0")
    ft_render_case(render_egl_gles3_packed egl-gles3 packed "OpenGL ES 3" "")
  endif()
  if(FIXTERRAIN_WITH_OSMESA)
    ft_render_case(render_osmesa osmesa auto "4." "")
  endif()
  list(LENGTH _images _n)
  if(_n GREATER 1)
    add_executable(test_render_compare test_render_compare.c)
    target_compile_options(test_render_compare PRIVATE ${FT_WARNINGS})
    target_include_directories(test_render_compare PRIVATE ${CMAKE_SOURCE_DIR}/tests)
    target_link_libraries(test_render_compare PRIVATE m)
    add_test(NAME render_compare COMMAND test_render_compare 320 240 ${_images})
    set_tests_properties(render_compare PROPERTIES FIXTURES_REQUIRED render_images)
  endif()

  # The GLSL ES 1.00 sources must pass a strict validator: Mesa compiles
  # ES 3 constructs even in an ES 2.0 context and would not catch them.
  find_program(GLSLANG glslangValidator)
  if(GLSLANG)
    add_test(NAME glsl_validate
             COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/glsl_validate.sh ${GLSLANG}
                     ${CMAKE_BINARY_DIR}/generated/shaders ${_out})
  endif()
endif()

if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_PNG)
  add_executable(test_no_heap test_no_heap.c)
  target_compile_options(test_no_heap PRIVATE ${FT_WARNINGS})
  target_include_directories(test_no_heap PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_no_heap PRIVATE ft_app)
  target_link_options(test_no_heap PRIVATE
    "LINKER:--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free,--wrap=strdup"
    "LINKER:--wrap=posix_memalign,--wrap=aligned_alloc,--wrap=mmap")
  if(FIXTERRAIN_WITH_EGL)
    add_test(NAME no_heap_egl COMMAND test_no_heap ${CMAKE_BINARY_DIR}/test-out/no_heap.png egl-gles3)
    if(FIXTERRAIN_WITH_METHOD_BINTREE)
      add_test(NAME no_heap_bintree_egl COMMAND test_no_heap
               ${CMAKE_BINARY_DIR}/test-out/no_heap_bintree.png egl-gles3 bintree replay)
      if(FIXTERRAIN_WITH_METHOD_PGRID)
        add_test(NAME no_heap_pgrid_egl COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_pgrid.png egl-gles3 pgrid)
        add_test(NAME no_heap_pgrid_columns_egl COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_pgrid_columns.png egl-gles3 pgrid-columns)
      endif()
      add_test(NAME no_heap_bintree_gles2 COMMAND test_no_heap
               ${CMAKE_BINARY_DIR}/test-out/no_heap_bintree_es2.png egl-gles2 bintree)
      set_tests_properties(no_heap_bintree_gles2 PROPERTIES
                           ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    endif()
    if(FIXTERRAIN_WITH_METHOD_PGM)
      add_test(NAME no_heap_pgm_egl COMMAND test_no_heap
               ${CMAKE_BINARY_DIR}/test-out/no_heap_pgm.png egl-gles3 pgm)
      add_test(NAME no_heap_pgm_gles2 COMMAND test_no_heap
               ${CMAKE_BINARY_DIR}/test-out/no_heap_pgm_es2.png egl-gles2 pgm)
      set_tests_properties(no_heap_pgm_gles2 PROPERTIES
                           ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    endif()
  endif()
  if(FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_CLIPMAP)
    # the cache's updates upload while the eye moves: still no heap
    add_test(NAME no_heap_clipmap_egl COMMAND test_no_heap
             ${CMAKE_BINARY_DIR}/test-out/no_heap_clipmap.png egl-gles3 clipmap replay)
    add_test(NAME no_heap_clipmap_gles2 COMMAND test_no_heap
             ${CMAKE_BINARY_DIR}/test-out/no_heap_clipmap_es2.png egl-gles2 clipmap)
    set_tests_properties(no_heap_clipmap_gles2 PROPERTIES
                         ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
    # over a .ftd window, the cache reading the database past it (pread,
    # tile checks, the coarser-level fallback) while frames and a replay run
    if(TARGET ft_tools)
      set(_nh_db ${CMAKE_BINARY_DIR}/test-out/no_heap_mosaic.ftd)
      add_test(NAME no_heap_ftd_database
               COMMAND fixterrain-tools import --database ${_nh_db}
                       ${FT_SHARED_DATA_DIR}/N41E001.hgt ${FT_SHARED_DATA_DIR}/N42E001.hgt)
      set_tests_properties(no_heap_ftd_database PROPERTIES FIXTURES_SETUP no_heap_ftd)
      add_test(NAME no_heap_clipmap_ftd COMMAND test_no_heap
               ${CMAKE_BINARY_DIR}/test-out/no_heap_clipmap_ftd.png egl-gles3 clipmap replay
               ${_nh_db})
      set_tests_properties(no_heap_clipmap_ftd PROPERTIES FIXTURES_REQUIRED no_heap_ftd)
      # pgm reading the same cache (pgm.heights = clipmap), on GLES 3 and 2
      if(FIXTERRAIN_WITH_METHOD_PGM)
        add_test(NAME no_heap_pgm_cache_ftd COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_pgm_cache_ftd.png egl-gles3 pgm-cache
                 replay ${_nh_db})
        add_test(NAME no_heap_pgm_cache_ftd_gles2 COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_pgm_cache_ftd_es2.png egl-gles2 pgm-cache
                 replay ${_nh_db})
        set_tests_properties(no_heap_pgm_cache_ftd no_heap_pgm_cache_ftd_gles2 PROPERTIES
                             FIXTURES_REQUIRED no_heap_ftd)
        set_tests_properties(no_heap_pgm_cache_ftd_gles2 PROPERTIES
                             ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
      endif()
      # pgrid over the cache (its cell ranges refreshed by every update)
      if(FIXTERRAIN_WITH_METHOD_PGRID)
        add_test(NAME no_heap_pgrid_cache_ftd COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_pgrid_cache_ftd.png egl-gles3 pgrid-cache
                 replay ${_nh_db})
        set_tests_properties(no_heap_pgrid_cache_ftd PROPERTIES FIXTURES_REQUIRED no_heap_ftd)
      endif()
      # the bintree's tiles over the cache (bintree.heights = clipmap)
      if(FIXTERRAIN_WITH_METHOD_BINTREE)
        add_test(NAME no_heap_bintree_cache_ftd COMMAND test_no_heap
                 ${CMAKE_BINARY_DIR}/test-out/no_heap_bintree_cache_ftd.png egl-gles3
                 bintree-cache replay ${_nh_db})
        set_tests_properties(no_heap_bintree_cache_ftd PROPERTIES FIXTURES_REQUIRED no_heap_ftd)
      endif()
    endif()
  endif()
  if(FIXTERRAIN_WITH_OSMESA)
    add_test(NAME no_heap_osmesa COMMAND test_no_heap ${CMAKE_BINARY_DIR}/test-out/no_heap_osmesa.png osmesa)
  endif()
endif()

if(TARGET ft_app AND FIXTERRAIN_WITH_REFERENCE)
  add_executable(test_metric_gpu test_metric_gpu.c)
  target_compile_options(test_metric_gpu PRIVATE ${FT_WARNINGS})
  target_include_directories(test_metric_gpu PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_compile_definitions(test_metric_gpu PRIVATE
    FT_SHARED_DATA_DIR="${FT_SHARED_DATA_DIR}" FT_TEST_OUT_DIR="${CMAKE_BINARY_DIR}/test-out")
  target_link_libraries(test_metric_gpu PRIVATE ft_app m)
  if(FIXTERRAIN_WITH_EGL)
    add_test(NAME metric_gpu_egl COMMAND test_metric_gpu egl-gles3)
    set_tests_properties(metric_gpu_egl PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
  endif()
  if(FIXTERRAIN_WITH_OSMESA)
    add_test(NAME metric_gpu_osmesa COMMAND test_metric_gpu osmesa)
    set_tests_properties(metric_gpu_osmesa PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600)
  endif()
endif()

if(TARGET ft_app)
  add_executable(test_gpu_pyramids test_gpu_pyramids.c)
  target_compile_options(test_gpu_pyramids PRIVATE ${FT_WARNINGS})
  target_include_directories(test_gpu_pyramids PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_gpu_pyramids PRIVATE ft_app m)
  if(FIXTERRAIN_WITH_EGL)
    add_test(NAME gpu_pyramids_float COMMAND test_gpu_pyramids egl-gles3 float)
    add_test(NAME gpu_pyramids_packed COMMAND test_gpu_pyramids egl-gles3 packed)
  endif()
  if(FIXTERRAIN_WITH_OSMESA)
    add_test(NAME gpu_pyramids_osmesa COMMAND test_gpu_pyramids osmesa float)
  endif()
endif()

# The window-surface path, on a real X server (Xvfb) when xvfb-run exists.
find_program(FT_XVFB_RUN xvfb-run)
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_X11 AND FT_XVFB_RUN)
  add_executable(test_window test_window.c)
  target_compile_options(test_window PRIVATE ${FT_WARNINGS})
  target_include_directories(test_window PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_window PRIVATE ft_app PkgConfig::X11)
  add_test(NAME window_x11_gles3
           COMMAND ${FT_XVFB_RUN} -a -s "-screen 0 640x480x24" $<TARGET_FILE:test_window> egl-gles3)
  add_test(NAME window_x11_gles2
           COMMAND ${FT_XVFB_RUN} -a -s "-screen 0 640x480x24" $<TARGET_FILE:test_window> egl-gles2)
  set_tests_properties(window_x11_gles2 PROPERTIES ENVIRONMENT "MESA_GLES_VERSION_OVERRIDE=2.0")
  set_tests_properties(window_x11_gles3 window_x11_gles2 PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()

# A broken invariant ends in the fail-safe annunciation (src/core/invariant.h).
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BRUTE)
  add_executable(test_invariant test_invariant.c)
  target_compile_options(test_invariant PRIVATE ${FT_WARNINGS})
  target_include_directories(test_invariant PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_invariant PRIVATE ft_app)
  add_test(NAME invariant_failsafe COMMAND test_invariant egl-gles3)
  set_tests_properties(invariant_failsafe PROPERTIES TIMEOUT 300)
endif()
