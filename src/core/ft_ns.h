/* ft_ns.h - checked and saturating arithmetic on uint64 nanosecond clocks.
 *
 * Every clock value that comes from outside (a log timestamp, a kernel
 * receive time) or grows with a frame count goes through these, so no clock
 * can wrap past 2^64 ns (584 years) and turn "later" into "earlier":
 *   - ft_ns_add / ft_ns_mul: 1 and the exact result, or 0 when it does not
 *     fit (*out is then UINT64_MAX, a value no caller may use as a time);
 *   - ft_ns_add_sat: a + b, or UINT64_MAX when it does not fit (for "not
 *     before" comparisons, where the end of the clock means "never");
 *   - ft_ns_sub_sat: a - b, or 0 when b > a (an age or a lateness);
 *   - ft_ns_from_ms: a duration in milliseconds (a double from a scene) to
 *     whole nanoseconds, rounded, when it is finite and in [min_ms, max_ms].
 * Header-only, no state. */
#ifndef FT_NS_H
#define FT_NS_H

#include <math.h>
#include <stdint.h>

static inline int ft_ns_add(uint64_t a, uint64_t b, uint64_t *out)
{
    if (a > UINT64_MAX - b) {
        *out = UINT64_MAX;
        return 0;
    }
    *out = a + b;
    return 1;
}

static inline int ft_ns_mul(uint64_t a, uint64_t b, uint64_t *out)
{
    if (b != 0u && a > UINT64_MAX / b) {
        *out = UINT64_MAX;
        return 0;
    }
    *out = a * b;
    return 1;
}

static inline uint64_t ft_ns_add_sat(uint64_t a, uint64_t b)
{
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

static inline uint64_t ft_ns_sub_sat(uint64_t a, uint64_t b)
{
    return a > b ? a - b : 0u;
}

/* max_ms must be at most 1.8e13 (about 584 years) so the result fits. */
static inline int ft_ns_from_ms(double ms, double min_ms, double max_ms, uint64_t *out)
{
    if (!isfinite(ms) || !(ms >= min_ms) || !(ms <= max_ms) || !(max_ms <= 1.8e13) ||
        ms < 0.0) {
        *out = 0u;
        return 0;
    }
    *out = (uint64_t)(ms * 1e6 + 0.5);
    return 1;
}

#endif
