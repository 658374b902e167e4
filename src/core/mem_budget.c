#include "core/mem_budget.h"

#include <stdio.h>
#include <string.h>

static const char *const k_pool_key[FT_POOL_COUNT] = {
#define FT_POOL_KEY(id, key, what) key,
    FT_POOL_LIST(FT_POOL_KEY)
#undef FT_POOL_KEY
};

static const char *const k_pool_what[FT_POOL_COUNT] = {
#define FT_POOL_WHAT(id, key, what) what,
    FT_POOL_LIST(FT_POOL_WHAT)
#undef FT_POOL_WHAT
};

const char *ft_pool_key(ft_pool_id id)
{
    return ((unsigned)id < FT_POOL_COUNT) ? k_pool_key[id] : "?";
}

const char *ft_pool_what(ft_pool_id id)
{
    return ((unsigned)id < FT_POOL_COUNT) ? k_pool_what[id] : "?";
}

int ft_pool_from_key(const char *key, ft_pool_id *out)
{
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        if (strcmp(key, k_pool_key[i]) == 0) {
            *out = (ft_pool_id)i;
            return 1;
        }
    }
    return 0;
}

size_t ft_arena_round(size_t bytes)
{
    /* Saturate instead of wrapping: a huge request must fail the budget
     * check, not turn into a small one. */
    if (bytes > SIZE_MAX - FT_ARENA_ALIGN) {
        return SIZE_MAX - (SIZE_MAX % FT_ARENA_ALIGN);
    }
    return (bytes + FT_ARENA_ALIGN - 1u) & ~(size_t)(FT_ARENA_ALIGN - 1u);
}

void ft_arena_plan(ft_arena *a, ft_pool_id id, size_t bytes)
{
    size_t r = ft_arena_round(bytes);
    ft_pool *p = &a->pools[id];
    p->need_bytes = (p->need_bytes > SIZE_MAX - r) ? SIZE_MAX : p->need_bytes + r;
}

ft_status ft_arena_check(const ft_arena *a, ft_error *err)
{
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        const ft_pool *p = &a->pools[i];
        if (p->need_bytes > p->budget_bytes) {
            return ft_fail(err, FT_ERR_BUDGET,
                           "pool '%s' (%s) needs %zu bytes but the scene budgets %zu "
                           "(raise budget.%s)",
                           k_pool_key[i], k_pool_what[i], p->need_bytes, p->budget_bytes,
                           k_pool_key[i]);
        }
    }
    return FT_OK;
}

size_t ft_arena_total_budget(const ft_arena *a)
{
    size_t total = 0;
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        size_t r = ft_arena_round(a->pools[i].budget_bytes);
        total = (total > SIZE_MAX - r) ? SIZE_MAX : total + r;
    }
    return total;
}

ft_status ft_arena_bind(ft_arena *a, void *memory, size_t size_bytes, ft_error *err)
{
    size_t need = ft_arena_total_budget(a);
    if (memory == NULL || ((uintptr_t)memory % FT_ARENA_ALIGN) != 0u) {
        return ft_fail(err, FT_ERR_ARG, "arena memory is NULL or not %u-byte aligned",
                       FT_ARENA_ALIGN);
    }
    if (size_bytes < need) {
        return ft_fail(err, FT_ERR_BUDGET, "arena reservation is %zu bytes, budgets sum to %zu",
                       size_bytes, need);
    }
    a->base = (uint8_t *)memory;
    a->size_bytes = size_bytes;
    a->locked = 0;
    size_t offset = 0;
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        a->pools[i].offset_bytes = offset;
        a->pools[i].used_bytes = 0;
        a->pools[i].high_water_bytes = 0;
        offset += ft_arena_round(a->pools[i].budget_bytes);
    }
    return FT_OK;
}

static ft_status take(ft_arena *a, ft_pool_id id, size_t bytes, void **out, ft_error *err)
{
    ft_pool *p = &a->pools[id];
    size_t r = ft_arena_round(bytes);
    *out = NULL;
    if (a->base == NULL) {
        return ft_fail(err, FT_ERR_ARG, "pool '%s': arena not bound", k_pool_key[id]);
    }
    if (r > p->budget_bytes || p->used_bytes > p->budget_bytes - r) {
        return ft_fail(err, FT_ERR_BUDGET,
                       "pool '%s' (%s): request of %zu bytes with %zu of %zu used exceeds the "
                       "budget (raise budget.%s)",
                       k_pool_key[id], k_pool_what[id], bytes, p->used_bytes, p->budget_bytes,
                       k_pool_key[id]);
    }
    uint8_t *ptr = a->base + p->offset_bytes + p->used_bytes;
    p->used_bytes += r;
    if (p->used_bytes > p->high_water_bytes) {
        p->high_water_bytes = p->used_bytes;
    }
    memset(ptr, 0, r);
    *out = ptr;
    return FT_OK;
}

ft_status ft_arena_take(ft_arena *a, ft_pool_id id, size_t bytes, void **out, ft_error *err)
{
    if ((unsigned)id >= FT_POOL_COUNT || out == NULL) {
        return ft_fail(err, FT_ERR_ARG, "ft_arena_take: bad pool id or output");
    }
    if (a->locked) {
        *out = NULL;
        return ft_fail(err, FT_ERR_ARENA_LOCKED,
                       "pool '%s': %zu bytes requested after init; the arena is locked",
                       k_pool_key[id], bytes);
    }
    return take(a, id, bytes, out, err);
}

size_t ft_arena_mark(const ft_arena *a, ft_pool_id id)
{
    return a->pools[id].used_bytes;
}

ft_status ft_arena_take_scratch(ft_arena *a, ft_pool_id id, size_t bytes, void **out)
{
    if ((unsigned)id >= FT_POOL_COUNT || out == NULL) {
        return FT_ERR_ARG;
    }
    return take(a, id, bytes, out, NULL);
}

void ft_arena_reset(ft_arena *a, ft_pool_id id, size_t mark)
{
    if (mark <= a->pools[id].used_bytes) {
        a->pools[id].used_bytes = mark;
    }
}

void ft_arena_lock(ft_arena *a)
{
    a->locked = 1;
}

size_t ft_arena_format_table(const ft_arena *a, char *buf, size_t cap)
{
    size_t n = 0;
    size_t used_total = 0;
    size_t budget_total = 0;
    int w;
    if (cap == 0) {
        return 0;
    }
    buf[0] = '\0';
    w = snprintf(buf, cap, "%-20s %14s %14s  %s\n", "pool", "bytes used", "bytes budgeted",
                 "holds");
    n += (w > 0) ? (size_t)w : 0;
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        const ft_pool *p = &a->pools[i];
        size_t used = (p->high_water_bytes > p->need_bytes) ? p->high_water_bytes : p->need_bytes;
        used_total += used;
        budget_total += p->budget_bytes;
        /* past the end only count (snprintf(NULL, 0) measures): the result is
         * the length the whole table needs, like snprintf's own */
        w = snprintf(n < cap ? buf + n : NULL, n < cap ? cap - n : 0,
                     "%-20s %14zu %14zu  %s\n", k_pool_key[i], used, p->budget_bytes,
                     k_pool_what[i]);
        n += (w > 0) ? (size_t)w : 0;
    }
    w = snprintf(n < cap ? buf + n : NULL, n < cap ? cap - n : 0, "%-20s %14zu %14zu\n",
                 "total", used_total, budget_total);
    n += (w > 0) ? (size_t)w : 0;
    return n;
}
