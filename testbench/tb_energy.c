/* tb_energy.c - toggles and energy of a run (tb_energy.h). */
#include "testbench/tb_energy.h"
#include "sim/sim_energy.h"

static int in_scope(const sim_signal *s, const sim_scope *sc)
{
    for (const sim_scope *p = s->scope; p; p = p->parent) if (p == sc) return 1;
    return 0;
}

double tb_energy_pj(const sim_ctx *c, const sim_scope *sc, tb_energy_count tog, void *data, uint64_t clocks,
                    uint64_t *toggles)
{
    double fj = (double)clocks * sim_energy_clock_fj(c);
    uint64_t n = 0;
    for (uint32_t i = 0, ns = sim_signal_count(c); i < ns; i++) {
        const sim_signal *s = sim_signal_at(c, i);
        if (s->kind == SIM_KIND_CLOCK || !in_scope(s, sc)) continue;
        uint64_t k = tog(s, data);
        n += k;
        fj += (double)k * sim_energy_toggle_fj(s);
    }
    if (toggles) *toggles = n;
    return fj * 1e-3;
}

void tb_energy_fill(tb_result *r, const tb_range *g, const sim_toggle *t, const sim_ctx *c, uint64_t clocks)
{
    tb_energy_fill_counts(r, g, NULL, t, c, clocks);
}

void tb_energy_fill_counts(tb_result *r, const tb_range *g, const uint64_t *count, const sim_toggle *t,
                           const sim_ctx *c, uint64_t clocks)
{
    double fj = (double)clocks * sim_energy_clock_fj(c);
    uint64_t n = 0;
    for (int i = 0; i < g->nsmp; i++) {
        uint64_t k = count ? count[i] : sim_toggle_count(t, g->smp[i]);
        if (r->sigs && i < r->nsigs) r->sigs[i].toggles = k;
        n += k;
        fj += (double)k * sim_energy_toggle_fj(g->smp[i]);
    }
    r->ppa.toggles = n;
    r->ppa.energy_pj_per_item = r->vectors ? fj * 1e-3 / (double)r->vectors : 0;
}
