#include "core/output.h"

#include <stdlib.h>
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

int ft_display_parse(const char *text, ft_display *out, char *device, size_t device_cap)
{
    static const char kms_prefix[] = "kms:";
    if (device == NULL || device_cap == 0u) {
        return 0;
    }
    device[0] = '\0';
    if (strncmp(text, kms_prefix, sizeof kms_prefix - 1u) == 0) {
        const char *path = text + sizeof kms_prefix - 1u;
        size_t n = strlen(path);
        if (n == 0u || n >= device_cap || strncmp(path, "/dev/", 5) != 0) {
            return 0;
        }
        memcpy(device, path, n + 1u);
        *out = FT_DISPLAY_KMS;
        return 1;
    }
    return ft_display_from_name(text, out);
}

static int parse_dim(const char *p, const char **end_out, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end = NULL;
    if (*p < '0' || *p > '9') {
        return 0;
    }
    unsigned long v = strtoul(p, &end, 10);
    if (end == p || v < lo || v > hi) {
        return 0;
    }
    *out = (uint32_t)v;
    *end_out = end;
    return 1;
}

int ft_display_mode_parse(const char *text, ft_display_mode *out)
{
    ft_display_mode m;
    const char *p = text;
    memset(&m, 0, sizeof m);
    if (strcmp(text, "preferred") == 0) {
        m.preferred = 1;
        *out = m;
        return 1;
    }
    if (!parse_dim(p, &p, 1u, 16384u, &m.width_px) || *p != 'x' ||
        !parse_dim(p + 1, &p, 1u, 16384u, &m.height_px)) {
        return 0;
    }
    if (*p == '@' && !parse_dim(p + 1, &p, 1u, 1000u, &m.refresh_hz)) {
        return 0;
    }
    if (*p != '\0') {
        return 0;
    }
    *out = m;
    return 1;
}
