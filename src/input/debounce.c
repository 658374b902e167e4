/* debounce.c - see debounce.h. */
#include "input/debounce.h"

#include <stddef.h>

#define FT_NS_PER_MS 1000000ull

ft_status ft_debounce_init(ft_debounce *d, uint32_t slot_count, uint32_t debounce_ms,
                           int active_low, const int *physical_levels, uint64_t now_ns,
                           ft_error *err)
{
    if (d == NULL || physical_levels == NULL) {
        return ft_fail(err, FT_ERR_ARG, "debounce: NULL state or levels");
    }
    if (slot_count == 0u || slot_count > FT_DEBOUNCE_SLOTS_MAX) {
        return ft_fail(err, FT_ERR_ARG, "debounce: %u inputs, must be 1..%u",
                       (unsigned)slot_count, (unsigned)FT_DEBOUNCE_SLOTS_MAX);
    }
    if (debounce_ms > FT_DEBOUNCE_MS_MAX) {
        return ft_fail(err, FT_ERR_ARG, "debounce: %u ms is more than the %u ms limit",
                       (unsigned)debounce_ms, (unsigned)FT_DEBOUNCE_MS_MAX);
    }
    *d = (ft_debounce){0};
    d->slot_count = slot_count;
    d->debounce_ns = (uint64_t)debounce_ms * FT_NS_PER_MS;
    d->active_low = active_low != 0 ? 1u : 0u;
    for (uint32_t i = 0; i < slot_count; ++i) {
        uint8_t level = physical_levels[i] != 0 ? 1u : 0u;
        d->slot[i].raw = level;
        d->slot[i].stable = level;
        d->slot[i].raw_since_ns = now_ns;
    }
    return FT_OK;
}

/* Commits the raw level of slot i if it differs from the debounced one and
 * has held for debounce_ns at t_ns. */
static int settle(ft_debounce *d, uint32_t i, uint64_t t_ns, ft_debounce_change *change)
{
    ft_debounce_slot *s = &d->slot[i];
    if (s->raw == s->stable || t_ns < s->raw_since_ns ||
        t_ns - s->raw_since_ns < d->debounce_ns) {
        return 0;
    }
    s->stable = s->raw;
    d->changes++;
    change->slot = i;
    change->active = (int)(s->stable ^ d->active_low);
    change->t_ns = s->raw_since_ns + d->debounce_ns;
    return 1;
}

int ft_debounce_edge(ft_debounce *d, uint32_t slot, int rising, uint64_t t_ns,
                     ft_debounce_change *change)
{
    if (slot >= d->slot_count) {
        d->bad_slot++;
        return 0;
    }
    ft_debounce_slot *s = &d->slot[slot];
    if (t_ns < s->raw_since_ns) {
        d->reordered++;
        t_ns = s->raw_since_ns;
    }
    /* The level before this edge held from raw_since_ns to t_ns. With
     * debounce > 0 only this can report a change (the new level has held for
     * 0 ns); with debounce 0 every earlier level was committed by its own
     * edge, so only the second settle can. Hence at most one change. */
    int changed = settle(d, slot, t_ns, change);
    uint8_t level = rising != 0 ? 1u : 0u;
    if (level == s->raw) {
        d->repeated++; /* the opposite edge was lost: a bounce, restart the hold */
    }
    s->raw = level;
    s->raw_since_ns = t_ns;
    if (changed) {
        return 1;
    }
    return settle(d, slot, t_ns, change);
}

int ft_debounce_sample(ft_debounce *d, uint32_t slot, int level, uint64_t t_ns,
                       ft_debounce_change *change)
{
    if (slot >= d->slot_count) {
        d->bad_slot++;
        return 0;
    }
    if ((level != 0 ? 1u : 0u) == d->slot[slot].raw) {
        return settle(d, slot, t_ns, change);
    }
    return ft_debounce_edge(d, slot, level, t_ns, change);
}

uint32_t ft_debounce_poll(ft_debounce *d, uint64_t now_ns, ft_debounce_change *out,
                          uint32_t cap)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < d->slot_count && n < cap; ++i) {
        n += (uint32_t)settle(d, i, now_ns, &out[n]);
    }
    return n;
}

int ft_debounce_active(const ft_debounce *d, uint32_t slot)
{
    if (slot >= d->slot_count) {
        return 0;
    }
    return (int)(d->slot[slot].stable ^ d->active_low);
}
