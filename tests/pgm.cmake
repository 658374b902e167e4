# Persistent grid mapping (method 'pgm'): the mapping math on the CPU
# (tests/test_pgm.c), and the method on real contexts over a real DEM
# (tests/test_pgm_gl.c).
ft_add_test(test_pgm SOURCES test_pgm.c)
