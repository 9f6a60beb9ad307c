/* tb_range.h - range logging and the per-signal table of a run, shared by
 * the in-memory testbench (tb_run.c) and the streaming one (tb_stream.c).
 *
 * Every signal in the unit's scope is sampled at each rising edge (its
 * settled value of the cycle that ended: what a logic analyzer, or
 * MATLAB's range logging, records; glitches between deltas are not).
 * Constants are recorded once; the others are packed so that the
 * per-clock loop touches only what can change.
 */
#ifndef TB_RANGE_H
#define TB_RANGE_H
#include "testbench/tb.h"

typedef struct tb_range {
    sim_signal **smp;           /* every logged signal */
    int64_t     *mn, *mx;       /* their min and max (after tb_range_finish) */
    int          nsmp;
    int         *live, nlive;   /* the entries that can change (not constants) */
    sim_signal **lsig;          /* smp[live[j]], packed for the per-clock loop */
    int64_t     *lmm;           /* its min, max pairs */
} tb_range;

/* The signals of scope sc (and below) but the clock. 0, or -1 (memory). */
int  tb_range_init(tb_range *g, sim_ctx *c, const sim_scope *sc, const sim_signal *clk);
/* At each rising edge (the monitor calls it). */
static inline void tb_range_sample(tb_range *g)
{
    sim_signal *const *ls = g->lsig;
    int64_t *mm = g->lmm;
    for (int j = 0, n = g->nlive; j < n; j++, mm += 2) {
        int64_t v = ls[j]->cur;
        mm[0] = v < mm[0] ? v : mm[0];
        mm[1] = v > mm[1] ? v : mm[1];
    }
}
/* r->sigs: each signal's name below sc, format, kind, overflows (an input
 * adds its quantization's, in_ovf[] in io's input order) and range. */
void tb_range_finish(tb_range *g, const sim_scope *sc, const unit_io *io, const uint64_t *in_ovf,
                     tb_result *r);
void tb_range_free(tb_range *g);

/* Overflows counted on every signal of sc and below. */
uint64_t tb_scope_overflows(const sim_scope *sc);
#endif
