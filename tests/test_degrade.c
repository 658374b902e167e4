/* test_degrade.c - the degradation policy: raise on a heavy frame, lower
 * only after a calm stretch, hold in between (hysteresis), bounded scale. */
#include "lod/degrade.h"
#include "test_util.h"

int main(void)
{
    ft_degrade d;
    ft_degrade_init(&d, 1, 10.0, 8.0);
    CHECK_NEAR(d.scale, 1.0, 0.0);
    /* a heavy frame raises at once */
    CHECK(ft_degrade_frame(&d, 9.5) == 1);
    CHECK_NEAR(d.scale, 1.5, 1e-12);
    CHECK(d.over_budget == 0u);
    /* a miss raises again and is counted */
    CHECK(ft_degrade_frame(&d, 12.0) == 1);
    CHECK_NEAR(d.scale, 2.25, 1e-12);
    CHECK(d.over_budget == 1u);
    /* between the bands: no change however long */
    for (int i = 0; i < 100; ++i) CHECK(ft_degrade_frame(&d, 7.0) == 0);
    CHECK_NEAR(d.scale, 2.25, 1e-12);
    /* calm frames lower only after FT_DEGRADE_CALM_FRAMES in a row */
    for (uint32_t i = 0; i + 1u < FT_DEGRADE_CALM_FRAMES; ++i) CHECK(ft_degrade_frame(&d, 3.0) == 0);
    CHECK(ft_degrade_frame(&d, 7.0) == 0); /* the streak is broken */
    for (uint32_t i = 0; i + 1u < FT_DEGRADE_CALM_FRAMES; ++i) CHECK(ft_degrade_frame(&d, 3.0) == 0);
    CHECK(ft_degrade_frame(&d, 3.0) == 1);
    CHECK_NEAR(d.scale, 1.5, 1e-12);
    /* bounded above and below */
    for (int i = 0; i < 50; ++i) (void)ft_degrade_frame(&d, 100.0);
    CHECK_NEAR(d.scale, 8.0, 0.0);
    for (int i = 0; i < 1000; ++i) (void)ft_degrade_frame(&d, 0.1);
    CHECK_NEAR(d.scale, 1.0, 0.0);
    CHECK(d.raises > 0u && d.lowers > 0u);
    /* disabled: counts misses, never changes the scale */
    ft_degrade_init(&d, 0, 10.0, 8.0);
    CHECK(ft_degrade_frame(&d, 50.0) == 0 && d.scale == 1.0 && d.over_budget == 1u);
    return ft_test_result("test_degrade");
}
