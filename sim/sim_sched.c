/* sim_sched.c - the scheduler: timers and clocks, time steps, the
 * delta-cycle loop, the end of a step (overflows settled, observers).
 *
 * One time step runs:   timers due now -> [evaluate -> update]* ->
 * overflows settled -> observers (sim_observe: value change dumps...).
 * Evaluate runs each runnable process once; processes only write signals'
 * next values (sim_write). Update copies next to current for every written
 * signal, and each signal that really changed wakes its sensitive processes
 * for the next delta. Because no process sees a write before the update,
 * the order in which processes run never changes the result.
 *
 * Where the time goes, and what keeps it short (every counter in
 * sim_stats and every signal's `changes` is what the plain algorithm
 * counts; sim_set_reference runs that plain algorithm, with none of the
 * fast paths marked *, and tests/test_kernel.c, tests/cli_engine.sh and
 * tests/cli_gold.sh hold the two to the same counters):
 *  * A primitive (sim_prim.c) whose exact result fits 62 bits is evaluated
 *    by the kernel itself (sim__proc.op, sim_internal.h): operands, one
 *    add or multiply, one shift (none when the result already has the
 *    output's fraction bits: the *_X operations), a range check, the
 *    write. Anything else, or a result out of range (an overflow to
 *    count), calls the process's own function. The delta loop is written
 *    once (sim_deltas.h) and compiled twice: the fast copy dispatches with
 *    a computed goto, the reference copy with a switch on a constant (every
 *    primitive through sim_elem_eval, from its record; any other process
 *    its function). sim_stats.fast_paths counts the entries into these
 *    paths: tests/test_reference.c holds the reference's at 0.
 *  * A logic element with a few input bits is a table (tabulate).
 *  * A time step whose only business is one clock edge (no other timer
 *    due, nothing pending) toggles the clock and runs the first delta's
 *    update in place (tick_in_place), without the timer and update
 *    machinery; a falling edge nobody waits for costs a few stores.
 *  - The list of changed signals observers read (sim_changed) is kept only
 *    while an observer asks for it: the update loop has a copy without
 *    it, and one that leaves the changed signals in order for the loop
 *    report, so the usual one does neither.
 *  - A write of the value a signal already has is not queued (sim.h).
 *  - A signal keeps the processes to wake per new value (zero / nonzero),
 *    so an edge-sensitive process is never looked at on the other edge.
 *  - A process is in the run list being built when its `listed` holds the
 *    list's generation, one number per delta: starting a new list is one
 *    increment, and a process costs no store when it runs.
 *  - The delta loop keeps the context's lists in locals (the run lists for
 *    the whole time step: processes never touch them), and the flags it
 *    writes are not char-typed (a char store may alias anything and would
 *    make the compiler reload every pointer after it).
 */
#include "sim/sim_internal.h"
#include "sim/sim_lut.h"
#include "sim/sim_op.h"
#include <stdio.h>
#include <string.h>

#ifndef SIM_KERNEL_SWITCH
#define SIM_KERNEL_SWITCH 0   /* 1: the fast copy dispatches with a switch too */
#endif

/* ------------------------------------------------------------------ timers */

typedef struct sim_clockgen {
    sim_signal *clk;
    sim_time half;
} sim_clockgen;

static int timer_before(const sim__timer *a, const sim__timer *b)
{
    return a->at < b->at || (a->at == b->at && a->seq < b->seq);
}

static void timer_push(sim_ctx *c, sim_time at, void (*fn)(sim_ctx *, void *), void *data)
{
    c->heap = sim__grow(c->heap, &c->capheap, sizeof *c->heap, c->nheap + 1);
    uint32_t i = c->nheap++;
    sim__timer t = { at, c->timer_seq++, fn, data };
    while (i > 0) {
        uint32_t up = (i - 1) / 2;
        if (!timer_before(&t, &c->heap[up])) break;
        c->heap[i] = c->heap[up];
        i = up;
    }
    c->heap[i] = t;
}

/* Put t at the root's place and sift it down: replaces the earliest timer
 * (a pop followed by a push of t, without the second walk). */
static void timer_sift_root(sim_ctx *c, sim__timer t)
{
    uint32_t i = 0, n = c->nheap;
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, m = i;
        const sim__timer *best = &t;
        if (l < n && timer_before(&c->heap[l], best)) { m = l; best = &c->heap[l]; }
        if (r < n && timer_before(&c->heap[r], best)) { m = r; }
        if (m == i) break;
        c->heap[i] = c->heap[m];
        i = m;
    }
    c->heap[i] = t;
}

static sim__timer timer_pop(sim_ctx *c)
{
    sim__timer top = c->heap[0];
    c->nheap--;
    if (c->nheap) timer_sift_root(c, c->heap[c->nheap]);
    return top;
}

static void clock_tick(sim_ctx *c, void *data)
{
    sim_clockgen *g = data;
    int64_t v = !g->clk->cur;
    sim_force(g->clk, v);
    if (v) c->stats.clocks++;
    timer_push(c, c->now + g->half, clock_tick, g);
}

void sim_clock(sim_ctx *c, sim_signal *clk, sim_time half_period, sim_time first_rise)
{
    if (clk->driver) {
        char path[256];
        sim__elab_error(c, "%s: a clock on a signal that a process drives (two drivers)",
                        sim_signal_path(clk, path, sizeof path));
        return;
    }
    sim_clockgen *g = sim_alloc(c, sizeof *g);
    g->clk = clk;
    g->half = half_period ? half_period : 1;
    clk->kind = SIM_KIND_CLOCK;
    /* The clock idles low; its first tick raises it. */
    timer_push(c, first_rise, clock_tick, g);
}

/* ------------------------------------------------------- the delta loop */

/* s changed to v: the processes waiting for such a change join list (n
 * long, of generation gen), each once; returns the new length. The one
 * wake loop of the update and of a clock's tick in place. */
static inline __attribute__((always_inline))
uint32_t wake(const sim_signal *s, int64_t v, sim__proc **list, uint32_t n, uint64_t gen)
{
    sim__proc *const *w = s->wake[v != 0];
    for (uint32_t j = 0, k = s->nwake[v != 0]; j < k; j++) {
        sim__proc *q = w[j];
        if (q->listed != gen) { q->listed = gen; list[n++] = q; }
    }
    return n;
}

/* A logic element's user function on its inputs' values (one input: read
 * in place). */
static inline int64_t logic_call(const sim__proc *p)
{
    if (p->op_n == 1) return p->op_logic(&p->op_a->cur, p->op_user);
    int64_t in[SIM__LOGIC_MAX];
    for (uint32_t i = 0; i < p->op_n; i++) in[i] = p->op_in[i]->cur;
    return p->op_logic(in, p->op_user);
}

/* Update phase: apply the writes; each signal that changes wakes its
 * processes into next (*nnext of them), the list of generation gen.
 * Returns the number of signals that changed. Two switches, constant at
 * every call site so that each copy of the loop has only the tests it
 * needs:
 *  - track: an observer reads sim_changed, so a changed signal is noted
 *    in the changed list (without one, the loop does not test for it);
 *  - compact: the signals that changed are left at the front of upd, in
 *    order (only the loop report reads them).
 * Lists and counts are in locals: stores through signal and process
 * pointers would otherwise make the compiler reload them. */
static inline __attribute__((always_inline))
uint32_t update(sim_ctx *c, sim_signal **upd, uint32_t nupd, sim__proc **next, uint32_t *nnext,
                uint64_t gen, int track, int compact)
{
    uint32_t nchanged = 0, nn = *nnext;
    sim_signal **chg = c->chg_on;
    uint32_t nchg = c->nchg;
    uint16_t epoch = (uint16_t)c->epoch;
    for (uint32_t i = 0; i < nupd; i++) {
        sim_signal *s = upd[i];
        s->queued = 0;
        int64_t v = s->nxt;
        if (v == s->cur) continue;
        s->cur = v;
        s->changes++;
        if (compact) upd[nchanged] = s;
        nchanged++;
        if (track && s->noted != epoch) { s->noted = epoch; chg[nchg++] = s; }
        nn = wake(s, v, next, nn, gen);
    }
    c->q.nupd = 0;
    if (track) c->nchg = nchg;
    c->stats.events += nchanged;
    *nnext = nn;
    return nchanged;
}

/* The two copies of the delta loop (sim_deltas.h). */
#define SIM__DELTAS_NAME   deltas_fast
#define SIM__DELTAS_REF    0
#define SIM__DELTAS_SWITCH SIM_KERNEL_SWITCH
#include "sim/sim_deltas.h"
#define SIM__DELTAS_NAME   deltas_ref
#define SIM__DELTAS_REF    1
#define SIM__DELTAS_SWITCH 1
#include "sim/sim_deltas.h"

static inline int run_deltas(sim_ctx *c, uint32_t *deltas, int once)
{
    if (__builtin_expect(c->reference, 0)) return deltas_ref(c, deltas, once);
    return deltas_fast(c, deltas, once);
}

/* One delta cycle (for the loop report). */
static uint32_t delta(sim_ctx *c)
{
    uint32_t d = 0;
    run_deltas(c, &d, 1);
    return c->changed;
}

/* Name the signals still changing when the delta bound was hit: after the
 * settled part of the design has stopped, only the loop keeps toggling.
 * A loop changes one signal per delta, so watch a few more deltas. */
static void report_loop(sim_ctx *c)
{
    sim_signal *seen[16];
    uint32_t n = 0;
    for (int d = 0; d < 16 && (c->nrun || c->q.nupd); d++) {
        uint32_t k = delta(c);
        for (uint32_t i = 0; i < k && n < 16; i++) {
            uint32_t j = 0;
            while (j < n && seen[j] != c->q.upd[i]) j++;
            if (j == n) seen[n++] = c->q.upd[i];
        }
    }
    int off = snprintf(c->err, sizeof c->err,
                       "combinational loop at time %llu: no stable value after %u delta cycles; still changing:",
                       (unsigned long long)c->now, c->max_deltas);
    char path[256];
    for (uint32_t i = 0; i < n && off > 0 && (size_t)off < sizeof c->err - 1; i++)
        off += snprintf(c->err + off, sizeof c->err - (size_t)off, "%s %s",
                        i ? " ->" : "", sim_signal_path(seen[i], path, sizeof path));
}

/* -------------------------------------------------------------- time steps */

/* Whether the time step's only business is the clock tick at heap[0]: no
 * other timer due now (the root's children are the earliest others) and
 * nothing pending. */
static inline int tick_alone(const sim_ctx *c)
{
    return c->heap[0].fn == clock_tick && !c->nrun && !c->q.nupd &&
           !(c->nheap > 1 && c->heap[1].at <= c->now) && !(c->nheap > 2 && c->heap[2].at <= c->now);
}

/* The tick done in place: the clock toggles and its update, the time
 * step's first delta cycle, wakes its processes; the timer becomes the
 * next tick. Counts exactly what clock_tick and the update count. */
static inline void tick_in_place(sim_ctx *c)
{
    sim__timer *t = &c->heap[0];
    sim_clockgen *g = t->data;
    sim_signal *clk = g->clk;
    int64_t v = !clk->cur;
    t->at = c->now + g->half;
    t->seq = c->timer_seq++;
    c->stats.clocks += (uint64_t)v;
    clk->nxt = clk->cur = v;
    clk->changes++;
    c->stats.deltas++;
    c->stats.events++;
    if (c->chg_on && clk->noted != c->epoch) { clk->noted = (uint16_t)c->epoch; c->chg_on[c->nchg++] = clk; }
    c->nrun = wake(clk, v, c->run, c->nrun, c->gen);
    if (c->nheap > 1) timer_sift_root(c, *t);
}

/* The start of every time step: the timers due now fire. Returns the
 * delta cycles that ran: 1 when the step was a clock's tick alone, done
 * in place (not in the reference), else 0. */
static inline uint32_t step_start(sim_ctx *c)
{
    if (!c->nheap || c->heap[0].at > c->now) return 0;
    if (!c->reference && tick_alone(c)) { c->stats.fast_paths++; tick_in_place(c); return 1; }
    do {
        sim__timer t = timer_pop(c);
        t.fn(c, t.data);
    } while (c->nheap && c->heap[0].at <= c->now);
    return 0;
}

/* A settled overflow counts in overflows when its value is used that
 * clock, else in ovf_discarded (sim__value_used). */
static void settle_overflows(sim_ctx *c)
{
    int fresh = 0;
    for (uint32_t i = 0; i < c->novfq; i++) {
        sim_signal *s = c->ovfq[i];
        s->ovf_pending = 0;
        if (s->cur != s->ovf_raw || (s->driver && sim__proc_of(s->driver)->runs != s->ovf_run)) continue;
        if (!fresh) {
            if (c->uses_nsig != c->nsig) { sim__uses_build(c); c->uses_nsig = c->nsig; }
            c->use_epoch++;
            fresh = 1;
        }
        if (sim__value_used(s, c->use_epoch)) s->overflows++;
        else s->ovf_discarded++;
    }
    c->novfq = 0;
}

/* The end of every time step: the overflows the settled values carry
 * counted, every observer, then a fresh changed list. */
static inline void step_end(sim_ctx *c)
{
    if (c->novfq) settle_overflows(c);
    if (c->nobs) {
        for (uint32_t i = 0; i < c->nobs; i++) c->obs[i].fn(c, c->now, c->obs[i].data);
        if (c->chg_on) sim__clear_changed(c);
    }
}

/* A logic element whose inputs have at most SIM_LUT_BITS_KERNEL bits in
 * all becomes a table (sim_lut.h, in the offset code), made once when
 * the simulation starts: an index and a load instead of a call. What it
 * gives for a value in range is what the call would. A value outside its
 * input's format (a raw forced from outside) still goes to the call. */
static void tabulate(sim_ctx *c, sim__proc *p)
{
    uint32_t n = p->op_n;
    int sh[SIM__LOGIC_MAX];
    uint64_t mask[SIM__LOGIC_MAX];
    if (n < 1 || n > SIM__LOGIC_MAX) return;
    int bits = sim_lut_layout((int)n, p->op_in, SIM_LUT_BITS_KERNEL, sh, mask);
    if (bits < 0) return;
    sim__lut_in *tin = sim_alloc(c, n * sizeof *tin);
    for (uint32_t j = 0; j < n; j++) {
        const sim_signal *in = p->op_in[j];
        tin[j].lo = in->raw_min;
        tin[j].span = (uint64_t)in->raw_max - (uint64_t)in->raw_min;
        tin[j].sh = sh[j];
    }
    c->stats.fast_paths++;
    SIM__ASSERT(bits <= SIM_LUT_BITS_KERNEL && (n > 1 || (uint64_t)p->op_in[0]->raw_max - (uint64_t)p->op_in[0]->raw_min < ((uint64_t)1 << bits)));
    int64_t *tab = sim_alloc(c, ((size_t)1 << bits) * sizeof *tab);
    sim_lut_fill(tab, bits, (int)n, p->op_in, mask, SIM_LUT_OFFSET,
                 p->op_logic, p->op_user, p->op_y->fmt);
    p->op_tab = tab;
    p->op_tin = tin;
    if (n == 1) {
        p->op_lo = tin[0].lo;
        p->op_hi = (int64_t)tin[0].span;
        p->op = SIM__OP_LUT1;
    } else {
        p->op = SIM__OP_LUTN;
    }
}

/* Initialization: every process runs once, as in SystemC, so that
 * combinational outputs agree with their inputs before time moves; the
 * logic tables are made (not in the reference). */
static void start(sim_ctx *c)
{
    c->started = 1;
    for (uint32_t i = 0; i < c->nproc; i++) {
        sim__proc *p = c->procs[i];
        if (!c->reference && (p->op == SIM__OP_LOGIC_S || p->op == SIM__OP_LOGIC_U)) tabulate(c, p);
        if (p->listed != c->gen && !p->pub.no_init) { p->listed = c->gen; c->run[c->nrun++] = p; }
    }
}

void sim_set_reference(sim_ctx *c, int on) { c->reference = on != 0; }

sim_status sim_run(sim_ctx *c, sim_time until)
{
    if (c->elab_err) return SIM_ERR_ELAB;
    if (!c->started) start(c);
    c->stop = 0;
    /* A time step is counted when it starts at a new time: here, unless
     * this run resumes the step the last one ended in, and below at each
     * advance of time. */
    c->stats.time_steps += !(c->stepped && c->now == c->step_time);
    c->stepped = 1;
    for (;;) {
        uint32_t deltas = step_start(c);
        if ((c->nrun || c->q.nupd) && (deltas >= c->max_deltas || run_deltas(c, &deltas, 0))) {
            c->step_time = c->now;
            report_loop(c);
            step_end(c);
            return SIM_ERR_LOOP;
        }
        step_end(c);
        if (c->stop || !c->nheap || c->heap[0].at > until) break;
        c->now = c->heap[0].at;
        c->stats.time_steps++;
    }
    c->step_time = c->now;
    if (!c->stop && until > c->now && until != (sim_time)-1) c->now = until;
    return SIM_OK;
}
