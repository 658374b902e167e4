/* candump.h - one line of a `candump -l` log, parsed and written.
 *
 * Line format (what can-utils' candump -l writes and canplayer reads):
 *   (1700000000.123456) vcan0 141#0102030405060708
 *   (seconds.microseconds) interface id#data
 * - timestamp: one or more decimal digits, '.', exactly 6 digits, in
 *   parentheses; it must fit in uint64 nanoseconds (seconds <= 18446744073);
 * - interface: 1..FT_CANDUMP_IFACE_MAX characters without blanks (Linux
 *   IFNAMSIZ is 16 including the terminator); candump right-aligns it, so
 *   one or more blanks separate the fields;
 * - id: exactly 3 hex digits (11-bit, <= 7FF) or 8 (29-bit, <= 1FFFFFFF);
 * - data: 0..16 hex digits, an even count (0..8 bytes), either case;
 * - optionally a direction flag " T" or " R" (candump -x), then the end.
 * A trailing "\n" or "\r\n" is accepted. Rejected with a reason (the
 * caller prefixes the file name and line number): lines longer than
 * FT_CANDUMP_LINE_MAX characters, empty lines, a missing field, bad hex, an
 * odd number of data digits, more than 8 data bytes, a timestamp not in
 * the digits.6digits form or too large, an interface name too long, remote
 * frames (id#R), CAN FD frames (id##...) and error frames (id with the
 * 0x20000000 error flag) - the last three are FT_ERR_UNSUPPORTED.
 *
 * The parser reads exactly len bytes (the line need not be terminated),
 * keeps no state and never writes outside *out. */
#ifndef FT_CANDUMP_H
#define FT_CANDUMP_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "input/canaero.h"

#define FT_CANDUMP_LINE_MAX 256u /* characters, not counting the line end */
#define FT_CANDUMP_IFACE_MAX 15u

typedef struct ft_candump_record {
    ft_can_frame frame; /* frame.t_ns from the timestamp */
    char iface[FT_CANDUMP_IFACE_MAX + 1u];
} ft_candump_record;

/* Parses line[0..len). On failure *out is zeroed and err says why, with the
 * 1-based column where it applies ("column 23: bad hex digit 'G' in data"). */
ft_status ft_candump_parse_line(const char *line, size_t len, ft_candump_record *out,
                                ft_error *err);

/* Writes the record as one line without a line end, the way candump -l does:
 * seconds zero-padded to 10 digits, 6 decimals (canplayer needs exactly 6),
 * ids as 3 or 8 upper-case hex digits, data upper-case. Nanoseconds below a
 * microsecond are truncated. *len_out (may be NULL) gets the length. Fails
 * with FT_ERR_ARG for an invalid record or FT_ERR_OVERSIZED if buf (cap
 * bytes, including the terminator) is too small; 64 bytes always suffice. */
ft_status ft_candump_format(const ft_candump_record *rec, char *buf, size_t cap, size_t *len_out,
                            ft_error *err);

#endif
