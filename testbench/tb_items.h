/* tb_items.h - one unit over a long list of independent items (a scene's
 * per-pixel shading: each pixel's inputs make one item) on the batch's
 * lanes, on threads.
 *
 * The list is cut into lanes of consecutive items, their number a function
 * of the list's length alone (not of the threads), each lane tb_batch_run's
 * (overflows counted as the kernel counts them; a lane whose counts the
 * batch cannot tell is simulated again by the kernel: tb_batch.h), in groups of lanes also fixed by the count (a lane's
 * switching is counted until the last lane of its group ends), the groups
 * on threads. So every figure is the same for any number of threads. The unit must give each
 * item's output from that item's inputs alone (no state carried between
 * items), as the shading units do. */
#ifndef TB_ITEMS_H
#define TB_ITEMS_H
#include "testbench/tb.h"

typedef struct tb_items_stats {
    size_t   items;
    uint32_t lanes;
    uint64_t clocks;             /* every lane's clocks, summed */
    double   cycles_per_item;    /* steady state: the longest lane's (last - first beat) / (items - 1) */
    uint64_t overflows;          /* the unit's own, summed */
    uint64_t in_overflows;       /* of the inputs' quantization, summed */
    double   energy_pj;          /* switching and clock energy, summed (energy asked for) */
    double   area_ge;            /* the built unit */
} tb_items_stats;

/* Run u (configuration cfg, formats f) on the n items in[n][n_in]
 * (n_in = unit_n_in(u)); out[i] = item i's first output, first beat, as a
 * real. energy: count switching energy (st->energy_pj). TB_OK, or
 * TB_FAIL / TB_BADINPUT / TB_UNSUPPORTED with a message. */
int tb_items_run(const unit_desc *u, const unit_cfg *cfg, const unit_fmts *f, const double *in, size_t n, int jobs,
                 int energy, double *out, tb_items_stats *st, char *err, size_t errlen);
#endif
