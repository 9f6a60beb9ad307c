/* sim_ival.h - interval evaluation of the primitives (sim_prim.h).
 *
 * For range analysis: each signal holds an interval of raw values [lo, hi]
 * instead of one value, and an element's output interval is computed from
 * its operands' the way the element computes a value: exact (128-bit)
 * before quantization, then rounded with the element's rounding mode.
 * Rounding (trunc = floor, half-up, even) is monotone, so rounding both
 * ends gives exactly the set's rounded ends; a sum's ends are the ends'
 * sums, a product's the hull of the four corner products. A point
 * interval gives exactly the element's value, so control signals (step
 * counters, decoders) that depend on no data stay points.
 *
 * Two intervals per element: pre, the rounded value before overflow
 * handling (what the format must hold not to overflow), and post, what
 * the signal then settles to (pre itself when it fits the format; else
 * saturated, or wrapped: the wrapped ends when the set does not straddle
 * a wrap, the whole format otherwise).
 *
 * A block key whose pass is a one-input logic function g(z) of the signal z
 * it passes, or of an operand of the element that computes what it passes,
 * passes only values computed from a z where g is nonzero: its interval
 * is taken over those (sim_ival.c, guarded).
 *
 * A multiplexer whose select is a one-input logic element g(z) stated
 * monotone (sim_logic_monotone: a sign test) passes each input only
 * where g gives its index (sim_ival_where): when the input is z, or an
 * operand p of z = p -+ q that z keeps exactly, its interval is taken
 * over those z.
 *
 * An adder y = a + m with m = t (b - a) and t in [0, 1] (interpolation)
 * is within hull(a, b), its roundings added exactly (sim_ival.c).
 *
 * A logic element is its function over its inputs' values when they are
 * few (an input computed from another of its inputs by a one-input logic
 * element is not enumerated as free), narrowed by what its unit states
 * of it (sim_logic_linear).
 *
 * Knows nothing of units: the caller holds one interval per signal,
 * indexed by sim_signal.index, and drives inputs and the clock itself.
 */
#ifndef SIM_IVAL_H
#define SIM_IVAL_H
#include "sim/sim_prim.h"

typedef struct sim_ival { sim_wide lo, hi; } sim_ival;   /* raws of the signal's format */

/* Element y's output interval from vals[] (indexed by signal index; only
 * y's operands are read, and for a register y's own current interval):
 * a combinational element's settled value, or a register's value after
 * the next rising edge (enable or reset not a point: the hull of both
 * outcomes). A constant is its value. Returns 0, or -1 when y is not an
 * element sim_prim_describe knows (an input, a clock, a user process). */
int sim_ival_eval(const sim_signal *y, const sim_ival *vals, sim_ival *pre, sim_ival *post);

/* Where g, a one-input logic element of some z stated monotone
 * (sim_logic_monotone: a sign test), gives the raw s, z within its
 * interval in vals: 1 and the first and last such z in *zs (by
 * bisection), 0 when no z does, -1 when g is no such element. */
int sim_ival_where(const sim_signal *g, const sim_ival *vals, int64_t s, sim_ival *zs);
/* Round x (raw with src_f fraction bits) to dst_f fraction bits, no
 * overflow handling: monotone in x. */
sim_wide sim_ival_round(sim_wide x, int src_f, int dst_f, sim_round r);
/* post from pre for format f with overflow mode o (see above). */
sim_ival sim_ival_fit(sim_ival pre, sim_fmt f, sim_ovf o);
/* Hull of a and b. */
static inline sim_ival sim_ival_hull(sim_ival a, sim_ival b)
{
    if (b.lo < a.lo) a.lo = b.lo;
    if (b.hi > a.hi) a.hi = b.hi;
    return a;
}
static inline int sim_ival_within(sim_ival in, sim_ival out) { return in.lo >= out.lo && in.hi <= out.hi; }
/* Smallest integer bits with which format f (its signedness and fraction
 * bits) holds v; -1 when none does (negative values in an unsigned
 * format, or more than 64 bits). */
int sim_ival_ibits(sim_ival v, sim_fmt f);
#endif
