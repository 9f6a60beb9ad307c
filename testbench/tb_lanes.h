/* tb_lanes.h - one stream of items simulated on the batch's lanes
 * (sim/sim_batch.h), with exactly the kernel's results for the stream
 * (run's engine; docs/batch.md, "One stream on lanes").
 *
 * The stream is cut into consecutive runs of items (pieces), one per
 * lane. Lane k starts from reset a few items early (a warm-up), and from
 * the clock edge where it offers its first own item it is taken to be the
 * stream itself at that point: the single-stream simulation (the
 * kernel's) would be in the same state there, if every signal of the
 * design holds the same value in lane k at that edge as in lane k-1 at the
 * edge where lane k-1 offers that item. That is checked for every lane and
 * every signal after the run; where it holds, the lanes' pieces joined end
 * to end are the stream: the beats and their clocks (each lane's shifted
 * by the clocks before it), the clock count, the toggles of every signal
 * (each lane's counted between its two junctions), every signal's
 * overflow counts (the same way, used and discarded, added to the
 * design's signals) and the ranges sampled at each edge. Where it does
 * not (an item that depends on more history than the warm-up), or an
 * overflow's count depends on the kernel's delta cycles
 * (sim_batch_ovf_unsure), or the design is not one the batch takes, the
 * wave is not taken and the caller runs the kernel.
 *
 * A stream of any length goes through in waves: a wave is a buffer of
 * consecutive items, its pieces simulated side by side, the first piece
 * joined to the last piece of the wave before (its state kept). The
 * buffer starts with the last items of the wave before (the warm-ups
 * reach back into them, and items still in flight there get their last
 * beats in this wave). The pieces of a wave are a function of its items
 * alone; they are simulated in groups of at most 64 lanes, the groups on
 * up to `threads` threads, each group on a build of the unit of its own:
 * every figure is the same for any number of threads.
 */
#ifndef TB_LANES_H
#define TB_LANES_H
#include "testbench/tb.h"
#include "testbench/tb_range.h"

/* A warm-up reaches back at most this many items: a wave's buffer starts
 * with at least this many of the items before (or all of them). */
#define TB_LANES_WARM_MAX 128

typedef struct tb_lanes tb_lanes;

/* The lanes of one stream of unit u; NULL with why when the unit does not
 * build or the batch does not take it (the kernel runs it). Out of
 * memory: base_out_of_memory. */
tb_lanes *tb_lanes_new(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *fmts, int threads,
                       char *why, size_t len);
void      tb_lanes_free(tb_lanes *x);
/* The groups of a wave on p's threads (base_pool.h) instead of threads
 * made for each wave (NULL: those). */
struct base_pool;
void      tb_lanes_pool(tb_lanes *x, struct base_pool *p);

typedef struct tb_lanes_wave {
    /* in */
    const int64_t *in_raw;      /* [pos][input], pos in [0, n): quantized inputs */
    size_t n, own;              /* items in the buffer; this wave's own from `own` on */
    size_t base;                /* the stream's number of the item at pos 0 */
    int    last;                /* the stream ends with this wave */
    /* out: the beats joined (the stream's clock of each, and its raws),
     * at their items' positions */
    uint64_t *beat_cycle;       /* [pos][beat] */
    int64_t  *raw;              /* [pos][beat][output] */
    size_t    beats_done;       /* the stream's beats joined so far: after the last wave, all */
} tb_lanes_wave;

/* 0: the wave's pieces joined to the stream; 1: not taken, why says why
 * (the stream is the kernel's from the start). */
int tb_lanes_wave_run(tb_lanes *x, tb_lanes_wave *w, char *why, size_t len);

/* After the last wave (once): the build whose figures the report takes
 * (area, critical path, its signals' overflow counts: the constants' and
 * the stream's), its range log with every live signal's range as the
 * stream's edges sampled it, each logged signal's toggles, the stream's
 * clocks, and the most lanes of a wave. */
typedef struct tb_lanes_out {
    sim_ctx          *c;
    const sim_scope  *sc;
    const unit_io    *io;
    tb_range         *rg;
    const uint64_t   *toggles;      /* per rg->smp signal */
    uint64_t          clocks;
    uint32_t          lanes;
} tb_lanes_out;
void tb_lanes_result(tb_lanes *x, tb_lanes_out *o);
#endif
