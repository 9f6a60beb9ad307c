/* ref_interp.h - exact float reference of the hardware of Nechyporuk & Romanyuk (2020).
 *
 * Plain functions for testbenches and tests, and the reference models
 * (vec_model) built on them: ref_interp.c's horner3, horner2, div3,
 * coef3_n1, coef3_n2, coef2, interp3, interp2 and ref_span.c's span1,
 * span2, span3, span23. Each unit's descriptor (units/) points at its
 * model (unit_desc.ref): there is no registry of models.
 *
 * Node numbering is the paper's: I1 = I(0), I2 = I(1), I3 = I(1/2) and
 * I4 = I(1/4) (node set N1) or I(3/4) (node set N2). Arrays are indexed
 * from 0, so I[0] is I1.
 */
#ifndef REF_INTERP_H
#define REF_INTERP_H
#include "vectors/vectors.h"

extern const vec_model ref_model_horner3, ref_model_horner2, ref_model_div3, ref_model_coef3_n1,
                       ref_model_coef3_n2, ref_model_coef2, ref_model_interp3, ref_model_interp2,
                       ref_model_span1, ref_model_span2, ref_model_span3, ref_model_span23;

/* Node positions t of I1..I4 (N1, N2) and I1..I3 (quadratic). */
extern const double ref_nodes_n1[4], ref_nodes_n2[4], ref_nodes_q[3];
/* The interpolant through the k nodes (tn[i], I[i]) at t, in Lagrange form
 * (ref_interp.c says why not as coefficients): the interpolation units'
 * and the span units' references both. */
double ref_lagrange(const double *tn, const double *I, int k, double t);

/* Cubic coefficients abcd = {A, B, C, D} of I(t) = A t^3 + B t^2 + C t + D
 * through the nodes, by the coefficient formulas (docs/units.md) (exact /3). */
void ref_coef3_n1(const double I[4], double abcd[4]);
void ref_coef3_n2(const double I[4], double abcd[4]);
/* Quadratic abc = {A, B, C} of I(t) = A t^2 + B t + C through I(0), I(1),
 * I(1/2). */
void ref_coef2(const double I[3], double abc[3]);

/* Horner evaluation: ((a t + b) t + c) t + d and (a t + b) t + c. */
double ref_horner3(double a, double b, double c, double d, double t);
double ref_horner2(double a, double b, double c, double t);

/* The exact cubic through the N1 nodes (or the quadratic through I1..I3) at
 * the L pixels t = k/L, k = 0..L-1, into y[0..L-1]; L >= 1. */
void ref_interp3(const double I[4], int L, double *y);
void ref_interp2(const double I[3], int L, double *y);

/* The divide-by-3 shift network (Fig. 7) in exact arithmetic.
 * REF_DIV3_PAPER:   x/2 - x/8 - x/32 - ...  (`terms` subtracted terms
 *                   after x/2; terms = 3 is the paper's 0.3359375 x).
 * REF_DIV3_QUARTER: x/4 + x/16 + x/64 + ... (`terms` terms).
 * Both converge to x/3 as terms grows (from above and below). terms < 0
 * counts as 0; terms beyond ~26 no longer change a double. An unknown
 * series gives NaN. */
enum { REF_DIV3_PAPER = 0, REF_DIV3_QUARTER = 1 };
double ref_div3_factor(int terms, int series);
double ref_div3_network(double x, int terms, int series);

#endif
