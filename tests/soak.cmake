# Soak (label `soak`, tests/test_soak.c): 31 minutes of log time from
# fixterrain-flightgen (an orbit with flightgen's own single faults), faults
# added every minute by the test, replayed through ft_app_replay at 64x48,
# 20 frames/s (37,200 frames): flat RSS and arena, 0 GL errors (glGetError
# after every frame), no deadline-miss drift. Wall time on 2 shared cores:
# 70-100 s measured (about 67 s of CPU); run it with `ctest -L soak`.
# the sanitized soaks' allocator settings (see below)
set(_soak_asan
    "ASAN_OPTIONS=string_append::quarantine_size_mb=0:allocator_release_to_os_interval_ms=-1")
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BINTREE
   AND TARGET fixterrain-flightgen)
  set(_soak_dir ${CMAKE_BINARY_DIR}/test-out/soak)
  file(MAKE_DIRECTORY ${_soak_dir})
  add_test(NAME soak_log
           COMMAND fixterrain-flightgen --path orbit --centre 46.5,8.0 --radius 2000 --alt 3000
                   --duration 1860 --quiet --drop-every 97 --nan-at 120.5 --bad-dlc-at 240.5
                   --duplicate-at 360.5 --gps-jump 900,300 --out ${_soak_dir}/raw.log)
  set_tests_properties(soak_log PROPERTIES FIXTURES_SETUP soak_log LABELS "soak")
  add_executable(test_soak test_soak.c)
  target_compile_options(test_soak PRIVATE ${FT_WARNINGS})
  target_include_directories(test_soak PRIVATE ${CMAKE_SOURCE_DIR}/tests)
  target_link_libraries(test_soak PRIVATE ft_app m)
  add_test(NAME soak COMMAND test_soak ${_soak_dir}/raw.log ${_soak_dir} 50)
  set_tests_properties(soak PROPERTIES FIXTURES_REQUIRED soak_log LABELS "soak" TIMEOUT 900)
  # ASan keeps freed blocks in a quarantine (256 MiB by default) before it
  # reuses them, so the driver's per-frame malloc/free grows the RSS until the
  # quarantine is full (1.7-3 MiB over the soak, measured): the flat-RSS check
  # would measure the sanitizer. The soak's sanitized run reuses at once, and
  # keeps freed pages instead of returning them to the OS every few seconds
  # (ASan's own trim: with it the per-minute RSS moved by 1-1.7 MiB with no
  # growth under it, measured), so RSS is the high water as with glibc below.
  if(FIXTERRAIN_SANITIZE)
    set_tests_properties(soak PROPERTIES ENVIRONMENT_MODIFICATION "${_soak_asan}")
  endif()
endif()
# The same checks for 10 minutes with the clipmap method over a .ftd window
# (N41E001 + N42E001, built by the fixture): the cache reads the database and
# uploads as the eye orbits 8 km around 42.5 N 1.5 E at 250 m/s (one revolution
# in 201 s, inside the 5-minute warm-up: every view is seen before RSS is
# judged).
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_CLIPMAP
   AND TARGET fixterrain-flightgen AND TARGET ft_tools)
  set(_soak_dir ${CMAKE_BINARY_DIR}/test-out/soak_clipmap)
  file(MAKE_DIRECTORY ${_soak_dir})
  add_test(NAME soak_clipmap_inputs
           COMMAND ${CMAKE_COMMAND} -E env
                   sh -c "$<TARGET_FILE:fixterrain-flightgen> --path orbit --centre 42.5,1.5 --radius 8000 --alt 4500 --speed 250 --duration 660 --quiet --drop-every 97 --nan-at 120.5 --bad-dlc-at 240.5 --duplicate-at 360.5 --gps-jump 500,300 --out ${_soak_dir}/raw.log && $<TARGET_FILE:fixterrain-tools> import --database ${_soak_dir}/mosaic.ftd ${FT_SHARED_DATA_DIR}/N41E001.hgt ${FT_SHARED_DATA_DIR}/N42E001.hgt")
  set_tests_properties(soak_clipmap_inputs PROPERTIES FIXTURES_SETUP soak_clipmap LABELS "soak")
  add_test(NAME soak_clipmap
           COMMAND test_soak ${_soak_dir}/raw.log ${_soak_dir} 50 10 ${_soak_dir}/mosaic.ftd)
  set_tests_properties(soak_clipmap PROPERTIES FIXTURES_REQUIRED soak_clipmap LABELS "soak"
                       TIMEOUT 900)
  if(FIXTERRAIN_SANITIZE)
    set_tests_properties(soak_clipmap PROPERTIES
      ENVIRONMENT_MODIFICATION "${_soak_asan}")
  endif()
  # and pgm reading the same cache (pgm.heights = clipmap)
  if(FIXTERRAIN_WITH_METHOD_PGM)
    file(MAKE_DIRECTORY ${_soak_dir}/pgm)
    add_test(NAME soak_pgm_cache
             COMMAND test_soak ${_soak_dir}/raw.log ${_soak_dir}/pgm 50 10 ${_soak_dir}/mosaic.ftd pgm)
    set_tests_properties(soak_pgm_cache PROPERTIES FIXTURES_REQUIRED soak_clipmap LABELS "soak"
                         TIMEOUT 900)
    if(FIXTERRAIN_SANITIZE)
      set_tests_properties(soak_pgm_cache PROPERTIES ENVIRONMENT_MODIFICATION "${_soak_asan}")
    endif()
  endif()
endif()
