/* sim_energy.h - dynamic energy from switching activity, per element kind.
 *
 * Each toggle of a signal's bit (sim_toggle.h) costs the energy of the
 * element driving it: the internal energy of its cells for one output
 * transition plus 1/2 C V^2 of the load the output charges (a rise draws
 * C V^2 from the supply, a fall none: 1/2 C V^2 a toggle on average).
 * Registers also cost clock energy every cycle, toggling or not.
 *
 * The constants are from the NanGate 45 nm Open Cell Library, typical
 * corner (NangateOpenCellLibrary_typical.lib: TypTyp, 1.10 V, 25 C), the
 * library sim_area.h takes its areas from. Internal energies are its
 * internal_power tables (energy per output transition, fJ) at the table
 * point input transition 0.0172 ns (index_1, third point) and output load
 * about 1.89 fF (index_2, second point: two X1 inputs), the rise and fall
 * tables averaged (a toggle is a rise or a fall), and where a cell's
 * tables depend on the state of its other inputs ("when"), those averaged
 * too. docs/timing.md, "Switching activity and energy", lists every value.
 * Leakage, glitches (a zero-delay simulation has none), wires beyond the
 * fixed load and other corners are left out.
 */
#ifndef SIM_ENERGY_H
#define SIM_ENERGY_H
#include "sim/sim.h"

#define SIM_E_VDD        1.10    /* V: nom_voltage */
#define SIM_E_CLOAD      1.89    /* fF: the table point's load, ~2 X1 inputs (AND2_X1 A1 0.918, A2 0.975) */
/* internal energy per output transition, fJ */
#define SIM_E_AND2       2.469   /* AND2_X1, ZN from A1 / A2 */
#define SIM_E_MUX2       2.916   /* MUX2_X1, Z from data inputs A / B */
#define SIM_E_FA_S       3.440   /* FA_X1, S (from B and CI, every state) */
#define SIM_E_FA_CO      3.618   /* FA_X1, CO (from A, B, CI, every state) */
#define SIM_E_DFF_Q      4.171   /* DFF_X1, Q from CK */
/* DFF_X1 per clock cycle without a change of Q: the CK pin's internal
 * (hidden) energy for a rise and a fall with D == Q (6.87 fJ) plus its
 * 0.950 fF pin charged once a cycle (C V^2 = 1.15 fJ). */
#define SIM_E_DFF_CLOCK  8.019

/* Energy of one toggle of a bit of s, fJ, by the element driving it:
 *   register       DFF Q + load
 *   multiplexer    a 2:1 mux + load per level of its tree (ceil log2 n)
 *   block key      AND2 + load
 *   adder, sub.    FA sum + load, plus half of FA carry + load (a single
 *                  input change flips the carry with probability 1/2)
 *   multiplier     the array's cells (wa wb AND2, (wa-1) wb adder cells,
 *                  as sim_area_mul) each switching once per output bit
 *                  kept, spread over those bits: a product toggle stands
 *                  for much internal switching
 *   logic          AND2 + load per output bit (a 2-input gate)
 *   input          the load alone (its driver is outside the design)
 *   wire, shift    0: the same wire as the signal it copies
 *   constant, clock 0 (the clock: sim_energy_clock_fj)
 */
double sim_energy_toggle_fj(const sim_signal *s);
/* Clock energy of one cycle: every flip-flop of the design (a register
 * of width w has w), fJ. */
double sim_energy_clock_fj(const sim_ctx *c);
/* Flip-flops of the design (the register bits sim_energy_clock_fj counts). */
uint64_t sim_energy_flops(const sim_ctx *c);
#endif
