/* line_reader.c - see line_reader.h. */
#include "core/line_reader.h"

#include <string.h>

void ft_line_reader_init(ft_line_reader *lr, const ft_reader *src)
{
    memset(lr, 0, sizeof *lr);
    lr->src = src;
}

static ft_status refill(ft_line_reader *lr, ft_error *err)
{
    size_t got = 0;
    ft_status st = lr->src->read(lr->src->ctx, lr->chunk, sizeof lr->chunk, &got);
    if (st != FT_OK) {
        return ft_fail(err, st, "%s: read failed after line %llu", lr->src->name,
                       (unsigned long long)lr->line_no);
    }
    lr->chunk_len = got;
    lr->chunk_pos = 0;
    if (got < sizeof lr->chunk) {
        lr->eof = 1;
    }
    return FT_OK;
}

ft_status ft_line_reader_next(ft_line_reader *lr, ft_line_kind *kind, ft_error *err)
{
    size_t len = 0;
    int overlong = 0, any = 0;
    /* Bound: every pass consumes one byte or refills; a refill that yields
     * nothing sets eof. The source is finite (size_bytes), so this ends. */
    for (;;) {
        if (lr->chunk_pos == lr->chunk_len) {
            if (lr->eof) {
                break;
            }
            ft_status st = refill(lr, err);
            if (st != FT_OK) {
                return st;
            }
            if (lr->chunk_len == 0u) {
                break;
            }
        }
        const char c = lr->chunk[lr->chunk_pos++];
        any = 1;
        if (c == '\n') {
            break;
        }
        if (len < FT_LINE_READER_LINE_MAX) {
            lr->line[len++] = c;
        } else {
            overlong = 1;
        }
    }
    if (!any) {
        *kind = FT_LINE_END;
        lr->len = 0;
        lr->line[0] = '\0';
        return FT_OK;
    }
    if (len > 0u && lr->line[len - 1u] == '\r') {
        --len;
    }
    lr->line[len] = '\0';
    lr->len = len;
    lr->line_no += 1u;
    *kind = overlong ? FT_LINE_OVERLONG : FT_LINE_OK;
    return FT_OK;
}
