# check_build_options.cmake - the table of build options
# (tools/build_options.cmake) against the code that uses them. Fails when
#  - the C code (src/, platform/, tools/, tests/) tests an FT_WITH_<NAME>
#    with no row: the build defines it nowhere, so `#if FT_WITH_NAME` is
#    silently 0 (-Wundef catches it only where it is compiled);
#  - a row's FT_WITH_<NAME> is used by no C code: an option that changes
#    nothing in the program;
#  - a CMake file, shell script or README names a FIXTERRAIN_WITH_<NAME> with
#    no row (a misspelt option in a test's condition is simply never true).
# Run: cmake -DSRC=source-dir -P check_build_options.cmake
cmake_policy(VERSION 3.25)
if(NOT IS_DIRECTORY "${SRC}")
  message(FATAL_ERROR "usage: cmake -DSRC=source-dir -P ${CMAKE_CURRENT_LIST_FILE}")
endif()
include("${SRC}/tools/build_options.cmake")

file(GLOB_RECURSE _c_files LIST_DIRECTORIES false
     "${SRC}/src/*.c" "${SRC}/src/*.h" "${SRC}/platform/*.c" "${SRC}/platform/*.h"
     "${SRC}/tools/*.c" "${SRC}/tools/*.h" "${SRC}/tests/*.c" "${SRC}/tests/*.h")
# the project's folders only (a build dir inside the tree holds generated files)
set(_text_files "${SRC}/CMakeLists.txt" "${SRC}/README.md")
foreach(_d src platform shaders tests config tools docs)
  file(GLOB_RECURSE _more LIST_DIRECTORIES false "${SRC}/${_d}/*.cmake" "${SRC}/${_d}/*.sh"
       "${SRC}/${_d}/*.md" "${SRC}/${_d}/CMakeLists.txt")
  list(APPEND _text_files ${_more})
endforeach()

set(_errors "")
set(_used "")
foreach(_f IN LISTS _c_files)
  file(STRINGS "${_f}" _lines REGEX "FT_WITH_[A-Z0-9_]+")
  foreach(_line IN LISTS _lines)
    string(REGEX MATCHALL "FT_WITH_[A-Z0-9_]+" _names "${_line}")
    # a name ending in _ is the prefix of a composed one (FT_WITH_${opt})
    list(FILTER _names EXCLUDE REGEX "_$")
    foreach(_n IN LISTS _names)
      string(REGEX REPLACE "^FT_WITH_" "" _n "${_n}")
      list(APPEND _used ${_n})
      if(NOT _n IN_LIST FT_BUILD_OPTIONS)
        file(RELATIVE_PATH _rel "${SRC}" "${_f}")
        list(APPEND _errors "${_rel}: FT_WITH_${_n} has no row in tools/build_options.cmake")
      endif()
    endforeach()
  endforeach()
endforeach()
foreach(_n IN LISTS FT_BUILD_OPTIONS)
  if(NOT _n IN_LIST _used)
    list(APPEND _errors "tools/build_options.cmake: row ${_n}: FT_WITH_${_n} is used by no C code")
  endif()
endforeach()
foreach(_f IN LISTS _text_files)
  file(STRINGS "${_f}" _lines REGEX "FIXTERRAIN_WITH_[A-Z0-9_]+")
  foreach(_line IN LISTS _lines)
    string(REGEX MATCHALL "FIXTERRAIN_WITH_[A-Z0-9_]+" _names "${_line}")
    list(FILTER _names EXCLUDE REGEX "_$")
    foreach(_n IN LISTS _names)
      string(REGEX REPLACE "^FIXTERRAIN_WITH_" "" _n "${_n}")
      if(NOT _n IN_LIST FT_BUILD_OPTIONS)
        file(RELATIVE_PATH _rel "${SRC}" "${_f}")
        list(APPEND _errors "${_rel}: FIXTERRAIN_WITH_${_n} has no row in tools/build_options.cmake")
      endif()
    endforeach()
  endforeach()
endforeach()

list(REMOVE_DUPLICATES _errors)
list(LENGTH FT_BUILD_OPTIONS _rows)
list(LENGTH _c_files _nc)
list(LENGTH _text_files _nt)
if(_errors)
  list(JOIN _errors "\n  " _msg)
  message(FATAL_ERROR "build options table and code disagree:\n  ${_msg}")
endif()
message(STATUS "build options: ${_rows} rows, each used by the C code (${_nc} files); no "
               "FT_WITH_* or FIXTERRAIN_WITH_* without a row (and ${_nt} CMake/shell/md files)")
