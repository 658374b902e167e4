/* clock_posix.c - the monotonic clock (never wall time: it can jump). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <time.h>

#include "core/platform_api.h"

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

void ft_plat_sleep_ns(uint64_t ns)
{
    /* An absolute deadline on the monotonic clock, so EINTR (a signal, e.g.
     * SIGTERM asking the loop to stop) just resumes the same wait; the loop
     * checks its stop flag right after. Bounded: at most 1 s per call. */
    if (ns > 1000000000ull) {
        ns = 1000000000ull;
    }
    struct timespec now;
    if (clock_gettime(CLOCK_MONOTONIC, &now) != 0) {
        return;
    }
    uint64_t t = (uint64_t)now.tv_sec * 1000000000ull + (uint64_t)now.tv_nsec + ns;
    struct timespec until = {(time_t)(t / 1000000000ull), (long)(t % 1000000000ull)};
    for (int i = 0; i < 8; ++i) {
        int rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, NULL);
        if (rc == 0 || rc != EINTR) {
            return;
        }
    }
}
