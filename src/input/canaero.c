/* canaero.c - CANaerospace normal-operation decoder (contract in canaero.h).
 * Bytes are assembled with shifts and reinterpreted with memcpy, so the
 * result does not depend on the host's byte order. */
#include "input/canaero.h"

#include <math.h>
#include <string.h>

_Static_assert(sizeof(float) == 4, "CANaerospace FLOAT is IEEE 754 single");
_Static_assert(sizeof(double) == 8, "CANaerospace DOUBLEH/L is IEEE 754 double");

static const char *const k_reject_name[FT_CAN_REJECT_COUNT] = {
#define FT_CAN_REJECT_NAME(id, text) #id,
    FT_CAN_REJECT_LIST(FT_CAN_REJECT_NAME)
#undef FT_CAN_REJECT_NAME
};

static const char *const k_reject_text[FT_CAN_REJECT_COUNT] = {
#define FT_CAN_REJECT_TEXT(id, text) text,
    FT_CAN_REJECT_LIST(FT_CAN_REJECT_TEXT)
#undef FT_CAN_REJECT_TEXT
};

const char *ft_can_reject_name(ft_can_reject r)
{
    return ((int)r >= 0 && r < FT_CAN_REJECT_COUNT) ? k_reject_name[r] : "FT_CAN_REJECT_?";
}

const char *ft_can_reject_text(ft_can_reject r)
{
    return ((int)r >= 0 && r < FT_CAN_REJECT_COUNT) ? k_reject_text[r] : "unknown reason";
}

/* ---- mapping table --------------------------------------------------------- */

static ft_status check_entry(const ft_can_map_entry *e, ft_error *err)
{
    if (e->can_id > FT_CAN_STD_ID_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u is not an 11-bit id",
                       (unsigned)e->can_id);
    }
    if ((int)e->qty < 0 || e->qty >= FT_QTY_COUNT) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u has an unknown quantity %d",
                       (unsigned)e->can_id, (int)e->qty);
    }
    if (!isfinite(e->scale) || e->scale == 0.0) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u (%s) scale must be finite and non-zero",
                       (unsigned)e->can_id, ft_pose_qty_name(e->qty));
    }
    if (!isfinite(e->min_value) || !isfinite(e->max_value) || e->min_value > e->max_value) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u (%s) range [%g, %g] is not valid",
                       (unsigned)e->can_id, ft_pose_qty_name(e->qty), e->min_value,
                       e->max_value);
    }
    if (e->timeout_ms == 0u) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u (%s) timeout must be > 0 ms",
                       (unsigned)e->can_id, ft_pose_qty_name(e->qty));
    }
    return FT_OK;
}

ft_status ft_can_map_add(ft_can_map *m, const ft_can_map_entry *e, ft_error *err)
{
    if (m == NULL || e == NULL) {
        return ft_fail(err, FT_ERR_ARG, "CAN map: no map or entry");
    }
    ft_status s = check_entry(e, err);
    if (s != FT_OK) {
        return s;
    }
    if (m->count > FT_CAN_MAP_MAX) {
        return ft_fail(err, FT_ERR_ARG, "CAN map: corrupt count %u", (unsigned)m->count);
    }
    for (uint32_t i = 0u; i < m->count; ++i) {
        if (m->e[i].can_id == e->can_id) {
            return ft_fail(err, FT_ERR_CONFIG, "CAN map: id %u is mapped twice",
                           (unsigned)e->can_id);
        }
    }
    if (m->count == FT_CAN_MAP_MAX) {
        return ft_fail(err, FT_ERR_BUDGET, "CAN map: full (%u entries) adding id %u",
                       FT_CAN_MAP_MAX, (unsigned)e->can_id);
    }
    m->e[m->count++] = *e;
    return FT_OK;
}

void ft_canaero_default_map(ft_can_map *m)
{
    if (m == NULL) {
        return;
    }
    /* id, qty, scale, min, max, timeout_ms, priority */
    static const ft_can_map_entry k_defaults[] = {
        {311u, FT_QTY_PITCH, 1.0, -90.0, 90.0, 100u, 0u},
        {312u, FT_QTY_ROLL, 1.0, -180.0, 180.0, 100u, 0u},
        {321u, FT_QTY_HEADING, 1.0, -360.0, 360.0, 100u, 0u},
        {303u, FT_QTY_PITCH_RATE, 1.0, -500.0, 500.0, 100u, 0u},
        {304u, FT_QTY_ROLL_RATE, 1.0, -500.0, 500.0, 100u, 0u},
        {305u, FT_QTY_YAW_RATE, 1.0, -500.0, 500.0, 100u, 0u},
        {1036u, FT_QTY_LAT, 1.0, -90.0, 90.0, 500u, 0u},
        {1037u, FT_QTY_LON, 1.0, -180.0, 180.0, 500u, 0u},
        {320u, FT_QTY_ALT, 1.0, -1000.0, 25000.0, 500u, 0u},
        {1038u, FT_QTY_ALT, 1.0, -1000.0, 25000.0, 500u, 1u},
        {1039u, FT_QTY_GROUND_SPEED, 1.0, 0.0, 1000.0, 500u, 0u},
        {1040u, FT_QTY_TRACK, 1.0, -360.0, 360.0, 500u, 0u},
        {314u, FT_QTY_ALT_RATE, 1.0, -500.0, 500.0, 500u, 0u},
    };
    _Static_assert(sizeof k_defaults / sizeof k_defaults[0] <= FT_CAN_MAP_MAX,
                   "default map fits");
    memset(m, 0, sizeof *m);
    for (size_t i = 0u; i < sizeof k_defaults / sizeof k_defaults[0]; ++i) {
        m->e[i] = k_defaults[i];
    }
    m->count = (uint32_t)(sizeof k_defaults / sizeof k_defaults[0]);
}

/* ---- decoder --------------------------------------------------------------- */

ft_status ft_canaero_init(ft_canaero *dec, const ft_can_map *map, ft_error *err)
{
    if (dec == NULL || map == NULL) {
        return ft_fail(err, FT_ERR_ARG, "CANaerospace decoder: no storage or map");
    }
    if (map->count > FT_CAN_MAP_MAX) {
        return ft_fail(err, FT_ERR_CONFIG, "CAN map: %u entries, at most %u",
                       (unsigned)map->count, FT_CAN_MAP_MAX);
    }
    memset(dec, 0, sizeof *dec);
    for (uint32_t i = 0u; i < map->count; ++i) {
        /* Re-adding checks each entry and rejects duplicate ids. */
        ft_status s = ft_can_map_add(&dec->map, &map->e[i], err);
        if (s != FT_OK) {
            memset(dec, 0, sizeof *dec);
            return s;
        }
    }
    return FT_OK;
}

static uint32_t be32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) |
           (uint32_t)p[3];
}

/* qty < 0: the frame has no quantity (unknown id). */
static ft_can_outcome reject(ft_canaero *dec, ft_can_result *out, ft_can_reject r, int qty)
{
    ++dec->rejects[r];
    if (qty >= 0 && qty < (int)FT_QTY_COUNT) {
        ++dec->rejects_by_qty[qty];
    }
    if (out != NULL) {
        out->outcome = FT_CAN_REJECTED;
        out->reason = r;
    }
    return FT_CAN_REJECTED;
}

static int dlc_ok_for_type(uint8_t type, uint8_t dlc)
{
    if (type == FT_CAN_TYPE_SHORT) {
        return dlc == 6u || dlc == 8u; /* int16 + optional 2 bytes padding */
    }
    return dlc == 8u;
}

/* The message-code accounting of canaero.h for one frame that passed 1-5.
 * uint8 arithmetic wraps 255 -> 0 for free. */
static void count_sequence(ft_canaero *dec, ft_can_id_state *st, uint8_t code, ft_can_result *out)
{
    uint32_t lost = 0u, withdrawn = 0u;
    uint8_t oos = 0u;
    if (!st->has_code) {
        st->expect_code = (uint8_t)(code + 1u);
    } else {
        if (st->has_jump) {
            /* Which sequence does this frame continue: the one after the
             * jump, or the one before it? The nearer one wins. */
            const uint8_t after_expect = (uint8_t)(code - st->expect_code);
            const uint8_t after_jump = (uint8_t)(code - st->jump_code - 1u);
            if (after_jump <= after_expect) {
                st->expect_code = (uint8_t)(st->jump_code + 1u); /* a real gap: keep it */
            } else {
                oos = 1u; /* the jumped frame was out of sequence: nothing was lost */
                withdrawn = (uint8_t)(st->jump_code - st->expect_code);
            }
            st->has_jump = 0u;
        }
        if (code == st->expect_code) {
            st->expect_code = (uint8_t)(code + 1u);
            if (oos && st->jump_code == st->expect_code) {
                st->expect_code = (uint8_t)(st->expect_code + 1u); /* swapped: it came early */
            }
        } else {
            lost = (uint8_t)(code - st->expect_code); /* until the next frame says otherwise */
            st->has_jump = 1u;
            st->jump_code = code;
        }
    }
    st->has_code = 1u;
    st->last_code = code;
    /* withdrawn was added by the jumped frame, so neither total goes below 0 */
    st->lost = st->lost + lost - withdrawn;
    dec->lost = dec->lost + lost - withdrawn;
    st->out_of_sequence += oos;
    dec->out_of_sequence += oos;
    if (out != NULL) {
        out->lost = lost;
        out->out_of_sequence = oos;
    }
}

ft_can_outcome ft_canaero_decode(ft_canaero *dec, const ft_can_frame *f, ft_can_result *out)
{
    if (out != NULL) {
        memset(out, 0, sizeof *out);
    }
    if (dec == NULL) {
        if (out != NULL) {
            out->outcome = FT_CAN_REJECTED;
            out->reason = FT_CAN_REJECT_UNKNOWN_ID;
        }
        return FT_CAN_REJECTED;
    }
    if (f == NULL) {
        return reject(dec, out, FT_CAN_REJECT_UNKNOWN_ID, -1);
    }
    /* 1. id */
    int idx = -1;
    if (!f->extended && f->can_id <= FT_CAN_STD_ID_MAX) {
        for (uint32_t i = 0u; i < dec->map.count && i < FT_CAN_MAP_MAX; ++i) {
            if (dec->map.e[i].can_id == f->can_id) {
                idx = (int)i;
                break;
            }
        }
    }
    if (idx < 0) {
        return reject(dec, out, FT_CAN_REJECT_UNKNOWN_ID, -1);
    }
    const ft_can_map_entry *me = &dec->map.e[idx];
    const int qty = (int)me->qty;
    /* 2. header present; 3. type; 4. DLC for the type. */
    if (f->dlc < 4u || f->dlc > 8u) {
        return reject(dec, out, FT_CAN_REJECT_DLC, qty);
    }
    uint8_t type = f->data[1];
    uint8_t code = f->data[3];
    if (out != NULL) {
        out->node_id = f->data[0];
        out->data_type = type;
        out->service_code = f->data[2];
        out->message_code = code;
    }
    if (type != FT_CAN_TYPE_FLOAT && type != FT_CAN_TYPE_LONG && type != FT_CAN_TYPE_SHORT &&
        type != FT_CAN_TYPE_DOUBLEH && type != FT_CAN_TYPE_DOUBLEL) {
        return reject(dec, out, FT_CAN_REJECT_TYPE, qty);
    }
    if (!dlc_ok_for_type(type, f->dlc)) {
        return reject(dec, out, FT_CAN_REJECT_DLC, qty);
    }
    /* 5. message code: duplicate or gap. */
    ft_can_id_state *st = &dec->st[idx];
    if (st->has_code && code == st->last_code) {
        return reject(dec, out, FT_CAN_REJECT_COUNTER_REPEAT, qty);
    }
    count_sequence(dec, st, code, out);

    /* 6. double halves. */
    double raw;
    uint64_t t_ns = f->t_ns;
    const uint8_t *d = &f->data[4];
    if (type == FT_CAN_TYPE_DOUBLEH) {
        if (st->has_high) {
            ++dec->rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING]; /* previous high abandoned */
            ++dec->rejects_by_qty[qty];
        }
        st->has_high = 1u;
        st->high_code = code;
        st->high_bits = be32(d);
        st->high_t_ns = f->t_ns;
        ++dec->pending;
        if (out != NULL) {
            out->outcome = FT_CAN_PENDING;
        }
        return FT_CAN_PENDING;
    }
    if (type == FT_CAN_TYPE_DOUBLEL) {
        int paired = st->has_high && (uint8_t)(st->high_code + 1u) == code;
        if (st->has_high && !paired) {
            ++dec->rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING]; /* high abandoned */
            ++dec->rejects_by_qty[qty];
        }
        if (!paired) {
            st->has_high = 0u;
            return reject(dec, out, FT_CAN_REJECT_DOUBLE_HALF_MISSING, qty);
        }
        uint64_t bits = ((uint64_t)st->high_bits << 32) | (uint64_t)be32(d);
        st->has_high = 0u;
        memcpy(&raw, &bits, sizeof raw);
        t_ns = st->high_t_ns;
    } else {
        if (st->has_high) {
            ++dec->rejects[FT_CAN_REJECT_DOUBLE_HALF_MISSING]; /* high abandoned */
            ++dec->rejects_by_qty[qty];
            st->has_high = 0u;
        }
        if (type == FT_CAN_TYPE_FLOAT) {
            uint32_t bits = be32(d);
            float v;
            memcpy(&v, &bits, sizeof v);
            raw = (double)v;
        } else if (type == FT_CAN_TYPE_LONG) {
            uint32_t bits = be32(d);
            int32_t v;
            memcpy(&v, &bits, sizeof v); /* two's complement, no impl-defined cast */
            raw = (double)v;
        } else { /* SHORT */
            uint16_t bits = (uint16_t)(((unsigned)d[0] << 8) | (unsigned)d[1]);
            int16_t v;
            memcpy(&v, &bits, sizeof v);
            raw = (double)v;
        }
    }
    /* 7. finite, 8. range (after scale: the range is in the quantity's unit). */
    double value = raw * me->scale;
    if (!isfinite(raw) || !isfinite(value)) {
        return reject(dec, out, FT_CAN_REJECT_NONFINITE, qty);
    }
    if (value < me->min_value || value > me->max_value) {
        return reject(dec, out, FT_CAN_REJECT_RANGE, qty);
    }
    ++dec->accepted;
    if (out != NULL) {
        out->outcome = FT_CAN_VALUE;
        out->input.qty = me->qty;
        out->input.value = value;
        out->input.t_ns = t_ns;
        out->input.timeout_ms = me->timeout_ms;
        out->input.priority = me->priority;
        out->input.source_id = me->can_id;
    }
    return FT_CAN_VALUE;
}
