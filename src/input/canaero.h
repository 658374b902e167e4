/* canaero.h - CANaerospace 1.7 normal-operation frames -> pose quantities.
 *
 * Frame layout (11-bit id, DLC 4..8):
 *   byte 0 node-id, byte 1 data type, byte 2 service code, byte 3 message
 *   code (a per-id counter 0..255 that wraps), bytes 4..7 data, big-endian.
 * Data types handled: FLOAT (2, IEEE 754 single), LONG (3, int32), SHORT (6,
 * int16 in bytes 4-5; DLC 6, or DLC 8 with padding), DOUBLEH/DOUBLEL (30/31,
 * the high then the low 32 bits of an IEEE 754 double, sent as two messages
 * with the same id and consecutive message codes). Every other type is
 * rejected (FT_CAN_REJECT_TYPE); DLC must be exactly 8 for FLOAT, LONG and
 * the double halves.
 *
 * Each frame is checked in this order, and the first failing check is the
 * reason it is rejected (a rejected frame is never applied):
 *   1. id in the map (11-bit, not extended)           FT_CAN_REJECT_UNKNOWN_ID
 *   2. DLC in 4..8                                    FT_CAN_REJECT_DLC
 *   3. data type known                                FT_CAN_REJECT_TYPE
 *   4. DLC right for the data type                    FT_CAN_REJECT_DLC
 *   5. message code differs from the last one         FT_CAN_REJECT_COUNTER_REPEAT
 *      (same code twice = duplicate). Any other code is accepted; the
 *      counters then tell a gap from a frame out of sequence (below).
 *   6. DOUBLEL completes the DOUBLEH with the code just before it, else it
 *      is rejected                                    FT_CAN_REJECT_DOUBLE_HALF_MISSING
 *      A stored DOUBLEH whose low half does not follow is abandoned by the
 *      next frame of its id that passes 1-5 and counted under the same
 *      reason, so that counter is the number of halves that never paired.
 *   7. value finite (raw and after scale)             FT_CAN_REJECT_NONFINITE
 *   8. scaled value in [min, max] of the map entry    FT_CAN_REJECT_RANGE
 * Message-code accounting (per id, codes wrap 255 -> 0; "expected" is the
 * code after the last frame in sequence):
 *   - the expected code: in sequence, nothing counted (254 255 0 1);
 *   - any other code is a jump: the codes skipped are counted lost at once
 *     (0 1 2 5: 3 and 4, 2 lost), and the next frame of the id judges it.
 *     That frame continues either the sequence after the jump or the one
 *     before it, whichever it is nearer to (fewer codes ahead, with wrap):
 *       * after the jump (0 1 2 5 6): a real gap, the count stands;
 *       * before it (0 1 2 3 4 200 5 6: 5 follows 4): the jumped frame was
 *         out of sequence (a corrupt code, or a frame sent early): its
 *         count is withdrawn and it is counted once in out_of_sequence;
 *         when the jumped frame is the one after this one, the two were
 *         swapped and the sequence goes on after both (00 02 01 03: 1 out
 *         of sequence, nothing lost);
 *     then the new frame is itself in sequence or a new jump (0 1 2 5 9 10:
 *     2 + 3 lost; 0 1 2 200 4 5: 200 out of sequence, 3 lost).
 *   A jump on the last frame of an id stays counted as a gap.
 * The counter history is updated by every frame that passes 1-5, including
 * frames rejected later for their value: the message was transmitted and
 * received, so it is not lost, and a retransmission of it is a duplicate.
 * With 256 codes a loss of exactly 256 messages looks like a duplicate and a
 * silence longer than the timeout makes the gap count a lower bound; both
 * are inherent in an 8-bit counter.
 *
 * Node-id and service code are passed through, not checked (a map entry is
 * per id, and in normal operation the service code is user-defined).
 *
 * Storage: the map and all state live in the caller's ft_canaero. */
#ifndef FT_CANAERO_H
#define FT_CANAERO_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"
#include "input/pose_state.h"

/* One classic CAN frame as received (also what candump.h parses). */
typedef struct ft_can_frame {
    uint32_t can_id;  /* 11-bit, or 29-bit when extended */
    uint8_t extended; /* 1 for a 29-bit id */
    uint8_t dlc;      /* 0..8 data bytes */
    uint8_t data[8];  /* bytes past dlc are 0 */
    uint64_t t_ns;    /* receive time */
} ft_can_frame;

#define FT_CAN_STD_ID_MAX 0x7FFu
#define FT_CAN_EXT_ID_MAX 0x1FFFFFFFu

/* CANaerospace data type codes used here. */
#define FT_CAN_TYPE_FLOAT 2u
#define FT_CAN_TYPE_LONG 3u
#define FT_CAN_TYPE_SHORT 6u
#define FT_CAN_TYPE_DOUBLEH 30u
#define FT_CAN_TYPE_DOUBLEL 31u

/* X(id, text) */
#define FT_CAN_REJECT_LIST(X)                                                 \
    X(FT_CAN_REJECT_UNKNOWN_ID, "CAN id not in the map (or extended)")        \
    X(FT_CAN_REJECT_DLC, "wrong DLC for the data type")                       \
    X(FT_CAN_REJECT_TYPE, "unknown data type")                                \
    X(FT_CAN_REJECT_COUNTER_REPEAT, "repeated message code (duplicate)")     \
    X(FT_CAN_REJECT_DOUBLE_HALF_MISSING, "DOUBLEH/DOUBLEL half missing")     \
    X(FT_CAN_REJECT_NONFINITE, "value is NaN or infinite")                    \
    X(FT_CAN_REJECT_RANGE, "value out of range for the quantity")

typedef enum ft_can_reject {
#define FT_CAN_REJECT_ENUM(id, text) id,
    FT_CAN_REJECT_LIST(FT_CAN_REJECT_ENUM)
#undef FT_CAN_REJECT_ENUM
    FT_CAN_REJECT_COUNT
} ft_can_reject;

const char *ft_can_reject_name(ft_can_reject r); /* "FT_CAN_REJECT_DLC" */
const char *ft_can_reject_text(ft_can_reject r); /* "wrong DLC for the data type" */

/* ---- mapping table --------------------------------------------------------- */

/* Room for a primary and a backup source of every quantity. */
#define FT_CAN_MAP_MAX 24u

typedef struct ft_can_map_entry {
    uint16_t can_id;     /* 11-bit */
    ft_pose_qty qty;
    double scale;        /* decoded number * scale = value in the quantity's unit */
    double min_value;    /* valid range after scaling, inclusive */
    double max_value;
    uint32_t timeout_ms; /* stale this long after the last good value */
    uint8_t priority;    /* 0 = primary; a larger number is a backup source */
} ft_can_map_entry;

typedef struct ft_can_map {
    ft_can_map_entry e[FT_CAN_MAP_MAX];
    uint32_t count;
} ft_can_map;

/* The CANaerospace 1.7 default identifiers (units as the standard sends
 * them: deg, deg/s, m, m/s), scale 1:
 *   311 body pitch angle    pitch       -90 ..    90 deg    100 ms
 *   312 body roll angle     roll       -180 ..   180 deg    100 ms
 *   321 heading angle       heading    -360 ..   360 deg    100 ms
 *   303 body pitch rate     pitch_rate -500 ..   500 deg/s  100 ms
 *   304 body roll rate      roll_rate  -500 ..   500 deg/s  100 ms
 *   305 body yaw rate       yaw_rate   -500 ..   500 deg/s  100 ms
 *  1036 GPS latitude        lat         -90 ..    90 deg    500 ms
 *  1037 GPS longitude       lon        -180 ..   180 deg    500 ms
 *   320 baro corr. altitude alt       -1000 .. 25000 m      500 ms  priority 0
 *  1038 GPS height          alt       -1000 .. 25000 m      500 ms  priority 1
 *  1039 GPS ground speed    ground_speed  0 ..  1000 m/s    500 ms
 *  1040 GPS true track      track      -360 ..   360 deg    500 ms
 *   314 altitude rate       alt_rate   -500 ..   500 m/s    500 ms
 * Heading accepts -360..360 because senders differ (0..360 or +-180); the
 * pose wraps it. 500 deg/s is beyond any airframe's sustained rate, so a
 * larger rate is a fault, not flight. 25000 m is above the service ceiling
 * of the aircraft this display targets; -1000 m covers the Dead Sea and the
 * geoid below the ellipsoid. 1038 is height above the ellipsoid, a backup
 * for the baro altitude only while 320 is silent (see ft_pose_state_apply).
 * The velocity feeds the position prediction (pose_state.h): 1000 m/s is
 * beyond the ground speed of any airframe this display targets (and the
 * fastest path fixterrain-flightgen accepts); a negative ground speed is not
 * a speed. 500 m/s vertical is beyond any sustained climb or dive. Track
 * accepts -360..360 for the same reason as heading. Their timeout is the
 * position's: a GPS sends velocity with every fix. */
void ft_canaero_default_map(ft_can_map *m);

/* Appends one entry after checking it: id <= 0x7FF and not already mapped,
 * qty valid, scale finite and non-zero, min <= max both finite, timeout > 0,
 * room left (FT_ERR_BUDGET when full). */
ft_status ft_can_map_add(ft_can_map *m, const ft_can_map_entry *e, ft_error *err);

/* ---- decoder --------------------------------------------------------------- */

typedef struct ft_can_id_state {
    uint8_t has_code;        /* a message code was seen */
    uint8_t last_code;       /* of the last frame (duplicate check) */
    uint8_t expect_code;     /* the code after the last frame in sequence */
    uint8_t has_jump;        /* the last frame jumped (its gap counted); the next judges it */
    uint8_t jump_code;
    uint8_t has_high;        /* a DOUBLEH is waiting for its DOUBLEL */
    uint8_t high_code;
    uint32_t high_bits;
    uint64_t high_t_ns;
    uint64_t lost;           /* messages lost on this id */
    uint64_t out_of_sequence; /* frames out of sequence on this id */
} ft_can_id_state;

typedef struct ft_canaero {
    ft_can_map map;
    ft_can_id_state st[FT_CAN_MAP_MAX];
    uint64_t rejects[FT_CAN_REJECT_COUNT];
    /* The same rejects by the quantity of the frame's id (steps 2..8; an
     * unknown id has no quantity and is only in rejects[]). */
    uint64_t rejects_by_qty[FT_QTY_COUNT];
    uint64_t accepted;       /* frames that produced a value */
    uint64_t pending;        /* DOUBLEH halves stored */
    uint64_t lost;           /* all ids */
    uint64_t out_of_sequence; /* all ids */
} ft_canaero;

/* Copies the map (every entry re-checked as by ft_can_map_add) and clears
 * all counters and histories. */
ft_status ft_canaero_init(ft_canaero *dec, const ft_can_map *map, ft_error *err);

typedef enum ft_can_outcome {
    FT_CAN_VALUE,    /* out->input holds a value ready for ft_pose_state_apply */
    FT_CAN_PENDING,  /* a DOUBLEH was stored; the value comes with its DOUBLEL */
    FT_CAN_REJECTED  /* out->reason says why; nothing to apply */
} ft_can_outcome;

typedef struct ft_can_result {
    ft_can_outcome outcome;
    ft_can_reject reason; /* valid when rejected */
    uint8_t node_id, data_type, service_code, message_code;
    uint32_t lost;        /* codes skipped just before this one (withdrawn if it turns
                           * out to be out of sequence) */
    uint8_t out_of_sequence; /* 1: this frame showed the one before it out of sequence
                              * (and withdrew that frame's lost count) */
    ft_pose_input input;  /* valid when outcome == FT_CAN_VALUE */
} ft_can_result;

/* Decodes one frame and updates the counters. For a double the value's time
 * is the DOUBLEH's receive time (the sample was taken before it was split).
 * out may be NULL when only the counters matter. */
ft_can_outcome ft_canaero_decode(ft_canaero *dec, const ft_can_frame *f, ft_can_result *out);

#endif
