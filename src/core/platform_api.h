/* platform_api.h - what src/ needs from the OS and drivers, declared here and
 * implemented in platform/ (files, memory reservation, clock, PNG output, GPU
 * contexts). src/ never includes platform/ or OS headers; the dependency runs
 * one way. All functions return ft_status and fill an ft_error on failure. */
#ifndef FT_PLATFORM_API_H
#define FT_PLATFORM_API_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "core/io.h"
#include "core/mem_budget.h"
#include "input/canaero.h"

/* ---- files -------------------------------------------------------------- */
#define FT_PATH_MAX 512u

typedef struct ft_file {
    int fd;          /* -1 when closed */
    uint64_t pos;
    char path[FT_PATH_MAX];
    ft_reader reader; /* valid after ft_plat_file_open_read */
    ft_reader_at reader_at; /* the same file by position (pread), same lifetime */
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
/* Sleeps ns (at most 1 s) on the monotonic clock (a signal does not cut it short). */
void ft_plat_sleep_ns(uint64_t ns);

/* ---- PNG output -------------------------------------------------------------- */
/* rgba: width*height*4 bytes, row 0 = top. libpng and zlib allocate only from
 * the arena's FT_POOL_PNG (scratch, reset after the call): no heap. */
ft_status ft_plat_png_write(const char *path, const uint8_t *rgba, uint32_t width_px,
                            uint32_t height_px, ft_arena *arena, ft_error *err);
/* Reads an RGBA8 PNG into caller storage (tests, golden images); uses the
 * same arena scratch. */
ft_status ft_plat_png_read(const char *path, uint8_t *rgba, size_t cap_bytes, uint32_t *width_px,
                           uint32_t *height_px, ft_arena *arena, ft_error *err);

/* ---- CAN input (platform/can_socketcan.c) ------------------------------------ */
/* One SocketCAN raw socket, non-blocking, with kernel filters for the mapped
 * ids only. Receive timestamps come from the kernel (SO_TIMESTAMPNS or
 * better) converted to the ft_plat_monotonic_ns time base, so they compare
 * directly with frame display times. */
#define FT_CAN_FILTERS_MAX 32u
typedef struct ft_can_port {
    int fd; /* -1 when closed */
    char iface[16];
    uint64_t rx_frames;    /* frames delivered */
    uint64_t rx_dropped;   /* frames the kernel dropped (SO_RXQ_OVFL), if known */
    uint64_t rx_ignored;   /* FD, remote or error frames (counted, not delivered) */
} ft_can_port;

ft_status ft_plat_can_open(ft_can_port *p, const char *iface, const uint16_t *ids,
                           uint32_t id_count, ft_error *err);
/* Reads the frames waiting now (up to cap, never blocks). */
ft_status ft_plat_can_read(ft_can_port *p, ft_can_frame *out, uint32_t cap, uint32_t *got,
                           ft_error *err);
void ft_plat_can_close(ft_can_port *p);

/* ---- GPIO (platform/gpio_gpiod.c, libgpiod 1.6; a 2.x port is that one file) ---- */
#define FT_GPIO_LINES_MAX 8u
#define FT_GPIO_EVENTS_MAX 32u
typedef struct ft_gpio_edge {
    uint32_t slot;  /* index into the `lines` given to ft_plat_gpio_open */
    int rising;     /* 1 rising, 0 falling (physical level) */
    uint64_t t_ns;  /* kernel event time on the ft_plat_monotonic_ns base */
} ft_gpio_edge;

typedef struct ft_gpio_port {
    void *chip;                         /* struct gpiod_chip * */
    void *in_lines[FT_GPIO_LINES_MAX];  /* struct gpiod_line * */
    uint32_t in_count;
    void *out_line;                     /* heartbeat, NULL if none */
    int out_level;
    uint64_t events;                    /* edges delivered */
} ft_gpio_port;

/* Requests the input lines for both-edge events and the output line (may be
 * -1 = none) driven low. Line numbers are offsets on `chip` (name, path or
 * label as libgpiod's lookup accepts). */
ft_status ft_plat_gpio_open(ft_gpio_port *g, const char *chip, const int *in_lines,
                            uint32_t in_count, int out_line, ft_error *err);
/* Current physical levels of the input lines (slot order). */
ft_status ft_plat_gpio_levels(ft_gpio_port *g, int *levels, ft_error *err);
/* Edges waiting now (up to cap, never blocks). */
ft_status ft_plat_gpio_read_edges(ft_gpio_port *g, ft_gpio_edge *out, uint32_t cap,
                                  uint32_t *got, ft_error *err);
ft_status ft_plat_gpio_set_output(ft_gpio_port *g, int level, ft_error *err);
void ft_plat_gpio_close(ft_gpio_port *g);

#endif
