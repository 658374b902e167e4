#include "core/invariant.h"

#include <stdio.h>
#include <stdlib.h>

static ft_fault g_fault;

void ft_fault_raise(const char *what, const char *file, int line, int abort_now)
{
    if (g_fault.count < UINT32_MAX) {
        g_fault.count += 1u;
    }
    if (!g_fault.latched) {
        g_fault.latched = 1;
        g_fault.what = what;
        g_fault.file = file;
        g_fault.line = line;
    }
    if (abort_now) {
        fprintf(stderr, "fixterrain: INTERNAL FAULT: %s (%s:%d)\n", what, file, line);
        abort();
    }
}

const ft_fault *ft_fault_latched(void)
{
    return g_fault.latched ? &g_fault : NULL;
}

const char *ft_fault_text(char *buf)
{
    (void)snprintf(buf, FT_FAULT_TEXT_MAX, "INTERNAL FAULT %s",
                   g_fault.latched ? g_fault.what : "");
    return buf;
}

void ft_fault_clear_for_test(void)
{
    g_fault = (ft_fault){0};
}
