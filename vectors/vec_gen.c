/* vec_gen.c - a generator streamed (vec_gen.h).
 *
 * A model's generator appends its n rows to a set in one call; a sweep
 * over millions of rows per design point would hold them all (hundreds of
 * MB per parameter set). Here the generator runs on a thread of its own
 * into a set whose flush hook (vectors.h) hands each full block over and
 * waits until the reader has taken it: three blocks rotate (the one being
 * filled, the one ready, the one the reader holds), so memory is three
 * blocks whatever n is, and the rows, being the generator's own, are
 * the same numbers in the same order as vec_set's. */
#include "vectors/vec_gen.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define VEC_GEN_BLOCK 16384      /* rows a block: a few MB at most */

struct vec_gen {
    const vec_model *m;
    vec_params p;
    size_t n;
    uint64_t seed;
    pthread_t th;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    vec_set fill, ready;         /* the generator's block, and the one handed over */
    int has_ready;               /* ready holds rows the reader has not taken */
    int done, failed, stop;      /* the generator returned (failed: -1), the reader left */
};

/* The block is full: wait until the last one was taken, hand this one
 * over (the reader's old block comes back to be filled). */
static int hand_over(vec_set *s, void *arg)
{
    vec_gen *g = arg;
    pthread_mutex_lock(&g->mu);
    while (g->has_ready && !g->stop) pthread_cond_wait(&g->cv, &g->mu);
    int stop = g->stop;
    if (!stop) {
        vec_set t = g->ready;
        g->ready.data = s->data; g->ready.cap_rows = s->cap_rows; g->ready.n_rows = s->n_rows;
        s->data = t.data; s->cap_rows = t.cap_rows; s->n_rows = 0;
        g->has_ready = 1;
        pthread_cond_broadcast(&g->cv);
    }
    pthread_mutex_unlock(&g->mu);
    return stop ? -1 : 0;
}

static void *run(void *arg)
{
    vec_gen *g = arg;
    int rc = g->m->gen(&g->p, g->n, g->seed, &g->fill);
    if (!rc && g->fill.n_rows) rc = hand_over(&g->fill, g);   /* the last, short block */
    pthread_mutex_lock(&g->mu);
    g->done = 1;
    g->failed = rc != 0 && !g->stop;
    pthread_cond_broadcast(&g->cv);
    pthread_mutex_unlock(&g->mu);
    return NULL;
}

vec_gen *vec_gen_open(const vec_model *m, const vec_params *p, size_t n, uint64_t seed, const vec_set *hdr)
{
    vec_gen *g = calloc(1, sizeof *g);
    if (!g) return NULL;
    g->m = m;
    g->p = *p;
    g->n = n;
    g->seed = seed;
    vec_set_init(&g->fill);
    vec_set_init(&g->ready);
    /* the header only (its rows, if any, stay with the caller) */
    memcpy(g->fill.unit, hdr->unit, sizeof g->fill.unit);
    g->fill.n_in = hdr->n_in;
    g->fill.n_out = hdr->n_out;
    memcpy(g->fill.in_names, hdr->in_names, sizeof g->fill.in_names);
    memcpy(g->fill.out_names, hdr->out_names, sizeof g->fill.out_names);
    g->fill.flush = hand_over;
    g->fill.flush_arg = g;
    g->fill.flush_rows = VEC_GEN_BLOCK;
    pthread_mutex_init(&g->mu, NULL);
    pthread_cond_init(&g->cv, NULL);
    if (pthread_create(&g->th, NULL, run, g)) {
        pthread_mutex_destroy(&g->mu);
        pthread_cond_destroy(&g->cv);
        free(g);
        return NULL;
    }
    return g;
}

int vec_gen_next(vec_gen *g, vec_set *rows)
{
    pthread_mutex_lock(&g->mu);
    while (!g->has_ready && !g->done) pthread_cond_wait(&g->cv, &g->mu);
    int rc;
    if (g->has_ready) {
        /* the reader's block for the ready one */
        double *d = rows->data;
        size_t cap = rows->cap_rows;
        rows->data = g->ready.data; rows->cap_rows = g->ready.cap_rows; rows->n_rows = g->ready.n_rows;
        g->ready.data = d; g->ready.cap_rows = cap; g->ready.n_rows = 0;
        g->has_ready = 0;
        pthread_cond_broadcast(&g->cv);
        rc = 1;
    } else {
        rows->n_rows = 0;
        rc = g->failed ? -1 : 0;
    }
    pthread_mutex_unlock(&g->mu);
    return rc;
}

void vec_gen_close(vec_gen *g)
{
    if (!g) return;
    pthread_mutex_lock(&g->mu);
    g->stop = 1;
    pthread_cond_broadcast(&g->cv);
    pthread_mutex_unlock(&g->mu);
    pthread_join(g->th, NULL);
    pthread_mutex_destroy(&g->mu);
    pthread_cond_destroy(&g->cv);
    free(g->fill.data);
    free(g->ready.data);
    free(g);
}
