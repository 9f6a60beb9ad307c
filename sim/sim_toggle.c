/* sim_toggle.c - settled bit toggles per signal (sim_toggle.h).
 *
 * An observer at the end of every time step: for each signal the kernel
 * lists as changed in the step, the bits that differ from the value last
 * seen. This is sim_vcd.c's comparison (a value that changed and changed
 * back is no change), so a dump read back gives the same counts. */
#include "sim/sim_toggle.h"
#include <stdlib.h>

struct sim_toggle {
    sim_ctx  *ctx;
    uint32_t  nsig;         /* signals counted: those that existed at sim_toggle_new */
    int       started;      /* the first step's values are the baseline */
    int64_t  *last;         /* per signal: its value at the last step */
    uint64_t *count;        /* per signal: its toggles */
    uint64_t *mask;         /* per signal: its format's bits (sim_toggle_mask), read
                             * here rather than from the signal's cold fields */
};

static void step(sim_ctx *c, sim_time now, void *data)
{
    (void)now;
    sim_toggle *t = data;
    if (!t->started) {
        t->started = 1;
        for (uint32_t i = 0; i < t->nsig; i++) t->last[i] = sim_signal_at(c, i)->cur;
        return;
    }
    uint32_t n;
    sim_signal *const *d = sim_changed(c, &n);
    int64_t *last = t->last;
    uint64_t *count = t->count;
    const uint64_t *mask = t->mask;
    const uint32_t nsig = t->nsig;
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = d[i];
        uint32_t k = s->index;
        int64_t v = s->cur;
        if (k >= nsig || v == last[k]) continue;
        count[k] += sim_toggle_popcount(((uint64_t)v ^ (uint64_t)last[k]) & mask[k]);
        last[k] = v;
    }
}

sim_toggle *sim_toggle_new(sim_ctx *c)
{
    sim_toggle *t = calloc(1, sizeof *t);
    if (!t) return NULL;
    t->ctx = c;
    t->nsig = sim_signal_count(c);
    size_t n = t->nsig ? t->nsig : 1;
    t->last = calloc(n, sizeof *t->last);
    t->count = calloc(n, sizeof *t->count);
    t->mask = malloc(n * sizeof *t->mask);
    if (!t->last || !t->count || !t->mask || sim_observe(c, step, t, SIM_OBS_CHANGES)) {
        free(t->last); free(t->count); free(t->mask); free(t);
        return NULL;
    }
    for (uint32_t i = 0; i < t->nsig; i++) t->mask[i] = sim_toggle_mask(sim_signal_at(c, i));
    return t;
}

void sim_toggle_free(sim_toggle *t)
{
    if (!t) return;
    sim_unobserve(t->ctx, step, t);
    free(t->last);
    free(t->count);
    free(t->mask);
    free(t);
}

uint64_t sim_toggle_count(const sim_toggle *t, const sim_signal *s)
{
    return s->index < t->nsig ? t->count[s->index] : 0;
}

uint64_t sim_toggle_total(const sim_toggle *t)
{
    uint64_t n = 0;
    for (uint32_t i = 0; i < t->nsig; i++)
        if (sim_signal_at(t->ctx, i)->kind != SIM_KIND_CLOCK) n += t->count[i];
    return n;
}
