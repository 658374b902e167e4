/* test_mem_budget.c - pools: planning, the named overflow error, capacity
 * exhaustion, the lock after init, scratch mark/reset, the table. */
#include <stdint.h>
#include <string.h>

#include "core/mem_budget.h"
#include "test_util.h"

static _Alignas(64) uint8_t g_memory[1u << 16];

int main(void)
{
    ft_arena a;
    ft_error err;
    void *p = NULL;
    memset(&a, 0, sizeof a);

    /* A need above its budget fails and names the pool, key and numbers. */
    a.pools[FT_POOL_HEIGHTS].budget_bytes = 1000;
    ft_arena_plan(&a, FT_POOL_HEIGHTS, 1001);
    CHECK(ft_arena_check(&a, &err) == FT_ERR_BUDGET);
    CHECK(strstr(err.text, "heights_bytes") != NULL);
    CHECK(strstr(err.text, "1024 bytes") != NULL); /* 1001 rounded to 64 */
    CHECK(strstr(err.text, "budgets 1000") != NULL);

    memset(&a, 0, sizeof a);
    a.pools[FT_POOL_HEIGHTS].budget_bytes = 4096;
    a.pools[FT_POOL_PNG].budget_bytes = 1024;
    ft_arena_plan(&a, FT_POOL_HEIGHTS, 4096);
    CHECK(ft_arena_check(&a, &err) == FT_OK);
    CHECK(ft_arena_total_budget(&a) == 4096 + 1024);
    CHECK(ft_arena_bind(&a, g_memory, sizeof g_memory, &err) == FT_OK);
    CHECK(ft_arena_bind(&a, g_memory + 1, sizeof g_memory - 1, &err) == FT_ERR_ARG);
    CHECK(ft_arena_bind(&a, g_memory, 100, &err) == FT_ERR_BUDGET);
    CHECK(ft_arena_bind(&a, g_memory, sizeof g_memory, &err) == FT_OK);

    /* Fill to capacity, then capacity + 1 fails with the pool's name. */
    for (int i = 0; i < 64; ++i) {
        CHECK(ft_arena_take(&a, FT_POOL_HEIGHTS, 64, &p, &err) == FT_OK);
        CHECK(p != NULL && ((uintptr_t)p % FT_ARENA_ALIGN) == 0);
    }
    CHECK(ft_arena_take(&a, FT_POOL_HEIGHTS, 1, &p, &err) == FT_ERR_BUDGET);
    CHECK(p == NULL);
    CHECK(strstr(err.text, "heights_bytes") != NULL);
    /* A pool never spills into its neighbour. */
    CHECK(ft_arena_take(&a, FT_POOL_PYRAMIDS, 1, &p, &err) == FT_ERR_BUDGET);
    /* Huge requests fail instead of wrapping around. */
    CHECK(ft_arena_take(&a, FT_POOL_PNG, SIZE_MAX, &p, &err) == FT_ERR_BUDGET);
    CHECK(ft_arena_take(&a, FT_POOL_PNG, SIZE_MAX - 10, &p, &err) == FT_ERR_BUDGET);

    /* After lock: takes fail, scratch still works within its budget. */
    ft_arena_lock(&a);
    CHECK(ft_arena_take(&a, FT_POOL_PNG, 64, &p, &err) == FT_ERR_ARENA_LOCKED);
    CHECK(strstr(err.text, "after init") != NULL);
    size_t mark = ft_arena_mark(&a, FT_POOL_PNG);
    CHECK(ft_arena_take_scratch(&a, FT_POOL_PNG, 1000, &p) == FT_OK);
    CHECK(ft_arena_take_scratch(&a, FT_POOL_PNG, 100, &p) == FT_ERR_BUDGET);
    ft_arena_reset(&a, FT_POOL_PNG, mark);
    CHECK(ft_arena_mark(&a, FT_POOL_PNG) == mark);
    CHECK(a.pools[FT_POOL_PNG].high_water_bytes == 1024);

    /* Table: every pool row plus header and total; truncation is safe. */
    char table[4096];
    size_t n = ft_arena_format_table(&a, table, sizeof table);
    CHECK(n < sizeof table);
    for (int i = 0; i < FT_POOL_COUNT; ++i) {
        CHECK(strstr(table, ft_pool_key((ft_pool_id)i)) != NULL);
    }
    CHECK(strstr(table, "total") != NULL);
    char tiny[16];
    CHECK(ft_arena_format_table(&a, tiny, sizeof tiny) == n);
    CHECK(strlen(tiny) < sizeof tiny);

    ft_pool_id id;
    CHECK(ft_pool_from_key("png_bytes", &id) && id == FT_POOL_PNG);
    CHECK(!ft_pool_from_key("nope", &id));
    return ft_test_result("test_mem_budget");
}
