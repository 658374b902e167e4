/* jobs.h - deferrable work run only in the time a frame has left.
 *
 * A fixed ring of FT_JOBS_MAX jobs (a function and a small payload copied
 * in, no pointers into the caller's stack). The frame loop calls
 * ft_jobs_run(q, deadline) after the frame is drawn and presented: jobs run
 * in order while the clock is before the deadline minus the job's declared
 * cost; what does not fit waits for the next frame. A full ring refuses a
 * new job (counted, and the caller decides: the live loop then writes its
 * pose record row at once rather than lose it). */
#ifndef FT_JOBS_H
#define FT_JOBS_H

#include <stddef.h>
#include <stdint.h>

#include "core/ft_status.h"

#define FT_JOBS_MAX 64u
#define FT_JOB_PAYLOAD_MAX 512u

typedef ft_status (*ft_job_fn)(void *ctx, const void *payload, size_t bytes);

typedef struct ft_job {
    ft_job_fn fn;
    void *ctx;
    uint64_t cost_ns; /* declared worst-case run time */
    size_t bytes;
    unsigned char payload[FT_JOB_PAYLOAD_MAX];
} ft_job;

typedef struct ft_jobs {
    ft_job ring[FT_JOBS_MAX];
    uint32_t head, count;
    uint64_t queued, run, refused, deferred_frames; /* deferred: frames that left work */
    uint32_t high_water;
} ft_jobs;

void ft_jobs_init(ft_jobs *q);

/* Copies payload (<= FT_JOB_PAYLOAD_MAX bytes). FT_ERR_BUDGET when full. */
ft_status ft_jobs_push(ft_jobs *q, ft_job_fn fn, void *ctx, uint64_t cost_ns, const void *payload,
                       size_t bytes, ft_error *err);

/* Runs jobs while now() + cost <= deadline_ns (now from the caller's clock,
 * read before each job); returns the first job failure. force = 1 runs all
 * (shutdown: nothing may be lost). */
ft_status ft_jobs_run(ft_jobs *q, uint64_t (*now)(void), uint64_t deadline_ns, int force,
                      ft_error *err);

#endif
