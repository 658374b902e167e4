/* ft_status.h - one error contract for the whole renderer.
 *
 * Every fallible function returns ft_status. The list below is an X-macro so
 * the enum and its human-readable strings cannot drift apart. Inputs are
 * validated in release builds too: these are data errors, not programmer
 * errors. A detail message (which pool, which line, which numbers) goes into
 * the per-thread-free, caller-owned ft_error record below, never to stdout. */
#ifndef FT_STATUS_H
#define FT_STATUS_H

#include <stddef.h>

#define FT_STATUS_LIST(X)                                                        \
    X(FT_OK, "ok")                                                               \
    X(FT_ERR_ARG, "invalid argument")                                            \
    X(FT_ERR_BUDGET, "a static budget is exceeded")                              \
    X(FT_ERR_ARENA_LOCKED, "memory requested after init (arena is locked)")      \
    X(FT_ERR_IO, "file input/output failed")                                     \
    X(FT_ERR_FORMAT, "malformed input data")                                     \
    X(FT_ERR_TRUNCATED, "input data is truncated")                               \
    X(FT_ERR_OVERSIZED, "input data is larger than declared or allowed")         \
    X(FT_ERR_CHECKSUM, "checksum mismatch")                                      \
    X(FT_ERR_VERSION, "unsupported format version")                              \
    X(FT_ERR_CONFIG, "invalid scene configuration")                              \
    X(FT_ERR_UNSUPPORTED, "not supported by this build or device")               \
    X(FT_ERR_GPU, "GPU/driver error")                                            \
    X(FT_ERR_NUMERIC, "non-finite or out-of-range number")

typedef enum ft_status {
#define FT_STATUS_ENUM(name, text) name,
    FT_STATUS_LIST(FT_STATUS_ENUM)
#undef FT_STATUS_ENUM
    FT_STATUS_COUNT
} ft_status;

const char *ft_status_str(ft_status s);

/* Caller-owned detail record: functions that can fail for data reasons
 * write one sentence here (which input, which field, which numbers).
 * May be NULL when the caller does not want details. */
#define FT_ERROR_TEXT_MAX 320
typedef struct ft_error {
    ft_status status;
    char text[FT_ERROR_TEXT_MAX];
} ft_error;

/* Sets err (if non-NULL) and returns s, so call sites read:
 *   return ft_fail(err, FT_ERR_FORMAT, "%s: bad magic", path); */
ft_status ft_fail(ft_error *err, ft_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#endif
