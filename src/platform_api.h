/* platform_api.h - what src/ needs from the OS and drivers, declared here and
 * implemented in platform/ (files, memory reservation, clock, PNG output, GPU
 * contexts). src/ never includes platform/ or OS headers; the dependency runs
 * one way. All functions return ft_status and fill an ft_error on failure. */
#ifndef FT_PLATFORM_API_H
#define FT_PLATFORM_API_H

#include <stddef.h>
#include <stdint.h>

#include "ft_status.h"
#include "io.h"
#include "mem_budget.h"

/* ---- files -------------------------------------------------------------- */
#define FT_PATH_MAX 512u

typedef struct ft_file {
    int fd;          /* -1 when closed */
    uint64_t pos;
    char path[FT_PATH_MAX];
    ft_reader reader; /* valid after ft_plat_file_open_read */
    ft_writer writer; /* valid after ft_plat_file_open_write */
} ft_file;

ft_status ft_plat_file_open_read(ft_file *f, const char *path, ft_error *err);
/* Writes go to "<path>.tmp" and are renamed over path by finish: a crash or
 * error never leaves a half-written file under the final name. */
ft_status ft_plat_file_open_write(ft_file *f, const char *path, ft_error *err);
ft_status ft_plat_file_finish_write(ft_file *f, ft_error *err);
void ft_plat_file_close(ft_file *f); /* closes; drops an unfinished .tmp */

/* Reads a whole small file (scene text) into buf, NUL-terminated. Fails with
 * FT_ERR_OVERSIZED naming the limit when it does not fit in cap-1 bytes. */
ft_status ft_plat_file_read_text(const char *path, char *buf, size_t cap, size_t *len,
                                 ft_error *err);

/* ---- memory: the one init-time reservation --------------------------------- */
/* Maps `bytes` of zeroed, pre-faulted memory (64-byte aligned). Not the heap. */
ft_status ft_plat_mem_reserve(size_t bytes, void **out, ft_error *err);
void ft_plat_mem_release(void *p, size_t bytes);

/* ---- clock ------------------------------------------------------------------ */
uint64_t ft_plat_monotonic_ns(void);
void ft_plat_sleep_ms(uint32_t ms);

/* ---- PNG output -------------------------------------------------------------- */
/* rgba: width*height*4 bytes, row 0 = top. libpng and zlib allocate only from
 * the arena's FT_POOL_PNG (scratch, reset after the call): no heap. */
ft_status ft_plat_png_write(const char *path, const uint8_t *rgba, uint32_t width_px,
                            uint32_t height_px, ft_arena *arena, ft_error *err);
/* Reads an RGBA8 PNG into caller storage (tests, golden images); uses the
 * same arena scratch. */
ft_status ft_plat_png_read(const char *path, uint8_t *rgba, size_t cap_bytes, uint32_t *width_px,
                           uint32_t *height_px, ft_arena *arena, ft_error *err);

#endif
