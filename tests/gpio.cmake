# Discrete inputs (GPIO): debouncing is pure core logic, tested on the host.
# The libgpiod and SocketCAN platform code is tested in the VM (tests/vm.cmake,
# vm_platform).
ft_add_test(test_debounce SOURCES test_debounce.c)
