/* mem_budget.h - all memory, reserved once at init, carved into named pools.
 *
 * The scene declares one byte budget per pool (config key "budget.<key>").
 * Init computes what each pool needs, fails with a message naming the pool
 * and the numbers if a need exceeds its budget, then reserves one arena of
 * the summed budgets (the caller provides the memory: platform/ maps it), and
 * hands out slices. ft_arena_lock() ends init: any later request fails with
 * FT_ERR_ARENA_LOCKED. There is no free; pools with per-use lifetime (the
 * png/zlib scratch) use a mark/reset pair.
 *
 * Cost: every call is O(1). */
#ifndef FT_MEM_BUDGET_H
#define FT_MEM_BUDGET_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"

/* X(id, config key, what it holds) */
#define FT_POOL_LIST(X)                                                            \
    X(FT_POOL_HEIGHTS, "heights_bytes", "full-resolution heights (float32, m)")    \
    X(FT_POOL_PYRAMIDS, "pyramids_bytes", "avg/min/max pyramids (float32, m)")     \
    X(FT_POOL_DEM_IO, "dem_io_bytes", "DEM row buffer, void-fill marks; .ftd index + tile")   \
    X(FT_POOL_FRAME_RGBA, "frame_rgba_bytes", "colour readback (RGBA8)")           \
    X(FT_POOL_FRAME_POS, "frame_pos_bytes", "position readback (RGBA32F)")         \
    X(FT_POOL_REFERENCE, "reference_bytes", "reference ray-caster output")         \
    X(FT_POOL_METRIC, "metric_bytes", "error metric scratch (per-pixel errors)")   \
    X(FT_POOL_GPU_STAGING, "gpu_staging_bytes", "upload staging (packed heights, vertex tables)") \
    X(FT_POOL_METHOD, "method_bytes", "LOD method state (templates, tile lists)")  \
    X(FT_POOL_PNG, "png_bytes", "PNG encoder scratch (libpng + zlib)")            \
    X(FT_POOL_CLIP, "clip_bytes", "clipmap cache: staging, bounds (method clipmap, pgrid or bintree over the cache, or a .ftd); over a .ftd, decoded tiles")

typedef enum ft_pool_id {
#define FT_POOL_ENUM(id, key, what) id,
    FT_POOL_LIST(FT_POOL_ENUM)
#undef FT_POOL_ENUM
    FT_POOL_COUNT
} ft_pool_id;

typedef struct ft_pool {
    size_t budget_bytes; /* declared by the scene */
    size_t need_bytes;   /* computed at init before reservation */
    size_t used_bytes;   /* handed out so far */
    size_t high_water_bytes;
    size_t offset_bytes; /* start of this pool inside the arena */
} ft_pool;

typedef struct ft_arena {
    uint8_t *base;
    size_t size_bytes;
    int locked;
    ft_pool pools[FT_POOL_COUNT];
} ft_arena;

const char *ft_pool_key(ft_pool_id id);  /* "heights_bytes" */
const char *ft_pool_what(ft_pool_id id); /* "full-resolution heights ..." */
int ft_pool_from_key(const char *key, ft_pool_id *out);

/* Every allocation is aligned to this (enough for float4, double, SIMD). */
#define FT_ARENA_ALIGN 64u

/* Round a request up to the arena alignment (what a request really costs). */
size_t ft_arena_round(size_t bytes);

/* Adds `bytes` (rounded) to the pool's computed need. Call during planning. */
void ft_arena_plan(ft_arena *a, ft_pool_id id, size_t bytes);

/* Checks every pool's need against its budget. On failure names the first
 * pool that does not fit: "pool heights_bytes needs N bytes, budget is M". */
ft_status ft_arena_check(const ft_arena *a, ft_error *err);

/* Sum of all budgets, rounded: the size of the one reservation. */
size_t ft_arena_total_budget(const ft_arena *a);

/* Binds the reserved memory (size >= total budget) and lays pools out. */
ft_status ft_arena_bind(ft_arena *a, void *memory, size_t size_bytes, ft_error *err);

/* Hands out a zeroed slice of `bytes` from pool `id`. Fails when the arena
 * is locked or the pool budget would be exceeded (the error names both). */
ft_status ft_arena_take(ft_arena *a, ft_pool_id id, size_t bytes, void **out, ft_error *err);

/* Per-use scratch: remember the fill level, give it back later. Allowed
 * after lock (it never grows the reservation). */
size_t ft_arena_mark(const ft_arena *a, ft_pool_id id);
ft_status ft_arena_take_scratch(ft_arena *a, ft_pool_id id, size_t bytes, void **out);
void ft_arena_reset(ft_arena *a, ft_pool_id id, size_t mark);

void ft_arena_lock(ft_arena *a);

/* Writes the "pool / used / budget" table into buf (always terminated);
 * returns the number of characters that were needed. */
size_t ft_arena_format_table(const ft_arena *a, char *buf, size_t cap);

#endif
