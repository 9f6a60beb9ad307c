/* sim_live.h - which bits of a signal can vary, for the delay model.
 *
 * A signal's bits are weighted 2^-F .. 2^(I-1) (its format sI.F or uI.F).
 * Not all of them need vary: a constant shift leaves constant zeros below
 * its source's lowest bit and copies of its top bit above its highest
 * (wiring); an adder of such terms varies only from the lower operand's
 * lowest bit to one above the higher's top. Synthesis propagates those
 * constants, so a mapped adder's carry chain runs only over the bits
 * where both operands vary; above them it is an incrementer of the longer
 * operand by the shorter's sign or carry (docs/timing.md, "Against
 * OpenSTA"). */
#ifndef SIM_LIVE_H
#define SIM_LIVE_H
#include "sim/sim.h"

/* The weights 2^*lo .. 2^*hi of s's bits that can vary: the bits below
 * *lo are constant zeros, the bits above *hi constants or copies of bit
 * *hi. Always within s's format, *lo <= *hi. */
void sim_live_span(const sim_signal *s, int *lo, int *hi);
/* The carry chain of an adder or subtractor whose operands vary over the
 * weights lo[k] .. hi[k] (k < n: its two operands; or, for the last
 * adder of a multi-operand chain (sim_delay_csa), every term the chain
 * adds) into format y: *chain bits where at least two terms vary (two
 * operands; a chain's carry-save vectors, the carry vector being where
 * two of its terms overlap), at least 1, then *ext bits up to y's top
 * where one does. The chain starts no lower than y's lowest bit: the
 * *low bits below it where two terms vary give only their carry into it
 * (sim_delay_add_span). */
void sim_live_chain(const int *lo, const int *hi, int n, sim_fmt y, int *chain, int *ext, int *low);
#endif
