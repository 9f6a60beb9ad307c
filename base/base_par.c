/* base_par.c - the parallel-for (see base_par.h).
 *
 * Items are handed out one at a time under a mutex: the items of a sweep
 * or a scene take milliseconds to seconds each and vary a lot, so taking
 * the next free item balances better than fixed blocks, and the lock is
 * taken far too rarely to matter.
 */
#include "base/base_par.h"
#include <pthread.h>
#include <stdlib.h>

typedef struct par_ctx {
    size_t n, next;
    pthread_mutex_t mu;
    void (*fn)(void *, size_t);
    void *ctx;
} par_ctx;

static void *par_worker(void *arg)
{
    par_ctx *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t i = p->next < p->n ? p->next++ : p->n;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->n) return NULL;
        p->fn(p->ctx, i);
    }
}

void base_par_for(size_t n, int threads, void (*fn)(void *ctx, size_t i), void *ctx)
{
    if (threads < 1) threads = 1;
    if ((size_t)threads > n) threads = (int)n;
    if (threads <= 1) {
        for (size_t i = 0; i < n; i++) fn(ctx, i);
        return;
    }
    par_ctx p = { n, 0, PTHREAD_MUTEX_INITIALIZER, fn, ctx };
    pthread_t *th = malloc((size_t)(threads - 1) * sizeof *th);
    int started = 0;
    while (th && started < threads - 1 && !pthread_create(&th[started], NULL, par_worker, &p)) started++;
    par_worker(&p);
    for (int t = 0; t < started; t++) pthread_join(th[t], NULL);
    free(th);
    pthread_mutex_destroy(&p.mu);
}
