/* tb_energy.h - a run's switching activity and energy per item
 * (tb_ppa.toggles, energy_pj_per_item; docs/timing.md), from the kernel's
 * toggle counts or the batch's: every signal of the unit's scope counted
 * (tb_range's signals, the clock left out), each toggle weighted by the
 * energy of its driving element (sim/sim_energy.h), plus the clock energy
 * of the design's flip-flops over the run's clock cycles. */
#ifndef TB_ENERGY_H
#define TB_ENERGY_H
#include "testbench/tb_range.h"
#include "sim/sim_toggle.h"

/* r->sigs[i].toggles (r->sigs in g's order, tb_range_finish), r->ppa.toggles
 * and r->ppa.energy_pj_per_item over r->vectors items and `clocks` cycles. */
void tb_energy_fill(tb_result *r, const tb_range *g, const sim_toggle *t, const sim_ctx *c, uint64_t clocks);
/* The same from counts given per signal of g (count[i] for g->smp[i]),
 * as the batch's lanes give them (tb_lanes.h); count NULL: t's. */
void tb_energy_fill_counts(tb_result *r, const tb_range *g, const uint64_t *count, const sim_toggle *t,
                           const sim_ctx *c, uint64_t clocks);
/* Energy of `clocks` cycles of c's design in which signal i of scope sc
 * (and below) toggled tog(i) times, pJ; the toggles summed into *toggles.
 * tog reads one lane of the batch's counts (or any count by signal). */
typedef uint64_t (*tb_energy_count)(const sim_signal *s, void *data);
double tb_energy_pj(const sim_ctx *c, const sim_scope *sc, tb_energy_count tog, void *data, uint64_t clocks,
                    uint64_t *toggles);
#endif
