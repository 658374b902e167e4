/* test_jobs.c - deferred jobs run in order, only in the time left, none lost. */
#include <string.h>

#include "core/jobs.h"
#include "test_util.h"

static uint64_t g_now;
static uint64_t fake_now(void) { return g_now; }

static char g_log[256];
static size_t g_len;

static ft_status append(void *ctx, const void *payload, size_t bytes)
{
    (void)ctx;
    memcpy(g_log + g_len, payload, bytes);
    g_len += bytes;
    g_now += 10; /* each job takes 10 ns of the fake clock */
    return FT_OK;
}

static ft_status failing(void *ctx, const void *payload, size_t bytes)
{
    (void)ctx; (void)payload; (void)bytes;
    return FT_ERR_IO;
}

int main(void)
{
    static ft_jobs q;
    ft_error err;
    ft_jobs_init(&q);
    CHECK(ft_jobs_push(&q, append, NULL, 10, "a", 1, &err) == FT_OK);
    CHECK(ft_jobs_push(&q, append, NULL, 10, "b", 1, &err) == FT_OK);
    CHECK(ft_jobs_push(&q, append, NULL, 10, "c", 1, &err) == FT_OK);
    /* time for two jobs only */
    g_now = 100;
    CHECK(ft_jobs_run(&q, fake_now, 120, 0, &err) == FT_OK);
    CHECK(g_len == 2 && memcmp(g_log, "ab", 2) == 0 && q.count == 1u && q.deferred_frames == 1u);
    /* no time at all: nothing runs */
    CHECK(ft_jobs_run(&q, fake_now, g_now, 0, &err) == FT_OK && q.count == 1u);
    /* force: everything runs */
    CHECK(ft_jobs_run(&q, fake_now, 0, 1, &err) == FT_OK && q.count == 0u);
    CHECK(g_len == 3 && memcmp(g_log, "abc", 3) == 0);
    /* full ring refuses, counted; oversized payload refused */
    for (uint32_t i = 0; i < FT_JOBS_MAX; ++i) {
        CHECK(ft_jobs_push(&q, append, NULL, 1, "x", 1, &err) == FT_OK);
    }
    CHECK(ft_jobs_push(&q, append, NULL, 1, "y", 1, &err) == FT_ERR_BUDGET && q.refused == 1u);
    static char big[FT_JOB_PAYLOAD_MAX + 1];
    CHECK(ft_jobs_push(&q, append, NULL, 1, big, sizeof big, &err) == FT_ERR_ARG);
    g_len = 0;
    CHECK(ft_jobs_run(&q, fake_now, 0, 1, &err) == FT_OK && g_len == FT_JOBS_MAX);
    CHECK(q.high_water == FT_JOBS_MAX);
    /* a failing job reports */
    CHECK(ft_jobs_push(&q, failing, NULL, 1, NULL, 0, &err) == FT_OK);
    CHECK(ft_jobs_run(&q, fake_now, 0, 1, &err) == FT_ERR_IO);
    return ft_test_result("test_jobs");
}
