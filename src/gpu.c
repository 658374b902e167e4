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
