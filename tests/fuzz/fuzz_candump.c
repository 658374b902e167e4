/* fuzz_candump.c - libFuzzer harness: the candump -l line parser
 * (src/input/candump.c) and the line splitter in front of it (src/core/line_reader.c).
 *
 * The whole input is parsed once as one line of exactly `size` bytes (the
 * parser must not read past it), then split into lines by ft_line_reader
 * over a memory reader, as replay reads a log, and each line parsed.
 * Invariants: a failed parse leaves the record zeroed and a message; an
 * accepted record formats (ft_candump_format, what flightgen writes) and
 * parses back to the same frame and interface (the timestamp has whole
 * microseconds). No state survives an input. */
#include <string.h>

#include "input/candump.h"
#include "fuzz_util.h"
#include "core/io.h"
#include "core/line_reader.h"

static ft_line_reader g_lr;

static void check_line(const char *line, size_t len)
{
    ft_candump_record rec;
    ft_error err;
    memset(&rec, 0xA5, sizeof rec); /* the parser must overwrite all of it */
    memset(&err, 0, sizeof err);
    ft_status st = ft_candump_parse_line(line, len, &rec, &err);
    if (st != FT_OK) {
        static const ft_candump_record zero;
        FUZZ_CHECK(memcmp(&rec, &zero, sizeof rec) == 0);
        FUZZ_CHECK(err.text[0] != '\0');
        FUZZ_CHECK_TEXT(err.text);
        return;
    }
    FUZZ_CHECK(rec.frame.dlc <= 8u);
    for (uint32_t k = rec.frame.dlc; k < 8u; ++k) {
        FUZZ_CHECK(rec.frame.data[k] == 0u);
    }
    FUZZ_CHECK(rec.frame.extended ? rec.frame.can_id <= FT_CAN_EXT_ID_MAX
                                  : rec.frame.can_id <= FT_CAN_STD_ID_MAX);
    FUZZ_CHECK(rec.frame.t_ns % 1000u == 0u);
    FUZZ_CHECK_TEXT(rec.iface);
    FUZZ_CHECK(rec.iface[0] != '\0');

    char buf[64];
    size_t n = 0u;
    st = ft_candump_format(&rec, buf, sizeof buf, &n, &err);
    FUZZ_CHECK(st == FT_OK);
    FUZZ_CHECK(n < sizeof buf && buf[n] == '\0' && strlen(buf) == n);
    ft_candump_record back;
    st = ft_candump_parse_line(buf, n, &back, &err);
    FUZZ_CHECK(st == FT_OK);
    FUZZ_CHECK(back.frame.can_id == rec.frame.can_id);
    FUZZ_CHECK(back.frame.extended == rec.frame.extended);
    FUZZ_CHECK(back.frame.dlc == rec.frame.dlc);
    FUZZ_CHECK(memcmp(back.frame.data, rec.frame.data, 8u) == 0);
    FUZZ_CHECK(back.frame.t_ns == rec.frame.t_ns);
    FUZZ_CHECK(strcmp(back.iface, rec.iface) == 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    check_line((const char *)data, size);

    ft_reader r;
    ft_mem_reader m;
    ft_mem_reader_init(&r, &m, data, size, "fuzz.log");
    ft_line_reader_init(&g_lr, &r);
    /* each line consumes at least its end; bounded by the input length */
    for (size_t guard = 0u; guard < size + 3u; ++guard) {
        ft_line_kind kind = FT_LINE_END;
        ft_error err;
        memset(&err, 0, sizeof err);
        ft_status st = ft_line_reader_next(&g_lr, &kind, &err);
        FUZZ_CHECK(st == FT_OK); /* a memory reader never fails */
        if (kind == FT_LINE_END) {
            return 0;
        }
        if (kind == FT_LINE_OK) {
            FUZZ_CHECK(g_lr.len <= FT_LINE_READER_LINE_MAX && g_lr.line[g_lr.len] == '\0');
            check_line(g_lr.line, g_lr.len);
        }
    }
    FUZZ_CHECK(0 && "line reader did not reach the end of the input");
    return 0;
}
