/* sim_toggle.h - switching activity: bit toggles of each signal's settled
 * value, one time step to the next.
 *
 * A toggle is one bit of a signal's format that differs between the value
 * it settled on at the end of one time step and at the end of the next:
 * popcount((old XOR new) masked to the format's width). Glitches within a
 * time step (a value that changes and changes back between delta cycles)
 * are no toggle, exactly as a value change dump records one value per
 * time step (sim_vcd.h) and as a levelized evaluation (sim_batch.h) gives
 * one value per clock: the three agree bit for bit.
 *
 * Counting starts from the values of the first time step the counter sees
 * (the values after initialization, when it is made before the first
 * sim_run). It watches the run as a kernel observer (sim_observe with
 * SIM_OBS_CHANGES): a run nobody counts pays nothing.
 *
 * The clock is counted like any signal (one toggle per edge: what its
 * VCD trace shows); sim_toggle_total leaves clock signals out, since clock
 * power is modeled per flip-flop and cycle (sim_energy.h).
 */
#ifndef SIM_TOGGLE_H
#define SIM_TOGGLE_H
#include "sim/sim.h"

typedef struct sim_toggle sim_toggle;

/* Count c's toggles from its next time step on. Signals made later are
 * not counted. NULL when out of memory. */
sim_toggle *sim_toggle_new(sim_ctx *c);
/* Stop counting and free. */
void        sim_toggle_free(sim_toggle *t);
/* Toggles of s so far (0 for a signal made after the counter). */
uint64_t    sim_toggle_count(const sim_toggle *t, const sim_signal *s);
/* The sum over every signal but clocks (SIM_KIND_CLOCK). */
uint64_t    sim_toggle_total(const sim_toggle *t);
/* Set bits of m, without the popcnt instruction the baseline x86-64 lacks
 * (the compiler would call a library function). */
static inline uint64_t sim_toggle_popcount(uint64_t m)
{
    m = m - ((m >> 1) & 0x5555555555555555ull);
    m = (m & 0x3333333333333333ull) + ((m >> 2) & 0x3333333333333333ull);
    m = (m + (m >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return (m * 0x0101010101010101ull) >> 56;
}
/* Bits of s's format set in a raw value: the mask toggles are counted in. */
static inline uint64_t sim_toggle_mask(const sim_signal *s)
{
    return s->fmt.width >= 64 ? UINT64_MAX : ((uint64_t)1 << s->fmt.width) - 1;
}
#endif
