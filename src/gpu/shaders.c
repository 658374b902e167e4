#include "gpu/shaders.h"

#include <string.h>

const char *ft_shader_find(const char *name)
{
    for (unsigned i = 0; i < ft_shader_source_count; ++i) {
        if (strcmp(ft_shader_sources[i].name, name) == 0) {
            return ft_shader_sources[i].text;
        }
    }
    return NULL;
}
