/* tb_batch.h - batch mode for any unit: several independent vector sets
 * (lanes) through one levelized evaluation of the unit (sim/sim_batch.h),
 * with tb_run's driver and monitor per lane.
 *
 * Each lane's output raws, beat clocks, clock count and overflow count are
 * what tb_run gives for that vector set alone (tests/test_batch.c checks
 * it for every unit), overflows counted as the kernel counts them
 * (sim_batch_overflows_on); a lane whose counts the batch cannot tell
 * is simulated again by the kernel. What the batch leaves out is what only
 * the kernel has: events, delta cycles, VCD, range logging.
 */
#ifndef TB_BATCH_H
#define TB_BATCH_H
#include "testbench/tb.h"

/* The unit is not one the batch mode can evaluate (a process that is not
 * a primitive, a combinational loop): err says why; use tb_run. */
enum { TB_UNSUPPORTED = 3 };

typedef struct tb_batch_lane {
    const vec_set *vs;       /* in: the lane's vectors */
    int64_t  *raw;           /* out: [item][beat][output] raws, malloc'd */
    uint64_t *beat_cycle;    /* out: [item][beat] clock of each beat, malloc'd */
    uint64_t  clocks;        /* out: clock edges simulated (tb_run's stats.clocks) */
    uint64_t  overflows;     /* out: the unit's own (constants and simulation) */
    uint64_t  in_overflows;  /* out: the inputs' quantization */
    int       batched;       /* out: 1 if the batch gave the lane, 0 the kernel */
    /* Switching activity (docs/timing.md), counted when `energy` is set in
     * any lane (off: the batch pays nothing for it): */
    int       energy;        /* in: count toggles and energy */
    uint64_t *sig_toggles;   /* out: per signal of the unit, in tb_run's r->sigs order, malloc'd */
    int       nsig;          /* out: entries of sig_toggles */
    uint64_t  toggles;       /* out: their sum (tb_run's ppa.toggles) */
    double    energy_pj_per_item;   /* out: tb_run's ppa.energy_pj_per_item */
} tb_batch_lane;

/* TB_OK; TB_UNSUPPORTED, TB_BADINPUT (vectors for another unit) or
 * TB_FAIL (no answer in time, out of memory) with err. */
int tb_batch_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts,
                 tb_batch_lane *lanes, size_t nlanes, char *err, size_t errlen);
#endif
