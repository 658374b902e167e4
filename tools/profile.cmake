# profile.cmake - a lean build sized to one scene ("leave out what a scene
# does not need"): cmake -DFIXTERRAIN_PROFILE=config/minimal.ini
#
# Forces every FIXTERRAIN_WITH_* option (the rows of tools/build_options.cmake):
# first all OFF, then ON what the scene uses: its method (scene.method),
# backend (scene.backend), display (scene.display), pose inputs (build.inputs:
# replay, can, gpio), PNG output (build.png), error metric (metric.enabled)
# and the presentation parts: relative colouring (presentation.colouring),
# horizon, haze (haze_km), ground grid (grid_m), night palette (palette =
# night, or a gpio.night_line). Everything else stays OFF,
# the GDAL import tool and any option this file does not know about
# included. Included by CMakeLists.txt before option().
#
# One parser: the scene is read by the runtime's own reader and parser
# (src/core/scene.c via tools/scene_options.c, compiled for the build host here
# and run at once), so a scene the runtime would refuse fails the configure
# with the runtime's message, keys absent from the file take the runtime's
# defaults, and every value means what it means at run time (metric.enabled
# is 0 or 1, build.inputs a comma list of whole words).
include(${CMAKE_CURRENT_LIST_DIR}/build_options.cmake)  # FT_BUILD_OPTIONS
set(FIXTERRAIN_PROFILE "" CACHE FILEPATH "scene file whose needs decide the build options")
if(FIXTERRAIN_PROFILE)
  if(NOT EXISTS "${FIXTERRAIN_PROFILE}")
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: no such scene file: ${FIXTERRAIN_PROFILE}")
  endif()
  if(CMAKE_CROSSCOMPILING AND NOT CMAKE_CROSSCOMPILING_EMULATOR)
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: the scene is read by the runtime's parser, built "
                        "and run at configure time; a cross build needs "
                        "CMAKE_CROSSCOMPILING_EMULATOR (or set the FIXTERRAIN_WITH_* options)")
  endif()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(FT_PROFILE_INIH REQUIRED inih)
  # the parser and what it links, nothing else (no GL, no driver)
  set(_p_sources tools/scene_options.c src/core/scene.c src/core/output.c src/input/canaero.c src/input/pose_state.c
                 src/core/mem_budget.c src/core/ft_status.c src/core/invariant.c src/core/io.c
                 platform/file_posix.c)
  list(TRANSFORM _p_sources PREPEND "${CMAKE_SOURCE_DIR}/")
  set(_p_dir "${CMAKE_BINARY_DIR}/profile")
  set(_p_tool "${_p_dir}/fixterrain-scene-options${CMAKE_EXECUTABLE_SUFFIX}")
  try_compile(_p_built "${_p_dir}/build"
    SOURCES ${_p_sources}
    CMAKE_FLAGS "-DINCLUDE_DIRECTORIES=${CMAKE_SOURCE_DIR}/src;${FT_PROFILE_INIH_INCLUDE_DIRS}"
    LINK_LIBRARIES ${FT_PROFILE_INIH_LINK_LIBRARIES} m
    C_STANDARD 11 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF
    OUTPUT_VARIABLE _p_log
    COPY_FILE "${_p_tool}")
  if(NOT _p_built)
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: building the scene parser (tools/scene_options.c) "
                        "failed:\n${_p_log}")
  endif()
  execute_process(COMMAND ${CMAKE_CROSSCOMPILING_EMULATOR} "${_p_tool}" "${FIXTERRAIN_PROFILE}"
                  RESULT_VARIABLE _p_rc OUTPUT_VARIABLE _p_out ERROR_VARIABLE _p_err)
  if(NOT _p_rc EQUAL 0)
    string(STRIP "${_p_err}" _p_err)
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: the runtime refuses this scene:\n  ${_p_err}")
  endif()
  # an edited scene (or parser) configures again
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${FIXTERRAIN_PROFILE}"
               ${_p_sources})
  string(REGEX MATCHALL "[a-z_]+=[a-z0-9-]*" _p_pairs "${_p_out}")
  foreach(_kv IN LISTS _p_pairs)
    string(REGEX MATCH "^([a-z_]+)=(.*)$" _kv "${_kv}")
    set(_p_${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
  endforeach()
  foreach(_k method backend display inputs_replay inputs_can inputs_gpio png metric relative
             horizon haze ground_grid night_palette)
    if(NOT DEFINED _p_${_k})
      message(FATAL_ERROR "FIXTERRAIN_PROFILE: the scene parser did not say '${_k}':\n${_p_out}")
    endif()
  endforeach()

  macro(_ft_force opt value)
    set(FIXTERRAIN_WITH_${opt} ${value} CACHE BOOL "set by FIXTERRAIN_PROFILE" FORCE)
  endmacro()
  # every option OFF first: a row added to the table and not mapped below is
  # left out of a profile build, never left ON from its default
  foreach(_opt IN LISTS FT_BUILD_OPTIONS)
    _ft_force(${_opt} OFF)
  endforeach()
  string(TOUPPER "METHOD_${_p_method}" _m)
  if(NOT _p_method MATCHES "^[a-z]+$" OR NOT _m IN_LIST FT_BUILD_OPTIONS)
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: scene.method '${_p_method}' has no build option")
  endif()
  _ft_force(${_m} ON)
  if(_p_backend MATCHES "^egl-gles[23]$")
    _ft_force(EGL ON)
  elseif(_p_backend STREQUAL "osmesa")
    _ft_force(OSMESA ON)
  else()
    message(FATAL_ERROR "FIXTERRAIN_PROFILE: scene.backend '${_p_backend}' has no build option")
  endif()
  if(_p_display STREQUAL "x11")
    _ft_force(X11 ON)
  elseif(_p_display STREQUAL "kms")
    _ft_force(KMS ON)
  endif()
  # the parser's 0/1 answers, never CMake truthiness of the file's text
  foreach(_pair "CAN;inputs_can" "GPIO;inputs_gpio" "PNG;png" "REFERENCE;metric"
                "RELATIVE_COLOURING;relative" "HORIZON;horizon" "HAZE;haze"
                "GROUND_GRID;ground_grid" "NIGHT_PALETTE;night_palette")
    list(GET _pair 0 _opt)
    list(GET _pair 1 _k)
    if(_p_${_k} STREQUAL "1")
      _ft_force(${_opt} ON)
    endif()
  endforeach()
  message(STATUS "fixterrain profile ${FIXTERRAIN_PROFILE} (read by the runtime's parser): "
                 "method ${_p_method}, backend ${_p_backend}, display ${_p_display}, inputs "
                 "replay ${_p_inputs_replay} can ${_p_inputs_can} gpio ${_p_inputs_gpio}, "
                 "png ${_p_png}, metric ${_p_metric}, relative colouring ${_p_relative}, "
                 "horizon ${_p_horizon}, haze ${_p_haze}, ground grid ${_p_ground_grid}, "
                 "night palette ${_p_night_palette}")
endif()
