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
#endif
