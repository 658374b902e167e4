/* jobs.c - see jobs.h. */
#include "core/jobs.h"

#include <string.h>

#include "core/invariant.h"

void ft_jobs_init(ft_jobs *q)
{
    memset(q, 0, sizeof *q);
}

ft_status ft_jobs_push(ft_jobs *q, ft_job_fn fn, void *ctx, uint64_t cost_ns, const void *payload,
                       size_t bytes, ft_error *err)
{
    if (bytes > FT_JOB_PAYLOAD_MAX) {
        return ft_fail(err, FT_ERR_ARG, "job payload of %zu bytes exceeds %u", bytes,
                       FT_JOB_PAYLOAD_MAX);
    }
    if (q->count == FT_JOBS_MAX) {
        q->refused += 1u;
        return ft_fail(err, FT_ERR_BUDGET, "job queue full (%u jobs)", FT_JOBS_MAX);
    }
    ft_job *j = &q->ring[(q->head + q->count) % FT_JOBS_MAX];
    j->fn = fn;
    j->ctx = ctx;
    j->cost_ns = cost_ns;
    j->bytes = bytes;
    if (bytes > 0u) {
        memcpy(j->payload, payload, bytes);
    }
    q->count += 1u;
    q->queued += 1u;
    if (q->count > q->high_water) {
        q->high_water = q->count;
    }
    return FT_OK;
}

ft_status ft_jobs_run(ft_jobs *q, uint64_t (*now)(void), uint64_t deadline_ns, int force,
                      ft_error *err)
{
    FT_INVARIANT(q->count <= FT_JOBS_MAX && q->head < FT_JOBS_MAX, "job ring out of its bounds");
    /* bounded: at most the jobs queued now */
    for (uint32_t n = q->count; n > 0u; --n) {
        ft_job *j = &q->ring[q->head];
        if (!force && now() + j->cost_ns > deadline_ns) {
            q->deferred_frames += 1u;
            return FT_OK;
        }
        ft_status st = j->fn(j->ctx, j->payload, j->bytes);
        q->head = (q->head + 1u) % FT_JOBS_MAX;
        q->count -= 1u;
        q->run += 1u;
        if (st != FT_OK) {
            return ft_fail(err, st, "a deferred job failed");
        }
    }
    return FT_OK;
}
