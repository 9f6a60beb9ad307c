/* unit_coef.h - the coefficient networks of Nechyporuk & Romanyuk (2020) (Fig. 8; the coefficient formulas of docs/units.md),
 * shared by the coefficient units (unit_coef.c) and the interpolators
 * (unit_interp.c).
 *
 * A network is data: one line per element, in build order (operands
 * first), each either
 *   X(name, op, a, b, k, what)   an internal signal, or
 *   O(name, op, a, b, k, what)   a coefficient (a unit output),
 * with op SHL (a * 2^k: wiring), ADD (a + b), SUB (a - b) or DIV3 (a/3 by
 * the Fig. 7 network, built in a sub-scope of that name; one format for all
 * of its terms, sums and output). Operands name earlier elements or the
 * inputs i1..i4; `_` is none. Every constant factor of the coefficient formulas is
 * a sum or difference of powers of two (7 = 8-1, 10 = 8+2, 13 = 8+4+1,
 * 14 = 16-2, 5 = 4+1, 3 = 2+1), and shared subterms (7 I1 in B and C of
 * N1) are built once.
 *
 * The same list expands into the units' signal tables (COEF_SIG_*), so a
 * network's element names, signal names and --fmt names are one thing.
 */
#ifndef UNIT_COEF_H
#define UNIT_COEF_H
#include "units/unit_net.h"

/* Node set N1 = {0, 1, 1/2, 1/4}:
 *   A = 8 ((I2 + 8 I4)/3 - (I1 + 2 I3))
 *   B = 2 ((7 I1 - I2) + (10 I3 - 16 I4))
 *   C = (I2 + 32 I4)/3 - (7 I1 + 4 I3)
 *   D = I1 */
#define COEF3_N1_NET(X, O) \
    X(i4x8,   SHL,  i4,     _,      3, "8 I4") \
    X(pa,     ADD,  i2,     i4x8,   0, "I2 + 8 I4") \
    X(div3_a, DIV3, pa,     _,      0, "(I2 + 8 I4)/3 by the /3 network (scope div3_a): its terms, sums and output") \
    X(i3x2,   SHL,  i3,     _,      1, "2 I3") \
    X(qa,     ADD,  i1,     i3x2,   0, "I1 + 2 I3") \
    X(da,     SUB,  div3_a, qa,     0, "(I2 + 8 I4)/3 - (I1 + 2 I3)") \
    O(a,      SHL,  da,     _,      3, "A = 8 (I2 + 8 I4)/3 - 8 (I1 + 2 I3)") \
    X(i1x8,   SHL,  i1,     _,      3, "8 I1") \
    X(i1x7,   SUB,  i1x8,   i1,     0, "7 I1 = 8 I1 - I1") \
    X(pb,     SUB,  i1x7,   i2,     0, "7 I1 - I2") \
    X(i3x8,   SHL,  i3,     _,      3, "8 I3") \
    X(i3x10,  ADD,  i3x8,   i3x2,   0, "10 I3 = 8 I3 + 2 I3") \
    X(i4x16,  SHL,  i4,     _,      4, "16 I4") \
    X(qb,     SUB,  i3x10,  i4x16,  0, "10 I3 - 16 I4") \
    X(sb,     ADD,  pb,     qb,     0, "7 I1 - I2 + 10 I3 - 16 I4") \
    O(b,      SHL,  sb,     _,      1, "B = 2 (7 I1 - I2 + 10 I3 - 16 I4)") \
    X(i4x32,  SHL,  i4,     _,      5, "32 I4") \
    X(pc,     ADD,  i2,     i4x32,  0, "I2 + 32 I4") \
    X(div3_c, DIV3, pc,     _,      0, "(I2 + 32 I4)/3 by the /3 network (scope div3_c): its terms, sums and output") \
    X(i3x4,   SHL,  i3,     _,      2, "4 I3") \
    X(qc,     ADD,  i1x7,   i3x4,   0, "7 I1 + 4 I3") \
    O(c,      SUB,  div3_c, qc,     0, "C = (I2 + 32 I4)/3 - 7 I1 - 4 I3") \
    O(d,      SHL,  i1,     _,      0, "D = I1")

/* Node set N2 = {0, 1, 1/2, 3/4}:
 *   A = 8 ((I2 + 2 I3) - (8 I4 + I1)/3)
 *   B = 2 ((3 I1 - 5 I2) + (16 I4 - 14 I3))
 *   C = 3 (I2 + 4 I3) - (13 I1 + 32 I4)/3
 *   D = I1 */
#define COEF3_N2_NET(X, O) \
    X(i3x2,   SHL,  i3,     _,      1, "2 I3") \
    X(pa,     ADD,  i2,     i3x2,   0, "I2 + 2 I3") \
    X(i4x8,   SHL,  i4,     _,      3, "8 I4") \
    X(qa,     ADD,  i4x8,   i1,     0, "8 I4 + I1") \
    X(div3_a, DIV3, qa,     _,      0, "(8 I4 + I1)/3 by the /3 network (scope div3_a): its terms, sums and output") \
    X(da,     SUB,  pa,     div3_a, 0, "(I2 + 2 I3) - (8 I4 + I1)/3") \
    O(a,      SHL,  da,     _,      3, "A = 8 (I2 + 2 I3) - 8 (8 I4 + I1)/3") \
    X(i1x2,   SHL,  i1,     _,      1, "2 I1") \
    X(i1x3,   ADD,  i1x2,   i1,     0, "3 I1 = 2 I1 + I1") \
    X(i2x4,   SHL,  i2,     _,      2, "4 I2") \
    X(i2x5,   ADD,  i2x4,   i2,     0, "5 I2 = 4 I2 + I2") \
    X(pb,     SUB,  i1x3,   i2x5,   0, "3 I1 - 5 I2") \
    X(i4x16,  SHL,  i4,     _,      4, "16 I4") \
    X(i3x16,  SHL,  i3,     _,      4, "16 I3") \
    X(i3x14,  SUB,  i3x16,  i3x2,   0, "14 I3 = 16 I3 - 2 I3") \
    X(qb,     SUB,  i4x16,  i3x14,  0, "16 I4 - 14 I3") \
    X(sb,     ADD,  pb,     qb,     0, "3 I1 - 5 I2 - 14 I3 + 16 I4") \
    O(b,      SHL,  sb,     _,      1, "B = 2 (3 I1 - 5 I2 - 14 I3 + 16 I4)") \
    X(i3x4,   SHL,  i3,     _,      2, "4 I3") \
    X(uc,     ADD,  i2,     i3x4,   0, "I2 + 4 I3") \
    X(ucx2,   SHL,  uc,     _,      1, "2 (I2 + 4 I3)") \
    X(ucx3,   ADD,  ucx2,   uc,     0, "3 (I2 + 4 I3) = 2 (I2 + 4 I3) + (I2 + 4 I3)") \
    X(i1x8,   SHL,  i1,     _,      3, "8 I1") \
    X(i1x4,   SHL,  i1,     _,      2, "4 I1") \
    X(i1x12,  ADD,  i1x8,   i1x4,   0, "12 I1 = 8 I1 + 4 I1") \
    X(i1x13,  ADD,  i1x12,  i1,     0, "13 I1 = 12 I1 + I1") \
    X(i4x32,  SHL,  i4,     _,      5, "32 I4") \
    X(pc,     ADD,  i1x13,  i4x32,  0, "13 I1 + 32 I4") \
    X(div3_c, DIV3, pc,     _,      0, "(13 I1 + 32 I4)/3 by the /3 network (scope div3_c): its terms, sums and output") \
    O(c,      SUB,  ucx3,   div3_c, 0, "C = 3 (I2 + 4 I3) - (13 I1 + 32 I4)/3") \
    O(d,      SHL,  i1,     _,      0, "D = I1")

/* Quadratic through I(0), I(1), I(1/2):
 *   A = 2 (I1 + I2) - 4 I3,  B = 4 I3 - (3 I1 + I2),  C = I1 */
#define COEF2_NET(X, O) \
    X(s12,    ADD,  i1,     i2,     0, "I1 + I2") \
    X(s12x2,  SHL,  s12,    _,      1, "2 (I1 + I2)") \
    X(i3x4,   SHL,  i3,     _,      2, "4 I3") \
    O(a,      SUB,  s12x2,  i3x4,   0, "A = 2 I1 + 2 I2 - 4 I3") \
    X(i1x2,   SHL,  i1,     _,      1, "2 I1") \
    X(i1x3,   ADD,  i1x2,   i1,     0, "3 I1 = 2 I1 + I1") \
    X(qb,     ADD,  i1x3,   i2,     0, "3 I1 + I2") \
    O(b,      SUB,  i3x4,   qb,     0, "B = 4 I3 - 3 I1 - I2") \
    O(c,      SHL,  i1,     _,      0, "C = I1")

/* Expansions into unit_sig entries. */
#define COEF_SIG_SKIP(name, op, a, b, k, what)
#define COEF_SIG_INT(nm_, op, a, b, k, wh_) { .name = #nm_, .role = UNIT_SIG_INTERNAL, .what = wh_ },
#define COEF_SIG_OUT(nm_, op, a, b, k, wh_) { .name = #nm_, .role = UNIT_SIG_OUT, .what = wh_ },
#define COEF_SIGS_I123 \
    { .name = "i1", .role = UNIT_SIG_IN, .what = "I1 = I(0)" }, { .name = "i2", .role = UNIT_SIG_IN, .what = "I2 = I(1)" }, \
    { .name = "i3", .role = UNIT_SIG_IN, .what = "I3 = I(1/2)" }
#define COEF_SIG_I4_N1 { .name = "i4", .role = UNIT_SIG_IN, .what = "I4 = I(1/4)" }
#define COEF_SIG_I4_N2 { .name = "i4", .role = UNIT_SIG_IN, .what = "I4 = I(3/4)" }
/* Elements of a network, as a constant: (0 NET(COEF_COUNT, COEF_COUNT)). */
#define COEF_COUNT(name, op, a, b, k, what) + 1
#define COEF3_N1_NODES (0 COEF3_N1_NET(COEF_COUNT, COEF_COUNT))
#define COEF3_N2_NODES (0 COEF3_N2_NET(COEF_COUNT, COEF_COUNT))
#define COEF2_NODES    (0 COEF2_NET(COEF_COUNT, COEF_COUNT))

/* A network as data (the list's X and O lines). */
typedef enum { COEF_SHL, COEF_ADD, COEF_SUB, COEF_DIV3 } coef_op;
typedef struct coef_node {
    const char *name;
    coef_op     op;
    const char *a, *b;      /* operand names ("_": none) */
    int         k;          /* SHL: shift */
    int         is_out;
} coef_node;

#define COEF_MAX_NODES 40

typedef struct coef_net {
    int nin, nout;          /* i1..i<nin>; outputs in list order */
    int nnodes;
    const coef_node *node;
    /* The coefficient formulas (docs/units.md) in exact arithmetic with `third` in place of
     * 1/3 (the ideal: third is the network's factor). */
    void (*formula)(const double *I, double third, double *out);
} coef_net;

extern const coef_net coef_net_n1, coef_net_n2, coef_net_q;

/* The formula exactly (dyadic inputs; third is a dyadic network factor):
 * the formulas are linear, so their coefficients are the formula at the
 * unit vectors, exact in double (small integers times a factor of at most
 * 2 * DIV3_MAX_TERMS + 1 bits). 0, or -1 when a value does not fit. */
int coef_exact(const coef_net *net, double third, const sim_dy *in, sim_dy *out);

/* Walk a network over inputs in[0..nin-1] (built, bounded or formatted by
 * n); DIV3 elements get sub-scopes when building. The coefficients' values
 * go to out[0..nout-1]. 0, or -1 with n->why set. */
int coef_walk(unet *n, const coef_net *net, const unet_val *in, int terms, int series,
              unet_val *out);

/* Node intensities span [0, 1]; the default rule's input format. */
sim_fmt coef_input_fmt(int width);
#endif
