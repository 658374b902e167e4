# CPU reference ray caster and the screen-space error metric.
if(FIXTERRAIN_WITH_REFERENCE)
  ft_add_test(test_reference SOURCES test_reference.c)
  ft_add_test(test_metric SOURCES test_metric.c)
endif()
