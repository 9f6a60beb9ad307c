/* sim_lut.h - a logic element (sim_logic) as a table: the one tabulator
 * the kernel (sim_sched.c, tabulate) and the batch mode (sim_batch_op.c)
 * both build their tables with. Not for other layers.
 *
 * The index is the inputs' fields side by side, input 0 lowest: input j's
 * field is its format's width w_j wide, at bit sh_j = w_0 + ... + w_(j-1).
 * A field holds the input's raw in one of two codes, each engine the one
 * its evaluation computes cheapest:
 *   SIM_LUT_OFFSET  raw - raw_min (the kernel: its range check already
 *                   has that difference; a raw outside the format is not
 *                   in the table and calls the function)
 *   SIM_LUT_TWOS    raw's low w_j bits (the batch mode: an AND, in
 *                   vectors too; its lanes hold only raws in the format)
 * An entry is what an evaluation gives: the element's function of the
 * inputs' raws, then the output's low bits sign- or zero-extended (the
 * function is defined for every raw value of its inputs' formats:
 * sim_prim.h), so a table changes no result, only the speed.
 *
 * The threshold: a table is made for at most SIM_LUT_BITS input bits in
 * all (4096 entries of 8 bytes, 32 KB), the batch mode's. The kernel
 * passes SIM_LUT_BITS_KERNEL as its own ceiling: a user's function may
 * count its calls, and tests/test_kernel.c (t_logic_table) pins that on
 * the kernel an element of 9 input bits calls its function at each
 * evaluation and is not tabulated. Either way the results are the same;
 * the ceiling decides only the speed. */
#ifndef SIM_LUT_H
#define SIM_LUT_H
#include "sim/sim.h"
#include "sim/sim_prim.h"

#define SIM_LUT_BITS 12
#define SIM_LUT_BITS_KERNEL 8
_Static_assert(SIM_LUT_BITS_KERNEL <= SIM_LUT_BITS, "one ceiling");

typedef enum { SIM_LUT_OFFSET, SIM_LUT_TWOS } sim_lut_code;

/* The layout of n inputs' fields: sh[j] and the field's mask (w_j ones)
 * for every j; returns the index's bits, or -1 when they are more than
 * max_bits (at most SIM_LUT_BITS) or n is outside 0..8. */
int sim_lut_layout(int n, sim_signal *const *in, int max_bits, int *sh, uint64_t *mask);
/* Fill tab[0 .. 2^bits - 1] (bits and mask from sim_lut_layout),
 * calling fn once per entry in increasing index order; out is the
 * output's format. */
void sim_lut_fill(int64_t *tab, int bits, int n, sim_signal *const *in, const uint64_t *mask,
                  sim_lut_code code, sim_logic_fn fn, void *user, sim_fmt out);
#endif
