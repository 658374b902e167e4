/* candump.c - candump -l line parser and writer (contract in candump.h).
 * A single forward scan with an index that only grows and is always checked
 * against len, so no input can read past the line or loop. */
#include "input/candump.h"

#include "core/ft_ns.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#define NS_PER_S UINT64_C(1000000000)
#define CAN_ERR_FLAG 0x20000000u

static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int hex_value(char c)
{
    if (c >= '0' && c <= '9') {
        return c - '0';
    }
    if (c >= 'a' && c <= 'f') {
        return c - 'a' + 10;
    }
    if (c >= 'A' && c <= 'F') {
        return c - 'A' + 10;
    }
    return -1;
}

/* A printable rendering of one byte for messages ("'G'" or "0x01"). */
static void char_repr(char c, char out[8])
{
    unsigned char u = (unsigned char)c;
    if (u >= 0x20u && u < 0x7Fu) {
        (void)snprintf(out, 8, "'%c'", c);
    } else {
        (void)snprintf(out, 8, "0x%02X", (unsigned)u);
    }
}

static ft_status fail_at(ft_error *err, ft_status s, size_t pos, const char *what)
{
    return ft_fail(err, s, "candump: column %zu: %s", pos + 1u, what);
}

static ft_status fail_char(ft_error *err, size_t pos, char c, const char *where)
{
    char rep[8];
    char_repr(c, rep);
    return ft_fail(err, FT_ERR_FORMAT, "candump: column %zu: bad hex digit %s in %s", pos + 1u,
                   rep, where);
}

static ft_status parse(const char *line, size_t len, ft_candump_record *out, ft_error *err)
{
    size_t i = 0u;

    /* ---- (seconds.microseconds) ---- */
    if (i >= len || line[i] != '(') {
        return fail_at(err, FT_ERR_FORMAT, i, "expected '(' starting the timestamp");
    }
    ++i;
    uint64_t sec = 0u;
    size_t sec_digits = 0u;
    int sec_overflow = 0;
    while (i < len && is_digit(line[i])) {
        uint64_t d = (uint64_t)(line[i] - '0');
        if (sec > (UINT64_MAX - d) / 10u) {
            sec_overflow = 1; /* keep scanning to report the whole field */
        } else {
            sec = sec * 10u + d;
        }
        ++sec_digits;
        ++i;
    }
    if (sec_digits == 0u || i >= len || line[i] != '.') {
        return fail_at(err, FT_ERR_FORMAT, i,
                       "timestamp must be (seconds.microseconds) with 6 decimals");
    }
    ++i;
    uint64_t usec = 0u;
    size_t usec_digits = 0u;
    while (i < len && is_digit(line[i]) && usec_digits < 7u) {
        usec = usec * 10u + (uint64_t)(line[i] - '0');
        ++usec_digits;
        ++i;
    }
    if (usec_digits != 6u || i >= len || line[i] != ')') {
        return fail_at(err, FT_ERR_FORMAT, i,
                       "timestamp must be (seconds.microseconds) with exactly 6 decimals");
    }
    ++i;
    /* sec * 1e9 + usec * 1000 must fit in uint64 (usec < 1e6: its product
     * cannot overflow). */
    uint64_t t_ns = 0u;
    if (sec_overflow || !ft_ns_mul(sec, NS_PER_S, &t_ns) ||
        !ft_ns_add(t_ns, usec * 1000u, &t_ns)) {
        return ft_fail(err, FT_ERR_NUMERIC,
                       "candump: timestamp with %zu second digits does not fit in 64-bit "
                       "nanoseconds (at most 18446744073.709551 s)",
                       sec_digits);
    }
    out->frame.t_ns = t_ns;

    /* ---- interface ---- */
    size_t blanks = 0u;
    while (i < len && is_blank(line[i])) {
        ++i;
        ++blanks;
    }
    if (blanks == 0u || i >= len) {
        return fail_at(err, FT_ERR_FORMAT, i, "missing interface name after the timestamp");
    }
    size_t if_start = i;
    while (i < len && !is_blank(line[i])) {
        ++i;
    }
    size_t if_len = i - if_start;
    if (if_len > FT_CANDUMP_IFACE_MAX) {
        return ft_fail(err, FT_ERR_OVERSIZED,
                       "candump: column %zu: interface name is %zu characters, at most %u",
                       if_start + 1u, if_len, FT_CANDUMP_IFACE_MAX);
    }
    for (size_t k = 0u; k < if_len; ++k) {
        unsigned char c = (unsigned char)line[if_start + k];
        if (c < 0x21u || c > 0x7Eu) {
            return fail_at(err, FT_ERR_FORMAT, if_start + k,
                           "interface name has a non-printable character");
        }
    }
    memcpy(out->iface, &line[if_start], if_len);
    out->iface[if_len] = '\0';

    /* ---- id#data ---- */
    blanks = 0u;
    while (i < len && is_blank(line[i])) {
        ++i;
        ++blanks;
    }
    if (blanks == 0u || i >= len) {
        return fail_at(err, FT_ERR_FORMAT, i, "missing frame (id#data) after the interface");
    }
    size_t id_start = i;
    uint32_t id = 0u;
    while (i < len && line[i] != '#' && !is_blank(line[i])) {
        int h = hex_value(line[i]);
        if (h < 0) {
            return fail_char(err, i, line[i], "the CAN id");
        }
        if (i - id_start < 8u) {
            id = (id << 4) | (uint32_t)h; /* more than 8 digits is rejected below */
        }
        ++i;
    }
    size_t id_digits = i - id_start;
    if (i >= len || line[i] != '#') {
        return fail_at(err, FT_ERR_FORMAT, i, "missing '#' between CAN id and data");
    }
    if (id_digits == 3u) {
        if (id > FT_CAN_STD_ID_MAX) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "candump: column %zu: standard id 0x%03" PRIX32 " exceeds 0x7FF",
                           id_start + 1u, id);
        }
        out->frame.extended = 0u;
    } else if (id_digits == 8u) {
        if ((id & CAN_ERR_FLAG) != 0u) {
            return fail_at(err, FT_ERR_UNSUPPORTED, id_start,
                           "error frame (id has the 0x20000000 error flag)");
        }
        if (id > FT_CAN_EXT_ID_MAX) {
            return ft_fail(err, FT_ERR_FORMAT,
                           "candump: column %zu: extended id 0x%08" PRIX32 " exceeds 0x1FFFFFFF",
                           id_start + 1u, id);
        }
        out->frame.extended = 1u;
    } else {
        return ft_fail(err, FT_ERR_FORMAT,
                       "candump: column %zu: CAN id has %zu hex digits, expected 3 (standard) "
                       "or 8 (extended)",
                       id_start + 1u, id_digits);
    }
    out->frame.can_id = id;
    ++i; /* '#' */
    if (i < len && line[i] == '#') {
        return fail_at(err, FT_ERR_UNSUPPORTED, i, "CAN FD frame (id##...) is not supported");
    }
    if (i < len && (line[i] == 'R' || line[i] == 'r')) {
        return fail_at(err, FT_ERR_UNSUPPORTED, i, "remote frame (id#R) carries no data");
    }
    size_t data_start = i;
    while (i < len && !is_blank(line[i])) {
        if (hex_value(line[i]) < 0) {
            return fail_char(err, i, line[i], "data");
        }
        ++i;
    }
    size_t data_digits = i - data_start;
    if (data_digits > 16u) {
        return ft_fail(err, FT_ERR_OVERSIZED,
                       "candump: column %zu: %zu data hex digits, at most 16 (8 bytes)",
                       data_start + 1u, data_digits);
    }
    if (data_digits % 2u != 0u) {
        return ft_fail(err, FT_ERR_FORMAT,
                       "candump: column %zu: odd number (%zu) of data hex digits", data_start + 1u,
                       data_digits);
    }
    out->frame.dlc = (uint8_t)(data_digits / 2u);
    for (size_t b = 0u; b < out->frame.dlc; ++b) {
        int hi = hex_value(line[data_start + 2u * b]);
        int lo = hex_value(line[data_start + 2u * b + 1u]);
        out->frame.data[b] = (uint8_t)((hi << 4) | lo);
    }

    /* ---- optional direction flag, then the end ---- */
    while (i < len && is_blank(line[i])) {
        ++i;
    }
    if (i < len && (line[i] == 'T' || line[i] == 'R') && (i + 1u == len || is_blank(line[i + 1u]))) {
        ++i;
        while (i < len && is_blank(line[i])) {
            ++i;
        }
    }
    if (i < len) {
        return fail_at(err, FT_ERR_FORMAT, i, "unexpected text after the frame");
    }
    return FT_OK;
}

ft_status ft_candump_parse_line(const char *line, size_t len, ft_candump_record *out,
                                ft_error *err)
{
    if (out != NULL) {
        memset(out, 0, sizeof *out);
    }
    if (line == NULL || out == NULL) {
        return ft_fail(err, FT_ERR_ARG, "candump: no line or output");
    }
    /* One line end is part of the line as read, not of the record. */
    if (len > 0u && line[len - 1u] == '\n') {
        --len;
        if (len > 0u && line[len - 1u] == '\r') {
            --len;
        }
    }
    if (len > FT_CANDUMP_LINE_MAX) {
        return ft_fail(err, FT_ERR_OVERSIZED, "candump: line is %zu characters, at most %u", len,
                       FT_CANDUMP_LINE_MAX);
    }
    size_t k = 0u;
    while (k < len && is_blank(line[k])) {
        ++k;
    }
    if (k == len) {
        return ft_fail(err, FT_ERR_FORMAT, "candump: empty line");
    }
    ft_status s = parse(line, len, out, err);
    if (s != FT_OK) {
        memset(out, 0, sizeof *out);
    }
    return s;
}

ft_status ft_candump_format(const ft_candump_record *rec, char *buf, size_t cap, size_t *len_out,
                            ft_error *err)
{
    if (len_out != NULL) {
        *len_out = 0u;
    }
    if (buf != NULL && cap > 0u) {
        buf[0] = '\0';
    }
    if (rec == NULL || buf == NULL || cap == 0u) {
        return ft_fail(err, FT_ERR_ARG, "candump: no record or buffer");
    }
    const ft_can_frame *f = &rec->frame;
    if (f->dlc > 8u) {
        return ft_fail(err, FT_ERR_ARG, "candump: DLC %u exceeds 8", (unsigned)f->dlc);
    }
    if (f->can_id > (f->extended ? FT_CAN_EXT_ID_MAX : FT_CAN_STD_ID_MAX)) {
        return ft_fail(err, FT_ERR_ARG, "candump: id 0x%" PRIX32 " too large for a %s frame",
                       f->can_id, f->extended ? "extended" : "standard");
    }
    size_t if_len = 0u;
    while (if_len <= FT_CANDUMP_IFACE_MAX && rec->iface[if_len] != '\0') {
        unsigned char c = (unsigned char)rec->iface[if_len];
        if (c < 0x21u || c > 0x7Eu) {
            return ft_fail(err, FT_ERR_ARG, "candump: interface name has a blank or "
                                            "non-printable character");
        }
        ++if_len;
    }
    if (if_len == 0u || if_len > FT_CANDUMP_IFACE_MAX) {
        return ft_fail(err, FT_ERR_ARG, "candump: interface name must be 1..%u characters",
                       FT_CANDUMP_IFACE_MAX);
    }
    char data[17];
    static const char k_hex[] = "0123456789ABCDEF";
    for (unsigned b = 0u; b < f->dlc; ++b) {
        data[2u * b] = k_hex[f->data[b] >> 4];
        data[2u * b + 1u] = k_hex[f->data[b] & 0x0Fu];
    }
    data[2u * f->dlc] = '\0';
    uint64_t sec = f->t_ns / NS_PER_S;
    uint64_t usec = (f->t_ns % NS_PER_S) / 1000u;
    int n;
    if (f->extended) {
        n = snprintf(buf, cap, "(%010" PRIu64 ".%06" PRIu64 ") %.*s %08" PRIX32 "#%s", sec, usec,
                     (int)if_len, rec->iface, f->can_id, data);
    } else {
        n = snprintf(buf, cap, "(%010" PRIu64 ".%06" PRIu64 ") %.*s %03" PRIX32 "#%s", sec, usec,
                     (int)if_len, rec->iface, f->can_id, data);
    }
    if (n < 0) {
        buf[0] = '\0';
        return ft_fail(err, FT_ERR_ARG, "candump: formatting failed");
    }
    if ((size_t)n >= cap) {
        buf[0] = '\0';
        return ft_fail(err, FT_ERR_OVERSIZED, "candump: line needs %d bytes, buffer has %zu",
                       n + 1, cap);
    }
    if (len_out != NULL) {
        *len_out = (size_t)n;
    }
    return FT_OK;
}
