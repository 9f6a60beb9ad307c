/* base_pool.h - threads made once and kept for a long job of many short
 * steps (a stream read and simulated a wave at a time): base_par_for's
 * loop without a thread's start and end at every call, and tasks that run
 * beside the caller (reading the next wave, folding the last one).
 *
 * A thread's start costs tens of microseconds of system time (its stack
 * mapped, then unmapped); a stream of 10^7 items takes about a thousand
 * waves of several loops each, where base_par_for spent a second of
 * system time on them alone.
 *
 * Determinism is base_par_for's: each item writes its own slot; which
 * thread runs it is free.
 */
#ifndef BASE_POOL_H
#define BASE_POOL_H
#include <stddef.h>

typedef struct base_pool base_pool;

/* A pool for loops of up to `threads` threads (the caller's among them)
 * and `tasks` tasks beside them: threads - 1 + tasks workers. NULL when
 * threads <= 1 and tasks == 0, or when no thread can be made: every
 * function below then runs its work on the caller, in order. Out of
 * memory: base_out_of_memory. */
base_pool *base_pool_new(int threads, int tasks);
void       base_pool_free(base_pool *p);

/* base_par_for on the pool: fn(ctx, i) for every i in [0, n), on the
 * caller and at most threads - 1 of the workers; returns when all are
 * done. */
void base_pool_for(base_pool *p, size_t n, void (*fn)(void *ctx, size_t i), void *ctx);

/* A task: fn(arg) on a worker while the caller goes on; base_pool_wait
 * returns once it has run (on the caller, if no worker had taken it). */
typedef struct base_task {
    void (*fn)(void *arg);
    void *arg;
    int   state;               /* 0 idle, 1 queued, 2 running, 3 done */
    struct base_task *next;
} base_task;
void base_pool_start(base_pool *p, base_task *t, void (*fn)(void *arg), void *arg);
void base_pool_wait(base_pool *p, base_task *t);
#endif
