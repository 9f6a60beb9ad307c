/* unit_rec.h - digit recurrences, one result bit a step: the restoring
 * square root and the restoring reciprocal (unit_rec.c). sqrt, norm3 and
 * shade build on them. Internal to units/.
 *
 * Both are written once as a step (a subtractor, its sign, a restore
 * multiplexer and wiring) on integer raws, and built two ways:
 *  - iterative: one step and its registers R (remainder), Q (result so
 *    far) and, for the root, X (the radicand's bits still to come), fed
 *    back; a step a clock, loaded in the first clock of an item;
 *  - unrolled: a step a stage, a pipeline register after each (an item a
 *    clock, the result K clocks after it entered), each stage's registers
 *    only as wide as its values can be.
 *
 * Square root (radix 4 in, one root bit out a step): with the radicand's
 * integer N = x_raw 2^(2F_q - F_x) of 2K bits (K = F_q + 1),
 *     R2 = 4 R + next two bits of N      wiring
 *     T  = R2 - (4 Q + 1)                subtractor (4Q + 1 is wiring)
 *     R <= T >= 0 ? T : R2,  Q <= 2 Q + (T >= 0)
 * after K steps Q = floor(sqrt(N)) = floor(sqrt(x) 2^F_q) exactly: the
 * root truncated to q's format, below one LSB of it.
 * Reciprocal of d in [1/2, 1] (u1.F_d): N = 2^(F_q + F_d), K = F_q + 2,
 * R starts at N / 2^K = 2^(F_d - 2) and zeros come in:
 *     R2 = 2 R,  T = R2 - d_raw,  R <= T >= 0 ? T : R2,  Q <= 2 Q + (T >= 0)
 * after K steps Q = floor(2^F_q / d): 1/d truncated to q's format (u2.F_q,
 * 1/d in [1, 2]). For d in [2^-e, 1] the same with K = F_q + 2 + e and R
 * starting at 2^(F_d - 2 - e) (still below d): u(2+e).F_q. */
#ifndef UNIT_REC_H
#define UNIT_REC_H
#include "units/unit.h"

typedef enum { REC_SQRT, REC_RECIP } rec_kind;

/* A recurrence: its kind, the fraction bits of its operand (x: F_x, d:
 * F_d) and of its result (F_q). */
typedef struct rec_spec {
    rec_kind kind;
    int      f_in, f_q;
    /* reciprocal: the divisor d in [2^-e, 1] (e = 0: the [1/2, 1] above),
     * e more steps and result bits (R starts at 2^(F_d - 2 - e), 1/d in
     * [1, 2^(e+1)]); a caller that keeps its divisor above 2^-e (a clamp)
     * sets it. 0 for the root. */
    int      e;
} rec_spec;

/* Steps (clocks or stages) of a recurrence: K. */
int     rec_steps(const rec_spec *s);
/* The result's format: sqrt u1.F_q (x in [0, 2)), reciprocal u(2+e).F_q. */
sim_fmt rec_out_fmt(const rec_spec *s);
/* 0, or -1 with a message when the recurrence cannot be built (F_q too
 * small for the radicand's bits, registers over 62 bits). */
int     rec_check(const rec_spec *s, char *err, size_t errlen);

/* Iterative: the step and its registers (named prefix "r", "q", "x"),
 * loading the operand in (x or d, held by the source for the whole item)
 * where first is 1. Q after K clocks; the caller's sequencer counts them.
 * en (NULL: always): the registers take a step only where it is 1 (a
 * root that must not run on past its K steps while a unit does
 * something else: Q would lose its top bits and R outgrow its register). */
sim_signal *rec_iter(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                     const rec_spec *s, sim_signal *in, sim_signal *first, sim_signal *en);
/* Unrolled and pipelined: stage k's registers are prefix "<k>_r", "_q",
 * "_x" (and "_d", the divisor carried along). The result (format
 * rec_out_fmt, a view of the last Q) K clocks after in entered. */
sim_signal *rec_pipe(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                     const rec_spec *s, sim_signal *in);
/* The same number of pipeline registers for a value travelling beside a
 * recurrence (or any k stages): prefix "<j>" names them. */
sim_signal *rec_delay(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *prefix,
                      sim_signal *v, int k);
#endif
