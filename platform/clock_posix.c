/* clock_posix.c - the monotonic clock (never wall time: it can jump). */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "platform_api.h"

uint64_t ft_plat_monotonic_ns(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) {
        return 0;
    }
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

void ft_plat_sleep_ms(uint32_t ms)
{
    struct timespec ts = {(time_t)(ms / 1000u), (long)(ms % 1000u) * 1000000L};
    /* EINTR ends the wait early; callers only use this to hold a frame. */
    (void)nanosleep(&ts, NULL);
}
