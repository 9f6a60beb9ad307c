/* tb_span.h - the span interpolation units (units/unit_span.c) driven
 * with a stream of intervals of varying length, as a scene's spans give
 * them: the scene testbench hands over every interval of every span, in
 * order, and gets every pixel back, with the clocks, overflows and area of
 * the simulated hardware.
 *
 * An interval of n pixels (1 <= n <= L) is one item: node intensities
 * I(0), I(1), I(1/2) and I(1/4) (node set N1) or I(3/4) (N2) -- the linear
 * unit reads I(0), I(1) only, the quadratic I(0), I(1), I(1/2) -- its
 * divisor dv (pixel k has t = k/dv; the scene uses dv = L for a full
 * interval and n - 1 for a span's last one, so that its t = 1 node is the
 * span's last pixel) and, for the adaptive unit, its degree (2 or 3).
 */
#ifndef TB_SPAN_H
#define TB_SPAN_H
#include "units/unit.h"

typedef struct tb_span_item {
    double node[4];     /* exact (double) node intensities, quantized by the testbench */
    int    n;           /* pixels, 1..L */
    int    dv;          /* divisor: t = k/dv, 1..L */
    int    deg;         /* span23 only: 2 or 3 */
} tb_span_item;

typedef struct tb_span_stats {
    uint64_t clocks;         /* clock cycles from the first accept to the last pixel */
    uint64_t pixels;
    uint64_t items, items_deg2;
    uint64_t overflows;      /* input quantization + every signal of the unit */
    double   area_ge;
    /* Switching activity, only when asked for (tb_span_run_energy, or a
     * lane's `energy`; else 0): the unit's settled bit toggles and its
     * energy over the whole run, every clock from the first
     * (docs/timing.md). */
    uint64_t toggles;
    double   energy_pj;
} tb_span_stats;

/* Simulate items[0..nitems-1] back to back through unit u (one of the
 * span units) at formats f; pix[] receives sum(items[i].n) pixel values
 * (the output's real value), in order. vcd_path: NULL or a VCD to write.
 * TB_OK, TB_FAIL or TB_BADINPUT (tb.h) with a message. */
int tb_span_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                const tb_span_item *items, size_t nitems, double *pix,
                tb_span_stats *st, const char *vcd_path, char *err, size_t errlen);
/* tb_span_run that also counts st->toggles and st->energy_pj. */
int tb_span_run_energy(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                       const tb_span_item *items, size_t nitems, double *pix,
                       tb_span_stats *st, const char *vcd_path, char *err, size_t errlen);
/* Batch mode: several independent streams (lanes) at once, each lane's
 * pixels, figures and error exactly what tb_span_run gives for its stream
 * alone. The lanes run side by side through one levelized evaluation of
 * the unit (sim/sim_batch.h); a lane that evaluation cannot reproduce
 * exactly (a quantization overflowed, or the unit stopped answering) is
 * simulated again by tb_span_run, as is every lane when batch is 0 or the
 * unit is not one the batch mode accepts. */
typedef struct tb_span_lane {
    const tb_span_item *items;   /* in: the stream */
    size_t nitems;
    double *pix;                 /* out: sum(items[i].n) pixels */
    tb_span_stats st;            /* out */
    int rc;                      /* out: TB_OK, TB_FAIL or TB_BADINPUT */
    int batched;                 /* out: 1 if the batch gave this lane */
    int energy;                  /* in: count st.toggles and st.energy_pj (the batch counts
                                  * when any lane asks; off, it pays nothing) */
    char err[300];               /* out: rc's message */
    const double *ref;           /* in: NULL, or sum(items[i].n) values the pixels are compared
                                  * with (tb_span_run_lanes_budget) */
    int stopped;                 /* out: 1 if the budget stopped the lane (rc TB_FAIL) */
} tb_span_lane;
void tb_span_run_lanes(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                       tb_span_lane *lanes, size_t nlanes, int batch);
/* The same, stopping as soon as the squared differences of the pixels from
 * their lanes' ref, summed over every lane of the batch, pass max_se: the
 * lanes still running then fail (rc TB_FAIL, stopped 1), as a caller that
 * only needs to know that the total error is over a budget wants; the
 * lanes that finished before are exact. A lane simulated outside the batch
 * (batch 0, an overflow) is not stopped. */
void tb_span_run_lanes_budget(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f,
                              tb_span_lane *lanes, size_t nlanes, int batch, double max_se);
#endif
