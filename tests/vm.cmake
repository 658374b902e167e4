# Tests that need real vcan interfaces and simulated GPIO lines run in a small
# qemu VM (tests/vm/README.md). The host kernel has neither CAN nor GPIO
# support, so a missing qemu/kernel/headers is a failure, never a skip:
# tools/install-deps.sh vm (part of `all`) installs what they need.
# gpio-sim and the initramfs are built by run-vm.sh into ${CMAKE_BINARY_DIR}/vm
# on first use and reused while their inputs are unchanged.
if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
  # AF_CAN raw-socket check run inside the guest (built here, on the host).
  add_executable(vm_can_socket_check ${CMAKE_SOURCE_DIR}/tests/vm/can-socket-check.c)
  target_compile_options(vm_can_socket_check PRIVATE ${FT_WARNINGS})

  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/test-out/vm_smoke)
  add_test(NAME vm_smoke
           COMMAND ${CMAKE_SOURCE_DIR}/tests/vm/run-vm.sh
                   "tests/vm/guest-smoke.sh $<TARGET_FILE:vm_can_socket_check>"
                   ${CMAKE_BINARY_DIR}/test-out/vm_smoke
           WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
  set_tests_properties(vm_smoke PROPERTIES
    TIMEOUT 400
    LABELS vm
    ENVIRONMENT "FT_VM_DIR=${CMAKE_BINARY_DIR}/vm;FT_VM_TIMEOUT=300")

  # The platform CAN and GPIO code (platform/can_socketcan.c, gpio_gpiod.c)
  # against vcan0 and gpio-sim: one boot, tests/vm/guest-platform.sh.
  if(TARGET ft_platform AND FIXTERRAIN_WITH_CAN AND FIXTERRAIN_WITH_GPIO)
    add_executable(vm_platform_check ${CMAKE_SOURCE_DIR}/tests/vm/platform-check.c)
    target_compile_options(vm_platform_check PRIVATE ${FT_WARNINGS})
    target_link_libraries(vm_platform_check PRIVATE ft_platform)

    file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/test-out/vm_platform)
    add_test(NAME vm_platform
             COMMAND ${CMAKE_SOURCE_DIR}/tests/vm/run-vm.sh
                     "tests/vm/guest-platform.sh $<TARGET_FILE:vm_platform_check>"
                     ${CMAKE_BINARY_DIR}/test-out/vm_platform
             WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
    set_tests_properties(vm_platform PROPERTIES
      TIMEOUT 400
      LABELS vm
      ENVIRONMENT "FT_VM_DIR=${CMAKE_BINARY_DIR}/vm;FT_VM_TIMEOUT=300")
  endif()
endif()
