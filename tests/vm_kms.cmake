# The cockpit display path: DRM/KMS + GBM + EGL.
# kms_pick, kms_cli: on the host (decisions without a device; the errors).
# vm_kms: in the test VM, one boot per display device (bochs-drm, virtio-gpu):
# the frame on KMS, captured by qemu's screendump, against the offscreen
# render; deadline misses of a short run; SIGTERM restores the CRTC
# (tests/vm/kms-test.sh, tests/vm/guest-kms.sh).
if(TARGET ft_platform AND FIXTERRAIN_WITH_KMS)
  ft_add_test(test_kms_pick SOURCES test_kms_pick.c LIBS ft_platform LABELS kms)
  target_include_directories(test_kms_pick PRIVATE ${CMAKE_SOURCE_DIR}/platform)

  add_test(NAME kms_cli COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/test_kms_cli.sh
                                $<TARGET_FILE:fixterrain> ${CMAKE_BINARY_DIR}/test-out/kms_cli)
  set_tests_properties(kms_cli PROPERTIES TIMEOUT 120 LABELS kms)

  if(CMAKE_SYSTEM_NAME STREQUAL "Linux" AND FIXTERRAIN_WITH_PNG AND FIXTERRAIN_WITH_CAN
     AND FIXTERRAIN_WITH_GPIO)
    add_executable(vm_compare_image ${CMAKE_SOURCE_DIR}/tests/vm/compare-image.c)
    target_compile_options(vm_compare_image PRIVATE ${FT_WARNINGS})
    target_link_libraries(vm_compare_image PRIVATE PkgConfig::PNG)
    add_executable(vm_qmp_screendump ${CMAKE_SOURCE_DIR}/tests/vm/qmp-screendump.c)
    target_compile_options(vm_qmp_screendump PRIVATE ${FT_WARNINGS})
    add_executable(vm_kms_crtc ${CMAKE_SOURCE_DIR}/tests/vm/kms-crtc.c)
    target_compile_options(vm_kms_crtc PRIVATE ${FT_WARNINGS})
    target_link_libraries(vm_kms_crtc PRIVATE PkgConfig::DRM)

    add_test(NAME vm_kms
             COMMAND ${CMAKE_SOURCE_DIR}/tests/vm/kms-test.sh ${CMAKE_BINARY_DIR}
                     ${CMAKE_BINARY_DIR}/test-out/vm_kms $<TARGET_FILE:vm_compare_image>
                     $<TARGET_FILE:vm_qmp_screendump> $<TARGET_FILE:vm_kms_crtc>
             WORKING_DIRECTORY ${CMAKE_SOURCE_DIR})
    # RUN_SERIAL: the emulated VM needs both cores to keep the frame period
    set_tests_properties(vm_kms PROPERTIES TIMEOUT 900 LABELS "vm;kms" RUN_SERIAL TRUE
      ENVIRONMENT "FT_VM_DIR=${CMAKE_BINARY_DIR}/vm;FT_VM_TIMEOUT=400")
  endif()
endif()
