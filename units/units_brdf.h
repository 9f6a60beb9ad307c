/* units_brdf.h - pieces of hardware and arithmetic the BRDF units share
 * (units_brdf.c: brdf_*; unit_powg.c: the power engine pw_*; unit_div.c:
 * the restoring divider dv_*). Internal to units/: the rest of the program
 * sees units only through unit.h. One header, so that a definition and its
 * users cannot drift apart (the compiler checks both against it). */
#ifndef UNITS_BRDF_H
#define UNITS_BRDF_H
#include "units/unit.h"
#include "units/unit_net.h"

/* ---- units_brdf.c ---- */
/* Bits of v (0 for 0). */
int    brdf_bitlen(uint64_t v);
/* Step counter of a multi-clock unit: in_valid, in_ready, out_valid, and
 * the registered "next step" and "first step" signals. */
void   brdf_seq(sim_ctx *c, sim_scope *sc, sim_signal *clk, int nsteps, unit_io *io,
                sim_signal **next_out, sim_signal **first_out);
/* A registered decoder of a step-indexed control table of n entries. */
sim_signal *brdf_decode(sim_ctx *c, sim_scope *sc, sim_signal *clk, const char *name,
                        sim_signal *next, const uint8_t *table, int n);
/* y = x * k, k a constant: a shift-and-add network; its area is the
 * adders synthesis builds (a row of x for each 1 of k: sim_area_cmul) plus
 * y's quantization logic (rounding, clamp), its delay a tree of one adder
 * per CSD digit of k after the first. */
sim_signal *brdf_cmul(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt fy,
                      sim_signal *x, sim_signal *k);
int    brdf_ibits(double x);
int    brdf_holds(sim_fmt f, double lo, double hi);
double brdf_range_bound(sim_fmt out, double ideal_max);
sim_signal *brdf_const(sim_ctx *c, sim_scope *sc, const char *name, sim_fmt f, double x);
double brdf_const_err(double x, sim_fmt f);
/* A hard-wired constant x in format f (brdf_const) as a value of a unet
 * walk: built when the walk builds; its error is the stored value's
 * distance from x, its fraction bits those its raw really has (a product
 * with it carries no more), its ideal magnitude |x|. */
unet_val brdf_uconst(unet *n, sim_fmt f, const char *name, double x);
/* Fraction bits the constant brdf_const stores really has (fewer than
 * f's when its raw ends in zeros; -64 for 0): what a product with it
 * carries, so that widening the constant's format adds no quantization. */
int    brdf_const_eff(double x, sim_fmt f);

/* ---- unit_powg.c: the one-multiplier power engine ---- */
/* The engine running prog on IN, as a step of a unet walk (unit_net.h)
 * of the unit n->u: building (n->c), the sequencer (into io) and the
 * engine, *rg its RG; bounding, every clock of the program, *rg RG's
 * value after it. 0, or -1 (a bad program; bounding: a format that cannot
 * hold its value). */
int    pw_engine(unet *n, unit_io *io, const char *prog, unet_val in, unet_val *rg);
sim_signal *pw_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                     const unit_fmts *f, unit_io *io, sim_signal *in, const char *prog);
/* in_fmt: the input's format with fbits the bits it really has; *eff_out
 * (may be NULL): those of RG after the program. */
double pw_bound(const unit_desc *u, const unit_fmts *f, sim_round r, sim_fmt in_fmt,
                double e_in, double m_in, const char *prog, double *m_out, int *eff_out);
/* Whether the engine running prog builds signal i (its operand muxes
 * exist only where an operand has more than one source); 1 for others. */
int    pw_sig_built(const unit_desc *u, const char *prog, int i);

/* The engine's program unrolled (shade's pipe): a stage a step, each a
 * multiplier (element "<pfx><k>_mul", format of signal sig) and its
 * register ("<pfx><k>", the last one named last), IN carried beside in
 * registers where a later step reads it. The same products and
 * quantizations as pw_engine's clocks, so the walk bounds it the same
 * way; *stages: its pipeline registers. 0, or -1 (a bad program). */
int    pw_unrolled(unet *n, const char *prog, unet_val in, int sig, const char *pfx,
                   const char *last, unet_val *rg, int *stages);

/* ---- unit_pow_n.c ---- */
#define PW_N_MAX 1024
/* 2 characters a step, at most 2 steps a bit of n: 10 bits after the lead. */
#define PW_N_PROG_LEN (4 * 11 + 1)
/* Left-to-right square and multiply for x^n: "II", then per bit of n
 * after the leading one "RR" and, for a 1 bit, "RI" ("I1" for n = 1).
 * NULL when n is outside 1..PW_N_MAX. */
const char *pow_n_prog(int n, char *buf);

/* ---- unit_div.c: the restoring divider ---- */
sim_signal *dv_build(const unit_desc *u, sim_ctx *c, sim_scope *sc, sim_signal *clk,
                     const unit_fmts *f, unit_io *io, sim_signal *num, sim_signal *den,
                     sim_signal *shr, int shr_max, char *err, size_t errlen);
/* Exact x^e by square and multiply, as the power units compute it: 0, or
 * -1 when it does not fit a sim_dy (the testbench then uses the interval
 * or says it cannot check). The interval form gives lower and upper
 * values cut to 240 fraction bits (x >= 0: every product is monotone). */
int brdf_pow_exact(const sim_dy *x, int e, sim_dy *out);
int brdf_pow_interval(const sim_dy *x, int e, sim_dy *lo, sim_dy *hi);
#endif
