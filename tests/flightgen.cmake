# fixterrain-flightgen: flight path -> CANaerospace candump log,
# decoded back through candump.h + canaero.h + pose_state.h.
ft_add_test(test_flightgen SOURCES test_flightgen.c ${CMAKE_SOURCE_DIR}/tools/flight_path.c
            LIBS m)
target_include_directories(test_flightgen PRIVATE ${CMAKE_SOURCE_DIR}/tools)

# The command line: same arguments -> byte-identical file, options reach the
# log, errors name the waypoint file line and leave no log behind.
if(TARGET fixterrain-flightgen)
  set(FG_OUT ${CMAKE_BINARY_DIR}/test-out)
  add_test(NAME test_flightgen_cli_deterministic
    COMMAND sh -c "\"$0\" --path orbit --duration 5 --quiet --out \"$1/fg_a.log\" && \"$0\" --path orbit --duration 5 --quiet --out \"$1/fg_b.log\" && cmp \"$1/fg_a.log\" \"$1/fg_b.log\" && test \"$(wc -l < \"$1/fg_a.log\")\" -eq 2800 && test \"$(\"$0\" --path orbit --duration 5 --quiet --no-velocity | wc -l)\" -eq 2650 && \"$0\" --path valley --duration 10 --start-time 1700000100.5 --iface can1 --nan-at 3 --quiet | grep -c '^(1700000103.500000) can1 137#010200F07FC00000$'"
            $<TARGET_FILE:fixterrain-flightgen> ${FG_OUT})
  set_tests_properties(test_flightgen_cli_deterministic PROPERTIES TIMEOUT 60)
  add_test(NAME test_flightgen_cli_errors
    COMMAND sh -c "printf '# bad\\n0 46.5 8 1000\\n1 46.5 8.001 1000\\n1 46.5 8.002 1000\\n' > \"$1/fg_bad.wp\" && \"$0\" --waypoints \"$1/fg_bad.wp\" --out \"$1/fg_bad.log\" 2>&1 || echo \"rc=$? log=$(test -e \"$1/fg_bad.log\" && echo yes || echo no)\" && \"$0\" --path loop 2>&1 || echo \"rc2=$?\""
            $<TARGET_FILE:fixterrain-flightgen> ${FG_OUT})
  set_tests_properties(test_flightgen_cli_errors PROPERTIES TIMEOUT 60
    PASS_REGULAR_EXPRESSION "fg_bad.wp line 4: time 1 s is not after the previous waypoint's 1 s \\([^\n]*fg_bad.wp line 3\\)\nrc=1 log=no\n[^\n]*unknown path 'loop'[^\n]*\nrc2=2")
  # A path shorter than one log period (times 0 and 1e-300) used to exit 0
  # with an empty log; refused now, and no log is left behind.
  add_test(NAME test_flightgen_cli_degenerate
    COMMAND sh -c "printf '0 46.5 8 1000\\n1e-300 46.5 8 1000\\n' > \"$1/fg_tiny.wp\" && rm -f \"$1/fg_tiny.log\" && { \"$0\" --waypoints \"$1/fg_tiny.wp\" --out \"$1/fg_tiny.log\" 2>&1; echo \"rc=$? log=$(test -e \"$1/fg_tiny.log\" && echo yes || echo no)\"; } && { \"$0\" --path orbit --duration 1e-300 --out \"$1/fg_tiny.log\" 2>&1; echo \"rc2=$?\"; } && { \"$0\" --path valley --nan-at -1 --out \"$1/fg_tiny.log\" 2>&1; echo \"rc3=$?\"; }"
            $<TARGET_FILE:fixterrain-flightgen> ${FG_OUT})
  set_tests_properties(test_flightgen_cli_degenerate PROPERTIES TIMEOUT 60
    PASS_REGULAR_EXPRESSION "fg_tiny.wp: the path lasts 1e-300 s \\([^\n]*fg_tiny.wp line 1 to [^\n]*fg_tiny.wp line 2\\), shorter than one log period of 0.0125 s[^\n]*\nrc=1 log=no\n[^\n]*duration 1e-300 s outside \\[0.0125, 36000\\][^\n]*\nrc2=1\n[^\n]*--nan-at -1 s is outside the logged path \\[0, 120\\) s[^\n]*\nrc3=1")
endif()
