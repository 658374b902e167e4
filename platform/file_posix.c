/* file_posix.c - files for src/ through ft_reader/ft_writer (POSIX fds). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/platform_api.h"

/* Bounded retry count for EINTR so no loop can spin forever. */
#define FT_IO_RETRY_MAX 64

/* Reads until `bytes` are in or the file ends, retrying an interrupted
 * call. offset < 0: from the file position (read); else at offset (pread:
 * no shared position, so positional reads never disturb the sequential
 * reader of the same file). */
static ft_status fd_read_fully(int fd, int64_t offset, void *dst, size_t bytes, size_t *got)
{
    size_t done = 0;
    int retries = 0;
    while (done < bytes) {
        const ssize_t n = (offset < 0)
                              ? read(fd, (char *)dst + done, bytes - done)
                              : pread(fd, (char *)dst + done, bytes - done,
                                      (off_t)((uint64_t)offset + done));
        if (n < 0) {
            if (errno == EINTR && ++retries < FT_IO_RETRY_MAX) {
                continue;
            }
            *got = done;
            return FT_ERR_IO;
        }
        if (n == 0) {
            break; /* end of file */
        }
        done += (size_t)n;
    }
    *got = done;
    return FT_OK;
}

static ft_status fd_read(void *ctx, void *dst, size_t bytes, size_t *got)
{
    ft_file *f = (ft_file *)ctx;
    const ft_status st = fd_read_fully(f->fd, -1, dst, bytes, got);
    if (st == FT_OK) {
        f->pos += *got;
    }
    return st;
}

static ft_status fd_read_at(void *ctx, uint64_t offset, void *dst, size_t bytes, size_t *got)
{
    const ft_file *f = (const ft_file *)ctx;
    *got = 0;
    if (offset > (uint64_t)INT64_MAX - (uint64_t)bytes) {
        return FT_ERR_ARG;
    }
    return fd_read_fully(f->fd, (int64_t)offset, dst, bytes, got);
}

static ft_status fd_write(void *ctx, const void *src, size_t bytes)
{
    ft_file *f = (ft_file *)ctx;
    size_t done = 0;
    int retries = 0;
    while (done < bytes) {
        ssize_t n = write(f->fd, (const char *)src + done, bytes - done);
        if (n < 0) {
            if (errno == EINTR && ++retries < FT_IO_RETRY_MAX) {
                continue;
            }
            return FT_ERR_IO;
        }
        done += (size_t)n;
    }
    f->pos += done;
    return FT_OK;
}

ft_status ft_plat_file_open_read(ft_file *f, const char *path, ft_error *err)
{
    struct stat st;
    memset(f, 0, sizeof *f);
    f->fd = -1;
    if (strlen(path) >= sizeof f->path) {
        return ft_fail(err, FT_ERR_ARG, "path longer than %u bytes: %.60s...", FT_PATH_MAX, path);
    }
    (void)snprintf(f->path, sizeof f->path, "%s", path);
    f->fd = open(path, O_RDONLY | O_CLOEXEC);
    if (f->fd < 0) {
        return ft_fail(err, FT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    }
    if (fstat(f->fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        (void)close(f->fd);
        f->fd = -1;
        return ft_fail(err, FT_ERR_IO, "%s: not a regular file", path);
    }
    f->reader.ctx = f;
    f->reader.read = fd_read;
    f->reader.size_bytes = (uint64_t)st.st_size;
    f->reader.name = f->path;
    f->reader_at.ctx = f;
    f->reader_at.read_at = fd_read_at;
    f->reader_at.size_bytes = (uint64_t)st.st_size;
    f->reader_at.name = f->path;
    return FT_OK;
}

ft_status ft_plat_file_open_write(ft_file *f, const char *path, ft_error *err)
{
    char tmp[FT_PATH_MAX + 8];
    memset(f, 0, sizeof *f);
    f->fd = -1;
    if (strlen(path) >= sizeof f->path) {
        return ft_fail(err, FT_ERR_ARG, "path longer than %u bytes", FT_PATH_MAX);
    }
    (void)snprintf(f->path, sizeof f->path, "%s", path);
    (void)snprintf(tmp, sizeof tmp, "%s.tmp", path);
    f->fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (f->fd < 0) {
        return ft_fail(err, FT_ERR_IO, "%s: cannot create: %s", tmp, strerror(errno));
    }
    f->writer.ctx = f;
    f->writer.write = fd_write;
    f->writer.name = f->path;
    return FT_OK;
}

ft_status ft_plat_file_finish_write(ft_file *f, ft_error *err)
{
    char tmp[FT_PATH_MAX + 8];
    (void)snprintf(tmp, sizeof tmp, "%s.tmp", f->path);
    if (f->fd < 0) {
        return ft_fail(err, FT_ERR_ARG, "%s: not open for writing", f->path);
    }
    int rc = close(f->fd);
    f->fd = -1;
    if (rc != 0) {
        (void)unlink(tmp);
        return ft_fail(err, FT_ERR_IO, "%s: close failed: %s", tmp, strerror(errno));
    }
    if (rename(tmp, f->path) != 0) {
        (void)unlink(tmp);
        return ft_fail(err, FT_ERR_IO, "%s: rename failed: %s", f->path, strerror(errno));
    }
    f->writer.write = NULL;
    return FT_OK;
}

void ft_plat_file_close(ft_file *f)
{
    if (f->fd >= 0) {
        (void)close(f->fd);
        f->fd = -1;
        if (f->writer.write != NULL) {
            char tmp[FT_PATH_MAX + 8];
            (void)snprintf(tmp, sizeof tmp, "%s.tmp", f->path);
            (void)unlink(tmp);
        }
    }
}

ft_status ft_plat_file_read_text(const char *path, char *buf, size_t cap, size_t *len,
                                 ft_error *err)
{
    ft_file f;
    ft_status s = ft_plat_file_open_read(&f, path, err);
    if (s != FT_OK) {
        return s;
    }
    if (cap == 0 || f.reader.size_bytes > (uint64_t)(cap - 1u)) {
        ft_plat_file_close(&f);
        return ft_fail(err, FT_ERR_OVERSIZED, "%s: %llu bytes; the limit is %zu bytes", path,
                       (unsigned long long)f.reader.size_bytes, cap ? cap - 1u : 0u);
    }
    size_t n = (size_t)f.reader.size_bytes;
    s = ft_read_exact(&f.reader, buf, n, err);
    ft_plat_file_close(&f);
    if (s != FT_OK) {
        return s;
    }
    buf[n] = '\0';
    if (memchr(buf, '\0', n) != NULL) {
        return ft_fail(err, FT_ERR_FORMAT, "%s: contains a NUL byte (not a text file)", path);
    }
    *len = n;
    return FT_OK;
}
