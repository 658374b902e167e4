/* debounce.h - debouncing of discrete inputs (gpio.debounce_ms,
 * gpio.active_low). Pure logic: no OS, no clock of its own, no heap; all
 * state lives in the caller's ft_debounce (static size).
 *
 * Per input slot the debouncer keeps the raw physical level (the last edge
 * or sample it was given) and the debounced level. A raw level becomes the
 * debounced level once it has held for debounce_ms without another edge:
 * an edge at t0 with no further edge changes the debounced level at exactly
 * t0 + debounce_ms (a poll at t0 + debounce_ms - 1 ns does not see it, a poll
 * or a later edge at t0 + debounce_ms does). Bounces shorter than
 * debounce_ms never show. debounce_ms = 0 passes every edge: each edge that
 * changes the level is a change at its own time.
 *
 * Levels handed out are logical: physical XOR active_low (active_low = 1:
 * a line pulled low is active).
 *
 * Time: nanoseconds on any one monotonic base (the platform's
 * ft_plat_monotonic_ns; GPIO edge times are converted to it). Edges must be
 * fed per slot in time order; an edge stamped before the previous one of its
 * slot is treated as happening at the previous one's time (counted in
 * `reordered`), so time never runs backwards inside a slot.
 *
 * An edge in the direction the raw level already has (e.g. two rising edges
 * in a row) means the opposite edge between them was lost (a kernel event
 * FIFO overflow, or a glitch shorter than the hardware can report): the line
 * bounced, so the hold time restarts at that edge (counted in `repeated`).
 * ft_debounce_sample() instead feeds an observed level (a periodic read of
 * the line): it only acts when the level differs from the raw one, which
 * repairs a lost edge without restarting a hold. */
#ifndef FT_DEBOUNCE_H
#define FT_DEBOUNCE_H

#include <stdint.h>

#include "core/ft_status.h"

#define FT_DEBOUNCE_SLOTS_MAX 8u    /* = FT_GPIO_LINES_MAX */
#define FT_DEBOUNCE_MS_MAX 60000u   /* scene range is [0, 1000] */

typedef struct ft_debounce_slot {
    uint8_t raw;          /* last physical level fed (0/1) */
    uint8_t stable;       /* debounced physical level (0/1) */
    uint64_t raw_since_ns; /* time of the edge that set `raw` */
} ft_debounce_slot;

typedef struct ft_debounce {
    uint32_t slot_count;
    uint64_t debounce_ns;
    uint8_t active_low;
    ft_debounce_slot slot[FT_DEBOUNCE_SLOTS_MAX];
    uint64_t changes;   /* debounced changes reported */
    uint64_t repeated;  /* edges in the direction the level already had */
    uint64_t reordered; /* edges older than the previous edge of their slot */
    uint64_t bad_slot;  /* edges or samples for a slot >= slot_count (ignored) */
} ft_debounce;

/* One debounced change. */
typedef struct ft_debounce_change {
    uint32_t slot;
    int active;    /* new logical level: 1 active, 0 inactive */
    uint64_t t_ns; /* when it became valid: last edge + debounce */
} ft_debounce_change;

/* physical_levels[slot_count]: the levels read at now_ns (0/1; any non-zero
 * value is 1). They are taken as already debounced: no change is reported for
 * them. Fails (FT_ERR_ARG) on slot_count 0 or > FT_DEBOUNCE_SLOTS_MAX,
 * debounce_ms > FT_DEBOUNCE_MS_MAX, or NULL pointers. */
ft_status ft_debounce_init(ft_debounce *d, uint32_t slot_count, uint32_t debounce_ms,
                           int active_low, const int *physical_levels, uint64_t now_ns,
                           ft_error *err);

/* Feeds one edge (rising = 1: the physical level is now 1). Returns 1 and
 * fills *change when the debounced level changed, 0 otherwise (at most one
 * change per call: the level held before this edge if it had held long
 * enough, or with debounce 0 this edge itself). */
int ft_debounce_edge(ft_debounce *d, uint32_t slot, int rising, uint64_t t_ns,
                     ft_debounce_change *change);

/* Feeds an observed physical level at t_ns: an edge if it differs from the
 * raw level, else nothing (the hold time does not restart). */
int ft_debounce_sample(ft_debounce *d, uint32_t slot, int level, uint64_t t_ns,
                       ft_debounce_change *change);

/* Advances every slot to now_ns: writes the changes that became valid at or
 * before now_ns (at most one per slot, slot order) to out[0..cap) and
 * returns their count. A change that does not fit in cap stays pending for
 * the next call. */
uint32_t ft_debounce_poll(ft_debounce *d, uint64_t now_ns, ft_debounce_change *out,
                          uint32_t cap);

/* Debounced logical level of a slot (1 active, 0 inactive; 0 for a bad slot). */
int ft_debounce_active(const ft_debounce *d, uint32_t slot);

#endif
