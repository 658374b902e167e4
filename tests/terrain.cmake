# Terrain data: pyramids, void fill, .ftt files, SRTM .hgt, synthetic terrain.
ft_add_test(test_pyramid SOURCES test_pyramid.c)
ft_add_test(test_void_fill SOURCES test_void_fill.c)
ft_add_test(test_terrain_file SOURCES test_terrain_file.c)
ft_add_test(test_hgt SOURCES test_hgt.c)
ft_add_test(test_synth SOURCES test_synth.c)
