# Error-bounded projective grid (method 'pgrid'): the CPU pieces
# (tests/test_pgrid.c).
ft_add_test(test_pgrid SOURCES test_pgrid.c)
