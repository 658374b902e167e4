# Core tests that need no GPU.
ft_add_test(test_scene SOURCES test_scene.c)
ft_add_test(test_mem_budget SOURCES test_mem_budget.c)
ft_add_test(test_clip_cache SOURCES test_clip_cache.c)
ft_add_test(test_bintree_template SOURCES test_bintree_template.c)
ft_add_test(test_bintree SOURCES test_bintree.c)
# the bintree over the clipmap cache on the CPU: conforming, resident, bounded
ft_add_test(test_bintree_cache SOURCES test_bintree_cache.c)
ft_add_test(test_view_scale SOURCES test_view_scale.c)
ft_add_test(test_pose_feed SOURCES test_pose_feed.c)
ft_add_test(test_degrade SOURCES test_degrade.c)
ft_add_test(test_jobs SOURCES test_jobs.c)
