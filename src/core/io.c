#include "core/io.h"

#include <string.h>

ft_status ft_read_exact(const ft_reader *r, void *dst, size_t bytes, ft_error *err)
{
    size_t got = 0;
    ft_status s = r->read(r->ctx, dst, bytes, &got);
    if (s != FT_OK) {
        return ft_fail(err, s, "%s: read of %zu bytes failed", r->name, bytes);
    }
    if (got != bytes) {
        return ft_fail(err, FT_ERR_TRUNCATED, "%s: truncated (wanted %zu bytes, got %zu)",
                       r->name, bytes, got);
    }
    return FT_OK;
}

static ft_status mem_read(void *ctx, void *dst, size_t bytes, size_t *got)
{
    ft_mem_reader *m = (ft_mem_reader *)ctx;
    size_t left = m->size_bytes - m->pos;
    size_t n = (bytes < left) ? bytes : left;
    if (n > 0) {
        memcpy(dst, m->data + m->pos, n);
    }
    m->pos += n;
    *got = n;
    return FT_OK;
}

void ft_mem_reader_init(ft_reader *r, ft_mem_reader *m, const void *data, size_t size_bytes,
                        const char *name)
{
    m->data = (const uint8_t *)data;
    m->size_bytes = size_bytes;
    m->pos = 0;
    r->ctx = m;
    r->read = mem_read;
    r->size_bytes = size_bytes;
    r->name = name;
}

static ft_status mem_write(void *ctx, const void *src, size_t bytes)
{
    ft_mem_writer *m = (ft_mem_writer *)ctx;
    if (bytes > m->cap_bytes - m->pos) {
        return FT_ERR_OVERSIZED;
    }
    memcpy(m->data + m->pos, src, bytes);
    m->pos += bytes;
    return FT_OK;
}

void ft_mem_writer_init(ft_writer *w, ft_mem_writer *m, void *data, size_t cap_bytes,
                        const char *name)
{
    m->data = (uint8_t *)data;
    m->cap_bytes = cap_bytes;
    m->pos = 0;
    w->ctx = m;
    w->write = mem_write;
    w->name = name;
}

ft_status ft_read_at_exact(const ft_reader_at *r, uint64_t offset, void *dst, size_t bytes,
                           ft_error *err)
{
    const char *name = (r->name != NULL) ? r->name : "(unnamed)";
    if (offset > r->size_bytes || (uint64_t)bytes > r->size_bytes - offset) {
        return ft_fail(err, FT_ERR_TRUNCATED,
                       "%s: truncated (wanted %zu bytes at offset %llu, the data is %llu bytes)",
                       name, bytes, (unsigned long long)offset,
                       (unsigned long long)r->size_bytes);
    }
    size_t got = 0;
    ft_status s = r->read_at(r->ctx, offset, dst, bytes, &got);
    if (s != FT_OK) {
        return ft_fail(err, s, "%s: read of %zu bytes at offset %llu failed", name, bytes,
                       (unsigned long long)offset);
    }
    if (got != bytes) {
        return ft_fail(err, FT_ERR_TRUNCATED,
                       "%s: truncated (wanted %zu bytes at offset %llu, got %zu)", name, bytes,
                       (unsigned long long)offset, got);
    }
    return FT_OK;
}

static ft_status mem_read_at(void *ctx, uint64_t offset, void *dst, size_t bytes, size_t *got)
{
    const ft_mem_reader *m = (const ft_mem_reader *)ctx;
    *got = 0;
    if (offset >= (uint64_t)m->size_bytes) {
        return FT_OK;
    }
    size_t left = m->size_bytes - (size_t)offset;
    size_t n = (bytes < left) ? bytes : left;
    if (n > 0) {
        memcpy(dst, m->data + offset, n);
    }
    *got = n;
    return FT_OK;
}

void ft_mem_reader_at_init(ft_reader_at *r, ft_mem_reader *m, const void *data,
                           size_t size_bytes, const char *name)
{
    m->data = (const uint8_t *)data;
    m->size_bytes = size_bytes;
    m->pos = 0;
    r->ctx = m;
    r->read_at = mem_read_at;
    r->size_bytes = size_bytes;
    r->name = name;
}
