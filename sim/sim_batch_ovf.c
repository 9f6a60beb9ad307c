/* sim_batch_ovf.c - the kernel's overflow counts, per signal and lane, on
 * the batch (sim_batch_overflows_on in sim_batch.h).
 *
 * What the kernel counts (sim_sched.c, settle_overflows): in each time
 * step, an element whose *last* evaluation overflowed, once; in
 * `overflows` when the value is used that clock (sim__value_used), else
 * in `ovf_discarded`. Its last evaluation sees the settled inputs, so
 * whether it overflowed is a function of settled values; whether it ran
 * at all is a matter of events:
 *  - a register runs at every rising edge: it counts at every edge at
 *    which its load (enabled, not in reset) overflows. The batch
 *    evaluates it only in the lanes where its input, enable or reset
 *    changed since the last edge; in the others the load is the one of
 *    the edge before, so each register keeps, per lane, whether its last
 *    load overflowed (rovf), and that counts at every edge;
 *  - a combinational element runs when one of its inputs had an event.
 *    The batch evaluates it in the lanes where an input's settled value
 *    changed (and the vector loops in some more, which compute what they
 *    hold: those are not counted). Where an input can change only once a
 *    time step (all its paths from the registers and inputs equally long,
 *    in delta cycles), an event is a change of the settled value, and the
 *    two agree. Where an input can change twice (paths of different
 *    lengths meet: it may glitch and come back), the kernel may run the
 *    element with no settled input changed. If that element holds an
 *    overflowed value then, the count depends on the kernel's delta
 *    cycles: that lane's time step is replayed as the kernel runs it
 *    (replay below: the values before the edge, kept for such lanes,
 *    then delta cycle after delta cycle, each element woken by an event
 *    evaluated by sim_elem_eval), and the element counts if it ran.
 *    The replay must end on the batch's settled values; if it does not
 *    (it cannot, short of a fault), or memory is short, the step is
 *    counted as unsure in that lane (sim_batch_ovf_unsure).
 * The evaluation loops note each quantization that overflowed
 * (sim__batch_ovf_note, from the exact path only, so nothing is added to
 * the fast paths); after each settle, sim__batch_ovf_step turns the notes
 * into counts.
 */
#include "sim/sim_batch_int.h"
#include <stdlib.h>
#include <string.h>

#define ALL_LANES UINT32_MAX

struct sim__batch_ovf {
    uint64_t *used, *disc;       /* nsig x lanes: the counts */
    uint64_t *log;               /* this settle's notes: signal << 32 | lane (ALL_LANES: every lane) */
    size_t    nlog, caplog;
    uint64_t *lmask;             /* nsig x nw: the lanes noted this settle */
    uint32_t *touched;           /* the signals noted this settle */
    uint32_t  ntouched;
    int32_t  *reg_of, *comb_of;  /* per signal: its register's or element's index, or -1 */
    unsigned char *glitchy;      /* per element: an input may change twice in a time step */
    uint64_t *eovf;              /* ncomb x nw: glitchy elements, the lanes whose value overflowed */
    uint64_t *rovf;              /* nreg x nw: the lanes whose last load overflowed */
    uint64_t *ev;                /* nreg x nw: the lanes each register is evaluated in at this edge */
    uint32_t  nheld;             /* eovf and rovf words not zero (0: nothing to carry) */
    uint64_t *unsure;            /* per lane: the time steps its counts may miss */
    /* used values: per signal, the signals of the primitives reading it (CSR) */
    uint32_t *ustart, *uses;
    sim_prim_info *info;         /* per signal, driven ones */
    uint64_t *uepoch;            /* per signal: the memo's (step, lane) */
    signed char *umemo;
    uint64_t  step;
    /* the replay: the values before the edge of the lanes that may need
     * one (lanes x nsig), each signal's readers among the elements (CSR) */
    int64_t  *old;
    uint64_t  oldm[SIM_BATCH_MAX_LANES / 64];   /* the lanes old holds */
    uint32_t *rstart, *readers;
    int64_t  *cur, *nv;          /* nsig, ncomb */
    uint32_t *evs, *nevs, *wk;   /* events of a delta, of the next, the elements woken */
    uint64_t *woke, *ran;        /* per element: the delta it was woken at, the replay it ran in */
    uint64_t  delta, replays;
};

void sim__batch_ovf_free(sim_batch *b)
{
    struct sim__batch_ovf *o = b->oc;
    if (!o) return;
    free(o->used); free(o->disc); free(o->log); free(o->lmask); free(o->touched); free(o->reg_of); free(o->comb_of);
    free(o->glitchy); free(o->eovf); free(o->rovf); free(o->ev); free(o->unsure); free(o->ustart); free(o->uses);
    free(o->info); free(o->uepoch); free(o->umemo);
    free(o->old); free(o->rstart); free(o->readers); free(o->cur); free(o->nv); free(o->evs); free(o->nevs); free(o->wk);
    free(o->woke); free(o->ran);
    free(o);
    b->oc = NULL;
}

void sim__batch_ovf_note(const bop *p, const unsigned char *ovf)
{
    sim_batch *b = p->owner;
    struct sim__batch_ovf *o = b->oc;
    uint32_t lane = b->in_uniform ? ALL_LANES : (uint32_t)(ovf - b->ovf);
    if (o->nlog == o->caplog) {
        size_t cap = o->caplog ? 2 * o->caplog : 64;
        uint64_t *n = realloc(o->log, cap * sizeof *n);
        if (!n) { for (uint32_t l = 0; l < b->lanes; l++) o->unsure[l]++; return; }   /* no memory to note it */
        o->log = n;
        o->caplog = cap;
    }
    o->log[o->nlog++] = (uint64_t)p->sig << 32 | lane;
}

/* The primitives reading each signal, as the kernel's sim__uses_build
 * lists them: a, b, c, reset and the inputs (a register's clock aside). */
static int build_uses(struct sim__batch_ovf *o, const sim_ctx *c, uint32_t nsig)
{
    o->ustart = calloc((size_t)nsig + 1, sizeof *o->ustart);
    if (!o->ustart) return -1;
    for (int fill = 0; fill < 2; fill++) {
        uint32_t *at = NULL;
        if (fill) {
            for (uint32_t i = 0; i < nsig; i++) o->ustart[i + 1] += o->ustart[i];
            o->uses = malloc(((size_t)o->ustart[nsig] + 1) * sizeof *o->uses);
            at = malloc(((size_t)nsig + 1) * sizeof *at);
            if (!o->uses || !at) { free(at); return -1; }
            memcpy(at, o->ustart, (size_t)nsig * sizeof *at);
        }
        for (uint32_t i = 0; i < nsig; i++) {
            const sim_prim_info *p = &o->info[i];
            if (!p->y || !sim_signal_at(c, i)->driver) continue;
            const sim_signal *r[4 + 256];
            int n = 0;
            const sim_signal *fixed[4] = { p->a, p->b, p->c, p->rst };
            for (int j = 0; j < 4; j++) if (fixed[j]) r[n++] = fixed[j];
            for (int j = 0; j < p->n && j < 256; j++) if (p->in[j]) r[n++] = p->in[j];
            for (int j = 0; j < n; j++) {
                if (!fill) o->ustart[r[j]->index + 1]++;
                else o->uses[at[r[j]->index]++] = i;
            }
        }
        free(at);
    }
    return 0;
}

/* Elements an input of which may change twice in a time step: each
 * signal's event comes at delta cycles in [mn, mx] after the edge
 * (registers and inputs at 0; an element one after its inputs); an input
 * with mn < mx may glitch. */
static void classify(struct sim__batch_ovf *o, const sim_batch *b)
{
    int32_t *mn = malloc((size_t)b->nsig * sizeof *mn), *mx = malloc((size_t)b->nsig * sizeof *mx);
    if (!mn || !mx) {   /* every element glitchy: counts marked unsure rather than wrong */
        memset(o->glitchy, 1, b->ncomb ? b->ncomb : 1);
        free(mn); free(mx);
        return;
    }
    for (uint32_t i = 0; i < b->nsig; i++) { mn[i] = INT32_MAX; mx[i] = -1; }   /* never an event */
    for (uint32_t i = 0; i < b->nin; i++) mn[b->in_sig[i]] = mx[b->in_sig[i]] = 0;
    for (uint32_t i = 0; i < b->nreg; i++) mn[b->reg[i].sig] = mx[b->reg[i].sig] = 0;
    for (uint32_t e = 0; e < b->ncomb; e++) {
        const bop *p = &b->comb[e];
        int32_t lo = INT32_MAX, hi = -1;
        for (int k = 0; k < p->ndep; k++) {
            uint32_t s = p->dep[k];
            if (mx[s] < 0) continue;
            if (mn[s] != mx[s]) o->glitchy[e] = 1;
            if (mn[s] < lo) lo = mn[s];
            if (mx[s] > hi) hi = mx[s];
        }
        if (hi >= 0) { mn[p->sig] = lo + 1; mx[p->sig] = hi + 1; }
    }
    free(mn); free(mx);
}

/* Each signal's readers among the combinational elements, and the
 * replay's scratch. */
static int build_readers(struct sim__batch_ovf *o, const sim_batch *b)
{
    size_t ns = b->nsig ? b->nsig : 1, nc = b->ncomb ? b->ncomb : 1;
    o->rstart = calloc(ns + 1, sizeof *o->rstart);
    o->old = malloc(ns * b->lanes * sizeof *o->old);
    o->cur = malloc(ns * sizeof *o->cur);
    o->nv = malloc(nc * sizeof *o->nv);
    o->evs = malloc(ns * sizeof *o->evs);
    o->nevs = malloc(ns * sizeof *o->nevs);
    o->wk = malloc(nc * sizeof *o->wk);
    o->woke = calloc(nc, sizeof *o->woke);
    o->ran = calloc(nc, sizeof *o->ran);
    if (!o->rstart || !o->old || !o->cur || !o->nv || !o->evs || !o->nevs || !o->wk || !o->woke || !o->ran) return -1;
    for (uint32_t e = 0; e < b->ncomb; e++)
        for (int k = 0; k < b->comb[e].ndep; k++) o->rstart[b->comb[e].dep[k] + 1]++;
    for (uint32_t i = 0; i < b->nsig; i++) o->rstart[i + 1] += o->rstart[i];
    o->readers = malloc(((size_t)o->rstart[b->nsig] + 1) * sizeof *o->readers);
    uint32_t *at = malloc(ns * sizeof *at);
    if (!o->readers || !at) { free(at); return -1; }
    memcpy(at, o->rstart, (size_t)b->nsig * sizeof *at);
    for (uint32_t e = 0; e < b->ncomb; e++)
        for (int k = 0; k < b->comb[e].ndep; k++) {
            uint32_t s = b->comb[e].dep[k];
            /* an element reading one signal twice is woken once */
            if (at[s] > o->rstart[s] && o->readers[at[s] - 1] == e) continue;
            o->readers[at[s]++] = e;
        }
    /* the slots a repeated read left unused: UINT32_MAX, skipped */
    for (uint32_t s = 0; s < b->nsig; s++)
        for (uint32_t k = at[s]; k < o->rstart[s + 1]; k++) o->readers[k] = UINT32_MAX;
    free(at);
    return 0;
}

int sim_batch_overflows_on(sim_batch *b)
{
    if (b->oc) return 0;
    if (b->started) return -1;
    struct sim__batch_ovf *o = calloc(1, sizeof *o);
    if (!o) return -1;
    b->oc = o;
    size_t n = (size_t)(b->nsig ? b->nsig : 1) * b->lanes, nw = b->nw;
    o->used = calloc(n, sizeof *o->used);
    o->disc = calloc(n, sizeof *o->disc);
    o->lmask = calloc((size_t)(b->nsig ? b->nsig : 1) * nw, sizeof *o->lmask);
    o->touched = malloc((size_t)(b->nsig ? b->nsig : 1) * sizeof *o->touched);
    o->reg_of = malloc((size_t)(b->nsig ? b->nsig : 1) * sizeof *o->reg_of);
    o->comb_of = malloc((size_t)(b->nsig ? b->nsig : 1) * sizeof *o->comb_of);
    o->glitchy = calloc(b->ncomb ? b->ncomb : 1, 1);
    o->eovf = calloc((size_t)(b->ncomb ? b->ncomb : 1) * nw, sizeof *o->eovf);
    o->rovf = calloc((size_t)(b->nreg ? b->nreg : 1) * nw, sizeof *o->rovf);
    o->ev = calloc((size_t)(b->nreg ? b->nreg : 1) * nw, sizeof *o->ev);
    o->unsure = calloc(b->lanes, sizeof *o->unsure);
    o->info = calloc(b->nsig ? b->nsig : 1, sizeof *o->info);
    o->uepoch = calloc(b->nsig ? b->nsig : 1, sizeof *o->uepoch);
    o->umemo = calloc(b->nsig ? b->nsig : 1, 1);
    if (!o->used || !o->disc || !o->lmask || !o->touched || !o->reg_of || !o->comb_of || !o->glitchy || !o->eovf ||
        !o->rovf || !o->ev || !o->unsure || !o->info || !o->uepoch || !o->umemo)
        goto oom;
    for (uint32_t i = 0; i < b->nsig; i++) {
        o->reg_of[i] = o->comb_of[i] = -1;
        const sim_signal *s = sim_signal_at(b->ctx, i);
        if (s->driver && sim_prim_describe(s, &o->info[i])) memset(&o->info[i], 0, sizeof o->info[i]);
    }
    for (uint32_t i = 0; i < b->nreg; i++) o->reg_of[b->reg[i].sig] = (int32_t)i;
    for (uint32_t i = 0; i < b->ncomb; i++) o->comb_of[b->comb[i].sig] = (int32_t)i;
    if (build_uses(o, b->ctx, b->nsig) || build_readers(o, b)) goto oom;
    classify(o, b);
    return 0;
oom:
    sim__batch_ovf_free(b);
    return -1;
}

const uint64_t *sim_batch_ovf_used(const sim_batch *b, const sim_signal *s)
{
    return b->oc && s->index < b->nsig ? b->oc->used + (size_t)s->index * b->lanes : NULL;
}

const uint64_t *sim_batch_ovf_discarded(const sim_batch *b, const sim_signal *s)
{
    return b->oc && s->index < b->nsig ? b->oc->disc + (size_t)s->index * b->lanes : NULL;
}

uint64_t sim_batch_ovf_unsure(const sim_batch *b, uint32_t lane)
{
    return !b->oc || lane >= b->lanes ? UINT64_MAX : b->oc->unsure[lane];
}

/* ---------------------------------------------------------- used values */

static inline int64_t lane_val(const sim_batch *b, const sim_signal *s, uint32_t l)
{
    return b->val[(size_t)s->index * b->lanes + l];
}

/* sim__value_used (sim_prim.c) on lane l's settled values; ep names the
 * (step, lane) of the memo. */
static int value_used(const sim_batch *b, const sim_signal *s, uint32_t l, uint64_t ep)
{
    struct sim__batch_ovf *o = b->oc;
    uint32_t i = s->index;
    if (s->kind == SIM_KIND_REG || s->is_output || o->ustart[i] == o->ustart[i + 1]) return 1;   /* state, a port, an end */
    if (o->uepoch[i] == ep) return o->umemo[i];
    int used = 0;
    for (uint32_t k = o->ustart[i]; k < o->ustart[i + 1] && !used; k++) {
        const sim_prim_info *p = &o->info[o->uses[k]];
        switch (p->y->kind) {
        case SIM_KIND_REG:      /* D: taken at the next edge if enabled and not reset */
            used = s != p->a || ((!p->c || lane_val(b, p->c, l)) && !(p->rst && lane_val(b, p->rst, l)));
            break;
        case SIM_KIND_MUX:
            if (s == p->c) used = value_used(b, p->y, l, ep);
            else {
                int64_t sel = lane_val(b, p->c, l);
                used = SIM_OP_SEL_IN(sel, p->n) && p->in[sel] == s && value_used(b, p->y, l, ep);
            }
            break;
        case SIM_KIND_BK:
            used = (s == p->c || lane_val(b, p->c, l)) && value_used(b, p->y, l, ep);
            break;
        default:
            used = value_used(b, p->y, l, ep);
        }
    }
    o->uepoch[i] = ep;
    o->umemo[i] = (signed char)used;
    return used;
}

/* One overflow of signal sig in each lane of m (word w). */
static void count_lanes(sim_batch *b, uint32_t sig, uint32_t w, uint64_t m)
{
    struct sim__batch_ovf *o = b->oc;
    const sim_signal *s = sim_signal_at(b->ctx, sig);
    while (m) {
        uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(m);
        m &= m - 1;
        size_t at = (size_t)sig * b->lanes + l;
        if (value_used(b, s, l, o->step * b->lanes + l + 1)) o->used[at]++;
        else o->disc[at]++;
    }
}

/* ------------------------------------------------------------- the edge */

void sim__batch_ovf_before_edge(sim_batch *b)
{
    struct sim__batch_ovf *o = b->oc;
    memcpy(o->ev, b->regm, (size_t)b->nreg * b->nw * sizeof *o->ev);
    /* the lanes where a glitchy element holds an overflowed value may
     * need a replay of this edge: their values before it */
    for (uint32_t w = 0; w < b->nw; w++) o->oldm[w] = 0;
    if (!o->nheld) return;
    for (uint32_t e = 0; e < b->ncomb; e++)
        if (o->glitchy[e])
            for (uint32_t w = 0; w < b->nw; w++) o->oldm[w] |= o->eovf[(size_t)e * b->nw + w];
    for (uint32_t w = 0; w < b->nw; w++)
        for (uint64_t x = o->oldm[w]; x; x &= x - 1) {
            uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(x);
            int64_t *to = o->old + (size_t)l * b->nsig;
            for (uint32_t i = 0; i < b->nsig; i++) to[i] = b->val[(size_t)i * b->lanes + l];
        }
}

/* Lane l's edge as the kernel runs it, from the values before it: the
 * registers' and inputs' changes are the events of the first delta
 * cycle; each delta, every element an event woke is evaluated on the
 * values then (sim_elem_eval), and the outputs that change are the next
 * delta's events. o->ran[e] == o->replays marks the elements that ran.
 * 0, or -1 if it did not end on the batch's settled values. */
static int replay(sim_batch *b, uint32_t l)
{
    struct sim__batch_ovf *o = b->oc;
    const int64_t *old = o->old + (size_t)l * b->nsig;
    int64_t *cur = o->cur;
    memcpy(cur, old, (size_t)b->nsig * sizeof *cur);
    o->replays++;
    uint32_t nev = 0;
    for (uint32_t i = 0; i < b->nin; i++) {
        uint32_t s = b->in_sig[i];
        int64_t v = b->val[(size_t)s * b->lanes + l];
        if (v != cur[s]) { cur[s] = v; o->evs[nev++] = s; }
    }
    for (uint32_t i = 0; i < b->nreg; i++) {
        uint32_t s = b->reg[i].sig;
        int64_t v = b->val[(size_t)s * b->lanes + l];
        if (v != cur[s]) { cur[s] = v; o->evs[nev++] = s; }
    }
    int64_t in[10 + 256];
    while (nev) {
        uint32_t nwk = 0;
        o->delta++;
        for (uint32_t k = 0; k < nev; k++)
            for (uint32_t r = o->rstart[o->evs[k]]; r < o->rstart[o->evs[k] + 1]; r++) {
                uint32_t e = o->readers[r];
                if (e == UINT32_MAX || o->woke[e] == o->delta) continue;
                o->woke[e] = o->delta;
                o->wk[nwk++] = e;
            }
        /* evaluate on this delta's values, then update */
        for (uint32_t k = 0; k < nwk; k++) {
            const bop *p = &b->comb[o->wk[k]];
            for (int j = 0; j < p->ndep; j++) in[j] = cur[p->dep[j]];
            int ov = 0;
            int64_t v = cur[p->sig];
            sim_elem_eval(&o->info[p->sig], in, &v, &ov);
            o->nv[k] = v;
            o->ran[o->wk[k]] = o->replays;
        }
        uint32_t nn = 0;
        for (uint32_t k = 0; k < nwk; k++) {
            uint32_t s = b->comb[o->wk[k]].sig;
            if (o->nv[k] != cur[s]) { cur[s] = o->nv[k]; o->nevs[nn++] = s; }
        }
        uint32_t *t = o->evs; o->evs = o->nevs; o->nevs = t;
        nev = nn;
    }
    for (uint32_t i = 0; i < b->nsig; i++)
        if (cur[i] != b->val[(size_t)i * b->lanes + l]) return -1;
    return 0;
}

/* The lanes element p runs in this settle, as the kernel would: an input
 * changed (every lane at the start). */
static void woken(const sim_batch *b, const bop *p, uint64_t *m)
{
    for (uint32_t w = 0; w < b->nw; w++) m[w] = b->started ? 0 : b->all[w];
    if (!b->started) return;
    for (int k = 0; k < p->ndep; k++)
        for (uint32_t w = 0; w < b->nw; w++) m[w] |= b->chg[(size_t)p->dep[k] * b->nw + w];
}

void sim__batch_ovf_step(sim_batch *b)
{
    struct sim__batch_ovf *o = b->oc;
    const uint32_t nw = b->nw;
    if (!o->nlog && !o->nheld) return;
    o->step++;
    /* the notes, as lanes per signal */
    for (size_t i = 0; i < o->nlog; i++) {
        uint32_t sig = (uint32_t)(o->log[i] >> 32), lane = (uint32_t)o->log[i];
        uint64_t *lm = o->lmask + (size_t)sig * nw;
        int fresh = 1;
        for (uint32_t w = 0; w < nw; w++) fresh &= !lm[w];
        if (fresh) o->touched[o->ntouched++] = sig;
        if (lane == ALL_LANES) memcpy(lm, b->all, nw * sizeof *lm);
        else lm[lane >> 6] |= (uint64_t)1 << (lane & 63);
    }
    o->nlog = 0;
    uint32_t held = 0;
    uint64_t m[SIM_BATCH_MAX_LANES / 64];
    /* registers: a lane evaluated takes this load's outcome, the others
     * keep theirs; each counts at every edge (not at the start) */
    if (b->started)
        for (uint32_t i = 0; i < b->nreg; i++) {
            const bop *p = &b->reg[i];
            uint64_t *r = o->rovf + (size_t)i * nw;
            const uint64_t *ev = o->ev + (size_t)i * nw, *lm = o->lmask + (size_t)p->sig * nw;
            for (uint32_t w = 0; w < nw; w++) {
                r[w] = (r[w] & ~ev[w]) | (lm[w] & ev[w]);
                if (r[w]) { held++; count_lanes(b, p->sig, w, r[w]); }
            }
        }
    /* combinational elements: counted in the lanes they run in */
    for (uint32_t t = 0; t < o->ntouched; t++) {
        uint32_t sig = o->touched[t];
        int32_t e = o->comb_of[sig];
        if (e < 0) continue;
        const bop *p = &b->comb[e];
        const uint64_t *lm = o->lmask + (size_t)sig * nw;
        woken(b, p, m);
        for (uint32_t w = 0; w < nw; w++) if (lm[w] & m[w]) count_lanes(b, sig, w, lm[w] & m[w]);
    }
    /* glitchy elements: what their values hold, and the lanes where the
     * kernel may run them with no settled input changed */
    uint64_t replayed[SIM_BATCH_MAX_LANES / 64] = { 0 };   /* this step's lanes replayed, */
    uint64_t failed[SIM_BATCH_MAX_LANES / 64] = { 0 };     /* and those that did not end where the batch did */
    uint64_t first = o->replays;                          /* ran[] of a replay after this */
    uint64_t rep_of[SIM_BATCH_MAX_LANES];
    for (uint32_t e = 0; e < b->ncomb; e++) {
        if (!o->glitchy[e]) continue;
        const bop *p = &b->comb[e];
        uint64_t *eo = o->eovf + (size_t)e * nw;
        const uint64_t *lm = o->lmask + (size_t)p->sig * nw;
        uint64_t any = 0;
        for (uint32_t w = 0; w < nw; w++) any |= eo[w] | lm[w];
        if (!any) continue;
        woken(b, p, m);
        for (uint32_t w = 0; w < nw; w++) {
            /* holding an overflowed value, no input changed: did a glitch run it? */
            uint64_t keep = eo[w] & ~m[w], ran = 0;
            for (uint64_t x = keep; x; x &= x - 1) {
                uint32_t l = w * 64 + (uint32_t)__builtin_ctzll(x);
                uint64_t bit = (uint64_t)1 << (l & 63);
                if (!(o->oldm[w] & bit)) { o->unsure[l]++; continue; }   /* (cannot be: kept before the edge) */
                if (!(replayed[w] & bit)) {
                    replayed[w] |= bit;
                    if (replay(b, l)) failed[w] |= bit;
                    rep_of[l] = o->replays;
                    /* the replays share ran[]: each lane's is read right after it */
                }
                if (failed[w] & bit) { o->unsure[l]++; continue; }
                if (o->ran[e] == rep_of[l]) ran |= bit;
                else if (o->ran[e] > first && rep_of[l] != o->replays) {
                    /* a later lane's replay overwrote it: this lane's again */
                    replay(b, l);
                    rep_of[l] = o->replays;
                    if (o->ran[e] == rep_of[l]) ran |= bit;
                }
            }
            if (ran) count_lanes(b, p->sig, w, ran);
            eo[w] = keep | (lm[w] & m[w]);
            if (eo[w]) held++;
        }
    }
    o->nheld = held;
    for (uint32_t t = 0; t < o->ntouched; t++) memset(o->lmask + (size_t)o->touched[t] * nw, 0, nw * sizeof *o->lmask);
    o->ntouched = 0;
}
