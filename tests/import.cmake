if(TARGET ft_tools)
  pkg_check_modules(GDAL_TEST REQUIRED IMPORTED_TARGET gdal)
  ft_add_test(test_import SOURCES test_import.c LIBS ft_tools ft_platform PkgConfig::GDAL_TEST)
endif()
