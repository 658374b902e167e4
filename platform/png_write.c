/* png_write.c - PNG output and input through libpng, with every libpng and
 * zlib allocation served from the arena's FT_POOL_PNG scratch pool (reset on
 * every exit path): writing a frame touches no heap.
 *
 * libpng reports errors by longjmp; locals that change after setjmp and are
 * read after a longjmp are volatile. Files are written to "<path>.tmp" and
 * renamed, so a failed write never leaves a half file under the final name. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <string.h>

#include "core/platform_api.h"

typedef struct png_io {
    ft_arena *arena;
    size_t asked_bytes;   /* total requested, for the budget message */
    int out_of_budget;
    char message[160];    /* libpng's own error text */
} png_io;

static png_voidp arena_malloc(png_structp png, png_alloc_size_t bytes)
{
    png_io *io = (png_io *)png_get_mem_ptr(png);
    void *p = NULL;
    io->asked_bytes += (size_t)bytes;
    if (ft_arena_take_scratch(io->arena, FT_POOL_PNG, (size_t)bytes, &p) != FT_OK) {
        io->out_of_budget = 1;
        return NULL; /* libpng turns this into png_error -> longjmp */
    }
    return p;
}

static void arena_free(png_structp png, png_voidp p)
{
    (void)png;
    (void)p; /* the whole scratch is reset after the call */
}

static void on_error(png_structp png, png_const_charp msg)
{
    png_io *io = (png_io *)png_get_error_ptr(png);
    (void)snprintf(io->message, sizeof io->message, "%s", msg);
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings do not stop the image */
}

static ft_status budget_fail(const png_io *io, const char *path, ft_error *err)
{
    return ft_fail(err, FT_ERR_BUDGET,
                   "%s: libpng/zlib asked for %zu bytes in all; pool 'png_bytes' budgets %zu "
                   "(raise budget.png_bytes)",
                   path, io->asked_bytes, io->arena->pools[FT_POOL_PNG].budget_bytes);
}

ft_status ft_plat_png_write(const char *path, const uint8_t *rgba, uint32_t width_px,
                            uint32_t height_px, ft_arena *arena, ft_error *err)
{
    char tmp[FT_PATH_MAX + 8];
    png_io io;
    volatile ft_status status = FT_OK; /* written after setjmp */
    memset(&io, 0, sizeof io);
    io.arena = arena;
    if (strlen(path) >= FT_PATH_MAX) {
        return ft_fail(err, FT_ERR_ARG, "PNG path longer than %u bytes", FT_PATH_MAX);
    }
    (void)snprintf(tmp, sizeof tmp, "%s.tmp", path);
    const size_t mark = ft_arena_mark(arena, FT_POOL_PNG);
    FILE *volatile f = fopen(tmp, "wb");
    if (f == NULL) {
        return ft_fail(err, FT_ERR_IO, "%s: cannot create: %s", tmp, strerror(errno));
    }
    png_structp png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning,
                                                &io, arena_malloc, arena_free);
    png_infop info = (png != NULL) ? png_create_info_struct(png) : NULL;
    if (png == NULL || info == NULL) {
        status = io.out_of_budget ? budget_fail(&io, path, err)
                                  : ft_fail(err, FT_ERR_IO, "%s: libpng init failed", path);
        goto cleanup;
    }
    if (setjmp(png_jmpbuf(png))) {
        status = io.out_of_budget ? budget_fail(&io, path, err)
                                  : ft_fail(err, FT_ERR_IO, "%s: PNG write failed: %s", path,
                                            io.message);
        goto cleanup;
    }
    png_init_io(png, f);
    png_set_compression_level(png, 6);
    png_set_IHDR(png, info, width_px, height_px, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (uint32_t y = 0; y < height_px; ++y) {
        png_write_row(png, rgba + (size_t)y * width_px * 4u);
    }
    png_write_end(png, NULL);

cleanup:
    if (png != NULL) {
        png_destroy_write_struct(&png, info != NULL ? &info : NULL);
    }
    ft_arena_reset(arena, FT_POOL_PNG, mark);
    if (fclose(f) != 0 && status == FT_OK) {
        status = ft_fail(err, FT_ERR_IO, "%s: close failed: %s", tmp, strerror(errno));
    }
    if (status == FT_OK && rename(tmp, path) != 0) {
        status = ft_fail(err, FT_ERR_IO, "%s: rename failed: %s", path, strerror(errno));
    }
    if (status != FT_OK) {
        (void)remove(tmp);
    }
    return status;
}

ft_status ft_plat_png_read(const char *path, uint8_t *rgba, size_t cap_bytes, uint32_t *width_px,
                           uint32_t *height_px, ft_arena *arena, ft_error *err)
{
    png_io io;
    volatile ft_status status = FT_OK; /* written after setjmp */
    memset(&io, 0, sizeof io);
    io.arena = arena;
    const size_t mark = ft_arena_mark(arena, FT_POOL_PNG);
    FILE *volatile f = fopen(path, "rb");
    if (f == NULL) {
        return ft_fail(err, FT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    }
    png_structp png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &io, on_error, on_warning,
                                               &io, arena_malloc, arena_free);
    png_infop info = (png != NULL) ? png_create_info_struct(png) : NULL;
    if (png == NULL || info == NULL) {
        status = io.out_of_budget ? budget_fail(&io, path, err)
                                  : ft_fail(err, FT_ERR_IO, "%s: libpng init failed", path);
        goto cleanup;
    }
    if (setjmp(png_jmpbuf(png))) {
        status = io.out_of_budget ? budget_fail(&io, path, err)
                                  : ft_fail(err, FT_ERR_FORMAT, "%s: not a readable PNG: %s",
                                            path, io.message);
        goto cleanup;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    uint32_t w = png_get_image_width(png, info);
    uint32_t h = png_get_image_height(png, info);
    /* Everything becomes 8-bit RGBA. */
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != (size_t)w * 4u) {
        status = ft_fail(err, FT_ERR_FORMAT, "%s: cannot convert to RGBA8", path);
        goto cleanup;
    }
    if (w == 0 || h == 0 || (size_t)w * h > cap_bytes / 4u) {
        status = ft_fail(err, FT_ERR_OVERSIZED, "%s: %ux%u RGBA needs more than the %zu bytes given",
                         path, w, h, cap_bytes);
        goto cleanup;
    }
    for (uint32_t y = 0; y < h; ++y) {
        png_read_row(png, rgba + (size_t)y * w * 4u, NULL);
    }
    png_read_end(png, NULL);
    *width_px = w;
    *height_px = h;

cleanup:
    if (png != NULL) {
        png_destroy_read_struct(&png, info != NULL ? &info : NULL, NULL);
    }
    ft_arena_reset(arena, FT_POOL_PNG, mark);
    (void)fclose(f);
    return status;
}
