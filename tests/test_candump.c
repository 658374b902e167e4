/* test_candump.c - candump -l lines: good ones (standard, extended, empty
 * data, direction flag, CRLF), every malformed kind with its status and
 * message, no crash on any byte soup, and writer -> parser round trips. */
#include <stdint.h>
#include <string.h>

#include "input/candump.h"
#include "test_util.h"

static ft_status parse_str(const char *s, ft_candump_record *rec, ft_error *err)
{
    return ft_candump_parse_line(s, strlen(s), rec, err);
}

static void test_good_lines(void)
{
    ft_candump_record rec;
    ft_error err = {0};
    REQUIRE(parse_str("(1700000000.123456) vcan0 141#0102030405060708", &rec, &err) == FT_OK);
    CHECK(rec.frame.t_ns == UINT64_C(1700000000123456000));
    CHECK(strcmp(rec.iface, "vcan0") == 0);
    CHECK(rec.frame.can_id == 0x141u && rec.frame.extended == 0u && rec.frame.dlc == 8u);
    for (int k = 0; k < 8; ++k) {
        CHECK(rec.frame.data[k] == (uint8_t)(k + 1));
    }
    /* Extended id, lower-case hex, short data, line end. */
    REQUIRE(parse_str("(0000000001.000001) can1 1abcdef0#deadBEEF\n", &rec, &err) == FT_OK);
    CHECK(rec.frame.t_ns == UINT64_C(1000001000));
    CHECK(rec.frame.can_id == 0x1ABCDEF0u && rec.frame.extended == 1u && rec.frame.dlc == 4u);
    CHECK(rec.frame.data[0] == 0xDEu && rec.frame.data[3] == 0xEFu && rec.frame.data[4] == 0u);
    /* No data, CRLF, right-aligned interface (candump pads with blanks). */
    REQUIRE(parse_str("(0.000000)   can0 7FF#\r\n", &rec, &err) == FT_OK);
    CHECK(rec.frame.t_ns == 0u && rec.frame.can_id == 0x7FFu && rec.frame.dlc == 0u);
    CHECK(strcmp(rec.iface, "can0") == 0);
    /* Direction flag from candump -x, trailing blanks. */
    REQUIRE(parse_str("(1.500000) can0 123#11 T", &rec, &err) == FT_OK);
    CHECK(rec.frame.dlc == 1u && rec.frame.data[0] == 0x11u);
    CHECK(parse_str("(1.500000) can0 123#11 R  ", &rec, &err) == FT_OK);
    CHECK(parse_str("(1.500000)\tcan0\t123#11", &rec, &err) == FT_OK);
    /* Largest representable time: 18446744073.709551 s. */
    REQUIRE(parse_str("(18446744073.709551) can0 000#00", &rec, &err) == FT_OK);
    CHECK(rec.frame.t_ns == UINT64_C(18446744073709551000));
    /* A 15-character interface name fits; the line need not be terminated. */
    char buf[64] = "(1.000000) abcdefghijklmno 123#AB";
    size_t n = strlen(buf);
    buf[n] = 'X'; /* the byte after len must not be read as part of the line */
    REQUIRE(ft_candump_parse_line(buf, n, &rec, &err) == FT_OK);
    CHECK(strcmp(rec.iface, "abcdefghijklmno") == 0);
    CHECK(rec.frame.dlc == 1u && rec.frame.data[0] == 0xABu);
}

struct bad_case {
    const char *line;
    ft_status status;
    const char *msg; /* a piece the message must contain */
};

static void test_bad_lines(void)
{
    static const struct bad_case cases[] = {
        {"", FT_ERR_FORMAT, "empty line"},
        {"\n", FT_ERR_FORMAT, "empty line"},
        {"   \t ", FT_ERR_FORMAT, "empty line"},
        {"1700000000.123456 vcan0 141#00", FT_ERR_FORMAT, "column 1: expected '('"},
        {"(1700000000.123456)", FT_ERR_FORMAT, "missing interface"},
        {"(1700000000.123456) ", FT_ERR_FORMAT, "missing interface"},
        {"(1700000000.123456) vcan0", FT_ERR_FORMAT, "missing frame"},
        {"(1700000000.123456) vcan0 ", FT_ERR_FORMAT, "missing frame"},
        {"(1700000000.123456)vcan0 141#00", FT_ERR_FORMAT, "missing interface"},
        {"(1700000000.123456) vcan0 14100", FT_ERR_FORMAT, "missing '#'"},
        {"(1700000000.12345) vcan0 141#00", FT_ERR_FORMAT, "exactly 6 decimals"},
        {"(1700000000.1234567) vcan0 141#00", FT_ERR_FORMAT, "exactly 6 decimals"},
        {"(1700000000) vcan0 141#00", FT_ERR_FORMAT, "6 decimals"},
        {"(.123456) vcan0 141#00", FT_ERR_FORMAT, "6 decimals"},
        {"(-1.000000) vcan0 141#00", FT_ERR_FORMAT, "6 decimals"},
        {"(1e9.000000) vcan0 141#00", FT_ERR_FORMAT, "6 decimals"},
        {"(1.000000 vcan0 141#00", FT_ERR_FORMAT, "6 decimals"},
        {"(18446744073.709552) vcan0 141#00", FT_ERR_NUMERIC, "64-bit nanoseconds"},
        {"(18446744074.000000) vcan0 141#00", FT_ERR_NUMERIC, "64-bit nanoseconds"},
        {"(99999999999999999999999999999.000000) vcan0 141#00", FT_ERR_NUMERIC,
         "29 second digits"},
        {"(1.000000) abcdefghijklmnop 141#00", FT_ERR_OVERSIZED, "16 characters, at most 15"},
        {"(1.000000) vcan0 1G1#00", FT_ERR_FORMAT, "column 19: bad hex digit 'G' in the CAN id"},
        {"(1.000000) vcan0 141#0G", FT_ERR_FORMAT, "column 23: bad hex digit 'G' in data"},
        {"(1.000000) vcan0 141#00.11", FT_ERR_FORMAT, "bad hex digit '.'"},
        {"(1.000000) vcan0 141#1122334455667788_E", FT_ERR_FORMAT, "bad hex digit '_'"},
        {"(1.000000) vcan0 141#012", FT_ERR_FORMAT, "odd number (3)"},
        {"(1.000000) vcan0 141#0", FT_ERR_FORMAT, "odd number (1)"},
        {"(1.000000) vcan0 141#010203040506070809", FT_ERR_OVERSIZED, "18 data hex digits"},
        {"(1.000000) vcan0 141#01020304050607080", FT_ERR_OVERSIZED, "17 data hex digits"},
        {"(1.000000) vcan0 141#R", FT_ERR_UNSUPPORTED, "remote frame"},
        {"(1.000000) vcan0 12345678#R5", FT_ERR_UNSUPPORTED, "remote frame"},
        {"(1.000000) vcan0 141##0112233", FT_ERR_UNSUPPORTED, "CAN FD"},
        {"(1.000000) vcan0 20000080#0000000000000000", FT_ERR_UNSUPPORTED, "error frame"},
        {"(1.000000) vcan0 40000000#00", FT_ERR_FORMAT, "exceeds 0x1FFFFFFF"},
        {"(1.000000) vcan0 800#00", FT_ERR_FORMAT, "exceeds 0x7FF"},
        {"(1.000000) vcan0 41#00", FT_ERR_FORMAT, "2 hex digits"},
        {"(1.000000) vcan0 0141#00", FT_ERR_FORMAT, "4 hex digits"},
        {"(1.000000) vcan0 123456789#00", FT_ERR_FORMAT, "9 hex digits"},
        {"(1.000000) vcan0 #00", FT_ERR_FORMAT, "0 hex digits"},
        {"(1.000000) vcan0 141#00 X", FT_ERR_FORMAT, "unexpected text"},
        {"(1.000000) vcan0 141#00 TT", FT_ERR_FORMAT, "unexpected text"},
        {"(1.000000) vcan0 141#00 T R", FT_ERR_FORMAT, "unexpected text"},
        {"(1.000000) vcan0 141 #00", FT_ERR_FORMAT, "missing '#'"},
        {"DROPCOUNT: dropped 3 CAN frames on 'can0' socket", FT_ERR_FORMAT, "expected '('"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        ft_candump_record rec;
        memset(&rec, 0x5A, sizeof rec);
        ft_error err = {0};
        ft_status s = parse_str(cases[c].line, &rec, &err);
        if (s != cases[c].status || strstr(err.text, cases[c].msg) == NULL) {
            fprintf(stderr, "case '%s': status %s, message '%s' (want %s, '%s')\n", cases[c].line,
                    ft_status_str(s), err.text, ft_status_str(cases[c].status), cases[c].msg);
            ++g_ft_test_failures;
        }
        CHECK(strncmp(err.text, "candump: ", 9) == 0);
        /* A failed parse leaves a zeroed record, never half a frame. */
        CHECK(rec.frame.dlc == 0u && rec.frame.can_id == 0u && rec.iface[0] == '\0');
    }
    /* Embedded NUL bytes (len-based input). */
    static const char nul_data[] = "(1.000000) vcan0 141#0\0";
    ft_candump_record rec;
    ft_error err = {0};
    CHECK(ft_candump_parse_line(nul_data, sizeof nul_data - 1u, &rec, &err) == FT_ERR_FORMAT);
    CHECK(strstr(err.text, "0x00") != NULL);
    static const char nul_if[] = "(1.000000) vc\0n0 141#00";
    CHECK(ft_candump_parse_line(nul_if, sizeof nul_if - 1u, &rec, &err) == FT_ERR_FORMAT);
    CHECK(strstr(err.text, "non-printable") != NULL);
    /* NULL arguments. */
    CHECK(ft_candump_parse_line(NULL, 3u, &rec, &err) == FT_ERR_ARG);
    CHECK(ft_candump_parse_line("x", 1u, NULL, &err) == FT_ERR_ARG);
    CHECK(parse_str("", &rec, NULL) == FT_ERR_FORMAT);
}

static void test_overlong(void)
{
    /* A valid line padded with trailing blanks to exactly the limit passes;
     * one more character is rejected before any field is read. */
    char line[FT_CANDUMP_LINE_MAX + 8u];
    const char *head = "(1.000000) vcan0 141#00";
    memset(line, ' ', sizeof line);
    memcpy(line, head, strlen(head));
    ft_candump_record rec;
    ft_error err = {0};
    CHECK(ft_candump_parse_line(line, FT_CANDUMP_LINE_MAX, &rec, &err) == FT_OK);
    line[FT_CANDUMP_LINE_MAX] = '\n'; /* the line end does not count */
    CHECK(ft_candump_parse_line(line, FT_CANDUMP_LINE_MAX + 1u, &rec, &err) == FT_OK);
    CHECK(ft_candump_parse_line(line, FT_CANDUMP_LINE_MAX + 1u - 1u, &rec, &err) == FT_OK);
    line[FT_CANDUMP_LINE_MAX] = ' ';
    CHECK(ft_candump_parse_line(line, FT_CANDUMP_LINE_MAX + 1u, &rec, &err) == FT_ERR_OVERSIZED);
    CHECK(strstr(err.text, "257 characters, at most 256") != NULL);
    /* A huge "line" (no terminator anywhere in reach is needed). */
    static char big[100000];
    memset(big, 'A', sizeof big);
    CHECK(ft_candump_parse_line(big, sizeof big, &rec, &err) == FT_ERR_OVERSIZED);
}

/* Deterministic byte soup: every prefix of a good line, every single-byte
 * corruption of it, and pseudo-random lines. Only "does not crash and
 * returns a status" is checked (plus the sanitizers if enabled). */
static void test_never_crashes(void)
{
    const char *good = "(1700000000.123456) vcan0 12345678#0102030405060708 T";
    size_t n = strlen(good);
    char line[80];
    ft_candump_record rec;
    ft_error err;
    int ok = 0;
    for (size_t len = 0; len <= n; ++len) {
        ok += ft_candump_parse_line(good, len, &rec, &err) == FT_OK;
    }
    /* Prefixes that end on a complete frame parse (data digits even). */
    CHECK(ok >= 1);
    for (size_t pos = 0; pos < n; ++pos) {
        for (int b = 0; b < 256; b += 7) {
            memcpy(line, good, n);
            line[pos] = (char)b;
            ft_status s = ft_candump_parse_line(line, n, &rec, &err);
            CHECK((int)s >= 0 && s < FT_STATUS_COUNT);
        }
    }
    uint32_t x = 12345u;
    static const char alphabet[] = "(0123456789.) #RTabcdefABCDEFxyz\t\n\r";
    for (int trial = 0; trial < 20000; ++trial) {
        size_t len = 0;
        x = x * 1664525u + 1013904223u;
        size_t want = (x >> 8) % sizeof line;
        while (len < want) {
            x = x * 1664525u + 1013904223u;
            line[len++] = alphabet[(x >> 16) % (sizeof alphabet - 1u)];
        }
        ft_status s = ft_candump_parse_line(line, len, &rec, &err);
        CHECK((int)s >= 0 && s < FT_STATUS_COUNT);
        if (s == FT_OK) {
            CHECK(rec.frame.dlc <= 8u);
        }
    }
}

static void test_round_trip(void)
{
    static const char *lines[] = {
        "(1700000000.123456) vcan0 141#0102030405060708",
        "(0000000000.000000) can0 000#",
        "(0000000012.000001) can1 1FFFFFFF#FF",
        "(18446744073.709551) abcdefghijklmno 7FF#00112233445566",
    };
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; ++k) {
        ft_candump_record rec;
        ft_error err = {0};
        REQUIRE(parse_str(lines[k], &rec, &err) == FT_OK);
        char out[64];
        size_t len = 0;
        REQUIRE(ft_candump_format(&rec, out, sizeof out, &len, &err) == FT_OK);
        CHECK(len == strlen(out));
        if (strcmp(out, lines[k]) != 0) {
            fprintf(stderr, "round trip: '%s' -> '%s'\n", lines[k], out);
            ++g_ft_test_failures;
        }
    }
    /* Writer -> parser over many frames. */
    uint32_t x = 777u;
    for (int trial = 0; trial < 5000; ++trial) {
        ft_candump_record a;
        memset(&a, 0, sizeof a);
        x = x * 1664525u + 1013904223u;
        a.frame.extended = (uint8_t)(x >> 31);
        a.frame.can_id = (x >> 3) & (a.frame.extended ? FT_CAN_EXT_ID_MAX : FT_CAN_STD_ID_MAX);
        x = x * 1664525u + 1013904223u;
        a.frame.dlc = (uint8_t)((x >> 20) % 9u);
        for (unsigned b = 0; b < a.frame.dlc; ++b) {
            x = x * 1664525u + 1013904223u;
            a.frame.data[b] = (uint8_t)(x >> 24);
        }
        x = x * 1664525u + 1013904223u;
        /* Whole microseconds: the format has 6 decimals. */
        a.frame.t_ns = ((uint64_t)x * UINT64_C(1000003)) % UINT64_C(18446744073709551) * 1000u;
        (void)snprintf(a.iface, sizeof a.iface, "can%u", (unsigned)(x % 100u));
        char out[64];
        ft_error err = {0};
        REQUIRE(ft_candump_format(&a, out, sizeof out, NULL, &err) == FT_OK);
        ft_candump_record b;
        REQUIRE(parse_str(out, &b, &err) == FT_OK);
        CHECK(memcmp(&a.frame, &b.frame, sizeof a.frame) == 0);
        CHECK(strcmp(a.iface, b.iface) == 0);
        /* Six decimals always, seconds padded to at least 10 digits. */
        const char *dot = strchr(out, '.');
        REQUIRE(dot != NULL);
        CHECK(dot - out >= 11 && dot[7] == ')');
    }
    /* Sub-microsecond time is truncated. */
    ft_candump_record t;
    memset(&t, 0, sizeof t);
    t.frame.t_ns = UINT64_C(1500000999);
    strcpy(t.iface, "can0");
    char out[64];
    REQUIRE(ft_candump_format(&t, out, sizeof out, NULL, NULL) == FT_OK);
    CHECK(strcmp(out, "(0000000001.500000) can0 000#") == 0);
    /* Writer errors. */
    ft_error err = {0};
    char small[20];
    CHECK(ft_candump_format(&t, small, sizeof small, NULL, &err) == FT_ERR_OVERSIZED);
    CHECK(small[0] == '\0');
    t.frame.dlc = 9u;
    CHECK(ft_candump_format(&t, out, sizeof out, NULL, &err) == FT_ERR_ARG);
    t.frame.dlc = 0u;
    t.frame.can_id = 0x800u;
    CHECK(ft_candump_format(&t, out, sizeof out, NULL, &err) == FT_ERR_ARG);
    t.frame.can_id = 1u;
    t.iface[0] = '\0';
    CHECK(ft_candump_format(&t, out, sizeof out, NULL, &err) == FT_ERR_ARG);
    strcpy(t.iface, "ca n");
    CHECK(ft_candump_format(&t, out, sizeof out, NULL, &err) == FT_ERR_ARG);
    memset(t.iface, 'x', sizeof t.iface); /* unterminated */
    CHECK(ft_candump_format(&t, out, sizeof out, NULL, &err) == FT_ERR_ARG);
    CHECK(ft_candump_format(NULL, out, sizeof out, NULL, &err) == FT_ERR_ARG);
}

int main(void)
{
    test_good_lines();
    test_bad_lines();
    test_overlong();
    test_never_crashes();
    test_round_trip();
    return ft_test_result("test_candump");
}
