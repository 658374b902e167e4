# Fuzz harnesses (tests/fuzz/): the input parsers under libFuzzer.
#
# Every build (any compiler) links each harness with tests/fuzz/fuzz_driver.c
# and registers fuzz_regress_<target>: the harness over every file of its
# seed corpus (tests/fuzz/corpus/<dir>) and of its regression inputs
# (tests/fuzz/regress/<dir>: each crash, hang or leak ever found, kept after
# the fix), label fuzz_regress.
# With -DFIXTERRAIN_FUZZ=ON (clang; tools/test-fuzz.sh) the harnesses are
# libFuzzer binaries instead: fuzz_regress_<target> runs the same inputs
# once (-runs=0), and fuzz_run_<target> (label fuzz) fuzzes for
# FIXTERRAIN_FUZZ_SECONDS, with a 10 s per-input hang limit and an RSS limit;
# new inputs go to <build>/fuzz-corpus/<target>, findings to
# <build>/fuzz-artifacts/<target>/ (copy them into regress/ with the fix).
set(FT_FUZZ_DIR ${CMAKE_SOURCE_DIR}/tests/fuzz)

# target | harness source | corpus and regress directory | compile definitions
set(FT_FUZZ_TARGETS canaero candump scene ftt ftt_crc ftd ftd_crc hgt waypoints)
set(FT_FUZZ_SRC_canaero fuzz_canaero.c)
set(FT_FUZZ_SRC_candump fuzz_candump.c)
set(FT_FUZZ_SRC_scene fuzz_scene.c)
set(FT_FUZZ_SRC_ftt fuzz_ftt.c)
set(FT_FUZZ_SRC_ftt_crc fuzz_ftt.c)
set(FT_FUZZ_SRC_ftd fuzz_ftd.c)
set(FT_FUZZ_SRC_ftd_crc fuzz_ftd.c)
set(FT_FUZZ_SRC_hgt fuzz_hgt.c)
set(FT_FUZZ_SRC_waypoints fuzz_waypoints.c)
set(FT_FUZZ_DATA_ftt_crc ftt)  # both .ftt modes share one corpus and regress dir
set(FT_FUZZ_DEFS_ftt FUZZ_FTT_FIX_CRC=0)
set(FT_FUZZ_DEFS_ftt_crc FUZZ_FTT_FIX_CRC=1)
set(FT_FUZZ_DATA_ftd_crc ftd)  # both .ftd modes share one corpus and regress dir
set(FT_FUZZ_DEFS_ftd FUZZ_FTD_FIX_CRC=0)
set(FT_FUZZ_DEFS_ftd_crc FUZZ_FTD_FIX_CRC=1)

add_custom_target(fuzz_all)
foreach(t ${FT_FUZZ_TARGETS})
  set(data ${t})
  if(DEFINED FT_FUZZ_DATA_${t})
    set(data ${FT_FUZZ_DATA_${t}})
  endif()
  set(corpus ${FT_FUZZ_DIR}/corpus/${data})
  set(regress ${FT_FUZZ_DIR}/regress/${data})
  set(srcs ${FT_FUZZ_DIR}/${FT_FUZZ_SRC_${t}})
  if(t STREQUAL "waypoints")
    list(APPEND srcs ${CMAKE_SOURCE_DIR}/tools/flight_path.c)
  endif()
  if(FIXTERRAIN_FUZZ)
    set(exe fuzz_${t})
    add_executable(${exe} ${srcs})
    target_compile_options(${exe} PRIVATE ${FT_WARNINGS} -fsanitize=fuzzer)
    target_link_options(${exe} PRIVATE -fsanitize=fuzzer)
    target_link_libraries(${exe} PRIVATE ft_core m)
    target_include_directories(${exe} PRIVATE ${FT_FUZZ_DIR} ${CMAKE_SOURCE_DIR}/tools)
    set(work ${CMAKE_BINARY_DIR}/fuzz-corpus/${t})
    set(artifacts ${CMAKE_BINARY_DIR}/fuzz-artifacts/${t})
    file(MAKE_DIRECTORY ${work} ${artifacts})
    add_test(NAME fuzz_regress_${t} COMMAND ${exe} -runs=0 ${corpus} ${regress})
    set_tests_properties(fuzz_regress_${t} PROPERTIES LABELS fuzz_regress TIMEOUT 600)
    # The first directory receives the new inputs, so the source tree stays clean.
    add_test(NAME fuzz_run_${t}
             COMMAND ${exe} -max_total_time=${FIXTERRAIN_FUZZ_SECONDS} -timeout=10
                     -rss_limit_mb=${FIXTERRAIN_FUZZ_RSS_MB} -print_final_stats=1
                     -artifact_prefix=${artifacts}/ ${work} ${corpus} ${regress})
    math(EXPR limit "${FIXTERRAIN_FUZZ_SECONDS} + 120")
    set_tests_properties(fuzz_run_${t} PROPERTIES LABELS fuzz TIMEOUT ${limit})
  else()
    set(exe fuzz_regress_${t})
    ft_add_test(${exe} SOURCES ${srcs} ${FT_FUZZ_DIR}/fuzz_driver.c LIBS m
                ARGS ${corpus} ${regress} LABELS fuzz_regress)
    target_include_directories(${exe} PRIVATE ${FT_FUZZ_DIR} ${CMAKE_SOURCE_DIR}/tools)
  endif()
  if(DEFINED FT_FUZZ_DEFS_${t})
    target_compile_definitions(${exe} PRIVATE ${FT_FUZZ_DEFS_${t}})
  endif()
  add_dependencies(fuzz_all ${exe})
endforeach()

# Writes the binary seeds (tests/fuzz/make_seeds.c); built only on request.
add_executable(fuzz_make_seeds EXCLUDE_FROM_ALL ${FT_FUZZ_DIR}/make_seeds.c)
target_compile_options(fuzz_make_seeds PRIVATE ${FT_WARNINGS})
target_link_libraries(fuzz_make_seeds PRIVATE ft_core m)
