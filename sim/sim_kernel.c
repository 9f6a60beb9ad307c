/* sim_kernel.c - signals, processes, the delta-cycle loop and timed events.
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
 * counts; tests/test_kernel.c pins them):
 *  - A primitive (sim_prim.c) whose exact result fits 62 bits is evaluated
 *    by the kernel itself (sim__proc.op, sim_internal.h): operands, one
 *    add or multiply, one shift (none when the result already has the
 *    output's fraction bits: the *_X operations), a range check, the
 *    write. Anything else, or a result out of range (an overflow to
 *    count), calls the process's own function. Dispatch is a computed
 *    goto (run_deltas).
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
 *  - A time step that is just a clock edge (clock_step) toggles the clock
 *    and runs the first delta's update without the timer and update
 *    machinery; a falling edge nobody waits for costs a few stores. While
 *    the only timer is one clock, whole time steps run in clock_steps,
 *    which leaves out the general loop's tests.
 *  - A logic element with a few input bits is a table (tabulate).
 *  - The delta loop keeps the context's lists in locals (the run lists for
 *    the whole time step: processes never touch them), and the flags it
 *    writes are not char-typed (a char store may alias anything and would
 *    make the compiler reload every pointer after it).
 */
#include "sim/sim_internal.h"
#include "sim/sim_lut.h"
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* A timed event: at time `at`, fn(data). Clocks are the only users so far;
 * a binary heap keeps them ordered (seq breaks ties first-come first). */
typedef struct sim_timer {
    sim_time at;
    uint64_t seq;
    void   (*fn)(sim_ctx *c, void *data);
    void    *data;
} sim_timer;

typedef struct sim_clockgen {
    sim_signal *clk;
    sim_time half;
} sim_clockgen;

typedef struct sim_obs {
    sim_observer_fn fn;
    void    *data;
    unsigned flags;
} sim_obs;

struct sim_chunk { struct sim_chunk *next; };

struct sim_ctx {
    sim_updq     q;                          /* written this delta (first: see sim_write) */
    sim_signal **sigs;   uint32_t nsig, capsig;
    sim__proc  **procs;  uint32_t nproc, capproc;
    sim__proc  **run;    uint32_t nrun;      /* runnable this delta; capacity capproc */
    sim__proc  **run2;   uint32_t nrun2;     /* woken for the next delta */
    sim_signal **chg;    uint32_t nchg;      /* changed this time step (sim_changed) */
    sim_signal **chg_on;                     /* chg while an observer reads it, else NULL */
    uint32_t     epoch;                      /* a signal is in chg iff its noted is this */
    uint64_t     gen;                        /* a process is in the run list being built iff
                                              * its listed is this (one per delta: never wraps) */
    sim_signal **ovfq;   uint32_t novfq;     /* overflowed this time step (sim__overflow) */
    uint32_t     uses_nsig;                  /* signals when the readers were listed (0: not) */
    uint64_t     use_epoch;                  /* one per settling that met an overflow */
    sim_timer   *heap;   uint32_t nheap, capheap;
    uint64_t     timer_seq;
    sim_time     now;
    sim_stats    stats;
    sim_round    rnd;
    sim_ovf      ovf;
    uint32_t     max_deltas;
    uint32_t     changed;                    /* signals the last update changed */
    int          started, stop;
    int          stepped;                    /* a time step ran, the last at step_time */
    sim_time     step_time;
    sim_obs     *obs;    uint32_t nobs, capobs;
    uint32_t     track;                      /* observers reading sim_changed */
    int          elab_err;                   /* err holds an elaboration error */
    sim_scope    root;
    struct sim_chunk *mem;
    char         err[512];
};

/* The layout the fast paths rely on. */
_Static_assert(offsetof(struct sim_ctx, q) == 0, "sim_write finds the update list at the start of the context");
_Static_assert(offsetof(sim_signal, changes) + sizeof(uint64_t) <= 64, "a signal's hot fields share one cache line");
_Static_assert(offsetof(sim__proc, op_hi) + sizeof(int64_t) <= 64, "the evaluate loop's first reads share one cache line");
_Static_assert(sizeof(((sim_signal *)0)->noted) >= 2 && sizeof(((sim_signal *)0)->queued) >= 2,
               "flags the kernel writes are not char (aliasing)");
_Static_assert(sizeof(((sim_signal *)0)->noted) == sizeof(uint16_t), "epochs of the changed list run up to UINT16_MAX");

/* ---------------------------------------------------------------- memory */

void *sim_alloc(sim_ctx *c, size_t n)
{
    /* Each allocation carries a link so sim_free can release them all;
     * the header is padded to max_align_t so the payload stays aligned. */
    size_t hdr = (sizeof(struct sim_chunk) + _Alignof(max_align_t) - 1)
                 / _Alignof(max_align_t) * _Alignof(max_align_t);
    struct sim_chunk *ch = calloc(1, hdr + n);
    if (!ch) { fputs("shadesim: out of memory\n", stderr); exit(3); }
    ch->next = c->mem;
    c->mem = ch;
    return (char *)ch + hdr;
}

char *sim_strdup(sim_ctx *c, const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = sim_alloc(c, n);
    memcpy(d, s, n);
    return d;
}

static void *grow(void *p, uint32_t *cap, size_t elem, uint32_t need)
{
    if (need <= *cap) return p;
    uint32_t n = *cap ? *cap : 16;
    while (n < need) n *= 2;
    void *q = realloc(p, (size_t)n * elem);
    if (!q) { fputs("shadesim: out of memory\n", stderr); exit(3); }
    *cap = n;
    return q;
}

/* ------------------------------------------------------------- elaboration */

sim_ctx *sim_new(void)
{
    sim_ctx *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->rnd = SIM_RND_TRUNC;
    c->ovf = SIM_OVF_WRAP;
    c->max_deltas = 1000;
    c->epoch = 1;
    c->gen = 1;
    c->root.name = "top";
    return c;
}

static void free_fanouts(sim_ctx *c);

void sim_free(sim_ctx *c)
{
    if (!c) return;
    free_fanouts(c);
    while (c->mem) { struct sim_chunk *n = c->mem->next; free(c->mem); c->mem = n; }
    free(c->sigs); free(c->procs); free(c->q.upd); free(c->run); free(c->run2);
    free(c->chg); free(c->ovfq); free(c->heap); free(c->obs);
    free(c);
}

void sim_set_quant(sim_ctx *c, sim_round r, sim_ovf o) { c->rnd = r; c->ovf = o; }
sim_round sim_get_round(const sim_ctx *c) { return c->rnd; }
sim_ovf sim_get_ovf(const sim_ctx *c) { return c->ovf; }
void sim_set_max_deltas(sim_ctx *c, uint32_t n) { c->max_deltas = n ? n : 1; }
sim_scope *sim_root(sim_ctx *c) { return &c->root; }
sim_time sim_now(const sim_ctx *c) { return c->now; }
const sim_stats *sim_get_stats(const sim_ctx *c) { return &c->stats; }
const char *sim_error(const sim_ctx *c) { return c->err; }
void sim_stop(sim_ctx *c) { c->stop = 1; }

void sim__elab_error(sim_ctx *c, const char *fmt, ...)
{
    if (c->elab_err) return;   /* the first is the one to fix */
    c->elab_err = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->err, sizeof c->err, fmt, ap);
    va_end(ap);
}
uint32_t sim_signal_count(const sim_ctx *c) { return c->nsig; }
sim_signal *sim_signal_at(const sim_ctx *c, uint32_t i) { return i < c->nsig ? c->sigs[i] : NULL; }

sim_scope *sim_scope_new(sim_ctx *c, sim_scope *parent, const char *name)
{
    sim_scope *s = sim_alloc(c, sizeof *s);
    s->name = sim_strdup(c, name);
    s->parent = parent ? parent : &c->root;
    /* Append so that children keep creation order in the VCD. */
    sim_scope **pp = &s->parent->first_child;
    while (*pp) pp = &(*pp)->next_sibling;
    *pp = s;
    return s;
}

/* Arena memory starting on a 64-byte boundary (a signal's hot fields then
 * share one cache line). */
static void *alloc_line(sim_ctx *c, size_t n)
{
    char *p = sim_alloc(c, n + 63);
    return p + ((64 - (uintptr_t)p % 64) % 64);
}

sim_signal *sim_signal_new(sim_ctx *c, sim_scope *sc, const char *name,
                           sim_fmt fmt, sim_kind kind)
{
    sim_signal *s = alloc_line(c, sizeof *s);
    s->ctx = c;
    s->fmt = fmt;
    s->raw_min = sim_fmt_raw_min(fmt);
    s->raw_max = sim_fmt_raw_max(fmt);
    s->kind = (uint8_t)kind;
    s->name = sim_strdup(c, name);
    s->scope = sc ? sc : &c->root;
    if (s->scope->last_sig) s->scope->last_sig->next_in_scope = s;
    else s->scope->first_sig = s;
    s->scope->last_sig = s;
    s->index = c->nsig;
    /* The update, changed and overflow lists hold every signal at most
     * once. */
    uint32_t cap = c->capsig;
    c->sigs = grow(c->sigs, &c->capsig, sizeof *c->sigs, c->nsig + 1);
    if (c->capsig != cap) {
        c->q.upd = realloc(c->q.upd, (size_t)c->capsig * sizeof *c->q.upd);
        c->chg = realloc(c->chg, (size_t)c->capsig * sizeof *c->chg);
        c->ovfq = realloc(c->ovfq, (size_t)c->capsig * sizeof *c->ovfq);
        if (!c->q.upd || !c->chg || !c->ovfq) { fputs("shadesim: out of memory\n", stderr); exit(3); }
        c->chg_on = c->track ? c->chg : NULL;
    }
    c->sigs[c->nsig++] = s;
    return s;
}

sim_signal *sim_bit_new(sim_ctx *c, sim_scope *sc, const char *name, sim_kind kind)
{
    sim_fmt f = { .is_signed = 0, .ibits = 1, .fbits = 0, .width = 1 };   /* u1.0 */
    return sim_signal_new(c, sc, name, f, kind);
}

sim_proc *sim_proc_new(sim_ctx *c, const char *name, sim_proc_fn fn, void *data)
{
    sim__proc *p = alloc_line(c, sizeof *p);
    p->fn = fn;
    p->pub.data = data;
    p->pub.ctx = c;
    p->name = sim_strdup(c, name);
    uint32_t cap = c->capproc;
    c->procs = grow(c->procs, &c->capproc, sizeof *c->procs, c->nproc + 1);
    if (c->capproc != cap) {
        c->run = realloc(c->run, (size_t)c->capproc * sizeof *c->run);
        c->run2 = realloc(c->run2, (size_t)c->capproc * sizeof *c->run2);
        if (!c->run || !c->run2) { fputs("shadesim: out of memory\n", stderr); exit(3); }
    }
    c->procs[c->nproc++] = p;
    return &p->pub;
}

uint32_t sim_proc_count(const sim_ctx *c) { return c->nproc; }
sim_proc *sim_proc_at(const sim_ctx *c, uint32_t i) { return i < c->nproc ? &c->procs[i]->pub : NULL; }
const char *sim_proc_name(const sim_proc *p) { return sim__proc_of(p)->name; }
uint64_t sim_proc_runs(const sim_proc *p) { return sim__proc_of(p)->runs; }

void sim_sensitive(sim_proc *pub, sim_signal *s, sim_edge e)
{
    sim__proc *p = sim__proc_of(pub);
    s->fan = grow(s->fan, &s->capfan, sizeof *s->fan, s->nfan + 1);
    s->fan[s->nfan].proc = pub;
    s->fan[s->nfan].edge = (uint8_t)e;
    s->nfan++;
    /* The wake lists split fan by the value a change goes to, each in
     * registration order (which fixes the order of the next delta's run
     * list, hence of writes, hence of a VCD's lines). */
    for (int v = 0; v < 2; v++) {
        if (e != SIM_EDGE_ANY && (e == SIM_EDGE_POS) != (v != 0)) continue;
        s->wake[v] = grow(s->wake[v], &s->capwake[v], sizeof *s->wake[v], s->nwake[v] + 1);
        s->wake[v][s->nwake[v]++] = p;
    }
}

/* Fanout arrays grow with realloc, so they are not arena memory: sim_free
 * releases them through the signal list. */
static void free_fanouts(sim_ctx *c)
{
    for (uint32_t i = 0; i < c->nsig; i++) {
        sim_signal *s = c->sigs[i];
        free(s->fan); free(s->wake[0]); free(s->wake[1]);
        s->fan = NULL; s->wake[0] = s->wake[1] = NULL;
    }
}

const char *sim_signal_path(const sim_signal *s, char *buf, size_t len)
{
    /* Collect scope names leaf to root, then print root first. */
    const char *parts[64];
    int n = 0;
    parts[n++] = s->name;
    for (const sim_scope *sc = s->scope; sc && n < 64; sc = sc->parent) parts[n++] = sc->name;
    size_t off = 0;
    buf[0] = 0;
    for (int i = n - 1; i >= 0 && off < len; i--) {
        int k = snprintf(buf + off, len - off, "%s%s", parts[i], i ? "." : "");
        if (k < 0) break;
        off += (size_t)k;
    }
    return buf;
}

sim_signal *sim_find(const sim_ctx *c, const sim_scope *sc, const char *path)
{
    const sim_scope *cur = sc ? sc : &c->root;
    const char *p = path;
    for (;;) {
        const char *dot = strchr(p, '.');
        size_t n = dot ? (size_t)(dot - p) : strlen(p);
        if (!dot) {
            for (sim_signal *s = cur->first_sig; s; s = s->next_in_scope)
                if (strlen(s->name) == n && !strncmp(s->name, p, n)) return s;
            return NULL;
        }
        const sim_scope *ch = cur->first_child;
        while (ch && !(strlen(ch->name) == n && !strncmp(ch->name, p, n))) ch = ch->next_sibling;
        if (!ch) return NULL;
        cur = ch;
        p = dot + 1;
    }
}

double sim_scope_area(const sim_scope *sc)
{
    double a = 0;
    for (const sim_signal *s = sc->first_sig; s; s = s->next_in_scope) a += s->area_ge;
    for (const sim_scope *ch = sc->first_child; ch; ch = ch->next_sibling) a += sim_scope_area(ch);
    return a;
}

/* ------------------------------------------------------------------ timers */

static int timer_before(const sim_timer *a, const sim_timer *b)
{
    return a->at < b->at || (a->at == b->at && a->seq < b->seq);
}

static void timer_push(sim_ctx *c, sim_time at, void (*fn)(sim_ctx *, void *), void *data)
{
    c->heap = grow(c->heap, &c->capheap, sizeof *c->heap, c->nheap + 1);
    uint32_t i = c->nheap++;
    sim_timer t = { at, c->timer_seq++, fn, data };
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
static void timer_sift_root(sim_ctx *c, sim_timer t)
{
    uint32_t i = 0, n = c->nheap;
    for (;;) {
        uint32_t l = 2 * i + 1, r = l + 1, m = i;
        const sim_timer *best = &t;
        if (l < n && timer_before(&c->heap[l], best)) { m = l; best = &c->heap[l]; }
        if (r < n && timer_before(&c->heap[r], best)) { m = r; }
        if (m == i) break;
        c->heap[i] = c->heap[m];
        i = m;
    }
    c->heap[i] = t;
}

static sim_timer timer_pop(sim_ctx *c)
{
    sim_timer top = c->heap[0];
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

/* ------------------------------------------------------------- the loop */

void sim_force(sim_signal *s, int64_t v)
{
    /* Queued even when v is the current value, unlike sim_write: the time
     * step then has its delta cycle whatever was forced, so the counters
     * (deltas, proc_runs of the initialization) do not depend on the
     * values a testbench forces. The update finds no change and wakes
     * nobody. */
    s->nxt = v;
    if (!s->queued) {
        sim_ctx *c = s->ctx;
        s->queued = 1;
        c->q.upd[c->q.nupd++] = s;
    }
}

/* Name the signals still changing when the delta bound was hit: after the
 * settled part of the design has stopped, only the loop keeps toggling.
 * A loop changes one signal per delta, so watch a few more deltas. */
static uint32_t delta(sim_ctx *c);
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

/* A signal's value changed to v in the update phase: count it, note it for
 * observers that read sim_changed, and wake the processes waiting for such
 * a change. */
static inline void changed(sim_ctx *c, sim_signal *s, int64_t v)
{
    s->changes++;
    if (c->chg_on && s->noted != c->epoch) { s->noted = (uint16_t)c->epoch; c->chg_on[c->nchg++] = s; }
    uint32_t n = s->nwake[v != 0];
    if (n) {
        sim__proc **w = s->wake[v != 0], **run = c->run;
        uint32_t nrun = c->nrun;
        uint64_t gen = c->gen;
        for (uint32_t i = 0; i < n; i++) {
            sim__proc *p = w[i];
            if (p->listed != gen) { p->listed = gen; run[nrun++] = p; }
        }
        c->nrun = nrun;
    }
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
 * Returns the number of signals
 * that changed. Two switches, constant at every call site so that each
 * copy of the loop has only the tests it needs:
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
        sim__proc **w = s->wake[v != 0];
        uint32_t n = s->nwake[v != 0];
        for (uint32_t j = 0; j < n; j++) {
            sim__proc *q = w[j];
            if (q->listed != gen) { q->listed = gen; next[nn++] = q; }
        }
    }
    c->q.nupd = 0;
    if (track) c->nchg = nchg;
    c->stats.events += nchanged;
    *nnext = nn;
    return nchanged;
}

/* Delta cycles, evaluate then update, while anything is runnable (one
 * only, if once). *deltas counts them within the time step; returns 1 when
 * the bound was reached with work left (a loop), else 0. With once,
 * c->changed is the number of signals the update changed, and they are
 * at the front of the update list (for report_loop).
 *
 * The run lists stay in locals for the whole call (no process reads
 * them: processes only write signals, through c->q), and are handed back
 * to the context at the end. */
static int run_deltas(sim_ctx *c, uint32_t *deltas, int once)
{
    /* Evaluate dispatches on p->op with a computed goto (a GNU C
     * extension that gcc and clang both have): a table load and a jump,
     * without the bounds check and the reload of op a switch costs, and
     * each operation ends by starting the next process (the compiler may
     * merge those tails). The table is made from SIM__OP_LIST
     * (sim_internal.h). */
#define OP_LABEL(O, label, x) [SIM__OP_##O] = &&label,
    static const void *const op_label[] = { SIM__OP_LIST(OP_LABEL) };
#undef OP_LABEL
    _Static_assert(sizeof op_label / sizeof *op_label == SIM__OP__COUNT, "one label per SIM__OP_*");
    sim__proc **run = c->run, **next = c->run2;
    uint32_t nrun = c->nrun;
    uint64_t gen = c->gen;
    sim_signal **upd = c->q.upd;
    uint32_t nd = *deltas;
    int hit = 0;
    for (;;) {
        uint32_t nupd = c->q.nupd, i = 0;
        sim__proc *p;
        int64_t v;
        /* Start process i: count the run, jump to its operation. (It
         * may be woken again for the next delta: that list has the next
         * generation, which no process is listed under yet.) */
#define EVAL_AT_I() do { p = run[i]; p->runs++; goto *op_label[p->op]; } while (0)
#define EVAL_NEXT() do { if (++i < nrun) EVAL_AT_I(); goto evaluated; } while (0)
        /* y <= (x + radd) >> k (arithmetic: floor) when in range; out of
         * range, the general evaluation counts the overflow. */
#define QUANT(x) do { v = (int64_t)((uint64_t)(x) + (uint64_t)p->op_radd) >> p->op_k; \
                      if (__builtin_expect(v < p->op_lo || v > p->op_hi, 0)) goto general; } while (0)
        /* The same when radd and k are 0 (the *_X operations). */
#define RANGE(x) do { v = (int64_t)(x); \
                      if (__builtin_expect(v < p->op_lo || v > p->op_hi, 0)) goto general; } while (0)
        /* y <= v: queued unless it is y's value and nothing else is pending
         * (as sim_write). */
#define WRITE_NEXT() do { sim_signal *y = p->op_y; y->nxt = v; \
                          if (!y->queued && v != y->cur) { y->queued = 1; upd[nupd++] = y; } \
                          EVAL_NEXT(); } while (0)
        if (nrun) EVAL_AT_I();
        goto evaluated;
    general:
        /* Anything the kernel does not know inline, and a primitive whose
         * fast result is out of range. */
        c->q.nupd = nupd;
        p->fn(&p->pub);
        nupd = c->q.nupd;
        EVAL_NEXT();
    /* Operands' widths bound the exact result below 2^62 (sim_prim.c
     * checks); the arithmetic is done unsigned, so that even a raw forced
     * outside its format cannot overflow. */
    op_copy:
        QUANT(p->op_a->cur);
        WRITE_NEXT();
    op_add:
        QUANT((uint64_t)p->op_a->cur + (uint64_t)p->op_b->cur);
        WRITE_NEXT();
    op_sub:
        QUANT((uint64_t)p->op_a->cur - (uint64_t)p->op_b->cur);
        WRITE_NEXT();
    op_mul:
        QUANT((uint64_t)p->op_a->cur * (uint64_t)p->op_b->cur);
        WRITE_NEXT();
    op_mux: {
            uint64_t sel = (uint64_t)p->op_c->cur;
            if (sel >= p->op_n) { v = 0; WRITE_NEXT(); }
            QUANT(p->op_in[sel]->cur);
            WRITE_NEXT();
        }
    op_bk:
        if (!p->op_c->cur) { v = 0; WRITE_NEXT(); }
        QUANT(p->op_a->cur);
        WRITE_NEXT();
    op_copy_x:
        RANGE(p->op_a->cur);
        WRITE_NEXT();
    op_add_x:
        RANGE((uint64_t)p->op_a->cur + (uint64_t)p->op_b->cur);
        WRITE_NEXT();
    op_sub_x:
        RANGE((uint64_t)p->op_a->cur - (uint64_t)p->op_b->cur);
        WRITE_NEXT();
    op_mux_x: {
            uint64_t sel = (uint64_t)p->op_c->cur;
            if (sel >= p->op_n) { v = 0; WRITE_NEXT(); }
            RANGE(p->op_in[sel]->cur);
            WRITE_NEXT();
        }
    op_bk_x:
        if (!p->op_c->cur) { v = 0; WRITE_NEXT(); }
        RANGE(p->op_a->cur);
        WRITE_NEXT();
    op_logic_s:
        v = (int64_t)((uint64_t)logic_call(p) << p->op_k) >> p->op_k;
        WRITE_NEXT();
    op_logic_u:
        v = (int64_t)((uint64_t)logic_call(p) & (uint64_t)p->op_radd);
        WRITE_NEXT();
    op_lut1: {
            uint64_t ix = (uint64_t)p->op_a->cur - (uint64_t)p->op_lo;
            if (__builtin_expect(ix > (uint64_t)p->op_hi, 0)) goto general;
            v = p->op_tab[ix];
            WRITE_NEXT();
        }
    op_lutn: {
            uint64_t ix = 0;
            for (uint32_t j = 0; j < p->op_n; j++) {
                const sim__lut_in *t = &p->op_tin[j];
                uint64_t d = (uint64_t)p->op_in[j]->cur - (uint64_t)t->lo;
                if (__builtin_expect(d > t->span, 0)) goto general;
                ix |= d << t->sh;
            }
            v = p->op_tab[ix];
            WRITE_NEXT();
        }
#undef EVAL_AT_I
#undef EVAL_NEXT
#undef QUANT
#undef RANGE
#undef WRITE_NEXT
    evaluated:
        c->stats.proc_runs += nrun;
        nd++;
        uint32_t nnext = 0, changed;
        gen++;
        if (__builtin_expect(once, 0)) changed = update(c, upd, nupd, next, &nnext, gen, c->chg_on != NULL, 1);
        else if (c->chg_on) changed = update(c, upd, nupd, next, &nnext, gen, 1, 0);
        else changed = update(c, upd, nupd, next, &nnext, gen, 0, 0);
        sim__proc **t = run; run = next; next = t;
        nrun = nnext;
        /* Counted after the update (nothing runs in between, so nobody
         * sees the difference): next to proc_runs's, gcc pairs the two
         * additions in a vector register, which costs more. */
        c->stats.deltas++;
        if (once) { c->changed = changed; break; }
        /* The update leaves no write pending, so what is left is the
         * processes it woke. */
        if (!nrun) break;
        if (nd >= c->max_deltas) { hit = 1; break; }
    }
    c->run = run; c->nrun = nrun;
    c->run2 = next;
    c->gen = gen;
    *deltas = nd;
    return hit;
}

/* One delta cycle (for the loop report). */
static uint32_t delta(sim_ctx *c)
{
    uint32_t d = 0;
    run_deltas(c, &d, 1);
    return c->changed;
}

/* ---------------------------------------------------------------- observers */

int sim_observe(sim_ctx *c, sim_observer_fn fn, void *data, unsigned flags)
{
    if (c->nobs == c->capobs) {
        uint32_t cap = c->capobs ? 2 * c->capobs : 4;
        sim_obs *o = realloc(c->obs, (size_t)cap * sizeof *o);
        if (!o) return -1;
        c->obs = o;
        c->capobs = cap;
    }
    c->obs[c->nobs++] = (sim_obs){ fn, data, flags };
    if (flags & SIM_OBS_CHANGES) c->track++;
    c->chg_on = c->track ? c->chg : NULL;
    return 0;
}

/* Start a new changed list. A signal is in the list when its noted field
 * holds the current epoch, so a new epoch empties the list without
 * touching the signals; when the 16-bit field would wrap, every signal's
 * is reset once, so an old epoch never matches a new one. */
static void clear_changed(sim_ctx *c)
{
    c->nchg = 0;
    if (++c->epoch > UINT16_MAX) {
        for (uint32_t i = 0; i < c->nsig; i++) c->sigs[i]->noted = 0;
        c->epoch = 1;
    }
}

void sim_unobserve(sim_ctx *c, sim_observer_fn fn, void *data)
{
    for (uint32_t i = 0; i < c->nobs; i++) {
        if (c->obs[i].fn != fn || c->obs[i].data != data) continue;
        if ((c->obs[i].flags & SIM_OBS_CHANGES) && !--c->track) clear_changed(c);
        c->chg_on = c->track ? c->chg : NULL;
        memmove(&c->obs[i], &c->obs[i + 1], (size_t)(c->nobs - i - 1) * sizeof *c->obs);
        c->nobs--;
        return;
    }
}

sim_signal *const *sim_changed(const sim_ctx *c, uint32_t *n)
{
    *n = c->track ? c->nchg : 0;
    return c->track ? c->chg : NULL;
}

/* End of a time step: every observer, then a fresh changed list. */
static void notify(sim_ctx *c)
{
    for (uint32_t i = 0; i < c->nobs; i++) c->obs[i].fn(c, c->now, c->obs[i].data);
    if (c->chg_on) clear_changed(c);
}

/* A clock's tick done in place: the clock toggles and its update, the
 * time step's first delta cycle, wakes its processes; the timer, heap[0],
 * becomes the next tick (the caller restores the heap's order if other
 * timers share it). Counts exactly what clock_tick and the general update
 * count. */
static inline void tick_in_place(sim_ctx *c)
{
    sim_timer *t = &c->heap[0];
    sim_clockgen *g = t->data;
    sim_signal *clk = g->clk;
    int64_t v = !clk->cur;
    t->at = c->now + g->half;
    t->seq = c->timer_seq++;
    c->stats.clocks += (uint64_t)v;
    clk->nxt = clk->cur = v;
    c->stats.deltas++;
    c->stats.events++;
    changed(c, clk, v);
}

/* The start of a time step whose only business is one clock edge (the
 * earliest timer is a clock tick, no other timer is due at the same time
 * and nothing is pending): the tick without the timer and update
 * machinery. Returns 0 if the step is not of this kind. */
static int clock_step(sim_ctx *c)
{
    sim_timer *t = &c->heap[0];
    if (t->fn != clock_tick || c->nrun || c->q.nupd) return 0;
    if ((c->nheap > 1 && c->heap[1].at <= c->now) || (c->nheap > 2 && c->heap[2].at <= c->now)) return 0;
    tick_in_place(c);
    if (c->nheap > 1) timer_sift_root(c, *t);
    return 1;
}

/* End of a time step: count the overflows the settled values carry. */
static void settle_overflows(sim_ctx *c);

/* Whole time steps while each is one clock edge and nothing else (the
 * only timer is a clock; nothing pending), the common testbench: the
 * tick, the deltas, the end of the step and the advance to the next edge,
 * without the general loop's tests for timers and writes that cannot be
 * there. Entered when one_clock_due holds. Returns SIM_CLK_NEXT when the
 * next step needs the general loop (time advanced to it), SIM_CLK_END
 * when the run is over, SIM_CLK_LOOP at a combinational loop. */
enum { SIM_CLK_NEXT, SIM_CLK_END, SIM_CLK_LOOP };
static inline int one_clock_due(const sim_ctx *c)
{
    return c->nheap == 1 && c->heap[0].fn == clock_tick && c->heap[0].at <= c->now && !c->nrun && !c->q.nupd;
}
static int clock_steps(sim_ctx *c, sim_time until)
{
    do {
        tick_in_place(c);
        uint32_t deltas = 1;   /* the tick's update; it queued no write */
        if (c->nrun && (deltas >= c->max_deltas || run_deltas(c, &deltas, 0))) return SIM_CLK_LOOP;
        if (c->novfq) settle_overflows(c);
        if (c->nobs) notify(c);
        if (c->stop || !c->nheap || c->heap[0].at > until) return SIM_CLK_END;
        c->now = c->heap[0].at;
        c->stats.time_steps++;
    } while (one_clock_due(c));
    return SIM_CLK_NEXT;
}

void sim__overflow(sim_signal *s, int64_t raw)
{
    sim_ctx *c = s->ctx;
    s->ovf_raw = raw;
    s->ovf_run = s->driver ? sim__proc_of(s->driver)->runs : 0;
    if (!s->ovf_pending) { s->ovf_pending = 1; c->ovfq[c->novfq++] = s; }
}

void sim__uses_stale(sim_ctx *c) { c->uses_nsig = 0; }

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

void sim_signal_output(sim_signal *s) { s->is_output = 1; }

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

sim_status sim_run(sim_ctx *c, sim_time until)
{
    if (c->elab_err) return SIM_ERR_ELAB;
    if (!c->started) {
        /* Initialization: every process runs once, as in SystemC, so that
         * combinational outputs agree with their inputs before time moves. */
        c->started = 1;
        for (uint32_t i = 0; i < c->nproc; i++) {
            sim__proc *p = c->procs[i];
            if (p->op == SIM__OP_LOGIC_S || p->op == SIM__OP_LOGIC_U) tabulate(c, p);
            if (p->listed != c->gen && !p->pub.no_init) { p->listed = c->gen; c->run[c->nrun++] = p; }
        }
    }
    c->stop = 0;
    /* A time step is counted when it starts at a new time: here, unless
     * this run resumes the step the last one ended in, and below at each
     * advance of time. */
    c->stats.time_steps += !(c->stepped && c->now == c->step_time);
    c->stepped = 1;
    for (;;) {
        if (one_clock_due(c)) {
            int k = clock_steps(c, until);
            if (k == SIM_CLK_NEXT) continue;
            if (k == SIM_CLK_END) break;
            goto loop;
        }
        uint32_t deltas = 0;
        if (c->nheap && c->heap[0].at <= c->now && clock_step(c)) {
            deltas = 1;
            if (deltas >= c->max_deltas && c->nrun) goto loop;
        }
        while (c->nheap && c->heap[0].at <= c->now) {
            sim_timer t = timer_pop(c);
            t.fn(c, t.data);
        }
        if ((c->nrun || c->q.nupd) && run_deltas(c, &deltas, 0)) goto loop;
        if (c->novfq) settle_overflows(c);
        if (c->nobs) notify(c);
        if (c->stop || !c->nheap || c->heap[0].at > until) break;
        c->now = c->heap[0].at;
        c->stats.time_steps++;
    }
    c->step_time = c->now;
    if (!c->stop && until > c->now && until != (sim_time)-1) c->now = until;
    return SIM_OK;
loop:
    c->step_time = c->now;
    report_loop(c);
    if (c->novfq) settle_overflows(c);
    if (c->nobs) notify(c);
    return SIM_ERR_LOOP;
}
