/* sim_op.h - the scalar operations of the element kinds, written once, as
 * Lua writes its arithmetic once (luai_numadd, luai_nummul: its VM and its
 * constant folder expand the same macros). Every scalar evaluation expands
 * these: sim_elem_eval (sim_elem_eval.c, the definition), the kernel's
 * inline operations (sim_deltas.h) and element functions (sim_prim.c), the
 * batch mode's scalar and sparse loops (sim_batch_eval.c, sim_batch_vec.h)
 * and the intervals' ends (sim_ival.c). Only the vector loops restate them,
 * in vectors; tests/test_cells.c holds those to sim_elem_eval. Not for
 * other layers.
 *
 * T is the type an operation is done in: sim_wide for the exact value
 * (128 bits hold every aligned operand, sum and product of 64-bit raws),
 * uint64_t on the fast paths, whose wrapping arithmetic is defined for
 * negative raws and exact when the operands' widths bound the result
 * below 2^62 (the sim__op_fits_* conditions below, which the kernel and
 * the batch mode both set their fast paths up with).
 */
#ifndef SIM_OP_H
#define SIM_OP_H
#include "sim/sim.h"

/* raw * 2^k: an operand aligned to k more fraction bits (an adder's
 * finer operand, a shift past the binary point). A multiplication, not a
 * shift, so that a negative raw in a signed T stays defined; the
 * compilers make it a shift. */
#define SIM_OP_ALIGN(T, x, k)  ((T)(x) * ((T)1 << (k)))
/* Adder, subtractor and multiplier, on aligned operands: the exact
 * result, with the finer operand's fraction bits (the sum of both
 * operands' for the product). */
#define SIM_OP_ADD(T, x, z)    ((T)(x) + (T)(z))
#define SIM_OP_SUB(T, x, z)    ((T)(x) - (T)(z))
#define SIM_OP_MUL(T, x, z)    ((T)(x) * (T)(z))
/* A multiplexer's select picks one of its n inputs; any other value
 * (negative or past the last) gives 0. */
#define SIM_OP_SEL_IN(sel, n)  ((uint64_t)(sel) < (uint64_t)(n))
/* The fast requantization of an exact s (|s| < 2^62): (s + radd) >> k,
 * arithmetic (floor on gcc and clang), which is truncation with radd 0
 * and half-up with radd 2^(k-1); sim_fx_requant is the definition, and
 * the caller checks the range. */
#define SIM_OP_QUANT(s, radd, k) ((int64_t)((uint64_t)(s) + (uint64_t)(radd)) >> (k))
/* x in [lo, hi], given as ulo = (uint64_t)lo and span = hi - lo: one
 * unsigned comparison. */
#define SIM_OP_IN_SPAN(x, ulo, span) ((uint64_t)(x) - (ulo) <= (span))

/* Low W bits of v, sign- or zero-extended: a logic element's output
 * (sim_fx_canon without the call). */
static inline int64_t sim__canon(int64_t v, sim_fmt f)
{
    int sh = 64 - f.width;
    if (f.is_signed) return (int64_t)((uint64_t)v << sh) >> sh;
    return (int64_t)((uint64_t)v & (UINT64_MAX >> sh));
}

/* ---- the fast paths' preconditions ----
 * From the operands' widths (a raw of W bits is below 2^W in magnitude)
 * and alignment shifts: the exact result of the uint64_t form stays below
 * 2^62, so adding the rounding constant cannot overflow either. The
 * kernel (sim_prim.c) and the batch mode (sim_batch_op.c) take the same. */

/* Bits bounding a signal's raw: |raw| <= 2^bits. */
static inline int sim__raw_bits(const sim_signal *s) { return s->fmt.width; }
/* A value passed on unchanged (register, multiplexer, block key, wire). */
static inline int sim__op_fits_copy(int w) { return w <= 62; }
/* An operand of w bits aligned by sa: below 2^61, so a sum of two is
 * below 2^62 (a shift's one operand likewise). */
static inline int sim__op_fits_aligned(int w, int sa) { return w + sa <= 61; }
/* A product of operands of wa and wb bits. */
static inline int sim__op_fits_mul(int wa, int wb) { return wa + wb <= 62; }
#endif
