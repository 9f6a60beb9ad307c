/* tb_expr.h - the ideal function of a datapath file: one expression per
 * output over the inputs (docs/datapaths.md).
 *
 * An expression is numbers, input names, + - * /, unary minus,
 * parentheses and the functions sqrt(x), abs(x), min(x, y) and max(x, y).
 * It is compiled once to a postfix program and evaluated in double for
 * the golden vectors, and exactly (sim_dy) where it has no division, no
 * square root and only constants a double holds exactly, so that the
 * verdict's check of the bound holds at every width as a built-in unit's
 * exact ideal does.
 */
#ifndef TB_EXPR_H
#define TB_EXPR_H
#include "sim/sim_fixed.h"
#include <stddef.h>

typedef struct tb_expr tb_expr;

/* Compile text over the variables vars[0..nvar-1]: the program in *out,
 * or -1 with "column C: what is wrong" in err. */
int    tb_expr_parse(const char *text, int nvar, const char *const *vars, tb_expr **out, char *err, size_t errlen);
double tb_expr_eval(const tb_expr *e, const double *x);
/* 1 if tb_expr_exact can evaluate e (no /, sqrt; dyadic constants). */
int    tb_expr_is_exact(const tb_expr *e);
/* e at x exactly: 0, or -1 when a value does not fit a sim_dy. */
int    tb_expr_exact(const tb_expr *e, const sim_dy *x, sim_dy *out);
void   tb_expr_free(tb_expr *e);
#endif
