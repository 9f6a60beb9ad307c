/* tb_items_memo.c - tb_items_run's results kept by their whole input
 * (tb_items_memo.h). */
#include "testbench/tb_items_memo.h"
#include "base/base_out.h"
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* The items, kept once for every run over them (a sweep runs the same
 * nodes on each of the unit's schedules). */
typedef struct memo_in {
    uint64_t hash;
    size_t nd;
    double *v;
} memo_in;

typedef struct memo_run {
    uint64_t hash;
    const unit_desc *u;
    unit_cfg cfg;
    unit_fmts f;
    int energy;
    size_t n, n_in, in;             /* in: index into the kept items */
    double *out;                    /* NULL while a thread runs it */
    tb_items_stats st;
} memo_run;

struct tb_items_memo {
    pthread_mutex_t mu;
    pthread_cond_t done;            /* a run finished (waiters look again) */
    memo_run *run;
    memo_in *in;
    size_t nrun, cap, nin, capin, hits;
};

/* FNV-1a's step over 8-byte words, then the bytes left: a quick filter;
 * equality is decided by memcmp. */
static uint64_t fnv(uint64_t h, const void *p, size_t len)
{
    const unsigned char *b = p;
    size_t i = 0;
    for (; i + 8 <= len; i += 8) {
        uint64_t w;
        memcpy(&w, b + i, 8);
        h = (h ^ w) * 0x100000001b3ull;
        h ^= h >> 29;
    }
    for (; i < len; i++) { h ^= b[i]; h *= 0x100000001b3ull; }
    return h;
}

static uint64_t key_hash(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, int energy, uint64_t hin)
{
    uint64_t h = fnv(hin, &u, sizeof u);
    h = fnv(h, cfg, sizeof *cfg);
    h = fnv(h, f, sizeof *f);
    return fnv(h, &energy, sizeof energy);
}

static int same(const tb_items_memo *m, const memo_run *r, uint64_t h, const unit_desc *u, const unit_cfg *cfg,
                const unit_fmts *f, int energy, const double *in, size_t n, size_t n_in)
{
    return r->hash == h && r->u == u && r->energy == energy && r->n == n && r->n_in == n_in &&
           !memcmp(&r->cfg, cfg, sizeof *cfg) && !memcmp(&r->f, f, sizeof *f) &&
           !memcmp(m->in[r->in].v, in, n * n_in * sizeof *in);
}

/* The kept copy of these items (made if new); under the lock. */
static size_t in_index(tb_items_memo *m, uint64_t hin, const double *in, size_t nd)
{
    for (size_t i = 0; i < m->nin; i++)
        if (m->in[i].hash == hin && m->in[i].nd == nd && !memcmp(m->in[i].v, in, nd * sizeof *in)) return i;
    if (m->nin == m->capin) {
        m->capin = m->capin ? 2 * m->capin : 16;
        m->in = realloc(m->in, m->capin * sizeof *m->in);
        if (!m->in) base_out_of_memory();
    }
    memo_in *k = &m->in[m->nin];
    k->hash = hin;
    k->nd = nd;
    k->v = malloc((nd ? nd : 1) * sizeof *k->v);
    if (!k->v) base_out_of_memory();
    memcpy(k->v, in, nd * sizeof *in);
    return m->nin++;
}

tb_items_memo *tb_items_memo_new(void)
{
    tb_items_memo *m = calloc(1, sizeof *m);
    if (!m) base_out_of_memory();
    pthread_mutex_init(&m->mu, NULL);
    pthread_cond_init(&m->done, NULL);
    return m;
}

void tb_items_memo_free(tb_items_memo *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->nrun; i++) free(m->run[i].out);
    for (size_t i = 0; i < m->nin; i++) free(m->in[i].v);
    free(m->run);
    free(m->in);
    pthread_mutex_destroy(&m->mu);
    pthread_cond_destroy(&m->done);
    free(m);
}

void tb_items_memo_counts(const tb_items_memo *m, size_t *kept, size_t *hits)
{
    *kept = m ? m->nrun : 0;           /* (when no run is under way) */
    *hits = m ? m->hits : 0;
}

int tb_items_run_memo(tb_items_memo *m, const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                      const double *in, size_t n, int jobs, int energy, double *out, tb_items_stats *st,
                      char *err, size_t errlen)
{
    if (!m) return tb_items_run(u, cfg, f, in, n, jobs, energy, out, st, err, errlen);
    size_t n_in = (size_t)unit_n_in(u);
    uint64_t hin = fnv(0xcbf29ce484222325ull, in, n * n_in * sizeof *in);
    uint64_t h = key_hash(u, cfg, f, energy, hin);
    pthread_mutex_lock(&m->mu);
    for (;;) {
        size_t i = 0;
        while (i < m->nrun && !same(m, &m->run[i], h, u, cfg, f, energy, in, n, n_in)) i++;
        if (i == m->nrun) break;
        if (m->run[i].out) {
            memcpy(out, m->run[i].out, n * sizeof *out);
            *st = m->run[i].st;
            m->hits++;
            pthread_mutex_unlock(&m->mu);
            return TB_OK;
        }
        /* another thread is running it (a sweep's neighbouring points
         * share their nodes): its answer, rather than the same run twice */
        pthread_cond_wait(&m->done, &m->mu);
    }
    /* not held: kept as running (out NULL) while it runs */
    if (m->nrun == m->cap) {
        m->cap = m->cap ? 2 * m->cap : 16;
        m->run = realloc(m->run, m->cap * sizeof *m->run);
        if (!m->run) base_out_of_memory();
    }
    m->run[m->nrun++] = (memo_run){ .hash = h, .u = u, .cfg = *cfg, .f = *f, .energy = energy, .n = n, .n_in = n_in,
                                    .in = in_index(m, hin, in, n * n_in) };
    pthread_mutex_unlock(&m->mu);
    int rc = tb_items_run(u, cfg, f, in, n, jobs, energy, out, st, err, errlen);
    double *keep = NULL;
    if (rc == TB_OK) {
        keep = malloc((n ? n : 1) * sizeof *keep);
        if (!keep) base_out_of_memory();
        memcpy(keep, out, n * sizeof *out);
    }
    pthread_mutex_lock(&m->mu);
    size_t i = 0;
    while (i < m->nrun && !(m->run[i].hash == h && !m->run[i].out && same(m, &m->run[i], h, u, cfg, f, energy, in, n, n_in)))
        i++;
    if (rc == TB_OK) {
        m->run[i].out = keep;
        m->run[i].st = *st;
    } else {
        /* a failed run is not kept: a thread waiting on it runs it itself */
        m->run[i] = m->run[--m->nrun];
    }
    pthread_cond_broadcast(&m->done);
    pthread_mutex_unlock(&m->mu);
    return rc;
}
