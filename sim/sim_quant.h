/* sim_quant.h - the scalar quantization step every engine takes, written
 * once: sim_prim.c (the kernel's elements, sim_quant_into) and the batch
 * mode's scalar loops (sim_batch_eval.c) call these; the vector loops
 * (sim_batch_vec.h) do the fast path's add, shift and range check in
 * vectors and hand a lane that leaves it back to the scalar loop. Not for
 * other layers.
 */
#ifndef SIM_QUANT_H
#define SIM_QUANT_H
#include "sim/sim_op.h"

/* The fast path of quantizing raw, with src_f fraction bits, into a
 * format of dst_f fraction bits and raw range [lo, hi], rounding r
 * (already the format's own): what datapaths do on almost every clock,
 * drop k < 63 low bits of a value that fits 63 bits by truncation or
 * half-up, and land in range. 1 with the result in *x when it applies;
 * 0 otherwise, and the caller takes the general path, sim_fx_requant,
 * which is the definition (tests compare both through the primitives).
 * The general call stays with the caller: kept out of here, the fast
 * path needs no overflow flag in memory. */
static inline int sim__quant_fits(sim_wide raw, int src_f, int dst_f, int64_t lo, int64_t hi, sim_round r,
                                  int64_t *x)
{
    int k = src_f - dst_f;
    if ((unsigned)k < 63 && raw >= -((sim_wide)1 << 62) && raw < ((sim_wide)1 << 62) && r != SIM_RND_EVEN) {
        int64_t v = SIM_OP_QUANT(raw, k && r == SIM_RND_HALF_UP ? (int64_t)1 << (k - 1) : 0, k);
        if (v >= lo && v <= hi) { *x = v; return 1; }
    }
    return 0;
}

/* The specialized fast path's constants for an exact result with src_f
 * fraction bits into dst_f: y = (s + *radd) >> *k when that lands in
 * range (floor((s + 2^(k-1)) / 2^k) is half-up rounding). *k is set in
 * any case; returns 1 when the path applies (trunc or half-up,
 * 0 <= k <= 61), else 0 with *radd untouched. */
static inline int sim__quant_fast(int src_f, int dst_f, sim_round r, int *k, int64_t *radd)
{
    *k = src_f - dst_f;
    if (*k < 0 || *k > 61 || r == SIM_RND_EVEN) return 0;
    *radd = (r == SIM_RND_HALF_UP && *k) ? (int64_t)1 << (*k - 1) : 0;
    return 1;
}

#endif
