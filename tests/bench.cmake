# fixterrain bench: the plot rasteriser and Pareto front (unit
# test), and a smoke run of `fixterrain bench` on a real DEM whose CSV and
# PNG are checked by test_plot --check-bench (skipped without ../shared/data;
# the bintree rows carry the oracle's columns, tools/bench_oracle.h).
ft_add_test(test_plot SOURCES test_plot.c ${CMAKE_SOURCE_DIR}/tools/plot.c LIBS m)
target_include_directories(test_plot PRIVATE ${CMAKE_SOURCE_DIR}/tools)

if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BRUTE
   AND FIXTERRAIN_WITH_METHOD_BINTREE)
  # brute + 2 bintree settings (+ 1 pgm grid when pgm is built), 6 frames of
  # the valley path at 160x120, the error on frames 0 and 5.
  set(FT_BENCH_METHODS brute,bintree)
  set(FT_BENCH_ROWS "brute:default" "bintree:template_k=3 tau_px=1" "bintree:template_k=3 tau_px=4")
  if(FIXTERRAIN_WITH_METHOD_PGM)
    set(FT_BENCH_METHODS brute,bintree,pgm)
    list(APPEND FT_BENCH_ROWS "pgm:grid=64x128")
  endif()
  add_test(NAME bench_smoke
    COMMAND sh -c "test -f \"$1/N42E001.hgt\" || { echo 'no ../shared/data: skipped'; exit 77; }; out=\"$2/bench\"; rm -rf \"$out\"; mkdir -p \"$out\" && \"$0\" bench --scene \"$3/config/pyrenees.ini\" --dem \"$1/N42E001.hgt\" --methods $4 --path valley --size 160x120 --frames 6 --settings 'bintree.tau_px=1,4;bintree.template_k=3' --settings pgm.grid=64x128 --csv \"$out/bench.csv\" --plot \"$out/bench.png\" --report \"$out/bench.md\" && cat \"$out/bench.csv\" && grep -q '^| bintree | template_k=3 tau_px=1 |' \"$out/bench.md\" && grep -q '| x brute | oracle ms (x) |' \"$out/bench.md\" && grep -q 'max error <= 1 px' \"$out/bench.md\" && head -c 8 \"$out/bench.png\" | od -An -c | grep -q 'P   N   G' && tp=\"$5\" && shift 5 && exec \"$tp\" --check-bench \"$out/bench.csv\" \"$out/bench.png\" 6 2 \"$@\""
            $<TARGET_FILE:fixterrain> ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out
            ${CMAKE_SOURCE_DIR} ${FT_BENCH_METHODS} $<TARGET_FILE:test_plot> ${FT_BENCH_ROWS})
  set_tests_properties(bench_smoke PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)

  # usage errors: exit 2 with the reason, before anything runs
  add_test(NAME bench_cli_errors
    COMMAND sh -c "\"$0\" bench --settings 'bintree.tau_px=' 2>&1; echo rc=$?; \"$0\" bench --path nowhere.wp 2>&1; echo rc=$?; \"$0\" bench --settings 'gpu.x=1' 2>&1; echo rc=$?; \"$0\" bench --settings 'pgm.grid=12' --methods pgm 2>&1; echo rc=$?; \"$0\" bench --help | head -1"
            $<TARGET_FILE:fixterrain>)
  set_tests_properties(bench_cli_errors PROPERTIES TIMEOUT 60
    PASS_REGULAR_EXPRESSION "bad key or values[^\n]*\nrc=2\n[^\n]*nowhere.wp: not a built-in path[^\n]*\nrc=2\n[^\n]*'gpu' is not a method\nrc=2\n[^\n]*expected COLSxROWS\nrc=2\nusage: fixterrain bench")
endif()

# --settings refuses what it cannot honour; the CSV quotes text fields
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BRUTE
   AND FIXTERRAIN_WITH_METHOD_BINTREE AND FIXTERRAIN_WITH_METHOD_PGM)
  add_test(NAME bench_settings
           COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_bench_settings.sh $<TARGET_FILE:fixterrain>
                      $<TARGET_FILE:test_plot> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(bench_settings PROPERTIES TIMEOUT 120)
endif()

# tools/pgrid-report.sh (the issue-4 report matrix): two grids x uniform/view
# x ray casting off/on + brute force, 2 frames at 96x72; every row present
# with sane numbers (test_plot --check-bench). Skipped without ../shared/data.
if(TARGET fixterrain AND FIXTERRAIN_WITH_REFERENCE AND FIXTERRAIN_WITH_METHOD_BRUTE
   AND FIXTERRAIN_WITH_METHOD_PGRID)
  set(FT_PGRID_REPORT_ROWS "brute:default")
  foreach(_g 150x600 430x430)
    foreach(_d uniform view)
      foreach(_rc 0 1)
        list(APPEND FT_PGRID_REPORT_ROWS "pgrid:grid=${_g} gamma_px=1 distribution=${_d} ray_casting=${_rc}")
      endforeach()
    endforeach()
  endforeach()
  add_test(NAME pgrid_report_smoke
    COMMAND sh -c "test -f \"$1/N42E001.hgt\" || { echo 'no ../shared/data: skipped'; exit 77; }; out=\"$2/pgrid-report\"; rm -rf \"$out\"; FIXTERRAIN=\"$0\" GRIDS=150x600,430x430 \"$3/tools/pgrid-report.sh\" \"$3/config/pyrenees.ini\" \"$out\" --dem \"$1/N42E001.hgt\" --path valley --size 96x72 --frames 2 --quiet && test -s \"$out/pgrid.md\" && tp=\"$4\" && shift 4 && exec \"$tp\" --check-bench \"$out/pgrid.csv\" \"$out/pgrid.png\" 2 1 \"$@\""
            $<TARGET_FILE:fixterrain> ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out
            ${CMAKE_SOURCE_DIR} $<TARGET_FILE:test_plot> ${FT_PGRID_REPORT_ROWS})
  set_tests_properties(pgrid_report_smoke PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endif()

# A newcomer's bench: the embedded default scene (its measurement budgets are
# 0: the bench sizes its own) with a DEM its pose does not lie over (the
# paths move to the terrain's centre, and the bench says so).
if(TARGET fixterrain AND FIXTERRAIN_WITH_METHOD_BINTREE AND FIXTERRAIN_WITH_REFERENCE)
  add_test(NAME bench_newcomer
    COMMAND sh -c "test -f \"$1/N42E001.hgt\" || { echo 'no ../shared/data: skipped'; exit 77; }; out=\"$2/bench-newcomer\"; rm -rf \"$out\"; mkdir -p \"$out\" && \"$0\" bench --dem \"$1/N42E001.hgt\" --methods bintree --settings 'bintree.tau_px=2;bintree.template_k=3' --path hover --frames 2 --size 160x120 --csv \"$out/b.csv\" --plot \"$out/b.png\" --quiet 2> \"$out/err.txt\" && cat \"$out/err.txt\" && grep -q 'paths centred on the terrain.s centre (--centre 42.500000,1.500000)' \"$out/err.txt\" && grep -q '^bintree,template_k=3 tau_px=2,hover,2,' \"$out/b.csv\""
            $<TARGET_FILE:fixterrain> ${FT_SHARED_DATA_DIR} ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(bench_newcomer PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endif()
