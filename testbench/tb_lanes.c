/* tb_lanes.c - one stream of items on the batch's lanes (tb_lanes.h).
 *
 * Lane k drives items [begin, end) of the wave's buffer from reset, with
 * tb_run's driver (tb_drive.h) and monitor (tb_batch.c's, per lane):
 * offer the next item once the unit accepted the last, record each beat
 * the unit marks valid. Its junction in is the edge at which it offers
 * item `from`, its junction out the one at which it offers `end` (the next
 * lane's `from`, or the next wave's first lane's). What the kernel does at
 * an edge (sample the values before it, collect a beat, offer an item)
 * belongs to the lane whose piece holds that edge: the junction out's to
 * lane k, edges after the junction in to lane k + 1 (the two edges are the
 * same edge of the stream).
 */
#include "testbench/tb_lanes.h"
#include "sim/sim_batch.h"
#include "testbench/tb_drive.h"
#include "base/base_out.h"
#include "base/base_par.h"
#include "base/base_pool.h"
#include <stdlib.h>
#include <string.h>

/* Lanes of at least this many items of their own: the warm-up is paid
 * once per lane. A stream in one wave takes at most LANES_ONE lanes (one
 * batch); the waves of a longer one LANES_WAVE, of at least
 * LANES_MIN_WAVE items each, in batches of at most LANES_GROUP. */
#define LANES_MIN_ITEMS 32
#define LANES_MIN_WAVE  128
#define LANES_ONE       64
#define LANES_WAVE      256
#define LANES_GROUP     64
/* A group of lanes of its own (a build, a batch, a thread) for at least
 * this many of a wave's items: below it the build and the batch's costs
 * per cycle outweigh what a second thread saves (a small run, such as a
 * unit's default vectors, runs on one build and no thread). */
#define LANES_GROUP_ITEMS 2048
/* Items before a lane's own, from reset: enough for most units' items in
 * flight (each costs the lane as much as an item of its own: with lanes of
 * 32 to 128 items, 8 of them are a few percent); a unit that needs more
 * fails the junction check, and the wave is run again with the long
 * warm-up (a deep pipeline: shade's, norm3's), which the later waves
 * keep; then on the kernel. */
#define LANES_WARM      8
#define LANES_WARM_LONG TB_LANES_WARM_MAX

/* One build of the unit: a group of lanes at a time simulates on it. */
typedef struct worker {
    tb_built b;
    tb_range rg;
    int      built;
} worker;

struct tb_lanes {
    const unit_desc *u;
    const unit_cfg  *cfg;
    const unit_fmts *fmts;
    int       threads, n_in, n_out, beats;
    base_pool *pool;            /* NULL: threads made for each wave */
    uint32_t  nsig;
    worker   *w;                /* [LANES_WAVE / 8]: built when a group first needs it */
    size_t    warm;
    /* the stream joined so far */
    uint64_t  at_edge;          /* its edges */
    size_t    beat_out;         /* its beats */
    int64_t  *state;            /* every signal at the last junction out */
    uint64_t *tog;              /* each logged signal's toggles */
    uint64_t *ovf;              /* every signal's overflows: used [0, nsig), discarded [nsig, 2 nsig) */
    int64_t  *mn, *mx;          /* each live signal's range */
    int       waves;
    uint32_t  lanes;
};

typedef struct lane {
    size_t   begin, from, end;  /* items driven: [begin, end); its own from `from` (positions) */
    size_t   got;               /* beats collected, counted from begin's first */
    int      phase;             /* 0 warm-up, 1 its piece, 2 done */
    int      first, last;       /* the stream's first piece (from reset), its last */
    uint64_t e_in, e_out;       /* the junction edges (the first piece: 0; the last: its last edge) */
    size_t   beat_in, beat_out; /* the buffer's beats before its piece, and at its end */
    int64_t  *state_in, *state_out;   /* every signal's value at the junctions */
    uint64_t *tog_in, *tog_out;       /* each logged signal's toggles at the junctions */
    uint64_t *ovf_in, *ovf_out;       /* every signal's overflows (used, then discarded) at the junctions */
    uint64_t unsure_in, unsure_out;   /* the batch's unsure steps at the junctions (sim_batch_ovf_unsure) */
    int64_t  *mn, *mx;                /* each live signal's range over its piece */
    tb_drive drv;               /* the driver (tb_drive.h): items [begin, end) of the inputs */
} lane;

/* A group of lanes [k0, k1) of a wave, on worker g. */
typedef struct group {
    size_t k0, k1;
    int    rc;                  /* 0, 1 not taken (why), 3 a lane late */
    int    unsure;              /* a piece's overflow counts depend on the kernel's delta cycles */
    char   why[200];
} group;

typedef struct wave_job {
    tb_lanes      *x;
    tb_lanes_wave *w;
    lane          *S;
    group         *G;
} wave_job;

tb_lanes *tb_lanes_new(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, int threads,
                       char *why, size_t len)
{
    tb_lanes *x = calloc(1, sizeof *x);
    if (!x || !(x->w = calloc(LANES_WAVE / 8, sizeof *x->w))) base_out_of_memory();
    x->u = u; x->cfg = cfg; x->fmts = fmts;
    x->threads = threads < 1 ? 1 : threads;
    x->n_in = unit_n_in(u); x->n_out = unit_n_out(u); x->beats = u->beats(cfg);
    x->warm = LANES_WARM;
    worker *w0 = &x->w[0];
    w0->built = 1;
    if (tb_build(u, cfg, fmts, &w0->b, why, len)) {
        snprintf(why, len, "the unit does not build");   /* the kernel says why */
        tb_lanes_free(x);
        return NULL;
    }
    char err[300];
    sim_batch *b = sim_batch_new(w0->b.c, w0->b.clk, 1, err, sizeof err);
    if (!b) { snprintf(why, len, "%s", err); tb_lanes_free(x); return NULL; }
    sim_batch_free(b);
    if (tb_range_init(&w0->rg, w0->b.c, w0->b.sc, w0->b.clk)) base_out_of_memory();
    x->nsig = sim_signal_count(w0->b.c);
    x->state = malloc(((size_t)x->nsig + 1) * sizeof *x->state);
    x->tog = calloc((size_t)w0->rg.nsmp + 1, sizeof *x->tog);
    x->ovf = calloc(2 * (size_t)x->nsig + 1, sizeof *x->ovf);
    x->mn = malloc(((size_t)w0->rg.nlive + 1) * sizeof *x->mn);
    x->mx = malloc(((size_t)w0->rg.nlive + 1) * sizeof *x->mx);
    if (!x->state || !x->tog || !x->ovf || !x->mn || !x->mx) base_out_of_memory();
    return x;
}

void tb_lanes_free(tb_lanes *x)
{
    if (!x) return;
    for (size_t g = 0; g < LANES_WAVE / 8; g++)
        if (x->w[g].built) {
            tb_range_free(&x->w[g].rg);
            sim_free(x->w[g].b.c);
        }
    free(x->w);
    free(x->state); free(x->tog); free(x->ovf); free(x->mn); free(x->mx);
    free(x);
}

void tb_lanes_pool(tb_lanes *x, base_pool *p) { x->pool = p; }

/* Worker g, built the first time (by the one task that uses it): 0, or 1
 * with why. */
static int worker_get(tb_lanes *x, size_t g, char *why, size_t len)
{
    worker *w = &x->w[g];
    if (w->built) return 0;
    w->built = 1;
    if (tb_build(x->u, x->cfg, x->fmts, &w->b, why, len)) return 1;
    if (tb_range_init(&w->rg, w->b.c, w->b.sc, w->b.clk)) base_out_of_memory();
    return 0;
}

static void snap_state(const sim_batch *b, const sim_ctx *c, uint32_t l, int64_t *to)
{
    for (uint32_t i = 0, n = sim_signal_count(c); i < n; i++) to[i] = sim_batch_val(b, sim_signal_at(c, i))[l];
}

static void snap_tog(const sim_batch *b, const tb_range *g, uint32_t l, uint64_t *to)
{
    for (int i = 0; i < g->nsmp; i++) to[i] = sim_batch_toggles(b, g->smp[i])[l];
}

/* every signal's overflow counts, used then discarded (2 nsig), and the
 * steps whose counts the batch cannot tell */
static void snap_ovf(const sim_batch *b, const sim_ctx *c, uint32_t l, uint64_t *to, uint64_t *unsure)
{
    uint32_t n = sim_signal_count(c);
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        to[i] = sim_batch_ovf_used(b, s)[l];
        to[n + i] = sim_batch_ovf_discarded(b, s)[l];
    }
    *unsure = sim_batch_ovf_unsure(b, l);
}

static void snap_range(const sim_batch *b, const tb_range *g, uint32_t l, int64_t *mn, int64_t *mx)
{
    for (int i = 0; i < g->nlive; i++) sim_batch_range(b, g->lv[i].sig, l, &mn[i], &mx[i]);
}

/* How many pieces a wave's own n items are cut into: a function of the
 * wave alone (not of the threads). A stream in one wave as before:
 * at most LANES_ONE, and fewer than 2 stays on the kernel (0). */
static size_t lanes_count(size_t n, int single)
{
    size_t L = n / (single ? LANES_MIN_ITEMS : LANES_MIN_WAVE), most = single ? LANES_ONE : LANES_WAVE;
    if (L > most) L = most;
    if (L >= 8) L &= ~(size_t)7;        /* the vector loops take multiples of their width */
    if (single) return L < 2 ? 0 : L;
    return L ? L : 1;
}

/* The wave's L pieces: lane k's own items [from, end), from `warm` items
 * before (the stream's first piece from reset). */
static void lanes_init(const tb_lanes *x, const tb_lanes_wave *w, lane *S, size_t L)
{
    size_t own = w->n - w->own;
    for (size_t k = 0; k < L; k++) {
        lane *s = &S[k];
        s->from = w->own + k * own / L;
        s->end = w->own + (k + 1) * own / L;
        s->first = k == 0 && w->base == 0 && w->own == 0;
        s->last = k == L - 1 && w->last;
        s->begin = s->first ? 0 : s->from > x->warm ? s->from - x->warm : 0;
        /* the source ends at the lane's end: valid drops past it */
        tb_drive_raws(&s->drv, x->n_in, w->in_raw, s->end);
        s->drv.next = s->begin;
        s->phase = s->first ? 1 : 0;
    }
}

static int lane_alloc(lane *s, uint32_t nsig, const tb_range *g)
{
    s->state_in = malloc(((size_t)nsig + 1) * sizeof *s->state_in);
    s->state_out = malloc(((size_t)nsig + 1) * sizeof *s->state_out);
    s->tog_in = calloc((size_t)g->nsmp + 1, sizeof *s->tog_in);
    s->tog_out = calloc((size_t)g->nsmp + 1, sizeof *s->tog_out);
    s->mn = malloc(((size_t)g->nlive + 1) * sizeof *s->mn);
    s->mx = malloc(((size_t)g->nlive + 1) * sizeof *s->mx);
    /* the stream's first piece counts from the start: its junction in is 0 */
    s->ovf_in = calloc(2 * (size_t)nsig + 1, sizeof *s->ovf_in);
    s->ovf_out = calloc(2 * (size_t)nsig + 1, sizeof *s->ovf_out);
    return s->state_in && s->state_out && s->tog_in && s->tog_out && s->mn && s->mx && s->ovf_in && s->ovf_out ? 0 : -1;
}

static void lane_free(lane *s)
{
    free(s->state_in); free(s->state_out); free(s->tog_in); free(s->tog_out);
    free(s->mn); free(s->mx); free(s->ovf_in); free(s->ovf_out);
}

/* The group's lanes side by side until each has driven its piece (the
 * stream's last: until its last beat), their beats' cycles and outputs
 * into w and their junction states, toggles and ranges into S. 1 if a
 * lane gave no answer in time. */
static int lanes_simulate(const tb_lanes *x, tb_lanes_wave *w, const worker *wk, sim_batch *b, lane *S, size_t L)
{
    size_t beats = (size_t)x->beats, nout = (size_t)x->n_out, total = w->n * beats;
    const tb_range *g = &wk->rg;
    const unit_io *io = &wk->b.io;
    tb_drive_lanes dw;
    dw.valid = sim_batch_next(b, io->in_valid);
    const int64_t *out[UNIT_MAX_IO];
    for (int i = 0; i < x->n_in; i++) dw.in[i] = sim_batch_next(b, io->in[i]);
    for (size_t o = 0; o < nout; o++) out[o] = sim_batch_val(b, io->out[o]);
    for (size_t k = 0; k < L; k++) tb_drive_lane_offer(&S[k].drv, &dw, (uint32_t)k);
    sim_batch_start(b);
    for (size_t k = 0; k < L; k++) sim_batch_range_reset(b, (uint32_t)k);   /* the first piece starts here */
    const int64_t *iv = sim_batch_val(b, io->in_valid), *ir = sim_batch_val(b, io->in_ready);
    const int64_t *ov = sim_batch_val(b, io->out_valid);
    size_t active = L;
    /* tb_run's budget for the items the group drives */
    uint64_t e = 0, budget = 1000 + (uint64_t)(S[L - 1].end - S[0].begin) * beats * 4096;
    int late = 0;
    while (active) {
        e++;
        for (size_t k = 0; k < L; k++) {
            lane *s = &S[k];
            if (s->phase == 2) continue;
            /* monitor: the cycle that just ended */
            if (ov[k]) {
                size_t at = s->begin * beats + s->got;
                if (s->phase == 1 && at < total) {
                    w->beat_cycle[at] = e - 1;
                    for (size_t o = 0; o < nout; o++) w->raw[at * nout + o] = out[o][k];
                }
                s->got++;
                if (s->last && at + 1 == total) {
                    /* the stream's last beat: tb_run stops after this edge, its driver's
                     * writes at it taken (a combinational unit's valid falls) */
                    s->phase = 2;
                    s->e_out = e;
                    s->beat_out = total;
                    snap_range(b, g, (uint32_t)k, s->mn, s->mx);
                    snap_ovf(b, wk->b.c, (uint32_t)k, s->ovf_out, &s->unsure_out);
                    active--;
                    if (iv[k] && ir[k]) tb_drive_lane_accept(&s->drv, &dw, (uint32_t)k, e);
                    continue;
                }
            }
            /* driver */
            if (iv[k] && ir[k]) {
                /* the accept; the offer after the junctions' snapshots */
                s->drv.next++;
                if (s->phase == 0 && s->drv.next == s->from) {
                    s->phase = 1;
                    s->e_in = e;
                    s->beat_in = s->begin * beats + s->got;
                    snap_state(b, wk->b.c, (uint32_t)k, s->state_in);
                    snap_tog(b, g, (uint32_t)k, s->tog_in);
                    snap_ovf(b, wk->b.c, (uint32_t)k, s->ovf_in, &s->unsure_in);
                    sim_batch_range_reset(b, (uint32_t)k);
                } else if (s->phase == 1 && !s->last && s->drv.next == s->end) {
                    s->phase = 2;
                    s->e_out = e;
                    s->beat_out = s->begin * beats + s->got;
                    snap_state(b, wk->b.c, (uint32_t)k, s->state_out);
                    snap_tog(b, g, (uint32_t)k, s->tog_out);
                    snap_ovf(b, wk->b.c, (uint32_t)k, s->ovf_out, &s->unsure_out);
                    snap_range(b, g, (uint32_t)k, s->mn, s->mx);
                    active--;
                    continue;
                }
                tb_drive_lane_offer(&s->drv, &dw, (uint32_t)k);
            }
            if (e >= budget) { late = 1; s->phase = 2; active--; }
        }
        sim_batch_cycle(b);
    }
    /* the stream's last piece's toggles and overflows through the last
     * edge's settling, where tb_run stops */
    if (S[L - 1].last) {
        snap_tog(b, g, (uint32_t)(L - 1), S[L - 1].tog_out);
        snap_ovf(b, wk->b.c, (uint32_t)(L - 1), S[L - 1].ovf_out, &S[L - 1].unsure_out);
    }
    return late;
}

/* One group on its worker (a base_par_for item). */
static void group_run(void *ctx, size_t gi)
{
    wave_job *j = ctx;
    group *G = &j->G[gi];
    tb_lanes *x = j->x;
    if (worker_get(x, gi, G->why, sizeof G->why)) { G->rc = 1; return; }
    worker *wk = &x->w[gi];
    size_t L = G->k1 - G->k0;
    char err[200];
    sim_batch *b = sim_batch_new(wk->b.c, wk->b.clk, (uint32_t)L, err, sizeof err);
    if (!b) { snprintf(G->why, sizeof G->why, "%s", err); G->rc = 1; return; }
    if (sim_batch_ranges_on(b) || sim_batch_overflows_on(b)) base_out_of_memory();
    lane *S = j->S + G->k0;
    if (lanes_simulate(x, j->w, wk, b, S, L)) G->rc = 3;
    /* a piece's counts are the kernel's unless a step between its
     * junctions was unsure (one in a warm-up is not the piece's) */
    for (size_t k = 0; k < L; k++)
        if (S[k].unsure_out != S[k].unsure_in) G->unsure = 1;
    sim_batch_free(b);
}

/* Whether the pieces join into the stream: each piece's state at its
 * junction in is its predecessor's at its junction out (else the warm-up
 * was too short: checked first, so that a longer one is tried), and every
 * piece's overflow counts are sure. 0, 1 not taken, or 2 with why. */
static int lanes_check(const tb_lanes *x, const tb_lanes_wave *w, const lane *S, size_t L, const group *G,
                       size_t ng, char *why, size_t len)
{
    for (size_t g = 0; g < ng; g++) {
        if (G[g].rc == 1) { snprintf(why, len, "%s", G[g].why); return 1; }
        if (G[g].rc == 3) { snprintf(why, len, "a lane gave no answer in time"); return 1; }
    }
    size_t nb = (size_t)x->beats;
    for (size_t k = 0; k < L; k++) {
        const lane *s = &S[k];
        if (s->first) continue;
        int same;
        if (k) same = S[k - 1].beat_out == s->beat_in
                      && !memcmp(S[k - 1].state_out, s->state_in, (size_t)x->nsig * sizeof *s->state_in);
        else same = x->beat_out == w->base * nb + s->beat_in
                    && !memcmp(x->state, s->state_in, (size_t)x->nsig * sizeof *s->state_in);
        if (!same) {
            snprintf(why, len, "item %zu depends on more than the %zu items before it", w->base + s->from, x->warm);
            return 2;
        }
    }
    for (size_t g = 0; g < ng; g++)
        if (G[g].unsure) {
            snprintf(why, len, "an overflow whose count depends on the kernel's delta cycles (a glitch may rerun its element)");
            return 1;
        }
    return 0;
}

/* The pieces joined to the stream: each piece's clocks shifted by the
 * stream's before it, the toggles and overflows summed, the live
 * signals' ranges joined, the last piece's state kept for the next
 * wave's first. */
static void lanes_join(tb_lanes *x, tb_lanes_wave *w, const lane *S, size_t L)
{
    const tb_range *g = &x->w[0].rg;
    for (size_t k = 0; k < L; k++) {
        const lane *s = &S[k];
        for (size_t b = s->beat_in; b < s->beat_out; b++) w->beat_cycle[b] += x->at_edge - s->e_in;
        x->at_edge += s->e_out - s->e_in;
        for (int i = 0; i < g->nsmp; i++) x->tog[i] += s->tog_out[i] - s->tog_in[i];
        for (size_t i = 0; i < 2 * (size_t)x->nsig; i++) x->ovf[i] += s->ovf_out[i] - s->ovf_in[i];
        for (int i = 0; i < g->nlive; i++) {
            int fresh = !x->waves && k == 0;
            if (fresh || s->mn[i] < x->mn[i]) x->mn[i] = s->mn[i];
            if (fresh || s->mx[i] > x->mx[i]) x->mx[i] = s->mx[i];
        }
    }
    const lane *z = &S[L - 1];
    x->beat_out = w->base * (size_t)x->beats + z->beat_out;
    if (!w->last) memcpy(x->state, z->state_out, (size_t)x->nsig * sizeof *x->state);
    w->beats_done = x->beat_out;
    x->waves++;
    if (L > x->lanes) x->lanes = (uint32_t)L;
}

/* The groups of a wave of `own` items: at most LANES_GROUP lanes each,
 * multiples of 8 lanes (the vector loops' width), at least one per thread
 * where there are lanes and items enough (LANES_GROUP_ITEMS a group). */
static size_t lanes_groups(size_t L, size_t own, int threads, group *G)
{
    size_t units = L >= 8 ? L / 8 : 1, per = L >= 8 ? 8 : L;
    size_t ng = (L + LANES_GROUP - 1) / LANES_GROUP, want = (size_t)threads;
    if (want > own / LANES_GROUP_ITEMS) want = own / LANES_GROUP_ITEMS;
    if (ng < want) ng = want;
    if (ng > units) ng = units;
    for (size_t g = 0; g < ng; g++) {
        memset(&G[g], 0, sizeof G[g]);
        G[g].k0 = units * g / ng * per;
        G[g].k1 = units * (g + 1) / ng * per;
    }
    return ng;
}

/* One try with the current warm-up: 0 joined, 2 the warm-up was too
 * short, 1 not taken. */
static int wave_try(tb_lanes *x, tb_lanes_wave *w, size_t L, char *why, size_t len)
{
    lane *S = calloc(L, sizeof *S);
    group G[LANES_WAVE / 8];
    if (!S) base_out_of_memory();
    const tb_range *g0 = &x->w[0].rg;
    for (size_t k = 0; k < L; k++)
        if (lane_alloc(&S[k], x->nsig, g0)) base_out_of_memory();
    lanes_init(x, w, S, L);
    size_t ng = lanes_groups(L, w->n - w->own, x->threads, G);
    wave_job j = { x, w, S, G };
    if (x->pool) base_pool_for(x->pool, ng, group_run, &j);
    else base_par_for(ng, x->threads, group_run, &j);
    int rc = lanes_check(x, w, S, L, G, ng, why, len);
    if (!rc) lanes_join(x, w, S, L);
    for (size_t k = 0; k < L; k++) lane_free(&S[k]);
    free(S);
    return rc;
}

int tb_lanes_wave_run(tb_lanes *x, tb_lanes_wave *w, char *why, size_t len)
{
    int single = w->base == 0 && w->own == 0 && w->last;
    size_t L = lanes_count(w->n - w->own, single);
    if (!L) { snprintf(why, len, "%zu items: too few for lanes", w->n); return 1; }
    /* the beats still to come must be the buffer's: a unit holding more
     * items than the buffer keeps of the wave before has no junction in it */
    if (x->beat_out < w->base * (size_t)x->beats) {
        snprintf(why, len, "unit %s holds more than %zu items at once", x->u->name, w->own);
        return 1;
    }
    int rc = wave_try(x, w, L, why, len);
    if (rc == 2 && x->warm < LANES_WARM_LONG) {
        /* the pieces did not join: a deep pipeline, again with the long
         * warm-up, which the later waves keep */
        x->warm = LANES_WARM_LONG;
        rc = wave_try(x, w, L, why, len);
    }
    return rc == 2 ? 1 : rc;
}

void tb_lanes_result(tb_lanes *x, tb_lanes_out *o)
{
    worker *w0 = &x->w[0];
    tb_range *g = &w0->rg;
    for (int i = 0; i < g->nlive; i++) {
        g->lv[i].lo = x->mn[i];
        g->lv[i].span = (uint64_t)x->mx[i] - (uint64_t)x->mn[i];
    }
    g->sampled = 1;
    /* every signal's overflows, onto what worker 0's build holds from its
     * constants' (once: x->ovf is emptied) */
    for (uint32_t i = 0; i < x->nsig; i++) {
        sim_signal *s = sim_signal_at(w0->b.c, i);
        s->overflows += x->ovf[i];
        s->ovf_discarded += x->ovf[x->nsig + i];
    }
    memset(x->ovf, 0, 2 * (size_t)x->nsig * sizeof *x->ovf);
    o->c = w0->b.c;
    o->sc = w0->b.sc;
    o->io = &w0->b.io;
    o->rg = g;
    o->toggles = x->tog;
    o->clocks = x->at_edge;
    o->lanes = x->lanes;
}
