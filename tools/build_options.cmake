# build_options.cmake - the one list of the FIXTERRAIN_WITH_* build options.
#
# Every place that needs the whole list takes it from here, so adding an
# option is one row and cannot leave a copy behind:
#   CMakeLists.txt         declares each option (name, doc, default), applies
#                          NEEDS, and sets FT_WITH_<NAME>=0|1 on ft_core;
#   tools/profile.cmake    turns every option OFF before forcing what the
#                          scene uses (an option it does not know stays OFF);
#   tests/test_lean_build.sh, tools/build-matrix.sh
#                          get "every option OFF" / "every option ON" from
#                          this file run as a script (below);
#   tests/scripts/check_build_options.cmake (test build_options_table)
#                          fails when the C code uses an FT_WITH_* with no
#                          row here, or a row is used by no C code.
#
# One row per option (the FT_WITH_* definitions follow the rows' order):
#   ft_build_option(NAME DEFAULT "doc" [NEEDS OTHER LEFT_OUT "what is lost"])
# NAME is the suffix of FIXTERRAIN_WITH_<NAME> and FT_WITH_<NAME>. NEEDS names an
# earlier row: when NAME is ON and OTHER is OFF, the configure says
# "FIXTERRAIN_WITH_<NAME> needs FIXTERRAIN_WITH_<OTHER>: <LEFT_OUT> is left out"
# and builds without NAME (the cache keeps the user's choice).
#
# As a script it prints every option set to one value, on one line:
#   cmake -DFT_OPTIONS_VALUE=OFF -P tools/build_options.cmake
#   -> -DFIXTERRAIN_WITH_EGL=OFF -DFIXTERRAIN_WITH_X11=OFF ...
include_guard(GLOBAL)
cmake_policy(VERSION 3.25)  # run with -P there is no project to set it

set(FT_BUILD_OPTIONS "")
function(ft_build_option name default doc)
  cmake_parse_arguments(PARSE_ARGV 3 _o "" "NEEDS;LEFT_OUT" "")
  if(_o_UNPARSED_ARGUMENTS OR NOT name MATCHES "^[A-Z][A-Z0-9_]*$"
     OR NOT default MATCHES "^(ON|OFF)$" OR doc STREQUAL "")
    message(FATAL_ERROR "tools/build_options.cmake: bad row '${name}' (want NAME ON|OFF \"doc\" "
                        "[NEEDS OTHER LEFT_OUT \"what\"]): ${ARGV}")
  endif()
  if(name IN_LIST FT_BUILD_OPTIONS)
    message(FATAL_ERROR "tools/build_options.cmake: option ${name} has two rows")
  endif()
  # an earlier row, so one pass over the table settles every NEEDS
  if(DEFINED _o_NEEDS AND (NOT _o_NEEDS IN_LIST FT_BUILD_OPTIONS OR NOT DEFINED _o_LEFT_OUT))
    message(FATAL_ERROR "tools/build_options.cmake: ${name} NEEDS '${_o_NEEDS}', which must be "
                        "an earlier row, and LEFT_OUT says what a build without it loses")
  endif()
  set(FT_BUILD_OPTION_${name}_DEFAULT "${default}" PARENT_SCOPE)
  set(FT_BUILD_OPTION_${name}_DOC "${doc}" PARENT_SCOPE)
  set(FT_BUILD_OPTION_${name}_NEEDS "${_o_NEEDS}" PARENT_SCOPE)
  set(FT_BUILD_OPTION_${name}_LEFT_OUT "${_o_LEFT_OUT}" PARENT_SCOPE)
  set(FT_BUILD_OPTIONS ${FT_BUILD_OPTIONS} ${name} PARENT_SCOPE)
endfunction()

# ---- the table ---------------------------------------------------------------
ft_build_option(EGL ON "EGL backends (egl-gles3, egl-gles2)")
# X11 is only compiled inside the EGL backend (platform/gpu_egl.c): a build
# without EGL leaves it out and says so, like KMS.
ft_build_option(X11 ON "EGL window-surface path on X11 (scene.display = x11; needs EGL)"
                NEEDS EGL LEFT_OUT "the X11 window path")
ft_build_option(KMS ON "full-screen DRM/KMS display, EGL on GBM (scene.display = kms; needs EGL)"
                NEEDS EGL LEFT_OUT "the KMS display")
ft_build_option(OSMESA ON "OSMesa offscreen backend (removed from Mesa >= 25.1)")
ft_build_option(METHOD_BRUTE ON "terrain method 'brute' (full-grid mesh)")
ft_build_option(METHOD_BINTREE ON "terrain method 'bintree' (crack-free triangle tiles)")
ft_build_option(METHOD_PGM ON "terrain method 'pgm' (persistent grid mapping)")
ft_build_option(METHOD_PGRID ON "terrain method 'pgrid' (error-bounded projective grid + ray casting)")
ft_build_option(METHOD_CLIPMAP ON "terrain method 'clipmap' (geometry clipmaps over the clip cache)")
ft_build_option(REFERENCE ON "CPU reference ray caster and error metric")
ft_build_option(PNG ON "PNG output (libpng)")
ft_build_option(RELATIVE_COLOURING ON "presentation.colouring = relative (TAWS-style bands)")
ft_build_option(HORIZON ON "presentation.horizon = 1 (the conformal zero-pitch line)")
ft_build_option(HAZE ON "presentation.haze_km > 0 (distance haze towards the sky colour)")
ft_build_option(GROUND_GRID ON "presentation.grid_m > 0 (ground grid, a low-level motion cue)")
ft_build_option(NIGHT_PALETTE ON "presentation.palette = night and gpio.night_line (night palette)")
ft_build_option(GDAL_TOOLS ON "'fixterrain import' (GDAL; tools only, never the runtime)")
ft_build_option(CAN ON "live CAN input over SocketCAN (can.interface)")
ft_build_option(GPIO ON "discrete inputs and heartbeat output over libgpiod 1.6 (gpio.*)")

# ---- run as a script: print every option set to FT_OPTIONS_VALUE -------------
if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT FT_OPTIONS_VALUE MATCHES "^(ON|OFF)$")
    message(FATAL_ERROR "usage: cmake -DFT_OPTIONS_VALUE=ON|OFF -P ${CMAKE_CURRENT_LIST_FILE}")
  endif()
  set(_args "")
  foreach(_n IN LISTS FT_BUILD_OPTIONS)
    string(APPEND _args " -DFIXTERRAIN_WITH_${_n}=${FT_OPTIONS_VALUE}")
  endforeach()
  string(STRIP "${_args}" _args)
  # message() writes to stderr; the shell callers read stdout
  execute_process(COMMAND ${CMAKE_COMMAND} -E echo "${_args}")
endif()
