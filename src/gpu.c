#include "gpu.h"

#include <string.h>

static const char *const k_backend_name[FT_BACKEND_COUNT] = {
#define FT_BACKEND_NAME(id, name, what) name,
    FT_BACKEND_LIST(FT_BACKEND_NAME)
#undef FT_BACKEND_NAME
};

const char *ft_backend_name(ft_backend b)
{
    return ((unsigned)b < FT_BACKEND_COUNT) ? k_backend_name[b] : "?";
}

int ft_backend_from_name(const char *name, ft_backend *out)
{
    for (int i = 0; i < FT_BACKEND_COUNT; ++i) {
        if (strcmp(name, k_backend_name[i]) == 0) {
            *out = (ft_backend)i;
            return 1;
        }
    }
    return 0;
}

static const char *const k_display_name[FT_DISPLAY_COUNT] = {
#define FT_DISPLAY_NAME(id, name, what) name,
    FT_DISPLAY_LIST(FT_DISPLAY_NAME)
#undef FT_DISPLAY_NAME
};

const char *ft_display_name(ft_display d)
{
    return ((unsigned)d < FT_DISPLAY_COUNT) ? k_display_name[d] : "?";
}

int ft_display_from_name(const char *name, ft_display *out)
{
    for (int i = 0; i < FT_DISPLAY_COUNT; ++i) {
        if (strcmp(name, k_display_name[i]) == 0) {
            *out = (ft_display)i;
            return 1;
        }
    }
    return 0;
}
