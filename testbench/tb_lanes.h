/* tb_lanes.h - one stream of items simulated on the batch's lanes
 * (sim/sim_batch.h), with exactly the kernel's results for the stream
 * (tb_run's engine for `run`; docs/batch.md, "One stream on lanes").
 *
 * The stream is cut into consecutive runs of items, one per lane. Lane k
 * starts from reset a few items early (a warm-up), and from the clock
 * edge where it offers its first own item it is taken to be the stream
 * itself at that point: the single-stream simulation (the kernel's) would
 * be in the same state there, if every signal of the design holds the
 * same value in lane k at that edge as in lane k-1 at the edge where
 * lane k-1 offers that item. That is checked for every lane and every
 * signal after the run; where it holds, the lanes' pieces joined end to
 * end are the stream: the beats and their clocks (each lane's shifted by
 * the clocks before it), the clock count, the toggles of every signal
 * (each lane's counted between its two junctions), every signal's
 * overflow counts (the same way, added to the design's signals) and the
 * ranges sampled at each edge. Where it does not (an item that depends on
 * more history than the warm-up), or an overflow's count depends on the
 * kernel's delta cycles (sim_batch_ovf_unsure), or the design is not one
 * the batch takes, nothing is filled and the caller runs the kernel.
 */
#ifndef TB_LANES_H
#define TB_LANES_H
#include "testbench/tb.h"
#include "testbench/tb_range.h"

typedef struct tb_lanes_job {
    /* in: the built unit (tb_build, no testbench processes, no clock
     * process) and the quantized inputs */
    sim_ctx          *c;
    const sim_signal *clk;
    const unit_io    *io;
    int               n_in, n_out, beats;
    size_t            n_items;
    const int64_t    *in_raw;       /* [item][input] */
    /* out (on success): tb_run's arrays and figures */
    uint64_t         *beat_cycle;   /* [item][beat] */
    int64_t          *raw;          /* [item][beat][output] */
    tb_range         *rg;           /* tb_range_init'ed: its live ranges are set (as sampled) */
    uint64_t         *toggles;      /* per rg->smp signal */
    uint64_t          clocks;
    uint32_t          lanes;        /* lanes used */
} tb_lanes_job;

/* 0: done, the outputs filled; 1: not taken, why says why (use the
 * kernel); -1: out of memory. */
int tb_lanes_run(tb_lanes_job *j, char *why, size_t len);
#endif
