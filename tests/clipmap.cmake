# Geometry clipmaps (method 'clipmap'): the layout, stitch rule and vertex
# mirror on the CPU (tests/test_clipmap.c).
ft_add_test(test_clipmap SOURCES test_clipmap.c)
