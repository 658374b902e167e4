# ftt_cli_reject.cmake - `fixterrain render` on .ftt files whose crc is right
# but whose content is impossible (written by test_terrain_file): each must
# fail with the reader's message, and no --stats file may hold a non-finite
# number (JSON has no inf/nan). The intact file renders and its stats are
# finite. Run: cmake -DFIXTERRAIN=bin -DOUT=dir -P ftt_cli_reject.cmake
set(cases
  "ftt_minmax_zeroed.ftt|min/max pyramid level 0 node (x 0, y 0)"
  "ftt_minmax_reversed.ftt|min/max pyramid level 0 node (x 0, y 0): min"
  "ftt_spacing_1e305.ftt|cell_x_m 1e+305 m is outside 0.001..200000 m"
  "ftt_spacing_1e308.ftt|cell_y_m 1e+308 m is outside"
  "ftt_deg_origin_1e15.ftt|origin_x (longitude) 1e+15 deg is outside -360..360 deg")

function(check_stats_finite path)
  if(EXISTS "${path}")
    file(READ "${path}" json)
    string(TOLOWER "${json}" lower)
    if(lower MATCHES "[^a-z_](inf|nan)[^a-z_]")
      message(FATAL_ERROR "${path} holds a non-finite number: ${json}")
    endif()
  endif()
endfunction()

foreach(c ${cases})
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 file)
  list(GET parts 1 want)
  set(stats "${OUT}/${file}.stats.json")
  file(REMOVE "${stats}")
  execute_process(COMMAND "${FIXTERRAIN}" render --dem "${OUT}/${file}" --backend osmesa
                          --size 64x48 --out "${OUT}/${file}.png" --stats "${stats}" --quiet
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "render accepted ${file}: ${out}${err}")
  endif()
  string(FIND "${out}${err}" "${want}" at)
  if(at LESS 0)
    message(FATAL_ERROR "render of ${file} failed without naming the problem (\"${want}\"): ${out}${err}")
  endif()
  check_stats_finite("${stats}")
  message(STATUS "${file}: refused (${rc})")
endforeach()

set(stats "${OUT}/ftt_good.stats.json")
file(REMOVE "${stats}")
execute_process(COMMAND "${FIXTERRAIN}" render --dem "${OUT}/ftt_good.ftt" --backend osmesa
                        --size 64x48 --out "${OUT}/ftt_good.png" --stats "${stats}" --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render of the intact ftt_good.ftt failed (${rc}): ${out}${err}")
endif()
if(NOT EXISTS "${stats}")
  message(FATAL_ERROR "render wrote no ${stats}")
endif()
check_stats_finite("${stats}")
message(STATUS "ftt_good.ftt: rendered, stats finite")
