# The live pose path in the test VM: fixterrain run on vcan0 + gpio-sim,
# compared with fixterrain replay of the same log (tests/vm/live-test.sh).
# Its scene switches the night palette on a GPIO line.
if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND TARGET fixterrain-flightgen AND FIXTERRAIN_WITH_CAN
   AND FIXTERRAIN_WITH_GPIO AND FIXTERRAIN_WITH_EGL AND FIXTERRAIN_WITH_NIGHT_PALETTE)
  add_executable(vm_compare_live ${CMAKE_SOURCE_DIR}/tests/vm/compare-live.c)
  target_compile_options(vm_compare_live PRIVATE ${FT_WARNINGS})
  target_link_libraries(vm_compare_live PRIVATE m)
  add_executable(vm_hb_sampler ${CMAKE_SOURCE_DIR}/tests/vm/hb-sampler.c)
  target_compile_options(vm_hb_sampler PRIVATE ${FT_WARNINGS})
  add_test(NAME vm_live
           COMMAND ${CMAKE_SOURCE_DIR}/tests/vm/live-test.sh ${CMAKE_BINARY_DIR}
                   ${CMAKE_BINARY_DIR}/test-out/vm_live $<TARGET_FILE:vm_compare_live>
                   $<TARGET_FILE:vm_hb_sampler>
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  # RUN_SERIAL: the emulated VM needs both cores to keep its frame period
  set_tests_properties(vm_live PROPERTIES TIMEOUT 600 LABELS vm RUN_SERIAL TRUE
    ENVIRONMENT "FT_VM_DIR=${CMAKE_BINARY_DIR}/vm;FT_VM_TIMEOUT=400")
endif()
