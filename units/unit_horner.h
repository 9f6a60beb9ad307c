/* unit_horner.h - the Horner datapath of Nechyporuk & Romanyuk (2020) (Fig. 9) and its faster
 * schedules, as a builder other units compose (interp3/interp2 put it
 * behind a coefficient unit).
 *
 * Schedules (their index is the same in every unit that contains the
 * datapath; interp adds fwd after them):
 *  - paper: Fig. 9, MUL = MX1 * t, Sm = MX2 + BK(RG), one step a clock,
 *    2 deg clocks per pixel (6 for the cubic);
 *  - mac:   one multiply-add a clock, RG <= MX1 * t + MX2, MX1 in {A, RG},
 *    MX2 in {B, C, D}: deg clocks per pixel, no BK;
 *  - pipe:  the deg multiply-adds unrolled into deg stages with pipeline
 *    registers carrying t and the coefficients still to come: a pixel per
 *    clock, the result deg clocks after it entered.
 * Each is its own datapath; the unit lists the union of their signals
 * (HORNER_SIGS3 / HORNER_SIGS2, counted by UNIT_SIGS), each masked with
 * the schedules that build it. One construction per schedule (a unet
 * walk, unit_net.h) builds the hardware, gives the default formats and
 * bounds the error, taking every format by signal name.
 *
 * The datapath reads its coefficients and t from signals the caller owns.
 * paper and mac run whenever `run` is 1 at step 0; once started, a pixel
 * runs to its end. pipe takes a pixel in every clock (run marks the valid
 * ones). The caller makes the output port (a view of the result) and
 * out_valid = a register of hw->done.
 */
#ifndef UNIT_HORNER_H
#define UNIT_HORNER_H
#include "units/unit.h"

/* Integer bits of the datapath's default rule (unit_horner.c says why). */
#define HORNER_IBITS 7

enum { HORNER_PAPER = 0, HORNER_MAC = 1, HORNER_PIPE = 2, HORNER_NSCHED = 3 };

#define H_P  UNIT_SCHED(HORNER_PAPER)
#define H_M  UNIT_SCHED(HORNER_MAC)
#define H_PP UNIT_SCHED(HORNER_PIPE)

/* The sequential datapaths (paper: all six; mac: no BK, and Sm adds MUL
 * and a coefficient). The order is the paper's, as the VCD shows it. */
#define HORNER_SIGS_SEQ \
    { .name = "mx1", .role = UNIT_SIG_INTERNAL, .what = "multiplexer MX1: A or RG into the multiplier", .scheds = H_P | H_M }, \
    { .name = "mul", .role = UNIT_SIG_INTERNAL, .what = "multiplier MUL = MX1 * t, quantized to its own format", .scheds = H_P | H_M }, \
    { .name = "mx2", .role = UNIT_SIG_INTERNAL, .what = "multiplexer MX2: paper MUL or a coefficient into the adder; mac a coefficient", .scheds = H_P | H_M }, \
    { .name = "bk",  .role = UNIT_SIG_INTERNAL, .what = "block key BK: passes RG or forces zero", .scheds = H_P }, \
    { .name = "sm",  .role = UNIT_SIG_INTERNAL, .what = "adder Sm: paper MX2 + BK, mac MUL + MX2", .scheds = H_P | H_M }, \
    { .name = "rg",  .role = UNIT_SIG_INTERNAL, .what = "register RG <= Sm every clock", .scheds = H_P | H_M }

/* Stage j of the pipe: mulJ = (A or rgJ-1) * t, smJ = mulJ + coefficient J,
 * rgJ <= smJ; tJ and cJ, dJ carry t and the later coefficients along. */
#define H_STAGE(j, wh_) \
    { .name = "mul" #j, .role = UNIT_SIG_INTERNAL, .what = "pipe stage " #j ": multiplier " wh_, .scheds = H_PP }, \
    { .name = "sm" #j,  .role = UNIT_SIG_INTERNAL, .what = "pipe stage " #j ": adder", .scheds = H_PP }, \
    { .name = "rg" #j,  .role = UNIT_SIG_INTERNAL, .what = "pipe stage " #j ": its result register", .scheds = H_PP }
#define H_DELAY(nm_, wh_) { .name = nm_, .role = UNIT_SIG_INTERNAL, .what = "pipe register: " wh_, .scheds = H_PP }

#define HORNER_SIGS3 HORNER_SIGS_SEQ, \
    H_STAGE(1, "A * t"), H_DELAY("t1", "t for stage 2"), H_DELAY("c1", "C for stage 2"), \
    H_DELAY("d1", "D for stage 2"), \
    H_STAGE(2, "rg1 * t1"), H_DELAY("t2", "t for stage 3"), H_DELAY("d2", "D for stage 3"), \
    H_STAGE(3, "rg2 * t2")
#define HORNER_SIGS2 HORNER_SIGS_SEQ, \
    H_STAGE(1, "A * t"), H_DELAY("t1", "t for stage 2"), H_DELAY("c1", "C for stage 2"), \
    H_STAGE(2, "rg1 * t1")

typedef struct h_sched h_sched;

typedef struct horner_hw {
    int deg, sched;
    const h_sched *s;
    sim_signal *mx1_sel, *mx2_sel, *bk_pass;   /* the controller's decoders (paper, mac) */
    sim_signal *last;   /* 1 in the clock where a pixel's last step runs: the
                         * inputs may change at the edge that ends it */
    sim_signal *done;   /* 1 in the clock before the result holds a finished
                         * pixel: out_valid is a register of it */
    sim_signal *rg;     /* the result register */
} horner_hw;

/* Clocks per pixel of schedule sched of degree deg (paper 6/4, mac 3/2,
 * pipe 1), and clocks from a pixel's start to its result (paper and mac
 * the same, pipe deg); -1 for a bad deg or sched. */
int horner_steps(int deg, int sched);
int horner_latency(int deg, int sched);

/* The controller of schedule sched, degree deg (3 or 2), in sc: paper and
 * mac a step counter that waits at step 0 while run is 0, and its
 * decoders; the one that is 1 in the last step is named last_name (horner3
 * calls it in_ready). pipe has none: every clock is a pixel's last, so
 * last is run itself. Built first so that a caller can derive its own
 * control from hw->last before it has the coefficient signals. 0, or -1
 * for a bad deg or sched. */
int horner_ctl_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, int deg, int sched, sim_signal *run,
                  const char *last_name, horner_hw *hw);
/* The datapath in sc, driven by hw's controller: coef[0..deg] are A, B, ...
 * (highest degree first), t the position; formats are u's signals of the
 * same names in f. Sets hw->rg and hw->done. */
void horner_dp_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw, sim_signal *run,
                  sim_signal *const *coef, sim_signal *t, const unit_desc *u, const unit_fmts *f);

/* The default rule of the degree-deg datapath's signals (every schedule's):
 * s7.(W-7), and u1.(W-1) for the pipe's copies of t; set by walking each
 * schedule's construction, so a signal u lacks is a bug (aborts). */
void horner_default_fmts(const unit_desc *u, int deg, int width, unit_fmts *out);

/* Worst-case |result - exact polynomial| after one pixel of schedule
 * sched, for coefficients held exactly in formats coef_f[0..deg] and t
 * exact in format t_f with |t| <= 1, with the datapath's formats u's
 * signals in f, then seen through format y_f: the datapath's own error
 * (docs/schedules.md). */
double horner_bound_on(int deg, int sched, const sim_fmt *coef_f, sim_fmt t_f, const unit_desc *u,
                       const unit_fmts *f, sim_fmt y_f, sim_round r);
#endif
