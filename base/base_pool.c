/* base_pool.c - threads kept for many short loops and tasks (base_pool.h).
 *
 * One mutex guards the pool: its loops (each on the stack of the thread
 * that runs it, several at once when a task runs a loop of its own) and
 * its queue of tasks. A worker takes a queued task first (tasks are the
 * long steps: the sooner started, the sooner done), else helps the first
 * loop with items left and room for a helper, else yields its core a
 * while (nap), then sleeps. The lock is
 * taken once per item: items are a wave's chunks, thousands of items'
 * work each.
 */
#include "base/base_pool.h"
#include "base/base_out.h"
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <time.h>

/* How long a thread with nothing to do keeps its core before it sleeps:
 * on a virtual machine a core whose threads all sleep halts, and waking
 * it again (the next loop's items, the reader's rows) takes a while;
 * meanwhile it yields to whatever else may run there. */
#define SPIN_NS 200000

typedef struct pool_loop {
    size_t n, next, done;
    int helpers, max_helpers;
    void (*fn)(void *ctx, size_t i);
    void *ctx;
    struct pool_loop *next_loop;
} pool_loop;

struct base_pool {
    pthread_mutex_t mu;
    pthread_cond_t  work, done;
    pthread_t      *th;
    int             nth, stop, max_helpers;
    pool_loop      *loops;
    base_task      *head, *tail;    /* queued tasks, in order */
    atomic_uint     gen;            /* bumped (under mu) at every change a waiter may wait for */
};

static void bump(base_pool *p) { atomic_fetch_add_explicit(&p->gen, 1, memory_order_release); }

/* pthread_cond_wait(c) (mu held), after up to SPIN_NS of yielding while
 * nothing changes; returns at once, mu held, when something did (the
 * caller checks again, as after any wait). */
static void nap(base_pool *p, pthread_cond_t *c)
{
    unsigned g = atomic_load_explicit(&p->gen, memory_order_relaxed);
    pthread_mutex_unlock(&p->mu);
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int i = 1; atomic_load_explicit(&p->gen, memory_order_acquire) == g; i++) {
        sched_yield();
        if (i % 16 == 0) {
            clock_gettime(CLOCK_MONOTONIC, &t);
            if ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) > SPIN_NS) break;
        }
    }
    pthread_mutex_lock(&p->mu);
    if (atomic_load_explicit(&p->gen, memory_order_relaxed) == g) pthread_cond_wait(c, &p->mu);
}

/* Items of L until none is left (the lock held on entry and exit). */
static void loop_items(base_pool *p, pool_loop *L)
{
    while (L->next < L->n) {
        size_t i = L->next++;
        pthread_mutex_unlock(&p->mu);
        L->fn(L->ctx, i);
        pthread_mutex_lock(&p->mu);
        L->done++;
    }
}

/* Help the first loop with items left and room for a helper, until it has
 * none left: 1, or 0 when there is no such loop (the lock held). */
static int help_loop(base_pool *p)
{
    pool_loop *L = p->loops;
    while (L && (L->next >= L->n || L->helpers >= L->max_helpers)) L = L->next_loop;
    if (!L) return 0;
    L->helpers++;
    loop_items(p, L);
    L->helpers--;
    bump(p);
    pthread_cond_broadcast(&p->done);
    return 1;
}

static base_task *task_pop(base_pool *p)
{
    base_task *t = p->head;
    if (t) {
        p->head = t->next;
        if (!p->head) p->tail = NULL;
        t->next = NULL;
    }
    return t;
}

static void *worker(void *arg)
{
    base_pool *p = arg;
    pthread_mutex_lock(&p->mu);
    while (!p->stop) {
        base_task *t = task_pop(p);
        if (t) {
            t->state = 2;
            pthread_mutex_unlock(&p->mu);
            t->fn(t->arg);
            pthread_mutex_lock(&p->mu);
            t->state = 3;
            bump(p);
            pthread_cond_broadcast(&p->done);
            continue;
        }
        if (!help_loop(p)) nap(p, &p->work);
    }
    pthread_mutex_unlock(&p->mu);
    return NULL;
}

base_pool *base_pool_new(int threads, int tasks)
{
    if (threads < 1) threads = 1;
    if (tasks < 0) tasks = 0;
    int want = threads - 1 + tasks;
    if (want < 1) return NULL;
    base_pool *p = calloc(1, sizeof *p);
    if (!p || !(p->th = malloc((size_t)want * sizeof *p->th))) base_out_of_memory();
    pthread_mutex_init(&p->mu, NULL);
    pthread_cond_init(&p->work, NULL);
    pthread_cond_init(&p->done, NULL);
    p->max_helpers = threads - 1;
    while (p->nth < want && !pthread_create(&p->th[p->nth], NULL, worker, p)) p->nth++;
    if (!p->nth) { base_pool_free(p); return NULL; }
    return p;
}

void base_pool_free(base_pool *p)
{
    if (!p) return;
    pthread_mutex_lock(&p->mu);
    p->stop = 1;
    bump(p);
    pthread_cond_broadcast(&p->work);
    pthread_mutex_unlock(&p->mu);
    for (int i = 0; i < p->nth; i++) pthread_join(p->th[i], NULL);
    pthread_cond_destroy(&p->work);
    pthread_cond_destroy(&p->done);
    pthread_mutex_destroy(&p->mu);
    free(p->th);
    free(p);
}

void base_pool_for(base_pool *p, size_t n, void (*fn)(void *ctx, size_t i), void *ctx)
{
    if (!p || n < 2 || p->max_helpers < 1) {
        for (size_t i = 0; i < n; i++) fn(ctx, i);
        return;
    }
    pool_loop L = { n, 0, 0, 0, p->max_helpers, fn, ctx, NULL };
    pthread_mutex_lock(&p->mu);
    L.next_loop = p->loops;
    p->loops = &L;
    bump(p);
    pthread_cond_broadcast(&p->work);
    pthread_cond_broadcast(&p->done);   /* a waiter helps too (base_pool_wait) */
    loop_items(p, &L);
    /* the helpers' last items, and the helpers gone from L */
    while (L.done < L.n || L.helpers) nap(p, &p->done);
    pool_loop **at = &p->loops;
    while (*at != &L) at = &(*at)->next_loop;
    *at = L.next_loop;
    pthread_mutex_unlock(&p->mu);
}

void base_pool_start(base_pool *p, base_task *t, void (*fn)(void *arg), void *arg)
{
    t->fn = fn;
    t->arg = arg;
    t->next = NULL;
    if (!p) {               /* no workers: now, on the caller */
        t->state = 2;
        fn(arg);
        t->state = 3;
        return;
    }
    pthread_mutex_lock(&p->mu);
    t->state = 1;
    if (p->tail) p->tail->next = t;
    else p->head = t;
    p->tail = t;
    bump(p);
    pthread_cond_signal(&p->work);
    pthread_mutex_unlock(&p->mu);
}

void base_pool_wait(base_pool *p, base_task *t)
{
    if (!p) return;
    pthread_mutex_lock(&p->mu);
    if (t->state == 1) {
        /* no worker took it: out of the queue, and run here */
        base_task **at = &p->head, *prev = NULL;
        while (*at != t) { prev = *at; at = &(*at)->next; }
        *at = t->next;
        if (p->tail == t) p->tail = prev;
        t->state = 2;
        pthread_mutex_unlock(&p->mu);
        t->fn(t->arg);
        pthread_mutex_lock(&p->mu);
        t->state = 3;
    }
    /* meanwhile, the items of a loop that has room for a helper (the
     * task's own, often), where the waiter would only sleep */
    while (t->state != 3)
        if (!help_loop(p)) nap(p, &p->done);
    pthread_mutex_unlock(&p->mu);
}
