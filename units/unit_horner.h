/* unit_horner.h - the Horner datapath of seed 000 (Fig. 9) as a builder
 * other units compose (interp3/interp2 put it behind a coefficient unit).
 *
 * The datapath reads its coefficients and t from signals the caller owns
 * and runs its paper schedule, one step a clock, whenever `run` is 1 at
 * step 0; once started, a pixel runs to its end. The caller makes the
 * output port (a view of RG) and out_valid (RG holds the result in the
 * cycle after `last`).
 */
#ifndef UNIT_HORNER_H
#define UNIT_HORNER_H
#include "units/unit.h"

/* Integer bits of the datapath's default rule (unit_horner.c says why). */
#define HORNER_IBITS 7

/* Internal signals, in this order, in every unit that contains the
 * datapath: their formats are passed as fi[HORNER_NINT]. */
enum { HORNER_MX1 = 0, HORNER_MUL, HORNER_MX2, HORNER_BK, HORNER_SM, HORNER_RG, HORNER_NINT };

#define HORNER_SIGS \
    { "mx1", UNIT_SIG_INTERNAL, "multiplexer MX1: A or RG into the multiplier" }, \
    { "mul", UNIT_SIG_INTERNAL, "multiplier MUL = MX1 * t, quantized to its own format" }, \
    { "mx2", UNIT_SIG_INTERNAL, "multiplexer MX2: MUL or a coefficient into the adder" }, \
    { "bk",  UNIT_SIG_INTERNAL, "block key BK: passes RG or forces zero" }, \
    { "sm",  UNIT_SIG_INTERNAL, "adder Sm = MX2 + BK" }, \
    { "rg",  UNIT_SIG_INTERNAL, "register RG <= Sm every clock" }

typedef struct horner_hw {
    int         deg;
    sim_signal *mx1_sel, *mx2_sel, *bk_pass;   /* the controller's decoders */
    sim_signal *last;   /* 1 during the last step of a pixel */
    sim_signal *rg;     /* register RG: the result after the last step */
} horner_hw;

/* Clocks per pixel of the paper schedule of degree deg (3: 6, 2: 4). */
int horner_steps(int deg);

/* The controller of degree deg (3 or 2) in sc: a step counter that waits
 * at step 0 while run is 0, and its decoders; the one that is 1 in the
 * last step is named last_name (horner3 calls it in_ready). Built first so
 * that a caller can derive its own control from hw->last before it has the
 * coefficient signals. 0, or -1 for a bad deg. */
int horner_ctl_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, int deg, sim_signal *run,
                  const char *last_name, horner_hw *hw);
/* The datapath in sc, driven by hw's controller: coef[0..deg] are A, B, ...
 * (highest degree first), t the position, fi the formats of the
 * HORNER_NINT internals. Sets hw->rg. */
void horner_dp_on(sim_ctx *c, sim_scope *sc, sim_signal *clk, horner_hw *hw,
                  sim_signal *const *coef, sim_signal *t, const sim_fmt *fi);

/* Worst-case |RG - exact polynomial| after one pixel, for coefficients
 * held exactly in formats coef_f[0..deg] and t exact in format t_f with
 * |t| <= 1, then seen through format y_f: the datapath's own error. */
double horner_bound_on(int deg, const sim_fmt *coef_f, sim_fmt t_f, const sim_fmt *fi,
                       sim_fmt y_f, sim_round r);
#endif
