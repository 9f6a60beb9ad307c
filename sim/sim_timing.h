/* sim_timing.h - static timing of a built design: its critical path.
 *
 * Every element carries its own delay (sim_signal.delay_ps, delay_lv, set
 * by the primitives from the delay model, sim_delay.h). Paths start at a
 * register's output (at its clock-to-q), at an input, or at a signal a
 * process other than a primitive drives (at 0); constants start none.
 * They run through the combinational elements and end at a register's D,
 * enable or reset (plus what the flip-flop needs there: the enable's
 * MUX2, the reset's gate, the setup time), or at any signal itself (so a
 * port that no register captures ends one). The critical path is the
 * longest in picoseconds; levels are the gate levels along it (clock-to-q
 * and setup count none). A combinational loop is an error.
 */
#ifndef SIM_TIMING_H
#define SIM_TIMING_H
#include <stddef.h>
#include "sim/sim.h"
#include "sim/sim_delay.h"

#define SIM_TIMING_PATH_MAX 64
typedef struct sim_timing {
    int     levels;          /* gate levels on the critical path */
    double  ps;              /* its delay, clock-to-q to setup, ps */
    double  fmax_mhz;        /* 1e6 / ps (0 when there is no path) */
    int     npath;           /* signals on it, start to end (at most SIM_TIMING_PATH_MAX) */
    int     nfull;           /* signals on the whole path (> npath: the middle is left out) */
    const sim_signal *path[SIM_TIMING_PATH_MAX];
} sim_timing;

/* 0 and *out filled; -1 with a message naming a signal of a
 * combinational loop (or "out of memory"). */
int sim_timing_analyze(const sim_ctx *c, sim_timing *out, char *err, size_t errlen);
/* The same with the carries a flow leaves (sim_delay.h: ripple, as
 * sim_timing_analyze, or prefix), every adder, subtractor and multiplier
 * costed with them. */
int sim_timing_analyze_carry(const sim_ctx *c, sim_carry carry, sim_timing *out, char *err, size_t errlen);

/* The input pins one bit of each signal drives, by signal index (arrays
 * of sim_signal_count(c)): sel[] select, enable, reset and key pins,
 * oth[] any other; a constant shift's are its source's (its own 0).
 * reads[] and adds[] (both NULL or both given): the elements reading each
 * signal, and the adders among them reading it as an operand. */
void sim_timing_pins(const sim_ctx *c, double *sel, double *oth, int *reads, int *adds);
#endif
