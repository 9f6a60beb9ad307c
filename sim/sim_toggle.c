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
    for (uint32_t i = 0; i < n; i++) {
        const sim_signal *s = d[i];
        uint32_t k = s->index;
        if (k >= t->nsig || s->cur == last[k]) continue;
        count[k] += sim_toggle_popcount(((uint64_t)s->cur ^ (uint64_t)last[k]) & sim_toggle_mask(s));
        last[k] = s->cur;
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
    if (!t->last || !t->count || sim_observe(c, step, t, SIM_OBS_CHANGES)) {
        free(t->last); free(t->count); free(t);
        return NULL;
    }
    return t;
}

void sim_toggle_free(sim_toggle *t)
{
    if (!t) return;
    sim_unobserve(t->ctx, step, t);
    free(t->last);
    free(t->count);
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
