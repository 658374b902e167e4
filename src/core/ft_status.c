#include "core/ft_status.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const k_status_text[FT_STATUS_COUNT] = {
#define FT_STATUS_TEXT(name, text) text,
    FT_STATUS_LIST(FT_STATUS_TEXT)
#undef FT_STATUS_TEXT
};

const char *ft_status_str(ft_status s)
{
    if ((int)s < 0 || s >= FT_STATUS_COUNT) {
        return "unknown status";
    }
    return k_status_text[s];
}

ft_status ft_fail(ft_error *err, ft_status s, const char *fmt, ...)
{
    if (err != NULL) {
        va_list ap;
        err->status = s;
        va_start(ap, fmt);
        (void)vsnprintf(err->text, sizeof err->text, fmt, ap);
        va_end(ap);
    }
    return s;
}
