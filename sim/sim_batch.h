/* sim_batch.h - batch mode: a design made only of primitives (sim_prim.h),
 * evaluated levelized for N independent copies of it side by side.
 *
 * The event-driven kernel (sim.h) is the reference: it evaluates an element
 * when one of its inputs changes, delta cycle after delta cycle. For a
 * synchronous design whose combinational part has no loop, the values it
 * settles on are a function of the registers and inputs alone, whatever
 * the order of evaluation. So they can also be computed by evaluating
 * every combinational element once per clock edge, in topological order
 * (levelization, as commercial event-driven simulators and Verilator's
 * static scheduling do), with no event queue at all. sim_batch does that
 * for `lanes` copies of the design at once, each element's values held as
 * an array over the lanes (structure of arrays), so that one pass over the
 * schedule advances every copy by one clock.
 *
 * Each lane is its own simulation: the same clock edges, its own inputs,
 * registers and outputs. Settled values, register contents and therefore
 * every output and clock count are those of the kernel running that
 * lane's stimulus alone.
 *
 * Overflow counts are the one thing a levelized evaluation does not give
 * directly (the kernel counts the time steps in which an element was
 * evaluated and settled on an overflowed quantization, and whether it was
 * evaluated depends on events). sim_batch flags a lane in which any
 * quantization overflowed; asked to (sim_batch_overflows_on), it counts
 * them per signal and lane as the kernel does (sim_batch_ovf.c says how,
 * and the one case where it cannot tell). A lane with no flag had no
 * overflow in any settled value, so the kernel would count none either
 * (sim__overflow counts only an element's last evaluation in a time step,
 * which sees the settled inputs).
 *
 * What the batch mode accepts (sim_batch_new says why it refuses):
 * every process of the context is a primitive's; registers are clocked by
 * the given clock's rising edge and nothing else reads the clock; the
 * combinational elements form no loop. Inputs are signals no element
 * drives; a testbench sets them per lane.
 *
 * Use: build the design into a context with no testbench processes, make
 * the batch, set the inputs of every lane, sim_batch_start (the kernel's
 * initialization), then per clock: read the values before the edge
 * (sim_batch_val), set the inputs the testbench writes at the edge
 * (sim_batch_set), sim_batch_cycle. The context must outlive the batch and
 * is not simulated itself.
 */
#ifndef SIM_BATCH_H
#define SIM_BATCH_H
#include "sim/sim.h"

typedef struct sim_batch sim_batch;

/* The batch for `lanes` copies (1..SIM_BATCH_MAX_LANES) of the design in c,
 * clocked by clk; NULL with the reason in err when the design is not one
 * the batch mode can evaluate (see above) or memory is short. */
#define SIM_BATCH_MAX_LANES 4096
sim_batch *sim_batch_new(sim_ctx *c, const sim_signal *clk, uint32_t lanes,
                         char *err, size_t errlen);
void       sim_batch_free(sim_batch *b);
uint32_t   sim_batch_lanes(const sim_batch *b);

/* The values of s now, one per lane. */
const int64_t *sim_batch_val(const sim_batch *b, const sim_signal *s);
/* The lanes (bit l%64 of word l/64) in which s took a new value at the
 * last sim_batch_cycle, until the next: a testbench looks at those lanes
 * only, instead of every lane at every edge. */
const uint64_t *sim_batch_changed(const sim_batch *b, const sim_signal *s);
/* 1 when every lane of s is known to hold one value (lanes that run in
 * step: the batch keeps this for its own shortcut); 0 when they differ or
 * it does not know. */
int sim_batch_uniform(const sim_batch *b, const sim_signal *s);
/* Input s of lane `lane` takes raw v at the next edge (or at the start, if
 * the batch has not started): what sim_write from a process woken by the
 * edge does. s must be an input (no element drives it): -1 otherwise. */
int  sim_batch_set(sim_batch *b, const sim_signal *s, uint32_t lane, int64_t v);
/* The same for every lane at once: the array (one per lane) of the values
 * input s takes at the next edge, to write in place; they stay set from
 * edge to edge until written again. NULL if s is not an input. */
int64_t *sim_batch_next(sim_batch *b, const sim_signal *s);
/* Input s was written through sim_batch_next since the last edge. Once a
 * testbench marks an input, the edges look only at the inputs marked
 * since the edge before (and those sim_batch_set wrote): the others are
 * not compared lane by lane for a change. */
void sim_batch_mark(sim_batch *b, const sim_signal *s);

/* The kernel's initialization: inputs set so far take their values, every
 * combinational element is evaluated (registers keep their reset values). */
void sim_batch_start(sim_batch *b);
/* One rising edge of the clock and what follows it: every register
 * samples its input as it was before the edge, the inputs set since the
 * last edge take their values, the combinational network settles. */
void sim_batch_cycle(sim_batch *b);

/* Batches made from now on use vector loops of at most `most` lanes an
 * instruction where the CPU has them: 8 (the default) AVX-512, else AVX2;
 * 4 AVX2 only; 0 the scalar loops only. A batch takes them when its lanes
 * (at most 64) are a multiple of the vector's. Their results are the same
 * bit for bit; the tests run each. Returns the width this CPU gives (0,
 * 4 or 8). Not to be called while another thread makes a batch. */
uint32_t sim_batch_vector(uint32_t most);
/* Groups of lanes (one vector each) the vector loops evaluated so far,
 * and how many of them they handed to the scalar loop (a fast result out
 * of range). */
void sim_batch_vector_stats(const sim_batch *b, uint64_t *groups, uint64_t *fell);

/* Switching activity (sim_toggle.h), off unless asked for: from the
 * values after sim_batch_start (or, asked later, from the values now),
 * each signal's bit toggles per lane, counted after each settle: what the
 * kernel's sim_toggle counts for that lane's stimulus run alone. The
 * clock is not simulated by the batch: its count stays 0. 0, or -1 when
 * out of memory. */
int  sim_batch_toggles_on(sim_batch *b);
/* The toggles of s so far, one per lane; NULL when not counting. */
const uint64_t *sim_batch_toggles(const sim_batch *b, const sim_signal *s);

/* Range tracking (tb_range's logging), off unless asked for (it turns
 * toggle counting on too): per signal and lane the smallest and largest
 * value settled on since the lane's last sim_batch_range_reset (or since
 * it was asked for), the value then included. 0, or -1 when out of
 * memory. */
int  sim_batch_ranges_on(sim_batch *b);
void sim_batch_range_reset(sim_batch *b, uint32_t lane);
void sim_batch_range(const sim_batch *b, const sim_signal *s, uint32_t lane, int64_t *mn, int64_t *mx);

/* 1 if some quantization in lane `lane` overflowed since the start. */
int  sim_batch_overflowed(const sim_batch *b, uint32_t lane);

/* Overflow counts (sim_batch_ovf.c), off unless asked for before
 * sim_batch_start: per signal and lane, the kernel's `overflows` (on
 * values used that clock) and `ovf_discarded` (sim.h) for that lane's
 * stimulus run alone, counted after each settle. A lane where the count
 * depends on the kernel's delta cycles (an element that may be run by a
 * glitch of an input while it holds an overflowed value) has that time
 * step counted as unsure: its counts over it are not to be used. 0, or -1 when out of memory
 * or already started. */
int  sim_batch_overflows_on(sim_batch *b);
const uint64_t *sim_batch_ovf_used(const sim_batch *b, const sim_signal *s);
const uint64_t *sim_batch_ovf_discarded(const sim_batch *b, const sim_signal *s);
/* The time steps so far in which lane's counts may differ from the
 * kernel's (0: none; UINT64_MAX: not counted). A caller compares it at
 * the two ends of the stretch it keeps. */
uint64_t sim_batch_ovf_unsure(const sim_batch *b, uint32_t lane);
/* Combinational elements and registers in the schedule, for reports. */
uint32_t sim_batch_elements(const sim_batch *b);
#endif
