/* line_reader.h - text lines from an ft_reader with a fixed buffer.
 *
 * For line-oriented inputs that come from outside (candump logs, waypoint
 * files): a line longer than FT_LINE_READER_LINE_MAX is not truncated into
 * something that might parse; it is reported as overlong (its characters up
 * to the next line end are skipped) so the caller can reject and count it.
 * A NUL byte inside a line is kept (callers reject it). Line numbers start
 * at 1. No heap: the buffer lives in the struct. */
#ifndef FT_LINE_READER_H
#define FT_LINE_READER_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "core/io.h"

#define FT_LINE_READER_LINE_MAX 1024u /* longest line delivered, without its end */
#define FT_LINE_READER_CHUNK 4096u

typedef enum ft_line_kind {
    FT_LINE_OK = 0,  /* line[0..len) holds the line, without \n or \r\n */
    FT_LINE_OVERLONG, /* the line was longer than FT_LINE_READER_LINE_MAX */
    FT_LINE_END       /* no more lines */
} ft_line_kind;

typedef struct ft_line_reader {
    const ft_reader *src;
    char chunk[FT_LINE_READER_CHUNK];
    size_t chunk_len, chunk_pos;
    int eof;
    char line[FT_LINE_READER_LINE_MAX + 1u]; /* NUL-terminated copy */
    size_t len;
    uint64_t line_no; /* number of the line just returned */
} ft_line_reader;

void ft_line_reader_init(ft_line_reader *lr, const ft_reader *src);

/* Next line. Read errors of the source are returned as a status. */
ft_status ft_line_reader_next(ft_line_reader *lr, ft_line_kind *kind, ft_error *err);

#endif
