/* sim_aff.h - affine evaluation of the primitives, beside the intervals
 * of sim_ival.h, for range analysis that keeps the relations a linear
 * network relies on.
 *
 * An interval forgets where a value came from: 8 x - x over x in [0, 1]
 * is [-1, 8], not [0, 7], and a chain of shifts and subtractors (the
 * coefficient units) piles such losses up into formats that "cannot
 * hold" values they always hold. An affine form (Comba and Stolfi's
 * affine arithmetic) writes a value as
 *     x0 + sum_i x_i e_i + [r_lo, r_hi],   each noise symbol e_i in [-1, 1],
 * the symbols shared between forms: sums, differences, shifts and
 * multiplexers with a known select are exact, so 8 x - x is 7 x. A
 * product keeps its linear part and puts the rest in the remainder;
 * rounding to the element's format adds its error range to the
 * remainder; what the forms cannot follow (a multiplexer with an unknown
 * select, logic, an overflow) becomes the element's interval as a fresh
 * symbol. A logic element its unit states linear (sim_logic_linear) is
 * k x plus its error as a symbol of its own (so that the forms computed
 * from it share it). A multiplexer selected by a monotone test of
 * z = p - q (sim_ival.h) bounds each input, and its difference from q,
 * given z where the test selects it; when all lie on one side of q the
 * output is q's form plus that difference as a new symbol: the relation
 * "below q" (a restoring divider's remainder under its divisor) carries
 * into the next clock. Values are reals (doubles); every operation widens the
 * remainder by a relative 2^-48 of the magnitudes involved, far above
 * the doubles' rounding, so the hull stays sound.
 *
 * Knows nothing of units: the caller holds one form per signal (indexed
 * by sim_signal.index), with the intervals sim_ival_eval gives, and
 * makes the symbols (sim_aff_symbol) for inputs and for state it joins.
 */
#ifndef SIM_AFF_H
#define SIM_AFF_H
#include "sim/sim_ival.h"

#define SIM_AFF_TERMS 24        /* past this, the smallest terms go to the remainder */

typedef struct sim_aff {
    double   c0, rlo, rhi;      /* centre and remainder, reals */
    int      n;                 /* terms, by increasing symbol */
    uint32_t sym[SIM_AFF_TERMS];
    double   co[SIM_AFF_TERMS];
} sim_aff;

/* The form of the reals lo..hi as one new symbol *next (then advanced). */
sim_aff sim_aff_symbol(double lo, double hi, uint32_t *next);
/* The form of a raw interval of format f: a point is exact, a wider one
 * a new symbol. */
sim_aff sim_aff_of_ival(sim_ival v, sim_fmt f, uint32_t *next);
/* ka a + kb b, the symbols shared. */
sim_aff sim_aff_lin(double ka, const sim_aff *a, double kb, const sim_aff *b);
/* Its hull as reals. */
void sim_aff_hull(const sim_aff *a, double *lo, double *hi);

/* Element y's forms (pre: rounded, before overflow handling; post: what
 * the signal settles to) from forms[] and the intervals vals[] of the
 * same signals (y's operands; for a register its own current value),
 * where ipre, ipost are y's intervals from sim_ival_eval. ipre and ipost
 * come back narrowed to what the forms prove (never wider). Returns 0, or
 * -1 for a signal sim_prim_describe does not know. */
int sim_aff_eval(const sim_signal *y, const sim_aff *forms, const sim_ival *vals, sim_ival *ipre, sim_ival *ipost,
                 sim_aff *pre, sim_aff *post, uint32_t *next);
#endif
