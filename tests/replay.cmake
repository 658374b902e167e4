# fixterrain replay end to end (tests/test_replay.c) on a real context.
if(TARGET ft_app AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_METHOD_BRUTE)
  add_executable(test_replay test_replay.c ${CMAKE_SOURCE_DIR}/tools/flight_path.c)
  target_compile_options(test_replay PRIVATE ${FT_WARNINGS})
  target_include_directories(test_replay PRIVATE ${CMAKE_SOURCE_DIR}/tests ${CMAKE_SOURCE_DIR}/tools)
  target_compile_definitions(test_replay PRIVATE FT_TEST_OUT_DIR="${CMAKE_BINARY_DIR}/test-out")
  target_link_libraries(test_replay PRIVATE ft_app m)
  add_test(NAME replay_faults COMMAND test_replay)
endif()

# The two logs that used to hang `replay` (a timestamp going backwards after a
# huge one; a display clock that would wrap past 2^64 ns), through the CLI:
# it finishes within the timeout, and the summary and the stats file count
# the rejected timestamps.
if(TARGET fixterrain)
  set(RP_OUT ${CMAKE_BINARY_DIR}/test-out)
  add_test(NAME replay_timestamps_cli
    COMMAND sh -c "mkdir -p \"$1\" && printf '(18446744014.000000) vcan0 137#01020000A6652EE1\\n(1.000000) vcan0 137#01020001A6652EE1\\n' > \"$1/rp_back.log\" && printf '(18446744013.709551) vcan0 137#0102000040400000\\n(18446744073.709551) vcan0 137#0102000140400000\\n' > \"$1/rp_wrap.log\" && \"$0\" replay --log \"$1/rp_back.log\" --stats \"$1/rp_back.json\" 2>&1 && \"$0\" replay --log \"$1/rp_wrap.log\" --stats \"$1/rp_wrap.json\" 2>&1 && tr -d ' \\n' < \"$1/rp_back.json\" && tr -d ' \\n' < \"$1/rp_wrap.json\""
    $<TARGET_FILE:fixterrain> ${RP_OUT})
  set_tests_properties(replay_timestamps_cli PROPERTIES TIMEOUT 60
    PASS_REGULAR_EXPRESSION "rp_back.log:2: timestamp 1.000000 s is earlier than the previous accepted frame's 18446744014.000000 s\n[^\n]*1 frames over[^\n]*\nreplay: timestamps rejected: 1 backwards, 0 out of range[^\n]*\n.*rp_wrap.log:2: timestamp 18446744073.709551 s is past the end of the replay timeline[^\n]*\n[^\n]*1 frames over[^\n]*\nreplay: timestamps rejected: 0 backwards, 1 out of range.*\"timestamps_backwards\":1,\"timestamps_out_of_range\":0,\"can_frames\":1,.*\"frames\":1,.*\"timestamps_backwards\":0,\"timestamps_out_of_range\":1,\"can_frames\":1,.*\"frames\":1,")
endif()

# A log whose positions do not lie over the terrain: the replay draws it
# (sky) and says so, per frame counted; over the terrain it says nothing.
if(TARGET fixterrain AND TARGET fixterrain-flightgen AND FIXTERRAIN_WITH_METHOD_BINTREE)
  add_test(NAME replay_off_terrain
    COMMAND sh -c "set -e; out=\"$2/replay-off\"; rm -rf \"$out\"; mkdir -p \"$out\"; \"$1\" --path orbit --centre 46.6,8.2 --duration 1 --out \"$out/o.log\" --quiet; \"$0\" replay --log \"$out/o.log\" --size 64x48 --method bintree --stats \"$out/on.json\" > /dev/null 2> \"$out/on.err\"; grep -q '\"frames_off_terrain\": 0' \"$out/on.json\"; test ! -s \"$out/on.err\"; \"$1\" --path orbit --centre 46.5,8 --duration 1 --out \"$out/sw.log\" --quiet; \"$0\" replay --log \"$out/sw.log\" --size 64x48 --method bintree --stats \"$out/off.json\" > /dev/null 2> \"$out/off.err\"; cat \"$out/off.err\"; grep -q 'warning: [1-9][0-9]* of [0-9]* frames were drawn from a position that does not lie over the terrain (synthetic terrain) (lat 46.500000..46.776271, lon 8.000000..8.401350)' \"$out/off.err\"; grep -q '\"frames_off_terrain\": [1-9]' \"$out/off.json\""
    $<TARGET_FILE:fixterrain> $<TARGET_FILE:fixterrain-flightgen> ${CMAKE_BINARY_DIR}/test-out)
  set_tests_properties(replay_off_terrain PROPERTIES TIMEOUT 300)
endif()
