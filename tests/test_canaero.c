/* test_canaero.c - CANaerospace decoder from hand-built frames: every data
 * type from known big-endian byte patterns, every reject reason, counter
 * wrap/gap/duplicate, DOUBLEH/L pairing, the map checks, and that a rejected
 * frame never reaches the pose. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "input/canaero.h"
#include "input/pose_state.h"
#include "test_util.h"

static ft_can_frame frame(uint32_t id, uint8_t dlc, uint8_t type, uint8_t code, uint8_t b4,
                          uint8_t b5, uint8_t b6, uint8_t b7, uint64_t t_ns)
{
    ft_can_frame f;
    memset(&f, 0, sizeof f);
    f.can_id = id;
    f.dlc = dlc;
    f.data[0] = 0x0Au; /* node-id */
    f.data[1] = type;
    f.data[2] = 0u; /* service code */
    f.data[3] = code;
    f.data[4] = b4;
    f.data[5] = b5;
    f.data[6] = b6;
    f.data[7] = b7;
    f.t_ns = t_ns;
    return f;
}

static ft_can_frame float_frame(uint32_t id, uint8_t code, float v, uint64_t t_ns)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    return frame(id, 8u, FT_CAN_TYPE_FLOAT, code, (uint8_t)(bits >> 24), (uint8_t)(bits >> 16),
                 (uint8_t)(bits >> 8), (uint8_t)bits, t_ns);
}

static void init_default(ft_canaero *dec)
{
    ft_can_map m;
    ft_canaero_default_map(&m);
    ft_error err = {0};
    REQUIRE(ft_canaero_init(dec, &m, &err) == FT_OK);
}

static void test_default_map(void)
{
    ft_can_map m;
    ft_canaero_default_map(&m);
    CHECK(m.count == 13u);
    static const struct {
        uint16_t id;
        ft_pose_qty qty;
        double lo, hi;
        uint32_t timeout_ms;
        uint8_t prio;
    } want[] = {
        {311u, FT_QTY_PITCH, -90.0, 90.0, 100u, 0u},
        {312u, FT_QTY_ROLL, -180.0, 180.0, 100u, 0u},
        {321u, FT_QTY_HEADING, -360.0, 360.0, 100u, 0u},
        {303u, FT_QTY_PITCH_RATE, -500.0, 500.0, 100u, 0u},
        {304u, FT_QTY_ROLL_RATE, -500.0, 500.0, 100u, 0u},
        {305u, FT_QTY_YAW_RATE, -500.0, 500.0, 100u, 0u},
        {1036u, FT_QTY_LAT, -90.0, 90.0, 500u, 0u},
        {1037u, FT_QTY_LON, -180.0, 180.0, 500u, 0u},
        {320u, FT_QTY_ALT, -1000.0, 25000.0, 500u, 0u},
        {1038u, FT_QTY_ALT, -1000.0, 25000.0, 500u, 1u},
        {1039u, FT_QTY_GROUND_SPEED, 0.0, 1000.0, 500u, 0u},
        {1040u, FT_QTY_TRACK, -360.0, 360.0, 500u, 0u},
        {314u, FT_QTY_ALT_RATE, -500.0, 500.0, 500u, 0u},
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
        int found = 0;
        for (uint32_t k = 0; k < m.count; ++k) {
            const ft_can_map_entry *e = &m.e[k];
            if (e->can_id == want[i].id) {
                found = 1;
                CHECK(e->qty == want[i].qty);
                CHECK(e->scale == 1.0);
                CHECK(e->min_value == want[i].lo && e->max_value == want[i].hi);
                CHECK(e->timeout_ms == want[i].timeout_ms);
                CHECK(e->priority == want[i].prio);
            }
        }
        CHECK(found);
    }
    ft_canaero dec;
    CHECK(ft_canaero_init(&dec, &m, NULL) == FT_OK);
}

static void test_map_checks(void)
{
    ft_can_map m;
    memset(&m, 0, sizeof m);
    ft_error err = {0};
    ft_can_map_entry e = {100u, FT_QTY_ALT, 0.1, -10.0, 10.0, 50u, 0u};
    CHECK(ft_can_map_add(&m, &e, &err) == FT_OK);
    CHECK(ft_can_map_add(&m, &e, &err) == FT_ERR_CONFIG); /* same id twice */
    CHECK(strstr(err.text, "twice") != NULL);
    ft_can_map_entry bad = e;
    bad.can_id = 0x800u;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    CHECK(strstr(err.text, "11-bit") != NULL);
    bad = e;
    bad.can_id = 101u;
    bad.scale = 0.0;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    bad.scale = NAN;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    bad = e;
    bad.can_id = 101u;
    bad.min_value = 5.0;
    bad.max_value = 4.0;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    bad.max_value = INFINITY;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    bad = e;
    bad.can_id = 101u;
    bad.timeout_ms = 0u;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    bad = e;
    bad.can_id = 101u;
    bad.qty = FT_QTY_COUNT;
    CHECK(ft_can_map_add(&m, &bad, &err) == FT_ERR_CONFIG);
    CHECK(m.count == 1u);
    for (uint16_t id = 200u; m.count < FT_CAN_MAP_MAX; ++id) {
        e.can_id = id;
        REQUIRE(ft_can_map_add(&m, &e, NULL) == FT_OK);
    }
    e.can_id = 1000u;
    CHECK(ft_can_map_add(&m, &e, &err) == FT_ERR_BUDGET);
    CHECK(strstr(err.text, "full") != NULL);
    /* init re-checks a map built by hand. */
    ft_canaero dec;
    m.e[3].can_id = m.e[4].can_id;
    CHECK(ft_canaero_init(&dec, &m, &err) == FT_ERR_CONFIG);
    m.count = FT_CAN_MAP_MAX + 1u;
    CHECK(ft_canaero_init(&dec, &m, &err) == FT_ERR_CONFIG);
    CHECK(ft_canaero_init(NULL, &m, &err) == FT_ERR_ARG);
}

static void test_data_types(void)
{
    ft_canaero dec;
    init_default(&dec);
    ft_can_result r;
    /* FLOAT 1.5 = 3F C0 00 00 on body pitch. */
    ft_can_frame f = frame(311u, 8u, FT_CAN_TYPE_FLOAT, 0u, 0x3Fu, 0xC0u, 0x00u, 0x00u, 1000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.outcome == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_PITCH && r.input.value == 1.5);
    CHECK(r.input.t_ns == 1000u && r.input.timeout_ms == 100u && r.input.source_id == 311u);
    CHECK(r.node_id == 0x0Au && r.data_type == FT_CAN_TYPE_FLOAT && r.message_code == 0u);
    /* FLOAT -2.25 = C0 10 00 00 on body roll. */
    f = frame(312u, 8u, FT_CAN_TYPE_FLOAT, 0u, 0xC0u, 0x10u, 0x00u, 0x00u, 2000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_ROLL && r.input.value == -2.25);

    /* LONG and SHORT with scales (a custom map, as a real installation has). */
    ft_can_map m;
    memset(&m, 0, sizeof m);
    ft_can_map_entry lat = {1036u, FT_QTY_LAT, 1e-7, -90.0, 90.0, 500u, 0u};
    ft_can_map_entry lon = {1037u, FT_QTY_LON, 1e-7, -180.0, 180.0, 500u, 0u};
    ft_can_map_entry rate = {305u, FT_QTY_YAW_RATE, 0.1, -500.0, 500.0, 100u, 0u};
    REQUIRE(ft_can_map_add(&m, &lat, NULL) == FT_OK);
    REQUIRE(ft_can_map_add(&m, &lon, NULL) == FT_OK);
    REQUIRE(ft_can_map_add(&m, &rate, NULL) == FT_OK);
    REQUIRE(ft_canaero_init(&dec, &m, NULL) == FT_OK);
    /* 469000000 = 1B F4 5F 40 -> 46.9 deg. */
    f = frame(1036u, 8u, FT_CAN_TYPE_LONG, 7u, 0x1Bu, 0xF4u, 0x5Fu, 0x40u, 3000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_LAT);
    CHECK_NEAR(r.input.value, 46.9, 1e-12);
    /* -1215000000 = B7 94 92 40 -> -121.5 deg (sign from two's complement). */
    f = frame(1037u, 8u, FT_CAN_TYPE_LONG, 7u, 0xB7u, 0x94u, 0x92u, 0x40u, 3000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK_NEAR(r.input.value, -121.5, 1e-12);
    /* SHORT -200 = FF 38 -> -20 deg/s, DLC 6 ... */
    f = frame(305u, 6u, FT_CAN_TYPE_SHORT, 1u, 0xFFu, 0x38u, 0u, 0u, 4000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK_NEAR(r.input.value, -20.0, 1e-12);
    /* ... and DLC 8 with padding (padding ignored). */
    f = frame(305u, 8u, FT_CAN_TYPE_SHORT, 2u, 0x01u, 0x2Cu, 0xAAu, 0x55u, 5000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK_NEAR(r.input.value, 30.0, 1e-12);
    /* SHORT -32768 = 80 00 -> -3276.8 deg/s: decoded, then out of range. */
    f = frame(305u, 6u, FT_CAN_TYPE_SHORT, 3u, 0x80u, 0x00u, 0u, 0u, 5000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_RANGE);
    /* 4999 = 13 87 -> 499.9 deg/s, inside. */
    f = frame(305u, 6u, FT_CAN_TYPE_SHORT, 4u, 0x13u, 0x87u, 0u, 0u, 5000u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK_NEAR(r.input.value, 499.9, 1e-12);
    CHECK(dec.accepted == 5u);
    CHECK(dec.rejects[FT_CAN_REJECT_RANGE] == 1u);
}

static void test_double_pairs(void)
{
    ft_canaero dec;
    init_default(&dec);
    ft_can_result r;
    /* 46.853 = 40 47 6D 2F | 1A 9F BE 77. */
    ft_can_frame hi =
        frame(1036u, 8u, FT_CAN_TYPE_DOUBLEH, 5u, 0x40u, 0x47u, 0x6Du, 0x2Fu, 10000u);
    ft_can_frame lo =
        frame(1036u, 8u, FT_CAN_TYPE_DOUBLEL, 6u, 0x1Au, 0x9Fu, 0xBEu, 0x77u, 10100u);
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    CHECK(r.outcome == FT_CAN_PENDING);
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_LAT && r.input.value == 46.853);
    CHECK(r.input.t_ns == 10000u); /* the high half's time */
    CHECK(dec.pending == 1u && dec.accepted == 1u);

    /* Pair across the counter wrap: 255 then 0. */
    hi.data[3] = 255u;
    lo.data[3] = 0u;
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    CHECK(r.lost == 248u); /* 6 -> 255 */
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_VALUE);
    CHECK(r.input.value == 46.853 && r.lost == 0u && r.out_of_sequence == 0u);

    /* Low half alone. */
    lo.data[3] = 10u;
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_DOUBLE_HALF_MISSING);
    CHECK(dec.rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING] == 1u);
    /* High, then a lost message, then low: codes 11, 13 are not consecutive;
     * the high is abandoned and the low rejected (2 halves never paired). */
    hi.data[3] = 11u;
    lo.data[3] = 13u;
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_DOUBLE_HALF_MISSING && r.lost == 1u);
    CHECK(dec.rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING] == 3u);
    /* High, high, low: the first high is abandoned, the second pairs. */
    hi.data[3] = 20u;
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    hi.data[3] = 21u;
    hi.data[4] = 0xC0u; /* -46.853 */
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    lo.data[3] = 22u;
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_VALUE);
    CHECK(r.input.value == -46.853);
    CHECK(dec.rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING] == 4u);
    /* High, then a FLOAT on the same id: high abandoned, float accepted. */
    hi.data[3] = 30u;
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    ft_can_frame fl = float_frame(1036u, 31u, 12.5f, 20000u);
    CHECK(ft_canaero_decode(&dec, &fl, &r) == FT_CAN_VALUE);
    CHECK(r.input.value == 12.5);
    CHECK(dec.rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING] == 5u);
    /* A duplicate of the high does not disturb the pending pair. */
    hi.data[3] = 40u;
    hi.data[4] = 0x40u;
    lo.data[3] = 41u;
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_PENDING);
    CHECK(ft_canaero_decode(&dec, &hi, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_COUNTER_REPEAT);
    CHECK(ft_canaero_decode(&dec, &lo, &r) == FT_CAN_VALUE);
    CHECK(r.input.value == 46.853);
    /* Double NaN and out-of-range double (1e300) are rejected once paired. */
    ft_can_frame nh = frame(1037u, 8u, FT_CAN_TYPE_DOUBLEH, 1u, 0x7Fu, 0xF8u, 0u, 0u, 1u);
    ft_can_frame nl = frame(1037u, 8u, FT_CAN_TYPE_DOUBLEL, 2u, 0u, 0u, 0u, 0u, 2u);
    CHECK(ft_canaero_decode(&dec, &nh, &r) == FT_CAN_PENDING);
    CHECK(ft_canaero_decode(&dec, &nl, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_NONFINITE);
    ft_can_frame bh = frame(1037u, 8u, FT_CAN_TYPE_DOUBLEH, 3u, 0x7Eu, 0x37u, 0xE4u, 0x3Cu, 3u);
    ft_can_frame bl = frame(1037u, 8u, FT_CAN_TYPE_DOUBLEL, 4u, 0x88u, 0x00u, 0x75u, 0x9Cu, 4u);
    CHECK(ft_canaero_decode(&dec, &bh, &r) == FT_CAN_PENDING);
    CHECK(ft_canaero_decode(&dec, &bl, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_RANGE);
}

static void expect_reject(ft_canaero *dec, const ft_can_frame *f, ft_can_reject want, int line)
{
    ft_can_result r;
    uint64_t before = dec->rejects[want];
    ft_can_outcome o = ft_canaero_decode(dec, f, &r);
    if (o != FT_CAN_REJECTED || r.outcome != FT_CAN_REJECTED || r.reason != want ||
        dec->rejects[want] != before + 1u) {
        fprintf(stderr, "line %d: expected %s, got outcome %d reason %s\n", line,
                ft_can_reject_name(want), (int)o, ft_can_reject_name(r.reason));
        ++g_ft_test_failures;
    }
}

static void test_rejects(void)
{
    ft_canaero dec;
    init_default(&dec);
    uint8_t code = 0u;
    /* Unknown id, extended id with a mapped number, id above 11 bits. */
    ft_can_frame f = float_frame(999u, code++, 1.0f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_UNKNOWN_ID, __LINE__);
    f = float_frame(311u, code++, 1.0f, 1u);
    f.extended = 1u;
    expect_reject(&dec, &f, FT_CAN_REJECT_UNKNOWN_ID, __LINE__);
    f = float_frame(311u | 0x800u, code++, 1.0f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_UNKNOWN_ID, __LINE__);
    /* DLC: too short for the header, too short for a FLOAT, SHORT with 7,
     * and an impossible 9. */
    f = float_frame(311u, code++, 1.0f, 1u);
    f.dlc = 3u;
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f.dlc = 0u;
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f.dlc = 6u;
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f.dlc = 9u;
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f = frame(311u, 7u, FT_CAN_TYPE_SHORT, code++, 0u, 1u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f = frame(311u, 4u, FT_CAN_TYPE_SHORT, code++, 0u, 1u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    f = frame(311u, 6u, FT_CAN_TYPE_DOUBLEH, code++, 0u, 1u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_DLC, __LINE__);
    /* Unknown data types: NODATA 0, ULONG 4, user-defined 100. */
    f = frame(311u, 8u, 0u, code++, 0u, 0u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_TYPE, __LINE__);
    f.data[1] = 4u;
    expect_reject(&dec, &f, FT_CAN_REJECT_TYPE, __LINE__);
    f.data[1] = 100u;
    expect_reject(&dec, &f, FT_CAN_REJECT_TYPE, __LINE__);
    /* None of the above touched the counter history. */
    CHECK(dec.st[0].has_code == 0u && dec.lost == 0u);
    /* NaN (7F C0 00 00), +Inf, -Inf. */
    f = frame(311u, 8u, FT_CAN_TYPE_FLOAT, 50u, 0x7Fu, 0xC0u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_NONFINITE, __LINE__);
    f = frame(311u, 8u, FT_CAN_TYPE_FLOAT, 51u, 0x7Fu, 0x80u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_NONFINITE, __LINE__);
    f = frame(311u, 8u, FT_CAN_TYPE_FLOAT, 52u, 0xFFu, 0x80u, 0u, 0u, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_NONFINITE, __LINE__);
    /* Range: pitch 91 and -90.5; the limits themselves are fine. */
    f = float_frame(311u, 53u, 91.0f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    f = float_frame(311u, 54u, -90.5f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    ft_can_result r;
    f = float_frame(311u, 55u, 90.0f, 1u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    f = float_frame(321u, 0u, 359.5f, 1u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    f = float_frame(321u, 1u, -180.0f, 1u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    f = float_frame(321u, 2u, 360.5f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    f = float_frame(320u, 0u, 25000.5f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    f = float_frame(1037u, 0u, -180.25f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    f = float_frame(304u, 0u, 500.5f, 1u);
    expect_reject(&dec, &f, FT_CAN_REJECT_RANGE, __LINE__);
    /* Overflow through the scale: finite double 1e300 * 1e10 = inf. */
    ft_can_map m;
    memset(&m, 0, sizeof m);
    ft_can_map_entry e = {100u, FT_QTY_ALT, 1e10, -1e300, 1e300, 100u, 0u};
    REQUIRE(ft_can_map_add(&m, &e, NULL) == FT_OK);
    ft_canaero d2;
    REQUIRE(ft_canaero_init(&d2, &m, NULL) == FT_OK);
    f = frame(100u, 8u, FT_CAN_TYPE_DOUBLEH, 0u, 0x7Eu, 0x37u, 0xE4u, 0x3Cu, 1u);
    CHECK(ft_canaero_decode(&d2, &f, &r) == FT_CAN_PENDING);
    f = frame(100u, 8u, FT_CAN_TYPE_DOUBLEL, 1u, 0x88u, 0x00u, 0x75u, 0x9Cu, 1u);
    expect_reject(&d2, &f, FT_CAN_REJECT_NONFINITE, __LINE__);
    /* FLOAT's largest finite value (7F 7F FF FF) is finite here, in range. */
    f = frame(100u, 8u, FT_CAN_TYPE_FLOAT, 2u, 0x7Fu, 0x7Fu, 0xFFu, 0xFFu, 1u);
    CHECK(ft_canaero_decode(&d2, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.value == (double)3.40282346638528859812e+38F * 1e10);
    /* NULL frame / decoder never crash. */
    CHECK(ft_canaero_decode(&dec, NULL, &r) == FT_CAN_REJECTED);
    CHECK(ft_canaero_decode(NULL, &f, &r) == FT_CAN_REJECTED);
    CHECK(ft_canaero_decode(&dec, &f, NULL) == FT_CAN_REJECTED);
    /* Names. */
    CHECK(strcmp(ft_can_reject_name(FT_CAN_REJECT_DLC), "FT_CAN_REJECT_DLC") == 0);
    CHECK(strcmp(ft_can_reject_name(FT_CAN_REJECT_DOUBLE_HALF_MISSING),
                 "FT_CAN_REJECT_DOUBLE_HALF_MISSING") == 0);
    CHECK(strcmp(ft_can_reject_text(FT_CAN_REJECT_RANGE), "value out of range for the quantity") ==
          0);
    CHECK(strcmp(ft_can_reject_name(FT_CAN_REJECT_COUNT), "FT_CAN_REJECT_?") == 0);
}

static void test_counters(void)
{
    ft_canaero dec;
    init_default(&dec);
    ft_can_result r;
    /* 254, 255, 0 wrap: nothing lost. */
    static const uint8_t wrap[] = {254u, 255u, 0u, 1u};
    for (size_t i = 0; i < sizeof wrap / sizeof wrap[0]; ++i) {
        ft_can_frame f = float_frame(312u, wrap[i], (float)i, 100u * i);
        CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
        CHECK(r.lost == 0u);
    }
    CHECK(dec.lost == 0u);
    /* 10 -> 13 loses 2 (accepted). */
    ft_can_frame f = float_frame(311u, 10u, 1.0f, 1u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    f = float_frame(311u, 13u, 2.0f, 2u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.lost == 2u && r.input.value == 2.0);
    CHECK(dec.lost == 2u && dec.st[0].lost == 2u);
    /* 255 -> 1 across the wrap loses 1 (code 0); each jump is confirmed as
     * a gap by the frame after it (it follows the jump). */
    f = float_frame(311u, 255u, 3.0f, 3u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.lost == 241u && r.out_of_sequence == 0u); /* 13 -> 255 */
    f = float_frame(311u, 1u, 4.0f, 4u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.lost == 1u && r.out_of_sequence == 0u);
    CHECK(dec.lost == 2u + 241u + 1u);
    /* Duplicate: same code twice is rejected, even with another value. */
    f = float_frame(311u, 1u, 5.0f, 5u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_COUNTER_REPEAT);
    CHECK(dec.rejects[FT_CAN_REJECT_COUNTER_REPEAT] == 1u);
    /* Counters are per id: code 1 on another id is fine. */
    f = float_frame(321u, 1u, 5.0f, 5u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    /* A frame rejected for its value still advances the history, so its
     * retransmission is a duplicate and no loss is counted after it. */
    f = float_frame(311u, 2u, 95.0f, 6u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_RANGE);
    f = float_frame(311u, 2u, 5.0f, 7u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED);
    CHECK(r.reason == FT_CAN_REJECT_COUNTER_REPEAT);
    f = float_frame(311u, 3u, 5.0f, 8u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.lost == 0u);
    CHECK(dec.lost == 2u + 241u + 1u && dec.out_of_sequence == 0u);
}

/* Feeds one id the codes (FLOAT pitch frames, all valid) on a fresh decoder;
 * returns the lost and out-of-sequence counts. */
static void run_codes(const uint8_t *codes, size_t n, uint64_t *lost, uint64_t *oos)
{
    ft_canaero dec;
    init_default(&dec);
    for (size_t i = 0; i < n; ++i) {
        ft_can_frame f = float_frame(311u, codes[i], 1.0f, 1000u * i);
        ft_can_result r;
        CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    }
    *lost = dec.lost;
    *oos = dec.out_of_sequence;
    CHECK(dec.st[0].lost == dec.lost && dec.st[0].out_of_sequence == dec.out_of_sequence);
}

#define CODES(...) (const uint8_t[]){__VA_ARGS__}, sizeof((const uint8_t[]){__VA_ARGS__})

/* Out-of-sequence frames are not gaps: one frame whose code jumps ahead
 * after which the sequence resumes used to count 255 lost, two swapped
 * frames 256. */
static void test_sequence_anomalies(void)
{
    uint64_t lost = 0u, oos = 0u;
    /* one frame jumps ahead, the sequence resumes */
    run_codes(CODES(0, 1, 2, 3, 4, 200, 5, 6, 7, 8), &lost, &oos);
    printf("jump ahead and resume: %llu lost, %llu out of sequence\n", (unsigned long long)lost,
           (unsigned long long)oos);
    CHECK(lost == 0u && oos == 1u);
    /* two frames swapped */
    run_codes(CODES(0x00, 0x02, 0x01, 0x03, 0x04), &lost, &oos);
    printf("swapped: %llu lost, %llu out of sequence\n", (unsigned long long)lost,
           (unsigned long long)oos);
    CHECK(lost == 0u && oos == 1u);
    /* a real gap: 3 and 4 missing */
    run_codes(CODES(0, 1, 2, 5, 6), &lost, &oos);
    CHECK(lost == 2u && oos == 0u);
    /* the wrap */
    run_codes(CODES(254, 255, 0, 1), &lost, &oos);
    CHECK(lost == 0u && oos == 0u);
    /* a gap across the wrap: 255 and 0 missing */
    run_codes(CODES(253, 254, 1, 2), &lost, &oos);
    CHECK(lost == 2u && oos == 0u);
    /* a swap across the wrap */
    run_codes(CODES(254, 0, 255, 1, 2), &lost, &oos);
    CHECK(lost == 0u && oos == 1u);
    /* two gaps in a row: 3, 4 then 6, 7, 8 */
    run_codes(CODES(0, 1, 2, 5, 9, 10), &lost, &oos);
    CHECK(lost == 5u && oos == 0u);
    /* a corrupt code in a lossy stream: 200 is out of sequence, 3 lost */
    run_codes(CODES(0, 1, 2, 200, 4, 5), &lost, &oos);
    CHECK(lost == 1u && oos == 1u);
    /* the result: the gap on the frame after it, the anomaly on the frame
     * that shows it (which withdraws the gap counted before) */
    ft_canaero dec;
    init_default(&dec);
    ft_can_result r;
    static const uint8_t k_seq[] = {0, 1, 200, 2, 3, 6, 7};
    static const uint8_t k_oos[] = {0, 0, 0, 1, 0, 0, 0};
    static const uint8_t k_lost[] = {0, 0, 198, 0, 0, 2, 0}; /* 198: withdrawn at 2 */
    for (size_t i = 0; i < sizeof k_seq; ++i) {
        ft_can_frame f = float_frame(312u, k_seq[i], 1.0f, 1000u * i);
        CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
        CHECK(r.out_of_sequence == k_oos[i] && r.lost == k_lost[i]);
    }
    /* a long stream: 1000 frames wrapping 3 times, with one jump ahead, one
     * swap and one real gap of 4 */
    uint8_t codes[1000];
    uint8_t c = 0u;
    for (size_t i = 0; i < sizeof codes; ++i) {
        if (i == 300) {
            c = (uint8_t)(c + 4u); /* 4 lost */
        }
        codes[i] = c++;
    }
    codes[100] = 17u; /* jumps ahead of 100, the sequence resumes at 101 */
    const uint8_t t = codes[600];
    codes[600] = codes[601]; /* swapped */
    codes[601] = t;
    run_codes(codes, sizeof codes, &lost, &oos);
    printf("long stream: %llu lost, %llu out of sequence\n", (unsigned long long)lost,
           (unsigned long long)oos);
    /* the frame whose code was overwritten (100) is one lost message */
    CHECK(lost == 4u + 1u && oos == 2u);
}

/* The velocity ids: decoded in their units, validated and counted per reason
 * and per quantity like every other quantity. */
static void test_velocity_ids(void)
{
    ft_canaero dec;
    init_default(&dec);
    ft_can_result r;
    const uint64_t t0 = UINT64_C(2000000000);
    /* 1039 ground speed 250 m/s, 1040 true track 45 deg, 314 altitude rate -12.5 m/s */
    ft_can_frame f = float_frame(1039u, 0u, 250.0f, t0);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_GROUND_SPEED && r.input.value == 250.0);
    CHECK(r.input.timeout_ms == 500u && r.input.source_id == 1039u);
    f = float_frame(1040u, 0u, 45.0f, t0 + 1u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_TRACK && r.input.value == 45.0);
    f = float_frame(314u, 0u, -12.5f, t0 + 2u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_ALT_RATE && r.input.value == -12.5);
    CHECK(dec.accepted == 3u);

    /* NaN, negative, infinite, out of range, wrong DLC, duplicate: rejected,
     * by reason and by quantity */
    f = frame(1039u, 8u, FT_CAN_TYPE_FLOAT, 1u, 0x7Fu, 0xC0u, 0u, 0u, t0 + 10u); /* NaN */
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_NONFINITE);
    f = float_frame(1039u, 2u, -1.0f, t0 + 11u); /* negative speed */
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_RANGE);
    f = float_frame(1039u, 3u, 1000.5f, t0 + 12u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_RANGE);
    f = float_frame(1040u, 1u, 361.0f, t0 + 13u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_RANGE);
    f = frame(1040u, 8u, FT_CAN_TYPE_FLOAT, 2u, 0xFFu, 0x80u, 0u, 0u, t0 + 14u); /* -inf */
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_NONFINITE);
    f = float_frame(314u, 1u, 500.5f, t0 + 15u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_RANGE);
    f = float_frame(314u, 2u, 5.0f, t0 + 16u);
    f.dlc = 7u;
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_DLC);
    f = float_frame(314u, 1u, 5.0f, t0 + 17u); /* code 1 again */
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED &&
          r.reason == FT_CAN_REJECT_COUNTER_REPEAT);
    /* an unknown id has no quantity */
    f = float_frame(1041u, 0u, 5.0f, t0 + 18u);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_UNKNOWN_ID);
    CHECK(dec.rejects_by_qty[FT_QTY_GROUND_SPEED] == 3u);
    CHECK(dec.rejects_by_qty[FT_QTY_TRACK] == 2u);
    CHECK(dec.rejects_by_qty[FT_QTY_ALT_RATE] == 3u);
    CHECK(dec.rejects[FT_CAN_REJECT_NONFINITE] == 2u && dec.rejects[FT_CAN_REJECT_RANGE] == 4u);
    CHECK(dec.rejects[FT_CAN_REJECT_DLC] == 1u && dec.rejects[FT_CAN_REJECT_COUNTER_REPEAT] == 1u);
    CHECK(dec.rejects[FT_CAN_REJECT_UNKNOWN_ID] == 1u);
    uint64_t by_qty = 0u;
    for (int q = 0; q < (int)FT_QTY_COUNT; ++q) {
        by_qty += dec.rejects_by_qty[q];
    }
    CHECK(by_qty == 8u && dec.accepted == 3u);

    /* replaceable: a map with ground speed in knots (scale 0.514444 m/s per
     * kt) on another id, range in m/s */
    ft_can_map m;
    ft_canaero_default_map(&m);
    for (uint32_t i = 0; i < m.count; ++i) {
        if (m.e[i].can_id == 1039u) {
            m.e[i].can_id = 1500u;
            m.e[i].scale = 0.514444;
        }
    }
    REQUIRE(ft_canaero_init(&dec, &m, NULL) == FT_OK);
    f = float_frame(1500u, 0u, 100.0f, t0);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
    CHECK(r.input.qty == FT_QTY_GROUND_SPEED);
    CHECK_NEAR(r.input.value, 51.4444, 1e-9);
    f = float_frame(1039u, 0u, 100.0f, t0);
    CHECK(ft_canaero_decode(&dec, &f, &r) == FT_CAN_REJECTED && r.reason == FT_CAN_REJECT_UNKNOWN_ID);
}

/* End to end: decoded values reach the pose; rejected frames never do. */
static void test_into_pose(void)
{
    ft_canaero dec;
    init_default(&dec);
    ft_pose_state ps;
    REQUIRE(ft_pose_state_init(&ps, 100u, NULL) == FT_OK);
    const uint64_t t0 = UINT64_C(1000000000);
    static const struct {
        uint32_t id;
        float v;
    } feed[] = {{311u, 5.0f},    {312u, -10.0f},  {321u, 270.0f},  {303u, 0.0f},
                {304u, 0.0f},    {305u, 0.0f},    {1036u, 46.5f},  {1037u, -121.75f},
                {320u, 1500.0f}, {1038u, 1530.0f}, {1039u, 0.0f},  {1040u, 0.0f},
                {314u, 0.0f}};
    for (size_t i = 0; i < sizeof feed / sizeof feed[0]; ++i) {
        ft_can_frame f = float_frame(feed[i].id, 0u, feed[i].v, t0);
        ft_can_result r;
        REQUIRE(ft_canaero_decode(&dec, &f, &r) == FT_CAN_VALUE);
        CHECK(ft_pose_state_apply(&ps, &r.input, NULL, NULL) == FT_OK);
    }
    ft_pose_estimate e;
    ft_pose_state_estimate(&ps, t0 + 10000000u, &e);
    CHECK(e.stale_mask == 0u);
    CHECK_NEAR(e.pose.pitch_deg, 5.0, 1e-9);
    CHECK_NEAR(e.pose.roll_deg, -10.0, 1e-9);
    CHECK_NEAR(e.pose.heading_deg, 270.0, 1e-9);
    CHECK(e.pose.lat_deg == 46.5 && e.pose.lon_deg == -121.75);
    CHECK(e.pose.alt_m == 1500.0); /* baro wins over GPS height */

    /* Out-of-range pitch, NaN roll, duplicate heading: all rejected, none
     * applied, the pose keeps its last good values. */
    ft_can_frame bad[3];
    bad[0] = float_frame(311u, 1u, 120.0f, t0 + 20000000u);
    bad[1] = frame(312u, 8u, FT_CAN_TYPE_FLOAT, 1u, 0x7Fu, 0xC0u, 0u, 0u, t0 + 20000000u);
    bad[2] = float_frame(321u, 0u, 10.0f, t0 + 20000000u);
    for (int i = 0; i < 3; ++i) {
        ft_can_result r;
        CHECK(ft_canaero_decode(&dec, &bad[i], &r) == FT_CAN_REJECTED);
    }
    uint64_t applied_before = ps.applied_count;
    ft_pose_state_estimate(&ps, t0 + 20000000u, &e);
    CHECK(ps.applied_count == applied_before);
    CHECK_NEAR(e.pose.pitch_deg, 5.0, 1e-9);
    CHECK_NEAR(e.pose.roll_deg, -10.0, 1e-9);
    CHECK_NEAR(e.pose.heading_deg, 270.0, 1e-9);
}

int main(void)
{
    test_default_map();
    test_map_checks();
    test_data_types();
    test_double_pairs();
    test_rejects();
    test_counters();
    test_sequence_anomalies();
    test_velocity_ids();
    test_into_pose();
    return ft_test_result("test_canaero");
}
