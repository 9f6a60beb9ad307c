/* sim_kernel.c - the design the kernel runs: memory, signals, processes,
 * scopes, sensitivity, observers, and the entry points a process or a
 * testbench calls (sim_force, sim__overflow). The scheduler that runs it
 * (timers, time steps, the delta-cycle loop and its fast paths) is
 * sim_sched.c; the context both share is in sim_internal.h.
 */
#include "sim/sim_internal.h"
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

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
    size_t hdr = (sizeof(struct sim__chunk) + _Alignof(max_align_t) - 1)
                 / _Alignof(max_align_t) * _Alignof(max_align_t);
    struct sim__chunk *ch = calloc(1, hdr + n);
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

void *sim__grow(void *p, uint32_t *cap, size_t elem, uint32_t need)
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
    while (c->mem) { struct sim__chunk *n = c->mem->next; free(c->mem); c->mem = n; }
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
    c->sigs = sim__grow(c->sigs, &c->capsig, sizeof *c->sigs, c->nsig + 1);
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
    c->procs = sim__grow(c->procs, &c->capproc, sizeof *c->procs, c->nproc + 1);
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
    s->fan = sim__grow(s->fan, &s->capfan, sizeof *s->fan, s->nfan + 1);
    s->fan[s->nfan].proc = pub;
    s->fan[s->nfan].edge = (uint8_t)e;
    s->nfan++;
    /* The wake lists split fan by the value a change goes to, each in
     * registration order (which fixes the order of the next delta's run
     * list, hence of writes, hence of a VCD's lines). */
    for (int v = 0; v < 2; v++) {
        if (e != SIM_EDGE_ANY && (e == SIM_EDGE_POS) != (v != 0)) continue;
        s->wake[v] = sim__grow(s->wake[v], &s->capwake[v], sizeof *s->wake[v], s->nwake[v] + 1);
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

int sim_signal_path_below(const sim_signal *s, const sim_scope *top, char *buf, size_t len)
{
    /* Collect scope names leaf to root, then print root first. */
    const char *parts[64];
    int n = 0;
    parts[n++] = s->name;
    const sim_scope *sc = s->scope;
    for (; sc && sc != top && n < 64; sc = sc->parent) parts[n++] = sc->name;
    if (sc != top) return -1;
    size_t off = 0;
    buf[0] = 0;
    for (int i = n - 1; i >= 0; i--) {
        int k = snprintf(buf + off, len - off, "%s%s", parts[i], i ? "." : "");
        if (k < 0 || (size_t)k >= len - off) return -1;    /* cut short (buf ends there) */
        off += (size_t)k;
    }
    return 0;
}

const char *sim_signal_path(const sim_signal *s, char *buf, size_t len)
{
    sim_signal_path_below(s, NULL, buf, len);
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

/* sim_scope_area: sim_area_net.c (it needs the timing's pin counts) */

/* ---------------------------------------------------------------- writes */

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

void sim__overflow(sim_signal *s, int64_t raw)
{
    sim_ctx *c = s->ctx;
    s->ovf_raw = raw;
    s->ovf_run = s->driver ? sim__proc_of(s->driver)->runs : 0;
    if (!s->ovf_pending) { s->ovf_pending = 1; c->ovfq[c->novfq++] = s; }
}

void sim__uses_stale(sim_ctx *c) { c->uses_nsig = 0; }

void sim_signal_output(sim_signal *s) { s->is_output = 1; }

/* ---------------------------------------------------------------- observers */

int sim_observe(sim_ctx *c, sim_observer_fn fn, void *data, unsigned flags)
{
    if (c->nobs == c->capobs) {
        uint32_t cap = c->capobs ? 2 * c->capobs : 4;
        sim__obs *o = realloc(c->obs, (size_t)cap * sizeof *o);
        if (!o) return -1;
        c->obs = o;
        c->capobs = cap;
    }
    c->obs[c->nobs++] = (sim__obs){ fn, data, flags };
    if (flags & SIM_OBS_CHANGES) c->track++;
    c->chg_on = c->track ? c->chg : NULL;
    return 0;
}

/* Start a new changed list. A signal is in the list when its noted field
 * holds the current epoch, so a new epoch empties the list without
 * touching the signals; when the 16-bit field would wrap, every signal's
 * is reset once, so an old epoch never matches a new one. */
void sim__clear_changed(sim_ctx *c)
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
        if ((c->obs[i].flags & SIM_OBS_CHANGES) && !--c->track) sim__clear_changed(c);
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
