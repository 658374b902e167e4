/* io.h - byte streams that src/ reads and writes through; platform/ implements
 * them over files (src/ never calls the OS). Tests implement them over memory. */
#ifndef FT_IO_H
#define FT_IO_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"

typedef struct ft_reader {
    void *ctx;
    /* Reads up to `bytes` into dst, sets *got. *got < bytes only at end of data. */
    ft_status (*read)(void *ctx, void *dst, size_t bytes, size_t *got);
    uint64_t size_bytes; /* total size of the stream, known up front */
    const char *name;    /* for error messages (file path) */
} ft_reader;

typedef struct ft_writer {
    void *ctx;
    ft_status (*write)(void *ctx, const void *src, size_t bytes);
    const char *name;
} ft_writer;

/* Random access (the tiled terrain database reads one tile where it lies).
 * Reads up to `bytes` at `offset` into dst, sets *got; *got < bytes only when
 * the data ends first. Keeps no position: calls do not depend on each other. */
typedef struct ft_reader_at {
    void *ctx;
    ft_status (*read_at)(void *ctx, uint64_t offset, void *dst, size_t bytes, size_t *got);
    uint64_t size_bytes; /* total size, known up front */
    const char *name;    /* for error messages (file path) */
} ft_reader_at;

/* Reads exactly `bytes` at `offset` or fails with FT_ERR_TRUNCATED naming
 * the stream (an offset + bytes past size_bytes is refused before reading). */
ft_status ft_read_at_exact(const ft_reader_at *r, uint64_t offset, void *dst, size_t bytes,
                           ft_error *err);

/* Reads exactly `bytes` or fails with FT_ERR_TRUNCATED naming the stream. */
ft_status ft_read_exact(const ft_reader *r, void *dst, size_t bytes, ft_error *err);

/* A reader over a memory block (tests, embedded data). */
typedef struct ft_mem_reader {
    const uint8_t *data;
    size_t size_bytes;
    size_t pos;
} ft_mem_reader;
void ft_mem_reader_init(ft_reader *r, ft_mem_reader *m, const void *data, size_t size_bytes,
                        const char *name);

/* Positional reads over the same memory block (pos unused). */
void ft_mem_reader_at_init(ft_reader_at *r, ft_mem_reader *m, const void *data,
                           size_t size_bytes, const char *name);

/* A writer into a caller-owned memory block; fails FT_ERR_OVERSIZED when full. */
typedef struct ft_mem_writer {
    uint8_t *data;
    size_t cap_bytes;
    size_t pos;
} ft_mem_writer;
void ft_mem_writer_init(ft_writer *w, ft_mem_writer *m, void *data, size_t cap_bytes,
                        const char *name);

#endif
