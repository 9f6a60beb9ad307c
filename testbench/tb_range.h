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

/* A signal that can change and its range so far, lo <= v <= lo + span,
 * span an unsigned width: one subtraction and one unsigned compare tell
 * whether a value is inside (tb_range_widen moves the ends when not). */
typedef struct tb_range_live {
    const sim_signal *sig;
    int64_t  lo;
    uint64_t span;
} tb_range_live;

typedef struct tb_range {
    sim_signal **smp;           /* every logged signal */
    int64_t     *mn, *mx;       /* their min and max (after tb_range_finish) */
    int          nsmp;
    int         *live, nlive;   /* the entries that can change (not constants) */
    tb_range_live *lv;          /* smp[live[j]] and its range, packed for the per-clock loop */
    int          sampled;       /* tb_range_sample has run (the ranges hold values) */
} tb_range;

/* The signals of scope sc (and below) but the clock. 0, or -1 (memory). */
int  tb_range_init(tb_range *g, sim_ctx *c, const sim_scope *sc, const sim_signal *clk);
/* Widen l's range to take the value lo + d (d as the sampling loop has
 * it, v - lo modulo 2^64); first: it holds nothing yet. */
void tb_range_widen(tb_range_live *l, uint64_t d, int first);
/* At each rising edge (the monitor calls it). A value inside its range so
 * far, the common case, costs two loads, a subtraction and a compare;
 * four signals a turn, as the loop's own count would cost as much. */
#define TB_RANGE_TAKE(l, first) do { \
        uint64_t d_ = (uint64_t)(l)->sig->cur - (uint64_t)(l)->lo; \
        if (d_ > (l)->span) tb_range_widen((l), d_, (first)); \
    } while (0)
static inline void tb_range_sample(tb_range *g)
{
    tb_range_live *l = g->lv, *end = l + g->nlive, *end4 = l + (g->nlive & ~3);
    int first = !g->sampled;
    for (; l < end4; l += 4) {
        TB_RANGE_TAKE(l, first);
        TB_RANGE_TAKE(l + 1, first);
        TB_RANGE_TAKE(l + 2, first);
        TB_RANGE_TAKE(l + 3, first);
    }
    for (; l < end; l++) TB_RANGE_TAKE(l, first);
    g->sampled = 1;
}
/* r->sigs: each signal's name below sc, format, kind, overflows (an input
 * adds its quantization's, in_ovf[] in io's input order) and range. */
void tb_range_finish(tb_range *g, const sim_scope *sc, const unit_io *io, const uint64_t *in_ovf,
                     tb_result *r);
void tb_range_free(tb_range *g);

/* s's dotted path below scope sc ("y", "div3_a.t1"), as the table names
 * it (and tb_timing.c the critical path's signals); 1 if s is in sc or
 * below it. */
void tb_range_name(const sim_signal *s, const sim_scope *sc, char *buf, size_t len);
int  tb_range_in_scope(const sim_signal *s, const sim_scope *sc);

/* Overflows counted on every signal of sc and below (of values used). */
uint64_t tb_scope_overflows(const sim_scope *sc);
/* The overflows on discarded values there (sim_prim.h, "used values"). */
uint64_t tb_scope_ovf_discarded(const sim_scope *sc);
#endif
