# Pose input: CANaerospace decoding, candump logs, pose assembly
# and attitude prediction. Pure core, no GPU.
ft_add_test(test_pose_state SOURCES test_pose_state.c)
ft_add_test(test_canaero SOURCES test_canaero.c)
ft_add_test(test_candump SOURCES test_candump.c)
